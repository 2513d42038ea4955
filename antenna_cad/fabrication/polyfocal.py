"""Fabrication plan of a polyfocal constrained lens (seed-001 §6, §8.1): the line table (CSV), the
1:1 section template of a 2-D lens (outline, channels, axis), the cut list and the masses.

Frame of the template: drawing x = y (transverse), drawing y = z (axis), mm, lens centre at 0.
"""

from __future__ import annotations

import io

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.polyfocal_design import PolyfocalDesign

LINE_COLUMNS = ("element", "x1_mm", "y1_mm", "z1_mm", "x2_mm", "y2_mm", "z2_mm", "l_synth_mm",
                "l_electrical_mm", "length_mm", "phase_index", "width_mm", "fill_eps_r")


def outline_polygon(design: PolyfocalDesign) -> Polygon:
    """2-D lens section in (y, z) mm: entry curve then exit curve reversed."""
    r1 = design.dense.r1 * design.unit_mm
    r2 = design.dense.r2 * design.unit_mm
    return Polygon([(y, z) for _, y, z in r1] + [(y, z) for _, y, z in r2[::-1]])


def channel_quads(design: PolyfocalDesign) -> list[list[tuple[float, float]]]:
    """Each 2-D channel in (y, z) mm: the rectangle of width a_i about the line from r1 to r2."""
    quads = []
    for p, q, w in zip(design.r1_mm[:, 1:], design.r2_mm[:, 1:], design.width_mm):
        t = (q - p) / np.linalg.norm(q - p)
        n = np.array([-t[1], t[0]]) * w / 2
        quads.append([tuple(p - n), tuple(p + n), tuple(q + n), tuple(q - n)])
    return quads


def line_rows(design: PolyfocalDesign) -> list[tuple]:
    """One row per element (LINE_COLUMNS): the table of lengths."""
    r1, r2 = design.r1_mm, design.r2_mm
    return [(i + 1, *map(float, r1[i]), *map(float, r2[i]), float(design.elements.l[i] * design.unit_mm),
             float(design.electrical_mm[i]), float(design.length_mm[i]), float(design.index[i]),
             float(design.width_mm[i]), float(design.fill_eps_r[i])) for i in range(len(r1))]


def lines_csv(design: PolyfocalDesign) -> str:
    buf = io.StringIO()
    buf.write(",".join(LINE_COLUMNS) + "\n")
    for row in line_rows(design):
        buf.write(",".join(str(row[0]) if k == 0 else f"{v:.6f}" for k, v in enumerate(row)) + "\n")
    return buf.getvalue()


def channel_clearance_check(design: PolyfocalDesign, wall_mm: float) -> Check:
    """2-D: the smallest septum between neighbouring channels (≥ the spec's wall)."""
    quads = [Polygon(q) for q in channel_quads(design)]
    gap = min(a.distance(b) for a, b in zip(quads, quads[1:]))
    return Check("channel_septum", "pass" if gap >= wall_mm - 1e-9 else "fail", float(gap), wall_mm, "mm",
                 f"thinnest septum between neighbouring channels: {gap:.4g} mm (minimum {wall_mm:g} mm)")


def fabricate_polyfocal(design: PolyfocalDesign, fill: Material, metal: Material, plate_mm: float,
                        margin_mm: float, title: str) -> FabPlan:
    h = design.height_mm
    files = {"lines.csv": lines_csv(design)}
    fill_vol = float(np.sum(design.width_mm * design.length_mm * h))
    fill_kg = fill_vol / 1e9 * fill.density_kg_m3
    rows = [CutRow("channels", "channel-fill", fill.name, "stock", 0, 0, False, 0, 0, h, 0, fill_kg,
                   2, f"{len(design.length_mm)} channels, lengths and fills in lines.csv")]
    drawings = ()
    metal_kg = 0.0
    if design.case.startswith("2d"):
        outline = outline_polygon(design)
        plate = outline.buffer(margin_mm, join_style=2)
        minx, miny, maxx, maxy = plate.bounds
        plate_kg = plate.area * plate_mm / 1e9 * metal.density_kg_m3
        body = outline.area - sum(Polygon(q).intersection(outline).area for q in channel_quads(design))
        body_kg = body * h / 1e9 * metal.density_kg_m3
        metal_kg = 2 * plate_kg + body_kg
        rows += [CutRow(f"plate-{s}", "metal-plate", metal.name, "stock", 0, 0, False, maxx - minx, maxy - miny,
                        plate_mm, plate.area / 1e6, plate_kg, 1 if s == "bottom" else 3, "outline + margin")
                 for s in ("bottom", "top")]
        rows.append(CutRow("septa", "metal-septa", metal.name, "stock", 0, 0, False, maxx - minx, maxy - miny, h,
                           body / 1e6, body_kg, 2, "lens outline minus the channels (section template)"))
        d = Drawing("section")
        d.add_polygon(outline)
        for q in channel_quads(design):
            d.cut.append([(round(y, 4), round(z, 4)) for y, z in q])
        d.marks.append([(0.0, miny - 10.0), (0.0, maxy + 10.0)])
        d.add_title([f"{title}: constrained-lens section 1:1, {len(design.length_mm)} channels, plate spacing "
                     f"{h:g} mm; channel lengths in lines.csv"], minx, maxy + 20.0)
        d.add_check_bar(minx, miny - 30.0)
        drawings = (d,)
    else:
        area = sum(float(np.ptp(g[..., 0]) * np.ptp(g[..., 1])) for g in design.surfaces) * design.unit_mm**2
        metal_kg = area * 1.0 / 1e9 * metal.density_kg_m3
        rows.append(CutRow("port-plates", "metal-surface", metal.name, "stock", 0, 0, False, 0, 0, 1.0,
                           area / 1e6, metal_kg, 1, "entry and exit B-spline surfaces (STEP), bounding area"))
    totals = {fill.name: fill_kg, metal.name: metal_kg, "all": fill_kg + metal_kg}
    return FabPlan((), {}, {}, drawings, tuple(rows), totals, {}, 0.0, files)
