"""The §1.5 polyfocal lens realised as the two-storey lens–mirror antenna (seed-001 §1.5 Realisation,
§8.1 item 2, §8.3): the layout (:mod:`antenna_cad.synthesis.two_storey`), its solids, the line
table and the 1:1 templates of both layers.

``lines.csv`` keeps the kind's columns (the lens read back by the σ verification) and adds the
mirror's: folded exit, kink and bend positions, the per-layer lengths and the total, equal for every
guide; ``l_electrical_mm`` is the total times the TE10 phase index at the design frequency.
"""

from __future__ import annotations

import io
from dataclasses import replace

import numpy as np
import shapely

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import solving
from antenna_cad.synthesis.polyfocal_design import PolyfocalDesign
from antenna_cad.synthesis.two_storey import (C_MM_GHZ, FIELD, TwoStorey, TwoStoreyParams, checks, layer_air, layout,
                                              outlines, pierce, slab_volumes)

COLUMNS = ("element", "x1_mm", "y1_mm", "z1_mm", "x2_mm", "y2_mm", "z2_mm", "z_exit_folded_mm", "z_kink_mm",
           "z_bend_mm", "l_layer1_mm", "l_bend_mm", "l_layer2_mm", "l_total_mm", "l_electrical_mm")


def with_mirror(spec, design: PolyfocalDesign) -> PolyfocalDesign:
    """The design with its two-storey layout; the straight-channel realisation's checks dropped."""
    g, m, ln = spec.design, spec.design.lens_mirror, spec.design.lines
    params = TwoStoreyParams(m.guide_width_mm, ln.plate_spacing_mm, m.septum_mm, ln.wall_mm,
                             m.guide_width_mm if m.bend_run_mm is None else m.bend_run_mm, m.mirror_clearance_mm,
                             m.setback_mm, m.horn_aperture_mm, m.horn_length_mm,
                             2 * m.guide_width_mm if m.horn_stub_mm is None else m.horn_stub_mm,
                             m.flare_length_mm, m.mouth_height_mm, tuple(m.band_ghz))
    e, d = design.elements, design.dense
    with solving(FIELD, "two-storey layout"):
        ts = layout(e.r1, e.r2, d.r1, d.r2, np.array([f.point for f in e.foci]), g.unit_mm, g.thickness, params)
        own, _ = checks(ts)
    kept = tuple(c for c in design.checks if c.name.startswith("focus_"))
    return replace(design, mirror=ts, checks=kept + tuple(own))


def foci_mm(design: PolyfocalDesign) -> list[tuple[np.ndarray, np.ndarray]]:
    """The design foci (point, output direction) in the (y, z) plane, mm."""
    return [(f.point[1:] * design.unit_mm, f.direction[1:]) for f in design.elements.foci]


def model(design: PolyfocalDesign, air: Material, metal: Material, plate_mm: float, margin_mm: float):
    from antenna_cad.geometry.two_storey import build_model
    return build_model(design.mirror, air, metal, plate_mm, margin_mm, foci_mm(design), design.aperture_mm)


def te10_index(ts: TwoStorey, lam_mm: float) -> float:
    return float(np.sqrt(1.0 - (lam_mm / (2 * ts.p.guide_width)) ** 2))


def lines_csv(design: PolyfocalDesign) -> str:
    ts, n = design.mirror, te10_index(design.mirror, design.wavelength_mm)
    buf = io.StringIO()
    buf.write(",".join(COLUMNS) + "\n")
    for i in range(len(ts.y1)):
        row = (0.0, ts.y1[i], ts.z1[i], 0.0, ts.y2[i], ts.z2[i], ts.ze[i], ts.zk[i], ts.zm[i], ts.l1[i], ts.l_bend,
               ts.l2[i], ts.total[i], n * ts.total[i])
        buf.write(f"{i + 1}," + ",".join(f"{float(v):.6f}" for v in row) + "\n")
    return buf.getvalue()


def _drawing(ts: TwoStorey, layer: int, outline, mouth: float, margin: float, title: str) -> Drawing:
    d = Drawing(f"layer-{layer}")
    d.add_polygon(outline)
    air = layer_air(ts, layer, mouth, pierce(margin))
    pocket = shapely.unary_union(air).intersection(outline)
    for poly in getattr(pocket, "geoms", [pocket]):
        d.add_polygon(poly)
    minx, miny, maxx, maxy = outline.bounds
    d.marks.append([(0.0, miny - 10.0), (0.0, maxy + 10.0)])
    what = ("feed region, H-plane horns at F, F1, F2, non-parallel guides to the U-bends" if layer == 1 else
            "axial output guides from the U-bends to the exit surface, output region to the mouth")
    d.add_title([f"{title}: two-storey lens–mirror antenna, layer {layer} 1:1 (pockets {ts.p.height:g} mm deep): "
                 f"{what}; bend planes and lengths in lines.csv"], minx, maxy + 20.0)
    d.add_check_bar(minx, miny - 30.0)
    return d


def fabricate(design: PolyfocalDesign, metal: Material, plate_mm: float, margin_mm: float, title: str) -> FabPlan:
    ts, h, t = design.mirror, design.mirror.p.height, design.mirror.p.septum
    mouth = 2 * ts.p.guide_width
    lower, upper = outlines(ts, mouth, margin_mm)
    cover = plate_mm + ts.p.mouth_height - h
    volumes = slab_volumes(ts, mouth, margin_mm, plate_mm)
    rows, total = [], 0.0
    notes = {"block-lower": "bottom plate, layer-1 pockets (template layer-1), U-bends' lower halves (STEP)",
             "block-upper": "septum, layer-2 pockets (template layer-2), U-bends' upper halves (STEP)",
             "cover": "top plate, E-plane flare milled in (STEP)"}
    for order, (label, poly, thick) in enumerate((("block-lower", lower, plate_mm + h), ("block-upper", upper, t + h),
                                                  ("cover", upper, cover)), 1):
        kg = volumes[label] / 1e9 * metal.density_kg_m3
        total += kg
        minx, miny, maxx, maxy = poly.bounds
        rows.append(CutRow(label, "metal-plate", metal.name, "stock", 0, 0, False, maxx - minx, maxy - miny, thick,
                           poly.area / 1e6, kg, order, notes[label]))
    drawings = tuple(_drawing(ts, k, poly, mouth, margin_mm, title) for k, poly in ((1, lower), (2, upper)))
    return FabPlan((), {}, {}, drawings, tuple(rows), {metal.name: total, "all": total}, {}, 0.0,
                   {"lines.csv": lines_csv(design)})


def summary(design: PolyfocalDesign) -> dict[str, float]:
    """The layout's figures and the guides' TE10 data at the design frequency."""
    ts = design.mirror
    figures = checks(ts)[1]
    return figures | {"te10_phase_index": te10_index(ts, design.wavelength_mm),
                      "guide_width_mm": ts.p.guide_width, "plate_spacing_mm": ts.p.height,
                      "band_low_ghz": ts.p.band_ghz[0], "band_high_ghz": ts.p.band_ghz[1],
                      "guide_cutoff_margin": ts.p.band_ghz[0] / (C_MM_GHZ / (2 * ts.p.guide_width))}
