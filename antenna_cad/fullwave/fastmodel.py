"""Fast sub-wavelength-aware model of a stair-stepped lens's phase error.

A stack of flat sheets differs from the ideal lens by Δd(r), the foam it has in excess along the axis at
radius r (zero where the lens is sanded to its profile). The thin phase screen k0(n−1)Δd (seed-000 §7.3)
takes every zone at face value; but thirteen of fifteen zones of a typical foam stack are narrower than
λ, so the staircase is a sub-wavelength grating whose higher orders are evanescent and only the
zone-averaged phase propagates (DESIGN.md "Verification models"). The model keeps the screen and lets
diffraction do the averaging: the screen's field exp(i·k0(n−1)Δd(r)) over the aperture is propagated
to the aperture plane by the exact scalar angular spectrum of a body of revolution (order-0 Hankel
transform, evanescent components decaying as exp(−2πL·√(ρ² − 1/λ²))), divided by the same
propagation of the unstepped aperture. L runs from the stack's mean front face to the aperture plane.
Its error against Meep is measured over the table in ``tests/data/fullwave_table.csv``.
"""

from __future__ import annotations

import numpy as np

SAMPLES_PER_LAMBDA = 40     # radial samples of the screen
RHO_MAX = 2.0               # spatial frequencies kept, units of 1/λ (≥ e^-20 decay beyond at L ≥ 2 λ)


def thin_screen_deg(delta_d_mm: np.ndarray, n: float, wavelength_mm: float) -> np.ndarray:
    """k0(n−1)Δd, the stair-step phase at face value (seed-000 §7.3), as a phase delay (deg; time
    e^{−iωt}, so a delay is a positive phase, as in Meep and the GO path)."""
    return 360.0 * (n - 1.0) * np.asarray(delta_d_mm) / wavelength_mm


def _hankel(u: np.ndarray, r: np.ndarray, dr: float, rho: np.ndarray) -> np.ndarray:
    from scipy.special import j0     # at use (scipy.special costs ~0.2 s; validating needs none)
    return 2 * np.pi * (j0(2 * np.pi * np.outer(rho, r)) @ (u * r[:, None])) * dr


def propagate(u: np.ndarray, r: np.ndarray, radius_mm: float, wavelength_mm: float, distance_mm: float,
              r_obs: np.ndarray) -> np.ndarray:
    """Scalar fields of the axisymmetric aperture fields u[:, j] (samples ``r``, spacing uniform) after
    ``distance_mm`` of free space, at radii ``r_obs``: angular spectrum by Hankel transform."""
    from scipy.special import j0
    dr = r[1] - r[0]
    d_rho = 1.0 / (4.0 * radius_mm)
    rho = np.arange(0.0, RHO_MAX / wavelength_mm, d_rho) + 0.5 * d_rho
    kz = 2 * np.pi * np.sqrt((1.0 / wavelength_mm ** 2 - rho ** 2).astype(complex))
    spectrum = _hankel(u, r, dr, rho) * np.exp(1j * kz * distance_mm)[:, None]
    return 2 * np.pi * (j0(2 * np.pi * np.outer(r_obs, rho)) @ (spectrum * rho[:, None])) * d_rho


def fast_phase(excess_mm, n: float, wavelength_mm: float, radius_mm: float, distance_mm: float,
               r_obs: np.ndarray) -> np.ndarray:
    """Phase (deg) that the excess foam ``excess_mm(r)`` (a function of r, mm) adds on the aperture plane
    at radii ``r_obs``, relative to the ideal lens: the sub-wavelength-aware model above."""
    step = wavelength_mm / SAMPLES_PER_LAMBDA
    r = np.arange(0.5 * step, radius_mm, step)
    screen = np.exp(1j * np.radians(thin_screen_deg(excess_mm(r), n, wavelength_mm)))
    stepped, ideal = propagate(np.column_stack([screen, np.ones_like(r)]), r, radius_mm, wavelength_mm,
                               distance_mm, r_obs).T
    return np.degrees(np.angle(stepped / ideal))
