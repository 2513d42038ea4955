"""GO rays through a spherically (or cylindrically) symmetric graded index, 2-D, vectorized.

The ray equation in the optical parameter τ (ds = n dτ): dX/dτ = P, dP/dτ = ∇(n²/2), with
|P| = n, and optical path dL/dτ = n² (Born & Wolf §3.2). For n² = ε(r²) the force is
ε'(r²)·X. Rays go straight from their origins to the sphere r = R, refract there (vector Snell,
seed-000 §2.7) into the graded medium, are integrated with classical RK4 at a fixed step, and
leave where r crosses R again: the crossing is located on the cubic Hermite interpolant of the
last step (4th order, like the steps), where they refract back into air. This is the continuous
law of seed-002 §2.1 traced as it stands, independently of the Abel inversion that built it.
Frame: ``(z, y)`` pairs as :mod:`antenna_cad.raytrace.trace2d`.
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


def trace_graded(eps_of_r2: EpsOfR2, radius: float, origins: np.ndarray, directions: np.ndarray,
                 steps_per_radius: int = 400, keep_every: int = 8) -> MediaTrace:
    """Trace rays through the graded sphere r < ``radius`` (ε = 1 outside). ``points`` keeps the
    origin, entry, every ``keep_every``-th step and the exit (for drawing the ray fan)."""
    X = np.array(origins, float, ndmin=2)
    d = np.array(directions, float, ndmin=2)
    d = d / np.linalg.norm(d, axis=1, keepdims=True)
    R2 = radius * radius
    N = len(X)
    opl = np.zeros(N)
    pts = [X.copy()]
    b = np.sum(X * d, axis=1)
    c = np.sum(X * X, axis=1) - R2
    disc = b * b - c
    outside = c > 0
    t_in = np.where(outside, -b - np.sqrt(np.maximum(disc, 0.0)), 0.0)
    enters = ~outside | ((disc > 0) & (t_in > 0))
    X = X + np.where(enters, t_in, 0.0)[:, None] * d
    opl += np.where(enters, t_in, 0.0)
    eps0, _ = eps_of_r2(np.minimum(np.sum(X * X, axis=1), R2))
    n_in = np.sqrt(eps0)
    d_in, ok_in = refract(d, np.where(outside[:, None], X, d), 1.0, np.where(outside, n_in, 1.0))
    d = np.where(outside[:, None], d_in, d)
    P = d * n_in[:, None]
    active = enters & ok_in
    pts.append(X.copy())
    h = radius / steps_per_radius

    def force(x):
        e, de = eps_of_r2(np.sum(x * x, axis=1))
        return de[:, None] * x, e

    exit_d = d.copy()
    for step in range(40 * steps_per_radius):
        if not active.any():
            break
        idx = np.flatnonzero(active)
        x0, p0 = X[idx], P[idx]
        # classical RK4 on (X, P, L): dX = P, dP = ε'(r²)·X, dL = ε (all per dτ)
        f1, e1 = force(x0)
        f2, e2 = force(x0 + 0.5 * h * p0)
        f3, e3 = force(x0 + 0.5 * h * (p0 + 0.5 * h * f1))
        f4, e4 = force(x0 + h * (p0 + 0.5 * h * f2))
        x1 = x0 + h / 6 * (p0 + 2 * (p0 + 0.5 * h * f1) + 2 * (p0 + 0.5 * h * f2) + (p0 + h * f3))
        p1 = p0 + h / 6 * (f1 + 2 * f2 + 2 * f3 + f4)
        out = (np.sum(x1 * x1, axis=1) >= R2) & (np.sum(x1 * p1, axis=1) > 0)
        stay = idx[~out]
        X[stay], P[stay] = x1[~out], p1[~out]
        opl[stay] += (h / 6 * (e1 + 2 * e2 + 2 * e3 + e4))[~out]
        if out.any():
            leave = idx[out]
            s_ = _exit_parameter(x0[out], p0[out], x1[out], p1[out], h, R2)
            xe, pe = _hermite(x0[out], p0[out], x1[out], p1[out], h, s_)
            xm, _ = _hermite(x0[out], p0[out], x1[out], p1[out], h, 0.5 * s_)
            e_exit = eps_of_r2(np.full(len(s_), R2))[0]
            opl[leave] += s_ / 6 * (e1[out] + 4 * eps_of_r2(np.sum(xm * xm, axis=1))[0] + e_exit)   # Simpson
            X[leave] = xe * (radius / np.linalg.norm(xe, axis=1, keepdims=True))
            dn, ok = refract(pe / np.linalg.norm(pe, axis=1, keepdims=True), X[leave], np.sqrt(e_exit), 1.0)
            exit_d[leave] = np.where(ok[:, None], dn, np.nan)
            active[leave] = False
        if step % keep_every == 0 or not active.any():
            pts.append(X.copy())
    pts.append(X.copy())
    left = enters & ok_in & ~active & np.all(np.isfinite(exit_d), axis=1)
    return MediaTrace(np.array(pts), np.where(enters[:, None], exit_d, d), opl, left | ~enters, np.zeros(N, int),
                      X.copy(), opl.copy())


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
