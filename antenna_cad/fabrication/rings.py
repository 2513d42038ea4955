"""Fabrication plan of a Luneburg sheet layup: pieces, nesting per grade (rings inside ring holes,
then boards), cut lists, dowel rows, masses and templates. The plan itself (sheets, rings, sector
splits, dowels: seed-002 §5.1) is ``ring_plan``, the pieces ``ring_pieces``, the drawings
``ring_drawings``; their public names are re-exported here."""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

from antenna_cad.fabrication.cutlist import CutRow, cutlist_csv
from antenna_cad.fabrication.nesting import Placement, nest
from antenna_cad.fabrication.outline import NEST_SPACING_MM, circle_polygon, foot_polygon
from antenna_cad.fabrication.ring_drawings import (SheetDrawings, _foot_drawing, _holes_text, _ring_drawing,
                                                  _sheet_drawing)
from antenna_cad.fabrication.ring_pieces import FootPiece, RingPiece, ring_pieces
from antenna_cad.fabrication.ring_plan import (Dowel, DowelHole, RingLayupPlan, RingPlan, RingSheet, ring_radii,
                                               plan_rings, sector_box, sector_count)
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check

__all__ = ["Dowel", "DowelHole", "FabPlanRings", "FootPiece", "RingLayupPlan", "RingPiece", "RingPlan", "RingSheet",
           "fabricate_rings", "plan_rings", "ring_pieces", "ring_radii", "sector_box", "sector_count"]


# ---------------------------------------------------------------- fabrication plan

@dataclass(frozen=True)
class FabPlanRings:
    """Same fields as ``sheets.FabPlan`` (what the pipeline reads) plus the nesting report."""
    pieces: tuple
    placements: dict[str, Placement]
    joints: dict
    drawings: Sequence[Drawing]               # SheetDrawings: built a sheet at a time when written
    rows: tuple[CutRow, ...]
    totals_kg: dict[str, float]
    boards: dict[str, int]
    kerf_mm: float
    in_hole: dict[str, str]                   # piece label -> host ring label
    in_hole_saving_m2: dict[str, float]       # grade -> board area saved by nesting in holes
    files: dict[str, str] = field(default_factory=dict)   # extra text files, as in ``FabPlan``
    cam: object = None                        # toolpaths (cam.plan.CamPlan), as in ``FabPlan``

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
    (all grades and one file per grade), dowels, mass per grade, templates per sheet, ring and foot."""
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
    draws: Sequence[Drawing] = ()
    if drawings:
        draws = _drawings(plan, pieces, title)
    return FabPlanRings(tuple(pieces), placements, {}, draws, tuple(rows), totals,
                        {m: len(ids) for m, ids in sorted(boards.items())}, kerf, in_hole, saving, files)


def _drawings(plan: RingLayupPlan, pieces: list, title: str) -> SheetDrawings:
    """Per sheet: its assembly view, one template per ring, its stand foot — drawn when asked."""
    per_sheet: dict[int, list] = {}
    per_ring: dict[str, list[RingPiece]] = {}
    for p in pieces:
        per_sheet.setdefault(p.sheet_index, []).append(p)
        if isinstance(p, RingPiece):
            per_ring.setdefault(p.ring.label, []).append(p)
    feet = {s.index: [p for p in per_sheet.get(s.index, []) if isinstance(p, FootPiece)] for s in plan.sheets}

    def build(k: int) -> list[Drawing]:
        s = plan.sheets[k]
        parts = ([_ring_drawing(plan, s, per_ring[r.label], title) for r in s.rings]
                 + [_foot_drawing(plan, s, p, title) for p in feet[s.index]])
        return [_sheet_drawing(plan, s, parts, title), *parts]

    return SheetDrawings([[s.label, *(r.label for r in s.rings), *(p.label for p in feet[s.index])]
                          for s in plan.sheets], build,
                         [s.radius_mm ** 2 + sum(r.r_outer_mm ** 2 for r in s.rings) for s in plan.sheets])


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
                     f"sheet frame (template {ring.label}), nested turned {p.nest_rotation_deg:.2f}°; butt-joint radially")
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
