"""RMS aberration of constrained lenses against the field angle (seed-001 (1.4), §4).

σ = (1/D)·sqrt(Σ (L_i − L_0)² / N): L_i the eikonal from a source S through line i to the image
S' (|S − r1| + l + |r2 − S'|) or, for a plane-wave output, |S − r1| + l − k·r2; L_0 the path through
the central line (so σ includes piston, seed-001 §4). Conventions (the seed is silent on some, see
the kind's notes):

* Sources lie on the **focal curve**: in 2-D the circle centred on the axis through the design foci
  (least squares when there are more than two distinct ones — exact for the seed's cases); in 3-D the
  **focal sphere** centred on the axis fitted to the five foci, scanned in the xz and yz planes. The
  source at field angle θ is where the ray from the lens centre O at angle θ to −z meets the curve.
* Images: two-plane-symmetric lenses image S at S' = −S (point symmetry, seed-001 §4.2);
  plane-wave lenses radiate in the direction that minimises σ (seed-001 §4.2, option 2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from antenna_cad.synthesis.polyfocal import ConstrainedLens, SymFocus, two_planes_2d


def focal_sphere(points: np.ndarray) -> tuple[float, float]:
    """(z_c, R) of the circle/sphere centred on the z axis through ``points`` (least squares):
    |F|² = 2 z_c F_z + (R² − z_c²)."""
    p = np.asarray(points, dtype=float)
    a = np.column_stack([2 * p[:, 2], np.ones(len(p))])
    (zc, c), *_ = np.linalg.lstsq(a, np.sum(p**2, axis=1), rcond=None)
    return float(zc), float(np.sqrt(c + zc**2))


def source_on(zc: float, radius: float, theta: float, azimuth: float = 0.0) -> np.ndarray:
    """Point of the axis-centred sphere (z_c, R) on the ray from O at angle θ to −z (azimuth from Oy)."""
    u = np.array([np.sin(theta) * np.sin(azimuth), np.sin(theta) * np.cos(azimuth), -np.cos(theta)])
    b = -2 * u[2] * zc                       # |t u − (0,0,zc)|² = R², t > 0 the near-feed root
    c = zc**2 - radius**2
    return u * (-b + np.sqrt(b * b - 4 * c)) / 2


def _central(lens: ConstrainedLens) -> int:
    return int(np.argmin(np.linalg.norm(lens.r1[:, :2], axis=1)))


def sigma(lens: ConstrainedLens, source: np.ndarray, image: np.ndarray | None = None,
          direction: np.ndarray | None = None) -> float:
    """(1.4) for one source: σ/D with the given image point or plane-wave direction."""
    path = np.linalg.norm(lens.r1 - source, axis=1) + lens.l
    path = path + (np.linalg.norm(lens.r2 - image, axis=1) if image is not None else -lens.r2 @ direction)
    dev = path - path[_central(lens)]
    return float(np.sqrt(np.mean(dev**2)) / lens.aperture)


def best_direction(lens: ConstrainedLens, source: np.ndarray) -> tuple[float, np.ndarray]:
    """(σ, k): the plane-wave output direction that minimises σ for ``source``."""
    k0 = -source / np.linalg.norm(source)
    c = _central(lens)
    free = [0, 1] if lens.dimensions == 3 else [1]

    def k_of(p):
        k = np.zeros(3)
        k[free] = p
        k[2] = np.sqrt(max(1.0 - float(np.sum(k[:2] ** 2)), 0.0))
        return k

    def dev(p):
        path = np.linalg.norm(lens.r1 - source, axis=1) + lens.l - lens.r2 @ k_of(p)
        return (path - path[c]) / (lens.aperture * np.sqrt(len(path)))

    fit = least_squares(dev, k0[free], xtol=1e-14, ftol=1e-14, gtol=1e-14)
    return float(np.sqrt(np.sum(fit.fun**2))), k_of(fit.x)


@dataclass(frozen=True)
class SigmaScan:
    """σ/D against the field angle (degrees) along one focal curve or sphere section."""
    label: str
    angle_deg: np.ndarray
    sigma: np.ndarray
    focal_centre_z: float
    focal_radius: float

    @property
    def max(self) -> float:
        return float(np.max(self.sigma))


def sigma_scan(lens: ConstrainedLens, half_view_deg: float, count: int = 61, azimuth: float = 0.0,
               label: str = "") -> SigmaScan:
    """σ over field angles 0 … ±half view on the lens's focal curve/sphere (plane of ``azimuth``)."""
    zc, radius = focal_sphere(np.array([f.point for f in lens.foci]))
    angles = np.linspace(-half_view_deg, half_view_deg, count)
    values = []
    for a in np.radians(angles):
        s = source_on(zc, radius, a, azimuth)
        if lens.foci[0].image is not None:
            values.append(sigma(lens, s, image=-s))
        else:
            values.append(best_direction(lens, s)[0])
    return SigmaScan(label, angles, np.array(values), zc, radius)


# seed-001 §1.3 60° designs (f1 = D = 25, λ = 1; 2z0 = 10 assumed as §1.2): label → foci
SEED_60_DEG = {
    "bifocal (a) equal lines, α 17.5°": [SymFocus(25.0, np.radians(17.5))],
    "trifocal, f3 22.55, β 27.5°": [SymFocus(25.0, 0.0), SymFocus(22.55, np.radians(27.5))],
    "four-focal, f3 22.925, α 11.7°, β 27.9°": [SymFocus(25.0, np.radians(11.7)), SymFocus(22.925, np.radians(27.9))],
}
SEED_BIFOCAL_ZF = -31.1          # seed-001 §1.2: the bifocal focal circle passes through (0, z_F)


def seed_comparison(half_view_deg: float = 30.0, z0: float = 5.0, count: int = 41) -> list[SigmaScan]:
    """The seed's best two-/three-/four-focal lenses for the 60° view (§1.2, §1.3), each on its
    focal circle, N = 101 lines; returns their σ scans (the seed: four-focal ≈ 1.5× below trifocal)."""
    y = np.linspace(0.0, 12.5, 51)
    scans = []
    for label, foci in SEED_60_DEG.items():
        lens = two_planes_2d(foci, z0, 25.0, y)
        if len(foci) == 1:
            pts = np.array([f.point for f in lens.foci] + [[0.0, 0.0, SEED_BIFOCAL_ZF]])
            zc, radius = focal_sphere(pts)
            angles = np.linspace(-half_view_deg, half_view_deg, count)
            vals = [sigma(lens, s, image=-s) for s in (source_on(zc, radius, a) for a in np.radians(angles))]
            scans.append(SigmaScan(label, angles, np.array(vals), zc, radius))
        else:
            scans.append(sigma_scan(lens, half_view_deg, count, label=label))
    return scans
