"""Patterns, test zone and AUT pattern distortion of the lenses of revolution, shared
by the collimator and bifocal kinds; the radiation models are in :mod:`antenna_cad.radiation`.

Aperture field: the exact meridional GO trace of :mod:`antenna_cad.asbuilt.lens` (ideal lens,
stepped stack as cut, stack as fabricated), taken back along the exit rays to the plane just
behind the lens (``z_ref``: the last point of its back face) — amplitude from Fresnel transmission
and dielectric loss as in seed-000 §4.4 (no ray-tube factor, an isotropic feed: the seed's model,
so no spillover), phase k·(optical path), zero outside the rim. A feed on the axis of a lens of
revolution gives a body of revolution E(r) (Hankel transform, exact); any other feed is the
meridional cut E(y) taken constant across x (the sagittal aberration is not traced).

Test zone and AUT: that field propagated to the AUT plane by the angular spectrum. The figures
use the 2-D form on the meridional cut (the seed's own, meridional, model), since an exactly symmetric
hard-edged aperture also focuses its edge wave onto the axis (an Arago-type caustic, ±1–3 dB
within a few λ of it at the seed's 10 cm), which measured ranges do not show (seed-000 §5.10:
"amplitude almost uniform") because no feed, edge or alignment is that symmetric; the exact
body-of-revolution result is reported beside it (``test_zone_diameter_bor_mm``). The AUT sees the
exact body-of-revolution field on the axis (the caustic covers too little area to matter in its
integrals) and the meridional cut taken constant across x for other feeds (an approximation that
overstates the rim ripple, which then spans whole chords). The AUT's sum
and difference cuts against the same AUT in a uniform plane wave, the linear phase tilt over the
AUT removed (it only points the beam), give Δ_Σ, Δ_main, Δ_side of seed-000 (1.20)–(1.23),
compared with the threshold the same AUT gets from a 22.5° quadratic phase error (the recipe of
Tables 1.6/1.7, recomputed). For reference the AUT is also put in the feed's spherical wave
without the lens (seed-000 Table 4.1 measured both).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.fullwave.verify import FullWave
from antenna_cad.asbuilt.lens import Lens, Medium, trace_lens
from antenna_cad.asbuilt.quiet_zone import lens_quiet_zone, lens_quiet_zone_off_axis
from antenna_cad.radiation.aperture import PatternFigures, bor_aperture, grid_aperture, pattern_figures
from antenna_cad.radiation.distortion import Aut, AutMeter, IntegralErrors
from antenna_cad.radiation.testzone import TestZone, largest_test_zone, propagate_bor, propagate_line
from antenna_cad.raytrace.collimator import axial_defocus_limits, trace_collimator
from antenna_cad.raytrace.trace2d import transmitted_amplitude
from antenna_cad.spec.common import TestZoneSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.collimator import edge_margin_mm, path_difference_approx_mm, path_difference_mm
from antenna_cad.verification import Plot, Series, Table, Verification, cell, finite_figures

SAMPLES_PER_WAVELENGTH = 20      # aperture and AUT-plane cuts
GRID_PER_WAVELENGTH = 4          # 2-D aperture grid (patterns of off-axis feeds)
PLOT_BEAMWIDTHS = 12             # pattern plots: ± this many λ/D about the beam
TEST_ZONE_RANGE = 1.25           # test-zone cut out to this × the lens radius
EDGE_HOLD_WAVELENGTHS = 0.5      # a trace ending this close to the rim is held out to it


@dataclass(frozen=True)
class Criteria:
    """``test_zone`` of the spec, and the AUT (None: :func:`_default_aut`)."""
    amplitude_db: float = 1.0
    phase_deg: float = 11.25
    aut: Aut | None = None
    difference: bool = True
    zone: TestZoneSpec = TestZoneSpec()          # the quiet-zone cylinder (antenna_cad.quietzone)


def criteria_from(aut_spec, test_zone_spec) -> Criteria:
    """The spec's ``aut`` and ``test_zone`` blocks (:mod:`antenna_cad.spec.common`) as criteria."""
    aut = None
    if aut_spec is not None:
        if aut_spec.diameter_mm is not None:
            aut = Aut(aut_spec.diameter_mm, aut_spec.diameter_mm, True, aut_spec.taper)
        else:
            aut = Aut(aut_spec.width_mm, aut_spec.height_mm, False, aut_spec.taper)
    return Criteria(test_zone_spec.amplitude_db, test_zone_spec.phase_deg, aut,
                    aut_spec is None or aut_spec.pattern == "sum_and_difference", test_zone_spec)


@dataclass(frozen=True)
class ExitField:
    y_mm: np.ndarray
    field: np.ndarray
    dissipative: float


def exit_field(lens: Lens, medium: Medium, feed, z_ref: float) -> ExitField:
    """GO field on the plane z = z_ref behind the lens, on a uniform cut over the aperture."""
    tr, keep = trace_lens(lens, medium, feed)
    zy, d = tr.points[-1][keep], tr.directions[-1][keep]
    back = (zy[:, 0] - z_ref) / d[:, 0]
    y, path = zy[:, 1] - back * d[:, 1], tr.opl[keep] - back
    amp = transmitted_amplitude(tr, lens.wavelength_mm, lens.tan_delta)[keep]
    lossless = transmitted_amplitude(tr, lens.wavelength_mm, 0.0)[keep]
    o = np.argsort(y)
    grid, e = resampled(y[o], amp[o], 2 * np.pi / lens.wavelength_mm * path[o], lens.radius_mm, lens.wavelength_mm)
    return ExitField(grid, e, float(np.sum(amp**2) / np.sum(lossless**2)))


def resampled(y_mm, amplitude, phase_rad, half_mm: float, wavelength_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """A field A·e^{jφ} known at increasing ``y_mm`` on the uniform cut −half … half. Where the
    samples stop short of ±half by less than ``EDGE_HOLD_WAVELENGTHS`` λ (the tracer aims its rays
    just inside the rim) the end samples are held out to the rim, so a uniform aperture stays uniform
    to its edge; beyond that (a shadow) the field is zero."""
    grid = np.linspace(-half_mm, half_mm, 2 * int(SAMPLES_PER_WAVELENGTH * half_mm / wavelength_mm) + 1)
    y = np.asarray(y_mm, float)
    hold = EDGE_HOLD_WAVELENGTHS * wavelength_mm
    lo, hi = (y[0] if y[0] + half_mm <= hold else -np.inf), (y[-1] if half_mm - y[-1] <= hold else np.inf)
    a = np.interp(np.clip(grid, lo, hi), y, amplitude, left=0.0, right=0.0)
    return grid, a * np.exp(1j * np.interp(grid, y, phase_rad))


def _aperture(lens: Lens, ef: ExitField, on_axis: bool, height_mm: float | None):
    return cut_aperture(ef.y_mm, ef.field, lens.wavelength_mm, lens.radius_mm, on_axis, height_mm)


def cut_aperture(y_mm: np.ndarray, field: np.ndarray, lam: float, R: float, on_axis: bool,
                 height_mm: float | None = None):
    """The aperture of a cut E(y) on the uniform symmetric grid ``y_mm``: a body of revolution E(r)
    (``on_axis``), else E(y) taken constant across a disc of radius ``R`` or, with ``height_mm``,
    across a strip 2R × height (a cylindrical or 2-D lens between plates)."""
    if on_axis:
        half = y_mm >= 0
        return bor_aperture(y_mm[half], field[half], lam, R)
    step = max(1, SAMPLES_PER_WAVELENGTH // GRID_PER_WAVELENGTH)
    y, e = y_mm[::step], field[::step]
    if height_mm is None:
        x = y.copy()
        inside = np.hypot(*np.meshgrid(x, y)) <= R
        return grid_aperture(x, y, np.where(inside, e[:, None], 0.0), lam, np.pi * R**2)
    x = np.linspace(-height_mm / 2, height_mm / 2, 2 * max(1, int(GRID_PER_WAVELENGTH * height_mm / 2 / lam)) + 1)
    return grid_aperture(x, y, np.broadcast_to(e[:, None], (len(y), len(x))), lam, 2 * R * height_mm)


def _at_aut(lens: Lens, ef: ExitField, on_axis: bool, distance_mm: float, y_out: np.ndarray) -> np.ndarray:
    if on_axis:
        half = ef.y_mm >= 0
        return propagate_bor(ef.y_mm[half], ef.field[half], lens.wavelength_mm, distance_mm, np.abs(y_out))
    return propagate_line(ef.y_mm, ef.field, lens.wavelength_mm, distance_mm, y_out)


def _detilted(x: np.ndarray, y: np.ndarray, e: np.ndarray, weight: np.ndarray) -> np.ndarray:
    """``e`` on the grid [iy, ix] with its weighted best-fit linear phase removed."""
    X, Y = np.meshgrid(x, y)
    on = weight > 0
    ph = np.unwrap(np.angle(e), axis=0)
    A = np.stack([np.ones(on.sum()), X[on], Y[on]], 1)
    w = np.sqrt(weight[on])
    coef = np.linalg.lstsq(A * w[:, None], ph[on] * w, rcond=None)[0]
    return e * np.exp(-1j * (coef[0] + coef[1] * X + coef[2] * Y))


def aut_field(lens: Lens, ef: ExitField, on_axis: bool, distance_mm: float):
    """The propagated field on the AUT plane as a function of (X, Y) grids: E(ρ) of the body of
    revolution on the axis, else the meridional cut E(y) taken constant across x."""
    def on_grid(X, Y):
        if not on_axis:
            return np.broadcast_to(_at_aut(lens, ef, False, distance_mm, Y[:, 0])[:, None], X.shape)
        rho = np.linspace(0.0, float(np.hypot(X, Y).max()), 2 * X.shape[0] + 1)
        e = _at_aut(lens, ef, True, distance_mm, rho)
        return np.interp(np.hypot(X, Y), rho, e.real) + 1j * np.interp(np.hypot(X, Y), rho, e.imag)
    return on_grid


def aut_errors(meter: AutMeter, field_on_grid) -> tuple[IntegralErrors, IntegralErrors, tuple]:
    """Sum and difference integral errors of the AUT in the field ``field_on_grid(X, Y)`` on the
    AUT plane, its linear tilt removed, and the cuts."""
    x, y = meter.x, meter.y
    return meter.errors(_detilted(x, y, field_on_grid(*np.meshgrid(x, y)), meter.excitation))



def lens_patterns(lens: Lens, variants: list[tuple[str, Medium]], feeds, criteria: Criteria,
                  height_mm: float | None = None, full_wave: FullWave | None = None) -> Verification:
    """Patterns, test zone and AUT errors of every lens variant at every feed (module docstring).
    ``variants``: (name, medium), ideal first and the as-built last; ``feeds``: (name, z, y), the
    nominal first; ``height_mm``: a cylindrical lens's height (None: a lens of revolution);
    ``full_wave``: the full-wave stage, whose fields over the quiet zone come first when they ran."""
    lam, R = lens.wavelength_mm, lens.radius_mm
    z_ref = float(np.max(lens.back_z(np.linspace(0.0, R, 401))))
    for _, medium in variants:
        if hasattr(medium, "z_edges"):
            z_ref = max(z_ref, float(medium.z_edges[-1]))
    distance = lens.antenna_z_mm - z_ref
    figures: dict[str, float] = {}
    rows, plots, fields, same_model = [], [], {}, {}
    for feed, z, y in feeds:
        on_axis = height_mm is None and y == 0.0
        chief = float(np.degrees(np.arctan2(-y, float(lens.front_z(0.0)) - z)))    # the ray through the vertex
        series, theta0 = [], None
        for variant, medium in variants:
            ef = exit_field(lens, medium, (z, y), z_ref)
            fields[(variant, feed)] = (ef, on_axis)
            ap = _aperture(lens, ef, on_axis, height_mm)
            pf: PatternFigures = pattern_figures(ap, dissipative=ef.dissipative)
            same_model[(variant, feed)] = (pattern_figures(_aperture(lens, ef, False, height_mm)).directivity_dbi
                                           if on_axis else pf.directivity_dbi)
            key = f"pattern_{'fabricated' if variant == 'fabricated' else variant}_{feed}"
            eff = pf.efficiency
            figures |= {f"{key}_directivity_dbi": pf.directivity_dbi, f"{key}_hpbw_deg": pf.beam.hpbw_deg,
                        f"{key}_sll_db": pf.beam.sll_db, f"{key}_efficiency": eff.total,
                        f"{key}_beam_deg": pf.beam.theta_deg, f"{key}_squint_deg": pf.beam.theta_deg - chief,
                        f"{key}_efficiency_taper": eff.taper,
                        f"{key}_efficiency_phase": eff.phase, f"{key}_efficiency_dissipative": eff.dissipative}
            rows.append((feed, variant, cell(pf.beam.theta_deg, 4), cell(pf.beam.theta_deg - chief, 4),
                         cell(pf.directivity_dbi), cell(pf.beam.hpbw_deg, 4),
                         cell(pf.beam.sll_db, 2), cell(eff.taper, 4), cell(eff.phase, 4), cell(eff.dissipative, 4),
                         cell(eff.total, 4)))
            theta0 = pf.beam.theta_deg if theta0 is None else theta0
            span = np.degrees(PLOT_BEAMWIDTHS * lam / (2 * R))
            th = np.linspace(theta0 - span, theta0 + span, 801)
            cut = ap.cut()
            series.append(Series(variant, th, cut.db(th, pf.beam.peak), "line" if not series else "dashed"))
        plots.append(Plot(f"pattern-{feed.replace('_', '-')}", f"Far-field pattern, feed {feed} (z {z:.0f}, y {y:.0f} mm)",
                          "θ in the scan plane (deg)", "relative power (dB)", tuple(series),
                          caption=("body of revolution: Hankel transform of E(r)" if on_axis else
                                   "meridional cut E(y) taken constant across the aperture") +
                          "; GO aperture field, scalar, no obliquity factor; each lens to its own peak"))
    nominal, edge = feeds[0][0], feeds[-1][0]
    for variant, _ in variants:
        figures[f"pattern_{variant}_{edge}_scan_loss_db"] = same_model[(variant, nominal)] - same_model[(variant, edge)]
    tables = [Table("patterns", "Far-field patterns per lens and feed",
                    ("feed", "lens", "beam deg", "squint deg", "directivity dBi", "HPBW deg", "first sidelobe dB", "η taper",
                     "η phase", "η dissipative", "efficiency"), tuple(rows),
                    caption="GO aperture field (Fresnel + dielectric loss, seed-000 §4.4; isotropic feed: no "
                            "spillover); squint: beam minus the feed's ray through the lens vertex; "
                            "D = (4πS/λ²)·η_taper·η_phase, efficiency = η_taper·η_phase·η_dissipative; scan loss: "
                            "nominal minus edge directivity, both with the meridional cut across the aperture")]
    tz_p, tz_f, zone, tz_table = _test_zone(lens, variants, fields, nominal, distance, criteria)
    figures |= tz_f
    plots += tz_p
    tables.append(tz_table)
    aut = criteria.aut or _default_aut(lens, zone, distance)
    a_tab, a_plot, a_fig, checks = _aut(lens, variants, feeds, fields, z_ref, distance, aut, criteria)
    if criteria.aut is None:
        checks = []                 # no AUT in the spec: the default one is reported, not judged
    figures |= a_fig
    v = Verification(finite_figures(figures), tuple(checks), tuple(tables + [a_tab]), tuple(plots + [a_plot]))
    if height_mm is not None:
        return v
    for feed in feeds:                      # the zone for every feed: on the axis over the disc, else on the cut
        ef, on_axis = fields[(variants[0][0], feed[0])]
        if on_axis:
            v = v.merged(lens_quiet_zone(lens, variants, feed, z_ref, criteria, full_wave))
        else:
            v = v.merged(lens_quiet_zone_off_axis(lens, variants, feed, z_ref, criteria, (ef.y_mm, ef.field),
                                                  feed is feeds[0]))
    return v


def _test_zone(lens: Lens, variants, fields, nominal: str, distance: float, criteria: Criteria):
    lam, R = lens.wavelength_mm, lens.radius_mm
    y = np.linspace(-TEST_ZONE_RANGE * R, TEST_ZONE_RANGE * R,
                    2 * int(SAMPLES_PER_WAVELENGTH / 2 * TEST_ZONE_RANGE * R / lam) + 1)
    zones: dict[str, TestZone] = {}
    for variant, _ in variants:
        ef, _ = fields[(variant, nominal)]
        zones[variant] = largest_test_zone(y, _at_aut(lens, ef, False, distance, y), criteria.amplitude_db,
                                   criteria.phase_deg)
    built = variants[-1][0]
    figures = {f"test_zone_diameter_mm_{v}": z.diameter_mm for v, z in zones.items()}
    figures |= {"test_zone_diameter_mm": zones[built].diameter_mm, "test_zone_distance_mm": distance}
    ef, on_axis = fields[(built, nominal)]
    if on_axis:
        bor = largest_test_zone(y, _at_aut(lens, ef, True, distance, y), criteria.amplitude_db, criteria.phase_deg)
        figures["test_zone_diameter_bor_mm"] = bor.diameter_mm
        zones[f"{built}, exact body of revolution"] = bor
    amp = Plot("test-zone-amplitude", f"Test zone: amplitude {distance:.0f} mm behind the lens",
               "y on the AUT plane (mm)", "amplitude to the centre (dB)",
               tuple(Series(f"{v} (zone Ø{z.diameter_mm:.0f} mm)", z.y_mm, z.amplitude_db, "line" if i == 0 else "dashed")
                     for i, (v, z) in enumerate(zones.items())),
               caption="angular-spectrum propagation of the GO exit field (edge diffraction included), 2-D on "
                       "the meridional cut; the body of revolution adds the axial caustic of its hard edge; "
                       f"criterion ±{criteria.amplitude_db:g} dB",
               hlines=((f"+{criteria.amplitude_db:g} dB", criteria.amplitude_db),
                       (f"−{criteria.amplitude_db:g} dB", -criteria.amplitude_db)))
    pha = Plot("test-zone-phase", f"Test zone: phase {distance:.0f} mm behind the lens",
               "y on the AUT plane (mm)", "phase, zone tilt removed (deg)",
               tuple(Series(v, z.y_mm, np.where(z.amplitude_db > -10, z.phase_deg, np.nan), "line" if i == 0 else "dashed")
                     for i, (v, z) in enumerate(zones.items())),
               caption=f"criterion ±{criteria.phase_deg:g}°; drawn where the amplitude is above −10 dB",
               hlines=((f"+{criteria.phase_deg:g}°", criteria.phase_deg), (f"−{criteria.phase_deg:g}°", -criteria.phase_deg)))
    table = Table("test-zone", "Test zone on the AUT plane alone (nominal feed; single-plane figures, kept beside "
                  "the quiet zone for comparison)", ("lens", "diameter mm", "distance mm"),
                  tuple((v, cell(z.diameter_mm, 1), cell(distance, 1)) for v, z in zones.items()),
                  caption=f"largest centred zone within ±{criteria.amplitude_db:g} dB and ±{criteria.phase_deg:g}° "
                          "(linear tilt removed); angular spectrum of plane waves (not Fresnel)")
    return (amp, pha), figures, zones[built].diameter_mm, table


def _default_aut(lens: Lens, zone_mm: float, distance_mm: float) -> Aut:
    """A circular AUT when the spec names none: the lens less the GO edge margin of seed-000 §4.6
    (2.1) on each side, or the test zone, whichever is larger, and at least 2λ."""
    lam = lens.wavelength_mm
    size = max(2 * lens.radius_mm - 2 * edge_margin_mm(lam, distance_mm), zone_mm, 2 * lam)
    return Aut(size, size, True, 0)


def _aut(lens: Lens, variants, feeds, fields, z_ref: float, distance: float, aut: Aut, criteria: Criteria):
    lam = lens.wavelength_mm
    meter = AutMeter(aut, lam)
    th_sum, th_diff = meter.thresholds()
    rows = [("threshold (22.5° quadratic)", "", _e(th_sum.total), _e(th_sum.main), _e(th_sum.side),
             _e(th_diff.total), _e(th_diff.main), _e(th_diff.side))]
    figures = {"aut_sum_threshold": th_sum.total, "aut_difference_threshold": th_diff.total}
    built, nominal = variants[-1][0], feeds[0][0]
    cuts = None
    fz, fy = feeds[0][1], feeds[0][2]
    z_aut = z_ref + distance
    k = 2 * np.pi / lam
    s, d, _ = aut_errors(meter, lambda X, Y: np.exp(1j * k * np.sqrt((z_aut - fz) ** 2 + X**2 + (Y - fy) ** 2)))
    rows.append((nominal, "no lens (feed's spherical wave)", _e(s.total), _e(s.main), _e(s.side), _e(d.total),
                 _e(d.main), _e(d.side)))
    figures |= {"aut_sum_integral_error_no_lens": s.total, "aut_difference_integral_error_no_lens": d.total}
    for feed, _, _ in feeds:
        for variant, _ in variants:
            s, d, c = aut_errors(meter, aut_field(lens, *fields[(variant, feed)], distance))
            rows.append((feed, variant, _e(s.total), _e(s.main), _e(s.side), _e(d.total), _e(d.main), _e(d.side)))
            tag = "" if (variant, feed) == (built, nominal) else f"_{variant}_{feed}"
            figures |= {f"aut_sum_integral_error{tag}": s.total, f"aut_difference_integral_error{tag}": d.total}
            if (variant, feed) == (built, nominal):
                figures |= {"aut_sum_main_error": s.main, "aut_sum_side_error": s.side,
                            "aut_difference_main_error": d.main, "aut_difference_side_error": d.side}
                cuts = c
    size = f"Ø{aut.height_mm:.0f} mm" if aut.circular else f"{aut.width_mm:.0f} × {aut.height_mm:.0f} mm"
    cols = ("feed", "lens", "ΔΣ sum", "Δmain sum", "Δside sum", "ΔΣ diff", "Δmain diff", "Δside diff")
    if not criteria.difference:
        rows = [r[:5] for r in rows]
        cols = cols[:5]
    table = Table("aut-distortion", f"AUT pattern distortion ({size}, taper cos^{aut.taper_k}, {distance:.0f} mm "
                  "behind the lens)", cols, tuple(rows),
                  caption="integral errors of seed-000 (1.20)–(1.23): |F| to its own peak, θ ±90°, main lobe to "
                          "the reference's first nulls, odd excitation for the difference pattern; the AUT in the "
                          "propagated field vs a plane wave, linear tilt removed")
    (a_sum, a_diff), (i_sum, i_diff) = cuts, meter.ideal
    span = np.degrees(8 * lam / aut.height_mm)
    th = np.linspace(-span, span, 801)
    series = [Series("sum, plane wave", th, i_sum.db(th), "line"), Series("sum, in the lens field", th, a_sum.db(th), "dashed")]
    if criteria.difference:
        ref = np.abs(i_diff(np.sin(np.radians(th)))).max()
        series += [Series("difference, plane wave", th, i_diff.db(th, ref), "line"),
                   Series("difference, in the lens field", th, a_diff.db(th), "dashed")]
    plot = Plot("aut-patterns", f"AUT patterns ({size}) in the {built} lens's field, nominal feed",
                "θ (deg)", "relative power (dB)", tuple(series), caption="each pattern to its own peak")
    checks = [Check("aut_sum_distortion", "warn" if figures["aut_sum_integral_error"] > th_sum.total else "pass",
                    figures["aut_sum_integral_error"], th_sum.total, "",
                    f"AUT {size} sum-pattern integral error {figures['aut_sum_integral_error']:.3g} vs the 22.5° "
                    f"quadratic threshold {th_sum.total:.3g} (seed-000 §4.5, recomputed)")]
    if criteria.difference:
        v = figures["aut_difference_integral_error"]
        checks.append(Check("aut_difference_distortion", "warn" if v > th_diff.total else "pass", v, th_diff.total,
                            "", f"AUT {size} difference-pattern integral error {v:.3g} vs threshold {th_diff.total:.3g}"))
    else:
        figures = {k: v for k, v in figures.items() if "difference" not in k}
    return table, plot, figures, checks


def _e(v: float) -> str:
    return f"{v:.3e}"


# ------------------------------------------------------------------ collimator feed-displacement limits

def _integral_error(design, gap_mm: float, meter: AutMeter, feed_y_mm: float, difference: bool) -> float:
    """Δ_Σ of a 1-D AUT (seed-000 (1.19), as Table 2.4) in the GO field of the ideal lens with the
    feed at (−f, y), on the plane ``gap_mm`` behind the flat face; linear tilt removed."""
    lam = design.wavelength_mm
    ap = trace_collimator(focal_length_mm=design.focal_length_mm, n=design.n, diameter_mm=design.diameter_mm,
                          back_z_mm=design.thickness_mm, antenna_z_mm=design.thickness_mm + gap_mm,
                          wavelength_mm=lam, feed_zy_mm=(-design.focal_length_mm, feed_y_mm), rays=401, margin=0.999)
    o = np.argsort(ap.y_mm)
    path = lambda X, Y: np.interp(Y, ap.y_mm[o], ap.path_mm[o])          # noqa: E731
    return aut_errors(meter, lambda X, Y: np.exp(1j * 2 * np.pi / lam * path(X, Y)))[1 if difference else 0].total


def _first_crossing(fun, grid: np.ndarray, level: float) -> float:
    """First point of the increasing ``grid`` where ``fun`` reaches ``level`` (brentq to 1e-4 of
    the grid span between samples; the grid's end when it never does, 0 at once)."""
    from scipy.optimize import brentq       # at use: validating a spec loads no optimizer
    prev = grid[0]
    if fun(prev) >= level:
        return float(prev)
    for x in grid[1:]:
        if fun(x) >= level:
            return float(brentq(lambda t: fun(t) - level, prev, x, xtol=1e-4 * float(np.ptp(grid))))
        prev = x
    return float(grid[-1])


def collimator_feed_limits(design, gap_mm: float, aut_height_mm: float, taper_k: int, difference: bool,
                           scan_grid: np.ndarray) -> Verification:
    """Feed-displacement limits of the single-surface lens (seed-000 §5.5–§5.7): along the axis by
    the phase rule (Table 2.1, σ < 1 and σ > 1), across it by the integral rule (Table 2.4: the
    transverse feed angle where the AUT's Δ_Σ reaches its 22.5° quadratic threshold, 1-D AUT of the
    AUT's height, GO field), and the path difference Δl (2.14)/(2.15)."""
    f, D, lam = design.focal_length_mm, design.diameter_mm, design.wavelength_mm
    lo, hi = axial_defocus_limits(f, D, design.eps_r, gap_mm, lam, design.phase_error_budget_deg)
    aut = Aut(lam, min(aut_height_mm, D), False, taper_k)
    meter = AutMeter(aut, lam)
    th = meter.thresholds()
    figures = {"path_difference_mm": path_difference_mm(D, f), "path_difference_approx_mm": path_difference_approx_mm(D, f),
               "axial_feed_limit_sigma_near": lo, "axial_feed_limit_sigma_far": np.nan if hi is None else hi}   # NaN: none
    rows = [("Δl (2.14) / (2.15)", f"{figures['path_difference_mm']:.3f} / {figures['path_difference_approx_mm']:.3f} mm"),
            ("axial feed limit σ < 1 (phase rule)", f"{lo:.3f} (feed at {lo * f:.0f} mm)"),
            ("axial feed limit σ > 1 (phase rule)", "none up to σ = 20" if hi is None else f"{hi:.3f} (feed at {hi * f:.0f} mm)")]
    for name, diff in (("sum", False), ("difference", True))[:2 if difference else 1]:
        edge = _first_crossing(lambda y: _integral_error(design, gap_mm, meter, y, diff), f * scan_grid,
                               th[diff].total)
        angle = float(np.degrees(np.arctan2(edge, f)))
        figures[f"scan_half_angle_integral_{name}_deg"] = angle
        rows.append((f"transverse feed angle, integral rule ({name}, Δ_Σ ≤ {th[diff].total:.3g})", f"±{angle:.2f}°"))
    table = Table("feed-limits", "Feed-displacement limits (ideal lens, seed-000 Tables 2.1 and 2.4)", ("limit", "value"),
                  tuple(rows), caption=f"σ = feed distance / f; 1-D AUT {aut.height_mm:g} mm, cos^{taper_k} taper, "
                  f"{gap_mm:g} mm behind the flat face; phase rule {design.phase_error_budget_deg:g}° p-p")
    return Verification(finite_figures(figures), (), (table,), ())
