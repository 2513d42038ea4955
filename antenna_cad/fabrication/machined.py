"""Fabrication plan of a machined (turned) lens: the blank and a 1:1 profile gauge drawing."""

from __future__ import annotations

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.outline import CHORD_TOL_MM
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.collimator import CollimatorDesign, profile_z_mm

PROFILE_TABLE_ROWS = 11


def profile_polygon(design: CollimatorDesign) -> Polygon:
    """Meridional section (x = r from −R to R, y = z), the hyperbola sampled finer than CHORD_TOL."""
    R, d = design.diameter_mm / 2, design.thickness_mm
    count = max(64, int(np.ceil(R / np.sqrt(CHORD_TOL_MM))) * 4)
    r = np.linspace(-R, R, count)
    z = profile_z_mm(np.abs(r), design.focal_length_mm, design.n)
    return Polygon(list(zip(r, z)) + [(R, d), (-R, d)])


def fabricate_machined(design: CollimatorDesign, material: Material, allowance_mm: float,
                       title: str) -> FabPlan:
    R, d = design.diameter_mm / 2, design.thickness_mm
    blank_d, blank_t = 2 * (R + allowance_mm), d + 2 * allowance_mm
    mass = np.pi * (blank_d / 2) ** 2 * blank_t / 1e9 * material.density_kg_m3
    row = CutRow("lens-blank", "machined-blank", material.name, "stock", 0.0, 0.0, False, blank_d, blank_d,
                 blank_t, np.pi * (blank_d / 2) ** 2 / 1e6, float(mass), 1,
                 f"turn to the profile; finished lens {design.volume_mm3 / 1e9 * material.density_kg_m3:.3f} kg")
    drawing = Drawing("profile")
    drawing.add_polygon(profile_polygon(design))
    drawing.marks.append([(0.0, -10.0), (0.0, d + 10.0)])             # optical axis
    x0 = R + 20.0
    rows = ["r mm      z mm"] + [f"{r:7.2f}  {float(profile_z_mm(r, design.focal_length_mm, design.n)):8.3f}"
                                  for r in np.linspace(0, R, PROFILE_TABLE_ROWS)]
    for k, text in enumerate(rows):
        drawing.texts.append((text, x0, d - k * 7.0, 4.0))
    drawing.add_title([f"{title}: profile gauge 1:1, {material.name}, D {design.diameter_mm:g} mm, "
                       f"thickness {d:.3f} mm; feed side at the bottom (z = 0 vertex)"], -R, d + 25.0)
    drawing.add_check_bar(-R, -30.0)
    return FabPlan((), {}, {}, (drawing,), (row,), {material.name: float(mass), "all": float(mass)},
                   {material.name: 1}, 0.0)
