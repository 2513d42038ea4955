"""Meridional (2-D) ray trace through the single-surface collimator, seed-000 §4.2.

Implements the algorithm of §4.2 with vector Snell (the printed angle bookkeeping (2.5)–(2.12)
is garbled, see the digest's erratum) on the generic tracer :mod:`antenna_cad.raytrace.trace2d`:
rays leave the feed, hit the hyperbolic face, refract, cross the lens to the flat face, refract
out and travel to the antenna plane. The phase is k0 × optical path; the linear tilt is removed
by a least-squares fit. Also the feed-scan range of the lens (seed-000 §5.5, Tables 2.1–2.3).
Frame: z along the axis (feed at −f, vertex 0), y transverse, millimetres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.raytrace.trace2d import Interface, Trace2D, aim_at_face, trace
from antenna_cad.synthesis.collimator import profile_z_mm, thickness_mm
from antenna_cad.verification import detrended

RIM_TOLERANCE = 1e-9        # relative: a ray aimed at the rim stays in the aperture despite rounding


@dataclass(frozen=True)
class ApertureTrace:
    y_mm: np.ndarray          # arrival points on the antenna plane
    path_mm: np.ndarray       # optical path length from the feed
    direction: np.ndarray     # exit directions (z, y)
    wavelength_mm: float

    @staticmethod
    def from_trace(tr: Trace2D, wavelength_mm: float, keep: np.ndarray) -> "ApertureTrace":
        """The rays ``keep`` of a trace, at their last point (the antenna plane)."""
        return ApertureTrace(tr.points[-1][keep, 1], tr.opl[keep], tr.directions[-1][keep], wavelength_mm)

    def phase_deg(self) -> np.ndarray:
        return np.degrees(2 * np.pi * self.path_mm / self.wavelength_mm)

    def detrended_phase_deg(self) -> np.ndarray:
        """Aperture phase with the best-fit linear tilt removed (seed-000 §4.1, (2.16))."""
        return detrended(self.y_mm, self.phase_deg())

    def peak_to_peak_deg(self) -> float:
        p = self.detrended_phase_deg()
        return float(p.max() - p.min())

    def rms_deg(self) -> float:
        p = self.detrended_phase_deg()
        return float(np.sqrt(np.mean((p - p.mean()) ** 2)))


def front_face(focal_length_mm: float, n: float, n_after: float | None = None) -> Interface:
    """The hyperbolic illuminated face, seed-000 §2.1 (1.9) corrected, as a tracer interface
    (even in y; slope dz/dr = r/((n²−1)z + (n−1)f)). ``n_after`` (default n) is the index behind it."""
    f = focal_length_mm

    def z_of_y(y):
        return profile_z_mm(y, f, n)

    def dz_dy(y):
        return np.asarray(y, float) / ((n**2 - 1) * z_of_y(y) + (n - 1) * f)

    return Interface(z_of_y, dz_dy, n if n_after is None else float(n_after), 0.0)


def trace_collimator(*, focal_length_mm: float, n: float, diameter_mm: float, back_z_mm: float,
                     antenna_z_mm: float, wavelength_mm: float,
                     feed_zy_mm: tuple[float, float] | None = None,
                     rays: int = 2001, margin: float = 1.0) -> ApertureTrace:
    """Trace ``rays`` rays from the feed (default: the focus (−f, 0)) through the lens to the
    plane z = antenna_z. Rays are aimed at points of the illuminated face spread uniformly in y
    over ``margin`` × the diameter, so both halves are covered under transverse defocus; rays
    that leave the flat face outside the rim (beyond rounding) are dropped."""
    feed = np.array(feed_zy_mm if feed_zy_mm is not None else (-focal_length_mm, 0.0))
    front = front_face(focal_length_mm, n)
    dirs = aim_at_face(front, feed, margin * diameter_mm / 2, rays)
    tr = trace(np.tile(feed, (rays, 1)), dirs, [front, Interface.plane(back_z_mm, 1.0)], 1.0, antenna_z_mm)
    rim = diameter_mm / 2 * (1 + RIM_TOLERANCE)
    return ApertureTrace.from_trace(tr, wavelength_mm, tr.ok & (np.abs(tr.points[2][:, 1]) <= rim))


def single_surface_p2p_deg(focal_length_mm: float, diameter_mm: float, eps_r: float, feed_y_mm: float,
                           back_mm: float, wavelength_mm: float, rays: int = 201) -> float:
    """Peak-to-peak aperture phase (deg, tilt removed) of the single-surface lens with the feed at
    (−f, feed_y), on the plane ``back_mm`` behind the flat face (seed-000 §4.2, §5.5)."""
    n = float(np.sqrt(eps_r))
    d = thickness_mm(diameter_mm, focal_length_mm, n)
    return trace_collimator(focal_length_mm=focal_length_mm, n=n, diameter_mm=diameter_mm, back_z_mm=d,
                            antenna_z_mm=d + back_mm, wavelength_mm=wavelength_mm,
                            feed_zy_mm=(-focal_length_mm, feed_y_mm), rays=rays, margin=0.999).peak_to_peak_deg()


def axial_p2p_deg(focal_length_mm: float, diameter_mm: float, eps_r: float, sigma: float, back_mm: float,
                  wavelength_mm: float, rays: int = 201) -> float:
    """Peak-to-peak aperture phase with the feed on the axis at σ·f from the vertex (σ < 1: toward
    the lens), seed-000 §5.5."""
    n = float(np.sqrt(eps_r))
    d = thickness_mm(diameter_mm, focal_length_mm, n)
    return trace_collimator(focal_length_mm=focal_length_mm, n=n, diameter_mm=diameter_mm, back_z_mm=d,
                            antenna_z_mm=d + back_mm, wavelength_mm=wavelength_mm,
                            feed_zy_mm=(-sigma * focal_length_mm, 0.0), rays=rays, margin=0.999).peak_to_peak_deg()


def axial_defocus_limits(focal_length_mm: float, diameter_mm: float, eps_r: float, back_mm: float,
                         wavelength_mm: float, budget_deg: float,
                         sigma_max: float = 20.0) -> tuple[float, float | None]:
    """Feed-displacement limits along the axis by the phase rule (seed-000 Table 2.1, σ < 1 and
    σ > 1): the σ = (feed distance)/f where the p-p phase reaches ``budget_deg`` moving toward the
    lens and away from it (None when it never does up to ``sigma_max``: the table's "−")."""
    from scipy.optimize import brentq       # at use: validating a spec loads no optimizer
    def p2p(sigma):
        return axial_p2p_deg(focal_length_mm, diameter_mm, eps_r, sigma, back_mm, wavelength_mm)

    near = np.linspace(1.0, 0.02, 50)
    vals = np.array([p2p(s) for s in near])
    i = int(np.argmax(vals > budget_deg))
    lo = float(brentq(lambda s: p2p(s) - budget_deg, near[i], near[i - 1], xtol=1e-6)) if vals[i] > budget_deg else 0.0
    far = np.geomspace(1.0, sigma_max, 60)
    vals = np.array([p2p(s) for s in far])
    j = int(np.argmax(vals > budget_deg))
    hi = float(brentq(lambda s: p2p(s) - budget_deg, far[j - 1], far[j], xtol=1e-6)) if vals[j] > budget_deg else None
    return lo, hi


def usable_half_range_mm(p2p_deg, feed_y_mm: np.ndarray, budget_deg: float) -> tuple[np.ndarray, float]:
    """Feed-scan study (seed-000 §5.5): ``p2p_deg(y)`` on the grid ``feed_y_mm`` (increasing from 0)
    and the first displacement where it reaches the budget (brentq between grid points; the last
    grid point when it never does, 0 when the budget is exceeded at once)."""
    vals, _, hi = usable_interval_mm(p2p_deg, feed_y_mm, budget_deg, float(feed_y_mm[0]))
    return vals, hi


def usable_interval_mm(p2p_deg, feed_y_mm: np.ndarray, budget_deg: float,
                       start_mm: float) -> tuple[np.ndarray, float, float]:
    """``p2p_deg`` on the increasing grid ``feed_y_mm`` and the interval [lo, hi] around ``start_mm``
    (a design focus) where it stays within the budget, each end by brentq between grid points (the
    grid ends when never reached; lo = hi = start when the budget is exceeded at the start)."""
    from scipy.optimize import brentq
    vals = np.array([p2p_deg(y) for y in feed_y_mm])
    if not p2p_deg(start_mm) <= budget_deg:
        return vals, start_mm, start_mm
    ok = vals <= budget_deg
    above, below = np.nonzero((feed_y_mm > start_mm) & ~ok)[0], np.nonzero((feed_y_mm < start_mm) & ~ok)[0]
    xtol = 1e-6 * float(np.ptp(feed_y_mm))
    root = lambda a, b: float(brentq(lambda y: p2p_deg(y) - budget_deg, a, b, xtol=xtol))  # noqa: E731
    hi = float(feed_y_mm[-1]) if len(above) == 0 else root(max(start_mm, feed_y_mm[above[0] - 1]),
                                                            feed_y_mm[above[0]])
    lo = float(feed_y_mm[0]) if len(below) == 0 else root(feed_y_mm[below[-1]],
                                                           min(start_mm, feed_y_mm[below[-1] + 1]))
    return vals, lo, hi
