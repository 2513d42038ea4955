"""Foam sheet layup of the graded-index lens (seed-001 §3.2): every slab of constant
permittivity cut from foam sheets of its grade, stacked along the extrusion.

The lens is planar — its section n(y) extruded by the plate spacing (the seed's §3.1 parallel-plate
set-up) — so each sheet's outline is its slab's section and the sheets stack along z, between the
plates. Sheet layer j spans z ∈ [−H/2 + (j−1)·t, −H/2 + j·t]; when H is not a multiple of t the top
layer is planed down to the remainder. Every sheet carries its slab's foam grade (the slab's εr, the
base material's loss and density). The plan is the single description that the 3-D model
(:mod:`antenna_cad.geometry.graded`) and the templates render, as for the other layups
(:mod:`antenna_cad.fabrication.layup`).

Frame: the synthesis frame in mm (x the lens axis, y transverse), z the extrusion centred on 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.graded import slab_material, slab_pieces, slabs_csv
from antenna_cad.fabrication.nesting import nest
from antenna_cad.fabrication.outline import Piece, split_for_board
from antenna_cad.fabrication.piece_labels import place_labels
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.graded_design import GradedDesign

PLANE_TOL_MM = 1e-6          # a top layer thinner than t by less than this is a whole sheet


@dataclass(frozen=True)
class GradedSheet:
    index: int               # 1 = first laid (bottom plate, slab order in y)
    piece: str               # slab piece label: "slab-03-top"
    slab: int                # slab index k (0: the central band)
    layer: int               # 1 = on the bottom plate
    z_min_mm: float
    z_max_mm: float
    outline: Polygon         # the slab's section, mm
    material: Material       # the slab's foam grade
    eps_r: float

    @property
    def label(self) -> str:
        return f"{self.piece}-sheet-{self.layer}"

    @property
    def thickness_mm(self) -> float:
        return self.z_max_mm - self.z_min_mm

    @property
    def radius_mm(self) -> float:
        """Outer |y| of the sheet (the distance of its far edge from the lens axis)."""
        _, y0, _, y1 = self.outline.bounds
        return max(abs(y0), abs(y1))

    has_neck = False

    def manifest_extra(self) -> dict:
        return {"material": self.material.name, "slab": self.slab, "piece": self.piece, "layer": self.layer,
                "eps_r": self.eps_r}


@dataclass(frozen=True)
class GradedLayup:
    sheet_thickness_mm: float
    height_mm: float
    layers: int
    kerf_mm: float
    board_width_mm: float
    board_length_mm: float
    sheets: tuple[GradedSheet, ...]

    @property
    def count(self) -> int:
        return len(self.sheets)

    @property
    def top_layer_mm(self) -> float:
        return self.height_mm - (self.layers - 1) * self.sheet_thickness_mm


def plan_graded_layup(design: GradedDesign, base: Material, height_mm: float, sheet_thickness_mm: float,
                      kerf_mm: float, board_width_mm: float, board_length_mm: float) -> GradedLayup:
    """Sheets of ``sheet_thickness_mm`` foam: every slab piece in every layer of the stack."""
    t = sheet_thickness_mm
    layers = max(1, math.ceil(height_mm / t - PLANE_TOL_MM / t))
    z = [-height_mm / 2 + j * t for j in range(layers)] + [height_mm / 2]
    pieces = slab_pieces(design)
    sheets = tuple(GradedSheet(j * len(pieces) + i + 1, label, k, j + 1, z[j], z[j + 1], poly,
                               slab_material(base, design.slab_eps[k]), float(design.slab_eps[k]))
                   for j in range(layers) for i, (label, k, poly) in enumerate(pieces))
    return GradedLayup(t, height_mm, layers, kerf_mm, board_width_mm, board_length_mm, sheets)


def fabricate_graded_layup(design: GradedDesign, layup: GradedLayup, title: str) -> FabPlan:
    """Pieces (a sheet, or its strips when it fits no board), nesting on boards of each grade, the
    cut list (a row per piece with its grade) and a 1:1 template per sheet."""
    pieces, joints = [], {}
    for s in layup.sheets:
        parts, js = split_for_board(Piece(s.label, s.index, s.outline, s.thickness_mm),
                                    layup.board_width_mm, layup.board_length_mm, layup.kerf_mm)
        pieces += parts
        joints[s.index] = tuple(js)
    sheet_of = {s.index: s for s in layup.sheets}
    placements = {}
    for grade in dict.fromkeys(s.material.name for s in layup.sheets):
        items = [(p.label, *_size(p.cut_path(layup.kerf_mm))) for p in pieces
                 if sheet_of[p.sheet_index].material.name == grade]
        placements |= {pl.key: pl for pl in nest(items, layup.board_width_mm, layup.board_length_mm, grade)}
    rows, totals = [], {}
    for p in pieces:
        s, pl = sheet_of[p.sheet_index], placements[p.label]
        w, h = _size(p.polygon)
        kg = p.polygon.area * p.thickness_mm / 1e9 * s.material.density_kg_m3
        totals[s.material.name] = totals.get(s.material.name, 0.0) + kg
        note = f"grade εr {s.eps_r:.4f}; layer {s.layer} of {layup.layers}"
        if s.thickness_mm < layup.sheet_thickness_mm - PLANE_TOL_MM:
            note += f"; plane to {s.thickness_mm:.3f} mm"
        rows.append(CutRow(p.label, "sheet" if p.label == s.label else "sheet-strip", s.material.name,
                           pl.board_id, pl.x_mm, pl.y_mm, pl.rotated, w, h, layup.sheet_thickness_mm,
                           p.polygon.area / 1e6, kg, s.index, note))
    totals["all"] = sum(totals.values())
    boards = {}
    for pl in placements.values():
        boards.setdefault(pl.board_id.rsplit("-B", 1)[0], set()).add(pl.board_id)
    drawings = tuple(_sheet_drawing(layup, s, [p for p in pieces if p.sheet_index == s.index], title)
                     for s in layup.sheets)
    return FabPlan(tuple(pieces), placements, joints, drawings, tuple(rows), totals,
                   {m: len(ids) for m, ids in boards.items()}, layup.kerf_mm, {"slabs.csv": slabs_csv(design)})


def _size(poly) -> tuple[float, float]:
    x0, y0, x1, y1 = poly.bounds
    return x1 - x0, y1 - y0


def _sheet_drawing(layup: GradedLayup, sheet: GradedSheet, pieces: list[Piece], title: str) -> Drawing:
    drawing = Drawing(sheet.label)
    for p in pieces:
        drawing.add_polygon(p.cut_path(layup.kerf_mm))
    if sheet.slab == 0:                                                  # the lens axis
        bx0, _, bx1, _ = sheet.outline.bounds
        drawing.marks.append([(bx0 - 10.0, 0.0), (bx1 + 10.0, 0.0)])
    if len(pieces) > 1:                                                  # names inside, off the axis
        place_labels(drawing, [((p.label,), p.cut_path(layup.kerf_mm), None) for p in pieces])
        drawing.pieces_named = True
    x0, y0, _, y1 = drawing.bounds()
    drawing.add_title([f"{title}: {sheet.label} 1:1 (sheet {sheet.index} of {layup.count}), foam grade "
                       f"{sheet.material.name}, sheet {layup.sheet_thickness_mm:g} mm, layer {sheet.layer} of "
                       f"{layup.layers}, z {sheet.z_min_mm:.3f} to {sheet.z_max_mm:.3f} mm",
                       f"CUT = tool path (kerf {layup.kerf_mm:g} mm); x along the lens axis, y across it"],
                      x0, y1 + 10.0)
    drawing.add_check_bar(x0, y0 - 20.0)
    return drawing
