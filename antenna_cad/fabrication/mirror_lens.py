"""Fabrication plan of the aplanatic mirror-lens (seed-004 §6–§7.1): the body machined or printed
from a solid blank (or the spine's sheet layup for foam-like stock), a 1:1 section gauge of both
faces, the mounting flange, and the mirror face as its own process step (coating of the back face
after the body is finished). Frame: seed-004 §1 in mm (feed at z = 0, body toward +z)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.mirror_lens import MirrorLensDesign

GAUGE_ROWS = 11
PROCESS = {"spray": "spray the conductive paint", "plating": "electroplate",
           "foil": "bond the metal foil", "vacuum_metallization": "vacuum-metallize"}


def flange_geometry(design: MirrorLensDesign, width_mm: float, thickness_mm: float):
    """(inner radius at both faces, outer radius, z0, z1): a ring on the side wall against the mirror rim."""
    p, D = design.profiles, design.diameter_mm
    (r0, z0), (r1, z1) = (p.s[-1] * D, p.f[-1] * D), (p.R_b[-1] * D, p.Z_b[-1] * D)
    top = z1
    bottom = max(z0, z1 - thickness_mm)
    wall = lambda z: r0 + (r1 - r0) * (z - z0) / (z1 - z0)        # noqa: E731
    outer = max(r0, r1) + width_mm
    return (wall(bottom), wall(top)), outer, bottom, top


def gauge_drawing(design: MirrorLensDesign, title: str, material: Material) -> Drawing:
    """Section of the body (drawing x = r from −R to R, y = z), front face at the bottom, with a
    table of both exact profiles and the mirror face marked."""
    ring = design.section_mm()
    half = Polygon(ring[:-1])
    mirrored = Polygon([(-r, z) for r, z in ring[:-1]])
    section = half.union(mirrored).buffer(0)
    drawing = Drawing("profile")
    drawing.add_polygon(section)
    p, D = design.profiles, design.diameter_mm
    z_lo, z_hi = design.z_range_mm
    drawing.marks.append([(0.0, z_lo - 10.0), (0.0, z_hi + 10.0)])                       # optical axis
    mirror = np.stack([p.R_b, p.Z_b], -1) * D
    drawing.marks.append([(float(r), float(z) + 3.0) for r, z in np.concatenate([mirror[::-1] * [-1, 1], mirror])[::8]])
    x0 = design.body_radius_mm + 20.0
    rows = ["r mm    front z mm  |  R mm   mirror Z mm"]
    for r in np.linspace(0.0, 0.5, GAUGE_ROWS):
        k = min(int(np.searchsorted(p.s, r)), len(p.s) - 1)
        rows.append(f"{p.s[k] * D:7.2f} {p.f[k] * D:9.3f}  | {p.R_b[k] * D:7.2f} {p.Z_b[k] * D:9.3f}")
    for k, text in enumerate(rows):
        drawing.texts.append((text, x0, z_hi - k * 7.0, 4.0))
    drawing.add_title([f"{title}: mirror-lens section gauge 1:1, {material.name}, D {D:g} mm; z from the feed "
                       "(focus); front face at the bottom, MARK dotted: the mirror face"], -design.body_radius_mm,
                      z_hi + 25.0)
    drawing.add_check_bar(-design.body_radius_mm, z_lo - 30.0)
    return drawing


def _mirror_row(design: MirrorLensDesign, mirror, order: int) -> CutRow:
    area = design.mirror_area_mm2()
    mass = area * mirror.thickness_mm / 1e9 * mirror.density_kg_m3
    return CutRow("mirror", "mirror-coating", mirror.metal, "process", 0.0, 0.0, False,
                  2 * design.profiles.R_b[-1] * design.diameter_mm, 2 * design.profiles.R_b[-1] * design.diameter_mm,
                  mirror.thickness_mm, area / 1e6, float(mass), order,
                  f"{PROCESS[mirror.process]} on the back (mirror) face only, {mirror.thickness_mm:g} mm; "
                  "mask the front face and the side wall")


def _flange_row(ring, material: Material, flange, order: int) -> CutRow:
    (ri0, ri1), ro, z0, z1 = ring
    area = np.pi * (ro**2 - min(ri0, ri1) ** 2)
    mass = area * (z1 - z0) / 1e9 * material.density_kg_m3
    return CutRow("flange", "flange", material.name, "stock", 0.0, 0.0, False, 2 * ro, 2 * ro, z1 - z0,
                  area / 1e6, float(mass), order, f"{flange.bolt_count} bolt holes Ø{flange.bolt_diameter_mm:g} mm; "
                  "bond to the side wall at the mirror rim (before coating)")


def fabricate_solid(design: MirrorLensDesign, spec_design, ring, material: Material, metal: Material,
                    allowance_mm: float, title: str) -> FabPlan:
    """Blank (turned or printed body), flange, then the mirror coating as the last step."""
    R = design.body_radius_mm + allowance_mm
    z_lo, z_hi = design.z_range_mm
    length = z_hi - z_lo + 2 * allowance_mm
    blank_kg = np.pi * R**2 * length / 1e9 * material.density_kg_m3
    body_kg = design.volume_mm3() / 1e9 * material.density_kg_m3
    rows = [CutRow("body-blank", "machined-blank", material.name, "stock", 0.0, 0.0, False, 2 * R, 2 * R, length,
                   np.pi * R**2 / 1e6, float(blank_kg), 1,
                   f"turn (or print) both faces to the gauge; finished body {body_kg:.3f} kg"),
            _flange_row(ring, material, spec_design.flange, 2), _mirror_row(design, spec_design.mirror, 3)]
    totals = {material.name: float(blank_kg + rows[1].mass_kg), metal.name: rows[2].mass_kg}
    totals["all"] = sum(totals.values())
    return FabPlan((), {}, {}, (gauge_drawing(design, title, material),), tuple(rows), totals,
                   {material.name: 1}, 0.0)


def add_mirror_step(fab: FabPlan, design: MirrorLensDesign, spec_design, material: Material, metal: Material,
                    title: str) -> FabPlan:
    """A sheet layup's plan plus the section gauge for sanding and the mirror coating after sanding."""
    last = max((r.assembly_order for r in fab.rows), default=0)
    row = _mirror_row(design, spec_design.mirror, last + 1)
    totals = dict(fab.totals_kg) | {metal.name: row.mass_kg}
    totals["all"] = fab.totals_kg["all"] + row.mass_kg
    return replace(fab, rows=fab.rows + (row,), totals_kg=totals,
                   drawings=fab.drawings + (gauge_drawing(design, title, material),))
