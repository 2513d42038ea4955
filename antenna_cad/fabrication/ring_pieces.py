"""Pieces of a Luneburg sheet layup (``ring_plan``): whole rings, discs and ring sectors with
analytic areas, board sizes and kerf tool paths (polylines and true arcs), and the stand feet."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.fabrication.outline import CHORD_TOL_MM
from antenna_cad.fabrication.ring_plan import DowelHole, RingPlan, sector_box
from antenna_cad.fabrication.templates import BulgePath
from antenna_cad.materials import Material

HOLE_CHORD_TOL_MM = 0.01


# ---------------------------------------------------------------- pieces

def vertex_count(radius: float, tol: float = CHORD_TOL_MM) -> int:
    """Vertices of ``outline.circle_polygon`` (same chord rule)."""
    return max(24, 4 * math.ceil(math.pi * math.sqrt(radius / (2 * tol)) / 4))


def _arc(radius: float, a0: float, a1: float, count: int, circumscribed: bool) -> np.ndarray:
    """Polygon vertices along an arc (``count`` per full turn): circumscribed about it (outer
    edges) or inscribed in it (hole edges), so the part never lies inside the nominal shape."""
    m = max(2, math.ceil(count * abs(a1 - a0) / (2 * math.pi)) + 1)
    a = np.linspace(a0, a1, m)
    rv = radius / math.cos(abs(a1 - a0) / (m - 1) / 2) if circumscribed else radius
    if circumscribed:                          # keep the end points on the radial edges
        rv = np.full(m, rv)
        rv[[0, -1]] = radius
    return np.column_stack([rv * np.cos(a), rv * np.sin(a)])


@dataclass(frozen=True)
class RingPiece:
    """A ring, disc or ring sector as cut, in the sheet frame. Area, size on the board and kerf
    path are analytic; the polygon is built only when drawn. ``a0_rad``/``a1_rad`` span a
    sector (None: the whole ring)."""
    label: str
    ring: RingPlan
    thickness_mm: float
    a0_rad: float | None = None
    a1_rad: float | None = None

    @property
    def sheet_index(self) -> int:
        return self.ring.sheet_index

    @property
    def is_sector(self) -> bool:
        return self.a0_rad is not None

    @property
    def holes(self) -> tuple[DowelHole, ...]:
        if not self.is_sector:
            return self.ring.holes
        return tuple(h for h in self.ring.holes
                     if (math.atan2(h.y_mm, h.x_mm) - self.a0_rad) % (2 * math.pi) < self.a1_rad - self.a0_rad)

    @property
    def half_rad(self) -> float:
        return math.pi if not self.is_sector else 0.5 * (self.a1_rad - self.a0_rad)

    @property
    def nest_rotation_deg(self) -> float:
        """Rotation that turns the sector's bisector to +Y (0 for a whole ring)."""
        return 0.0 if not self.is_sector else 90.0 - math.degrees(0.5 * (self.a0_rad + self.a1_rad))

    @property
    def area_mm2(self) -> float:
        r = self.ring
        return self.half_rad * (r.r_outer_mm**2 - r.r_inner_mm**2) - sum(
            math.pi * h.diameter_mm**2 / 4 for h in self.holes if h.face == "through")

    def size_mm(self, kerf_mm: float = 0.0) -> tuple[float, float]:
        """Bounding box on the board (nesting orientation) of the cut path."""
        return sector_box(self.ring.r_inner_mm, self.ring.r_outer_mm, self.half_rad, kerf_mm)

    def cut_path(self, kerf_mm: float) -> Polygon:
        """Tool path: outline offset outward (through holes inward) by half the kerf, mitred
        corners. Blind dowel holes are drilled, not cut (drawn on MARK)."""
        r, c = self.ring, kerf_mm / 2
        count = vertex_count(r.r_outer_mm)
        ro, ri = r.r_outer_mm + c, r.r_inner_mm - c
        holes = [_arc(h.diameter_mm / 2 - c, 0.0, 2 * math.pi, vertex_count(h.diameter_mm / 2, HOLE_CHORD_TOL_MM),
                      True)[:-1][::-1] + (h.x_mm, h.y_mm) for h in self.holes if h.face == "through"]
        if not self.is_sector:
            outer = _arc(ro, 0.0, 2 * math.pi, count, True)[:-1]
            if r.r_inner_mm > 0:
                holes.append(_arc(ri, 0.0, 2 * math.pi, count, False)[:-1][::-1])
            return Polygon(outer, holes)
        a0, a1 = self.a0_rad, self.a1_rad
        g_o = math.asin(min(c / ro, 1.0))
        outer = _arc(ro, a0 - g_o, a1 + g_o, count, True)
        if ri > c:
            g_i = math.asin(c / ri)
            inner = _arc(ri, a1 + g_i, a0 - g_i, count, False)
        elif self.half_rad < math.pi / 2 - 1e-12:                                  # apex of a disc sector
            bis = 0.5 * (a0 + a1)
            inner = -c / math.sin(self.half_rad) * np.array([[math.cos(bis), math.sin(bis)]])
        else:                                                                       # half disc: one edge line
            inner = np.empty((0, 2))
        return Polygon(np.vstack([outer, inner]), holes)

    def cut_arcs(self, kerf_mm: float) -> list[BulgePath]:
        """``cut_path`` with true arcs (DXF bulges), its rings in the same order: the outline,
        then the through holes, then the inner circle."""
        r, c = self.ring, kerf_mm / 2
        ro, ri = r.r_outer_mm + c, r.r_inner_mm - c
        holes = [_circle(h.diameter_mm / 2 - c, h.x_mm, h.y_mm) for h in self.holes if h.face == "through"]
        if not self.is_sector:
            return [_circle(ro), *holes] + ([_circle(ri)] if r.r_inner_mm > 0 else [])
        a0, a1 = self.a0_rad, self.a1_rad
        g_o = math.asin(min(c / ro, 1.0))
        path = [_polar(ro, a0 - g_o, math.tan((a1 - a0 + 2 * g_o) / 4)), _polar(ro, a1 + g_o, 0.0)]
        if ri > c:
            g_i = math.asin(c / ri)
            path += [_polar(ri, a1 + g_i, -math.tan((a1 - a0 + 2 * g_i) / 4)), _polar(ri, a0 - g_i, 0.0)]
        elif self.half_rad < math.pi / 2 - 1e-12:                                  # apex of a disc sector
            bis = 0.5 * (a0 + a1)
            path.append(_polar(-c / math.sin(self.half_rad), bis, 0.0))
        return [path, *holes]

    @cached_property
    def polygon(self) -> Polygon:
        """Nominal part (the size it must come out), sheet frame."""
        return self.cut_path(0.0)


def _circle(radius: float, x: float = 0.0, y: float = 0.0) -> BulgePath:
    """A full circle as two half-circle bulges (counter-clockwise)."""
    return [(x + radius, y, 1.0), (x - radius, y, 1.0)]


def _polar(radius: float, angle: float, bulge: float) -> tuple[float, float, float]:
    return radius * math.cos(angle), radius * math.sin(angle), bulge


@dataclass(frozen=True)
class FootPiece:
    """A stand foot (sheet frame): the cradle outline, cut with shapely's kerf offset."""
    label: str
    sheet_index: int
    thickness_mm: float
    polygon: Polygon
    material: Material
    holes: tuple[DowelHole, ...]
    is_sector = False
    nest_rotation_deg = 0.0

    @property
    def area_mm2(self) -> float:
        return float(self.polygon.area)

    def cut_path(self, kerf_mm: float) -> Polygon:
        return self.polygon if kerf_mm == 0 else self.polygon.buffer(kerf_mm / 2, quad_segs=64)

    def size_mm(self, kerf_mm: float = 0.0) -> tuple[float, float]:
        x0, y0, x1, y1 = self.cut_path(kerf_mm).bounds
        return x1 - x0, y1 - y0


def ring_pieces(ring: RingPlan, thickness_mm: float) -> list[RingPiece]:
    """The ring itself, or its sectors labelled -a, -b, … counter-clockwise from its first joint."""
    if ring.sectors == 1:
        return [RingPiece(ring.label, ring, thickness_mm)]
    step = 2 * math.pi / ring.sectors
    return [RingPiece(f"{ring.label}-{_suffix(j)}", ring, thickness_mm,
                      ring.sector_start_rad + j * step, ring.sector_start_rad + (j + 1) * step)
            for j in range(ring.sectors)]


def _suffix(j: int) -> str:
    return chr(97 + j) if j < 26 else f"{chr(97 + j // 26 - 1)}{chr(97 + j % 26)}"
