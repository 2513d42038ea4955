"""Propagation of an aperture field to the antenna-under-test plane, and the test zone
(seed-000 §4.6, §5.10).

Method: the **angular spectrum of plane waves** (exact scalar propagation between parallel planes,
Rayleigh–Sommerfeld; no Fresnel approximation, which fails at the seed's 10 cm spacing from a
metre-wide aperture). Evanescent components are kept up to where they have decayed by e^{-14}.

    body of revolution:  Ẽ(κ) = ∫ E(r) J0(κr) r dr,   E(ρ, z) = ∫ Ẽ(κ) e^{j k_z z} J0(κρ) κ dκ
    line (2-D problem):  Ẽ(κ) = ∫ E(y) e^{-jκy} dy,    E(y, z) = (1/2π) ∫ Ẽ(κ) e^{j k_z z} e^{jκy} dκ

with k_z = √(k² − κ²) (= j√(κ² − k²) for evanescent waves). The Hankel form is a direct quadrature (small matrices); the line form an FFT.

Test zone: the largest centred diameter over which the amplitude stays within ±``amplitude_db``
and the phase within ±``phase_deg`` of their mid-range values (peak-to-peak 2× each); the defaults
±1 dB and ±11.25° (22.5° p-p, the seed's plane-front limit π/8).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from antenna_cad.radiation.aperture import matvec, trapezoid_weights

EVANESCENT_NEPERS = 14.0
NEAREST_WAVELENGTHS = 0.25  # nearer planes (down to 0) keep the spectrum of this distance: up to ≈ 9 k,
                            # finer than the λ/20 sampling of the fields, and a bounded cost
KAPPA_SAMPLES = 48      # κ step π/(48·extent): the on-axis field of a hard-edged disc (its edge wave
                        # focuses there, the hardest case) to ≈ 1 % against the exact form at λ/40 sampling


def _spectrum_axis(wavelength_mm: float, distance_mm: float, extent_mm: float, symmetric: bool) -> np.ndarray:
    k = 2 * math.pi / wavelength_mm
    kmax = math.sqrt(k**2 + (EVANESCENT_NEPERS / max(distance_mm, NEAREST_WAVELENGTHS * wavelength_mm)) ** 2)
    dk = math.pi / (KAPPA_SAMPLES * extent_mm)
    n = int(kmax / dk) + 2
    kappa = np.linspace(0.0, kmax, n)
    return np.concatenate([-kappa[:0:-1], kappa]) if symmetric else kappa


def _kz(kappa: np.ndarray, wavelength_mm: float) -> np.ndarray:
    k = 2 * math.pi / wavelength_mm
    return np.sqrt((k**2 - kappa**2).astype(complex))


def propagate_bor(r_mm, field, wavelength_mm: float, distance_mm: float, rho_mm) -> np.ndarray:
    """E(ρ, z = distance) of the axisymmetric aperture field E(r) (module docstring)."""
    return propagate_bor_planes(r_mm, field, wavelength_mm, np.array([distance_mm]), rho_mm)[0]


def propagate_bor_planes(r_mm, field, wavelength_mm: float, distances_mm, rho_mm) -> np.ndarray:
    """[plane, ρ] :func:`propagate_bor` at several distances: one spectrum (sampled for the nearest
    plane, whose evanescent waves reach furthest in κ), one propagation factor per plane."""
    from scipy import special      # at use: validating a spec loads no scipy.special
    r, rho, d = np.asarray(r_mm, float), np.asarray(rho_mm, float), np.asarray(distances_mm, float)
    kappa = _spectrum_axis(wavelength_mm, float(d.min()), r.max() + rho.max(), False)
    spec = matvec(special.j0(np.outer(kappa, r)), np.asarray(field, complex) * r * trapezoid_weights(r))
    spec = spec * kappa * trapezoid_weights(kappa)
    factors = np.exp(1j * np.outer(d, _kz(kappa, wavelength_mm))) * spec        # [plane, κ]
    return np.einsum("ik,pk->pi", special.j0(np.outer(rho, kappa)), factors)


def propagate_line(y_mm, field, wavelength_mm: float, distance_mm: float, y_out_mm) -> np.ndarray:
    """E(y', z = distance) of the line aperture field E(y) (2-D problem, module docstring), on a
    uniform ``y_mm``: FFT of the zero-padded aperture (padding wide enough that nothing wraps
    round onto ``y_out_mm``), interpolated onto ``y_out_mm``."""
    y, yo = np.asarray(y_mm, float), np.asarray(y_out_mm, float)
    dy = float(y[1] - y[0])
    span = np.ptp(y) + 2 * (np.abs(yo).max() + np.abs(y).max() + 4 * distance_mm)
    n = 1 << int(math.ceil(math.log2(span / dy)))
    buf = np.zeros(n, complex)
    buf[:len(y)] = field
    kappa = 2 * math.pi * np.fft.fftfreq(n, dy)
    out = np.fft.ifft(np.fft.fft(buf) * np.exp(1j * _kz(kappa, wavelength_mm) * distance_mm))
    grid = y[0] + dy * np.arange(n)
    grid = np.where(grid > y[0] + dy * n / 2 + np.ptp(y) / 2, grid - dy * n, grid)
    order = np.argsort(grid)
    g, o = grid[order], out[order]
    return np.interp(yo, g, o.real) + 1j * np.interp(yo, g, o.imag)


@dataclass(frozen=True)
class TestZone:
    """Largest centred test zone on a cut through the AUT plane, and the cut's amplitude (dB, to
    the centre) and phase (deg, the zone's linear tilt removed: a tilt only points the beam)."""
    diameter_mm: float
    y_mm: np.ndarray
    amplitude_db: np.ndarray
    phase_deg: np.ndarray

    __test__ = False                # not a pytest class


def largest_test_zone(y_mm, field, amplitude_db: float = 1.0, phase_deg: float = 11.25) -> TestZone:
    """The largest diameter 2ρ such that over |y| ≤ ρ the amplitude and the phase (best-fit linear
    tilt removed) stay within ±amplitude_db and ±phase_deg of their mid-range (module docstring).
    ``y_mm``: a cut through the centre, increasing; the zone is centred on y = 0."""
    y = np.asarray(y_mm, float)
    e = np.asarray(field, complex)
    c = int(np.argmin(np.abs(y)))
    amp = 20 * np.log10(np.maximum(np.abs(e) / max(abs(e[c]), 1e-300), 1e-12))
    ph = np.degrees(np.unwrap(np.angle(e / e[c])))
    ph -= ph[c]
    best, flat = 0.0, ph
    for rho in np.sort(np.abs(y[y >= 0])):
        inside = np.abs(y) <= rho
        if inside.sum() < 3:
            continue
        res = ph[inside] - np.polyval(np.polyfit(y[inside], ph[inside], 1), y[inside])
        if np.ptp(amp[inside]) > 2 * amplitude_db or np.ptp(res) > 2 * phase_deg:
            break
        best = rho
        flat = ph - np.polyval(np.polyfit(y[inside], ph[inside], 1), y)
    return TestZone(2 * float(best), y, amp, flat)
