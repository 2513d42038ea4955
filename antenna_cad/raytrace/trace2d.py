"""Exact 2-D (meridional) geometrical-optics trace through a sequence of refracting interfaces.

Frame: points and directions are ``(z, y)`` pairs — z along the optical axis (+Z toward the
antenna under test), y transverse. Every interface is a profile ``z = f(y)`` (a lens face seen
in section), given by a callable and its derivative; the medium *after* the interface has index
``n_after``. Rays are intersected exactly (vectorized Newton on the ray parameter), refracted
with vector Snell (:mod:`antenna_cad.raytrace.snell`, seed-000 §2.7 / §4.2 corrected) and the
optical path ``Σ n·length`` is accumulated. Lengths are in whatever unit the caller uses (mm at
the project's interfaces); the tracer is scale free.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from antenna_cad.raytrace.snell import reflect, refract, transmission

Profile = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Interface:
    """A refracting profile ``z = z_of_y(y)`` followed by a medium of index ``n_after``."""

    z_of_y: Profile
    dz_dy: Profile
    n_after: float
    z_guess: float          # a representative z, used to start the intersection search

    @staticmethod
    def plane(z0: float, n_after: float) -> "Interface":
        return Interface(lambda y: np.full_like(np.asarray(y, float), z0),
                         lambda y: np.zeros_like(np.asarray(y, float)), float(n_after), float(z0))

    @staticmethod
    def from_points(y: np.ndarray, z: np.ndarray, n_after: float,
                    dz_dy: np.ndarray | None = None) -> "Interface":
        """Cubic profile through samples (y strictly increasing): Hermite when slopes are known
        (C¹, 4th-order accurate), else a not-a-knot cubic spline. Extrapolates past the ends."""
        from scipy.interpolate import CubicHermiteSpline, CubicSpline   # at use: validate needs no spline
        y = np.asarray(y, float)
        z = np.asarray(z, float)
        spl = (CubicHermiteSpline(y, z, np.asarray(dz_dy, float)) if dz_dy is not None
               else CubicSpline(y, z))
        der = spl.derivative()
        return Interface(lambda q: spl(np.asarray(q, float)), lambda q: der(np.asarray(q, float)),
                         float(n_after), float(np.median(z)))


@dataclass(frozen=True)
class Trace2D:
    """Result of :func:`trace`. ``points[k]`` is where the rays are after interface k (``points[0]``
    are the origins; the last entry is the target plane when one was given). ``directions[k]`` is
    the unit direction leaving ``points[k]``. ``opl`` is the optical path from the origin to the
    last point. ``ok`` is False for rays that missed an interface, were totally reflected, or went
    backwards. ``index[k]`` is the refractive index along the segment ``points[k] → points[k+1]``.
    ``riser[i]`` (stepped sections only): ray i was refracted or reflected at a riser."""

    points: np.ndarray        # (K+1[+1], N, 2)  (z, y)
    directions: np.ndarray    # (K+1[+1], N, 2)
    opl: np.ndarray           # (N,)
    ok: np.ndarray            # (N,) bool
    index: np.ndarray | None = None   # (K[+1], N)
    riser: np.ndarray | None = None   # (N,) bool


def aim_at_face(face: Interface, feed: np.ndarray, half_width_mm: float, rays: int) -> np.ndarray:
    """Unit directions from ``feed`` to ``rays`` points of ``face`` spread uniformly over |y| ≤ half_width."""
    y = np.linspace(-half_width_mm, half_width_mm, rays)
    v = np.stack([face.z_of_y(y), y], -1) - np.asarray(feed, float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def intersect(origins: np.ndarray, directions: np.ndarray, surf: Interface,
              tol: float = 1e-12, max_iter: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """Ray parameter t ≥ 0 where ``origin + t·direction`` meets ``z = f(y)``; returns (t, ok)."""
    p = np.asarray(origins, float)
    d = np.asarray(directions, float)
    scale = max(1.0, float(np.max(np.abs(p))) if p.size else 1.0, abs(surf.z_guess))
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (surf.z_guess - p[:, 0]) / d[:, 0]
    t = np.where(np.isfinite(t), t, 0.0)
    for _ in range(max_iter):
        y = p[:, 1] + t * d[:, 1]
        g = p[:, 0] + t * d[:, 0] - surf.z_of_y(y)
        dg = d[:, 0] - surf.dz_dy(y) * d[:, 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(np.abs(dg) > 1e-14, g / dg, 0.0)
        t = t - step
        if np.all(np.abs(step) <= tol * scale):
            break
    y = p[:, 1] + t * d[:, 1]
    g = p[:, 0] + t * d[:, 0] - surf.z_of_y(y)
    ok = np.isfinite(t) & (np.abs(g) <= 1e3 * tol * scale) & (t >= -tol * scale)
    return t, ok


def trace(origins: np.ndarray, directions: np.ndarray, interfaces: list[Interface] | tuple,
          n_start: float = 1.0, z_target: float | None = None) -> Trace2D:
    """Trace rays through ``interfaces`` in order, then (optionally) straight on to the plane
    ``z = z_target`` in the last medium. All arrays are ``(N, 2)`` in (z, y)."""
    p = np.array(origins, float, ndmin=2)
    d = np.array(directions, float, ndmin=2)
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    n_cur = float(n_start)
    opl = np.zeros(len(p))
    ok = np.ones(len(p), bool)
    pts, dirs, index = [p.copy()], [d.copy()], [n_cur]
    for surf in interfaces:
        t, hit = intersect(p, d, surf)
        ok &= hit
        p = p + t[:, None] * d
        opl = opl + n_cur * t
        normal = np.stack([np.ones(len(p)), -surf.dz_dy(p[:, 1])], axis=-1)
        d, no_tir = refract(d, normal, n_cur, surf.n_after)
        ok &= no_tir
        n_cur = surf.n_after
        pts.append(p.copy())
        dirs.append(d.copy())
        index.append(n_cur)
    if z_target is not None:
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (z_target - p[:, 0]) / d[:, 0]
        ok &= np.isfinite(t) & (t >= 0.0)
        p = p + t[:, None] * d
        opl = opl + n_cur * t
        pts.append(p.copy())
        dirs.append(d.copy())
    ok &= np.isfinite(opl)
    index = np.broadcast_to(np.array(index[:len(pts) - 1])[:, None], (len(pts) - 1, len(p)))
    return Trace2D(np.array(pts), np.array(dirs), opl, ok, index)


@dataclass(frozen=True)
class Slabs:
    """A stepped section: slab k spans ``z_edges[k] ≤ z ≤ z_edges[k+1]`` (a sheet); within it the
    cell between ``y_breaks[j−1]`` and ``y_breaks[j]`` (j = 0 … M, open at both ends) is dielectric of
    index ``n`` where ``material[k, j]``, air elsewhere. Faces are planes z = const (sheet faces)
    and y = const (risers, the cut edges of the sheets)."""

    z_edges: np.ndarray       # (K+1,) increasing
    y_breaks: np.ndarray      # (M,) increasing
    material: np.ndarray      # (K, M+1) bool
    n: float

    @staticmethod
    def from_intervals(z_edges, intervals, n: float) -> "Slabs":
        """Slab k is dielectric on the y-intervals ``intervals[k]`` (a list of (lo, hi) pairs)."""
        breaks = np.unique([y for slab in intervals for iv in slab for y in iv])
        mid = np.concatenate([[breaks[0] - 1.0], (breaks[:-1] + breaks[1:]) / 2, [breaks[-1] + 1.0]])
        material = np.zeros((len(intervals), len(mid)), bool)
        for k, slab in enumerate(intervals):
            for lo, hi in slab:
                material[k] |= (lo < mid) & (mid < hi)
        return Slabs(np.asarray(z_edges, float), breaks, material, float(n))


def trace_slabs(origins: np.ndarray, directions: np.ndarray, slabs: Slabs, z_target: float,
                n_outside: float = 1.0) -> Trace2D:
    """Exact trace through a :class:`Slabs` section, then on to the plane ``z = z_target``.

    Rays start in front of the first slab. Every crossing of a sheet face or a riser is an event:
    the ray refracts by vector Snell into the next cell, or is mirror-reflected and stays in its cell
    where it is totally internally reflected (grazing hits on a riser from inside a sheet). A ray is
    ``ok`` when it leaves through the back face ``z_edges[-1]``; ``riser`` marks the rays refracted or
    reflected at a riser. All rays advance one event per step.
    """
    p0 = np.array(origins, float, ndmin=2)
    d = np.array(directions, float, ndmin=2)
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    K, M = slabs.material.shape[0], len(slabs.y_breaks)
    z_edges, y_ext = slabs.z_edges, np.concatenate([[-np.inf], slabs.y_breaks, [np.inf]])
    t = (z_edges[0] - p0[:, 0]) / d[:, 0]
    p, opl = p0 + t[:, None] * d, n_outside * t
    n_cur = np.full(len(p), float(n_outside))
    k, j = np.full(len(p), -1), np.searchsorted(slabs.y_breaks, p[:, 1])
    k_next, j_next = np.zeros(len(p), int), j.copy()          # at the front face, entering slab 0
    pts, dirs, index = [p0, p.copy()], [d.copy()], [n_cur.copy()]
    axis_z, axis_y = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    normal = np.tile(axis_z, (len(p), 1))
    active = np.ones(len(p), bool)
    riser = np.zeros(len(p), bool)
    for _ in range(4 * (K + M) + 16):
        enter = (k_next >= 0) & (k_next < K)
        n_new = np.where(enter & slabs.material[np.clip(k_next, 0, K - 1), np.clip(j_next, 0, M)],
                         slabs.n, n_outside)
        d_new, ok = refract(d, normal, n_cur, n_new)
        go, tir = active & ok, active & ~ok
        riser |= (tir | (go & (n_new != n_cur))) & (normal[:, 1] != 0)
        d = np.where(go[:, None], d_new, np.where(tir[:, None], reflect(d, normal), d))
        k, j, n_cur = np.where(go, k_next, k), np.where(go, j_next, j), np.where(go, n_new, n_cur)
        active &= (k >= 0) & (k < K)
        if not active.any():
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            tz = (np.where(d[:, 0] > 0, z_edges[np.clip(k + 1, 0, K)], z_edges[np.clip(k, 0, K)]) - p[:, 0]) / d[:, 0]
            ty = (np.where(d[:, 1] > 0, y_ext[j + 1], y_ext[j]) - p[:, 1]) / d[:, 1]
        tz, ty = np.where(d[:, 0] != 0, tz, np.inf), np.where(d[:, 1] != 0, ty, np.inf)
        cross_z = tz <= ty
        step = np.where(active, np.minimum(tz, ty), 0.0)
        dirs.append(d.copy())
        index.append(n_cur.copy())
        p = p + step[:, None] * d
        opl = opl + n_cur * step
        pts.append(p.copy())
        k_next = k + np.where(cross_z, np.sign(d[:, 0]), 0).astype(int)
        j_next = j + np.where(cross_z, 0, np.sign(d[:, 1])).astype(int)
        normal = np.where(cross_z[:, None], axis_z, axis_y)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (z_target - p[:, 0]) / d[:, 0]
    ok = ~active & (k >= K) & np.isfinite(t) & (t >= 0.0)
    t = np.where(ok, t, 0.0)
    dirs.append(d.copy())
    index.append(n_cur.copy())
    pts.append(p + t[:, None] * d)
    dirs.append(d.copy())
    return Trace2D(np.array(pts), np.array(dirs), opl + n_cur * t, ok, np.array(index), riser)


def transmitted_amplitude(tr: Trace2D, wavelength_mm: float, tan_delta: float,
                          polarisation: str = "perp") -> np.ndarray:
    """Field amplitude of each ray at its last point for a unit amplitude at the feed, seed-000 §4.4:
    the product of the Fresnel transmission coefficients (2.20)–(2.22) at every index change and the
    dielectric loss exp(−α·l), α = π·n·tanδ/λ0 (2.25), along every segment inside a dielectric.
    Totally reflected rays keep their amplitude. As in the seed, no ray-tube spreading factor."""
    n_a, n_b = tr.index[:-1], tr.index[1:]
    d_a, d_b = tr.directions[:-2], tr.directions[1:-1]
    change = n_a != n_b
    with np.errstate(invalid="ignore"):
        normal = n_a[..., None] * d_a - n_b[..., None] * d_b
        normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
        cos_i = np.abs(np.sum(d_a * normal, -1))
        cos_t = np.abs(np.sum(d_b * normal, -1))
        tau = np.where(change, transmission(cos_i, cos_t, n_a, n_b, polarisation), 1.0)
    length = np.linalg.norm(np.diff(tr.points, axis=0), axis=-1)
    loss = np.pi * tan_delta / wavelength_mm * np.sum(np.where(tr.index > 1.0, tr.index * length, 0.0), axis=0)
    return np.prod(tau, axis=0) * np.exp(-loss)
