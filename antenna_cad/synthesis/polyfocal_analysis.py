"""RMS aberration of constrained lenses against the field angle (seed-001 (1.4), §4).

σ = (1/D)·sqrt(Σ (L_i − L_0)² / N): L_i the eikonal from a source S through line i to the image
S' (|S − r1| + l + |r2 − S'|) or, for a plane-wave output, |S − r1| + l − k·r2; L_0 the path through
the central line (so σ includes piston, seed-001 §4). Conventions (the seed is silent on some, see
the kind's notes):

* Sources lie on the **focal curve**, a circle (2-D) or sphere (3-D) centred on the axis. Two-pair
  2-D lenses (three or four foci): the circle through the design foci (exact for the seed's cases).
  Bifocal 2-D lenses: the circle through F1, F2 and the axis point (0, z_F); one pair leaves z_F
  free, so it is given or optimised for the least peak σ over the view (the seed's procedure,
  seed-001 §1.2). 3-D lenses: the sphere whose (centre, radius) minimise the peak σ over the view in
  the yz and xz planes (the seed optimises its focal sphere's radius, seed-001 §2.2–§2.4; no sphere
  centred on the axis passes through five general foci), scanned in both planes. The source at field
  angle θ is where the ray from the lens centre O at angle θ to −z meets the curve.
* Images: two-plane-symmetric lenses image S at S' = −S (point symmetry, seed-001 §4.2); lenses
  with f ≠ f' (§1.4) on the image circle through the F_i', in the direction opposite to S;
  plane-wave lenses radiate in the direction that minimises σ (seed-001 §4.2, option 2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize, minimize_scalar

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
    disc = b * b - 4 * c
    return u * (-b + np.sqrt(disc)) / 2 if disc >= 0 else np.full(3, np.nan)   # NaN: the ray misses it


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
    """(σ, k): the plane-wave output direction that minimises σ for ``source`` (Gauss–Newton on the
    free transverse components of k, k_z = sqrt(1 − k_x² − k_y²), analytic Jacobian, from the
    direction away from the source)."""
    k0 = -source / np.linalg.norm(source)
    c = _central(lens)
    free = [0, 1] if lens.dimensions == 3 else [1]
    scale = lens.aperture * np.sqrt(len(lens.l))
    base = np.linalg.norm(lens.r1 - source, axis=1) + lens.l
    base, rel = base - base[c], lens.r2 - lens.r2[c]
    p = k0[free].copy()
    for _ in range(30):
        kz = np.sqrt(max(1.0 - float(np.sum(p**2)), 1e-30))
        k = np.zeros(3)
        k[free], k[2] = p, kz
        dev = base - rel @ k
        jac = -rel[:, free] + rel[:, [2]] * (p / kz)
        step = np.linalg.solve(jac.T @ jac, -jac.T @ dev)
        p = p + step
        if np.max(np.abs(step)) < 1e-10:       # σ is stationary in k: its error ~ step²
            break
    k = np.zeros(3)
    k[free], k[2] = p, np.sqrt(max(1.0 - float(np.sum(p**2)), 0.0))
    return float(np.linalg.norm(base - rel @ k) / scale), k


def design_foci_sigma(lens: ConstrainedLens) -> np.ndarray:
    """(1.4) at each design focus with its own image or output direction (0 for a perfect focus)."""
    c = _central(lens)
    out = []
    for f in lens.foci:
        path = f.path(lens.r1, lens.l, lens.r2)
        out.append(np.sqrt(np.mean((path - path[c]) ** 2)) / lens.aperture)
    return np.array(out)


def image_circle(lens: ConstrainedLens) -> tuple[float, float, float] | None:
    """(z_e, z_c, R) of the image curve when the images are not the foci point-reflected (seed-001
    §1.4, f ≠ f'): F_i' = e − (f_i'/f_i)·F_i about the exit-surface centre (0, 0, z_e), so the image
    of S is e − (the point of the axis-centred circle through e − F_i' in S's direction); None for
    point-symmetric or plane-wave lenses."""
    if lens.foci[0].image is None or all(np.allclose(f.image, -f.point) for f in lens.foci):
        return None
    z_e = float(lens.r2[_central(lens), 2])
    return (z_e, *focal_sphere(np.array([[0.0, 0.0, z_e] - f.image for f in lens.foci])))


def _sigma_on(lens: ConstrainedLens, zc: float, radius: float, theta: float, azimuth: float = 0.0,
              images: tuple[float, float, float] | None = None) -> float:
    """σ for the source at field angle θ on the sphere (z_c, R); inf where the ray misses the sphere.
    The image of S is −S, or on the image curve ``images`` (:func:`image_circle`)."""
    s = source_on(zc, radius, theta, azimuth)
    if not np.all(np.isfinite(s)):
        return np.inf
    if lens.foci[0].image is not None:
        return sigma(lens, s, image=-s if images is None else image_of(images, theta, azimuth))
    return best_direction(lens, s)[0]


def image_of(images: tuple[float, float, float], theta: float, azimuth: float = 0.0) -> np.ndarray:
    """The image point on the curve ``images`` (:func:`image_circle`) for the field angle θ."""
    z_e, zc, radius = images
    return np.array([0.0, 0.0, z_e]) - source_on(zc, radius, theta, azimuth)


@dataclass(frozen=True)
class SigmaScan:
    """σ/D against the field angle (degrees) along one focal curve or sphere section; ``curve`` says
    how the curve was chosen."""
    label: str
    angle_deg: np.ndarray
    sigma: np.ndarray
    focal_centre_z: float
    focal_radius: float
    curve: str = "through the design foci"

    @property
    def max(self) -> float:
        return float(np.max(self.sigma))


def sigma_scan(lens: ConstrainedLens, half_view_deg: float, count: int = 61, azimuth: float = 0.0,
               label: str = "", sphere: tuple[float, float, str] | None = None) -> SigmaScan:
    """σ over field angles 0 … ±half view on the sphere ``(z_c, R, how)`` (default: the least-squares
    sphere through the design foci) in the plane of ``azimuth``."""
    zc, radius, how = sphere or (*focal_sphere(np.array([f.point for f in lens.foci])), "through the design foci")
    angles = np.linspace(-half_view_deg, half_view_deg, count)
    images = image_circle(lens)
    values = np.array([_sigma_on(lens, zc, radius, a, azimuth, images) for a in np.radians(angles)])
    return SigmaScan(label, angles, values, zc, radius, how)


def axis_point_circle(lens: ConstrainedLens, z_axis: float) -> tuple[float, float]:
    """(z_c, R) of the axis-centred circle through the bifocal pair and the axis point (0, z_F)."""
    return focal_sphere(np.array([lens.foci[0].point, [0.0, 0.0, z_axis]]))


def optimal_axis_point(lens: ConstrainedLens, half_view_deg: float, count: int = 21) -> float:
    """Seed-001 §1.2: the axis point z_F of the bifocal focal circle that minimises the peak σ over
    ±half view (a grid over z_f ± D, z_f the foci's z, refined by a bounded scalar search). z_F is
    the circle's far axis point z_c − R, the one the sources pass through (the near one, z_c + R,
    would name a different scanned arc)."""
    angles = np.radians(np.linspace(0.0, half_view_deg, count))       # σ is even in θ (two symmetry planes)
    z_f, D = float(lens.foci[0].point[2]), lens.aperture

    def peak(z_axis: float) -> float:
        if abs(z_axis - z_f) < 1e-6 * D:
            return np.inf
        zc, radius = axis_point_circle(lens, z_axis)
        if z_axis >= zc:                 # the sources lie on the far arc: z_F must be its axis point zc − R
            return np.inf
        return max(_sigma_on(lens, zc, radius, a) for a in angles)

    grid = z_f + D * np.concatenate([np.linspace(-1.0, -0.01, 100), np.linspace(0.01, 1.0, 100)])
    values = np.array([peak(z) for z in grid])
    if not np.isfinite(values).any():
        raise ValueError("no focal circle through the foci covers the view")
    k = int(np.argmin(values))
    step = D * 0.01
    res = minimize_scalar(peak, bounds=(grid[k] - step, grid[k] + step), method="bounded",
                          options={"xatol": 1e-7 * D})
    return float(res.x) if res.fun <= values[k] else float(grid[k])


def fitted_sphere(lens: ConstrainedLens, half_view_deg: float, count: int = 5) -> tuple[float, float]:
    """(z_c, R) of the axis-centred focal sphere that minimises the peak σ over ±half view in the yz
    (θ ≥ 0: the lens is symmetric in y) and xz planes, from the least-squares sphere through the foci."""
    pos = np.radians(np.linspace(0.0, half_view_deg, count))
    both = np.radians(np.linspace(-half_view_deg, half_view_deg, 2 * count - 1))
    cases = [(a, 0.0) for a in pos] + [(a, np.pi / 2) for a in both]

    images = image_circle(lens)

    def peak(p) -> float:
        return max(_sigma_on(lens, p[0], p[1], a, az, images) for a, az in cases)

    start = np.array(focal_sphere(np.array([f.point for f in lens.foci])))
    res = minimize(peak, start, method="Nelder-Mead",
                   options={"xatol": 1e-4 * lens.aperture, "fatol": 1e-9, "maxiter": 120,
                            "initial_simplex": [start, start + [0.05 * lens.aperture, 0], start + [0, 0.05 * lens.aperture]]})
    best = res.x if res.fun <= peak(start) else start
    return float(best[0]), float(best[1])


# seed-001 §1.3 60° designs (f1 = D = 25, λ = 1; 2z0 = 10 assumed as §1.2): label → foci
SEED_60_DEG = {
    "bifocal (a) equal lines, α 17.5°": [SymFocus(25.0, np.radians(17.5))],
    "trifocal, f3 22.55, β 27.5°": [SymFocus(25.0, 0.0), SymFocus(22.55, np.radians(27.5))],
    "four-focal, f3 22.925, α 11.7°, β 27.9°": [SymFocus(25.0, np.radians(11.7)), SymFocus(22.925, np.radians(27.9))],
}
SEED_BIFOCAL_ZF = -31.1          # seed-001 §1.2: the bifocal focal circle passes through (0, z_F)


SEED_HALF_VIEW = 30.0            # the seed's 60° view (±30°) of these designs


def seed_comparison(z0: float = 5.0, count: int = 41) -> list[SigmaScan]:
    """The seed's best two-/three-/four-focal lenses for the 60° view (§1.2, §1.3), each on its
    focal circle over ±30° whatever the user's view, N = 101 lines; returns their σ scans (the seed:
    four-focal ≈ 1.5× below trifocal)."""
    y = np.linspace(0.0, 12.5, 51)
    scans = []
    for label, foci in SEED_60_DEG.items():
        lens = two_planes_2d(foci, z0, 25.0, y)
        sphere = None
        if len(foci) == 1:
            sphere = (*axis_point_circle(lens, SEED_BIFOCAL_ZF), f"through F1, F2 and the seed's z_F {SEED_BIFOCAL_ZF}")
        scans.append(sigma_scan(lens, SEED_HALF_VIEW, count, label=label, sphere=sphere))
    return scans
