"""Patterns, directivity and aperture efficiency of the Luneburg lenses per lens and feed
(seed-002 §2.5–§2.6), from the GO fans :mod:`antenna_cad.kinds.luneburg_verify` already traced.

Aperture field of a fan (on the plane u·p = 2R across the beam, :mod:`antenna_cad.raytrace.luneburg`):
power density from the rays' feed-power weights binned over the aperture — per annulus of |s|
for the sphere (a body of revolution about the beam: Hankel transform), per strip of s for the
cylinder (constant over its height between the plates) — and phase k·OPL, the weighted mean
phasor of each bin. Spillover: the design's feed spillover (cos^q feed, seed-002 §2.5) times the
fraction of the feed power the fan delivers forward; dissipative: the GO axial-ray loss (§2.7).
A scanned feed of a stepped sphere is a meridional fan taken as a body of revolution about its
beam (the staircase's other sections are not traced). The multilayer-sphere (Mie) pattern is
not computed here.
"""

from __future__ import annotations

import numpy as np

from antenna_cad.radiation.aperture import ApertureField, bor_aperture, grid_aperture, pattern_figures
from antenna_cad.verification import Plot, Series, Table, Verification, finite_figures

LENS_NAMES = {"ideal": "ideal", "stepped": "stepped", "as_built": "fabricated"}
RAYS_PER_BIN = 8
SAMPLES_PER_WAVELENGTH = 20
PLOT_BEAMWIDTHS = 10


def fan_aperture(fan, design) -> ApertureField:
    """The fan's aperture field (module docstring)."""
    lam, R = design.wavelength_mm, design.radius_mm
    ok = fan.ok
    s, w = fan.s_mm[ok], fan.weight[ok]
    phasor = w * np.exp(1j * 2 * np.pi / lam * fan.opl_mm[ok])
    sphere = design.shape == "sphere"
    bins = max(8, int(ok.sum() / RAYS_PER_BIN / (2 if sphere else 1)))
    if sphere:
        edges = np.linspace(0.0, R, bins + 1)
        idx = np.clip(np.digitize(np.abs(s), edges) - 1, 0, bins - 1)
        area = np.pi * np.diff(edges**2)
    else:
        edges = np.linspace(-R, R, bins + 1)
        idx = np.clip(np.digitize(s, edges) - 1, 0, bins - 1)
        area = np.diff(edges)
    power = np.bincount(idx, w, bins)
    ph = np.bincount(idx, phasor.real, bins) + 1j * np.bincount(idx, phasor.imag, bins)
    centre = 0.5 * (edges[1:] + edges[:-1])
    amp = np.sqrt(power / area)
    phase = np.unwrap(np.angle(np.where(power > 0, ph, 1.0)))
    n = int(SAMPLES_PER_WAVELENGTH * R / lam) + 1
    if sphere:
        r = np.linspace(0.0, R, n)
        e = np.interp(r, centre, amp) * np.exp(1j * np.interp(r, centre, phase))
        return bor_aperture(r, e, lam, R)
    y = np.linspace(-R, R, 2 * n - 1)[::max(1, SAMPLES_PER_WAVELENGTH // 4)]
    e = np.interp(y, centre, amp) * np.exp(1j * np.interp(y, centre, phase))
    h = design.height_mm
    x = np.linspace(-h / 2, h / 2, 2 * int(2 * h / lam) + 3)
    return grid_aperture(x, y, np.broadcast_to(e[:, None], (len(y), len(x))), lam, 2 * R * h)


def luneburg_patterns(design, fans: dict) -> Verification:
    """Pattern figures per (lens, feed) of ``fans`` ((case, feed) → Fan), table and plots."""
    lam, R = design.wavelength_mm, design.radius_mm
    dissipative = 10 ** (-design.axial_loss_db / 10)
    figures, rows, curves = {}, [], {}
    for (case, feed), fan in fans.items():
        if case not in LENS_NAMES:
            continue
        ap = fan_aperture(fan, design)
        kept = float(fan.weight[fan.ok].sum() / fan.weight.sum())
        pf = pattern_figures(ap, spillover=design.efficiency_spillover * kept, dissipative=dissipative)
        key = f"pattern_{LENS_NAMES[case]}_{feed}"
        eff = pf.efficiency
        figures |= {f"{key}_directivity_dbi": pf.directivity_dbi, f"{key}_hpbw_deg": pf.beam.hpbw_deg,
                    f"{key}_sll_db": pf.beam.sll_db, f"{key}_efficiency": eff.total,
                    f"{key}_gain_dbi": pf.directivity_dbi + 10 * np.log10(eff.spillover * eff.dissipative)}
        rows.append((LENS_NAMES[case], feed, round(pf.directivity_dbi, 3),
                     round(float(figures[f"{key}_gain_dbi"]), 3), round(pf.beam.hpbw_deg, 4),
                     None if not np.isfinite(pf.beam.sll_db) else round(pf.beam.sll_db, 2), round(eff.taper, 4),
                     round(eff.phase, 4), round(eff.spillover, 4), round(eff.dissipative, 4), round(eff.total, 4)))
        span = np.degrees(PLOT_BEAMWIDTHS * lam / (2 * R))
        th = np.linspace(-span, span, 601)
        curves[(case, feed)] = Series(f"{LENS_NAMES[case]}, {feed}", th, ap.cut().db(th, pf.beam.peak),
                                      "line" if case == "ideal" else "dashed")
    feeds = sorted({f for _, f in curves}, key=[f for _, f in fans].index)
    plots = tuple(Plot(f"pattern-{feed}", f"Far-field pattern, feed {feed}", "θ from the beam (deg)",
                       "relative power (dB)", tuple(s for (c, f), s in curves.items() if f == feed),
                       caption="GO aperture field of the traced fan; sphere: Hankel transform about the beam; "
                               "each lens to its own peak")
                  for feed in feeds if any(c != "ideal" and f == feed for c, f in curves)
                  and (feed == feeds[0] or _differs(curves, feed, feeds[0])))
    table = Table("patterns", "Far-field patterns per lens and feed", (
        "lens", "feed", "directivity dBi", "gain dBi", "HPBW deg", "first sidelobe dB", "η taper", "η phase",
        "η spillover", "η dissipative", "aperture efficiency"), tuple(rows),
        caption="D = (4πS/λ²)·η_taper·η_phase; gain adds spillover (cos^q feed, rays lost) and the axial-ray "
                "dielectric loss (seed-002 §2.5–§2.7)")
    return Verification(finite_figures(figures), (), (table,), plots)


def _differs(curves: dict, feed: str, nominal: str) -> bool:
    """A scanned feed is plotted only when some lens's pattern differs from its nominal one."""
    return any(not np.allclose(s.y, curves[(c, nominal)].y, atol=0.01)
               for (c, f), s in curves.items() if f == feed and (c, nominal) in curves)
