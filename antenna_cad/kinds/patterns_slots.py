"""Array factor, directivity, gain and beam direction of the waveguide-slot arrays over the band,
every feed (seed-003 §3.9, (3.8)–(3.11)).

Each radiating cell of the slot table as written is an element at its reference point (x, y):
phase Φ_gm of :mod:`antenna_cad.raytrace.slot_array` (feed → beam former → guide → cell, the −1st
spatial harmonic), E = A·e^{jΦ}; amplitude from the leaky-wave taper along each guide: the cell's
attenuation α from its slot length by the cell fit α(L1) = a0·e^{b0·L1} (seed-003 §3.2, the Ka
4-slot cell; its a0/b0 or the spec's), or for other layouts from the taper law the lengths were
designed to (1.1); the guide power decays as e^{−2∫α dy} and each cell radiates what it takes
out. Across the guides the excitation is uniform (the mirror's edge illumination η of (3.10) is
not given by the thesis). Element pattern √cos θ (3.9). Directivity by the aperture formula with
each cell's area pitch × period, times the element's cos θ toward the beam (the projected
aperture: scan loss); gain = directivity × the radiated fraction (the rest is
absorbed by the load). The frequency-scan sector is the elevation range over the band where the
aperture efficiency (gain / (4πS/λ²)) stays ≥ 0.5, the thesis's definition; its full-wave sectors
(two-mirror > 60°, single-mirror ≈ 30°, seed-003 §4) are documentation only (R11).
"""

from __future__ import annotations

import csv
import io

import numpy as np

from antenna_cad.radiation.aperture import points_aperture, pattern_figures
from antenna_cad.raytrace.slot_array import cell_phase_rad, fit_beam
from antenna_cad.synthesis.slot_array import taper_alpha_np_per_m, traced_eikonal_mm, wavenumber_per_mm
from antenna_cad.verification import Plot, Series, Table, Verification, finite_figures

KA_CELL_FIT = (0.0078, 2.01)       # α(L1) = a0·exp(b0·L1), Np/m and 1/mm (seed-003 §3.2)
KIP_SECTOR = 0.5                   # the thesis's frequency-scan sector: where КИП ≥ 0.5 (seed-003 §4)


def cell_amplitudes(spec, cells, slots_csv: str) -> tuple[np.ndarray, float]:
    """(G, M) cell amplitudes and the radiated power fraction per guide (mean), module docstring."""
    G, M = cells.y_mm.shape
    p = cells.period_mm
    taper = spec.slots.taper
    if spec.slots.layout == "longitudinal_4":
        L1 = np.zeros((G, M))
        for r in csv.DictReader(io.StringIO(slots_csv)):
            if int(r["slot"]) == 0:
                L1[int(r["guide"]), int(r["cell"])] = float(r["length_mm"])
        a0 = taper.a0 if taper.a0 is not None else KA_CELL_FIT[0]
        b0 = taper.b0 if taper.b0 is not None else KA_CELL_FIT[1]
        alpha = a0 * np.exp(b0 * L1)
    else:
        y = (np.arange(M) + 0.5) * p
        alpha = np.broadcast_to(taper_alpha_np_per_m(y, spec.array.length_mm, taper.law, taper.eta, taper.pedestal),
                                (G, M))
    loss = 2 * alpha * p / 1000.0                                  # power nepers per cell
    before = np.exp(-np.concatenate([np.zeros((G, 1)), np.cumsum(loss, axis=1)[:, :-1]], axis=1))
    radiated = before * (1 - np.exp(-loss))
    return np.sqrt(radiated), float(np.mean(radiated.sum(axis=1)))


def _pitch(cells) -> float:
    x = cells.guide_x_mm
    return float(np.mean(np.diff(x))) if x.size > 1 else float(cells.width_mm[0])


def slot_patterns(spec, design, lenses, slots_csv: str, f_ghz: np.ndarray, i_design: int) -> Verification:
    """``lenses``: (name, beam former, cells) — ideal and as written/built. Figures per lens and
    feed at the design frequency, gain and beam direction against frequency, scan sector."""
    feeds = design.feeds.aperture_centres_mm
    figures, rows, gain_series, beam_series, cuts = {}, [], [], [], []
    for name, bf, cells in lenses:
        amp, eta = cell_amplitudes(spec, cells, slots_csv)
        area = _pitch(cells) * cells.period_mm
        X = np.broadcast_to(cells.guide_x_mm[:, None], cells.y_mm.shape)
        for k, src in enumerate(feeds, start=1):
            path = traced_eikonal_mm(bf, np.asarray(src, float), cells.guide_x_mm)
            phase = cell_phase_rad(path, bf.guide_curve.y_at(cells.guide_x_mm), cells, f_ghz)
            fit = fit_beam(phase, cells, f_ghz)
            kz = wavenumber_per_mm(f_ghz)
            ux, uy = np.sin(fit.azimuth_rad), np.sin(fit.elevation_rad)
            field = amp[None] * np.exp(1j * phase)
            steer = np.exp(-1j * kz[:, None, None] * (ux[:, None, None] * X + uy[:, None, None] * cells.y_mm))
            peak = np.abs(np.sum(field * steer, axis=(1, 2))) * area
            lam = 2 * np.pi / kz
            element = 10 * np.log10(np.sqrt(np.clip(1 - ux**2 - uy**2, 1e-12, 1)))     # |√cos θ|²
            d_dbi = 10 * np.log10(4 * np.pi * peak**2 / (lam**2 * np.sum(amp**2) * area)) + element
            gain = d_dbi + 10 * np.log10(eta)
            feed = f"horn{k}"
            gain_series.append(Series(f"{name}, {feed}", f_ghz, gain, "line" if name == "ideal" else "dashed"))
            beam_series.append(Series(f"{name}, {feed}", f_ghz, np.degrees(fit.elevation_rad),
                                      "line" if name == "ideal" else "points"))
            ap = points_aperture(X, cells.y_mm, field[i_design], area, float(lam[i_design]))
            pf = pattern_figures(ap, "y", float(ux[i_design]), dissipative=eta)
            key = f"pattern_{name}_{feed}"
            figures |= {f"{key}_directivity_dbi": float(d_dbi[i_design]), f"{key}_hpbw_deg": pf.beam.hpbw_deg,
                        f"{key}_sll_db": pf.beam.sll_db, f"{key}_efficiency": pf.efficiency.total,
                        f"{key}_beam_deg": pf.beam.theta_deg, f"{key}_gain_dbi": float(gain[i_design]),
                        f"{key}_band_gain_min_dbi": float(np.nanmin(gain)),
                        f"{key}_band_gain_max_dbi": float(np.nanmax(gain))}
            rows.append((name, feed, round(pf.beam.theta_deg, 3), round(float(np.degrees(fit.azimuth_rad[i_design])), 3),
                         round(float(d_dbi[i_design]), 3), round(float(gain[i_design]), 3), round(pf.beam.hpbw_deg, 3),
                         None if not np.isfinite(pf.beam.sll_db) else round(pf.beam.sll_db, 2),
                         round(pf.efficiency.taper, 4), round(pf.efficiency.phase, 4), round(eta, 4)))
            if k == (len(feeds) + 1) // 2:
                th = pf.beam.theta_deg + np.linspace(-30, 30, 601)
                cuts.append(Series(f"{name}, {feed}", th, ap.cut("y", float(ux[i_design])).db(th, pf.beam.peak),
                                   "line" if name == "ideal" else "dashed"))
                elev = np.degrees(fit.elevation_rad)
                kip = 10 ** (gain / 10) / (4 * np.pi * area * amp.size / lam**2)      # КИП over the band
                good = elev[np.isfinite(elev) & (kip >= KIP_SECTOR)]
                figures |= {f"scan_sector_min_deg_{name}": float(np.nanmin(elev)),
                            f"scan_sector_max_deg_{name}": float(np.nanmax(elev)),
                            f"frequency_scan_sector_deg_{name}": float(np.ptp(good)) if good.size else 0.0}
    f_d = float(f_ghz[i_design])
    table = Table("slot-patterns", f"Array patterns per feed at {f_d:g} GHz", (
        "lens", "feed", "elevation deg", "azimuth deg", "directivity dBi", "gain dBi", "HPBW deg (elevation)",
        "first sidelobe dB", "η taper", "η phase", "radiated fraction"), tuple(rows),
        caption="array factor of the slot table as written (cells, lengths → taper), √cos θ element; gain = "
                "directivity × radiated fraction (seed-003 §3.9); frequency-scan sector of the centre feed where the "
                "aperture efficiency stays ≥ 0.5: " + ", ".join(f"{n} {figures[f'frequency_scan_sector_deg_{n}']:.1f}°"
                                                                for n, _, _ in lenses))
    plots = (Plot("pattern-elevation", f"Elevation pattern, centre feed, {f_d:g} GHz", "θ from broadside (deg)",
                  "relative power (dB)", tuple(cuts), caption="cut along the guides through the beam's azimuth"),
             Plot("gain-vs-frequency", "Gain against frequency, every feed", "frequency GHz", "gain (dBi)",
                  tuple(gain_series), caption="aperture-formula directivity at the traced beam × radiated fraction"),
             Plot("beam-vs-frequency", "Beam elevation against frequency (frequency scan), every feed",
                  "frequency GHz", "elevation from broadside (deg)", tuple(beam_series)))
    return Verification(finite_figures(figures), (), (table,), plots)
