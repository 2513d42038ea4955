"""Templates of a Luneburg sheet layup: one assembly drawing per sheet and one 1:1 drawing per
piece (whole rings in the sheet frame, sectors turned to their nesting orientation), with dowel
hole marks and title blocks."""

from __future__ import annotations

import math

from shapely import affinity

from antenna_cad.fabrication.outline import CHORD_TOL_MM, Circle, arc_paths
from antenna_cad.fabrication.ring_pieces import FootPiece, RingPiece, _arc, _rotated, _suffix
from antenna_cad.fabrication.ring_plan import RingLayupPlan, RingSheet
from antenna_cad.fabrication.templates import TEXT_HEIGHT_MM, Drawing


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
