"""Fabrication of the slot array: 1:1 drawings of slotted top walls and beam-former plates,
the slot table (slots.csv) and the cut list. Pure numpy/shapely (no CAD kernel)."""

from __future__ import annotations

import csv
import io

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import TEXT_HEIGHT_MM, Drawing
from antenna_cad.geometry.slot_layout import (coupling_edge, guide_extent, layer_indices,
                                              mirror_back_sign, plate_rect, slot_outline)
from antenna_cad.materials import Material
from antenna_cad.synthesis.slot_array import Curve, SlotArrayDesign, offset_curve

SLOT_FIELDS = ["guide", "cell", "slot", "slot_id", "x_mm", "y_mm", "local_x_mm", "local_y_mm",
               "length_mm", "width_mm", "offset_mm", "angle_deg"]


def slot_id(guide: int, cell: int, slot: int) -> str:
    return f"{guide:02d}.{cell:02d}.{slot}"


def slots_csv(design: SlotArrayDesign, y0s: np.ndarray) -> str:
    """One row per slot: array frame (x, y) and strip frame (from the strip's left/start edge)."""
    s = design.slots
    buf = io.StringIO()
    wr = csv.writer(buf, lineterminator="\n")
    wr.writerow(SLOT_FIELDS)
    for i in range(s.count):
        g, c, k = int(s.guide_index[i]), int(s.cell_index[i]), int(s.slot_in_cell[i])
        wr.writerow([g, c, k, slot_id(g, c, k), f"{s.x_mm[i]:.4f}", f"{s.y_mm[i]:.4f}",
                     f"{s.offset_mm[i]:.4f}", f"{s.y_mm[i] - y0s[g]:.4f}", f"{s.length_mm[i]:.4f}",
                     f"{s.width_mm[i]:.4f}", f"{s.offset_mm[i]:.4f}", f"{np.degrees(s.angle_rad[i]):.3f}"])
    return buf.getvalue()


def _ring(points) -> list[tuple[float, float]]:
    return [(round(float(x), 4), round(float(y), 4)) for x, y in points]


def _curve_ring(a: Curve, b: Curve, n: int = 241) -> list[tuple[float, float]]:
    lo, hi = max(a.x_range_mm[0], b.x_range_mm[0]), min(a.x_range_mm[1], b.x_range_mm[1])
    xs = np.linspace(lo, hi, n)
    return _ring([(x, a.y_at(x)) for x in xs] + [(x, b.y_at(x)) for x in xs[::-1]])


def fabricate_slot_array(design: SlotArrayDesign, dielectric: Material, metal: Material, *,
                         broad_wall_mm: float, mirror_wall_mm: float, plate_margin_mm: float,
                         title: str) -> FabPlan:
    bf, s = design.beamformer, design.slots
    t, h, a, w = broad_wall_mm, design.guide_height_mm, design.guide_width_mm, design.wall_mm
    y0s, y1s, half = guide_extent(design, w)
    rows: list[CutRow] = []
    drawings: list[Drawing] = []
    rho_m, rho_d = metal.density_kg_m3 / 1e9, dielectric.density_kg_m3 / 1e9
    slot_area = s.length_mm * s.width_mm - (4 - np.pi) * (s.width_mm / 2) ** 2
    text_h = float(min(1.0, max(0.4, 0.8 * s.period_mm / 4)))
    for g, gx in enumerate(s.guide_x_mm):
        L = float(y1s[g] - y0s[g])
        sel = np.flatnonzero(s.guide_index == g)
        d = Drawing(f"top-{g:02d}")
        d.cut.append(_ring([(-half, 0), (half, 0), (half, L), (-half, L)]))
        for i in sel:
            d.cut.append(_ring(slot_outline(float(s.x_mm[i] - gx), float(s.y_mm[i] - y0s[g]),
                                            float(s.length_mm[i]), float(s.width_mm[i]), float(s.angle_rad[i]))))
            d.texts.append((f"{int(s.cell_index[i]):02d}.{int(s.slot_in_cell[i])}", half + 1.0,
                            float(s.y_mm[i] - y0s[g]) - text_h / 2, text_h))
        d.marks.append([(0.0, -3.0), (0.0, L + 3.0)])                  # guide axis
        d.texts.append((f"{title} top wall of guide {g:02d}: {metal.name} {t:g} mm, {len(sel)} slots "
                        f"(ids cell.slot; slots.csv); y = 0 at the coupling-slot end", -half, L + 8.0, 3.0))
        d.add_check_bar(-half, -20.0)
        drawings.append(d)
        top_area = 2 * half * L - float(slot_area[sel].sum())
        body = 2 * half * L * t + (2 * w * L * h)
        rows.append(CutRow(f"top-{g:02d}", "slotted-top-wall", metal.name, "plate", 0.0, 0.0, False,
                           2 * half, L, t, top_area / 1e6, top_area * t * rho_m, 3,
                           f"{len(sel)} slots, drawing top-{g:02d}"))
        rows.append(CutRow(f"waveguide-{g:02d}", "guide-body", metal.name, "plate", 0.0, 0.0, False,
                           2 * half, L, h + t, 2 * half * L / 1e6, body * rho_m, 2,
                           "bottom wall + side walls" if w > 0 else "bottom wall (wall_mm = 0: no side walls)"))
        rows.append(CutRow(f"core-{g:02d}", "guide-core", dielectric.name, "stock", 0.0, 0.0, False,
                           a, L, h, a * L / 1e6, a * L * h * rho_d, 2, f"εr {design.fill_eps_r:g}"))
    x0, y0, x1, y1 = plate_rect(design, plate_margin_mm)
    n_layers = max(max(layer_indices(m)) for m in bf.mirrors)
    for k in range(n_layers):
        d = Drawing(f"plate-{k}")
        d.cut.append(_ring([(x0, y0), (x1, y0), (x1, y1), (x0, y1)]))
        holes = [m for m in bf.mirrors if layer_indices(m)[0] == k and k > 0]
        for m in holes:
            d.cut.append(_curve_ring(m, coupling_edge(design, m)))
        for m in bf.mirrors:                                            # mirror lines to align walls
            d.marks.append(_ring(m.points_mm[:: max(1, len(m.points_mm) // 200)]))
        for c in design.feeds.aperture_centres_mm:
            d.add_cross(float(c[0]), float(c[1]), 3.0)
        d.texts.append((f"{title} plate-{k}: {metal.name} {t:g} mm, "
                        + (f"{len(holes)} coupling slot(s) {design.coupling_slot_mm:g} mm" if holes else "base plate")
                        + "; MARK: mirror faces, + feed aperture centres", x0, y1 + 8.0, TEXT_HEIGHT_MM))
        d.add_check_bar(x0, y0 - 20.0)
        drawings.append(d)
        area = (x1 - x0) * (y1 - y0)
        rows.append(CutRow(f"plate-{k}", "beamformer-plate", metal.name, "plate", 0.0, 0.0, False,
                           x1 - x0, y1 - y0, t, area / 1e6, area * t * rho_m, 1,
                           f"{len(holes)} coupling slot(s)" if holes else "base plate"))
    for j, m in enumerate(bf.mirrors, start=1):
        back_sign = mirror_back_sign(design, m)
        back = offset_curve(m, back_sign * mirror_wall_mm, f"{m.name}_back")
        d = Drawing(f"mirror-{j}")
        d.cut.append(_curve_ring(m, back))
        d.texts.append((f"{title} mirror-{j} ({m.layer}): {metal.name} wall {mirror_wall_mm:g} mm, "
                        f"height {design.layer_height_mm * len(layer_indices(m)) + t * (len(layer_indices(m)) - 1):g} mm",
                        float(m.points_mm[0, 0]), float(m.points_mm[:, 1].max()) + 12.0, TEXT_HEIGHT_MM))
        d.add_check_bar(float(m.points_mm[0, 0]), float(m.points_mm[:, 1].min()) - 20.0)
        drawings.append(d)
        length = float(np.sum(np.linalg.norm(np.diff(m.points_mm, axis=0), axis=1)))
        hgt = design.layer_height_mm * len(layer_indices(m))
        rows.append(CutRow(f"mirror-{j}", "mirror-wall", metal.name, "plate", 0.0, 0.0, False,
                           length, hgt, mirror_wall_mm, length * hgt / 1e6, length * hgt * mirror_wall_mm * rho_m,
                           2, "C1 curve: mill to the drawing"))
    for j, lens in enumerate(bf.lenses, start=1):
        label = f"lens-{j}" if len(bf.lenses) > 1 else "lens"
        m = bf.mirrors[0]
        d = Drawing(label)
        ring = _curve_ring(m, lens)
        d.cut.append(ring)
        area = Polygon(ring).area
        d.texts.append((f"{title} {label}: {dielectric.name} εr {design.fill_eps_r:g}, thickness "
                        f"{design.layer_height_mm:g} mm", ring[0][0], max(p[1] for p in ring) + 12.0, TEXT_HEIGHT_MM))
        d.add_check_bar(ring[0][0], min(p[1] for p in ring) - 20.0)
        drawings.append(d)
        rows.append(CutRow(label, "lens-region", dielectric.name, "stock", 0.0, 0.0, False,
                           float(np.ptp([p[0] for p in ring])), float(np.ptp([p[1] for p in ring])),
                           design.layer_height_mm, area / 1e6, area * design.layer_height_mm * rho_d, 2, ""))
    metal_kg = sum(r.mass_kg for r in rows if r.material == metal.name)
    diel_kg = sum(r.mass_kg for r in rows if r.material == dielectric.name)
    rows.sort(key=lambda r: (r.assembly_order, r.part))
    return FabPlan((), {}, {}, tuple(drawings), tuple(rows),
                   {f"{metal.name}": metal_kg, f"{dielectric.name}": diel_kg, "all": metal_kg + diel_kg},
                   {}, 0.0, files={"slots.csv": slots_csv(design, y0s)})
