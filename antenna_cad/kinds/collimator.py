"""Adapters of the single-surface collimator (seed-000) between its spec and the stages. A printed lens
(``fabrication.method: printed``) is synthesized at ``design.refractive_index`` and printed as a uniform
lattice (:mod:`antenna_cad.kinds.uniform_printed`); the as-built checks trace it at the εr as printed."""

from __future__ import annotations

from dataclasses import replace
from functools import partial

import numpy as np

from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fabrication.outline import CHORD_TOL_MM
from antenna_cad.asbuilt.lens import Lens, lens_variants, zone_depth_mm
from antenna_cad.asbuilt.stock import stock_study
from antenna_cad.asbuilt.verify import verify_lens
from antenna_cad.asbuilt.revolved import revolved, scan_edge_go
from antenna_cad.kinds.layup import fabricate_layup, layup_figures, neck_checks, plan_layup_and_box, plan_sheets
from antenna_cad.asbuilt.patterns import collimator_feed_limits, criteria_from, lens_patterns
from antenna_cad.raytrace.collimator import front_face, single_surface_p2p_deg, usable_half_range_mm
from antenna_cad.raytrace.trace2d import Interface
from antenna_cad.kinds.uniform_printed import index_material
from antenna_cad.spec.collimator import CollimatorSpec
from antenna_cad.spec.common import resolve_material
from antenna_cad.spec.printed import PrintedSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.collimator import CollimatorDesign, profile_z_mm, synthesize_collimator
from antenna_cad.verification import Verification

DEFAULT_ANTENNA_GAP_MM = 100.0      # seed-000 §5.10: the scan plane 10 cm behind the flat face
SCAN_GRID = np.linspace(0.0, 1.0, 41)   # transverse feed displacement / f searched for the scan edge


def synthesize(spec: CollimatorSpec) -> CollimatorDesign:
    m = index_material(spec)
    aut = spec.design.aut
    return synthesize_collimator(
        diameter_mm=spec.design.diameter_mm, focal_length_mm=spec.design.focal_length_mm,
        eps_r=m.eps_r, tan_delta=m.tan_delta, frequency_ghz=spec.frequency_ghz,
        phase_error_budget_deg=spec.design.phase_error_budget_deg,
        antenna_aperture_mm=aut.span_mm if aut else None,
        antenna_distance_mm=_antenna_gap_mm(spec) if aut else None)


def cone_radius(spec: CollimatorSpec, design: CollimatorDesign):
    """r(z): the lens radius at depth z from the vertex (the lens's own radius behind it): what a
    taper-cut sheet's cone passes through at each face."""
    return lambda z: float(design.radius_at(min(max(z, 0.0), design.thickness_mm)))


def _sheets(spec: CollimatorSpec, design: CollimatorDesign):
    return partial(plan_sheets, spec.fabrication, lens_radius_mm=design.diameter_mm / 2,
                   lens_thickness_mm=design.thickness_mm, radius_at=design.radius_at)


def _antenna_gap_mm(spec: CollimatorSpec) -> float:
    aut = spec.design.aut
    return aut.distance_mm if aut is not None and aut.distance_mm is not None else DEFAULT_ANTENNA_GAP_MM


def _lens(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None) -> Lens:
    """The lens the as-built trace sees: its flat face at the back of the stack (the back slab stays); a
    printed lens at the εr of its lattice as printed."""
    m = index_material(spec, as_printed=True)
    f, n = design.focal_length_mm, design.n
    back = layup.sheets[-1].z_max_mm if layup is not None else design.thickness_mm
    return Lens(radius_mm=design.diameter_mm / 2, eps_r=m.eps_r, tan_delta=m.tan_delta,
                wavelength_mm=design.wavelength_mm, budget_deg=design.phase_error_budget_deg,
                antenna_z_mm=back + _antenna_gap_mm(spec), feed=(-f, 0.0),
                faces=lambda n_lens: (front_face(f, n, n_lens), Interface.plane(back, 1.0)),
                zone=spec.design.test_zone, aut_diameter_mm=spec.design.aut.span_mm if spec.design.aut else None)


def plan(spec: CollimatorSpec, design: CollimatorDesign):
    """(LayupPlan, box panels) for a sheet layup, the sheet thickness resolved; (None, ()) for a
    machined lens."""
    return plan_layup_and_box(spec.fabrication, _sheets(spec, design), partial(_lens, spec, design),
                              spec.verification)


def model(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None, panels):
    from antenna_cad.geometry.collimator import build_model
    fab = spec.fabrication
    box_material = resolve_material(fab.box.material) if layup else None
    built = build_model(design, layup, index_material(spec, as_printed=True), box_material, panels)
    if not isinstance(fab, PrintedSpec):
        return built
    # printed: the STEP holds the lens's envelope for reference (the lattice is in printed/)
    return replace(built, parts=tuple(replace(p, role="reference") for p in built.parts))


def printed_section(design: CollimatorDesign, skin_mm: float) -> np.ndarray:
    """The lens's meridian section (r, z) in the printer's frame: the flat face on the bed, the vertex up
    (no overhang: each layer lies inside the one below); the hyperbola sampled finer than CHORD_TOL_MM.
    The flat face lies at z = −``skin_mm`` so that the skin's inner face is a plane of cell centres
    (z = 0): the horizontal rods there are half fused into the skin, and the lattice above it holds its
    mean fill (a plane off the cell's symmetry planes cuts a layer of other fill along the whole face)."""
    R, d = design.diameter_mm / 2, design.thickness_mm
    r = np.linspace(0.0, R, max(32, int(np.ceil(R / np.sqrt(CHORD_TOL_MM))) * 2))
    z = d - profile_z_mm(r, design.focal_length_mm, design.n)
    return np.vstack([np.column_stack([r, z]), [(0.0, 0.0)]]) - (0.0, skin_mm)


def fabricate(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None, panels):
    m = index_material(spec, as_printed=True)
    if isinstance(spec.fabrication, PrintedSpec):
        from antenna_cad.kinds.uniform_printed import fabricate_printed
        return fabricate_printed(spec, printed_section(design, spec.fabrication.skin_mm), design.volume_mm3,
                                 design.diameter_mm / 2,
                                 "print on the flat face, the vertex up")
    if layup is None:
        from antenna_cad.fabrication.machined import fabricate_machined
        return fabricate_machined(design, m, spec.fabrication.stock_allowance_mm, spec.name)
    return fabricate_layup(spec.fabrication, layup, panels, m, spec.name)


def summary(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None) -> dict[str, float]:
    """Key figures for the manifest and the terminal table."""
    figures = design.key_figures()
    if layup is not None:
        figures |= layup_figures(layup)
    if isinstance(spec.fabrication, PrintedSpec):
        from antenna_cad.kinds.uniform_printed import summary_figures
        figures |= summary_figures(spec)
    return figures


def fabrication_checks(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None) -> list[Check]:
    """Sheet discs against the ideal lens (contain it, with no excess), and material the layup
    adds inside the aperture (necks) as a warning with its volume."""
    if layup is None:
        return []
    fit = 0.0
    for s in layup.sheets:
        z = np.linspace(s.z_min_mm, s.z_max_mm, 257)
        fit = max(fit, abs(s.radius_mm - float(np.max(design.radius_at(z)))))
    return [Check.upper("sheet_disc_fit", fit, 1e-6, "mm",
                        "sheet disc radius vs largest lens radius in its slab (contains, no excess)")
            ] + neck_checks(layup)


def verify(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None, fab) -> Verification:
    """As-built verification (:mod:`antenna_cad.asbuilt`) on axis and at the edge of the
    scan range: the transverse feed displacement where the ideal lens reaches the phase budget
    (seed-000 §5.5); the full-wave stage solves that feed too when its budget allows
    (:mod:`antenna_cad.fullwave.scan`)."""
    from antenna_cad.fullwave.scan import plan_scan_edge, scan_edge_study   # scipy.integrate: kept out of validate
    f, D, gap = design.focal_length_mm, design.diameter_mm, _antenna_gap_mm(spec)
    _, edge = usable_half_range_mm(
        lambda y: single_surface_p2p_deg(f, D, design.eps_r, y, gap, design.wavelength_mm),
        f * SCAN_GRID, design.phase_error_budget_deg)
    study = (stock_study(_sheets(spec, design), partial(_lens, spec, design), spec.fabrication.stock_thicknesses_mm,
                         spec.verification)
             if layup is not None else ())
    lens, feeds = _lens(spec, design, layup), (("on_axis", -f, 0.0), ("edge", -f, edge))
    # decided before the on-axis runs, so that auto's estimate counts every run still to do
    rl = revolved(lens, layup, fab)
    edge_plan = plan_scan_edge(rl, spec.verification, edge, zone_depth_mm(lens, rl.plane_z_mm(0.0)))
    v, fw = verify_lens(lens, feeds, spec.tolerances, layup, fab, study, spec.verification)
    go_edge = scan_edge_go(lens, layup, fab, (-f, edge)) if edge_plan.python else {}
    v = v.merged(scan_edge_study(edge_plan, go_edge))
    crit = criteria_from(spec.design.aut, spec.design.test_zone)
    v = v.merged(lens_patterns(lens, lens_variants(lens, layup, fab), feeds, crit, full_wave=fw)).merged(
        collimator_feed_limits(design, gap, crit.aut.height_mm if crit.aut else D, crit.aut.taper_k if crit.aut else 0,
                               crit.difference, SCAN_GRID))
    if isinstance(spec.fabrication, PrintedSpec) and getattr(fab, "lens", None) is not None:
        from antenna_cad.kinds.printed_package import printed_verification
        v = printed_verification(fab).merged(v)
    return replace(v, figures={"scan_half_range_mm": edge,
                               "scan_half_angle_deg": float(np.degrees(np.arctan2(edge, f)))} | v.figures)
