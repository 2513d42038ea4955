"""Adapters of the bifocal lens (seed-000 §3.2; seed-001 §3.1) between its spec and the stages.

Frame: the synthesis frame (:mod:`antenna_cad.synthesis.bifocal`) — feed plane z = 0, foci (0, ±a),
illuminated vertex z = ρ1, rim z = X_B, shadow vertex z = ρ2. A sheet layup reuses the spine
(:func:`plan_layup` with ``max_radius_in`` and ``z_origin_mm = ρ1``): both faces are curved, so sheet
i's disc is the largest lens radius inside its slab on either face; the N·t − d overhang beyond the
shadow vertex is sanded off with the steps. Taper-cut (``edge: taper``): each sheet's rim is the cone
through the lens's half-width at its two faces (:func:`cone_radius`) — widening on the illuminated
side, narrowing on the shadow side; the sheet holding the rim X_B is the chord across it, and the
last sheet's cone closes at the axis on its back face (the overhang stays: no sanding).
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import partial

import numpy as np

from antenna_cad.fabrication import bifocal_plates as bp
from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.asbuilt.lens import Lens, lens_variants
from antenna_cad.asbuilt.stock import stock_study
from antenna_cad.asbuilt.verify import verify_lens
from antenna_cad.kinds.layup import (cone_fit_check, fabricate_layup, layup_figures, neck_checks, plan_layup_and_box,
                                    plan_sheets)
from antenna_cad.asbuilt.patterns import criteria_from, lens_patterns
from antenna_cad.materials import Material
from antenna_cad.spec.bifocal import BifocalSpec
from antenna_cad.spec.common import resolve_material
from antenna_cad.synthesis.bifocal import (BifocalDesign, defocus_study, lens_volume_mm3, max_radius_in,
                                           synthesize_bifocal)
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.collimator import dissipative_loss_db, loss_check, wavelength_mm
from antenna_cad.verification import Plot, Series, Table, Verification


def _height(spec: BifocalSpec) -> float | None:
    return spec.design.height_mm if spec.design.shape == "cylindrical" else None


def synthesize(spec: BifocalSpec) -> BifocalDesign:
    m = resolve_material(spec.material)
    g = spec.design
    design = synthesize_bifocal(edge_y_mm=g.edge_y_mm, eps_r=m.eps_r, edge_x_mm=g.edge_x_mm,
                                focus_offset_mm=g.focus_offset_mm, beam_tilt_deg=g.beam_tilt_deg,
                                antenna_x_mm=g.antenna_x_mm, shape=g.shape, construction=g.construction,
                                kinber=g.kinber.model_dump() if g.kinber else None)
    loss = dissipative_loss_db(design.n, m.tan_delta, design.thickness_mm, wavelength_mm(spec.frequency_ghz))
    return replace(design, checks=(*design.checks, loss_check(loss)))


def _slab_radius(design: BifocalDesign):
    return lambda lo, hi: max_radius_in(design, design.rho1_mm + lo, design.rho1_mm + hi)


def cone_radius(spec: BifocalSpec, design: BifocalDesign):
    """r(z): the lens's half-width at depth z (lens frame), 0 outside it — what a taper-cut sheet's
    cone passes through at each face (and what ``make-lens check`` holds the wire to)."""
    return lambda z: max_radius_in(design, z, z)


def _sheets(spec: BifocalSpec, design: BifocalDesign):
    r = cone_radius(spec, design)
    return partial(plan_sheets, spec.fabrication, lens_radius_mm=design.edge_y_mm,
                   lens_thickness_mm=design.thickness_mm, max_radius_in=_slab_radius(design),
                   radius_at=lambda z: r(design.rho1_mm + z), z_origin_mm=design.rho1_mm)


def _lens(spec: BifocalSpec, design: BifocalDesign, layup: LayupPlan | None) -> Lens:
    """The lens the as-built trace sees, fed from the design focus O1 = (0, a); the antenna plane is
    z = c, or the stack's back face when that lies beyond c."""
    m = resolve_material(spec.material)
    ill, sh = design.interfaces()
    back = layup.sheets[-1].z_max_mm if layup is not None else design.rho2_mm
    return Lens(radius_mm=design.edge_y_mm, eps_r=m.eps_r, tan_delta=m.tan_delta,
                wavelength_mm=wavelength_mm(spec.frequency_ghz), budget_deg=spec.design.phase_error_budget_deg,
                antenna_z_mm=max(design.antenna_x_mm, back), feed=(0.0, design.focus_offset_mm),
                faces=lambda n: (replace(ill, n_after=n), sh))


def plan(spec: BifocalSpec, design: BifocalDesign):
    """(LayupPlan, box panels) for a sheet layup, the sheet thickness resolved; (None, ()) for a
    machined lens."""
    return plan_layup_and_box(spec.fabrication, _sheets(spec, design), partial(_lens, spec, design),
                              spec.verification)


def _metal(pp) -> Material:
    return Material(pp.metal, 1.0, 0.0, pp.metal_density_kg_m3, "metal (conductor), design.parallel_plate")


def _plates(spec: BifocalSpec, design: BifocalDesign):
    """(plate outline, horn or None) in the (z, y) section for a lens between plates; None without."""
    pp = spec.design.parallel_plate
    if pp is None:
        return None
    horn_ = None if pp.horn is None else bp.horn(design, pp.horn, wavelength_mm(spec.frequency_ghz))
    return bp.plate_outline(design, horn_, pp.margin_mm), horn_


def model(spec: BifocalSpec, design: BifocalDesign, layup: LayupPlan | None, panels):
    from antenna_cad.geometry.bifocal import build_model, plate_parts
    box_material = resolve_material(spec.fabrication.box.material) if layup else None
    plates, pp = _plates(spec, design), spec.design.parallel_plate
    extra = ([], []) if plates is None else plate_parts(
        plates[0], [] if plates[1] is None else bp.wall_parts(plates[1]), spec.design.height_mm,
        pp.plate_thickness_mm, _metal(pp))
    return build_model(design, _height(spec), layup, resolve_material(spec.material), box_material, panels, extra)


def fabricate(spec: BifocalSpec, design: BifocalDesign, layup: LayupPlan | None, panels):
    m = resolve_material(spec.material)
    if layup is not None:
        return fabricate_layup(spec.fabrication, layup, panels, m, spec.name)
    from antenna_cad.fabrication.bifocal import fabricate_machined_bifocal
    fab = fabricate_machined_bifocal(design, _height(spec), m, spec.fabrication.stock_allowance_mm, spec.name)
    plates, pp = _plates(spec, design), spec.design.parallel_plate
    if plates is None:
        return fab
    metal, h = _metal(pp), spec.design.height_mm
    rows = bp.plate_rows(plates[0], plates[1], metal, pp.plate_thickness_mm, h)
    metal_kg = sum(r.mass_kg for r in rows)
    drawing = bp.plates_drawing(design, plates[0], plates[1], spec.name, h, pp.plate_thickness_mm)
    return replace(fab, drawings=fab.drawings + (drawing,), rows=fab.rows + tuple(rows),
                   totals_kg=fab.totals_kg | {metal.name: metal_kg, "all": fab.totals_kg["all"] + metal_kg})


def sanding_allowance_mm3(design: BifocalDesign, layup: LayupPlan) -> float:
    """Stack discs (lens part of every sheet, full sheet thickness) minus the lens, analytic."""
    stack = sum(math.pi * s.radius_mm**2 * s.thickness_mm for s in layup.sheets)
    return stack - lens_volume_mm3(design)


def summary(spec: BifocalSpec, design: BifocalDesign, layup: LayupPlan | None) -> dict[str, float]:
    """Key figures: foci, geometry, residuals (the scan range is a verification figure)."""
    (f1z, f1y), (f2z, f2y) = design.foci_mm
    figures = {
        "focus_1_z_mm": float(f1z), "focus_1_y_mm": float(f1y), "focus_2_z_mm": float(f2z),
        "focus_2_y_mm": float(f2y), "focus_offset_mm": design.focus_offset_mm,
        "beam_tilt_deg": float(np.degrees(design.beam_tilt_rad)), "edge_x_mm": design.edge_x_mm,
        "edge_y_mm": design.edge_y_mm, "antenna_x_mm": design.antenna_x_mm,
        "illuminated_vertex_z_mm": design.rho1_mm, "shadow_vertex_z_mm": design.rho2_mm, "thickness_mm": design.thickness_mm, "n": design.n,
        "lens_volume_mm3": lens_volume_mm3(design, _height(spec)),
        "residual_path_error_focus_1_mm": float(design.residual_path_error_mm[0]),
        "residual_path_error_focus_2_mm": float(design.residual_path_error_mm[1]),
        "poly_fit_residual_mm": design.poly_fit_residual_mm,
        "wavelength_mm": wavelength_mm(spec.frequency_ghz),
    }
    if design.shape == "cylindrical":
        figures["height_mm"] = float(spec.design.height_mm)
    figures |= _kinber_figures(spec, design)
    if layup is not None:
        figures |= layup_figures(layup)
        if layup.edge == "stepped":
            figures["sanding_allowance_mm3"] = sanding_allowance_mm3(design, layup)
    return figures


def fabrication_checks(spec: BifocalSpec, design: BifocalDesign, layup: LayupPlan | None) -> list[Check]:
    """Sheet discs against the lens on both faces (contain it, no excess) and neck material; for a lens
    between plates: the plate spacing below λ/2 (only the TEM mode in the air region) and the horn
    clear of the lens."""
    if layup is None:
        plates = _plates(spec, design)
        if plates is None:
            return []
        lam = wavelength_mm(spec.frequency_ghz)
        checks = [Check.upper("plate_spacing_tem_only", spec.design.height_mm, lam / 2, "mm",
                              "plate spacing vs λ/2 (the TM1 cut-off of the air-filled plates)")]
        return checks + ([] if plates[1] is None else [bp.horn_clearance_check(design, plates[1])])
    if layup.edge == "taper":
        return [cone_fit_check(layup, cone_radius(spec, design))] + neck_checks(layup)
    fit, y = 0.0, np.linspace(0.0, design.edge_y_mm, 2001)
    zi, zs = design.profile("illuminated", y), design.profile("shadow", y)
    for s in layup.sheets:
        inside = (zi <= s.z_max_mm) & (zs >= s.z_min_mm)             # chord at y meets the slab
        sampled = float(np.max(y[inside])) if inside.any() else 0.0
        fit = max(fit, sampled - s.radius_mm)                        # > 0: lens outside the disc
        exact = max_radius_in(design, s.z_min_mm, s.z_max_mm)
        fit = max(fit, abs(s.radius_mm - exact))
    return [Check.upper("sheet_disc_fit", fit, 1e-6, "mm",
                        "sheet disc radius vs largest lens radius in its slab on both faces")
            ] + neck_checks(layup)


def _kinber_figures(spec: BifocalSpec, design: BifocalDesign) -> dict[str, float]:
    """Kinber's lens: the resolved central segments (h given or optimised), the image points of a
    point-image lens, σ over the view, the plates and the horn."""
    if design.view is None:
        return {}
    v, D = design.view, 2 * design.edge_y_mm
    figures = {k: float(x) for k, x in design.params.items() if k.startswith("kinber_") and x is not None}
    figures |= {"kinber_h_optimised": float(v.h_optimised), "kinber_focal_axis_x": v.focal_axis_x,
                "kinber_focal_axis_optimised": float(v.focal_axis_optimised),
                "kinber_view_angle_deg": v.view_angle_deg, "kinber_sigma_over_D_max": float(v.sigma.max()),
                "kinber_sigma_max_mm": float(v.sigma.max() * D),
                "kinber_sigma_max_deg": float(v.sigma.max() * D / wavelength_mm(spec.frequency_ghz) * 360.0)}
    if design.image_points_mm is not None:
        (iz, iy), _ = design.image_points_mm
        figures |= {"image_1_z_mm": float(iz), "image_1_y_mm": float(iy)}
    plates = _plates(spec, design)
    if plates is not None and plates[1] is not None:
        figures |= {"horn_flare_length_mm": plates[1].flare_length_mm,
                    "dielectric_tm1_cutoff_spacing_mm": wavelength_mm(spec.frequency_ghz) / (2 * design.n)}
    return figures


def _sigma_view(spec: BifocalSpec, design: BifocalDesign) -> Verification:
    """σ (3.10) against the source angle on the focal circle (seed-001 §3.1, §4): the Hermite faces the
    CAD splines pass through, exact trace, best image point / output direction per source."""
    v = design.view
    D = 2 * design.edge_y_mm
    out = "point image" if design.image_points_mm is not None else "plane output"
    plot = Plot("sigma", "RMS aberration against the source angle (seed-001 (3.10))", "source angle (deg)",
                "σ / D", (Series(f"Kinber lens, {out}", v.angles_deg, v.sigma),),
                caption=f"focal circle through F1, F2 crossing the axis at {v.focal_axis_x:.4f} D "
                        f"({'optimised' if v.focal_axis_optimised else 'given'}); max σ {v.sigma.max():.3g} D = "
                        f"{v.sigma.max() * D:.4g} mm")
    table = Table("sigma", "σ against the source angle", ("angle_deg", "sigma_over_D", "sigma_mm"),
                  tuple((float(a), float(s), float(s * D)) for a, s in zip(v.angles_deg, v.sigma)))
    return Verification({}, (), (table,), (plot,))


def verify(spec: BifocalSpec, design: BifocalDesign, layup: LayupPlan | None, fab) -> Verification:
    """As-built verification (:mod:`antenna_cad.asbuilt`) at the design focus O1 and at
    the edge of the usable scan range, plus the defocus study (seed-000 §5.9): p-p phase
    error against the feed displacement along the focal line, bifocal vs the single-surface lens of
    the same aperture and focal distance."""
    if design.image_points_mm is not None:     # a point-image lens is no collimator: σ only
        return _sigma_view(spec, design)
    budget = spec.design.phase_error_budget_deg
    st = defocus_study(design, budget_deg=budget, frequency_ghz=spec.frequency_ghz)
    study = (stock_study(_sheets(spec, design), partial(_lens, spec, design), spec.fabrication.stock_thicknesses_mm,
                         spec.verification)
             if layup is not None else ())
    lens, feeds = _lens(spec, design, layup), (("focus", 0.0, design.focus_offset_mm),
                                               ("edge", 0.0, st.usable_half_range_mm))
    v, fw = verify_lens(lens, feeds, spec.tolerances, layup, fab, study, spec.verification)
    v = v.merged(lens_patterns(lens, lens_variants(lens, layup, fab), feeds,
                               criteria_from(spec.design.aut, spec.design.test_zone), _height(spec), full_wave=fw))
    scan = {"usable_feed_half_range_mm": st.usable_half_range_mm, "usable_half_angle_deg": st.usable_half_angle_deg,
            "usable_feed_inner_mm": st.usable_inner_mm,
            "single_surface_usable_feed_half_range_mm": st.single_usable_half_range_mm,
            "single_surface_usable_half_angle_deg": st.single_usable_half_angle_deg,
            "single_surface_thickness_mm": st.single_thickness_mm,
            "on_axis_phase_error_p2p_deg": float(st.p2p_deg[0])}
    plot = Plot("defocus", "Aperture phase error against feed displacement", "feed y on the focal line (mm)",
                "p-p phase error, tilt removed (deg)",
                (Series("bifocal", st.feed_y_mm, st.p2p_deg),
                 Series(f"single-surface lens, f {design.edge_x_mm:g} mm, D {2 * design.edge_y_mm:g} mm",
                        st.feed_y_mm, st.single_p2p_deg, "dashed")),
                caption=f"usable feed band around the focus: bifocal {st.usable_inner_mm:.0f}…{st.usable_half_range_mm:.0f} mm "
                        f"({st.usable_half_angle_deg:.2f}°), single-surface {st.single_usable_half_range_mm:.0f} mm "
                        f"({st.single_usable_half_angle_deg:.2f}°)",
                hlines=(("budget", budget),))
    v = replace(v, figures=scan | v.figures, plots=v.plots + (plot,))
    return v if design.view is None else v.merged(_sigma_view(spec, design))
