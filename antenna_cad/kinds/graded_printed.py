"""``fabrication.method: printed`` for the trifocal graded-index lens (seed-001 §3.2): the lens between
the plates printed from one filament (``material``) as a cubic lattice whose fill follows
εr(y) = n(y)² (antenna_cad.printed), a whole number of cells between the plates, a solid skin on the
two refracting faces (the plates' faces are the cells' own).

The lattice is graded row by row across the aperture: each row of cells (centre y = j·a) has the rod
width of the law at its centre, dithered along the lens axis between the two nearest widths a slicer
places (:func:`antenna_cad.printed.fill.dithered_widths`), so the lens as printed is a staircase
εr_j of step a — far below the wavelength, so the wave sees the rows' average and a ray trace of the
steps (refracting at each row) would not describe it. The verification reports the rows' εr error and
the first-order aperture path error it adds to the law's σ (:func:`path_error_mm`).
"""

from __future__ import annotations

import numpy as np

from antenna_cad.kinds.printed_package import (WIDTH_STEP_NOZZLES, PrintedFabPlan, fill_checks, package,
                                              registration_pins)
from antenna_cad.limits import LIMITS
from antenna_cad.printed.fill import FillMap, dithered_fill, dithered_widths, eps_of_width, fill_map, rod_width_mm
from antenna_cad.printed.lattice import Printable, fill_fraction
from antenna_cad.spec.common import resolve_material
from antenna_cad.stages import with_cad
from antenna_cad.spec.printed import C_MM_GHZ
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


def _limits(spec) -> tuple[float, float, float]:
    fab = spec.fabrication
    return fab.nozzle_mm * WIDTH_STEP_NOZZLES, fab.wall_mm, fab.cell_mm - fab.gap_mm


def row_widths(spec, fmap: FillMap, y_mm, x_index) -> np.ndarray:
    """Rod widths of the cells centred at ``y_mm``: the law's width dithered along the lens axis
    (``x_index``) between the two nearest widths a slicer places, so each row's mean follows the law."""
    fab = spec.fabrication
    eps = eps_of_width(fab.lattice, resolve_material(spec.material).eps_r, fab.cell_mm)
    w, _ = dithered_widths(rod_width_mm(fmap, np.abs(np.asarray(y_mm, float))), x_index, *_limits(spec), eps)
    return w


def printed_steps(spec, design) -> tuple[np.ndarray, np.ndarray]:
    """(row edges |y| mm (K + 1), mean εr_eff of each row as printed (K)): rows j = 0 … of the lattice,
    centred at y = j·a, the last one reaching past the aperture."""
    fab = spec.fabrication
    fmap = _fill(spec, design)
    a, top = fab.cell_mm, design.half_aperture * design.unit_mm
    rows = np.arange(int(np.ceil(top / a - 0.5)) + 1)
    _, eps = dithered_fill(rod_width_mm(fmap, rows * a), *_limits(spec), a, fab.lattice,
                           resolve_material(spec.material).eps_r)
    return np.r_[0.0, (rows + 0.5) * a], eps


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
    from antenna_cad.export.forked import forked_map
    from antenna_cad.printed.body import Envelope, body_cells, build_lattice_body, reference_volume_mm3
    tol = spec.outputs.mesh_tolerance_mm
    env = Envelope("extruded", sec, spec.design.height_mm)
    idx, centre, inner = body_cells(env, fab.cell_mm, fab.skin_mm, tol)
    a = fab.cell_mm
    ref = reference_volume_mm3(env, lambda u, w: fill_fraction("cubic", rod_width_mm(fmap, np.abs(w)) / a),
                               fab.skin_mm, a * REFERENCE_STEP_CELLS)
    lens = build_lattice_body(env, idx, centre, inner, row_widths(spec, fmap, centre[:, 1], idx[:, 0]), a,
                              skin_mm=fab.skin_mm,
                              bed_mm=(fab.bed.x_mm, fab.bed.y_mm, fab.bed.z_mm), tolerance_mm=tol, segments=0,
                              reference_volume_mm3=ref, pins=registration_pins(fab), map_parts=forked_map)
    return package(spec, m, fmap, lens, too_many, (),
                   step="print on a plate face (the lens axis on the bed)")



def path_error_mm(spec, design, y_mm: np.ndarray) -> np.ndarray:
    """First-order optical path error of the printed lens at aperture height ``y_mm``: the index the
    lattice gives (row values, linear between row centres: the homogenized medium a wave averages over
    sub-wavelength rows) less the law's, times the lens thickness there (near-axial rays)."""
    edges, eps = printed_steps(spec, design)
    centres = np.arange(len(eps)) * spec.fabrication.cell_mm
    n_printed = np.sqrt(np.interp(np.abs(y_mm), centres, eps))
    yn = np.asarray(y_mm) / design.unit_mm
    thickness = (design.x2(yn) - design.x1(yn)) * design.unit_mm
    return (n_printed - np.sqrt(law(design)(y_mm))) * thickness


def printed_verification(spec, design) -> Verification:
    """The printed rows' εr against the law and the aperture path error they add (first order, feed on
    axis), RSS with the law's σ; plots of both."""
    lam = C_MM_GHZ / spec.frequency_ghz
    half = design.half_aperture * design.unit_mm
    y = np.linspace(-half, half, 401)
    err = path_error_mm(spec, design, y)
    err = err - err.mean()
    rms = float(np.sqrt(np.mean(err**2)))
    edges, eps = printed_steps(spec, design)
    centres = np.arange(len(eps)) * spec.fabrication.cell_mm
    inside = centres <= half
    step_err = float(np.max(np.abs(eps[inside] - law(design)(centres[inside]))))
    sigma_law = float(design.sigma[len(design.sigma) // 2]) * design.unit_mm
    figures = {"printed_rows": float(len(eps)), "printed_row_max_eps_error": step_err,
               "printed_path_error_rms_mm": rms, "printed_path_error_rms_deg": rms / lam * 360,
               "printed_path_error_pp_mm": float(np.ptp(err)),
               "printed_sigma_on_axis_mm": float(np.hypot(sigma_law, rms))}
    yy = np.linspace(0, half, 200)
    plots = (Plot("printed-eps", "εr across the aperture: law and printed rows", "y (mm)", "εr",
                  (Series("n(y)² synthesized", yy, law(design)(yy)),
                   Series("printed rows (unit-cell table, mean of the dithered rods)", edges, np.r_[eps, eps[-1]], "steps")),
                  caption="one mean εr per row of cells (centre y = j·a): rods of the two nearest printable widths alternated along the axis"),
             Plot("printed-path-error", "Aperture path error of the printed rows (feed on axis)", "y (mm)",
                  "path error (mm)", (Series("(n_printed − n)·thickness, piston removed", y, err),),
                  caption=f"first order, near-axial rays; RMS {rms:.3f} mm = {rms / lam * 360:.1f}° at "
                          f"{spec.frequency_ghz:g} GHz; with the law's σ on axis {np.hypot(sigma_law, rms):.3f} mm "
                          "(RSS); the skin is not included"))
    return Verification(figures, (), (), plots)
