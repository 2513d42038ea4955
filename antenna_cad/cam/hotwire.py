"""Hot-wire ruled surfaces of a sheet's pieces: matched contours on the two foam faces.

A wire cuts a ruled surface: the straight line between a point of the contour on the feed-side face
(z_min) and the matching point on the antenna-side face (z_max). A taper-cut lens disc is the cone
through the lens profile at the two faces (radial rulings), a board strip of it also has the planes
of its butt joints; every other piece has vertical edges (front = back, XY = UV on the machine).

Kerf: the wire melts a slot ``kerf`` wide centred on it, so the wire runs kerf/2 outside the part,
measured normal to the cut surface: on a cone of slope Δr/t that is (kerf/2)·√(t² + Δr²)/t in the
face planes. Chords: an arc of radius r is cut in steps whose sagitta is at most ``CHORD_MM``.
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

    @property
    def thickness_mm(self) -> float:
        return self.z_back_mm - self.z_front_mm


def _arc(r: float, a0: float, a1: float, count: int) -> np.ndarray:
    a = np.linspace(a0, a1, count + 1)
    return np.stack([r * np.cos(a), r * np.sin(a)], -1)


def _arc_count(r_max: float, sweep: float) -> int:
    step = 2 * math.acos(max(-1.0, 1 - CHORD_MM / max(r_max, CHORD_MM)))
    return max(1, math.ceil(abs(sweep) / step))


def _strip(r: float, lo: float, hi: float, counts: tuple[int, int]) -> np.ndarray:
    """Closed contour (without the repeated first point) of the disc of radius r cut to
    lo ≤ x ≤ hi (±inf: no cut), counter-clockwise from the right cut's top corner (the disc's top
    when uncut); ``counts``: chords of the upper and lower arcs."""
    if lo == -math.inf and hi == math.inf:
        return _arc(r, math.pi / 2, math.pi / 2 + 2 * math.pi, counts[0])[:-1]
    if not (-r < lo < r or lo == -math.inf) or not (-r < hi < r or hi == math.inf):
        raise ValueError("the strip's cut lines miss the disc at this face")
    right = math.atan2(math.sqrt(r * r - hi * hi), hi) if hi < math.inf else None
    left = math.atan2(math.sqrt(r * r - lo * lo), lo) if lo > -math.inf else None
    if right is None:                                   # cut on the left only: one arc round the right
        return _arc(r, -left, left, counts[0])          # the left line closes it
    if left is None:                                    # cut on the right only
        return _arc(r, right, 2 * math.pi - right, counts[0])
    top = _arc(r, right, left, counts[0])
    bottom = _arc(r, 2 * math.pi - left, 2 * math.pi - right, counts[1])
    return np.concatenate([top, bottom])


def _cuts(poly: Polygon, r: float) -> tuple[str, float, float]:
    """The board cut lines of a disc strip: axis ("x": lines x = c, "y": y = c) and lo/hi."""
    x0, y0, x1, y1 = poly.bounds
    eps = 1e-6 * max(r, 1.0)
    if x0 > -r + eps or x1 < r - eps:
        return "x", x0 if x0 > -r + eps else -math.inf, x1 if x1 < r - eps else math.inf
    if y0 > -r + eps or y1 < r - eps:
        return "y", y0 if y0 > -r + eps else -math.inf, y1 if y1 < r - eps else math.inf
    return "x", -math.inf, math.inf


def _from_top(front: np.ndarray, back: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Both contours started at the back contour's highest point (the entry)."""
    k = int(np.argmax(back[:, 1] + 1e-9 * back[:, 0]))
    return np.roll(front, -k, axis=0), np.roll(back, -k, axis=0)


def cone_cut(piece: Piece, sheet: SheetPlan, kerf_mm: float) -> RuledCut:
    """A taper-cut lens disc (or a board strip of it): the cone r0 → r1 over the sheet, kerf/2
    normal to the cone (the strip's joint planes kerf/2 outward)."""
    t, r0, r1 = sheet.thickness_mm, sheet.front_radius_mm, sheet.radius_mm
    grow = kerf_mm / 2 * math.hypot(t, r1 - r0) / t
    axis, lo, hi = _cuts(piece.polygon, r1)
    lo, hi = lo - kerf_mm / 2, hi + kerf_mm / 2
    rf, rb = r0 + grow, r1 + grow
    sweep = 2 * math.pi
    counts = (_arc_count(rb, sweep), _arc_count(rb, sweep))
    try:
        front, back = _strip(rf, lo, hi, counts), _strip(rb, lo, hi, counts)
    except ValueError:
        raise ValueError(f"fabrication.edge: taper: {piece.label} vanishes from a board strip at its "
                         f"front face (cone radius {r0:.1f} mm); use wider boards") from None
    if axis == "y":                          # computed in the frame (u, v) = (y, −x), where the cuts are u = c
        front, back = (np.stack([-c[:, 1], c[:, 0]], -1) for c in (front, back))
    front, back = _from_top(front, back)
    return RuledCut(piece.label, front, back, sheet.z_min_mm, sheet.z_max_mm, kerf_mm, True)


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


def piece_cut(piece: Piece, sheet: SheetPlan, kerf_mm: float) -> RuledCut:
    """The ruled cut of a sheet's piece: a cone for a taper-cut lens piece, else vertical edges."""
    if sheet.tapered and "-foot" not in piece.label:
        return cone_cut(piece, sheet, kerf_mm)
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
