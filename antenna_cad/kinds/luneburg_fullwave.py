"""Full-wave stage of the Luneburg verification (seed-002 §2.4).

The sphere with its feed on the axis, in Meep's body-of-revolution solver (:mod:`antenna_cad.fullwave`),
in three variants named as the collimator's so that the manifest keys read the same for every kind:

* ``ideal`` — the continuous law of seed-002 §2.1 as a per-pixel ε(r) (the runner's ``graded`` table);
* ``stepped`` — the lens the GO check calls stepped: the shells with their design εr, or for a sphere
  sheet layup the staircase its sheets make (rings at the sheet mid-planes);
* ``fabricated`` — the GO check's as-built lens: shells (or a layup turned to the spheres) with the
  grades chosen, or the mid-plane staircase of the grades. A ring layup is a body of revolution
  about the feed axis (sheets normal to it, rings concentric with it), so it needs no approximation;
  the feed boss and the stand lie below the lens, off the axis, and are left out (the only parts that
  are not of revolution).

Feed: a point source at the focus z = −b (:mod:`antenna_cad.fullwave.sphere`): an electric dipole for
``verification.feed_pattern: dipole``, the Huygens element of seed-002 §2.4.5 ((1 + cos θ)/2) for
``cos_q`` (a point source cannot carry an arbitrary cos^q; the GO check keeps the design's q).
Figures on the plane ``plane_offset_lambda`` behind the sphere over 0.5 λ ≤ r ≤ 0.9 R
(:mod:`antenna_cad.fullwave.aperture`). Reference: the exact multilayer-sphere series (Mie,
``scattnlay``) for plane-wave focusing; the gain of the lens fed by a short dipole at the focus by
reciprocity, 1.5·|E(focus)/E0|², from Mie for every spherical variant (the law as thin shells), and
from Meep for the design shells lit by a plane wave — their difference is the stage's own error bar.
Beside it, the gains of the lens fed by the Huygens element and by the dipole from the feed series
(2) and the power they radiate (:mod:`antenna_cad.fullwave.feed_series`).
The cylindrical (parallel-plate) lens is not a body of revolution about its feed axis: no run.
"""

from __future__ import annotations

import os

import numpy as np

from antenna_cad.fullwave.aperture import aperture_stats, difference_stats, phase_deg
from antenna_cad.fullwave.feed_series import feed_gains_dbi
from antenna_cad.fullwave.mie import shell_parts
from antenna_cad.fullwave.sphere import (MIE_MAX_D_LAMBDA, aperture_gain_dbi, feed_deck, fine_shells, focal_gain_dbi,
                                         law_table, mie_focal_field, mie_focal_gain_dbi, plane_wave_decks)
from antenna_cad.fullwave.verify import budget_decision, deck_files, run_named
from antenna_cad.raytrace.media import Shells, Staircase
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.luneburg import LuneburgDesign, traced_law
from antenna_cad.verification import Plot, Series, Verification

VARIANTS = ("ideal", "stepped", "fabricated")
POINT_FEED = {"dipole": "dipole", "cos_q": "huygens"}
MIE_AGREEMENT_DB = 1.0      # Meep's focal gain of the shells within this of Mie, else a warning
SPOT_LAMBDA = 1.5           # focal-spot plot out to this radius


def medium_parts(medium, label: str) -> list[dict]:
    """A traced medium as the runner's (r, z) parts: shells as half discs/annuli (a feed boss
    dropped: it is not of revolution about the axis), a staircase as one quadrilateral per ring
    (a rectangle, or a trapezoid for a taper-cut ring's cones)."""
    if isinstance(medium, Shells):
        return shell_parts(medium.radii, np.square(medium.n))
    assert isinstance(medium, Staircase), medium
    slopes = np.zeros_like(medium.breaks) if medium.slopes is None else medium.slopes
    parts = []
    for k in range(len(medium.z_edges) - 1):
        z0, z1 = (float(z) for z in medium.z_edges[k:k + 2])
        inner = (0.0, 0.0)
        for b, s, n in zip(medium.breaks[k], slopes[k], medium.n[k]):
            if not np.isfinite(b):
                break
            outer = (float(b), float(b + s * (z1 - z0)))
            if n > 1.0 and max(outer[0] - inner[0], outer[1] - inner[1]) > 0:
                corners = [(inner[0], z0), (outer[0], z0), (outer[1], z1), (inner[1], z1)]
                parts.append({"label": f"{label}-sheet-{k + 1:02d}", "eps_r": float(n * n),
                              "polygon": [[round(r, 4), round(z, 4)] for r, z in corners]})
            inner = outer
    return parts


def luneburg_full_wave(spec, design: LuneburgDesign, media: dict, go: dict) -> Verification:
    """The stage. ``media``: the GO check's stepped and fabricated media (``Shells``/``Staircase``);
    ``go``: variant → (aperture coordinate, phase deg) of the GO fans on axis, drawn under Meep's."""
    settings = spec.verification
    R, lam, b = design.radius_mm, design.wavelength_mm, design.focal_distance_mm
    if design.shape != "sphere":
        return Verification(checks=(Check("full_wave", "skip", 0.0, settings.budget_s, "s",
                                          "full-wave stage not run: the cylindrical (parallel-plate) lens is not a "
                                          "body of revolution about its feed axis (a 2-D run would be needed)"),))
    law = traced_law(design.law, design.focal_distance_ratio, design.outer_shell, R)
    radii = np.array([L.r_outer_mm for L in design.layers])
    shells = (radii, np.array([L.eps_r_design for L in design.layers]))
    mie = {"ideal": fine_shells(law.eps, R, lam), "shells": shells}
    if isinstance(media["fabricated"], Shells):
        mie["fabricated"] = (media["fabricated"].radii, np.square(media["fabricated"].n))
    if 2 * R / lam > MIE_MAX_D_LAMBDA:
        mie = {}
    figures = {f"mie_{v}_focal_gain_dbi": mie_focal_gain_dbi(*m, lam, b) for v, m in mie.items()}
    for v, m in mie.items():                      # the feeds' own gains by the series (2) (seed-002 §2.4.5)
        figures |= {f"mie_{v}_{feed}_feed_gain_dbi": g for feed, g in feed_gains_dbi(*m, lam, b).items()}
    figures["aperture_gain_limit_dbi"] = aperture_gain_dbi(R, lam)

    pattern = POINT_FEED[settings.feed_pattern]
    geometry = {"ideal": ([], [law_table(law.eps, R)])} | {
        v: (medium_parts(media[v], v), []) for v in VARIANTS[1:]}
    common = dict(frequency_ghz=design.frequency_ghz, resolution=settings.resolution_px_per_lambda)
    decks = [feed_deck(R, parts=p, graded=g, feed_z_mm=-b, pattern=pattern, field_map=v != "ideal",
                       plane_offset_lambda=settings.plane_offset_lambda, **common)    # the map shows the stepped lens
             for v, (p, g) in geometry.items()]
    decks += plane_wave_decks(shell_parts(*shells), R, b, **common)
    names = [*VARIANTS, "plane_wave_shells", "plane_wave_empty"]
    jobs = max(1, min(len(decks), os.cpu_count() or 1))
    decision = budget_decision(settings, decks, jobs)
    files = deck_files(names, decks)
    model = (f"full-wave (Meep, body of revolution, point {pattern} feed at the focus, "
             f"{settings.resolution_px_per_lambda:g} px/λ)")
    if decision.python is None:
        return Verification(figures, (_note(f"{decision.why}; D/λ = {2 * R / lam:.3g}", decision.estimate_s, settings,
                                            figures, decision.status),), files=files)
    ran = run_named(names, decks, decision, jobs)
    out = {v: o for v, o in ran.results.items() if o is not None}
    for v in (v for v in VARIANTS if v in out):
        figures |= {f"fullwave_{v}_on_axis_{k}": x
                    for k, x in vars(aperture_stats(out[v]["r_mm"], out[v]["er"], lam, R)).items()}
    for v in (v for v in VARIANTS[1:] if v in out and "ideal" in out):
        p2p, rms = difference_stats(out["ideal"]["r_mm"], out[v]["er"], out["ideal"]["er"], lam, R)
        figures |= {f"fullwave_{v}_minus_ideal_p2p_deg": p2p, f"fullwave_{v}_minus_ideal_rms_deg": rms}
    plane_wave = "plane_wave_empty" in out and "plane_wave_shells" in out
    if plane_wave:
        incident = out["plane_wave_empty"]["er"][0]
        figures["fullwave_plane_wave_shells_focal_gain_dbi"] = focal_gain_dbi(out["plane_wave_shells"]["er"][0]
                                                                              / incident)
    figures |= {"fullwave_resolution_px_per_lambda": settings.resolution_px_per_lambda} | ran.figures()
    checks = [_note(f"{decision.why}; {ran.text()}; {model}", decision.estimate_s, settings, figures, ran.status)]
    if mie and plane_wave:
        figures["fullwave_shells_focal_gain_minus_mie_db"] = (figures["fullwave_plane_wave_shells_focal_gain_dbi"]
                                                             - figures["mie_shells_focal_gain_dbi"])
        checks.append(_against_mie(figures))
    plots = _plots(design, out, go, mie, settings) if not ran.cut else ()
    return Verification(figures, tuple(checks), plots=plots, files=files)


def _against_mie(figures: dict) -> Check:
    """Meep's plane-wave focal gain of the design shells against the exact series."""
    error = figures["fullwave_shells_focal_gain_minus_mie_db"]
    bad = abs(error) > MIE_AGREEMENT_DB
    return Check("fullwave_vs_mie", "warn" if bad else "pass", abs(error), MIE_AGREEMENT_DB, "dB",
                 f"focal gain of the design shells in a plane wave: Meep "
                 f"{figures['fullwave_plane_wave_shells_focal_gain_dbi']:.2f} dBi vs the exact multilayer Mie series "
                 f"{figures['mie_shells_focal_gain_dbi']:.2f} dBi (seed-002 §2.4)"
                 + ("; raise verification.resolution_px_per_lambda" if bad else ""))


def _note(why: str, estimate: float, settings, figures: dict, status: str) -> Check:
    def listed(suffix):
        return ", ".join(f"{k.removeprefix('mie_').removesuffix(suffix)} {v:.2f}" for k, v in figures.items()
                         if k.startswith("mie_") and k.endswith(suffix))
    gains, huygens = listed("_focal_gain_dbi"), listed("_huygens_feed_gain_dbi")
    mie = (f"Exact Mie series, gain of a dipole-fed lens by reciprocity (dBi): {gains}; of the lens fed by the "
           f"Huygens element of seed-002 (2): {huygens}; uniform aperture "
           f"{figures['aperture_gain_limit_dbi']:.2f}" if gains else
           f"Mie series not evaluated above D/λ = {MIE_MAX_D_LAMBDA:g}")
    return Check("full_wave", status, estimate, settings.budget_s, "s", f"full-wave stage {why}. {mie}")


def _plots(design: LuneburgDesign, out: dict, go: dict, mie: dict, settings) -> tuple[Plot, ...]:
    R, lam, b = design.radius_mm, design.wavelength_mm, design.focal_distance_mm
    r = out["ideal"]["r_mm"]
    sel = r <= R
    phase = [Series(f"full-wave {v}", r[sel], phase_deg(r, out[v]["er"], lam, R)[sel]) for v in VARIANTS]
    for v, (s, ph) in go.items():
        keep = s >= 0
        phase.append(Series(f"GO {v}", s[keep], ph[keep] - np.average(ph[keep]), "dashed"))
    amplitude = []
    for v in VARIANTS:
        amp = np.abs(out[v]["er"][sel])
        ref = np.mean(amp[(r[sel] >= 0.5 * lam) & (r[sel] <= 1.5 * lam)])
        amplitude.append(Series(f"full-wave {v}", r[sel], 20 * np.log10(np.maximum(amp / ref, 1e-6))))
    caption = (f"point feed on the axis at the focus; plane {settings.plane_offset_lambda:g} λ behind the sphere; "
               "statistics over 0.5 λ ≤ r ≤ 0.9 R")
    spot = r <= SPOT_LAMBDA * lam
    pw = np.abs(out["plane_wave_shells"]["er"][spot] / out["plane_wave_empty"]["er"][0])
    focal = [Series("full-wave shells (Meep)", r[spot], 20 * np.log10(np.maximum(pw, 1e-6)))]
    for v, (radii, eps) in mie.items():
        e = np.abs(mie_focal_field(radii, eps, lam, b, r[spot]))
        focal.append(Series(f"Mie {v}", r[spot], 20 * np.log10(np.maximum(e, 1e-6)), "dashed"))
    plots = [Plot("fullwave-aperture-phase", "Full-wave aperture phase over GO (feed on axis)", "r (mm)",
                  "phase, mean removed (deg)", tuple(phase), caption=caption),
             Plot("fullwave-aperture-amplitude", "Full-wave aperture amplitude (feed on axis)", "r (mm)",
                  "|E| relative to 0.5–1.5 λ (dB)", tuple(amplitude), caption=caption),
             Plot("fullwave-focal-spot", "Plane-wave focal spot: Meep vs the exact multilayer series", "r (mm)",
                  "|E_x| / |E0| at z = b (dB)", tuple(focal),
                  caption="plane wave along the axis; focal plane z = b; Mie: scattnlay (seed-002 §2.4)")]
    m = out["stepped"].get("map_abs")
    if m is not None:
        image = 20 * np.log10(np.maximum(m / m.max(), 1e-3))
        plots.append(Plot("fullwave-field-map", "|E| in the (r, z) plane, stepped lens", "z (mm)", "r (mm)", (),
                          caption="dB relative to the maximum; point feed on the left, aperture plane on the right",
                          image=(image, tuple(float(x) for x in out["stepped"]["map_extent_mm"]))))
    return tuple(plots)
