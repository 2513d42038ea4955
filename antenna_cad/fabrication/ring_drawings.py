"""Templates of a Luneburg sheet layup: one assembly drawing per sheet, one 1:1 drawing per ring
(its sectors' cut paths in place) and per stand foot, all in the sheet frame, with dowel hole
marks and title blocks. :class:`SheetDrawings` builds them a sheet at a time, when a writer asks:
a 3 m layup has 4,456 ring templates that a ``validate`` or a build without templates
never draws."""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable, Iterator, Sequence

import numpy as np
from shapely.geometry import LineString, Point
from shapely.ops import unary_union

from antenna_cad.fabrication.outline import CHORD_TOL_MM, Circle, arc_paths
from antenna_cad.fabrication.ring_pieces import FootPiece, RingPiece, _arc, _suffix
from antenna_cad.fabrication.ring_plan import RingLayupPlan, RingSheet
from antenna_cad.fabrication.piece_labels import Label, place_labels
from antenna_cad.fabrication.templates import Drawing


LABEL_ANGLES = 36          # spots tried for a ring's name in the assembly view, around its band


# ---------------------------------------------------------------- templates

class SheetDrawings(Sequence):
    """The layup's drawings in sheet order (each sheet's assembly view, its rings, its foot), built
    lazily by ``build(sheet_index)`` one sheet at a time (the last sheet's kept); the labels (per
    sheet: ``groups``) and the count are known without drawing anything, ``weights`` estimates
    each sheet's share of the work (its pages). The same drawings, in the same order, as building
    them all at once."""

    def __init__(self, labels: list[list[str]], build: Callable[[int], list[Drawing]], weights: list[float]):
        self.groups = tuple(tuple(group) for group in labels)
        self.weights = list(weights)
        self.labels = tuple(label for group in labels for label in group)
        self._starts = [0]
        for group in labels:
            self._starts.append(self._starts[-1] + len(group))
        self._build = build
        self._cached: tuple[int, list[Drawing]] = (-1, [])

    def __len__(self) -> int:
        return len(self.labels)

    def sheet(self, k: int) -> list[Drawing]:
        """The drawings of the ``k``-th sheet (in plan order)."""
        if self._cached[0] != k:
            self._cached = (k, self._build(k))
        return self._cached[1]

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        if not -len(self) <= i < len(self):
            raise IndexError(i)
        i %= len(self)
        k = bisect.bisect_right(self._starts, i) - 1
        return self.sheet(k)[i - self._starts[k]]

    def __iter__(self) -> Iterator[Drawing]:
        for k in range(len(self._starts) - 1):
            yield from self.sheet(k)


def _sheet_drawing(plan: RingLayupPlan, sheet: RingSheet, parts: list[Drawing], title: str) -> Drawing:
    """The sheet's assembly view: the cut paths of its ring and foot templates ``parts`` (the same
    arrays, not drawn again), ring labels and grades, sector letters, dowel holes."""
    d = Drawing(sheet.label)
    for part in parts:
        for k, path in enumerate(part.cut):
            if k in part.arcs:
                d.arcs[len(d.cut)] = part.arcs[k]
            d.cut.append(path)
    for ring in sheet.rings:
        rm = 0.5 * (ring.r_inner_mm + ring.r_outer_mm)
        for a0 in ring.joint_angles_rad:                     # sector ids next to their first joint
            d.texts.append((_suffix(int(round((a0 - ring.sector_start_rad) / (2 * math.pi) * ring.sectors))),
                            rm * math.cos(a0 + 0.02), rm * math.sin(a0 + 0.02), 3.0))
        _mark_holes(d, ring.holes)
    _mark_holes(d, sheet.foot_holes)
    _frame_marks(d, max(sheet.radius_mm, 20.0))
    place_labels(d, [_ring_label(ring, sheet) for ring in sheet.rings])
    _title(d, [f"{title}  {sheet.label} of {plan.count}: z {sheet.z_min_mm:g} to {sheet.z_max_mm:g} mm, "
               f"thickness {sheet.thickness_mm:g} mm, {len(sheet.rings)} rings ({plan.sizing} sizing)",
               "grades, inside out: " + ", ".join(f"{r.label[-7:]} {r.material.name}" for r in sheet.rings),
               "assembly view, seen from +Z: each ring is cut from its own grade (see the ring templates); "
               "dowel holes (T: drilled into the top face, B: the bottom face; positions as seen from +Z) "
               "take dowels of the ring's grade"])
    return d


def _ring_label(ring, sheet: RingSheet) -> Label:
    """The ring's name (else its number) inside the band of radii that is its alone (``contain`` rings
    overlap their neighbours until turned), clear of the joints, holes and other texts: on the band's
    middle circle, from an angle that differs from ring to ring (the grades are in the title block)."""
    lo = max([ring.r_inner_mm] + [r.r_outer_mm for r in sheet.rings if r.shell_index < ring.shell_index])
    hi = min([ring.r_outer_mm] + [r.r_inner_mm for r in sheet.rings
                                  if r.shell_index > ring.shell_index and r.r_inner_mm > lo])
    if hi - lo < 1e-3:
        lo, hi = ring.r_inner_mm, ring.r_outer_mm
    centre = Point(0.0, 0.0)
    band = centre.buffer(hi, 256).difference(centre.buffer(lo, 256)) if lo > 0 else centre.buffer(hi, 256)
    joints = [LineString([(0.0, 0.0), (2 * hi * math.cos(j), 2 * hi * math.sin(j))]) for j in ring.joint_angles_rad]
    piece = band.difference(unary_union(joints).buffer(0.5)) if joints else band
    a, rm = math.radians(20 + 25 * (ring.shell_index % 7)) + 2 * np.pi * np.arange(LABEL_ANGLES) / LABEL_ANGLES, \
        0.5 * (lo + hi)
    spots = np.stack([rm * np.cos(a), rm * np.sin(a)], -1)
    parts = list(getattr(piece, "geoms", [piece]))
    piece = next((p for p in parts if p.contains(Point(spots[0]))), max(parts, key=lambda p: p.area))
    name = ring.label[-7:]
    return (name, name[-2:]), piece, spots


def _foot_drawing(plan: RingLayupPlan, sheet: RingSheet, piece: FootPiece, title: str) -> Drawing:
    """A stand foot in the sheet frame, the lens centre at the cross."""
    d = Drawing(piece.label)
    path = piece.cut_path(plan.kerf_mm)                       # the cradle follows the lens circle
    d.add_polygon(path, arc_paths(path, [Circle(0.0, 0.0, plan.lens_radius_mm - plan.kerf_mm / 2,
                                                CHORD_TOL_MM, plan.lens_radius_mm)]))
    _mark_holes(d, piece.holes)
    d.add_cross(0.0, 0.0, 10.0)
    _title(d, [f"{title}  {piece.label}: stand foot of {sheet.label} (z {sheet.z_min_mm:g} to "
               f"{sheet.z_max_mm:g} mm), lens centre at the cross",
               f"grade {piece.material.name}, board thickness {sheet.thickness_mm:g} mm; "
               + (_holes_text(piece.holes) if piece.holes else "no dowel holes")
               + f"; CUT = tool path (kerf {plan.kerf_mm:g} mm)"])
    return d


def _ring_drawing(plan: RingLayupPlan, sheet: RingSheet, pieces: list[RingPiece], title: str) -> Drawing:
    """One ring's template in the sheet frame (centre cross, +X tick: the holes' reference): the
    whole ring, or every sector's own cut path where it lies in the ring, its letter inside it.
    One drawing per ring, not per sector: a 3 m layup has 31,700 sectors, and the
    sectors of a ring differ only in their holes, all marked here."""
    ring = pieces[0].ring
    d = Drawing(ring.label)
    paths = [piece.cut_path(plan.kerf_mm) for piece in pieces]
    for piece, path in zip(pieces, paths):
        d.add_polygon(path, piece.cut_arcs(plan.kerf_mm))
    rm = 0.5 * (ring.r_inner_mm + ring.r_outer_mm)
    if ring.sectors > 1:
        where = (f"{ring.sectors} sectors {pieces[0].label} to {pieces[-1].label}, counter-clockwise from "
                 f"{math.degrees(ring.sector_start_rad) % 360:.2f}° of the sheet frame, "
                 f"{360 / ring.sectors:.4g}° each: each outline is one piece (its name or letter inside); "
                 "cut them apart and butt-joint them radially")
    else:
        where = "one piece"
    _frame_marks(d, max(ring.r_outer_mm, 20.0))
    _mark_holes(d, ring.holes)
    spots = [0.5 * (p.a0_rad + p.a1_rad) if ring.sectors > 1 else math.pi / 2 for p in pieces]
    place_labels(d, [((p.label, p.label.rsplit("-", 1)[1]) if ring.sectors > 1 else (p.label,), path,
                      (rm * math.cos(a), rm * math.sin(a))) for p, path, a in zip(pieces, paths, spots)])
    d.pieces_named = True
    holes = _holes_text(ring.holes) if ring.holes else "no dowel holes"
    _title(d, [f"{title}  {ring.label}: sheet {sheet.label} (z {sheet.z_min_mm:g} to {sheet.z_max_mm:g} mm), "
               f"ring of shell {ring.shell_index:02d}; {where}",
               f"grade {ring.material.name}: εr {ring.material.eps_r:.4g}, {ring.material.density_kg_m3:.4g} kg/m³, "
               f"board thickness {sheet.thickness_mm:g} mm",
               f"R out {ring.r_outer_mm:.2f} mm, R in {ring.r_inner_mm:.2f} mm; {holes}; CUT = tool path "
               f"(kerf {plan.kerf_mm:g} mm); drawn in the sheet frame: align the +X tick with the sheet's +X mark"])
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


def _mark_holes(drawing: Drawing, holes) -> None:
    """Blind holes on MARK: a circle, a cross, and "T"/"B" for the face they are drilled from ("TB":
    drilled from both faces at one spot); through holes are CUT paths already."""
    faces: dict[tuple[float, float, float], str] = {}
    for h in holes:
        if h.face != "through":
            key = (round(h.x_mm, 6), round(h.y_mm, 6), h.diameter_mm)
            faces[key] = faces.get(key, "") + ("T" if h.face == "top" else "B")
    for (x, y, diameter), face in faces.items():
        drawing.marks.append(_arc(diameter / 2, 0.0, 2 * math.pi, 48, False) + (x, y))
        drawing.add_cross(x, y, diameter * 0.4)
        drawing.texts.append(("".join(sorted(face, reverse=True)), x + diameter * 0.7, y, 3.0))


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
