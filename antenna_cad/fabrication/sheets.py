"""Fabrication plan of a sheet layup: pieces, joints, nesting, cut list and per-sheet drawings.

Assembly order (seed-000 §6.2 step 5): the box floor and side walls first, then the sheets from
the flat face (largest, index N) toward the vertex, each pinned to the previous one with its foam
dowels, then the end walls are screwed on to clamp the stack; finally sand the steps off.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from antenna_cad.fabrication.box import Panel
from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fabrication.nesting import Placement, nest
from antenna_cad.fabrication.outline import Joint, Piece, arc_paths, sheet_circles, sheet_pieces, split_for_board
from antenna_cad.fabrication.piece_labels import place_labels
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check


@dataclass(frozen=True)
class FabPlan:
    pieces: tuple[Piece, ...]
    placements: dict[str, Placement]
    joints: dict[int, tuple[Joint, ...]]      # sheet index -> board joints
    drawings: tuple[Drawing, ...]             # one per sheet (or per plate/profile)
    rows: tuple[CutRow, ...]
    totals_kg: dict[str, float]
    boards: dict[str, int]                    # material -> boards used
    kerf_mm: float
    files: dict[str, str] = field(default_factory=dict)   # extra text files: name -> content
    cam: object = None                        # antenna_cad.cam.plan.CamPlan when the spec has a cam block

    @property
    def checks(self) -> tuple[Check, ...]:
        """Checks of the plan itself (none here; the Luneburg ring plan reports its nesting)."""
        return ()


BOX_FIRST_STEPS = {"box-floor": 1, "box-wall-left": 2, "box-wall-right": 2}   # end walls go on last


def _piece_kind(piece: Piece) -> str:
    base = f"sheet-{piece.sheet_index:02d}"
    return {base: "sheet", f"{base}-foot": "sheet-foot"}.get(piece.label, "sheet-strip")


def fabricate_sheets(plan: LayupPlan, panels: tuple[Panel, ...], foam: Material, box_material: Material,
                     box_board: tuple[float, float], title: str) -> FabPlan:
    pieces: list[Piece] = []
    joints: dict[int, tuple[float, ...]] = {}
    for sheet in plan.sheets:
        sheet_joints: list[Joint] = []
        for piece in sheet_pieces(plan, sheet):
            parts, js = split_for_board(piece, plan.board_width_mm, plan.board_length_mm, plan.kerf_mm)
            pieces += parts
            sheet_joints += js
        joints[sheet.index] = tuple(sheet_joints)
    foam_items = [(p.label, *_size(p.cut_path(plan.kerf_mm))) for p in pieces]
    placements = {pl.key: pl for pl in nest(foam_items, plan.board_width_mm, plan.board_length_mm, foam.name)}
    box_items = [(p.label, *p.face_mm) for p in panels]
    placements.update({pl.key: pl for pl in nest(box_items, *box_board, box_material.name)})

    n = plan.count
    rows = []
    for p in pieces:
        pl = placements[p.label]
        w, h = _size(p.polygon)
        area = p.polygon.area / 1e6
        kind = _piece_kind(p)
        note = "joint: butt against its neighbour strip" if kind == "sheet-strip" else ""
        rows.append(CutRow(p.label, kind, foam.name, pl.board_id, pl.x_mm, pl.y_mm, pl.rotated, w, h,
                           p.thickness_mm, area, area * p.thickness_mm / 1e3 * foam.density_kg_m3,
                           3 + (n - p.sheet_index), note))
    for panel in panels:
        pl = placements[panel.label]
        w, h = panel.face_mm
        rows.append(CutRow(panel.label, "box-panel", box_material.name, pl.board_id, pl.x_mm, pl.y_mm,
                           pl.rotated, w, h, panel.thickness_mm, w * h / 1e6,
                           panel.volume_mm3 / 1e9 * box_material.density_kg_m3,
                           BOX_FIRST_STEPS.get(panel.label, n + 3),
                           f"{len(panel.holes)} screw holes" if panel.holes else ""))
    foam_kg = sum(r.mass_kg for r in rows if r.material == foam.name and r.kind != "box-panel")
    box_kg = sum(r.mass_kg for r in rows if r.kind == "box-panel")
    boards = {}
    for pl in placements.values():
        material = pl.board_id.rsplit("-B", 1)[0]
        boards.setdefault(material, set()).add(pl.board_id)
    drawings = tuple(_sheet_drawing(plan, s.index, [p for p in pieces if p.sheet_index == s.index],
                                    joints[s.index], foam, title) for s in plan.sheets)
    return FabPlan(tuple(pieces), placements, joints, drawings, tuple(sorted(rows, key=lambda r: (r.assembly_order, r.part))),
                   {f"{foam.name} (as cut)": foam_kg, f"{box_material.name} box": box_kg, "all": foam_kg + box_kg},
                   {m: len(ids) for m, ids in sorted(boards.items())}, plan.kerf_mm)


def _size(poly) -> tuple[float, float]:
    x0, y0, x1, y1 = poly.bounds
    return x1 - x0, y1 - y0


def _sheet_drawing(plan: LayupPlan, index: int, pieces: list[Piece], joints: tuple[Joint, ...],
                   foam: Material, title: str) -> Drawing:
    sheet = plan.sheets[index - 1]
    drawing = Drawing(sheet.label)
    circles = sheet_circles(plan, sheet, plan.kerf_mm)
    paths = [p.cut_path(plan.kerf_mm) for p in pieces]
    for path in paths:
        drawing.add_polygon(path, arc_paths(path, circles))
    r = sheet.radius_mm
    drawing.add_cross(0.0, 0.0, 20.0)                                   # lens axis
    for x, y in ((r, 0), (-r, 0), (0, r), (0, -r)):                      # axis marks at the rim
        drawing.marks.append([(x * 0.96, y * 0.96), (x * 0.9, y * 0.9)])
    for h in sheet.lens_dowels + sheet.foot_dowels:
        drawing.add_cross(h.x_mm, h.y_mm, h.diameter_mm * 0.3)
    y_lo, y_hi = plan.foot_bottom_y_mm - 15, plan.lens_radius_mm + 15
    x_hi = max(plan.lens_radius_mm, plan.pedestal_width_mm / 2) + 15
    for j in joints:
        drawing.marks.append([(j.at_mm, y_lo), (j.at_mm, y_hi)] if j.axis == "x" else [(-x_hi, j.at_mm), (x_hi, j.at_mm)])
    place_labels(drawing, [((p.label,), path, None) for p, path in zip(pieces, paths)])   # names inside, off the marks
    drawing.pieces_named = True
    x0, y0, _, y1 = drawing.bounds()
    lines = [f"{title}  {sheet.label} of {plan.count}: {foam.name}, thickness {sheet.thickness_mm:g} mm, "
             f"z {sheet.z_min_mm:g}-{sheet.z_max_mm:g} mm",
             f"lens disc R {sheet.radius_mm:.2f} mm; CUT = tool path (kerf {plan.kerf_mm:g} mm); "
             f"dowels: foam, same material",
             "Drawn as seen from the antenna side: the face on the table looks toward the FEED"]
    if joints:
        lines.append("MARK lines: board joints (butt joints, staggered against the next sheet)")
    drawing.add_title(lines, x0, y1 + 12)
    drawing.add_check_bar(x0, y0 - 20)
    return drawing
