"""Adapters of the trifocal graded-index lens (seed-001 §3.2) between its spec and the stages.

``material`` is the base dielectric (loss, density) of the slabs; each slab's εr is the mean of the
synthesized n²(y) over its band. Verification recomputes σ (3.10) against the field angle and the
seed's comparison with the homogeneous bifocal lens, and exposes the aperture field as arrays.
``printed``: the lens as a graded lattice of one filament (:mod:`antenna_cad.kinds.graded_printed`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from antenna_cad.asbuilt.patterns_arrays import array_patterns, best_focus, imaged_case, path_mm
from antenna_cad.spec.common import resolve_material
from antenna_cad.spec.graded import GradedLayupSpec, GradedSpec
from antenna_cad.spec.printed import PrintedSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.collimator import wavelength_mm
from antenna_cad.synthesis.graded_design import GradedDesign, ray_paths, synthesize_graded
from antenna_cad.synthesis.graded_lens import GradedParams
from antenna_cad.verification import Plot, Series, Table, Verification

SUMMARY_ANGLES = 5


def synthesize(spec: GradedSpec) -> GradedDesign:
    g = spec.design
    d1 = g.thickness * g.d1_fraction
    params = GradedParams(g.n0, g.m, g.a2, g.a4, g.y_a, g.rho, g.rho_prime, g.rho1, g.rho1_prime, d1,
                          g.thickness - d1, 1.0, g.points)
    return synthesize_graded(params=params, unit_mm=g.unit_mm, view_angle_deg=g.view_angle_deg,
                             slab_count=g.slabs.count)


def plan(spec: GradedSpec, design: GradedDesign):
    """Sheet layup: the foam sheets of every slab (no box); solid: none, the slabs are machined."""
    fab = spec.fabrication
    if not isinstance(fab, GradedLayupSpec):
        return None, ()
    from antenna_cad.fabrication.graded_layup import plan_graded_layup
    return plan_graded_layup(design, resolve_material(spec.material), spec.design.height_mm,
                             fab.sheet_thickness_mm, fab.kerf_mm, fab.board.width_mm, fab.board.length_mm), ()


def model(spec: GradedSpec, design: GradedDesign, layup, panels):
    from antenna_cad.geometry.graded import build_model
    built = build_model(design, resolve_material(spec.material), spec.design.height_mm, layup)
    if not isinstance(spec.fabrication, PrintedSpec):
        return built
    # printed: the STEP holds the lens envelope and its slabs for reference (the lattice is in printed/)
    return replace(built, parts=tuple(replace(p, role="reference") for p in built.parts))


def fabricate(spec: GradedSpec, design: GradedDesign, layup, panels):
    if isinstance(spec.fabrication, PrintedSpec):
        from antenna_cad.kinds.graded_printed import fabricate_printed
        return fabricate_printed(spec, design)
    if layup is not None:
        from antenna_cad.fabrication.graded_layup import fabricate_graded_layup
        fab = fabricate_graded_layup(design, layup, spec.name)
        if spec.fabrication.cam is None:
            return fab
        from antenna_cad.cam.straight import plan_straight_cam
        cam = plan_straight_cam(layup.sheets, fab.pieces, spec.fabrication.cam)
        return replace(fab, files=fab.files | cam.files, cam=cam)
    from antenna_cad.fabrication.graded import fabricate_graded
    return fabricate_graded(design, resolve_material(spec.material), spec.design.height_mm,
                            spec.fabrication.stock_allowance_mm, spec.name)


def fabrication_checks(spec: GradedSpec, design: GradedDesign, layup) -> list[Check]:
    """Slab permittivity steps against the law they replace: the largest |εr_k − n²(y)| in a band."""
    worst = 0.0
    for lo, hi, eps in zip(design.slab_edges[:-1], design.slab_edges[1:], design.slab_eps):
        worst = max(worst, float(np.max(np.abs(design.n(np.linspace(lo, hi, 101)) ** 2 - eps))))
    return [Check("slab_eps_step", "pass", worst, 0.0, "", f"largest departure of a slab's εr from n²(y) in "
                  f"its band: {worst:.4f} (set slabs.count for finer steps)")]


def _angles(design: GradedDesign) -> dict[str, float]:
    idx = np.linspace(len(design.angle_deg) // 2, len(design.angle_deg) - 1, SUMMARY_ANGLES).round().astype(int)
    return {f"sigma_at_{design.angle_deg[i]:.1f}deg": float(design.sigma[i]) for i in idx}


def summary(spec: GradedSpec, design: GradedDesign, layup) -> dict[str, float]:
    """Key figures: foci, layers, slabs, and σ (D = 1) against the field angle."""
    u = design.unit_mm
    v1 = np.array([float(design.x1(0.0)), 0.0])
    F1 = design.foci["F1"]
    figures = {"aperture_mm": 2 * design.half_aperture * u, "aperture_fraction_of_D": 2 * design.half_aperture,
               "wavelength_mm": wavelength_mm(spec.frequency_ghz), "synthesis_layers": len(design.layers),
               "slab_count": len(design.slab_eps), "n_edge": float(design.n(np.array([design.half_aperture]))[0]),
               "eps_r_min": float(design.slab_eps.min()), "eps_r_max": float(design.slab_eps.max()),
               "side_focus_angle_from_vertex_deg": float(np.degrees(np.arctan2(-F1[1], v1[0] - F1[0]))),
               "focus_F1_x_mm": float(F1[0] * u), "focus_F1_y_mm": float(F1[1] * u),
               "sigma_max": float(design.sigma.max()),
               "bifocal_comparison_sigma_max": float(design.comparison_sigma.max()),
               "bifocal_over_trifocal_sigma_ratio": float(design.comparison_sigma.max() / design.sigma.max())}
    if layup is not None:
        figures |= {"sheet_count": layup.count, "sheet_layers": layup.layers,
                    "sheet_thickness_mm": layup.sheet_thickness_mm, "top_layer_mm": layup.top_layer_mm}
    return figures | _angles(design)


def aperture_field(design: GradedDesign, wavelength: float, angle_deg: float = 0.0):
    """Plain arrays for the radiation-pattern module: exit points on surface 2 (mm, (x, y)), relative
    amplitude (uniform: the ray density is not weighted) and phase −2π/λ·(optical path from the source
    on the focal circle at ``angle_deg``), radians."""
    from antenna_cad.synthesis.graded_design import _circle, _on_circle
    xc, r = _circle(design.foci["F"], design.foci["F1"])
    s = _on_circle(xc, r, np.array([float(design.x1(0.0)), 0.0]), np.radians(angle_deg), -1.0)
    q, lengths = ray_paths(design.medium, design.x1, design.x2, design.half_aperture, s)
    return q * design.unit_mm, np.ones(len(q)), -2 * np.pi / wavelength * lengths * design.unit_mm


def verify(spec: GradedSpec, design: GradedDesign, layup, fab) -> Verification:
    """σ (3.10) against the field angle, the seed's bifocal comparison, the layer and slab tables."""
    lam = wavelength_mm(spec.frequency_ghz)
    pos, amp, phase = aperture_field(design, lam)
    plots = (Plot("sigma", "RMS aberration (3.10) against the field angle (seed-001 §3.2)", "field angle (deg)",
                  "σ / D", (Series("trifocal graded lens", design.angle_deg, design.sigma),
                            Series("homogeneous bifocal lens 1 (§3.1)", design.comparison_angle_deg,
                                   design.comparison_sigma, "dashed")),
                  caption="sources on the circle through F, F1, F2 (angle from the surface-1 vertex); images on "
                          "the circle through F', F1', F2' at the σ-minimising angle; N = 100 rays"),
             Plot("index", "Index across the aperture", "y (mm)", "n",
                  (Series("n(y) synthesized", np.linspace(0, design.half_aperture, 200) * design.unit_mm,
                          design.n(np.linspace(0, design.half_aperture, 200))),
                   Series("slabs", design.slab_edges * design.unit_mm,
                          np.sqrt(np.r_[design.slab_eps, design.slab_eps[-1]]), "steps"))))
    layers = Table("layers", "Synthesis layers (3.11): n² C¹, m_i solved per layer (3.31)",
                   ("y_lo_mm", "y_hi_mm", "m_i"),
                   tuple((lo * design.unit_mm, hi * design.unit_mm, m) for lo, hi, m in design.layers))
    field = Table("aperture-field", "Aperture field on surface 2, feed on axis (plain arrays for the pattern "
                  "module)", ("x_mm", "y_mm", "amplitude", "phase_rad"),
                  tuple((float(p[0]), float(p[1]), float(a), float(ph)) for p, a, ph in zip(pos, amp, phase)))
    figures = {"sigma_max": float(design.sigma.max()), "sigma_max_mm": float(design.sigma.max() * design.unit_mm),
               "sigma_max_deg": float(design.sigma.max() * design.unit_mm / lam * 360.0),
               "aperture_field_rays": len(pos)}
    v = Verification(figures, (), (layers, field), plots).merged(_patterns(spec, design, lam))
    if isinstance(spec.fabrication, PrintedSpec):
        from antenna_cad.kinds.graded_printed import printed_verification
        from antenna_cad.kinds.printed_package import printed_verification as parts_verification
        v = v.merged(printed_verification(spec, design))
        if getattr(fab, "lens", None) is not None:
            v = v.merged(parts_verification(fab))
    return v


def _patterns(spec: GradedSpec, design: GradedDesign, lam: float) -> Verification:
    """Patterns of the synthesized lens (continuous n(y); the slabs are not traced), feed on axis
    and at the field edge, referred to the best-focus image point (:mod:`antenna_cad.asbuilt.patterns_arrays`)."""
    cases, u = [], design.unit_mm
    for feed, angle in (("on_axis", 0.0), ("field_edge", spec.design.view_angle_deg / 2)):
        pos, amp, phase = aperture_field(design, lam, angle)
        a = np.radians(angle)
        guess = pos.mean(axis=0) + u * np.array([np.cos(a), np.sin(a)])    # across the axis, ~D behind
        image = best_focus(pos, path_mm(phase, lam), guess)
        cases.append(imaged_case("ideal", feed, pos, amp, phase, image, True, lam, design.half_aperture * u,
                                 spec.design.height_mm))
    return array_patterns(cases, "GO exit field of the continuous index law (uniform amplitude over the traced rays) "
                                 "referred to its best-focus image point; line aperture × the plate spacing")
