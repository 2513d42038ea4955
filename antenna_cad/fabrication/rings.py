"""Sheet layup of a multilayer Luneburg lens: slabs of stock thickness, concentric rings per slab.

seed-002 digest §5.1 (b): the sphere is sliced by planes z = z_k into sheets of thickness t; each
sheet is a set of concentric rings, one per shell crossed, each cut from the board of its own
foam grade. Ring sizing (selectable, reported):

* ``contain``: over the slab [z_lo, z_hi] the ring of shell (r_in, r_out) has outer radius
  max sqrt(r_out² − z²) and inner radius min sqrt(max(r_in² − z², 0)), so turning/sanding the
  bevelled faces to the spheres only removes material (neighbouring rings overlap radially by
  that finishing allowance until turned);
* ``mid_plane``: radii sqrt(r² − z_m²) at the sheet mid-plane (stepped lens, rings butt, no
  finishing); shell caps that do not reach the mid-plane are dropped (reported).

A ring whose cut path fits no board is cut into equal sectors with radial butt joints,
staggered by half a sector in neighbouring sheets (planned here, so the registration holes can
keep clear of the joints).

Registration (seed-002 §5.1 item 5, "registration holes through stacked sheets"): across every
joint between sheets k and k+1, each shell crossed by both sheets gets three dowels at 120° on
one circle, in blind holes drilled ``depth`` = min(t/2, 2·Ø) into the joint faces of both sheets
(top face of sheet k, bottom face of sheet k+1); the pattern turns by 60° from one joint to the
next. The circle is the middle of the band of radii where a dowel lies in both rings and
(``contain``, rings turned to the spheres) inside its shell over its length; through the lens's
outer surface turning trims it with the rings. The dowels are cut from the shell's own grade, so
they leave every layer's εr unchanged. A Luneburg sphere has no region outside the aperture (its
beam scans over the whole sphere), which is why the holes are made electrically invisible
instead of being moved out of the ray path; they stay off the axis and off sector joints. A
cylinder (parallel-plate) lens is sliced along its axis and its rings are the layer radii; its
dowels are pins through the whole stack at each ring's mid-radius that also locate the rings in
matching holes of the plates.

Pure numpy/shapely: no CAD imports. Outlines, kerf offsets and nesting sizes are analytic, so
the cost is linear in sheets × rings (+ sector pieces); polygons are built only for drawings.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from shapely import affinity
from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow, cutlist_csv
from antenna_cad.fabrication.layup import Cradle
from antenna_cad.fabrication.nesting import Placement, nest
from antenna_cad.fabrication.outline import (CHORD_TOL_MM, NEST_SPACING_MM, Circle, arc_paths, circle_polygon, fits_board,
                                             foot_polygon)
from antenna_cad.fabrication.templates import TEXT_HEIGHT_MM, BulgePath, Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check

REG_CLEARANCE_MM = 3.0           # foam kept between a dowel hole and a ring edge or sector joint
DOWEL_PATTERN_DEG = (90.0, 210.0, 330.0)
HOLE_CHORD_TOL_MM = 0.01


@dataclass(frozen=True)
class DowelHole:
    """A registration hole in the sheet frame: ``face`` "top" (z_max) or "bottom" (z_min) for a
    blind hole ``depth_mm`` deep, "through" for a hole cut through the ring."""
    x_mm: float
    y_mm: float
    diameter_mm: float
    depth_mm: float
    face: str


@dataclass(frozen=True)
class RingPlan:
    label: str               # "sheet-03-ring-02" (ring of shell 2 in sheet 3)
    sheet_index: int
    shell_index: int
    r_inner_mm: float        # 0 for a disc
    r_outer_mm: float
    material: Material       # the shell's foam grade
    sectors: int = 1         # equal sectors with radial butt joints (1: one piece)
    sector_start_rad: float = 0.0   # angle of the first radial joint, sheet frame, from +X
    holes: tuple[DowelHole, ...] = ()    # registration dowel holes

    @property
    def joint_angles_rad(self) -> np.ndarray:
        if self.sectors == 1:
            return np.empty(0)
        return self.sector_start_rad + 2 * math.pi * np.arange(self.sectors) / self.sectors


@dataclass(frozen=True)
class Dowel:
    """A registration dowel of the shell's grade through ``sheets`` (the plates too, cylinder)."""
    shell_index: int
    sheets: tuple[int, ...]
    x_mm: float
    y_mm: float
    diameter_mm: float
    length_mm: float
    material: Material


@dataclass(frozen=True)
class RingSheet:
    index: int
    label: str
    z_min_mm: float
    z_max_mm: float
    rings: tuple[RingPlan, ...]
    has_neck: bool = False
    foot_holes: tuple[DowelHole, ...] = ()     # stand foot's dowel holes (with a stand)

    @property
    def thickness_mm(self) -> float:
        return self.z_max_mm - self.z_min_mm

    @property
    def radius_mm(self) -> float:
        return max((r.r_outer_mm for r in self.rings), default=0.0)

    def manifest_extra(self) -> dict:
        """Per-sheet manifest fields beyond the common ones (pipeline hook)."""
        return {"material": sorted({r.material.name for r in self.rings}),
                "rings": [{"label": r.label, "shell": r.shell_index, "r_inner_mm": r.r_inner_mm,
                           "r_outer_mm": r.r_outer_mm, "material": r.material.name,
                           "sectors": r.sectors,
                           "holes": [{"x_mm": h.x_mm, "y_mm": h.y_mm, "diameter_mm": h.diameter_mm,
                                      "depth_mm": h.depth_mm, "face": h.face} for h in r.holes]}
                          for r in self.rings]}


@dataclass(frozen=True)
class RingLayupPlan(Cradle):
    sheets: tuple[RingSheet, ...]
    sheet_thickness_mm: float
    sizing: str
    shape: str
    kerf_mm: float
    board_width_mm: float
    board_length_mm: float
    registration_hole_mm: float
    dropped_caps: int        # mid_plane: shell caps that miss their sheet's mid-plane
    dowels: tuple[Dowel, ...] = ()
    undowelled_joints: int = 0   # (joint, shell) pairs whose band is too thin for a dowel
    lens_radius_mm: float = 0.0
    pedestal_width_mm: float | None = None     # the stand (None: none); names as ``layup.LayupPlan``
    pedestal_height_mm: float | None = None
    stand_material: Material | None = None

    @property
    def count(self) -> int:
        return len(self.sheets)

    @property
    def rings(self) -> list[RingPlan]:
        return [r for s in self.sheets for r in s.rings]


def ring_radii(r_inner: np.ndarray, r_outer: np.ndarray, z_lo: float, z_hi: float, sizing: str
               ) -> tuple[np.ndarray, np.ndarray]:
    """(inner, outer) ring radii of spherical shells crossed by the slab (outer 0: not crossed)."""
    if sizing == "mid_plane":
        zm = 0.5 * (z_lo + z_hi)
        return (np.sqrt(np.maximum(r_inner**2 - zm * zm, 0.0)),
                np.sqrt(np.maximum(r_outer**2 - zm * zm, 0.0)))
    z_near = 0.0 if z_lo <= 0.0 <= z_hi else min(abs(z_lo), abs(z_hi))
    z_far = max(abs(z_lo), abs(z_hi))
    outer = np.sqrt(np.maximum(r_outer**2 - z_near * z_near, 0.0))
    inner = np.sqrt(np.maximum(r_inner**2 - z_far * z_far, 0.0))
    return inner, outer


# ---------------------------------------------------------------- sectors (analytic outlines)

def sector_box(r_in: float, r_out: float, half_rad: float, kerf_mm: float) -> tuple[float, float]:
    """Bounding box (w, h) of a sector's cut path turned so its bisector points to +Y.

    The cut path is the sector offset outward by kerf/2 with mitred corners: arcs of radius
    r_out + kerf/2 (+ the chord tolerance of the circumscribed polygon) and r_in − kerf/2, radial
    edges moved kerf/2 outward (a disc sector's apex moves to kerf/2 / sin(half) below the
    centre). ``half_rad`` = π gives the whole ring."""
    c = kerf_mm / 2
    ro = r_out + c + CHORD_TOL_MM
    if half_rad >= math.pi - 1e-12:
        return 2 * ro, 2 * ro
    hollow = r_in - c > c
    s_o = math.sqrt(ro * ro - c * c)
    sh, ch = math.sin(half_rad), math.cos(half_rad)
    # right edge (the left one mirrors it in x): direction (sin h, cos h), outward normal (cos h, −sin h)
    xo, yo = s_o * sh + c * ch, s_o * ch - c * sh
    if hollow:
        s_i = math.sqrt((r_in - c) ** 2 - c * c)
        x_in, y_low = s_i * sh + c * ch, min(yo, s_i * ch - c * sh)
    elif half_rad < math.pi / 2 - 1e-12:
        x_in, y_low = 0.0, min(yo, -c / sh)              # apex of the offset disc sector
    else:
        x_in, y_low = 0.0, yo
    x_ext = ro if yo < 0 else max(xo, x_in)              # the outer arc passes ±X
    return 2 * x_ext, ro - y_low


def sector_count(r_in: float, r_out: float, board_w: float, board_l: float, kerf_mm: float) -> int:
    """1 if the ring's cut path fits a board, else the fewest equal sectors that fit one and whose
    bounding box is at most twice the sector's area (thin rings: short arcs, less waste)."""
    if fits_board(*sector_box(r_in, r_out, math.pi, kerf_mm), board_w, board_l):
        return 1
    reach = (max(board_w, board_l) - 2 * NEST_SPACING_MM) / (2 * (r_out + kerf_mm))
    first = 2 if reach >= 1 else max(2, math.floor(math.pi / math.asin(reach)))   # chord ≤ the board
    for k in range(first, 721):
        half = math.pi / k
        w, h = sector_box(r_in, r_out, half, kerf_mm)
        if fits_board(w, h, board_w, board_l) and (w * h <= 2.0 * half * (r_out**2 - r_in**2) or k == 720):
            return k
    raise ValueError(f"ring R {r_out:.0f} mm: no sector split fits a {board_w:g} × {board_l:g} mm board")


# ---------------------------------------------------------------- the plan

def plan_rings(r_inner_mm, r_outer_mm, materials: list[Material], *, shape: str, height_mm: float | None,
               sheet_thickness_mm: float, sizing: str, kerf_mm: float, board_width_mm: float,
               board_length_mm: float, registration_hole_mm: float, pedestal_height_mm: float | None = None,
               pedestal_width_mm: float | None = None) -> RingLayupPlan:
    """Sheets, their rings (radii, grade, sector split, dowel holes), the dowels, and the stand."""
    ri, ro = np.asarray(r_inner_mm, float), np.asarray(r_outer_mm, float)
    span = 2.0 * ro[-1] if shape == "sphere" else float(height_mm)
    t = sheet_thickness_mm
    n = max(1, math.ceil(span / t - 1e-9))
    z0 = -0.5 * n * t
    sheets, dropped = [], 0
    for k in range(n):
        z_lo, z_hi = z0 + k * t, z0 + (k + 1) * t
        if shape == "sphere":
            inner, outer = ring_radii(ri, ro, z_lo, z_hi, sizing)
            if sizing == "mid_plane":
                dropped += int(np.sum((outer <= 1e-9) & (ring_radii(ri, ro, z_lo, z_hi, "contain")[1] > 1e-9)))
        else:
            inner, outer = ri, ro
        label = f"sheet-{k + 1:02d}"
        rings = []
        for j in range(len(ro)):
            if outer[j] <= 1e-9 or outer[j] - inner[j] <= 1e-9:
                continue
            parts = sector_count(float(inner[j]), float(outer[j]), board_width_mm, board_length_mm, kerf_mm)
            start = 0.0 if k % 2 == 0 or parts == 1 else math.pi / parts      # staggered joints
            rings.append(RingPlan(f"{label}-ring-{j + 1:02d}", k + 1, j + 1, float(inner[j]), float(outer[j]),
                                  materials[j], parts, start))
        sheets.append(RingSheet(k + 1, label, z_lo, z_hi, tuple(rings)))
    sheets, dowels, missing = _registration(sheets, ri, ro, shape, sizing, registration_hole_mm, kerf_mm)
    R = float(ro[-1])
    width = None if pedestal_height_mm is None else (pedestal_width_mm or 1.2 * R)
    if width is not None:
        sheets, feet = _stand_dowels(sheets, R, width, pedestal_height_mm, registration_hole_mm, materials[-1])
        dowels += feet
    return RingLayupPlan(tuple(sheets), t, sizing, shape, kerf_mm, board_width_mm, board_length_mm,
                         registration_hole_mm, dropped, tuple(dowels), missing, R, width, pedestal_height_mm,
                         materials[-1] if width is not None else None)


def _stand_dowels(sheets: list[RingSheet], R: float, width: float, height: float, d: float, grade: Material
                  ) -> tuple[list[RingSheet], list[Dowel]]:
    """Two dowels per joint between consecutive feet, at ±w/4 halfway down the foot, in blind
    holes as the rings'."""
    if d <= 0:
        return sheets, []
    holes: dict[int, list[DowelHole]] = {s.index: [] for s in sheets}
    dowels = []
    y = -R - height / 2
    for a, b in zip(sheets, sheets[1:]):
        depth = min(0.5 * min(a.thickness_mm, b.thickness_mm), 2 * d)
        for x in (-width / 4, width / 4):
            holes[a.index].append(DowelHole(x, y, d, depth, "top"))
            holes[b.index].append(DowelHole(x, y, d, depth, "bottom"))
            dowels.append(Dowel(0, (a.index, b.index), x, y, d, 2 * depth, grade))
    return [RingSheet(s.index, s.label, s.z_min_mm, s.z_max_mm, s.rings, s.has_neck, tuple(holes[s.index]))
            for s in sheets], dowels


def _registration(sheets: list[RingSheet], ri: np.ndarray, ro: np.ndarray, shape: str, sizing: str, d: float,
                  kerf: float) -> tuple[list[RingSheet], list[Dowel], int]:
    """Dowel holes (module docstring): per joint and shared shell, three at 120° on the middle of
    the band of radii where a dowel lies in both rings and, once the rings are turned to the
    spheres (``contain``), inside its shell along its length — except through the lens surface,
    where turning trims the dowel with the rings (it must still reach the joint plane inside
    the lens). Nudged off sector joints."""
    if d <= 0:
        return sheets, [], 0
    by_label = {r.label: r for s in sheets for r in s.rings}
    holes: dict[str, list[DowelHole]] = {label: [] for label in by_label}
    dowels, missing = [], 0
    if shape == "sphere":
        joints = [(k, (sheets[k - 1], sheets[k])) for k in range(1, len(sheets))]
    else:
        joints = [(0, tuple(sheets))]                  # through pins, also into the plates
    turned = shape == "sphere" and sizing == "contain"
    for k, members in joints:
        if shape == "sphere":
            z_joint = members[0].z_max_mm
            depth = min(0.5 * min(s.thickness_mm for s in members), 2 * d)
            z_lo, z_hi, faces = z_joint - depth, z_joint + depth, ("top", "bottom")
        else:
            z_lo, z_hi = members[0].z_min_mm, members[-1].z_max_mm
            depth, faces = members[0].thickness_mm, ("through",) * len(members)
        z_near = 0.0 if z_lo <= 0.0 <= z_hi else min(abs(z_lo), abs(z_hi))
        z_far = max(abs(z_lo), abs(z_hi))
        for j in range(len(ro)):
            rings = [by_label.get(f"{s.label}-ring-{j + 1:02d}") for s in members]
            if any(r is None for r in rings):
                continue
            band_in = max(r.r_inner_mm for r in rings)
            band_out = min(r.r_outer_mm for r in rings)
            if turned:
                band_in = max(band_in, math.sqrt(max(ri[j] ** 2 - z_near**2, 0.0)))
                z_out = abs(z_joint) if j == len(ro) - 1 else z_far
                band_out = min(band_out, math.sqrt(max(ro[j] ** 2 - z_out**2, 0.0)))
            if band_out - band_in < d + 2 * REG_CLEARANCE_MM:
                missing += 1
                continue
            rho = 0.5 * (band_in + band_out)
            cuts = np.concatenate([r.joint_angles_rad for r in rings])
            gap = (d / 2 + REG_CLEARANCE_MM + kerf / 2) / rho
            for base in DOWEL_PATTERN_DEG:
                a = _clear_of(math.radians(base + 60.0 * (k % 2)), cuts, gap)
                if a is None:
                    continue
                x, y = round(rho * math.cos(a), 6), round(rho * math.sin(a), 6)
                if any(math.hypot(x - h.x_mm, y - h.y_mm) < d + REG_CLEARANCE_MM for r in rings for h in holes[r.label]):
                    continue
                for r, face in zip(rings, faces):
                    holes[r.label].append(DowelHole(x, y, d, depth, face))
                dowels.append(Dowel(j + 1, tuple(s.index for s in members), x, y, d, z_hi - z_lo, rings[0].material))
    out = [RingSheet(s.index, s.label, s.z_min_mm, s.z_max_mm,
                     tuple(RingPlan(r.label, r.sheet_index, r.shell_index, r.r_inner_mm, r.r_outer_mm, r.material,
                                    r.sectors, r.sector_start_rad, tuple(holes[r.label])) for r in s.rings),
                     s.has_neck) for s in sheets]
    return out, dowels, missing


def _clear_of(angle: float, cuts: np.ndarray, gap: float) -> float | None:
    """``angle`` moved the least so it is at least ``gap`` (rad) from every angle in ``cuts``;
    None if the joints leave no room."""
    if cuts.size == 0:
        return angle
    for _ in range(3):
        delta = (angle - cuts + math.pi) % (2 * math.pi) - math.pi
        i = int(np.argmin(np.abs(delta)))
        if abs(delta[i]) >= gap - 1e-12:
            return angle
        angle += math.copysign(gap - abs(delta[i]), delta[i] if delta[i] != 0 else 1.0)
    delta = (angle - cuts + math.pi) % (2 * math.pi) - math.pi
    return angle if np.min(np.abs(delta)) >= gap - 1e-9 else None


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


def _rotated(paths: list[BulgePath], degrees: float) -> list[BulgePath]:
    """Paths turned about the origin (bulges are invariant under rotation)."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    return [[(c * x - s * y, s * x + c * y, b) for x, y, b in path] for path in paths]


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


# ---------------------------------------------------------------- fabrication plan

@dataclass(frozen=True)
class FabPlanRings:
    """Same fields as ``sheets.FabPlan`` (what the pipeline reads) plus the nesting report."""
    pieces: tuple
    placements: dict[str, Placement]
    joints: dict
    drawings: tuple[Drawing, ...]
    rows: tuple[CutRow, ...]
    totals_kg: dict[str, float]
    boards: dict[str, int]
    kerf_mm: float
    in_hole: dict[str, str]                   # piece label -> host ring label
    in_hole_saving_m2: dict[str, float]       # grade -> board area saved by nesting in holes
    files: dict[str, str] = field(default_factory=dict)   # extra text files, as in ``FabPlan``

    @property
    def checks(self) -> tuple[Check, ...]:
        """Nesting report (the pipeline adds a fabrication plan's ``checks``)."""
        if not self.pieces:
            return ()
        saved = sum(self.in_hole_saving_m2.values())
        return (Check("rings_in_holes", "pass", saved, 0.0, "m2",
                      f"{len(self.in_hole)} rings/discs cut inside ring holes of their grade, saving "
                      f"{saved:.3f} m² of board (bounding squares)"),)


def fabricate_rings(plan: RingLayupPlan, title: str, drawings: bool = True) -> FabPlanRings:
    """Pieces, nesting per grade (discs/rings inside ring holes first, then rectpack), cut list
    (all grades and one file per grade), dowels, mass per grade, templates per sheet and piece."""
    kerf = plan.kerf_mm
    pieces: list = [p for s in plan.sheets for r in s.rings for p in ring_pieces(r, s.thickness_mm)]
    if plan.pedestal_height_mm is not None:
        foot = foot_polygon(plan, circle_polygon(0.0, 0.0, plan.lens_radius_mm))
        pieces += [FootPiece(f"{s.label}-foot", s.index, s.thickness_mm, foot, plan.stand_material, s.foot_holes)
                   for s in plan.sheets]
    by_grade: dict[str, list] = {}
    for p in pieces:
        by_grade.setdefault(_material(p).name, []).append(p)
    placements: dict[str, Placement] = {}
    in_hole: dict[str, str] = {}
    saving: dict[str, float] = {}
    for grade, items in sorted(by_grade.items()):
        hosted, saved = _nest_in_holes(items, kerf)
        in_hole |= hosted
        saving[grade] = saved
        free = [(p.label, *p.size_mm(kerf)) for p in items if p.label not in hosted]
        placements |= {pl.key: pl for pl in nest(free, plan.board_width_mm, plan.board_length_mm, grade)}
        whole = {p.label: p.ring for p in items if isinstance(p, RingPiece)}
        for label in sorted(hosted, key=lambda s: -whole[s].r_outer_mm):    # hosts are placed before guests
            host = placements[hosted[label]]
            hr, r = whole[hosted[label]].r_outer_mm, whole[label].r_outer_mm
            placements[label] = Placement(label, host.board_id, host.x_mm + hr - r, host.y_mm + hr - r, False)
    rows = [_row(p, placements[p.label], in_hole.get(p.label), plan) for p in pieces]
    rows += _dowel_rows(plan)
    rows = sorted(rows, key=lambda r: (r.assembly_order, r.part))
    totals = _totals(rows)
    boards: dict[str, set] = {}
    for pl in placements.values():
        boards.setdefault(pl.board_id.rsplit("-B", 1)[0], set()).add(pl.board_id)
    files = {f"cutlist-{grade}.csv": cutlist_csv(g_rows, _totals(g_rows))
             for grade in sorted(by_grade) for g_rows in [[r for r in rows if r.material == grade]]}
    draws: tuple[Drawing, ...] = ()
    if drawings:
        per_sheet: dict[int, list[RingPiece]] = {}
        for p in pieces:
            per_sheet.setdefault(p.sheet_index, []).append(p)
        draws = tuple(d for s in plan.sheets for d in
                      [_sheet_drawing(plan, s, per_sheet.get(s.index, []), title)] +
                      [_piece_drawing(plan, s, p, title) for p in per_sheet.get(s.index, [])])
    return FabPlanRings(tuple(pieces), placements, {}, draws, tuple(rows), totals,
                        {m: len(ids) for m, ids in sorted(boards.items())}, kerf, in_hole, saving, files)


def _material(piece) -> Material:
    return piece.material if isinstance(piece, FootPiece) else piece.ring.material


def _totals(rows: list[CutRow]) -> dict[str, float]:
    totals: dict[str, float] = {}
    for r in rows:
        totals[r.material] = totals.get(r.material, 0.0) + r.mass_kg
    return dict(sorted(totals.items())) | {"all": sum(totals.values())}


def _row(p, pl: Placement, host: str | None, plan: RingLayupPlan) -> CutRow:
    w, h = p.size_mm()
    area = p.area_mm2 / 1e6
    if isinstance(p, FootPiece):
        return CutRow(p.label, "stand-foot", p.material.name, pl.board_id, pl.x_mm, pl.y_mm, pl.rotated, w, h,
                      p.thickness_mm, area, area * p.thickness_mm / 1e3 * p.material.density_kg_m3, p.sheet_index,
                      "stand cradle below the aperture; " + _holes_text(p.holes) if p.holes else
                      "stand cradle below the aperture")
    m, ring = p.ring.material, p.ring
    kind = ("disc" if ring.r_inner_mm == 0 else "ring") + ("-sector" if p.is_sector else "")
    notes = []
    if host:
        notes.append(f"cut inside the hole of {host}")
    if p.is_sector:
        notes.append(f"sector {math.degrees(p.a0_rad) % 360:.2f}° to {math.degrees(p.a1_rad) % 360:.2f}° of the "
                     f"sheet frame, nested turned {p.nest_rotation_deg:.2f}°; butt-joint radially")
    if p.holes:
        notes.append(_holes_text(p.holes))
    if plan.sizing == "contain" and plan.shape == "sphere":
        notes.append("turn/sand bevelled faces to the shell spheres")
    return CutRow(p.label, kind, m.name, pl.board_id, pl.x_mm, pl.y_mm, pl.rotated, w, h, p.thickness_mm,
                  area, area * p.thickness_mm / 1e3 * m.density_kg_m3, p.sheet_index, "; ".join(notes))


def _dowel_rows(plan: RingLayupPlan) -> list[CutRow]:
    """One row per grade and dowel length: count, Ø, length, mass (cut from the grade's offcuts)."""
    groups: dict[tuple[str, float], list[Dowel]] = {}
    for dw in plan.dowels:
        groups.setdefault((dw.material.name, round(dw.length_mm, 3)), []).append(dw)
    rows = []
    for (grade, length), items in sorted(groups.items()):
        d, m = items[0].diameter_mm, items[0].material
        volume = len(items) * math.pi * d * d / 4 * length
        rows.append(CutRow(f"dowels-{grade}-L{length:g}", "dowel-rod", grade, "offcuts", 0.0, 0.0, False, d, length,
                           d, volume / length / 1e6, volume / 1e9 * m.density_kg_m3, 0,
                           f"{len(items)} dowels Ø{d:g} × {length:g} mm of this grade; glue into the "
                           "registration holes of the sheets they join"))
    return rows


def _nest_in_holes(items: list, kerf: float) -> tuple[dict[str, str], float]:
    """Greedy, largest first: each whole ring/disc goes into the smallest free ring hole of the
    same grade that holds it with the nesting gap; its own hole then becomes free. O(n log n)."""
    whole = sorted((p for p in items if isinstance(p, RingPiece) and not p.is_sector),
                   key=lambda p: (-p.ring.r_outer_mm, p.label))
    holes: list[tuple[float, str]] = []                 # sorted (usable radius, host label)
    hosted: dict[str, str] = {}
    saved = 0.0
    for p in whole:
        r_in, r_out = p.ring.r_inner_mm, p.ring.r_outer_mm
        need = r_out + kerf / 2 + NEST_SPACING_MM
        i = bisect.bisect_left(holes, (need, ""))
        if i < len(holes):
            _, host = holes.pop(i)
            hosted[p.label] = host
            saved += (2 * r_out + kerf + 2 * NEST_SPACING_MM) ** 2 / 1e6
        if r_in > 0:
            bisect.insort(holes, (r_in - kerf / 2, p.label))
    return hosted, saved


# ---------------------------------------------------------------- templates

def _sheet_drawing(plan: RingLayupPlan, sheet: RingSheet, pieces: list[RingPiece], title: str) -> Drawing:
    d = Drawing(sheet.label)
    for p in pieces:
        d.add_polygon(p.cut_path(plan.kerf_mm), p.cut_arcs(plan.kerf_mm) if isinstance(p, RingPiece) else None)
    for ring in sheet.rings:
        a = math.radians(20 + 25 * (ring.shell_index % 7))
        rm = 0.5 * (ring.r_inner_mm + ring.r_outer_mm)
        d.texts.append((f"{ring.label[-7:]} {ring.material.name}", rm * math.cos(a) - 10, rm * math.sin(a), 3.0))
        for a0 in ring.joint_angles_rad:                     # sector ids next to their first joint
            d.texts.append((_suffix(int(round((a0 - ring.sector_start_rad) / (2 * math.pi) * ring.sectors))),
                            rm * math.cos(a0 + 0.02), rm * math.sin(a0 + 0.02), 3.0))
        _mark_holes(d, ring.holes, 0.0)
    _mark_holes(d, sheet.foot_holes, 0.0)
    _frame_marks(d, max(sheet.radius_mm, 20.0))
    _title(d, [f"{title}  {sheet.label} of {plan.count}: z {sheet.z_min_mm:g} to {sheet.z_max_mm:g} mm, "
               f"thickness {sheet.thickness_mm:g} mm, {len(sheet.rings)} rings ({plan.sizing} sizing)",
               "assembly view, seen from +Z: each ring is cut from its own grade (see the ring templates); "
               "dowel holes (T: drilled into the top face, B: the bottom face; positions as seen from +Z) "
               "take dowels of the ring's grade"])
    return d


def _piece_drawing(plan: RingLayupPlan, sheet: RingSheet, piece, title: str) -> Drawing:
    """Whole rings and feet in the sheet frame (centre cross, +X tick: the holes' reference);
    sectors turned to their nesting orientation (bisector up) with the arc centre marked on the
    bisector."""
    d = Drawing(piece.label)
    if isinstance(piece, FootPiece):
        path = piece.cut_path(plan.kerf_mm)                   # the cradle follows the lens circle
        d.add_polygon(path, arc_paths(path, [Circle(0.0, 0.0, plan.lens_radius_mm - plan.kerf_mm / 2,
                                                    CHORD_TOL_MM, plan.lens_radius_mm)]))
        _mark_holes(d, piece.holes, 0.0)
        d.add_cross(0.0, 0.0, 10.0)
        _title(d, [f"{title}  {piece.label}: stand foot of {sheet.label} (z {sheet.z_min_mm:g} to "
                   f"{sheet.z_max_mm:g} mm), lens centre at the cross",
                   f"grade {piece.material.name}, board thickness {sheet.thickness_mm:g} mm; "
                   + (_holes_text(piece.holes) if piece.holes else "no dowel holes")
                   + f"; CUT = tool path (kerf {plan.kerf_mm:g} mm)"])
        return d
    ring = piece.ring
    path = piece.cut_path(plan.kerf_mm)
    if piece.is_sector:
        rot = piece.nest_rotation_deg
        d.add_polygon(affinity.rotate(path, rot, origin=(0, 0)), _rotated(piece.cut_arcs(plan.kerf_mm), rot))
        y_in = max(ring.r_inner_mm - 15.0, 0.0)
        d.marks.append([(0.0, y_in), (0.0, ring.r_outer_mm + 15.0)])                # bisector
        d.texts.append((f"{piece.label}", 3.0, 0.5 * (ring.r_inner_mm + ring.r_outer_mm), TEXT_HEIGHT_MM))
        where = [f"sector {_suffix(int(round((piece.a0_rad - ring.sector_start_rad) / (2 * math.pi) * ring.sectors)))}"
                 f" of {ring.sectors}: {math.degrees(piece.a0_rad) % 360:.2f}° to {math.degrees(piece.a1_rad) % 360:.2f}° "
                 f"of the sheet frame; the MARK line is its bisector, the arc centre lies on it "
                 f"{ring.r_outer_mm:.2f} mm below the outer arc"]
    else:
        d.add_polygon(path, piece.cut_arcs(plan.kerf_mm))
        _frame_marks(d, max(ring.r_outer_mm, 20.0))
        where = ["drawn in the sheet frame: align the +X tick with the sheet's +X mark"]
    holes = _holes_text(piece.holes) if piece.holes else "no dowel holes"
    _mark_holes(d, piece.holes, piece.nest_rotation_deg)
    _title(d, [f"{title}  {piece.label}: sheet {sheet.label} (z {sheet.z_min_mm:g} to {sheet.z_max_mm:g} mm), "
               f"ring of shell {ring.shell_index:02d}",
               f"grade {ring.material.name}: εr {ring.material.eps_r:.4g}, {ring.material.density_kg_m3:.4g} kg/m³, "
               f"board thickness {sheet.thickness_mm:g} mm",
               f"R out {ring.r_outer_mm:.2f} mm, R in {ring.r_inner_mm:.2f} mm; {holes}; CUT = tool path "
               f"(kerf {plan.kerf_mm:g} mm)", *where])
    return d


def _holes_text(holes) -> str:
    """"3 × Ø6 ↑12 (top face), 3 × Ø6 ↓12 (bottom face)" for a cut-list note or a title."""
    groups: dict[tuple, int] = {}
    for h in holes:
        key = (h.diameter_mm, h.depth_mm, h.face)
        groups[key] = groups.get(key, 0) + 1
    words = {"top": "blind from the top face", "bottom": "blind from the bottom face", "through": "through"}
    return "dowel holes " + ", ".join(f"{n} × Ø{dia:g}" + (f" {depth:g} deep " if face != "through" else " ")
                                      + words[face] for (dia, depth, face), n in sorted(groups.items()))


def _mark_holes(drawing: Drawing, holes, rotate_deg: float) -> None:
    """Blind holes on MARK: a circle, a cross, and "T"/"B" for the face they are drilled from
    (through holes are CUT paths already)."""
    c, s_ = math.cos(math.radians(rotate_deg)), math.sin(math.radians(rotate_deg))
    for h in holes:
        if h.face == "through":
            continue
        x, y = c * h.x_mm - s_ * h.y_mm, s_ * h.x_mm + c * h.y_mm
        ring = _arc(h.diameter_mm / 2, 0.0, 2 * math.pi, 48, False) + (x, y)
        drawing.marks.append([tuple(p) for p in ring])
        drawing.add_cross(x, y, h.diameter_mm * 0.4)
        drawing.texts.append(("T" if h.face == "top" else "B", x + h.diameter_mm * 0.7, y, 3.0))


def _frame_marks(drawing: Drawing, r: float) -> None:
    """Centre cross and rim ticks on ±X, ±Y (the +X tick is long: the angular reference)."""
    drawing.add_cross(0.0, 0.0, 10.0)
    for x, y, extra in ((1, 0, 12.0), (-1, 0, 0.0), (0, 1, 0.0), (0, -1, 0.0)):
        drawing.marks.append([(x * (r + 3), y * (r + 3)), (x * (r + 9 + extra), y * (r + 9 + extra))])
    drawing.texts.append(("+X", r + 24.0, -2.0, 4.0))


def _title(d: Drawing, lines: list[str]) -> None:
    x0, y0, _, y1 = d.bounds()
    d.add_title(lines, x0, y1 + 12)
    d.add_check_bar(x0, y0 - 20)
