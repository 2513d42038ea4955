"""Fabrication of the slot array: 1:1 drawings of the slotted lids, beam-former plates, mirror
walls, lens and horns, the slot table (slots.csv) and the cut list. Pure numpy/shapely (no CAD
kernel); outlines come from :mod:`antenna_cad.geometry.slot_layout`, as for the solids."""

from __future__ import annotations

import csv
import io

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import MIN_TEXT_MM, Drawing, text_box
from antenna_cad.geometry.slot_layout import (GuideExtent, PartSizes, band_ring, core_and_load_rings, coupling_edge,
                                              guide_extent, horn_outlines, layer_indices, mirror_back_sign,
                                              plate_polygon, slot_bulges, slot_outline)
from antenna_cad.materials import Material
from antenna_cad.synthesis.slot_array import SlotArrayDesign, offset_curve

SLOT_FIELDS = ["guide", "cell", "slot", "slot_id", "x_mm", "y_mm", "local_x_mm", "local_y_mm",
               "length_mm", "width_mm", "offset_mm", "angle_deg"]


def slot_id(guide: int, cell: int, slot: int) -> str:
    return f"{guide:02d}.{cell:02d}.{slot}"


def slots_csv(design: SlotArrayDesign, y0s: np.ndarray) -> str:
    """One row per slot: array frame (x, y) and lid frame (from the lid's axis / start edge)."""
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
    """Vertices rounded to 0.1 µm (``tolist`` gives the Python floats ``float(x)`` would, at a
    third of the cost of iterating numpy rows: 3,200 slot rings per Ka array)."""
    return [(round(x, 4), round(y, 4)) for x, y in np.asarray(points, float).tolist()]


def _row(part: str, kind: str, material: Material, width: float, length: float, thickness: float,
         area_mm2: float, volume_mm3: float, order: int, note: str) -> CutRow:
    """Cut-list row; metal parts are milled from plate, dielectrics and absorber from stock."""
    board = "stock" if material.eps_r > 1.0 else "plate"
    return CutRow(part, kind, material.name, board, 0.0, 0.0, False, width, length, thickness, area_mm2 / 1e6,
                  volume_mm3 * material.density_kg_m3 / 1e9, order, note)


def _guide_pieces(design: SlotArrayDesign, g: int, ext: GuideExtent, t: float, metal: Material,
                  dielectric: Material, absorber: Material, title: str) -> tuple[Drawing, list[CutRow]]:
    """Lid drawing (slot ids cell.slot at every slot) and the cut-list rows of guide g."""
    s = design.slots
    h, a, w = design.guide_height_mm, design.guide_width_mm, design.wall_mm
    gx, y0, half = float(s.guide_x_mm[g]), float(ext.y0[g]), ext.half
    L = float(ext.y_end[g] - y0)
    sel = np.flatnonzero(s.guide_index == g)
    d = Drawing(f"top-{g:02d}")
    d.cut.append(_ring([(-half, 0), (half, 0), (half, L), (-half, L)]))
    for i in sel:
        slot = (float(s.x_mm[i] - gx), float(s.y_mm[i]) - y0, float(s.length_mm[i]), float(s.width_mm[i]),
                float(s.angle_rad[i]))
        d.arcs[len(d.cut)] = slot_bulges(*slot)                         # DXF: true round ends
        d.cut.append(_ring(slot_outline(*slot)))
    _slot_ids(d, [f"{int(s.cell_index[i]):02d}.{int(s.slot_in_cell[i])}" for i in sel],
              [float(s.y_mm[i]) - y0 for i in sel], half + 1.0)
    d.marks.append([(0.0, -3.0), (0.0, L + 3.0)])                      # guide axis
    d.marks.append([(-half, float(ext.y_slots_end[g]) - y0), (half, float(ext.y_slots_end[g]) - y0)])
    load = design.termination == "matched_load"
    d.add_title([f"{title} slotted lid of guide {g:02d}: {metal.name} {t:g} mm, {len(sel)} slots "
                 f"(ids cell.slot; slots.csv); y = 0 at the coupling-slot end; MARK across: end of the slots"
                 + (", load beyond" if load else "")], -half, L + 8.0, 3.0)
    d.add_check_bar(-half, -20.0)
    slot_area = float(np.sum(s.length_mm[sel] * s.width_mm[sel] - (4 - np.pi) * (s.width_mm[sel] / 2) ** 2))
    core, wedge = core_and_load_rings(a, y0, float(ext.y_slots_end[g]), float(ext.y_load_end[g]))
    cavity = a * float(ext.y_load_end[g] - y0)
    rows = [_row(f"top-{g:02d}", "slotted-lid", metal, 2 * half, L, t, 2 * half * L - slot_area,
                 (2 * half * L - slot_area) * t, 3, f"{len(sel)} slots, drawing top-{g:02d}"),
            _row(f"waveguide-{g:02d}", "guide-body", metal, 2 * half, L, h + t, 2 * half * L,
                 2 * half * L * (h + t) - cavity * h, 2,
                 ("bottom, side and end walls" if w > 0 else "bottom and end walls (wall_mm = 0: no side walls)")
                 + f"; cavity {a:g} × {h:g} mm"),
            _row(f"core-{g:02d}", "guide-core", dielectric, a, float(ext.y_load_end[g] - y0), h,
                 Polygon(core).area, Polygon(core).area * h, 2,
                 f"εr {design.fill_eps_r:g}" + ("; tapered end: wedge to the load" if wedge else ""))]
    if wedge:
        rows.append(_row(f"load-{g:02d}", "load-wedge", absorber, a, design.load_length_mm, h, Polygon(wedge).area,
                         Polygon(wedge).area * h, 2, "matched load: absorber wedge against the end wall"))
    return d, rows


def _slot_ids(d: Drawing, ids: list[str], ys: list[float], x: float) -> None:
    """Slot ids beside the lid at their slots' y, ``MIN_TEXT_MM`` high: in as many columns as
    it takes for the ids of one column to stand a line apart."""
    h = MIN_TEXT_MM
    width = max((text_box(i, h)[0] for i in ids), default=0.0) + 2.0
    last: list[float] = []                                             # per column: y of its last id
    for k in sorted(range(len(ids)), key=lambda k: ys[k]):
        col = next((c for c, y in enumerate(last) if ys[k] - y >= 1.5 * h), len(last))
        last[col:col + 1] = [ys[k]]
        d.texts.append((ids[k], x + col * width, ys[k] - h / 2, h))


def fabricate_slot_array(design: SlotArrayDesign, dielectric: Material, metal: Material, absorber: Material,
                         sizes: PartSizes, *, title: str) -> FabPlan:
    bf, s = design.beamformer, design.slots
    t = sizes.broad_wall_mm
    ext = guide_extent(design, design.wall_mm, t)
    rows: list[CutRow] = []
    drawings: list[Drawing] = []
    for g in range(len(s.guide_x_mm)):
        d, r = _guide_pieces(design, g, ext, t, metal, dielectric, absorber, title)
        drawings.append(d)
        rows += r
    horns = horn_outlines(design, sizes)
    n_layers = max(max(layer_indices(m)) for m in bf.mirrors)
    for k in range(n_layers):
        d = Drawing(f"plate-{k}")
        outline = plate_polygon(design, k, sizes, horns)
        d.add_polygon(outline)
        holes = [m for m in bf.mirrors if layer_indices(m)[0] == k and k > 0]
        area = outline.area
        for m in holes:
            ring = band_ring(m, coupling_edge(design, m))
            d.cut.append(ring)
            area -= Polygon(ring).area
        for m in bf.mirrors:                                            # mirror lines to align walls
            d.marks.append(_ring(m.points_mm[:: max(1, len(m.points_mm) // 200)]))
        for c in design.feeds.aperture_centres_mm:
            d.add_cross(float(c[0]), float(c[1]), 3.0)
        x0, y0, x1, y1 = outline.bounds
        d.add_title([f"{title} plate-{k}: {metal.name} {t:g} mm, "
                     + (f"{len(holes)} coupling slot(s) {design.coupling_slot_mm:g} mm" if holes else "base plate")
                     + ("; notched for the horns" if k <= 1 else "")
                     + "; MARK: mirror faces, + feed aperture centres"], x0, y1 + 8.0)
        d.add_check_bar(x0, y0 - 20.0)
        drawings.append(d)
        rows.append(_row(f"plate-{k}", "beamformer-plate", metal, x1 - x0, y1 - y0, t, area, area * t, 1,
                         f"{len(holes)} coupling slot(s)" if holes else "base plate"))
    for j, m in enumerate(bf.mirrors, start=1):
        back = offset_curve(m, mirror_back_sign(design, m) * sizes.mirror_wall_mm, f"{m.name}_back")
        ring = band_ring(m, back)
        hgt = design.layer_height_mm * len(layer_indices(m)) + t * (len(layer_indices(m)) - 1)
        d = Drawing(f"mirror-{j}")
        d.cut.append(ring)
        d.add_title([f"{title} mirror-{j} ({m.layer}): {metal.name} wall {sizes.mirror_wall_mm:g} mm, "
                     f"height {hgt:g} mm"], float(m.points_mm[0, 0]), float(m.points_mm[:, 1].max()) + 12.0)
        d.add_check_bar(float(m.points_mm[0, 0]), float(m.points_mm[:, 1].min()) - 20.0)
        drawings.append(d)
        length = float(np.sum(np.linalg.norm(np.diff(m.points_mm, axis=0), axis=1)))
        rows.append(_row(f"mirror-{j}", "mirror-wall", metal, length, hgt, sizes.mirror_wall_mm,
                         Polygon(ring).area, Polygon(ring).area * hgt, 2, "C1 curve: mill to the drawing"))
    for j, lens in enumerate(bf.lenses, start=1):
        label = f"lens-{j}" if len(bf.lenses) > 1 else "lens"
        ring = band_ring(bf.mirrors[0], lens)
        d = Drawing(label)
        d.cut.append(ring)
        area = Polygon(ring).area
        d.add_title([f"{title} {label}: {dielectric.name} εr {design.fill_eps_r:g}, thickness "
                     f"{design.layer_height_mm:g} mm"], ring[0][0], max(p[1] for p in ring) + 12.0)
        d.add_check_bar(ring[0][0], min(p[1] for p in ring) - 20.0)
        drawings.append(d)
        rows.append(_row(label, "lens-region", dielectric, float(np.ptp([p[0] for p in ring])),
                         float(np.ptp([p[1] for p in ring])), design.layer_height_mm, area,
                         area * design.layer_height_mm, 2, ""))
    h1 = design.layer_height_mm
    for k, horn in enumerate(horns, start=1):
        d = Drawing(f"horn-{k}")
        d.add_polygon(horn.footprint)
        d.marks.append(_ring(horn.channel.exterior.coords[:-1]))
        x0, y0, _, y1 = horn.footprint.bounds
        d.add_title([f"{title} horn-{k}: split block, {metal.name}. CUT: outline of body ({t + h1:g} mm) and "
                     f"lid ({t:g} mm); MARK: channel, pocket {h1:g} mm deep through both ends"], x0, y1 + 8.0)
        d.add_check_bar(x0, y0 - 20.0)
        drawings.append(d)
        area = horn.footprint.area
        f = design.feeds
        rows.append(_row(f"horn-{k}", "feed-horn", metal, f.aperture_mm[0] + 2 * sizes.horn_wall_mm,
                         f.length_mm + sizes.flange_thickness_mm, 2 * t + h1, area,
                         area * (2 * t + h1) - horn.channel.area * h1, 4,
                         f"H-sectoral {f.throat_mm[0]:g} → {f.aperture_mm[0]:g} mm, E {h1:g} mm; body + lid"))
    totals = {name: sum(r.mass_kg for r in rows if r.material == name)
              for name in dict.fromkeys(m.name for m in (metal, dielectric, absorber))}
    totals["all"] = sum(r.mass_kg for r in rows)
    rows.sort(key=lambda r: (r.assembly_order, r.part))
    return FabPlan((), {}, {}, tuple(drawings), tuple(rows), totals, {}, 0.0,
                   files={"slots.csv": slots_csv(design, ext.y0)})
