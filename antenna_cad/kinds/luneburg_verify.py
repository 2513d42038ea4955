"""As-built verification of the multilayer Luneburg lens (seed-002 §2.1b, §2.5, §2.8).

Three lenses are traced from the feed to the aperture in a meridional plane (2-D: exact for
shells and the cylinder, the in-plane fan for a sheet stack):

* ideal — the continuous law of §2.1 (:mod:`antenna_cad.raytrace.graded`, RK4);
* stepped — the layers with their design εr: homogeneous shells (``shells``, the cylinder's
  rings), or for a sphere sheet layup the staircase its sheets make (ring radii at the sheet
  mid-planes: the shell boundaries become sheet faces and ring edges);
* as built — the grades actually chosen (nearest available εr) and the real geometry: shells
  with the foam feed boss in the vertical plane that holds it; a sphere layup as sized
  (``contain``: rings turned to the spheres, i.e. shells; ``mid_plane``: the staircase;
  ``edge: taper``: every ring edge the cone through its sphere at the sheet's two faces, stepped
  and as built alike).

Feeds: on the axis, and scanned 45° and 90° from it (the sheets' normal). A lens of revolution
about its centre (graded law, shells) is the same at every scan angle, so only staircases are
traced scanned; the scan plane is the horizontal one, which the boss below the lens does not
cut. Staircases with sheets thinner than the first Fresnel zone √(λR) are not GO facets (the
wave averages their risers): they enter to first order in the index change along the shell rays
(Fermat, :func:`antenna_cad.raytrace.luneburg.first_order_opl`); their GO-facet trace is
reported too (``stepped_go_facets``). Thicker sheets are traced as facets.

Sensitivity (as built, on axis, ``spec.tolerances``), to first order along the nominal rays, so
that rays never jump branch at the stepped lens's GO folds: εr of each grade uniform in ±tol,
one value per grade (a production batch), ``DRAWS`` seeded draws; thickness: each shell
boundary radius ± tol (machining, turning, ring cutting; the outer one stays put under a feed
resting on the surface) or, for a staircase, each sheet ± tol (stack re-centred); feed: ± tol
along and across its axis, worst of four (Hamilton: ΔL = −δ·t̂). Figure: the aperture phase the
tolerance adds (tilt removed), RMS over the draws, and its Ruze loss; first order, so the loss
grows with the square of the tolerance. Pins and registration dowels are of their shell's own
grade and inside it, so they do not enter.

Full-wave (Meep, point feed at the focus) and the exact multilayer-sphere series (Mie) follow in
:mod:`antenna_cad.kinds.luneburg_fullwave` on the same media.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from antenna_cad.fabrication.rings import RingLayupPlan, ring_radii
from antenna_cad.kinds.luneburg_fullwave import luneburg_full_wave
from antenna_cad.kinds.patterns_luneburg import luneburg_patterns
from antenna_cad.raytrace.graded import trace_graded
from antenna_cad.raytrace.luneburg import (RUZE_DB_PER_RAD2, Fan, added_phase_rms, fan_figures, feed_fan,
                                           feed_move_opl, first_order_opl, focus_shift)
from antenna_cad.raytrace.media import Shells, Staircase, trace_media
from antenna_cad.spec.luneburg import LuneburgShellsSpec
from antenna_cad.spec.printed import PrintedSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.luneburg import LuneburgDesign, traced_law
from antenna_cad.verification import Plot, Series, Table, Verification

FEEDS = (("axis", 0.0), ("scan45", 45.0), ("scan90", 90.0))
N_RAYS = 512
FAN_RAYS = 30
DRAWS = 16
GUIDE_RMS_DEG = 22.5          # λ/16 RMS, as the synthesis check
IDEAL_RMS_LIMIT_DEG = 0.1     # the RK4 trace of the continuous law must focus to this


class _Lens:
    """One traced configuration. ``medium``: what the rays see for first-order path integrals
    (the traced medium, or the staircase entered to first order along the rays of ``trace``);
    ``staircase``: the medium changes with the scan angle; ``in_scan_plane``: the lens as seen
    in the horizontal scan plane (without the boss), where it differs."""

    def __init__(self, design: LuneburgDesign, trace, medium=None, *, first_order: bool = False,
                 staircase: bool = False, extend_mm: float = 0.0, in_scan_plane: "_Lens | None" = None):
        self.design, self.trace, self.medium = design, trace, medium
        self.first_order, self.staircase, self.extend_mm = first_order, staircase, extend_mm
        self.in_scan_plane = in_scan_plane

    def fan(self, scan_deg: float = 0.0, axial_mm: float = 0.0, lateral_mm: float = 0.0) -> Fan:
        d = self.design
        f = feed_fan(self.trace, d.radius_mm, d.focal_distance_mm, d.feed_q, d.shape, scan_rad=math.radians(scan_deg),
                     n_rays=N_RAYS, axial_mm=axial_mm, lateral_mm=lateral_mm)
        if not self.first_order:
            return f
        return replace(f, opl_mm=f.opl_mm + first_order_opl(self.medium, f.trace, self.extend_mm))

    def scanned(self, scan_deg: float) -> tuple["_Lens", float]:
        """The lens and angle a feed scanned by ``scan_deg`` is traced with: a staircase as it is;
        a lens of revolution about its centre at 0° (identical), in the scan plane."""
        if self.staircase or not scan_deg:
            return self, scan_deg
        return (self.in_scan_plane or self), 0.0


def _traced(design: LuneburgDesign, medium, **kw) -> _Lens:
    return _Lens(design, lambda o, d: trace_media(medium, o, d), medium, **kw)


def _shells(design: LuneburgDesign, eps, radius_shift=None, boss=None) -> Shells:
    ro = np.array([L.r_outer_mm for L in design.layers])
    if radius_shift is not None:
        ro = np.maximum.accumulate(np.maximum(ro + radius_shift, 1e-3))
    return Shells(ro, np.sqrt(np.asarray(eps, float)), boss)


def _staircase(design: LuneburgDesign, layup: RingLayupPlan, eps, sheet_shift=None) -> Staircase:
    """Rings at the sheet mid-planes (as planned, z nominal), or the taper-cut rings' cones as cut
    (``edge: taper``, their faces the spheres' radii at the sheet faces), each with its shell's εr;
    sheets thickened by ``sheet_shift`` (a cone keeps its two face radii) and the stack re-centred."""
    ri = np.array([L.r_inner_mm for L in design.layers])
    ro = np.array([L.r_outer_mm for L in design.layers])
    n = np.sqrt(np.asarray(eps, float))
    rings = []
    for s in layup.sheets:
        if layup.edge == "taper":
            rings.append([(r.cone_inner_mm, r.cone_outer_mm, n[r.shell_index - 1]) for r in s.rings])
            continue
        inner, outer = ring_radii(ri, ro, s.z_min_mm, s.z_max_mm, "mid_plane")
        rings.append([((a, a), (b, b), nn) for a, b, nn in zip(inner, outer, n) if b - a > 1e-9])
    t = np.array([s.thickness_mm for s in layup.sheets]) + (0.0 if sheet_shift is None else sheet_shift)
    z = np.concatenate([[0.0], np.cumsum(t)])
    return Staircase.from_cones(z - 0.5 * z[-1], rings)


def staircase_as_facets(design: LuneburgDesign, layup: RingLayupPlan) -> bool:
    """GO facets only for sheets thicker than the first Fresnel zone √(λR): finer risers are
    averaged by diffraction and enter to first order."""
    return layup.sheet_thickness_mm >= math.sqrt(design.wavelength_mm * design.radius_mm)


def _staircase_lens(design: LuneburgDesign, layup: RingLayupPlan, eps, facets: bool, sheet_shift=None) -> _Lens:
    medium = _staircase(design, layup, eps, sheet_shift)
    if facets:
        return _traced(design, medium, staircase=True)
    return _Lens(design, lambda o, d: trace_media(_shells(design, eps), o, d), medium, first_order=True,
                 staircase=True, extend_mm=2 * layup.sheet_thickness_mm)


def _lenses(spec, design: LuneburgDesign, layup: RingLayupPlan | None, grade_eps: np.ndarray,
            *, radius_shift=None, sheet_shift=None, as_built_only: bool = False) -> dict[str, _Lens]:
    """ideal / stepped / as_built (or only as_built, for the tolerance draws)."""
    R = design.radius_mm
    stair = layup is not None and design.shape == "sphere"
    facets = stair and staircase_as_facets(design, layup)
    fab = spec.fabrication
    boss = None
    if isinstance(fab, LuneburgShellsSpec) and fab.feed_boss is not None and design.shape == "sphere":
        rb, length = fab.feed_boss.diameter_mm / 2, fab.feed_boss.length_mm
        boss = (-rb, rb, -R - length, 0.0, math.sqrt(grade_eps[-1]))
    if stair and (layup.sizing == "mid_plane" or layup.edge == "taper"):
        built = _staircase_lens(design, layup, grade_eps, facets, sheet_shift)
    else:                                   # shells (+ boss), cylinder, or a layup turned to the spheres
        built = _traced(design, _shells(design, grade_eps, radius_shift, boss),
                        in_scan_plane=_traced(design, _shells(design, grade_eps, radius_shift)) if boss else None)
    if isinstance(fab, PrintedSpec):        # the lattice homogenized, clipped where unprintable, and its skin
        from antenna_cad.kinds.luneburg_printed import printed_medium
        built = _traced(design, printed_medium(spec, design))
    if as_built_only:
        return {"as_built": built}
    law = traced_law(design.law, design.focal_distance_ratio, design.outer_shell, R)
    ideal_eps = [L.eps_r_design for L in design.layers]
    return {"ideal": _Lens(design, lambda o, d: trace_graded(law.eps_of_r2, R, o, d, steps_per_radius=200,
                                                            core_mm=law.core_mm, shell_eps=law.shell_eps)),
            "stepped": _staircase_lens(design, layup, ideal_eps, facets) if stair else
            _traced(design, _shells(design, ideal_eps)),
            "as_built": built}


def verify_luneburg(spec, design: LuneburgDesign, layup: RingLayupPlan | None, fab, materials) -> Verification:
    """Figures, checks, tables and plots of the three lenses and the tolerance study."""
    R, lam, shape = design.radius_mm, design.wavelength_mm, design.shape
    grade_eps = np.array([L.eps_r for L in design.layers])
    figs = lambda fan: fan_figures(fan, lam, R, shape, design.efficiency_taper, design.efficiency_spillover)  # noqa: E731
    lenses = _lenses(spec, design, layup, grade_eps)
    results, fans, done = {}, {}, {}
    for case, lens in lenses.items():
        for feed, scan in FEEDS:
            use, angle = lens.scanned(scan)
            if (id(use), angle) not in done:
                done[(id(use), angle)] = _trace_with_focus(use, angle, figs)
            fans[(case, feed)], results[(case, feed)] = done[(id(use), angle)]
    stair = layup is not None and shape == "sphere"
    if stair and not staircase_as_facets(design, layup):     # the staircase as GO facets, for comparison
        facets = _staircase_lens(design, layup, [L.eps_r_design for L in design.layers], True)
        for feed, scan in FEEDS:
            fans[("stepped_go_facets", feed)] = fan = facets.fan(scan)
            results[("stepped_go_facets", feed)] = (figs(fan), None, None)
    figures: dict[str, float] = {}
    for (case, feed), (ff, shift, rms_at) in results.items():
        key = f"{case}_{feed}"
        figures |= {f"{key}_phase_pp_deg": ff.phase_pp_deg, f"{key}_phase_rms_deg": ff.phase_rms_deg,
                    f"{key}_phase_rms_full_deg": ff.phase_rms_full_deg,
                    f"{key}_gain_loss_db": ff.gain_loss_db, f"{key}_efficiency": ff.efficiency,
                    f"{key}_amplitude_taper_db": ff.amplitude_taper_db, f"{key}_squint_deg": ff.squint_deg,
                    f"{key}_lost_fraction": ff.lost_fraction}
        if shift is not None:
            figures |= {f"{key}_focus_shift_mm": shift, f"{key}_focus_rms_deg": rms_at}
    sens_rows, sens_plot, sens_figs, dominant = _sensitivity(spec, design, layup, grade_eps, materials,
                                                             lenses["as_built"], fans[("as_built", "axis")])
    figures |= sens_figs
    if stair:
        figures["sheet_thickness_over_wavelength"] = layup.sheet_thickness_mm / lam
    tables = (_layer_table(design, materials), _grade_table(design, layup, fab, materials),
              _aperture_table(results, stair),
              Table("sensitivity", "Tolerances: phase and gain they add to the as-built lens (on axis)",
                    ("parameter", "tolerance", "model", "added phase RMS deg", "added Ruze loss dB"),
                    tuple(sens_rows), f"dominant: {dominant[0]}; first order along the nominal rays, tilt removed"))
    plots = (_fan_plot(design, layup if stair and layup.sizing == "mid_plane" else None, fans[("as_built", "axis")],
                       "ray-fan", "Ray fan through the as-built lens, feed on axis"),
             *([_fan_plot(design, layup, fans[("stepped", "scan90")], "ray-fan-scan90",
                          "Ray fan through the sheet staircase (GO facets), feed at 90° to the sheet normal")]
               if stair and staircase_as_facets(design, layup) else []),
             _phase_plot(results, stair), _eps_plot(design), sens_plot)
    checks = _checks(design, layup, results, dominant, sens_figs["sens_total_gain_loss_db"])
    go = {v: (results[(case, "axis")][0].s_mm, results[(case, "axis")][0].phase_deg)
          for v, case in (("ideal", "ideal"), ("stepped", "stepped"), ("fabricated", "as_built"))}
    full_wave = luneburg_full_wave(spec, design, {"stepped": lenses["stepped"].medium,
                                                  "fabricated": lenses["as_built"].medium}, go)
    return Verification(figures, tuple(checks), tables, plots).merged(luneburg_patterns(design, fans)).merged(full_wave)


def _trace_with_focus(lens: _Lens, angle: float, figs) -> tuple[Fan, tuple]:
    """The fan, its figures, and the focus shift (first order, never into the lens) with the RMS
    traced there (0 and the nominal RMS if the move does not help)."""
    d = lens.design
    fan = lens.fan(angle)
    ff = figs(fan)
    shift = max(focus_shift(fan, d.wavelength_mm, d.radius_mm), d.radius_mm - d.focal_distance_mm)
    rms_at = figs(lens.fan(angle, axial_mm=shift)).phase_rms_deg if shift else ff.phase_rms_deg
    if rms_at >= ff.phase_rms_deg:
        shift, rms_at = 0.0, ff.phase_rms_deg
    return fan, (ff, shift, rms_at)


# ---------------------------------------------------------------- sensitivity

def _sensitivity(spec, design: LuneburgDesign, layup, grade_eps, materials, built: _Lens, nominal: Fan):
    """Added phase RMS and Ruze loss per tolerance (module docstring), first order: table rows,
    plot, figures and the dominant tolerance (label, loss dB)."""
    tol = spec.tolerances
    lam = design.wavelength_mm
    rng = np.random.default_rng(20041223)                 # seeded: reproducible files
    names = sorted({m.name for m in materials})
    stair = layup is not None and design.shape == "sphere" and layup.sizing == "mid_plane"
    grade_draws = rng.uniform(-1, 1, (DRAWS, len(names)))
    geo_draws = rng.uniform(-1, 1, (DRAWS, layup.count if stair else len(design.layers)))
    on_surface = design.focal_distance_mm <= design.radius_mm + 1e-9
    if not stair and on_surface:
        geo_draws[:, -1] = 0.0                            # the feed rests on the outer surface
    col = [names.index(m.name) for m in materials]
    extend = max(2 * layup.sheet_thickness_mm if stair else 0.0, 10 * tol.thickness_tolerance_mm + 1.0)
    ref = first_order_opl(built.medium, nominal.trace, extend)

    def rms(delta_opl) -> float:
        return added_phase_rms(nominal, delta_opl, lam, design.radius_mm)

    def perturbed(**kw) -> float:
        medium = _lenses(spec, design, layup, kw.pop("eps", grade_eps), as_built_only=True, **kw)["as_built"].medium
        return rms(first_order_opl(medium, nominal.trace, extend) - ref)

    e, t, f = tol.eps_r_tolerance, tol.thickness_tolerance_mm, tol.feed_position_tolerance_mm
    shift = "sheet_shift" if stair else "radius_shift"
    moves = [(a, b) for a, b in ((f, 0.0), (-f, 0.0), (0.0, f), (0.0, -f)) if not (on_surface and a < 0)]
    thickness_model = ("each sheet ± tol, stack re-centred" if stair else
                       "each ring radius ± tol (cutting)" if design.shape == "cylinder" else
                       "each shell boundary radius ± tol (machining/turning)")
    cases = (("eps_r", "εr of each grade", f"±{e:g}", f"uniform, one draw per grade, RMS of {DRAWS} draws",
              [perturbed(eps=np.maximum(grade_eps + e * d[col], 1.0)) for d in grade_draws]),
             ("thickness", "thickness", f"±{t:g} mm", f"{thickness_model}, RMS of {DRAWS} draws",
              [perturbed(**{shift: t * d}) for d in geo_draws]),
             ("feed", "feed position", f"±{f:g} mm", "along and across the feed axis, worst of 4",
              [max(rms(feed_move_opl(nominal, a, b)) for a, b in moves)]))
    rows, series, figs, losses = [], [], {}, {}
    scale = np.linspace(0.0, 2.0, 21)
    for key, label, tol_text, model, values in cases:
        phase = float(np.sqrt(np.mean(np.square(values))))
        loss = RUZE_DB_PER_RAD2 * math.radians(phase) ** 2
        losses[label] = loss
        rows.append((label, tol_text, model, round(phase, 3), round(loss, 4)))
        figs |= {f"sens_{key}_phase_rms_deg": phase, f"sens_{key}_gain_loss_db": loss}
        series.append(Series(label, scale, loss * scale**2, "line"))
    figs["sens_total_gain_loss_db"] = sum(losses.values())
    dominant = max(losses.items(), key=lambda item: item[1])
    plot = Plot("sensitivity", "Added Ruze loss vs tolerance (as built, on axis)", "tolerance (× spec value)",
                "added gain loss (dB)", tuple(series), f"first order: loss ∝ tolerance²; dominant at 1×: {dominant[0]}")
    return rows, plot, figs, dominant


# ---------------------------------------------------------------- checks, tables, plots

def _checks(design, layup, results, dominant: tuple[str, float], total: float) -> list[Check]:
    ideal = results[("ideal", "axis")][0]
    built = results[("as_built", "axis")][0]
    out = [Check.upper("ideal_lens_focus", ideal.phase_rms_deg, IDEAL_RMS_LIMIT_DEG, "deg",
                       "RK4 trace of the continuous law: aperture phase RMS (tracer and law agree)"),
           Check("as_built_phase_rms", "warn" if built.phase_rms_deg > GUIDE_RMS_DEG else "pass",
                 built.phase_rms_deg, GUIDE_RMS_DEG, "deg",
                 f"as-built GO aperture phase {built.phase_rms_deg:.3g}° RMS on axis, gain loss "
                 f"{built.gain_loss_db:.3g} dB (λ/16 = 22.5° guide; GO overstates few-layer errors, seed-002 §2.1b)"),
           Check("tolerance_dominant", "pass", dominant[1], total, "dB",
                 f"largest added Ruze loss from the tolerances: {dominant[0]}, {dominant[1]:.3g} dB "
                 f"of {total:.3g} dB in all (first order, on axis)")]
    if layup is not None and design.shape == "sphere":
        t, zone = layup.sheet_thickness_mm, math.sqrt(design.wavelength_mm * design.radius_mm)
        facets = staircase_as_facets(design, layup)
        worst = max(results[("stepped", f)][0].phase_rms_deg for f, _ in FEEDS)
        text = (f"sheets {t:g} mm ({t / design.wavelength_mm:.2f} λ) vs the Fresnel zone √(λR) = {zone:.3g} mm: "
                + ("staircase traced as GO facets" if facets else
                   "staircase entered to first order along the shell rays (sub-zone risers are averaged by "
                   "diffraction; the GO-facet trace is reported as stepped_go_facets)")
                + f"; worst stepped RMS over the scan {worst:.3g}°")
        out.append(Check("staircase_model", "pass", t / zone, 1.0, "t/√(λR)", text))
    return out


def _layer_table(design: LuneburgDesign, materials) -> Table:
    rows = []
    for L, m in zip(design.layers, materials):
        if design.shape == "sphere":
            vol = 4.0 / 3.0 * math.pi * (L.r_outer_mm**3 - L.r_inner_mm**3)
        else:
            vol = math.pi * (L.r_outer_mm**2 - L.r_inner_mm**2) * design.height_mm
        rows.append((L.index, round(L.r_inner_mm, 3), round(L.r_outer_mm, 3), round(L.eps_r_design, 5), m.name,
                     round(L.eps_r, 5), round(L.eps_r - L.eps_r_design, 5), float(f"{L.tan_delta:.3g}"),
                     round(vol / 1e6, 4), round(vol / 1e9 * m.density_kg_m3, 4)))
    return Table("layers", "Layer table", ("shell", "r_in mm", "r_out mm", "εr ideal", "grade", "εr chosen",
                                           "error", "tanδ eff", "volume L", "mass kg"), tuple(rows),
                 "εr ideal: the law at the layer's radial midpoint (seed-002 §2.2); chosen: the nearest grade "
                 "or the ideal foam; tanδ eff of §2.7; mass of the finished shell")


def _grade_table(design, layup, fab, materials) -> Table:
    rows = []
    for name in sorted({m.name for m in materials}):
        m = next(x for x in materials if x.name == name)
        shells = [L.index for L, x in zip(design.layers, materials) if x.name == name]
        if layup is not None:
            rings = [r for r in layup.rings if r.material.name == name]
            counts = (len({r.sheet_index for r in rings}), len(rings), sum(r.sectors for r in rings),
                      fab.boards.get(name, 0))
        else:
            counts = (0, 0, sum(1 for r in fab.rows if r.material == name), 0)
        rows.append((name, round(m.eps_r, 5), round(m.density_kg_m3, 2), " ".join(map(str, shells)), *counts,
                     round(fab.totals_kg.get(name, 0.0), 4)))
    return Table("grades", "Sheets and rings per grade", ("grade", "εr", "kg/m³", "shells", "sheets", "rings",
                                                          "pieces", "boards", "mass kg"), tuple(rows),
                 "pieces: rings, sectors of split rings (layup) or blanks (shells); mass as cut")


def _aperture_table(results, stair: bool) -> Table:
    rows = []
    for (case, feed), (ff, shift, rms_at) in results.items():
        rows.append((case, feed, round(ff.phase_pp_deg, 3), round(ff.phase_rms_deg, 3), round(ff.gain_loss_db, 4),
                     round(ff.efficiency, 4), round(ff.amplitude_taper_db, 2), round(ff.squint_deg, 4),
                     "" if shift is None else round(shift, 3), "" if rms_at is None else round(rms_at, 3)))
    return Table("aperture", "Aperture figures (GO, meridional fan)", (
        "lens", "feed", "phase p-p deg", "phase RMS deg", "Ruze loss dB", "efficiency", "amplitude taper dB",
        "squint deg", "focus shift mm", "RMS at focus deg"), tuple(rows),
        "phase after removing the linear tilt; p-p within 0.95 R; efficiency = spillover × ideal taper × phase"
        + ("; scanned feeds differ only through the sheet staircase" if stair else
           "; lenses of revolution about their centre: scanned = on axis"))


def _polylines(paths: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    xs, ys = [], []
    for p in paths:
        xs += [p[:, 0], [np.nan]]
        ys += [p[:, 1], [np.nan]]
    return np.concatenate(xs), np.concatenate(ys)


def _fan_plot(design, layup: RingLayupPlan | None, fan: Fan, name: str, title: str) -> Plot:
    """Rays (z, y) from the feed to the exit and on for R/3 along the beam; layer outlines: the
    sheet staircase of ``layup``, or circles."""
    R = design.radius_mm
    pick = np.unique(np.linspace(0, len(fan.ok) - 1, FAN_RAYS).round().astype(int))
    paths = []
    for i in pick:
        if not fan.ok[i]:
            continue
        p = fan.trace.points[:, i, :]
        keep = np.concatenate([[True], np.any(np.diff(p, axis=0) != 0, axis=1)])
        p = p[keep]
        paths.append(np.vstack([p, p[-1] + R / 3 * fan.trace.direction[i]]))
    rz, ry = _polylines(paths)
    if layup is not None:                                        # each shell boundary as its staircase
        outlines = []
        for L in design.layers:
            steps = [(z, r) for sh in layup.sheets
                     for r in [math.sqrt(max(L.r_outer_mm**2 - (0.5 * (sh.z_min_mm + sh.z_max_mm)) ** 2, 0.0))]
                     for z in (sh.z_min_mm, sh.z_max_mm)]
            outlines += [np.array(steps), np.array(steps) * [1.0, -1.0]]
    else:
        a = np.linspace(0, 2 * np.pi, 721)
        outlines = [np.column_stack([L.r_outer_mm * np.cos(a), L.r_outer_mm * np.sin(a)]) for L in design.layers]
    oz, oy = _polylines(outlines)
    return Plot(name, title, "z (mm)", "y (mm)",
                (Series("layer boundaries", oz, oy, "dashed"), Series("rays", rz, ry, "line"),
                 Series("feed", fan.feed_zy_mm[:1], fan.feed_zy_mm[1:], "points")),
                f"{len(paths)} rays of the GO fan; outline: shells, or sheet-by-sheet ring radii", equal_aspect=True)


def _phase_plot(results, stair: bool) -> Plot:
    series = []
    for case, style in (("ideal", "line"), ("stepped", "dashed"), ("as_built", "points")):
        ff = results[(case, "axis")][0]
        series.append(Series(f"{case.replace('_', '-')}, on axis", ff.s_mm, ff.phase_deg, style))
    if stair:
        for feed in ("scan45", "scan90"):
            ff = results[("stepped", feed)][0]
            series.append(Series(f"stepped, {feed}", ff.s_mm, ff.phase_deg, "points"))
    return Plot("aperture-phase", "Aperture phase (linear tilt removed)", "aperture coordinate (mm)", "phase (deg)",
                tuple(series), "GO, meridional fan; ideal = continuous law (RK4)")


def _eps_plot(design: LuneburgDesign) -> Plot:
    r = np.linspace(0.0, design.radius_mm, 401)
    law = traced_law(design.law, design.focal_distance_ratio, design.outer_shell, design.radius_mm)
    edges = np.array([0.0] + [L.r_outer_mm for L in design.layers])

    def steps(values):
        return np.repeat(edges, 2)[1:-1], np.repeat(values, 2)

    xd, yd = steps([L.eps_r_design for L in design.layers])
    xg, yg = steps([L.eps_r for L in design.layers])
    return Plot("eps-profile", "Permittivity vs radius", "r (mm)", "εr",
                (Series("continuous law", r, law.eps(r), "line"), Series("layers (ideal εr)", xd, yd, "steps"),
                 Series("chosen grades", xg, yg, "steps")), "seed-002 §2.1 law, §2.2 layers, grades as chosen")
