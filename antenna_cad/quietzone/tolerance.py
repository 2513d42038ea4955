"""The build tolerances as perturbations of the smooth lens, and the gain from the aperture field itself.

The stack's own error (its quiet-zone figure) is a property of the steps; the tolerances are small,
smooth changes of the lens, so each is taken to first order along the rays of the smooth lens
(Fermat: the rays themselves move only to second order), never by geometrical optics through the steps:

* material εr → εr + δ: the optical path of each ray changes by Δn·L, L its geometric path inside the
  lens and Δn = √(εr + δ) − √εr (≈ δ/2n);
* thickness (every sheet, or the lens, thicker by a factor 1 + ε about the stack's front): each face
  moves by δz = ε·(z − z_front) where the ray crosses it, and the path changes by
  δz·(n₁·d₁z − n₂·d₂z) (the index and direction before and after the face; n₁d₁ − n₂d₂ is normal
  to the face by Snell's law, so only the normal part of the move counts).

An added phase is judged as the quiet-zone figures are: over the disc (weight |y|, the revolved area),
with its tilt and piston removed, peak-to-peak and area-weighted RMS. The gain follows the aperture
efficiency η = |∫E dA|² / (A·∫|E|² dA) of a field over a disc of revolution (seed-000 §4.6), the loss
of a fabricated field the ratio of its η to the ideal field's (not Ruze on an RMS).
"""

from __future__ import annotations

import numpy as np

from antenna_cad.radiation.aperture import trapezoid_weights
from antenna_cad.raytrace.trace2d import Trace2D


def eps_r_added_deg(tr: Trace2D, keep: np.ndarray, n: float, delta_eps_r: float, wavelength_mm: float) -> np.ndarray:
    """Phase (deg) εr + ``delta_eps_r`` adds to each kept ray of a trace through the smooth lens of index n."""
    seg = np.linalg.norm(np.diff(tr.points, axis=0), axis=-1)[: len(tr.index)]       # (segments, rays)
    inside = np.where(np.isclose(tr.index, n), seg, 0.0).sum(axis=0)
    dn = np.sqrt(n * n + delta_eps_r) - n
    return 360.0 / wavelength_mm * dn * inside[keep]


def thickness_added_deg(tr: Trace2D, keep: np.ndarray, faces: int, z_front_mm: float, stretch: float,
                        wavelength_mm: float) -> np.ndarray:
    """Phase (deg) added to each kept ray when the lens's ``faces`` (the first ones the rays cross) are
    stretched along z by 1 + ``stretch`` about ``z_front_mm``."""
    added = np.zeros(tr.points.shape[1])
    for k in range(1, faces + 1):
        dz = stretch * (tr.points[k][:, 0] - z_front_mm)
        added += dz * (tr.index[k - 1] * tr.directions[k - 1][:, 0] - tr.index[k] * tr.directions[k][:, 0])
    return 360.0 / wavelength_mm * added[keep]


def _weights(y_mm: np.ndarray) -> np.ndarray:
    return np.abs(y_mm) + 1e-12 * (1.0 + np.abs(y_mm).max())


def residual_deg(y_mm: np.ndarray, added_deg: np.ndarray) -> np.ndarray:
    """An added phase on rays at ``y_mm`` (across the disc) with its area-weighted tilt and piston removed."""
    w = _weights(y_mm)
    p = added_deg - np.polyval(np.polyfit(y_mm, added_deg, 1, w=np.sqrt(w)), y_mm)
    return p - np.average(p, weights=w)


def added_figures(y_mm: np.ndarray, added_deg: np.ndarray) -> tuple[float, float]:
    """(p-p, area-weighted RMS) of an added phase over the disc, its tilt and piston removed (weight |y|)."""
    p = residual_deg(y_mm, added_deg)
    return float(p.max() - p.min()), float(np.sqrt(np.average(p * p, weights=_weights(y_mm))))


def aperture_efficiency(r_mm: np.ndarray, field: np.ndarray) -> float:
    """|∫E dA|² / (A·∫|E|² dA) over the disc r ≤ r_max of a field of revolution (r increasing from 0)."""
    w = trapezoid_weights(r_mm) * r_mm
    return float(abs(np.sum(w * field)) ** 2 / (np.sum(w) * np.sum(w * np.abs(field) ** 2)))


def efficiency_loss_db(r_mm: np.ndarray, ideal: np.ndarray, built: np.ndarray) -> float:
    """Gain loss (dB) of the ``built`` aperture field against the ``ideal`` one, from their efficiencies."""
    return float(10 * np.log10(aperture_efficiency(r_mm, ideal) / aperture_efficiency(r_mm, built)))
