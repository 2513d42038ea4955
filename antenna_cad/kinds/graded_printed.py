"""``fabrication.method: printed`` for the trifocal graded-index lens (seed-001 §3.2): the lens between
the plates printed from one filament (``material``) as a cubic lattice whose fill follows
εr(y) = n(y)² (antenna_cad.printed), a whole number of cells between the plates, a solid skin on the
two refracting faces (the plates' faces are the cells' own).

The lattice is graded row by row across the aperture: each row of cells (centre y = j·a) has the rod
width of the law at its centre, rounded to what a slicer places, so the lens as printed is a staircase
εr_j of step a. The verification traces that staircase (:func:`printed_medium`) through the
synthesized surfaces and reports σ (3.10) against the field angle beside the continuous law's.
"""

from __future__ import annotations

import types

import numpy as np

from antenna_cad.kinds.printed_package import (WIDTH_STEP_NOZZLES, PrintedFabPlan, fill_checks, package,
                                              registration_check)
from antenna_cad.limits import LIMITS
from antenna_cad.printed.fill import FillMap, fill_map, rod_width_mm
from antenna_cad.printed.homogenization import homogenized
from antenna_cad.printed.lattice import Printable, fill_fraction
from antenna_cad.spec.common import resolve_material
from antenna_cad.stages import with_cad
from antenna_cad.synthesis.graded import Layer, Medium
from antenna_cad.verification import Plot, Series, Verification

REFERENCE_STEP_CELLS = 1 / 4    # midpoint grid of the analytic ∫fill dV, in cells


def law(design):
    """εr(|y| mm) of the synthesized index law."""
    u = design.unit_mm
    return lambda y: design.n(np.minimum(np.abs(y) / u, design.half_aperture)) ** 2


def _fill(spec, design) -> FillMap:
    fab = spec.fabrication
    m = resolve_material(spec.material)
    printable = Printable(fab.lattice, fab.cell_mm, fab.wall_mm, fab.gap_mm)
    return fill_map(law(design), design.half_aperture * design.unit_mm, fab.lattice, m.eps_r, printable)


def row_widths(spec, fmap: FillMap, y_mm) -> np.ndarray:
    """Rod widths of the cells centred at ``y_mm``, rounded to an eighth of the nozzle, printable."""
    from antenna_cad.printed.parts import rounded_widths
    fab = spec.fabrication
    return rounded_widths(fmap, np.abs(np.asarray(y_mm, float)), fab.nozzle_mm * WIDTH_STEP_NOZZLES, fab.wall_mm,
                          fab.gap_mm)


def printed_steps(spec, design) -> tuple[np.ndarray, np.ndarray]:
    """(row edges |y| mm (K + 1), εr_eff of each row as printed (K)): rows j = 0 … of the lattice,
    centred at y = j·a, the last one reaching past the aperture."""
    fab = spec.fabrication
    fmap = _fill(spec, design)
    a, top = fab.cell_mm, design.half_aperture * design.unit_mm
    rows = np.arange(int(np.ceil(top / a - 0.5)) + 1)
    w = row_widths(spec, fmap, rows * a)
    eps = homogenized(fab.lattice, resolve_material(spec.material).eps_r).eps_at(fill_fraction("cubic", w / a))
    edges = np.r_[0.0, (rows + 0.5) * a]
    return edges, eps


def printed_medium(spec, design) -> Medium:
    """The staircase εr_j as the ray tracer's layered medium (normalised y; constant n² per row)."""
    edges, eps = printed_steps(spec, design)
    e = edges / design.unit_mm
    layers = [Layer(float(lo), float(hi), float(n2), 0.0, 0.0) for lo, hi, n2 in zip(e[:-1], e[1:], eps)]
    layers[-1].hi = np.inf
    return Medium(float(np.sqrt(eps[0])), 0.0, layers)


def fabricate_printed(spec, design) -> PrintedFabPlan:
    from antenna_cad.fabrication.graded import section_polygon
    fab = spec.fabrication
    m = resolve_material(spec.material)
    fmap = _fill(spec, design)
    sec = section_polygon(design)
    too_many = LIMITS["cells"].check(round(sec.area * spec.design.height_mm / fab.cell_mm**3))
    if not with_cad():
        return PrintedFabPlan((), {}, {}, (), (), {}, {}, 0.0, {}, {}, fill=fmap, material=m,
                              check_list=tuple(too_many + fill_checks(spec, fab, m, fmap)))
    from antenna_cad.printed.body import Envelope, body_cells, build_lattice_body, reference_volume_mm3
    tol = spec.outputs.mesh_tolerance_mm
    env = Envelope("extruded", sec, spec.design.height_mm)
    idx, centre, inner = body_cells(env, fab.cell_mm, fab.skin_mm, tol)
    a = fab.cell_mm
    ref = reference_volume_mm3(env, lambda u, w: fill_fraction("cubic", rod_width_mm(fmap, np.abs(w)) / a),
                               fab.skin_mm, a * REFERENCE_STEP_CELLS)
    lens = build_lattice_body(env, idx, centre, inner, row_widths(spec, fmap, centre[:, 1]), a, skin_mm=fab.skin_mm,
                              bed_mm=(fab.bed.x_mm, fab.bed.y_mm, fab.bed.z_mm), tolerance_mm=tol, segments=0,
                              reference_volume_mm3=ref)
    return package(spec, m, fmap, lens, too_many, (registration_check(fab, lens),),
                   step="print on a plate face (the lens axis on the bed)")


def printed_verification(spec, design) -> Verification:
    """σ (3.10) of the printed staircase against the field angle, beside the continuous law's; the
    staircase's εr against the law (max |error|)."""
    from antenna_cad.synthesis.graded_design import sigma_scan
    f = design.foci
    construction = types.SimpleNamespace(F=f["F"], F1=f["F1"], Fp=f["F'"], F1p=f["F1'"])
    medium = printed_medium(spec, design)
    half_view = spec.design.view_angle_deg / 2
    angles, sigma = sigma_scan(construction, medium, design.x1, design.x2, design.half_aperture, half_view,
                               len(design.angle_deg))
    edges, eps = printed_steps(spec, design)
    mid = (edges[:-1] + edges[1:]) / 2
    inside = mid <= design.half_aperture * design.unit_mm
    step_err = float(np.max(np.abs(eps[inside] - law(design)(mid[inside]))))
    figures = {"printed_sigma_max": float(np.max(sigma)), "printed_sigma_max_mm": float(np.max(sigma) * design.unit_mm),
               "printed_rows": float(len(eps)), "printed_row_max_eps_error": step_err}
    y = np.linspace(0, design.half_aperture, 200) * design.unit_mm
    plots = (Plot("printed-sigma", "RMS aberration (3.10): continuous law and the printed lattice's rows", "field angle (deg)",
                  "σ / D", (Series("continuous law", design.angle_deg, design.sigma),
                            Series("printed rows (homogenized εr per row of cells)", angles, sigma, "dashed")),
                  caption="GO through the synthesized surfaces; the printed lens is a staircase of one εr per "
                          "row of cells (unit-cell table, rods rounded to an eighth of the nozzle); the skin is "
                          "not traced"),
             Plot("printed-eps", "εr across the aperture: law and printed rows", "y (mm)", "εr",
                  (Series("n(y)² synthesized", y, law(design)(y)),
                   Series("printed rows", edges, np.r_[eps, eps[-1]], "steps"))))
    return Verification(figures, (), (), plots)
