"""Adapters of the aplanatic mirror-lens (seed-004) between its spec and the stages.

Frame: seed-004 §1 in mm — feed (focus) at the origin, +Z into the body, the beam leaves toward −Z.
A sheet layup reuses the spine (:func:`plan_sheets` with ``max_radius_in``, anchored at the body's
lowest z): both faces are curved and sanded; the mirror face must be smooth to be metallised, so
the body as fabricated is the sanded stack (GO sees no sheet joints of the same material). Taper-cut
(``edge: taper``): each sheet's rim is the cone through the body's half-width at its two faces
(:func:`cone_radius`), so only the chords' sagitta is left to smooth.

Verification (3-D GO, :mod:`antenna_cad.raytrace.mirror_lens`): the body as fabricated is the one
the CAD holds — splines through the sampled exact profiles — traced against the exact synthesis;
then εr, thickness and feed position at ± their tolerances; σ against the field angle with the feed
on the focal curve; and the aperture field (amplitude, phase) as plain arrays for the radiation
and full-wave modules (:func:`aperture_field`). A printed body (:mod:`antenna_cad.kinds.uniform_printed`)
is synthesized at ``design.refractive_index`` and traced as fabricated at the εr its lattice has.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import partial

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.asbuilt.lens import ruze_loss_db
from antenna_cad.kinds.layup import (cone_fit_check, fabricate_layup, layup_figures, neck_checks, plan_layup_and_box,
                                    plan_sheets)
from antenna_cad.kinds.mirror_lens_fullwave import body_parts, full_wave_verification
from antenna_cad.asbuilt.patterns_arrays import array_patterns, line_case, path_mm
from antenna_cad.asbuilt.taper import cone_table
from antenna_cad.materials import Material
from antenna_cad.raytrace.mirror_lens import Body, Surface, aperture_field as trace_aperture_field, sigma_at
from antenna_cad.spec.common import SheetLayupSpec, resolve_material
from antenna_cad.spec.mirror_lens import MirrorLensSpec
from antenna_cad.spec.printed import PrintedSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.mirror_lens import (MirrorLensDesign, astigmatism_rows, synthesize_mirror_lens,
                                               target_value)
from antenna_cad.verification import Plot, Series, Table, Verification

CAD_SAMPLES = 257           # = geometry.mirror_lens.SPLINE_POINTS (the spline the STEP holds)
TOLERANCE_STEPS = (-1.0, 1.0)
PROFILE_ROWS = 11
PATTERN_CAPTION = ("3-D GO exit field of the scan-plane cut (isotropic feed, Fresnel and dielectric loss), beam tilt "
                   "removed; on axis a body of revolution (Hankel transform), at the field edge E(x) across the disc")


def _metal(spec: MirrorLensSpec) -> Material:
    m = spec.design.mirror
    return Material(m.metal, 1.0, 0.0, m.density_kg_m3, "metal (conductor) of the mirror layer, from design.mirror")


def body_material(spec: MirrorLensSpec, as_printed: bool = False) -> Material:
    """The body's dielectric: the spec's material, or a printed lattice at n² (``as_printed``: at the
    εr its rounded rods give)."""
    from antenna_cad.kinds.uniform_printed import index_material
    return index_material(spec, as_printed)


def synthesize(spec: MirrorLensSpec) -> MirrorLensDesign:
    g = spec.design
    m = body_material(spec)
    return synthesize_mirror_lens(diameter_mm=g.diameter_mm, frequency_ghz=spec.frequency_ghz, n=m.n,
                                  f0=g.f0_norm, d0=g.d0_norm, gamma=g.gamma_norm,
                                  optimize=g.optimize.model_dump() if g.optimize else None,
                                  field_half_angle_deg=g.field_half_angle_deg)


def cone_radius(spec: MirrorLensSpec, design: MirrorLensDesign):
    """r(z): the body's half-width at depth z (seed-004 frame), 0 outside it — what a taper-cut
    sheet's cone passes through at each face (and what ``make-lens check`` holds the wire to); z is
    clamped to the body (its flat face is a sheet face: a manifest's rounded z stays on it)."""
    lo, hi = design.z_range_mm
    return lambda z: design.max_radius_in_mm(min(max(z, lo), hi), min(max(z, lo), hi))


def _sheets(spec: MirrorLensSpec, design: MirrorLensDesign):
    z_lo, z_hi = design.z_range_mm
    r = cone_radius(spec, design)
    return partial(plan_sheets, spec.fabrication, lens_radius_mm=design.body_radius_mm,
                   lens_thickness_mm=z_hi - z_lo, z_origin_mm=z_lo, radius_at=lambda z: r(z_lo + z),
                   max_radius_in=lambda lo, hi: design.max_radius_in_mm(z_lo + lo, z_lo + hi))


def plan(spec: MirrorLensSpec, design: MirrorLensDesign):
    """(LayupPlan, box panels) for a sheet layup; (None, ()) for a solid body. ``auto`` sheet
    thickness takes the thickest stock (the faces are sanded: no unsanded trace applies)."""
    fab = spec.fabrication
    if isinstance(fab, SheetLayupSpec) and fab.sheet_thickness_mm == "auto":
        fab = fab.model_copy(update={"sheet_thickness_mm": max(fab.stock_thicknesses_mm)})
        spec = spec.model_copy(update={"fabrication": fab})
    return plan_layup_and_box(fab, _sheets(spec, design), None)


def _ring(spec: MirrorLensSpec, design: MirrorLensDesign):
    from antenna_cad.fabrication.mirror_lens import flange_geometry
    f = spec.design.flange
    return flange_geometry(design, f.width_mm, f.thickness_mm)


def model(spec: MirrorLensSpec, design: MirrorLensDesign, layup: LayupPlan | None, panels):
    from antenna_cad.geometry.mirror_lens import build_model
    box = resolve_material(spec.fabrication.box.material) if layup else None
    built = build_model(design, spec.design, layup, body_material(spec, as_printed=True), _metal(spec), box, panels)
    if not isinstance(spec.fabrication, PrintedSpec):
        return built
    # printed: the STEP holds the body's envelope for reference (the lattice is in printed/); no flange
    return replace(built, parts=tuple(replace(p, role="reference") if p.label == "body" else p
                                      for p in built.parts if p.label != "flange"))


def fabricate(spec: MirrorLensSpec, design: MirrorLensDesign, layup: LayupPlan | None, panels):
    from antenna_cad.fabrication.mirror_lens import add_mirror_step, fabricate_solid
    m = body_material(spec, as_printed=True)
    if isinstance(spec.fabrication, PrintedSpec):
        from antenna_cad.kinds.uniform_printed import fabricate_printed
        z_lo, _ = design.z_range_mm
        section = design.section_mm() - (0.0, z_lo)       # the printer's frame: axis up, z from the lowest point
        plan = fabricate_printed(spec, section, design.volume_mm3(), design.body_radius_mm,
                                 "print with the axis up, the front face on the bed")
        return plan if plan.lens is None else add_mirror_step(plan, design, spec.design, m, _metal(spec), spec.name)
    if layup is None:
        return fabricate_solid(design, spec.design, _ring(spec, design), m, _metal(spec),
                               spec.fabrication.stock_allowance_mm, spec.name)
    fab = fabricate_layup(spec.fabrication, layup, panels, m, spec.name)
    return add_mirror_step(fab, design, spec.design, m, _metal(spec), spec.name)


def fabrication_checks(spec: MirrorLensSpec, design: MirrorLensDesign, layup: LayupPlan | None) -> list[Check]:
    """Sheet discs against the body (contain it with no excess), and neck material."""
    if layup is None:
        return []
    if layup.edge == "taper":
        return [cone_fit_check(layup, cone_radius(spec, design))] + neck_checks(layup)
    fit = max(abs(s.radius_mm - design.max_radius_in_mm(s.z_min_mm, s.z_max_mm)) for s in layup.sheets)
    return [Check.upper("sheet_disc_fit", fit, 1e-6, "mm", "sheet disc radius vs largest body radius in its slab")
            ] + neck_checks(layup)


def summary(spec: MirrorLensSpec, design: MirrorLensDesign, layup: LayupPlan | None) -> dict[str, float]:
    """Key figures: parameters, series coefficients, profiles at the rim, exact − series at the rim,
    σ against the field angle (units of D, as seed-004 (18)), volume and mass."""
    p, D = design.profiles, design.diameter_mm
    m = body_material(spec, as_printed=True)
    front_diff, mirror_diff = design.rim_difference()
    figures = {"n": p.n, "diameter_mm": D, "f0_mm": p.f0 * D, "d0_mm": p.d0 * D, "gamma_mm": p.gamma * D,
               "f0_D": p.f0, "d0_D": p.d0, "gamma_D": p.gamma, "wavelength_mm": design.wavelength_mm,
               "diameter_wavelengths": D / design.wavelength_mm,
               "feed_half_angle_deg": float(np.degrees(design.feed_half_angle_rad)),
               "front_rim_r_mm": p.s[-1] * D, "front_rim_z_mm": p.f[-1] * D,
               "mirror_vertex_z_mm": p.Z_b[0] * D, "mirror_rim_r_mm": p.R_b[-1] * D, "mirror_rim_z_mm": p.Z_b[-1] * D,
               "entry_zone_radius_mm": float(p.r_a[-1] * D) if not p.feed_on_surface else 0.0,
               "front_exact_minus_series_at_rim_mm": front_diff * D,
               "mirror_exact_minus_series_at_rim_mm": mirror_diff * D,
               "target_A_exact": target_value(design),
               "body_volume_mm3": design.volume_mm3(), "body_mass_kg": design.volume_mm3() / 1e9 * m.density_kg_m3,
               "mirror_area_mm2": design.mirror_area_mm2()}
    if design.series is not None:
        c = design.series
        figures |= {"f2": c.f2, "f4": c.f4, "F2": c.F2, "F4": c.F4}
    else:
        figures |= {"R2": design.R2R4[0], "R4": design.R2R4[1]}
    if design.optimum is not None:
        figures |= {"gamma_optimum_D": float(design.optimum.gamma), "target_A_optimum": design.optimum.A}
    for ang, sig in zip(design.scan.field_angle_deg, design.scan.sigma):
        figures[f"sigma_D_at_{ang:.1f}deg"] = float(sig)
    if layup is not None:
        figures |= layup_figures(layup)
    if isinstance(spec.fabrication, PrintedSpec):
        from antenna_cad.kinds.uniform_printed import summary_figures
        figures |= summary_figures(spec)
    return figures


# ------------------------------------------------------------------ verification

def _surface(r, z, dz) -> Surface:
    spl = CubicHermiteSpline(r, z, dz)
    return Surface(spl, spl.derivative(), float(r[-1]))


def fabricated_body(design: MirrorLensDesign, tan_delta: float = 0.0, n: float | None = None,
                    mirror_shift: float = 0.0) -> Body:
    """The body the CAD holds (units of D): splines through the CAD samples of both exact faces;
    ``mirror_shift`` moves the mirror along z (a thickness error)."""
    D = design.diameter_mm
    rf, zf, df = design.face_samples_mm("front", CAD_SAMPLES)
    rm, zm, dm = design.face_samples_mm("mirror", CAD_SAMPLES)
    p = design.profiles
    return Body(_surface(rf / D, zf / D, df), _surface(rm / D, zm / D + mirror_shift, dm), p.n if n is None else n,
                float(p.s[-1]), p.gamma, p.feed_on_surface, tan_delta)


@dataclass(frozen=True)
class ApertureFieldMM:
    """The aperture field on the exit face along the scan-plane cut, in mm and degrees (plain
    arrays for the radiation and full-wave modules). ``amplitude``: isotropic feed (multiply by the
    feed pattern at ``launch_angle_rad``), relative to its maximum; ``phase_deg``: tilt removed."""
    r_mm: np.ndarray
    amplitude: np.ndarray
    phase_deg: np.ndarray
    launch_angle_rad: np.ndarray
    beam_angle_deg: float


def aperture_field(spec: MirrorLensSpec, design: MirrorLensDesign, feed_mm=(0.0, 0.0, 0.0),
                   body: Body | None = None) -> ApertureFieldMM:
    """GO aperture field of the body as fabricated for a feed at ``feed_mm`` (x, y, z in the kind's frame)."""
    D = design.diameter_mm
    m = body_material(spec, as_printed=True)
    body = body or fabricated_body(design, m.tan_delta, m.n)
    af = trace_aperture_field(body, np.asarray(feed_mm, float) / D, design.wavelength_mm / D)
    return ApertureFieldMM(af.x * D, af.amplitude, af.phase_deg, af.launch_angle, af.beam_angle_deg)


def _rms_deg(design: MirrorLensDesign, sigma_D: float) -> float:
    return 360.0 * sigma_D * design.diameter_mm / design.wavelength_mm


def _phase_stats(design: MirrorLensDesign, body: Body, feed_D=(0.0, 0.0, 0.0)) -> tuple[float, float]:
    """(RMS, p-p) aperture phase error in degrees over the 3-D ray set, tilt removed."""
    wf = sigma_at(body, feed_D)
    return _rms_deg(design, wf.sigma), _rms_deg(design, float(np.ptp(wf.error)))


def _r(x) -> float:
    return round(float(x), 6)


def _sensitivity(spec: MirrorLensSpec, design: MirrorLensDesign):
    """Aperture phase error of the body as fabricated, nominal feed, at ± each build tolerance; the
    added errors combined by root-sum-square against the budget (as the other lenses)."""
    tol, D = spec.tolerances, design.diameter_mm
    m = body_material(spec)
    thick, eps, feed = tol.thickness_tolerance_mm / D, tol.eps_r_tolerance, tol.feed_position_tolerance_mm
    axis = (0.0, 0.0, 0.0)
    cases = (("εr", f"{eps:g}", lambda s: (fabricated_body(design, n=np.sqrt(m.eps_r + s * eps)), axis)),
             ("thickness", f"{thick * D:g} mm", lambda s: (fabricated_body(design, mirror_shift=s * thick), axis)),
             ("feed axial", f"{feed:g} mm", lambda s: (fabricated_body(design), (0.0, 0.0, s * feed / D))),
             ("feed transverse", f"{feed:g} mm", lambda s: (fabricated_body(design), (s * feed / D, 0.0, 0.0))))
    base = _phase_stats(design, fabricated_body(design))
    rows, added = [("nominal", "", _r(base[0]), _r(base[1]), _r(ruze_loss_db(base[0])))], {}
    for name, size, at in cases:
        stats = [_phase_stats(design, *at(s)) for s in TOLERANCE_STEPS]
        rows += [(name, f"{sign}{size}", _r(rms), _r(pp), _r(ruze_loss_db(rms)))
                 for sign, (rms, pp) in zip("−+", stats)]
        added[name] = tuple(max(0.0, max(st[k] ** 2 for st in stats) - base[k] ** 2) for k in (0, 1))
    rms = float(np.sqrt(base[0] ** 2 + sum(a[0] for a in added.values())))
    p2p = float(np.sqrt(base[1] ** 2 + sum(a[1] for a in added.values())))
    dominant = max(added, key=lambda k: added[k][0])
    budget = spec.design.phase_error_budget_deg
    table = Table("sensitivity", "Aperture phase error against the build tolerances (nominal feed)",
                  ("tolerance", "deviation", "RMS deg", "p-p deg", "gain loss dB"), tuple(rows),
                  caption="3-D GO trace of the body as fabricated, tilt removed; thickness: the mirror face off "
                          f"along z (machining or sanding to the gauge); RSS {p2p:.2f}° p-p, {rms:.2f}° RMS; "
                          f"dominant: {dominant}")
    check = Check("tolerance_budget", "warn" if p2p > budget else "pass", p2p, budget, "deg",
                  f"as built with every tolerance (RSS of the added errors): {p2p:.1f}° p-p, {rms:.2f}° RMS "
                  f"vs budget {budget:g}°; dominant: {dominant}")
    return table, check, {"tolerance_rss_p2p_deg": p2p, "tolerance_rss_rms_deg": rms,
                          "tolerance_rss_gain_loss_db": ruze_loss_db(rms)}


def _profile_plot(design: MirrorLensDesign) -> Plot:
    p, D = design.profiles, design.diameter_mm
    return Plot("profiles", "Generatrices: exact synthesis and truncated series", "z (mm)", "r (mm)",
                (Series("front face, exact", p.f * D, p.s * D),
                 Series("front face, series", design.front_series(p.s) * D, p.s * D, "dashed"),
                 Series("mirror, exact", p.Z_b * D, p.R_b * D),
                 Series("mirror, series", design.mirror_series(p.R_b) * D, p.R_b * D, "dashed"),
                 Series("feed (focus)", np.array([0.0]), np.array([0.0]), "points")), equal_aspect=True,
                caption="feed at z = 0; exact − series at the rim: front {:.2f} mm, mirror {:.2f} mm".format(
                    *(v * D for v in design.rim_difference())))


def _profile_table(design: MirrorLensDesign) -> Table:
    p, D = design.profiles, design.diameter_mm
    rows = []
    for r in np.linspace(0.05, 0.5, 10):
        k = min(int(np.searchsorted(p.s, r - 1e-12)), len(p.s) - 1)
        rows.append((_r(p.s[k] * D), _r(p.f[k] * D), _r(design.front_series(p.s[k]) * D), _r(np.degrees(p.alpha[k])),
                     _r(p.R_b[k] * D), _r(p.Z_b[k] * D), _r(design.mirror_series(p.R_b[k]) * D)))
    return Table("profiles", "Exact profiles and truncated series (mm)",
                 ("exit r", "front z exact", "front z series", "launch α deg", "mirror R", "mirror Z exact",
                  "mirror Z series"), tuple(rows), caption="seed-004 §5.2/§5.3 layout, scaled to D")


def _field_plot_and_table(design: MirrorLensDesign):
    sc = design.scan
    plot = Plot("sigma-field", "RMS aberration σ against the field angle (3-D ray trace)", "field angle (deg)",
                "σ (units of D)", (Series("feed on the focal curve (δZ optimised)", sc.field_angle_deg, sc.sigma),
                                    Series("feed on the focal plane (δZ = 0)", sc.field_angle_deg,
                                           sc.sigma_on_axis_focus, "dashed")),
                caption="seed-004 (18): eikonal RMS over the rays that reach the aperture, tilt and piston removed; rays "
                        "launched uniformly in direction cosines over 1.25× the on-axis cone (a displaced feed still "
                        "fills the aperture; over the on-axis cone alone σ at the field edge is ≈ 20 % lower)")
    D = design.diameter_mm
    rows = tuple((_r(a), _r(dr * D), _r(dz * D), float(f"{s:.4g}"), _r(_rms_deg(design, s)))
                 for a, dr, dz, s in zip(sc.field_angle_deg, sc.delta_r, sc.delta_z, sc.sigma))
    table = Table("field", "Aberration over the field (feed on the focal curve)",
                  ("field angle deg", "feed δR mm", "feed δZ mm", "σ (D)", "RMS phase deg"), rows)
    return plot, table


def _astigmatism_table(design: MirrorLensDesign) -> Table:
    rows = tuple(tuple(None if v is None else _r(v) for v in row) for row in astigmatism_rows(design))
    return Table("astigmatism", "δR² coefficients L_X, L_Y (units of 1/D)",
                 ("exit r (D)", "L_X exact", "L_Y exact", "L_X series (19)", "L_Y series (19)"), rows,
                 caption="exact: general formula of seed-004 §3.2 (or (20) for the feed on the surface) on the "
                         "marched geometry, validated against 3-D stationary paths in the tests")


def _aperture_plot(spec, design: MirrorLensDesign, name: str, feed, bodies):
    """Aperture phase of the ideal and the fabricated body and the amplitude, for one feed (mm);
    the plot, its figures and the pattern cases of :mod:`antenna_cad.asbuilt.patterns_arrays`."""
    series, figures, cases = [], {}, []
    for variant, body in bodies:
        rms, pp = _phase_stats(design, body, np.asarray(feed) / design.diameter_mm)
        af = aperture_field(spec, design, feed, body)
        figures |= {f"{variant}_{name}_rms_deg": rms, f"{variant}_{name}_p2p_deg": pp,
                    f"{variant}_{name}_gain_loss_db": ruze_loss_db(rms),
                    f"{variant}_{name}_edge_amplitude_db": float(20 * np.log10(min(af.amplitude[[0, -1]])))}
        series.append(Series(f"phase, {variant}", af.r_mm, af.phase_deg, "line" if variant == "ideal" else "dashed"))
        lam = design.wavelength_mm
        cases.append(line_case(variant, name, af.r_mm, af.amplitude, path_mm(np.radians(af.phase_deg), lam), lam,
                               design.diameter_mm / 2, on_axis=not any(feed[:2]),
                               note=f"beam {af.beam_angle_deg:.2f}°, tilt removed"))
    series.append(Series("amplitude × 100 (isotropic feed)", af.r_mm, 100 * af.amplitude, "dashed"))
    figures[f"{name}_beam_angle_deg"] = af.beam_angle_deg
    title = f"Aperture field, feed {name.replace('_', ' ')} ({feed[0]:.1f}, {feed[1]:.1f}, {feed[2]:.1f}) mm"
    return Plot(f"aperture-field-{name.replace('_', '-')}", title, "x on the exit face, scan plane (mm)",
                "phase (deg), amplitude × 100", tuple(series),
                caption=f"3-D GO, beam at {af.beam_angle_deg:.2f}°, tilt removed"), figures, cases


def _fullwave_parts(spec: MirrorLensSpec, design: MirrorLensDesign, layup: LayupPlan | None) -> dict[str, list]:
    """The full-wave decks' bodies: ideal, and as fabricated (a solid body with its flange ring)."""
    kw = dict(coating_mm=spec.design.mirror.thickness_mm, resolution=spec.verification.resolution_px_per_lambda,
              cad_samples=CAD_SAMPLES)
    solid = layup is None and not isinstance(spec.fabrication, PrintedSpec)
    return {"ideal": body_parts(design, "ideal", eps_r=body_material(spec).eps_r, **kw),
            "fabricated": body_parts(design, "fabricated", eps_r=body_material(spec, as_printed=True).eps_r,
                                     flange=_ring(spec, design) if solid else None, **kw)}


def verify(spec: MirrorLensSpec, design: MirrorLensDesign, layup: LayupPlan | None, fab) -> Verification:
    """The exact and the fabricated body on axis and at the field edge (feed on the focal curve),
    σ over the field, the tolerance study; p-p phase against the budget; the full-wave check with
    the feed on the axis (:mod:`antenna_cad.kinds.mirror_lens_fullwave`)."""
    m, built = body_material(spec), body_material(spec, as_printed=True)
    D, sc = design.diameter_mm, design.scan
    bodies = (("ideal", design.body(m.tan_delta)), ("fabricated", fabricated_body(design, built.tan_delta, built.n)))
    figures, plots, cases = {}, [_profile_plot(design)], []
    for name, feed in (("on_axis", (0.0, 0.0, 0.0)), ("field_edge", (-sc.delta_r[-1] * D, 0.0, sc.delta_z[-1] * D))):
        plot, fig, case = _aperture_plot(spec, design, name, feed, bodies)
        plots.append(plot)
        figures |= fig
        cases += case
    field_plot, field_table = _field_plot_and_table(design)
    sens_table, sens_check, sens_figures = _sensitivity(spec, design)
    figures |= sens_figures
    budget, edge = spec.design.phase_error_budget_deg, figures["fabricated_field_edge_p2p_deg"]
    edge_check = Check("field_edge_phase_error", "warn" if edge > budget else "pass", edge, budget, "deg",
                       f"aperture phase at the field edge ({sc.field_angle_deg[-1]:.1f}°, feed on the focal "
                       f"curve): {edge:.1f}° p-p vs budget {budget:g}°")
    cones = (cone_table(layup, cone_radius(spec, design)),) if layup is not None and layup.edge == "taper" else ()
    if isinstance(spec.fabrication, PrintedSpec) and getattr(fab, "lens", None) is not None:
        from antenna_cad.kinds.printed_package import printed_verification
        printed = printed_verification(fab)
    else:
        printed = Verification()
    return printed.merged(Verification(figures, (sens_check, edge_check),
                        (_profile_table(design), field_table, _astigmatism_table(design), sens_table) + cones,
                        tuple(plots + [field_plot])).merged(array_patterns(cases, PATTERN_CAPTION)).merged(
        full_wave_verification(design, spec.verification, _fullwave_parts(spec, design, layup),
                               aperture_field(spec, design))))
