"""2-D cutting outlines of layup sheets (shapely): pieces, board joints and kerf.

Arcs are polygons *circumscribed* about the true circle with a chord tolerance of
``CHORD_TOL_MM``: a part outline never cuts inside the nominal disc, and no vertex lies further
than the tolerance outside it. Coordinates are the sheet frame of ``fabrication.layup``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shapely import affinity
from shapely.geometry import Polygon, box
from shapely.ops import unary_union

from antenna_cad.fabrication.layup import Hole, LayupPlan, SheetPlan
from antenna_cad.synthesis.checks import DesignError

CHORD_TOL_MM = 0.002
NEST_SPACING_MM = 10.0       # gap between pieces and to the board edge


def circle_vertex_count(radius: float, tol: float) -> int:
    return max(24, 4 * math.ceil(math.pi * math.sqrt(radius / (2 * tol)) / 4))


def circle_polygon(x: float, y: float, radius: float, tol: float = CHORD_TOL_MM) -> Polygon:
    """Polygon whose edges are tangent to the circle (vertices at most ``tol`` outside it)."""
    count = circle_vertex_count(radius, tol)
    rv = radius / math.cos(math.pi / count)
    angles = [2 * math.pi * k / count for k in range(count)]
    return Polygon([(x + rv * math.cos(a), y + rv * math.sin(a)) for a in angles])


HOLE_TOL_MM = 0.01


def hole_polygons(holes: tuple[Hole, ...]) -> list[Polygon]:
    return [circle_polygon(h.x_mm, h.y_mm, h.diameter_mm / 2, tol=HOLE_TOL_MM) for h in holes]


@dataclass(frozen=True)
class Circle:
    """A true circle an outline follows: centre, radius (of the tool path), and the chord
    tolerance and radius of the polygon that approximated it."""
    x: float
    y: float
    r: float
    tol: float
    polygon_r: float

    def max_step_rad(self) -> float:
        return 2 * math.pi / circle_vertex_count(self.polygon_r, self.tol) * 1.01


def sheet_circles(plan: LayupPlan, sheet: SheetPlan, kerf_mm: float) -> list[Circle]:
    """The circles of a sheet's tool paths: its disc and the aperture (material inside, or the
    foot's notch outside), and its dowel holes; radii offset by half the kerf."""
    c = kerf_mm / 2
    out = [Circle(0.0, 0.0, r + s * c, CHORD_TOL_MM, r) for r in {sheet.radius_mm, plan.lens_radius_mm}
           for s in (1, -1)]
    return out + [Circle(h.x_mm, h.y_mm, h.diameter_mm / 2 - c, HOLE_TOL_MM, h.diameter_mm / 2)
                  for h in sheet.lens_dowels + sheet.foot_dowels]


def arc_paths(poly: Polygon, circles: list[Circle]) -> list[list[tuple[float, float, float]]]:
    """The polygon's rings (exterior, then holes) as DXF bulge paths: each run of vertices lying
    on one of ``circles`` (within its chord tolerance) joined by steps no longer than that
    circle's polygon step becomes true arcs (≤ 90° each, ends projected onto the circle); other
    edges stay straight. A straight chord is never taken for an arc: a chord that short sags less
    than the chord tolerance."""
    return [_ring_arcs(list(ring.coords)[:-1], circles) for ring in (poly.exterior, *poly.interiors)]


def _ring_arcs(pts, circles: list[Circle]) -> list[tuple[float, float, float]]:
    n = len(pts)

    def on(i: int) -> int:
        x, y = pts[i % n]
        return next((k for k, c in enumerate(circles) if abs(math.hypot(x - c.x, y - c.y) - c.r) <= 2 * c.tol), -1)

    def step(i: int, k: int) -> float:
        c = circles[k]
        (x0, y0), (x1, y1) = pts[i % n], pts[(i + 1) % n]
        return math.atan2((x0 - c.x) * (y1 - c.y) - (y0 - c.y) * (x1 - c.x),
                          (x0 - c.x) * (x1 - c.x) + (y0 - c.y) * (y1 - c.y))

    circle_of = [on(i) for i in range(n)]
    arc = [circle_of[i] >= 0 and circle_of[i] == circle_of[(i + 1) % n]
           and abs(step(i, circle_of[i])) <= circles[circle_of[i]].max_step_rad() for i in range(n)]
    if all(arc):                                   # a full circle: start anywhere
        start = 0
    elif not any(arc):
        return [(x, y, 0.0) for x, y in pts]
    else:
        start = next(i for i in range(n) if arc[i] and not arc[i - 1])
    out: list[tuple[float, float, float]] = []
    i = start
    while i < start + n:
        if not arc[i % n]:
            out.append((*pts[i % n], 0.0))
            i += 1
            continue
        k, sweep, j = circle_of[i % n], 0.0, i
        while j < start + n and arc[j % n] and circle_of[j % n] == k:
            sweep += step(j, k)
            j += 1
        c = circles[k]
        a0 = math.atan2(pts[i % n][1] - c.y, pts[i % n][0] - c.x)
        pieces = max(1, math.ceil(abs(sweep) / (math.pi / 2) - 1e-9))
        for p in range(pieces):
            a = a0 + sweep * p / pieces
            out.append((c.x + c.r * math.cos(a), c.y + c.r * math.sin(a), math.tan(sweep / pieces / 4)))
        i = j
        if j < start + n:                          # the run's end vertex, projected on the circle
            a = a0 + sweep
            pts[j % n] = (c.x + c.r * math.cos(a), c.y + c.r * math.sin(a))
    return out


@dataclass(frozen=True)
class Piece:
    label: str               # "sheet-03", "sheet-03-foot", "sheet-07-b"
    sheet_index: int
    polygon: Polygon         # nominal part (the size it must come out), sheet frame, mm
    thickness_mm: float

    def cut_path(self, kerf_mm: float) -> Polygon:
        """Tool-centre path: the outline offset outward (holes inward) by half the kerf."""
        return self.polygon if kerf_mm == 0 else self.polygon.buffer(kerf_mm / 2, quad_segs=64)


def foot_polygon(plan: LayupPlan, aperture: Polygon) -> Polygon:
    w = plan.pedestal_width_mm
    return box(-w / 2, plan.foot_bottom_y_mm, w / 2, plan.foot_corner_y_mm).difference(aperture)


def sheet_pieces(plan: LayupPlan, sheet: SheetPlan) -> list[Piece]:
    """The sheet's pieces before board splitting: one piece, or lens disc + foot (dowels mode)."""
    R = plan.lens_radius_mm
    aperture = circle_polygon(0.0, 0.0, R)
    disc = aperture if sheet.radius_mm >= R - 1e-9 else circle_polygon(0.0, 0.0, sheet.radius_mm)
    foot = foot_polygon(plan, aperture)
    lens_holes = unary_union(hole_polygons(sheet.lens_dowels))
    foot_holes = unary_union(hole_polygons(sheet.foot_dowels))
    t = sheet.thickness_mm
    if (sheet.radius_mm < R - 1e-9 or sheet.tapered) and not sheet.has_neck:   # a cone and a straight foot
        return [Piece(sheet.label, sheet.index, disc.difference(lens_holes), t),
                Piece(f"{sheet.label}-foot", sheet.index, foot.difference(foot_holes), t)]
    parts = [disc, foot]
    if sheet.has_neck:
        parts.append(box(-plan.neck_width_mm / 2, -R, plan.neck_width_mm / 2, 0.0))
    whole = unary_union(parts).difference(lens_holes).difference(foot_holes)
    return [Piece(sheet.label, sheet.index, whole, t)]


def added_in_aperture_mm2(plan: LayupPlan, sheet: SheetPlan) -> float:
    """Area of the sheet inside the aperture circle but outside its own lens disc (a neck)."""
    aperture = circle_polygon(0.0, 0.0, plan.lens_radius_mm)
    disc = circle_polygon(0.0, 0.0, sheet.radius_mm)
    sheet_area = unary_union([p.polygon for p in sheet_pieces(plan, sheet)])
    return float(sheet_area.intersection(aperture).difference(disc).area)


def fits_board(width: float, height: float, board_w: float, board_l: float) -> bool:
    w, h = width + 2 * NEST_SPACING_MM, height + 2 * NEST_SPACING_MM
    return (w <= board_w and h <= board_l) or (w <= board_l and h <= board_w)


@dataclass(frozen=True)
class Joint:
    axis: str          # "x": a vertical line x = at_mm; "y": a horizontal line y = at_mm
    at_mm: float


def split_for_board(piece: Piece, board_w: float, board_l: float, kerf_mm: float
                    ) -> tuple[list[Piece], list[Joint]]:
    """Split a piece that fits no board into parallel strips with butt joints.

    Tries the fewest strips first, joints across x (vertical lines) before y. Joints of
    neighbouring sheets are staggered by ±1/8 strip so they never line up in the stack. Returns
    the strips (labelled -a, -b, …; every connected component is its own piece) and the joints.
    """
    x0, y0, x1, y1 = piece.cut_path(kerf_mm).bounds
    if fits_board(x1 - x0, y1 - y0, board_w, board_l):
        return [piece], []
    for strips in range(2, 27):
        for axis in ("x", "y"):
            lo, hi = (x0, x1) if axis == "x" else (y0, y1)
            pitch = (hi - lo) / strips
            shift = (1 if piece.sheet_index % 2 else -1) * pitch / 8
            cuts = [lo + k * pitch + shift for k in range(1, strips)]
            edges = [lo - 1.0] + cuts + [hi + 1.0]
            windows = [box(a, y0 - 1, b, y1 + 1) if axis == "x" else box(x0 - 1, a, x1 + 1, b)
                       for a, b in zip(edges, edges[1:])]
            parts = [g for w in windows for g in _polygons(piece.polygon.intersection(w))]
            if all(fits_board(*_size(p.buffer(kerf_mm / 2) if kerf_mm else p), board_w, board_l)
                   for p in parts):
                return ([Piece(f"{piece.label}-{chr(97 + k)}", piece.sheet_index, p, piece.thickness_mm)
                         for k, p in enumerate(parts)], [Joint(axis, c) for c in cuts])
    raise DesignError("fabrication.board", f"piece {piece.label} ({x1 - x0:.0f} × {y1 - y0:.0f} mm) cannot "
                      f"be split into strips that fit a {board_w:g} × {board_l:g} mm board")


def _size(poly) -> tuple[float, float]:
    x0, y0, x1, y1 = poly.bounds
    return x1 - x0, y1 - y0


def _polygons(geom) -> list[Polygon]:
    """Every connected component of a cut strip is a piece of its own (nothing is dropped)."""
    parts = [geom] if isinstance(geom, Polygon) else list(geom.geoms)
    return [p for p in parts if isinstance(p, Polygon) and p.area > 1e-6]


def rotate_to_board(poly: Polygon, rotated: bool) -> Polygon:
    return affinity.rotate(poly, 90, origin=(0, 0)) if rotated else poly
