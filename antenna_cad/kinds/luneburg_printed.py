"""``fabrication.method: printed`` for the Luneburg lens: the law εr(r) (seed-002 §2.1) as a graded
cubic lattice of one filament (antenna_cad.printed), its printable parts, 3MF/STL, cut list and checks.

The fill follows εr_eff(fill) of the shipped unit-cell table, clipped to the printable range; the
parts are checked closed and oriented, their volume against the analytic ∫fill dV, and their size
against the bed. Mass, filament length and print time (volume / flow) per part.
"""

from __future__ import annotations

import math

import numpy as np

from antenna_cad.kinds.printed_package import (WIDTH_STEP_NOZZLES, PrintedFabPlan, fill_checks, package,
                                              registration_pins)
from antenna_cad.limits import LIMITS
from antenna_cad.materials import Material
from antenna_cad.printed.fill import FillMap, fill_integral_mm3, fill_map
from antenna_cad.printed.lattice import Printable, gyroid_edge_mm, gyroid_grid_points
from antenna_cad.raytrace.media import Shells
from antenna_cad.spec.common import resolve_material
from antenna_cad.spec.printed import PrintedSpec
from antenna_cad.stages import with_cad
from antenna_cad.synthesis.luneburg import eps_profile

PROFILE_SHELLS = 48         # shells of the printed εr(r) seen by the GO, Mie and full-wave checks


def law(design):
    """εr(r mm) of the design's continuous law (not its layers)."""
    R = design.radius_mm
    return lambda r: eps_profile(r / R, design.law, design.focal_distance_ratio, design.outer_shell)


def _fill(spec, design) -> tuple[Material, FillMap]:
    fab: PrintedSpec = spec.fabrication
    m = resolve_material(spec.material)
    printable = Printable(fab.lattice, fab.cell_mm, fab.wall_mm, fab.gap_mm)
    return m, fill_map(law(design), design.radius_mm, fab.lattice, m.eps_r, printable)


def printed_medium(spec, design, shells: int = PROFILE_SHELLS) -> Shells:
    """The lens as printed, for the GO, Mie and full-wave checks ("fabricated"): the lattice's
    εr_eff(fill) (clipped) on ``shells`` equal-thickness shells under the skin, and the skin of solid
    filament."""
    m, fmap = _fill(spec, design)
    R, skin = design.radius_mm, spec.fabrication.skin_mm
    edges = np.linspace(0.0, R - skin, shells + 1)
    mid = (edges[:-1] + edges[1:]) / 2
    eps = np.interp(mid, fmap.r_mm, fmap.eps_printed)
    if skin > 0:
        edges, eps = np.append(edges, R), np.append(eps, m.eps_r)
    return Shells(edges[1:], np.sqrt(eps))


def fabricate_printed(spec, design) -> PrintedFabPlan:
    fab: PrintedSpec = spec.fabrication
    R = design.radius_mm
    body = 4 / 3 * math.pi * R**3 if design.shape == "sphere" else math.pi * R**2 * design.height_mm
    too_many = LIMITS["cells"].check(round(body / fab.cell_mm**3))     # before any meshing
    m, fmap = _fill(spec, design)
    if fab.lattice == "gyroid":
        edge = gyroid_edge_mm(fab.cell_mm, fmap.fill_range)
        height = R if design.shape == "sphere" else design.height_mm
        too_many += LIMITS["gyroid_points"].check(gyroid_grid_points(design.shape, R, height, edge))
    skin = fab.skin_mm
    shape = design.shape
    if shape == "sphere":
        ref = fill_integral_mm3(fmap, R - skin, shape) + 4 / 3 * math.pi * (R**3 - (R - skin) ** 3)
    else:
        ref = fill_integral_mm3(fmap, R - skin, shape, design.height_mm) + math.pi * (R**2 - (R - skin) ** 2) * design.height_mm
    if not with_cad():          # the CAD-free validate: the limits and the fill, not the lattice's mesh
        checks = too_many + fill_checks(spec, fab, m, fmap)
        return PrintedFabPlan((), {}, {}, (), (), {}, {}, 0.0, {}, {}, fill=fmap, material=m, check_list=tuple(checks))
    from antenna_cad.printed.parts import build_printed_lens
    lens = build_printed_lens(shape, R, design.height_mm, fmap, skin_mm=skin, wall_mm=fab.wall_mm, gap_mm=fab.gap_mm,
                              width_step_mm=fab.nozzle_mm * WIDTH_STEP_NOZZLES,
                              bed_mm=(fab.bed.x_mm, fab.bed.y_mm, fab.bed.z_mm), pins=registration_pins(fab),
                              tolerance_mm=spec.outputs.mesh_tolerance_mm, reference_volume_mm3=ref)
    return package(spec, m, fmap, lens, too_many)


