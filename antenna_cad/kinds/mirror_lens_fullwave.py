"""Full-wave check of the aplanatic mirror-lens (seed-004) with the feed on the axis.

The body of revolution in Meep (:mod:`antenna_cad.fullwave.runner`, cylindrical m = +1): the
dielectric between the front face and the mirror, the mirror a perfect conductor behind the back
face. Its coating (tens of µm) is far below a grid cell and the field behind it is zero, so the
conductor is drawn ``METAL_CELLS`` cells thick (or the coating, if thicker). The feed's analytic
field enters on a Huygens sheet 1.5 λ in front of the front vertex, radiating toward the body; the
reflected beam passes back through the sheet to the aperture plane ``plane_offset_lambda`` in front
of it, where the co-polar field is read. The sheet's own back lobe is measured by the same deck
without parts and subtracted (the fields add linearly). The feed and its support are not meshed: their blockage of the outgoing beam
is ignored, as in the GO trace. The feed-on-surface body (f0 = 0) leaves no room for the sheet: the
feed is the runner's point source on the front vertex, the focus the synthesis assumes (its rays
start in the dielectric, seed-004 §2.4), a transverse dipole or the Huygens element (Er + Hφ), which
radiates toward +z, into the body, in this frame (measured in the tests); the plane lies
``plane_offset_lambda`` in front of the feed, and the parts-free run gives the element's back lobe.
Variants: ``ideal`` (the exact marched profiles) and ``fabricated`` (the CAD's splines; a solid body
with its flange ring; a sanded layup has the exact faces, so its deck equals the ideal one and runs
once). Figures ``fullwave_<variant>_on_axis_*`` and
``fullwave_fabricated_minus_ideal_*``, compared in a table with the GO aperture phase of
:mod:`antenna_cad.raytrace.mirror_lens` over the same window (0.5 λ ≤ r ≤ 0.9 R).
"""

from __future__ import annotations

import os

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from antenna_cad.fullwave.aperture import aperture_stats, difference_stats, phase_deg, phase_stats, window
from antenna_cad.fullwave.deck import DECIMALS, PROFILE_POINTS, make_deck
from antenna_cad.fullwave.runner import feed_pattern
from antenna_cad.fullwave.verify import budget_decision, deck_files, run_named
from antenna_cad.synthesis.checks import Check
from antenna_cad.verification import Plot, Series, Table, Verification

METAL_CELLS = 2.0       # drawn conductor thickness in grid cells (the field behind the mirror is zero)
MODEL = "full-wave (Meep, body of revolution, mirror a perfect conductor)"
POINT_FEED = {"dipole": "dipole", "cos_q": "huygens"}     # the point source of a feed on the surface


def _polygon(r: np.ndarray, z: np.ndarray) -> list:
    return np.round(np.column_stack([r, z]), DECIMALS).tolist()


def _faces(design, variant: str, cad_samples: int):
    """(front z(r), mirror Z(R)) in mm on ``PROFILE_POINTS`` radii each: the marched profiles
    (``ideal``) or the splines the CAD holds (``fabricated``)."""
    p, D = design.profiles, design.diameter_mm
    out = []
    for face, (r, z) in (("front", (p.s, p.f)), ("mirror", (p.R_b, p.Z_b))):
        rr = np.linspace(0.0, r[-1] * D, PROFILE_POINTS)
        if variant == "ideal":
            out.append((rr, np.interp(rr, r * D, z * D)))
        else:
            rs, zs, dz = design.face_samples_mm(face, cad_samples)
            out.append((rr, CubicHermiteSpline(rs, zs, dz)(rr)))
    return out


def body_parts(design, variant: str, *, eps_r: float, coating_mm: float, resolution: float,
               cad_samples: int, flange=None) -> list[dict]:
    """The deck's parts of ``variant`` (mm, seed-004 frame): body, mirror (metal) and, for a solid
    body as fabricated, its flange ring ``((r_in0, r_in1), r_out, z0, z1)``."""
    (rf, zf), (rm, zm) = _faces(design, variant, cad_samples)
    body = np.concatenate([np.column_stack([rf, zf]), np.column_stack([rm[::-1], zm[::-1]])])
    t = max(coating_mm, METAL_CELLS * design.wavelength_mm / resolution)
    mirror = np.concatenate([np.column_stack([rm, zm]), np.column_stack([rm[::-1], zm[::-1] + t])])
    parts = [{"label": "body", "eps_r": float(eps_r), "polygon": _polygon(*body.T)},
             {"label": "mirror", "metal": True, "polygon": _polygon(*mirror.T)}]
    if flange is not None:
        (ri0, ri1), ro, z0, z1 = flange
        ring = np.array([(ri0, z0), (ro, z0), (ro, z1), (ri1, z1)])
        parts.append({"label": "flange", "eps_r": float(eps_r), "polygon": _polygon(*ring.T)})
    return parts


def decks(design, settings, parts: dict[str, list[dict]]) -> dict[str, dict]:
    """Every variant's deck on one domain (the widest part), plus ``free``: the same domain without
    parts, whose field on the aperture plane is the feed's (sheet's or point element's) back lobe."""
    radius = max(max(pt[0] for part in ps for pt in part["polygon"]) for ps in parts.values())
    point = POINT_FEED[settings.feed_pattern] if design.profiles.feed_on_surface else None
    out = {v: make_deck(ps, frequency_ghz=design.frequency_ghz, resolution=settings.resolution_px_per_lambda,
                        feed_z_mm=0.0, feed_pattern=settings.feed_pattern, feed_q=settings.feed_q,
                        radius_mm=radius, plane_offset_lambda=settings.plane_offset_lambda, reflected=True,
                        point_feed=point)
           for v, ps in parts.items()}
    first = next(iter(out.values()))
    out["free"] = dict(first, parts=[], field_map=False)
    return out


def full_wave_verification(design, settings, parts: dict[str, list[dict]], go) -> Verification:
    """The stage: runs (or declines, saying why) and returns figures, the comparison table, plots
    and the deck folder. ``go``: the GO on-axis aperture field (ApertureFieldMM) of the body as fabricated."""
    all_decks = decks(design, settings, parts)
    names = sorted(all_decks, key=lambda n: n != "free")     # every figure needs the back lobe: it runs first
    deck_list = [all_decks[n] for n in names]
    jobs = max(1, min(len(deck_list), os.cpu_count() or 1))
    decision = budget_decision(settings, deck_list, jobs)
    files = deck_files(names, deck_list)
    if decision.python is None:
        return Verification(checks=(_note(decision.why, decision.estimate_s, settings, decision.status),), files=files)
    ran = run_named(names, deck_list, decision, jobs)
    results = {v: o for v, o in ran.results.items() if o is not None}
    if "free" not in results or "ideal" not in results:      # every figure needs the back lobe and the ideal body
        note = _note(f"{decision.why}; {ran.text()}; no full-wave figures", decision.estimate_s, settings, ran.status)
        return Verification(ran.figures(), (note,), files=files)
    lam, R = design.wavelength_mm, design.diameter_mm / 2
    r = results["free"]["r_mm"]
    back = _co(results["free"])
    fields = {v: _co(results[v]) - back for v in parts if v in results}
    figures = {}
    for v, e in fields.items():
        figures |= {f"fullwave_{v}_on_axis_{k}": val for k, val in vars(aperture_stats(r, e, lam, R)).items()}
    if "fabricated" in fields:
        p2p, rms = difference_stats(r, fields["fabricated"], fields["ideal"], lam, R)
        figures |= {"fullwave_fabricated_minus_ideal_p2p_deg": p2p, "fullwave_fabricated_minus_ideal_rms_deg": rms}
    sel = window(r, lam, R)
    point = all_decks["free"]["feed"].get("kind") == "point"
    feed_back = np.abs(back[sel]).mean() / np.abs(fields["ideal"][sel]).mean()
    figures |= {"fullwave_resolution_px_per_lambda": settings.resolution_px_per_lambda,
                f"fullwave_{'feed' if point else 'sheet'}_back_lobe_db": float(20 * np.log10(feed_back))}
    figures |= ran.figures()
    go_r, go_phase, go_amp = _go_curves(go, settings, point)
    go_p2p, go_rms = phase_stats(go_r, _centred(go_r, go_phase, lam, R), lam, R)
    figures |= {"fullwave_go_on_axis_p2p_deg": go_p2p, "fullwave_go_on_axis_rms_deg": go_rms}
    name = f"Meep {results['free']['meep_version']}, {settings.resolution_px_per_lambda:g} px/λ"
    feed = (f"point {all_decks['free']['feed']['pattern']} feed on the front vertex" if point
            else "the feed's Huygens sheet")
    note = _note(f"{decision.why}; {ran.text()}, {name}", decision.estimate_s, settings, ran.status)
    rows = [(v, *(round(figures[f"fullwave_{v}_on_axis_{k}"], 3)
                  for k in ("p2p_deg", "rms_deg", "taper_db", "phase_efficiency_db"))) for v in fields]
    rows.append(("GO (3-D trace, as fabricated)", round(go_p2p, 3), round(go_rms, 3),
                 round(float(_taper(go_r, go_amp, lam, R)), 3), None))
    table = Table("fullwave", "Full-wave aperture field against GO (feed on the axis)",
                  ("model", "p-p deg", "RMS deg", "taper dB at 0.9 R", "phase efficiency dB"), tuple(rows),
                  caption=f"{MODEL}, {name}; plane {settings.plane_offset_lambda:g} λ in front of {feed}; "
                          "over 0.5 λ ≤ r ≤ 0.9 R (the axis of a body of revolution carries a caustic); feed "
                          "blockage ignored; GO with the same feed pattern")
    plots = _plots(r, fields, (go_r, go_phase, go_amp), results, lam, R, feed)
    return Verification(figures, (note,), (table,), plots, files)


def _co(result: dict) -> np.ndarray:
    """Co-polar field of the m = +1 run on the plane, (E_r − iE_φ)/2: the part uniform in φ (x̂ + iŷ);
    (E_r + iE_φ)/2 varies as e^{2iφ}, the cross-polar part (−16 dB here after two refractions and the
    mirror, so E_r alone would mix it in). Not used on the axis, where Meep's E_φ is wrong."""
    return (result["er"] - 1j * result["ep"]) / 2


def _note(why: str, estimate: float, settings, status: str) -> Check:
    """The stage's record: estimated time against budget_s and what ran; the verdicts stay GO's."""
    return Check("full_wave", status, estimate, settings.budget_s, "s",
                 f"full-wave stage {why}; verdicts from the 3-D GO trace, the full-wave figures beside them")


def _go_curves(go, settings, point: bool):
    """GO radius ≥ 0, phase (deg) and amplitude with the deck's feed pattern (co-polar mean of the
    E- and H-plane patterns: the m = +1 field); a point Huygens element's is (1 + cos θ)/2 in both."""
    keep = go.r_mm >= 0
    theta = go.launch_angle_rad[keep]
    if point and settings.feed_pattern == "cos_q":
        fe = fh = (1 + np.cos(theta)) / 2
    else:
        fe, fh = feed_pattern(theta, settings.feed_pattern, settings.feed_q)
    return go.r_mm[keep], go.phase_deg[keep], go.amplitude[keep] * (fe + fh) / 2


def _centred(r, ph, lam, R):
    w = window(r, lam, R)
    return ph - np.average(ph[w], weights=r[w])


def _taper(r, amp, lam, R):
    ref = np.mean(amp[(r >= 0.5 * lam) & (r <= 1.5 * lam)])
    return 20 * np.log10(np.interp(0.9 * R, r, amp) / ref)


def _plots(r, fields: dict, go, results: dict, lam: float, R: float, feed: str) -> tuple[Plot, ...]:
    sel = r <= R
    ref = (r >= 0.5 * lam) & (r <= 1.5 * lam)
    phase = [Series(f"full-wave {v}", r[sel], phase_deg(r, e, lam, R)[sel]) for v, e in fields.items()]
    amp = [Series(f"full-wave {v}", r[sel], 20 * np.log10(np.maximum(np.abs(e[sel]) / np.abs(e[ref]).mean(), 1e-6)))
           for v, e in fields.items()]
    go_r, go_phase, go_amp = go
    gsel = go_r >= 0.5 * lam
    phase.append(Series("GO (3-D trace)", go_r[gsel], _centred(go_r, go_phase, lam, R)[gsel], "dashed"))
    go_ref = np.mean(go_amp[(go_r >= 0.5 * lam) & (go_r <= 1.5 * lam)])
    amp.append(Series("GO (3-D trace)", go_r[gsel], 20 * np.log10(go_amp[gsel] / go_ref), "dashed"))
    caption = "feed on the axis; statistics over 0.5 λ ≤ r ≤ 0.9 R; mean removed; feed blockage ignored"
    plots = [Plot("fullwave-aperture-phase", "Full-wave aperture phase over GO", "r (mm)",
                  "phase, mean removed (deg)", tuple(phase), caption=caption),
             Plot("fullwave-aperture-amplitude", "Full-wave aperture amplitude over GO", "r (mm)",
                  "|E| relative to 0.5–1.5 λ (dB)", tuple(amp), caption=caption)]
    if "map_abs" in results["ideal"]:
        m = results["ideal"]["map_abs"]
        plots.append(Plot("fullwave-field-map", "|E| in the (r, z) plane, ideal body", "z (mm)", "r (mm)", (),
                          caption=f"dB relative to the maximum; {feed} launches the wave toward +z, the "
                                  "mirror sends the beam back toward −z, past the feed",
                          image=(20 * np.log10(np.maximum(m / m.max(), 1e-3)),
                                 tuple(float(x) for x in results["ideal"]["map_extent_mm"]))))
    return tuple(plots)
