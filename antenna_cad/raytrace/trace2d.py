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
from scipy.interpolate import CubicHermiteSpline, CubicSpline

from antenna_cad.raytrace.snell import refract

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
    backwards."""

    points: np.ndarray        # (K+1[+1], N, 2)  (z, y)
    directions: np.ndarray    # (K+1[+1], N, 2)
    opl: np.ndarray           # (N,)
    ok: np.ndarray            # (N,) bool


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
    pts, dirs = [p.copy()], [d.copy()]
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
    if z_target is not None:
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (z_target - p[:, 0]) / d[:, 0]
        ok &= np.isfinite(t) & (t >= 0.0)
        p = p + t[:, None] * d
        opl = opl + n_cur * t
        pts.append(p.copy())
        dirs.append(d.copy())
    ok &= np.isfinite(opl)
    return Trace2D(np.array(pts), np.array(dirs), opl, ok)
