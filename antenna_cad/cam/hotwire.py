"""Hot-wire ruled surfaces of a sheet's pieces: matched contours on the two foam faces.

A wire cuts a ruled surface: the straight line between a point of the contour on the feed-side face
(z_min) and the matching point on the antenna-side face (z_max). A taper-cut lens disc is the cone
through the lens profile at the two faces (radial rulings); every other piece has vertical edges
(front = back, XY = UV on the machine). A taper-cut disc wider than a board is cut as board strips
with vertical edges, glued into a blank, and the blank cut to the cone: a cone and a butt-joint plane
meet in a conic, which no single wire pass follows.

Kerf: the wire melts a slot ``kerf`` wide centred on it, so the wire runs kerf/2 outside the part,
measured normal to the cut surface: on a cone of slope Δr/t that is (kerf/2)·√(t² + Δr²)/t in the
face planes. On a cone the two faces' wire ends move at different speeds and melt different slots
(FreeCAD FoamCut scales kerf with speed): each face is compensated by its own kerf. Chords: an arc of radius r is cut in steps whose sagitta is at most ``CHORD_MM``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.fabrication.layup import SheetPlan
from antenna_cad.fabrication.outline import Piece

CHORD_MM = 0.02             # sagitta of a chord of the wire path (the check allows 0.05 mm)
SIMPLIFY_MM = 0.005         # straight pieces: vertices closer to a straight run than this are dropped


@dataclass(frozen=True)
class RuledCut:
    """One piece's cut: ``front`` and ``back`` are matched closed contours (N, 2), sheet frame mm,
    kerf-compensated (the wire's path), starting at the entry point (the top), counter-clockwise."""
    part: str
    front: np.ndarray
    back: np.ndarray
    z_front_mm: float
    z_back_mm: float
    kerf_mm: float
    cone: bool              # a taper-cut lens piece (else vertical edges)
    face_kerf_mm: tuple[float, float] | None = None     # (front, back) kerf of a cone's faces; None: kerf_mm

    @property
    def kerfs(self) -> tuple[float, float]:
        return self.face_kerf_mm or (self.kerf_mm, self.kerf_mm)

    @property
    def thickness_mm(self) -> float:
        return self.z_back_mm - self.z_front_mm


def _arc(r: float, a0: float, a1: float, count: int) -> np.ndarray:
    a = np.linspace(a0, a1, count + 1)
    return np.stack([r * np.cos(a), r * np.sin(a)], -1)


def _arc_count(r_max: float, sweep: float) -> int:
    step = 2 * math.acos(max(-1.0, 1 - CHORD_MM / max(r_max, CHORD_MM)))
    return max(1, math.ceil(abs(sweep) / step))


def _from_top(front: np.ndarray, back: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Both contours started at the back contour's highest point (the entry)."""
    k = int(np.argmax(back[:, 1] + 1e-9 * back[:, 0]))
    return np.roll(front, -k, axis=0), np.roll(back, -k, axis=0)


def cone_ring(part: str, radii: tuple[float, float], z: tuple[float, float], kerf_mm: float,
              inward: bool = False, face_kerf_mm: tuple[float, float] | None = None) -> RuledCut:
    """The cone radii[0] → radii[1] between the faces z[0], z[1] with radial rulings, the wire kerf/2
    off it normal to the cone: outside (an outer edge) or, ``inward``, inside (a ring's inner edge);
    ``face_kerf_mm``: each face's own kerf (the wire's speed differs at the two faces)."""
    (r0, r1), t = radii, z[1] - z[0]
    k0, k1 = face_kerf_mm or (kerf_mm, kerf_mm)
    grow = (-1.0 if inward else 1.0) / 2 * math.hypot(t, r1 - r0) / t
    g0, g1 = k0 * grow, k1 * grow
    count = _arc_count(max(r0 + abs(g0), r1 + abs(g1)), 2 * math.pi)
    a = math.pi / 2 + 2 * math.pi * np.arange(count) / count          # from the top, counter-clockwise
    ring = np.stack([np.cos(a), np.sin(a)], -1)
    return RuledCut(part, (r0 + g0) * ring, (r1 + g1) * ring, z[0], z[1], kerf_mm, True, face_kerf_mm)


def cone_cut(sheet: SheetPlan, kerf_mm: float, part: str | None = None,
             face_kerf_mm: tuple[float, float] | None = None) -> RuledCut:
    """A taper-cut lens disc: its cone over the sheet (:func:`cone_ring`). A disc wider than a board
    is cut so from the blank its board strips are glued into (the strips' own cuts are straight)."""
    return cone_ring(part or sheet.label, sheet.cone_mm, (sheet.z_min_mm, sheet.z_max_mm), kerf_mm,
                     face_kerf_mm=face_kerf_mm)


def straight_cut(piece: Piece, sheet: SheetPlan, kerf_mm: float) -> RuledCut:
    """A piece with vertical edges: its outline offset kerf/2 outward, the same on both faces.
    Holes are not cut (a wire reaches them only through a slit): they go to the drilling file."""
    outline = Polygon(piece.polygon.exterior)
    path = outline.buffer(kerf_mm / 2, quad_segs=32, join_style="round") if kerf_mm > 0 else outline
    path = path.simplify(SIMPLIFY_MM, preserve_topology=True)
    pts = np.asarray(path.exterior.coords)[:-1]
    if Polygon(pts).exterior.is_ccw is False:
        pts = pts[::-1]
    front, back = _from_top(pts, pts.copy())
    return RuledCut(piece.label, front, back, sheet.z_min_mm, sheet.z_max_mm, kerf_mm, False)


def piece_cut(piece: Piece, sheet: SheetPlan, kerf_mm: float,
              face_kerf_mm: tuple[float, float] | None = None) -> RuledCut:
    """The ruled cut of a sheet's piece: the cone of a taper-cut lens disc, else vertical edges (feet,
    stepped discs, and the board strips of a taper-cut disc, whose cone is cut once they are glued)."""
    if sheet.tapered and piece.label == sheet.label:
        return cone_cut(sheet, kerf_mm, face_kerf_mm=face_kerf_mm)
    return straight_cut(piece, sheet, kerf_mm)


def tower_paths(cut: RuledCut, front_wire_mm: float, span_mm: float, center: tuple[float, float]
                ) -> tuple[np.ndarray, np.ndarray]:
    """The two towers' paths (closed: the entry point repeated at the end): the wire through each
    pair of matched face points, extended to the tower planes at 0 and ``span_mm`` along the wire
    (the feed-side face at ``front_wire_mm``), in machine coordinates with the lens axis at ``center``."""
    front = np.concatenate([cut.front, cut.front[:1]])
    back = np.concatenate([cut.back, cut.back[:1]])
    slope = (back - front) / cut.thickness_mm
    c = np.asarray(center, float)
    return front - slope * front_wire_mm + c, front + slope * (span_mm - front_wire_mm) + c
