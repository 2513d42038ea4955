"""The trifocal graded-index lens (seed-001 §3.2) as a design: construction, RMS aberration (3.10)
against the field angle, the bifocal comparison, and the split into slabs of constant permittivity.

Conventions where the seed is silent (stated in the kind's notes and the README):

* Sources lie on the circle centred on the axis through F, F1, F2; the field angle is the source's
  direction seen from the vertex of surface 1. The image of a source lies on the circle through F',
  F1', F2' at the angle (seen from the vertex of surface 2) that minimises σ.
* σ = sqrt(Σ (L_i − L_0)² / N), N = 100 rays aimed uniformly in y at surface 1 over the aperture,
  L_0 the ray through the vertex (D = 1, so σ is σ/D). Rays leaving the synthesized layers, missing
  surface 2, or past the fold of the aperture map y1 → y2 (where the outermost layer turns them back)
  are dropped; the figures report how many remain.
* Slabs: K bands of equal thickness in |y| (mirrored about the axis), εr_k = the mean of n²(y) over the
  band; the band boundaries are reported beside the synthesis layers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from antenna_cad.raytrace.snell import refract
from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.graded import LeavesMedium, Medium, Ray
from antenna_cad.synthesis.graded_lens import Construction, GradedParams, scalar_spline, surface_spline

N_RAYS = 100
SIDE_FOCUS_LIMIT = 1e-5     # σ at the side foci through the interpolated surfaces (construction exact)
COMPARISON_BIFOCAL = dict(n=1.6, a0=-0.3333, a2=1.2939, h1=0.0441, b0=0.3333, b2=-1.2939, h2=0.0441,
                          rho1=0.6667, rho2=0.6667)          # seed-001 §3.1 lens 1 (symmetric focal curves)


@dataclass(frozen=True)
class GradedDesign:
    params: GradedParams
    unit_mm: float
    medium: Medium                  # the synthesized layers (rays above them are dropped)
    layers: tuple[tuple[float, float, float], ...]     # (lo, hi, m_i) of the synthesis layers (normalised)
    x1: object                      # surface splines x(y), normalised
    x2: object
    half_aperture: float            # reached (normalised)
    foci: dict[str, np.ndarray]
    angle_deg: np.ndarray
    sigma: np.ndarray
    comparison_angle_deg: np.ndarray
    comparison_sigma: np.ndarray
    slab_edges: np.ndarray          # |y| boundaries (normalised), K + 1
    slab_eps: np.ndarray            # K
    checks: tuple[Check, ...]

    def n(self, y) -> np.ndarray:
        return self.medium.n(y)


def _circle(p_axis: np.ndarray, p_side: np.ndarray) -> tuple[float, float]:
    """(x_c, R) of the circle centred on the axis through an axial point and a side point."""
    xc = (p_axis[0] ** 2 - p_side[0] ** 2 - p_side[1] ** 2) / (2 * (p_axis[0] - p_side[0]))
    return xc, abs(p_axis[0] - xc)


def _on_circle(xc: float, r: float, vertex: np.ndarray, angle: float, side: float) -> np.ndarray:
    """Point of the circle (x_c, R) on the ray from ``vertex`` at ``angle`` to the axis, going to
    ``side`` (−1: left, +1: right)."""
    u = np.array([side * np.cos(angle), side * np.sin(angle)])
    d = vertex - np.array([xc, 0.0])
    b = float(u @ d)
    return vertex + u * (-b + np.sqrt(b * b - (d @ d - r * r)))


def ray_paths(medium: Medium, x1, x2, half: float, source: np.ndarray, n_rays: int = N_RAYS):
    """Exit points Q_i and paths |S − P_i| + L_i (inside) for rays aimed at y_i on surface 1 (the
    first at the vertex); rays that leave the aperture on surface 2 are dropped. A ray is traced
    to just beyond surface 2's farthest sampled x, not 3 lens units on (two thirds of its layer
    crossings were past the lens); one that has not crossed it there is traced the full way."""
    slope, x2_at = x1.derivative(), scalar_spline(x2)
    x_stop = float(np.max(x2(np.linspace(-half, half, 201)))) + 0.01 * half
    ys = np.concatenate([[0.0], np.linspace(-half, half, n_rays) * (1 - 1e-9)])
    out_q, out_l, out_y = [], [], []
    P = np.stack([x1(ys), ys], -1)                       # entry points, normals, indices, refraction:
    to_p = P - source                                    # all rays at once
    dist = np.linalg.norm(to_p, axis=-1)
    n_in = medium.n(ys)
    V, OK = refract(to_p / dist[:, None], np.stack([np.ones_like(ys), -slope(ys)], -1), 1.0, n_in)
    for y, p, v, ok, n, r in zip(ys.tolist(), P.tolist(), V.tolist(), OK, n_in.tolist(), dist.tolist()):
        if not ok:
            continue
        args = (medium, p[0], y, n * v[0], math.copysign(1.0, v[1]) if v[1] else 1.0)
        try:
            ray = Ray(*args, min(x_stop, p[0] + 3.0))
            if not ray.left and ray.x_end - x2_at(min(max(ray.y_at(ray.x_end), -half), half)) <= 0:
                ray = Ray(*args, p[0] + 3.0)
            x = brentq(lambda t: t - x2_at(min(max(ray.y_at(t), -half), half)), p[0] + 1e-9, ray.x_end,
                       xtol=1e-14)
        except (ValueError, LeavesMedium):
            continue                   # leaves the synthesized layers or misses surface 2
        yq, _, path = ray.at(x)
        if abs(yq) > half * (1 + 1e-9):
            continue
        out_q.append([x, yq])
        out_l.append(r + path)
        out_y.append(y)
    q, lengths = np.array(out_q), np.array(out_l)
    if len(q) < 3:
        return q, lengths
    rising = np.diff(q[1:, 1]) > 0               # the aperture map y1 → y2 must be monotonic: rays past
    run = np.flatnonzero(~rising)                  # its fold (the outermost layer) are dropped
    mid = int(np.argmin(np.abs(np.array(out_y[1:]))))
    lo = run[run < mid].max() + 1 if np.any(run < mid) else 0
    hi = run[run >= mid].min() + 1 if np.any(run >= mid) else len(q) - 1
    keep = np.r_[0, 1 + np.arange(lo, hi)]
    return q[keep], lengths[keep]


def sigma_310(q: np.ndarray, lengths: np.ndarray, image: np.ndarray) -> float:
    total = lengths + np.linalg.norm(q - image, axis=1)
    return float(np.sqrt(np.mean((total[1:] - total[0]) ** 2)))


def sigma_scan(c: Construction, medium: Medium, x1, x2, half: float, half_view_deg: float, count: int):
    """σ (3.10) against the field angle (sources on the object circle, best image on the image circle)."""
    xc, r = _circle(c.F, c.F1)
    xcp, rp = _circle(c.Fp, c.F1p)
    v1, v2 = np.array([float(x1(0.0)), 0.0]), np.array([float(x2(0.0)), 0.0])
    side_in = np.arctan2(c.F1[1], v1[0] - c.F1[0])
    side_out = np.arctan2(c.F1p[1], c.F1p[0] - v2[0])
    angles = np.linspace(-half_view_deg, half_view_deg, count)
    out = []
    for a in np.radians(angles):
        s = _on_circle(xc, r, v1, a, -1.0)
        q, lengths = ray_paths(medium, x1, x2, half, s)
        guess = -a * side_out / side_in          # F1 (below, a > 0) images to F1' (above)
        fit = minimize_scalar(lambda b: sigma_310(q, lengths, _on_circle(xcp, rp, v2, b, 1.0)),
                              bounds=(guess - 0.05, guess + 0.05), method="bounded", options={"xatol": 1e-10})
        out.append(fit.fun)
    return angles, np.array(out)


def _slabs(medium: Medium, half: float, count: int) -> tuple[np.ndarray, np.ndarray]:
    edges = np.linspace(0.0, half, count + 1)
    eps = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        y = np.linspace(lo, hi, 201)
        eps.append(float(np.mean(medium.n(y) ** 2)))
    return edges, np.array(eps)


def synthesize_graded(*, params: GradedParams, unit_mm: float, view_angle_deg: float, slab_count: int,
                      scan_count: int = 21) -> GradedDesign:
    c = Construction(params)
    try:
        c.run()
    except DesignError as exc:
        if "folds back" not in exc.message:
            raise
        fold = exc.message                      # stop at the fold; the aperture reached is checked
    else:
        fold = ""
    half = min(c.surf1[-1].p[1], c.surf2[-1].p[1], params.aperture / 2)
    layers = tuple((float(L.lo), float(min(L.hi, half)), float(L.p if i else -params.m))
                   for i, L in enumerate(c.medium.layers) if L.lo < half)
    medium = c.medium.copy()
    x1, x2 = surface_spline(c.surf1), surface_spline(c.surf2)
    checks = [Check.upper("aperture_reached", params.aperture / 2 - half, 0.02 * params.aperture, "",
                          "half aperture the construction reaches short of D/2 (normalised"
                          + (f"; stopped: {fold}" if fold else "") + ")", warn_margin=0.02 * params.aperture)]
    q, lengths = ray_paths(medium, x1, x2, half, c.F1)
    side = sigma_310(q, lengths, c.F1p) if len(q) > 2 else np.inf
    checks.append(Check.upper("side_focus_sigma", side, SIDE_FOCUS_LIMIT, "",
                              "σ at the design side focus F1 → F1' through the fitted surfaces (exact by construction)"))
    jumps = [abs(medium.n2_at(L.lo - 1e-12) - medium.n2_at(L.lo + 1e-12)) for L in medium.layers[1:]]
    checks.append(Check.upper("index_continuity", max(jumps, default=0.0), 1e-9, "",
                              "n² jump at the layer boundaries (C¹ law (3.11))"))
    n_aperture = medium.n(np.linspace(0, half, 401))
    n_min = float(np.min(n_aperture))
    checks.append(Check("index_above_one", "pass" if n_min >= 1 else "fail", n_min, 1.0, "",
                        f"lowest index in the aperture {n_min:.4f} (≥ 1)"))
    rise = float(np.max(np.diff(n_aperture), initial=0.0))
    checks.append(Check.upper("index_falls_outward", rise, 1e-12, "", "largest rise of n(y) from the axis to the "
                              "edge (the layers' m_i swing in sign; a rising index is their runaway)"))
    _refuse(checks)
    angles, sigma = sigma_scan(c, medium, x1, x2, half, view_angle_deg / 2, scan_count)
    comp_a, comp_s = _bifocal_comparison(view_angle_deg / 2, scan_count)
    edges, eps = _slabs(medium, half, slab_count)
    foci = {"F": c.F, "F1": c.F1, "F2": c.F2, "F'": c.Fp, "F1'": c.F1p, "F2'": c.F2p}
    return GradedDesign(params, unit_mm, medium, layers, x1, x2, half, foci, angles, sigma, comp_a, comp_s,
                        edges, eps, tuple(checks))


REFUSED_BY = {"aperture_reached": "design.m", "side_focus_sigma": "design.y_a", "index_continuity": "design.m",
              "index_above_one": "design.m", "index_falls_outward": "design.m"}


def _refuse(checks: list[Check]) -> None:
    """A failed construction check is a design the seed's synthesis cannot make: refused, naming
    the spec field that moves it (the layer law m for the layers, y_A for the side foci)."""
    for c in checks:
        if c.status == "fail":
            raise DesignError(REFUSED_BY[c.name], f"{c.name}: {c.message}; change m, a2, a4 or y_a")


def _bifocal_comparison(half_view_deg: float, count: int):
    """σ of the seed's homogeneous bifocal lens 1 (§3.1, n = 1.6, D = 1) over the same field — the
    lens the seed compares its trifocal graded lens with (digest §3.2: 20× higher σ)."""
    from antenna_cad.synthesis.bifocal import kinber_focal_circle_rms, kinber_lens
    lens = kinber_lens(**COMPARISON_BIFOCAL)
    angles, rms = kinber_focal_circle_rms(lens, x_axis=-1.008, half_view_deg=half_view_deg, num=count)
    return np.asarray(angles, dtype=float), np.asarray(rms, dtype=float)
