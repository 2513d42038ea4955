"""As-built trace of a waveguide-slot array (seed-003): feed → beam former → guides → slots.

Pure numpy. The beam former is traced through whatever surfaces it carries (the synthesised
curves, or the C¹ splines as modelled: :func:`antenna_cad.synthesis.slot_array.with_surfaces`);
the slots are the cell reference points as written to the slot table. Frame and units as in
:mod:`antenna_cad.synthesis.slot_array` (x across, y along the guides, mm, GHz, rad).

Phase of the −1st spatial harmonic radiated by cell m of guide g (seed-003 §3.1, §3.9 (3.41)):

    Φ_gm = k [L_g + n_g (y_gm − y_Q,g)] − 2π m,    n_g = γ(f; a_g, ε_g)/k,

L_g the traced path from the feed to the guide entry Q_g on the last mirror, y_gm the first-slot
centre of the cell. The progression along the guides gives u_y = sin θ (θ from broadside toward
+y; cos β of (3.1) for nominal guides), the tilt across them u_x (sine of the azimuth); the
residual of Φ − k u_y y detrended across the guides (:func:`antenna_cad.verification.detrended`)
is the phase error at the slots (:func:`fit_beam`).
Gain loss from it is the Ruze-type exp(−σ²) (σ the RMS residual in radians, unweighted by the
aperture taper, so slightly pessimistic).
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass

import numpy as np

from antenna_cad.synthesis.slot_array import (BeamFormer, guide_gamma_per_mm, traced_eikonal_mm,
                                              wavenumber_per_mm, with_surfaces)
from antenna_cad.verification import detrended

DB_PER_NP2 = 10.0 * np.log10(np.e)      # Ruze: loss_dB = 10 log10(e) σ², σ in radians


@dataclass(frozen=True)
class Cells:
    """Radiating cells as written: guide axes ``guide_x_mm`` (G,), first-slot centre of every
    cell ``y_mm`` (G, M), and per guide the width ``width_mm`` and fill ``eps_r`` (G,)."""
    guide_x_mm: np.ndarray
    y_mm: np.ndarray
    width_mm: np.ndarray
    eps_r: np.ndarray

    def perturbed(self, d_width_mm=0.0, d_eps_r=0.0) -> "Cells":
        """Guides with widths/permittivities shifted by scalars or per-guide arrays."""
        return Cells(self.guide_x_mm, self.y_mm, self.width_mm + d_width_mm, self.eps_r + d_eps_r)

    @property
    def period_mm(self) -> float:
        """Mean cell period of the written table (least-squares slope of y over the cell index)."""
        m = np.arange(self.y_mm.shape[1])
        return float(np.mean(np.polyfit(m, self.y_mm.T, 1)[0]))


def cells_from_slot_table(csv_text: str, width_mm: float, eps_r: float) -> Cells:
    """Read slots.csv back (columns guide, cell, slot, x_mm, y_mm, offset_mm): slot 0 of every
    cell is its reference point; the guide axis is x − offset."""
    rows = [r for r in csv.DictReader(io.StringIO(csv_text)) if int(r["slot"]) == 0]
    g = np.array([int(r["guide"]) for r in rows])
    c = np.array([int(r["cell"]) for r in rows])
    G, M = g.max() + 1, c.max() + 1
    y = np.full((G, M), np.nan)
    y[g, c] = [float(r["y_mm"]) for r in rows]
    axis = np.zeros(G)
    axis[g] = [float(r["x_mm"]) - float(r["offset_mm"]) for r in rows]
    if np.isnan(y).any():
        raise ValueError("slot table: a cell has no slot 0")
    return Cells(axis, y, np.full(G, float(width_mm)), np.full(G, float(eps_r)))


@dataclass(frozen=True)
class BeamFit:
    """Beam of one feed at each frequency: elevation θ and azimuth (rad, NaN where the −1st
    harmonic does not radiate), detrended phase residual at the cells (deg, (F, G, M)), its RMS
    and peak-to-peak (deg), and the Ruze gain loss (dB)."""
    f_ghz: np.ndarray
    elevation_rad: np.ndarray
    azimuth_rad: np.ndarray
    residual_deg: np.ndarray
    rms_deg: np.ndarray
    pp_deg: np.ndarray

    @property
    def ruze_loss_db(self) -> np.ndarray:
        return DB_PER_NP2 * np.radians(self.rms_deg) ** 2


def cell_phase_rad(path_mm: np.ndarray, entry_y_mm: np.ndarray, cells: Cells, f_ghz) -> np.ndarray:
    """Φ (F, G, M) of the module docstring for traced paths ``path_mm`` (G,) to the entries."""
    f = np.atleast_1d(np.asarray(f_ghz, float))
    k = wavenumber_per_mm(f)[:, None, None]
    n = guide_gamma_per_mm(f[:, None], cells.width_mm[None, :], cells.eps_r[None, :])[:, :, None] / k
    m = np.arange(cells.y_mm.shape[1])[None, None, :]
    return k * (path_mm[None, :, None] + n * (cells.y_mm[None] - entry_y_mm[None, :, None])) - 2 * np.pi * m


def fit_beam(phase_rad: np.ndarray, cells: Cells, f_ghz) -> BeamFit:
    """Beam direction and phase error from Φ (F, G, M).

    Along the guides every cell row radiates the −1st harmonic, so the elevation direction cosine
    u_y is the mean over the guides of the least-squares slope dΦ/(k dy) (it is cos β of (3.1)
    for nominal guides). Across the guides, Φ − k u_y y is fitted with a + k u_x x (azimuth) and
    its residual (:func:`antenna_cad.verification.detrended`) is the phase error at the cells.
    """
    f = np.atleast_1d(np.asarray(f_ghz, float))
    k = wavenumber_per_mm(f)
    y = cells.y_mm
    dy = y - y.mean(axis=1, keepdims=True)
    uy = np.mean(np.sum(dy * phase_rad, axis=2) / np.sum(dy * dy, axis=1), axis=1) / k
    x = np.broadcast_to(cells.guide_x_mm[:, None], y.shape).reshape(-1)
    ref = (phase_rad - (k * uy)[:, None, None] * y).reshape(len(f), -1)
    ux = np.polyfit(x, ref.T, 1)[0] / k
    res = np.stack([detrended(x, np.degrees(r)) for r in ref])
    radiates = ux**2 + uy**2 < 1.0
    return BeamFit(f, np.where(radiates, np.arcsin(np.clip(uy, -1, 1)), np.nan),
                   np.where(radiates, np.arcsin(np.clip(ux, -1, 1)), np.nan), res.reshape(phase_rad.shape),
                   np.sqrt(np.mean(res**2, axis=1)), np.ptp(res, axis=1))


def trace_beam(bf: BeamFormer, source_mm, cells: Cells, f_ghz) -> BeamFit:
    """Trace ``source_mm`` through ``bf`` to every guide entry and fit the beam at ``f_ghz``."""
    path = traced_eikonal_mm(bf, np.asarray(source_mm, float), cells.guide_x_mm)
    entry = bf.guide_curve.y_at(cells.guide_x_mm)
    return fit_beam(cell_phase_rad(path, entry, cells, f_ghz), cells, f_ghz)


def beamwidths_rad(cells: Cells, f_ghz: float, elevation_rad: float, azimuth_rad: float) -> tuple[float, float]:
    """Half-power widths (elevation, azimuth) of a uniformly lit rectangle, 0.886 λ/(D cos):
    the yardstick of the pointing loss in :func:`pointing_loss_db`."""
    lam = 2 * np.pi / float(wavenumber_per_mm(f_ghz))
    G, M = cells.y_mm.shape
    pitch = float(np.mean(np.diff(cells.guide_x_mm))) if G > 1 else float(cells.width_mm[0])
    return (0.886 * lam / (M * cells.period_mm * np.cos(elevation_rad)),
            0.886 * lam / (G * pitch * np.cos(azimuth_rad)))


def pointing_loss_db(d_elevation_rad, d_azimuth_rad, widths_rad: tuple[float, float]):
    """Gain lost toward the nominal direction when the beam moves: 12 (Δ/θ3)² dB per plane
    (Gaussian main lobe: −3 dB at Δ = θ3/2)."""
    return 12.0 * ((np.asarray(d_elevation_rad) / widths_rad[0]) ** 2
                   + (np.asarray(d_azimuth_rad) / widths_rad[1]) ** 2)


@dataclass(frozen=True)
class ToleranceEffect:
    """Worst effect of one build tolerance over the feeds and both signs, at one frequency:
    beam shifts (rad), RMS phase error at the slots (deg) and gain lost toward the nominal beam
    (Ruze increase + pointing, dB)."""
    name: str
    value: float
    unit: str
    d_elevation_rad: float
    d_azimuth_rad: float
    rms_deg: float
    loss_db: float


def tolerance_effects(bf: BeamFormer, cells: Cells, sources_mm: np.ndarray, aims: np.ndarray, f_ghz: float, *,
                      eps_r_tol: float, width_tol_mm: float, feed_tol_mm: float,
                      scale: float = 1.0) -> tuple[ToleranceEffect, ...]:
    """Sensitivity of the as-built beam to the spec tolerances, each alone.

    Fill εr and guide width act through n = γ/k of every guide (width → λg): common to all guides
    (moves the frequency-scanned beam; a mirror–lens lens of the same dielectric gets n² + Δε)
    and alternating guide to guide (the worst-case spread: a phase error growing along the
    guides). The feed moves ± along and across its axis. ``scale`` multiplies every tolerance.
    The rays of a feed through a beam former are traced once: εr and width change only the guides
    (the same guide axes), so those cases refit the same paths.
    """
    alt = np.where(np.arange(cells.guide_x_mm.size) % 2, -1.0, 1.0)
    sides = np.stack([-aims[:, 1], aims[:, 0]], -1)
    traced: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}

    def beam(bfv: BeamFormer, source, cv: Cells, f) -> BeamFit:
        """:func:`trace_beam` with the paths kept by (beam former, source); ``cases`` below keeps
        every beam former alive, so its id is its own."""
        key = (id(bfv), *np.asarray(source, float).tolist())
        if key not in traced:
            traced[key] = (traced_eikonal_mm(bfv, np.asarray(source, float), cv.guide_x_mm),
                           bfv.guide_curve.y_at(cv.guide_x_mm))
        path, entry = traced[key]
        return fit_beam(cell_phase_rad(path, entry, cv, f), cv, f)

    nominal = [beam(bf, s, cells, f_ghz) for s in sources_mm]
    widths = beamwidths_rad(cells, f_ghz, float(nominal[0].elevation_rad[0]), float(nominal[0].azimuth_rad[0]))

    def lens_bf(d_eps):
        if not bf.lenses:
            return bf
        return with_surfaces(bf, bf.mirrors, bf.lenses, np.sqrt(bf.params["n"] ** 2 + d_eps))

    e, w, d = eps_r_tol * scale, width_tol_mm * scale, feed_tol_mm * scale
    cases = [("fill εr, all guides", eps_r_tol, "", [(lens_bf(sg * e), cells.perturbed(d_eps_r=sg * e), 0.0)
                                                    for sg in (1.0, -1.0)]),
             ("fill εr, guide to guide (alternating)", eps_r_tol, "", [(bf, cells.perturbed(d_eps_r=e * alt), 0.0)]),
             ("guide width, all guides", width_tol_mm, "mm", [(bf, cells.perturbed(d_width_mm=sg * w), 0.0)
                                                               for sg in (1.0, -1.0)]),
             ("guide width, guide to guide (alternating)", width_tol_mm, "mm",
              [(bf, cells.perturbed(d_width_mm=w * alt), 0.0)]),
             ("feed position, along the axis", feed_tol_mm, "mm", [(bf, cells, sg * d * aims) for sg in (1.0, -1.0)]),
             ("feed position, across the axis", feed_tol_mm, "mm", [(bf, cells, sg * d * sides) for sg in (1.0, -1.0)])]
    out = []
    for name, value, unit, variants in cases:
        worst = None
        for bfv, cv, shift in variants:
            for k, (src, nom) in enumerate(zip(sources_mm, nominal)):
                fit = beam(bfv, src + (shift[k] if np.ndim(shift) else 0.0), cv, f_ghz)
                de = float(fit.elevation_rad[0] - nom.elevation_rad[0])
                da = float(fit.azimuth_rad[0] - nom.azimuth_rad[0])
                loss = float(fit.ruze_loss_db[0] - nom.ruze_loss_db[0] + pointing_loss_db(de, da, widths))
                if worst is None or loss > worst.loss_db:
                    worst = ToleranceEffect(name, value * scale, unit, de, da, float(fit.rms_deg[0]), loss)
        out.append(worst)
    return tuple(out)
