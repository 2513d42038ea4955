"""Adapters of the single-surface collimator (seed-000) between its spec and the stages."""

from __future__ import annotations

import numpy as np

from antenna_cad.verification import Verification
from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.kinds.layup import fabricate_layup, layup_figures, neck_checks, plan_layup_and_box
from antenna_cad.spec.collimator import CollimatorSpec
from antenna_cad.spec.common import SheetLayupSpec, resolve_material
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.collimator import CollimatorDesign, synthesize_collimator


def synthesize(spec: CollimatorSpec) -> CollimatorDesign:
    m = resolve_material(spec.material)
    fab = spec.fabrication
    antenna = spec.design.antenna
    return synthesize_collimator(
        diameter_mm=spec.design.diameter_mm, focal_length_mm=spec.design.focal_length_mm,
        eps_r=m.eps_r, tan_delta=m.tan_delta, frequency_ghz=spec.frequency_ghz,
        phase_error_budget_deg=spec.design.phase_error_budget_deg,
        antenna_aperture_mm=antenna.aperture_mm if antenna else None,
        antenna_distance_mm=antenna.distance_mm if antenna else None,
        sheet_thickness_mm=fab.sheet_thickness_mm if isinstance(fab, SheetLayupSpec) else None)


def plan(spec: CollimatorSpec, design: CollimatorDesign):
    """(LayupPlan, box panels) for a sheet layup; (None, ()) for a machined lens."""
    fab = spec.fabrication
    if not isinstance(fab, SheetLayupSpec):
        return None, ()
    return plan_layup_and_box(fab, lens_radius_mm=design.diameter_mm / 2,
                              lens_thickness_mm=design.thickness_mm, radius_at=design.radius_at)


def model(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None, panels):
    from antenna_cad.geometry.collimator import build_model
    fab = spec.fabrication
    box_material = resolve_material(fab.box.material) if layup else None
    return build_model(design, layup, resolve_material(spec.material), box_material, panels)


def fabricate(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None, panels):
    m = resolve_material(spec.material)
    if layup is None:
        from antenna_cad.fabrication.machined import fabricate_machined
        return fabricate_machined(design, m, spec.fabrication.stock_allowance_mm, spec.name)
    return fabricate_layup(spec.fabrication, layup, panels, m, spec.name)


def summary(spec: CollimatorSpec, design: CollimatorDesign, layup: LayupPlan | None) -> dict[str, float]:
    """Key figures for the manifest and the terminal table."""
    figures = design.key_figures()
    if layup is not None:
        figures |= layup_figures(layup)
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


def verify(spec, design, layup, fab) -> Verification:
    """As-built verification (issue 6): filled in per kind."""
    return Verification()
