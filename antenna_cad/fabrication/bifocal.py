"""Fabrication plan of a machined bifocal lens (seed-000 §3.2, seed-001 §3.1): the blank and a 1:1
section gauge of both faces (the meridional section for a revolved lens; the extruded section for a
cylindrical one). Frame: synthesis frame, drawing x = y (transverse), drawing y = z − ρ1 (illuminated
vertex at 0)."""

from __future__ import annotations

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.outline import CHORD_TOL_MM
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.bifocal import BifocalDesign, lens_volume_mm3

PROFILE_TABLE_ROWS = 11


def section_polygon(design: BifocalDesign) -> Polygon:
    """Both faces sampled finer than CHORD_TOL, illuminated face at the bottom, z from the vertex."""
    yb = design.edge_y_mm
    count = max(64, int(np.ceil(yb / np.sqrt(CHORD_TOL_MM))) * 4)
    y = np.linspace(-yb, yb, count)
    zi = design.profile("illuminated", y) - design.rho1_mm
    zs = design.profile("shadow", y[::-1]) - design.rho1_mm
    return Polygon(list(zip(y, zi)) + list(zip(y[::-1], zs))[1:-1])


def fabricate_machined_bifocal(design: BifocalDesign, height_mm: float | None, material: Material,
                               allowance_mm: float, title: str) -> FabPlan:
    yb, d = design.edge_y_mm, design.thickness_mm
    a = allowance_mm
    if design.shape == "cylindrical":
        size = (2 * (yb + a), height_mm + 2 * a)
        area = size[0] * size[1]
        shape = f"cylindrical, height {height_mm:g} mm"
    else:
        size = (2 * (yb + a), 2 * (yb + a))
        area = np.pi * (yb + a) ** 2
        shape = "revolved"
    blank_t = d + 2 * a
    mass = area * blank_t / 1e9 * material.density_kg_m3
    lens_kg = lens_volume_mm3(design, height_mm) / 1e9 * material.density_kg_m3
    row = CutRow("lens-blank", "machined-blank", material.name, "stock", 0.0, 0.0, False, size[0], size[1],
                 blank_t, area / 1e6, float(mass), 1, f"machine both faces to the gauge; finished lens {lens_kg:.3f} kg")
    drawing = Drawing("profile")
    drawing.add_polygon(section_polygon(design))
    drawing.marks.append([(0.0, -10.0), (0.0, d + 10.0)])             # optical axis
    x0 = yb + 20.0
    rows = ["y mm   z_ill mm  z_sh mm"] + [
        f"{y:7.2f} {float(design.profile('illuminated', y)) - design.rho1_mm:8.3f} "
        f"{float(design.profile('shadow', y)) - design.rho1_mm:8.3f}"
        for y in np.linspace(0, yb, PROFILE_TABLE_ROWS)]
    for k, text in enumerate(rows):
        drawing.texts.append((text, x0, d - k * 7.0, 4.0))
    drawing.add_title([f"{title}: bifocal section gauge 1:1 ({shape}), {material.name}, 2Y_B "
                       f"{2 * yb:g} mm, thickness {d:.3f} mm; z from the illuminated vertex "
                       f"(feed plane {design.rho1_mm:.3f} mm below)"], -yb, d + 25.0)
    drawing.add_check_bar(-yb, -30.0)
    return FabPlan((), {}, {}, (drawing,), (row,), {material.name: float(mass), "all": float(mass)},
                   {material.name: 1}, 0.0)
