"""Aperture statistics of a full-wave (or fast-model) field on the plane behind the lens.

Over 0.5 λ ≤ r ≤ 0.9 R: the exact body of revolution carries a physical caustic on its axis (ring-edge
diffraction arriving in phase: ±15°, ±2 dB within r < 0.5 λ), so the axis is left out. Phase
peak-to-peak and area-weighted RMS (weight r) about the weighted mean; taper = level at 0.9 R relative
to the mean level over 0.5–1.5 λ; phase efficiency = |∫E dA|² / (∫|E| dA)² (the loss of gain the
phase alone costs, ≤ 0 dB).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class ApertureStats:
    p2p_deg: float
    rms_deg: float
    taper_db: float
    phase_efficiency_db: float


def window(r_mm: np.ndarray, wavelength_mm: float, radius_mm: float) -> np.ndarray:
    return (r_mm >= 0.5 * wavelength_mm) & (r_mm <= 0.9 * radius_mm)


def phase_deg(r_mm: np.ndarray, field: np.ndarray, wavelength_mm: float, radius_mm: float) -> np.ndarray:
    """Unwrapped phase (deg) over the window, area-weighted mean removed (NaN outside)."""
    sel = window(r_mm, wavelength_mm, radius_mm)
    ph = np.full(r_mm.shape, np.nan)
    unwrapped = np.degrees(np.unwrap(np.angle(field[sel])))
    w = r_mm[sel]
    ph[sel] = unwrapped - np.sum(w * unwrapped) / np.sum(w)
    return ph


def phase_stats(r_mm, phase: np.ndarray, wavelength_mm: float, radius_mm: float) -> tuple[float, float]:
    """(p-p, area-weighted RMS) of a phase curve (deg) over the window."""
    sel = window(r_mm, wavelength_mm, radius_mm) & np.isfinite(phase)
    w, ph = r_mm[sel], phase[sel]
    mean = np.sum(w * ph) / np.sum(w)
    return float(np.ptp(ph)), float(np.sqrt(np.sum(w * (ph - mean) ** 2) / np.sum(w)))


def aperture_stats(r_mm: np.ndarray, field: np.ndarray, wavelength_mm: float, radius_mm: float) -> ApertureStats:
    p2p, rms = phase_stats(r_mm, phase_deg(r_mm, field, wavelength_mm, radius_mm), wavelength_mm, radius_mm)
    amp = np.abs(field)
    ref = np.mean(amp[(r_mm >= 0.5 * wavelength_mm) & (r_mm <= 1.5 * wavelength_mm)])
    taper = 20 * np.log10(np.interp(0.9 * radius_mm, r_mm, amp) / ref)
    sel = window(r_mm, wavelength_mm, radius_mm)
    w = r_mm[sel]
    eff = np.abs(np.sum(w * field[sel])) ** 2 / np.sum(w * amp[sel]) ** 2
    return ApertureStats(p2p, rms, float(taper), float(10 * np.log10(eff)))


def difference_stats(r_mm, field: np.ndarray, reference: np.ndarray, wavelength_mm: float,
                     radius_mm: float) -> tuple[float, float]:
    """(p-p, RMS) of the phase of field / reference: e.g. stepped − ideal."""
    return phase_stats(r_mm, phase_deg(r_mm, field / reference, wavelength_mm, radius_mm), wavelength_mm, radius_mm)
