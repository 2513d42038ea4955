"""Fast sub-wavelength-aware models of a stair-stepped lens: its phase error on one plane, and its
field over the quiet zone (:func:`multislice_field`).

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

from typing import Callable

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


# The multi-slice model of the quiet zone (the whole lens, feed to zone), measured against Meep over
# the zone's volume in tests/data/quiet_zone_table.csv.
SLICE_WAVELENGTHS = 0.125       # slice thickness (λ/16 changes the table's figures by < 1°)
RADIAL_PER_WAVELENGTH = 16      # samples of the quasi-discrete Hankel transform per λ
SUBSAMPLES = 4                  # foam lengths averaged over each sample's cell (ring edges between samples)
SPILL_WAVELENGTHS = (1.0, 5.0)  # the feed's own field beside the rim: whole to R + 1 λ, cos² to 0 at R + 5 λ
DOMAIN_WAVELENGTHS = 8.0        # the transform's radius beyond the rim (its wall reflects: absorbed before it)
ABSORB_NEPERS = 1.0             # per λ of slices at the wall, growing as the square from the spill-over's end


class _QuasiDiscreteHankel:
    """The order-0 quasi-discrete Hankel transform on a disc of radius ``radius_mm`` (Guizar-Sicairos
    and Gutiérrez-Vega, J. Opt. Soc. Am. A 21, 53, 2004): samples r_n = α_n·R/S at the zeros α_n of J0
    (S the (N+1)-th), spatial frequencies κ_m = α_m/R, and the symmetric matrix T that is its own
    inverse, so that a propagation by dz is J·T·e^{i k_z dz}·T·(E/J)."""

    def __init__(self, radius_mm: float, wavelength_mm: float):
        from scipy import special
        zeros = special.jn_zeros(0, int(RADIAL_PER_WAVELENGTH * radius_mm / wavelength_mm) + 1)
        s, alpha = zeros[-1], zeros[:-1]
        self.j1 = np.abs(special.j1(alpha))
        self.t = 2 * special.j0(np.outer(alpha, alpha) / s) / (np.outer(self.j1, self.j1) * s)
        self.r = alpha * radius_mm / s
        k = 2 * np.pi / wavelength_mm
        self.kz = np.sqrt((k**2 - (alpha / radius_mm) ** 2).astype(complex))

    def propagate(self, field: np.ndarray, dz_mm: float) -> np.ndarray:
        return self.j1 * (self.t @ (np.exp(1j * self.kz * dz_mm) * (self.t @ (field / self.j1))))


def spill_window(r: np.ndarray, radius_mm: float, wavelength_mm: float) -> np.ndarray:
    """1 out to the rim + SPILL_WAVELENGTHS[0] λ, then cos² to 0 at + SPILL_WAVELENGTHS[1] λ."""
    a, b = (radius_mm + s * wavelength_mm for s in SPILL_WAVELENGTHS)
    return np.cos(0.5 * np.pi * np.clip((r - a) / (b - a), 0.0, 1.0)) ** 2


def multislice_field(foam_mm: Callable[[float, float, np.ndarray], np.ndarray], z_front_mm: float, z_back_mm: float,
                     z_end_mm: float, feed_z_mm: float, radius_mm: float, n: float, wavelength_mm: float,
                     pattern: str = "dipole", q: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """(r, E) of a lens of revolution on the plane ``z_end_mm`` behind it, from its feed on the axis,
    by the split-step angular spectrum (the beam-propagation method): the feed's field E_r (m = +1,
    its ``pattern`` as the full-wave stage's, :func:`antenna_cad.fullwave.runner.feed_fields`) on a
    plane just before the lens's foremost point — over the lens and beside it, the spill-over past
    the rim (rolled off by :func:`spill_window` well outside it, as the full-wave cell's absorber
    does) — then, slice by slice through the lens, half a slice of free space, the phase
    k0(n−1)·ℓ(r) of the foam length ℓ(r) in the slice (``foam_mm(z0, z1, r)``), half a slice; each
    propagation the exact scalar angular spectrum of a body of revolution (evanescent waves decay).
    So the rim and every ring edge diffract where they are (their axial caustics are carried to the
    zone), a sub-wavelength staircase averages itself, and the amplitude follows from the feed's
    pattern, the ray-tube spreading of the lens and the normal-incidence Fresnel transmission
    4n/(1+n)² of each column of foam (seed-000 §4.4). Paraxial only in the foam: a wave at angle θ
    there gets k0(n−1)ℓ instead of k0(√(n² − sin²θ) − cos θ)ℓ."""
    from antenna_cad.fullwave.runner import feed_fields
    h = _QuasiDiscreteHankel(radius_mm + DOMAIN_WAVELENGTHS * wavelength_mm, wavelength_mm)
    r, k = h.r, 2 * np.pi / wavelength_mm
    cell = np.gradient(r)
    rs = (r[:, None] + cell[:, None] * ((np.arange(SUBSAMPLES) + 0.5) / SUBSAMPLES - 0.5)).ravel()

    def length(z0: float, z1: float) -> np.ndarray:
        return np.asarray(foam_mm(z0, z1, rs), float).reshape(len(r), SUBSAMPLES).mean(axis=1)

    start = z_front_mm - 0.25 * wavelength_mm
    field = feed_fields(r, np.asarray(start - feed_z_mm), k, pattern, q)[0] * spill_window(r, radius_mm, wavelength_mm)
    slices = max(1, int(np.ceil((z_back_mm - start) / (SLICE_WAVELENGTHS * wavelength_mm))))
    edges = np.linspace(start, z_back_mm, slices + 1)
    outer = radius_mm + SPILL_WAVELENGTHS[1] * wavelength_mm
    absorb = np.exp(-ABSORB_NEPERS * (edges[1] - edges[0]) / wavelength_mm
                    * (np.clip(r - outer, 0.0, None) / (r[-1] - outer)) ** 2)
    for z0, z1 in zip(edges[:-1], edges[1:]):
        half = (z1 - z0) / 2
        field = absorb * h.propagate(np.exp(1j * k * (n - 1) * length(z0, z1)) * h.propagate(field, half), half)
    field = field * np.where(length(start, z_back_mm) > 0, 4 * n / (1 + n) ** 2, 1.0)
    return r, h.propagate(field, z_end_mm - z_back_mm)
