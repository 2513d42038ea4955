"""Quiet-zone figures, tables, plots and the check, from the per-plane fields of each model.

Each figure is the worst over the planes (largest phase p-p, phase RMS, ripple and |taper|; smallest
diameter within the limits): ``quiet_zone_<lens>_<feed>_<figure>`` from the best model that ran (its
name in the tables and the check: full-wave, else the fast model), ``quiet_zone_fast_…`` (when
full-wave ran) and ``quiet_zone_go_…`` from the others beside it. The
cross-polarization is GO's for both: the Fresnel transmissions of the two polarizations differ, and a
linearly polarized feed on the axis of a body of revolution then gets a cross-polar field
(τ∥ − τ⊥)/2·sin 2φ against the co-polar (τ∥ + τ⊥)/2 (largest at φ = 45°); the scalar fast model
carries none. The stack's own figures ``quiet_zone_<lens>_added_<feed>_phase_*`` are each stepped
variant's field over the ideal lens's (:func:`stack_own`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.quietzone.cut import cut_plane_figures, residual_phase_deg
from antenna_cad.quietzone.stats import PlaneFigures, plane_figures
from antenna_cad.quietzone.volume import Zone
from antenna_cad.synthesis.checks import Check
from antenna_cad.verification import Plot, Series, Table, Verification, finite_figures

# The fast model's worst error against full-wave on the phase verdict figures, over the wide-zone
# lenses of tests/data/quiet_zone_table.csv (rings 2.3–4.6 λ wide, εr 1.047–1.3; two zones each): the
# as-built lens's phase p-p over the zone, and the stack's own (stepped over ideal) p-p. Both sit on the
# axis near a null of the ring edges' caustic, where the phase is most sensitive.
FAST_ERROR_DEG = {"phase_p2p_deg": 11.0, "own_phase_p2p_deg": 17.0}
UNCERTAIN = "uncertain — run full-wave"


def undecided(value: float, limit: float, error: float) -> bool:
    """Whether a model whose error is ``error`` cannot decide ``value`` ≤ ``limit``: its error exceeds a
    quarter of the limit and the value lies within it of the limit."""
    return error > limit / 4 and abs(value - limit) <= error


FIGURES = ("phase_p2p_deg", "phase_rms_deg", "amplitude_ripple_db", "amplitude_taper_db", "diameter_mm")
WORST = {"phase_p2p_deg": max, "phase_rms_deg": max, "amplitude_ripple_db": max, "diameter_mm": min,
         "amplitude_taper_db": lambda vals: max(vals, key=abs)}


@dataclass(frozen=True)
class ModelPlanes:
    """One model's fields: variant → [(r, E) per plane of the zone]; ``cut``: (y, E) on the meridional
    cut of a beam off the axis instead (:mod:`antenna_cad.quietzone.cut`)."""
    name: str
    key: str                     # figure prefix after ``quiet_zone_``: "" (the best model) or "go_"
    fields: dict[str, list[tuple[np.ndarray, np.ndarray]]]
    cut: bool = False


@dataclass(frozen=True)
class Judged:
    disc_mm: float
    planes: list[PlaneFigures]

    def worst(self, figure: str) -> tuple[float, float]:
        """(worst value, the plane's z) of ``figure``."""
        vals = [getattr(p, figure) for p in self.planes]
        v = WORST[figure](vals)
        return float(v), self.planes[vals.index(v)].z_mm


def judged(zone: Zone, planes: list[tuple[np.ndarray, np.ndarray]], cut: bool = False) -> Judged:
    """Every plane over the zone's disc (``cut``: planes of the meridional cut, :mod:`antenna_cad.quietzone.cut`)."""
    figures = cut_plane_figures if cut else plane_figures
    return Judged(zone.diameter_mm, [figures(r, e, zone.diameter_mm, z, zone.amplitude_db, zone.phase_deg)
                                     for z, (r, e) in zip(zone.planes_mm, planes)])


def _r(v: float, nd: int = 3):
    return round(float(v), nd) + 0.0


def stack_own(zone: Zone, best: ModelPlanes, feed: str) -> tuple[dict[str, float], list[tuple]]:
    """The stack's own figures: each stepped variant's field over the ideal lens's, by the best model,
    over the zone on every plane (what sanding removes; the rim's caustic divides out)."""
    figures, rows = {}, []
    ideal = best.fields["ideal"]
    for variant, planes in best.fields.items():
        if variant == "ideal":
            continue
        j = judged(zone, [(r, e / ei) for (r, e), (_, ei) in zip(planes, ideal)], best.cut)
        for fig in ("phase_p2p_deg", "phase_rms_deg"):
            value, z = j.worst(fig)
            figures[f"quiet_zone_{variant}_added_{feed}_{fig}"] = value
            rows.append((f"{best.name}: {variant} / ideal", variant, fig, _r(value), _r(z, 1)))
    return figures, rows


def quiet_zone_study(zone: Zone, models: list[ModelPlanes], feed: str, cross_pol_db: dict[str, float],
                     judged_zone: bool, error_deg: float = 0.0, nominal: bool = True) -> Verification:
    """Figures, per-plane table, worst-plane table, plots and (``judged_zone``: the zone comes from the
    spec or the AUT) the check of the last variant by the first model, whose error on the phase p-p is
    ``error_deg`` (the check says :data:`UNCERTAIN` where that cannot decide, :func:`undecided`). When
    the first model has the ideal lens on the same radii, also the stack's own figures (:func:`stack_own`).
    A feed other than the ``nominal`` one names its tables, plots and check after itself."""
    cut = models[0].cut
    suffix = "" if nominal else "-" + feed.replace("_", "-")
    figures = {"quiet_zone_disc_mm": zone.diameter_mm, "quiet_zone_distance_mm": zone.distance_mm,
               "quiet_zone_depth_mm": zone.depth_mm, "quiet_zone_planes": float(len(zone.planes_mm))}
    rows, worst_rows, results = [], [], {}
    for m in models:
        for variant, planes in m.fields.items():
            j = judged(zone, planes, m.cut)
            results[(m.name, variant)] = j
            key = f"quiet_zone_{m.key}{variant}_{feed}"
            for fig in FIGURES:
                value, z = j.worst(fig)
                figures[f"{key}_{fig}"] = value
                worst_rows.append((m.name, variant, fig, _r(value), _r(z, 1)))
            figures[f"{key}_cross_pol_db"] = cross_pol_db[variant]
            rows += [(m.name, variant, _r(p.z_mm, 1), _r(p.disc_mm, 1), _r(p.phase_p2p_deg), _r(p.phase_rms_deg),
                      _r(p.amplitude_ripple_db), _r(p.amplitude_taper_db), _r(p.amplitude_p2p_db), _r(p.diameter_mm, 1))
                     for p in j.planes]
    best, built = models[0], list(models[0].fields)[-1]
    j = results[(best.name, built)]
    if "ideal" in best.fields and built != "ideal" and _same_radii(best):
        own, own_rows = stack_own(zone, best, feed)
        figures |= own
        worst_rows += own_rows
    caption = (f"zone Ø{j.disc_mm:.0f} mm, {zone.distance_mm:.0f}–{zone.distance_mm + zone.depth_mm:.0f} mm behind "
               f"the stack, {len(zone.planes_mm)} planes; " + (
                   "the meridional cut E(y) taken constant across x (a feed off the axis), each sample weighted by "
                   "the disc's chord through it; phase piston and tilt removed per plane (a tilt points the beam); "
                   "taper: the symmetric part of an a + b·y + c·y² fit, edge − centre" if cut else
                   "over the whole disc including the axis; phase piston removed per plane (no tilt on the axis of "
                   "a body of revolution), area-weighted RMS; taper: a + b·r² fit, edge − centre")
               + f"; ripple: ± about that fit; limits {zone.limits_text()}")
    tables = (Table("quiet-zone-planes" + suffix, f"Quiet zone per plane, feed {feed}",
                    ("model", "lens", "z mm", "disc mm", "phase p-p deg", "phase RMS deg", "ripple ±dB", "taper dB",
                     "amplitude p-p dB", "largest Ø within limits mm"), tuple(rows), caption=caption),
              Table("quiet-zone" + suffix, f"Quiet zone: worst over the planes, feed {feed}",
                    ("model", "lens", "figure", "worst", "at z mm"), tuple(worst_rows),
                    caption=caption + "; cross-pol (GO Fresnel ∥ vs ⊥, φ = 45°): "
                    + ", ".join(f"{v} {x:.1f} dB" for v, x in cross_pol_db.items())))
    own = figures.get(f"quiet_zone_{built}_added_{feed}_phase_p2p_deg")
    checks = (_check(zone, j, best.name, built, cross_pol_db[built], own, error_deg, "quiet_zone" + suffix.replace("-", "_"),
                     "" if nominal else f"feed {feed}: "),) if judged_zone else ()
    return Verification(finite_figures(figures), checks, tables, _plots(zone, best, built, j, suffix))


def _same_radii(model: ModelPlanes) -> bool:
    radii = [r for planes in model.fields.values() for r, _ in planes]
    return all(len(r) == len(radii[0]) and np.array_equal(r, radii[0]) for r in radii)


def _check(zone: Zone, j: Judged, model: str, variant: str, cross_pol: float, own_p2p: float | None,
           error_deg: float, name: str, lead: str) -> Check:
    p2p, zp = j.worst("phase_p2p_deg")
    amp = max(p.amplitude_p2p_db for p in j.planes)
    za = next(p.z_mm for p in j.planes if p.amplitude_p2p_db == amp)
    over = [p2p > 2 * zone.phase_deg, amp > 2 * zone.amplitude_db,
            zone.cross_pol_db is not None and cross_pol > zone.cross_pol_db]
    unsure = undecided(p2p, 2 * zone.phase_deg, error_deg)
    return Check(name, "warn" if any(over) or unsure else "pass", p2p, 2 * zone.phase_deg, "deg",
                 lead + (f"{UNCERTAIN} (the model's error on the phase p-p is {error_deg:.0f}°, over a quarter of the "
                  f"limit): " if unsure else "") +
                 f"quiet zone Ø{j.disc_mm:.0f} mm × {zone.depth_mm:.0f} mm ({len(zone.planes_mm)} planes), {variant} "
                 f"lens: phase {p2p:.1f}° p-p (worst at {zp:.0f} mm), amplitude {amp:.2f} dB p-p (at {za:.0f} mm), "
                 f"cross-pol {cross_pol:.1f} dB vs {zone.limits_text()} ({model})"
                 + (f"; the stack's own phase ({variant} / ideal) {own_p2p:.1f}° p-p" if own_p2p is not None else ""))


def _plots(zone: Zone, model: ModelPlanes, variant: str, j: Judged, suffix: str) -> tuple[Plot, ...]:
    planes = model.fields[variant]
    phase, amp = [], []
    for i, (z, (r, e)) in enumerate(zip(zone.planes_mm, planes)):
        inside = np.abs(r) <= j.disc_mm / 2 * (1 + 1e-12)
        if model.cut:
            x_ph, ph = residual_phase_deg(r, e, j.disc_mm)
        else:
            x_ph, ph = r[inside], np.degrees(np.unwrap(np.angle(e[inside] / e[0])))
            w = r[inside] * np.gradient(r[inside]) if inside.sum() > 1 else np.ones(1)
            ph = ph - np.sum(w * ph) / np.sum(w)
        lv = 20 * np.log10(np.maximum(np.abs(e) / np.abs(e[inside]).max(), 1e-6))
        style = "line" if i % 2 == 0 else "dashed"
        phase.append(Series(f"z {z:.0f} mm", x_ph, ph, style))
        amp.append(Series(f"z {z:.0f} mm", r, lv, style))
    caption = f"{variant} lens, {model.name}; disc Ø{j.disc_mm:.0f} mm"
    x, removed = ("y", "piston and tilt") if model.cut else ("r", "piston")
    r0 = planes[0][0]
    grid = np.array([np.interp(r0, r, np.abs(e)) for r, e in planes]).T        # [r, z]
    image = 20 * np.log10(np.maximum(grid / grid.max(), 1e-3))
    dz = zone.depth_mm / max(1, len(zone.planes_mm) - 1) / 2
    return (Plot("quiet-zone-phase" + suffix, f"Quiet zone: phase against {x} on every plane", f"{x} (mm)",
                 f"phase, {removed} removed (deg)", tuple(phase), caption=caption,
                 hlines=((f"+{zone.phase_deg:g}°", zone.phase_deg), (f"−{zone.phase_deg:g}°", -zone.phase_deg))),
            Plot("quiet-zone-amplitude" + suffix, f"Quiet zone: amplitude against {x} on every plane", f"{x} (mm)",
                 "amplitude to the disc's peak (dB)", tuple(amp), caption=caption),
            Plot("quiet-zone-map" + suffix, f"Quiet zone: |E| over ({x}, z), {variant} lens", "z behind the stack (mm)",
                 f"{x} (mm)", (), caption=caption + "; dB to the maximum",
                 image=(image, (float(r0[0]), float(r0[-1]), float(zone.planes_mm[0] - dz),
                                float(zone.planes_mm[-1] + dz)))))
