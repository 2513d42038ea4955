"""Meridional (2-D) ray trace through the single-surface collimator, seed-000 §4.2.

Implements the algorithm of §4.2 with vector Snell (the printed angle bookkeeping (2.5)–(2.12)
is garbled, see the digest's erratum): rays leave the feed, hit the hyperbolic face at sampled
points, refract, cross the lens to the flat face, refract out and travel to the antenna plane.
The phase is k0 × optical path; the linear tilt is removed by a least-squares fit.
Frame: z along the axis (feed at −f, vertex 0), y transverse, millimetres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.raytrace.snell import refract
from antenna_cad.synthesis.collimator import profile_z_mm, surface_normal
from antenna_cad.verification import detrended


@dataclass(frozen=True)
class ApertureTrace:
    y_mm: np.ndarray          # arrival points on the antenna plane
    path_mm: np.ndarray       # optical path length from the feed
    direction: np.ndarray     # exit directions (z, y)
    wavelength_mm: float

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


def trace_collimator(*, focal_length_mm: float, n: float, diameter_mm: float, back_z_mm: float,
                     antenna_z_mm: float, wavelength_mm: float,
                     feed_zy_mm: tuple[float, float] | None = None,
                     rays: int = 2001) -> ApertureTrace:
    """Trace ``rays`` rays from the feed (default: the focus (−f, 0)) through the lens to the
    plane z = antenna_z. Rays are aimed at points of the illuminated face sampled uniformly in
    y over the full diameter, so both halves are covered under transverse defocus."""
    feed = np.array(feed_zy_mm if feed_zy_mm is not None else (-focal_length_mm, 0.0))
    y = np.linspace(-diameter_mm / 2, diameter_mm / 2, rays)
    z = profile_z_mm(np.abs(y), focal_length_mm, n)
    hit = np.stack([z, y], axis=-1)
    leg1 = hit - feed
    len1 = np.linalg.norm(leg1, axis=-1)
    normal = surface_normal(z, np.abs(y), focal_length_mm, n) * np.stack([np.ones_like(y), np.sign(y)], axis=-1)
    inside, ok = refract(leg1 / len1[:, None], normal, 1.0, n)
    t_back = (back_z_mm - z) / inside[:, 0]
    back = hit + t_back[:, None] * inside
    out, ok_out = refract(inside, np.tile([1.0, 0.0], (rays, 1)), n, 1.0)
    t_ant = (antenna_z_mm - back[:, 0]) / out[:, 0]
    arrival = back + t_ant[:, None] * out
    path = len1 + n * t_back + t_ant
    keep = ok & ok_out
    return ApertureTrace(arrival[keep, 1], path[keep], out[keep], wavelength_mm)
