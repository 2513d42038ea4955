"""GO rays through a spherically (or cylindrically) symmetric graded index, 2-D, vectorized.

The ray equation in the optical parameter τ (ds = n dτ): dX/dτ = P, dP/dτ = ∇(n²/2), with
|P| = n, and optical path dL/dτ = n² (Born & Wolf §3.2). For n² = ε(r²) the force is
ε'(r²)·X. The lens is a graded core r < ``core_mm`` inside an optional homogeneous shell
core_mm ≤ r < R of permittivity ``shell_eps`` (the outer-shell law of seed-002 §2.1). ε(r²) must
continue smoothly a little past the core: RK4 samples there inside the step that leaves it. Rays go straight in
air and in the shell, refract at r = R and r = core_mm (vector Snell, seed-000 §2.7), and are
integrated in the core with classical RK4 at a fixed step; a step that leaves the core is cut at
the crossing, located on the cubic Hermite interpolant of the step (4th order, like the steps).
This is the continuous law traced as it stands, independently of the Abel inversion that built
it. Frame: ``(z, y)`` pairs as :mod:`antenna_cad.raytrace.trace2d`.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from antenna_cad.raytrace.media import MediaTrace
from antenna_cad.raytrace.snell import refract

EpsOfR2 = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]   # r² -> (ε, dε/d(r²))


def _hermite(x0, v0, x1, v1, h, s):
    """Cubic Hermite through (x0, v0) at 0 and (x1, v1) at h, evaluated at s (value, slope)."""
    u = (s / h)[:, None]
    h00, h10, h01, h11 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u, -2 * u**3 + 3 * u**2, u**3 - u**2
    d00, d10, d01, d11 = (6 * u**2 - 6 * u) / h, 3 * u**2 - 4 * u + 1, (-6 * u**2 + 6 * u) / h, 3 * u**2 - 2 * u
    return h00 * x0 + h10 * h * v0 + h01 * x1 + h11 * h * v1, d00 * x0 + d10 * v0 + d01 * x1 + d11 * v1


def _line_circle(p, d, r):
    """Parameters (near, far) where p + t·d meets the circle of radius r (NaN: no meeting)."""
    b = np.sum(p * d, axis=1)
    disc = b * b - (np.sum(p * p, axis=1) - r * r)
    root = np.sqrt(np.where(disc >= 0, disc, np.nan))
    return -b - root, -b + root


def trace_graded(eps_of_r2: EpsOfR2, radius: float, origins: np.ndarray, directions: np.ndarray,
                 steps_per_radius: int = 400, keep_every: int = 8, core_mm: float | None = None,
                 shell_eps: float = 1.0) -> MediaTrace:
    """Trace rays through the lens r < ``radius`` (ε = 1 outside). ``points`` keeps the origin,
    the boundary crossings and every ``keep_every``-th RK4 step (for drawing the ray fan)."""
    X = np.array(origins, float, ndmin=2)
    d = np.array(directions, float, ndmin=2)
    d = d / np.linalg.norm(d, axis=1, keepdims=True)
    core = radius if core_mm is None else float(core_mm)
    C2, R2 = core * core, radius * radius
    n_shell = float(np.sqrt(shell_eps))
    N = len(X)
    r2 = np.sum(X * X, axis=1)
    region = np.where(r2 < C2, 2, np.where(r2 < R2, 1, 0))       # 0 air, 1 shell, 2 graded core
    n = np.where(region == 2, np.sqrt(eps_of_r2(np.minimum(r2, C2))[0]), np.where(region == 1, n_shell, 1.0))
    P = d * n[:, None]
    opl = np.zeros(N)
    active = np.ones(N, bool)
    entered = region > 0
    exit_zy, exit_opl = X.copy(), opl.copy()
    pts = [X.copy()]
    h = radius / steps_per_radius

    def force(x):
        e, de = eps_of_r2(np.sum(x * x, axis=1))
        return de[:, None] * x, e

    def cross(i, normal, n_to):
        """Refract rays ``i`` at their points (normal ``normal``) into index ``n_to``."""
        n_from = np.linalg.norm(P[i], axis=1)
        n_to = np.broadcast_to(np.asarray(n_to, float), n_from.shape)
        t, ok = refract(P[i] / n_from[:, None], normal, n_from, n_to)
        active[i[~ok]] = False
        P[i[ok]] = t[ok] * n_to[ok, None]
        return ok

    for step in range(40 * steps_per_radius):
        if not active.any():
            break
        moved = False
        for zone in (0, 1):                                          # straight hops in air and the shell
            i = np.flatnonzero(active & (region == zone))
            if not i.size:
                continue
            moved = True
            dd = P[i] / np.linalg.norm(P[i], axis=1, keepdims=True)
            near_r, far_r = _line_circle(X[i], dd, radius)
            near_c, _ = _line_circle(X[i], dd, core)
            if zone == 0:                                            # air: to the lens (a feed on it: t = 0)
                t = np.where(entered[i] | ~(near_r > -1e-9 * radius), np.nan, np.maximum(near_r, 0.0))
            else:                                                    # shell: to the core or out at R
                t = np.where(near_c > 1e-12 * radius, near_c, far_r)
            hit = np.isfinite(t) & (t >= 0)
            active[i[~hit]] = False
            i, t, dd = i[hit], t[hit], dd[hit]
            X[i] = X[i] + t[:, None] * dd
            opl[i] += t * np.linalg.norm(P[i], axis=1)
            normal = X[i] / np.linalg.norm(X[i], axis=1, keepdims=True)
            inward = np.sum(X[i] * dd, axis=1) < 0
            if zone == 0:
                to = np.where(core < radius, n_shell, np.sqrt(eps_of_r2(np.full(len(i), R2))[0]))
                ok = cross(i, normal, to)
                region[i[ok]] = np.where(core < radius, 1, 2)
                entered[i] = True
            else:
                to_core = inward & (np.abs(np.sum(X[i] ** 2, axis=1) - C2) < 1e-6 * C2)
                n_to = np.where(to_core, np.sqrt(eps_of_r2(np.full(len(i), C2))[0]), 1.0)
                ok = cross(i, normal, n_to)
                region[i[ok]] = np.where(to_core[ok], 2, 0)
                out = i[ok & ~to_core]
                exit_zy[out], exit_opl[out] = X[out], opl[out]
        i = np.flatnonzero(active & (region == 2))
        if i.size:
            moved = True
            x0, p0 = X[i], P[i]
            # classical RK4 on (X, P, L): dX = P, dP = ε'(r²)·X, dL = ε (all per dτ)
            f1, e1 = force(x0)
            f2, e2 = force(x0 + 0.5 * h * p0)
            f3, e3 = force(x0 + 0.5 * h * (p0 + 0.5 * h * f1))
            f4, e4 = force(x0 + h * (p0 + 0.5 * h * f2))
            x1 = x0 + h / 6 * (p0 + 2 * (p0 + 0.5 * h * f1) + 2 * (p0 + 0.5 * h * f2) + (p0 + h * f3))
            p1 = p0 + h / 6 * (f1 + 2 * f2 + 2 * f3 + f4)
            out = (np.sum(x1 * x1, axis=1) >= C2) & (np.sum(x1 * p1, axis=1) > 0)
            stay = i[~out]
            X[stay], P[stay] = x1[~out], p1[~out]
            opl[stay] += (h / 6 * (e1 + 2 * e2 + 2 * e3 + e4))[~out]
            if out.any():
                leave = i[out]
                s = _exit_parameter(x0[out], p0[out], x1[out], p1[out], h, C2)
                xe, pe = _hermite(x0[out], p0[out], x1[out], p1[out], h, s)
                xm, _ = _hermite(x0[out], p0[out], x1[out], p1[out], h, 0.5 * s)
                e_edge = eps_of_r2(np.full(len(s), C2))[0]
                opl[leave] += s / 6 * (e1[out] + 4 * eps_of_r2(np.sum(xm * xm, axis=1))[0] + e_edge)   # Simpson
                X[leave] = xe * (core / np.linalg.norm(xe, axis=1, keepdims=True))
                P[leave] = pe
                ok = cross(leave, X[leave] / core, n_shell if core < radius else 1.0)
                region[leave[ok]] = 1 if core < radius else 0
                if core >= radius:
                    exit_zy[leave[ok]], exit_opl[leave[ok]] = X[leave[ok]], opl[leave[ok]]
        if moved and (step % keep_every == 0 or not (active & (region == 2)).any()):
            pts.append(X.copy())
    pts.append(X.copy())
    left = entered & (region == 0) & np.isfinite(exit_opl)
    direction = P / np.linalg.norm(P, axis=1, keepdims=True)
    return MediaTrace(np.array(pts), direction, opl, left | ~entered, exit_zy, exit_opl)


def _exit_parameter(x0, p0, x1, p1, h, R2):
    """τ in (0, h] where the Hermite step crosses r² = R² (Newton from the linear guess)."""
    r0, r1 = np.sum(x0 * x0, axis=1), np.sum(x1 * x1, axis=1)
    s = h * np.clip((R2 - r0) / np.where(r1 > r0, r1 - r0, 1.0), 0.0, 1.0)
    for _ in range(8):
        x, v = _hermite(x0, p0, x1, p1, h, s)
        g = np.sum(x * x, axis=1) - R2
        dg = 2 * np.sum(x * v, axis=1)
        s = np.clip(s - g / np.where(np.abs(dg) > 1e-300, dg, 1.0), 0.0, h)
    return s
