"""The closed-form steps shared by the bifocal constructions (seed-000 §2.7 vector Snell; seed-001
§3.1 (3.2)–(3.9)): one feed's eikonal record, the forward step surface 1 → surface 2, the backward
step surface 2 → surface 1, and the even Hermite profiles through the constructed points.

Frame and units: those of :mod:`antenna_cad.synthesis.bifocal` (points stored as (z, y) rows; the
Kinber lens uses the same rows in the seed's normalised frame, :mod:`antenna_cad.synthesis.kinber`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from antenna_cad.raytrace.snell import refract



def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _mirror(p: np.ndarray) -> np.ndarray:
    return p * np.array([1.0, -1.0])


@dataclass(frozen=True)
class _Optics:
    """One feed F (left), its conjugate (plane direction k, or image point Fp), index n and the
    eikonal constant L: ``|F−P| + n|PQ| + e(Q) = L`` with ``e(Q) = −k·Q`` (plane) or ``|Fp−Q|``."""

    F: np.ndarray
    n: float
    L: float
    k: np.ndarray | None = None
    Fp: np.ndarray | None = None

    def exit_dir(self, Q: np.ndarray) -> np.ndarray:
        return np.broadcast_to(self.k, Q.shape) if self.k is not None else _unit(self.Fp - Q)

    def e(self, Q: np.ndarray) -> np.ndarray:
        return -(Q @ self.k) if self.k is not None else np.linalg.norm(self.Fp - Q, axis=-1)


def _smallest_positive_root(A: float, B: np.ndarray, C: np.ndarray, budget: np.ndarray,
                            n: float) -> np.ndarray:
    """Root s > 0 of ``A s² + 2B s + C = 0`` with ``budget − n s > 0`` (NaN if none)."""
    disc = B**2 - A * C
    sq = np.sqrt(np.where(disc >= 0.0, disc, np.nan))
    q = -(B + np.copysign(sq, B))
    with np.errstate(divide="ignore", invalid="ignore"):
        r1, r2 = q / A, C / q
    good = lambda r: np.isfinite(r) & (r > 0.0) & (budget - n * r > 0.0)  # noqa: E731
    r1 = np.where(good(r1), r1, np.inf)
    r2 = np.where(good(r2), r2, np.inf)
    r = np.minimum(r1, r2)
    return np.where(np.isfinite(r), r, np.nan)


def _fwd(P: np.ndarray, NP: np.ndarray, o: _Optics) -> tuple[np.ndarray, np.ndarray]:
    """Ray F→P (surface 1, normal NP) refracted into the lens → exit point Q on surface 2 and the
    surface-2 normal there (∥ n·v − w). Plane exit: t linear (seed-000 §2.7 step 2); point exit:
    quadratic (seed-001 (3.4)–(3.5))."""
    d = _unit(P - o.F)
    v, ok = refract(d, NP, 1.0, o.n)
    r1 = np.linalg.norm(P - o.F, axis=-1)
    if o.k is not None:
        t = (o.L - r1 + P @ o.k) / (o.n - v @ o.k)
    else:
        w0 = o.Fp - P
        R0 = o.L - r1
        t = _smallest_positive_root(1.0 - o.n**2, o.n * R0 - np.sum(v * w0, -1),
                                    np.sum(w0 * w0, -1) - R0**2, R0, o.n)
    t = np.where(ok & (t > 0.0), t, np.nan)
    Q = P + t[:, None] * v
    NQ = _unit(o.n * v - o.exit_dir(Q))
    return Q, NQ


def _back(Q: np.ndarray, NQ: np.ndarray, o: _Optics) -> tuple[np.ndarray, np.ndarray]:
    """Inverse step: from a surface-2 point Q (normal NQ) trace the conjugate ray backwards into the
    lens and find the surface-1 point P with the same eikonal (seed-000 §2.7 step 3, quadratic
    ``(1−n²)s² + 2(w·d_b + nK)s + |w|² − K² = 0``; seed-001 (3.8)–(3.9))."""
    vb, ok = refract(-o.exit_dir(Q), NQ, 1.0, o.n)
    K = o.L - o.e(Q)
    w = Q - o.F
    s = _smallest_positive_root(1.0 - o.n**2, np.sum(w * vb, -1) + o.n * K, np.sum(w * w, -1) - K**2,
                                K, o.n)
    s = np.where(ok, s, np.nan)
    P = Q + s[:, None] * vb
    NP = _unit(_unit(P - o.F) + o.n * vb)          # ∥ d − n·v with v = −vb
    return P, NP


def _slopes(N: np.ndarray) -> np.ndarray:
    """dz/dy of a profile z = f(y) from its normal (N ∥ (1, −f'))."""
    return -N[:, 1] / N[:, 0]


def _symmetric_profile(pts: np.ndarray, nrm: np.ndarray, y_max: float | None = None
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Fold points to y ≥ 0, mirror to a full even profile, sort, drop duplicates.
    Returns (y, z, dz/dy) arrays, strictly increasing y."""
    y = pts[:, 1].copy()
    z = pts[:, 0].copy()
    sl = _slopes(nrm)
    neg = y < 0
    y[neg], sl[neg] = -y[neg], -sl[neg]
    keep = np.isfinite(y) & np.isfinite(z) & np.isfinite(sl)
    if y_max is not None:
        keep &= y <= y_max
    y, z, sl = y[keep], z[keep], sl[keep]
    order = np.argsort(y)
    y, z, sl = y[order], z[order], sl[order]
    uniq = np.concatenate([[True], np.diff(y) > 1e-9 * max(1.0, float(y[-1]) if len(y) else 1.0)])
    y, z, sl = y[uniq], z[uniq], sl[uniq]
    if y[0] <= 1e-12 * max(1.0, y[-1]):
        y0, z0, s0 = y[:1] * 0.0, z[:1], sl[:1] * 0.0
        y, z, sl = y[1:], z[1:], sl[1:]
        return (np.concatenate([-y[::-1], y0, y]), np.concatenate([z[::-1], z0, z]),
                np.concatenate([-sl[::-1], s0, sl]))
    return np.concatenate([-y[::-1], y]), np.concatenate([z[::-1], z]), np.concatenate([-sl[::-1], sl])


def _hermite(y: np.ndarray, z: np.ndarray, sl: np.ndarray) -> CubicHermiteSpline:
    return CubicHermiteSpline(y, z, sl)


# --- the same steps for one point on floats (the Nikulina chain's inner loop: a point at a time) ---

def _unit1(x: float, y: float) -> tuple[float, float]:
    r = math.sqrt(x * x + y * y)
    return x / r, y / r


def _refract1(d, nrm, eta: float):
    """:func:`antenna_cad.raytrace.snell.refract` of one unit direction, floats (NaN on TIR)."""
    d, nrm = _unit1(*d), _unit1(*nrm)
    cos_i = -(d[0] * nrm[0] + d[1] * nrm[1])
    if cos_i < 0.0:
        nrm, cos_i = (-nrm[0], -nrm[1]), -cos_i
    k = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
    a = eta * cos_i - (math.sqrt(k) if k >= 0.0 else math.nan)
    return eta * d[0] + a * nrm[0], eta * d[1] + a * nrm[1]


def _root1(A: float, B: float, C: float, budget: float, n: float) -> float:
    """:func:`_smallest_positive_root` for one equation."""
    disc = B * B - A * C
    q = -(B + math.copysign(math.sqrt(disc), B)) if disc >= 0.0 else math.nan
    roots = [q / A, C / q if q != 0.0 else math.nan]
    good = [r for r in roots if math.isfinite(r) and r > 0.0 and budget - n * r > 0.0]
    return min(good) if good else math.nan


def _fwd_plane1(P, NP, o: _Optics):
    """:func:`_fwd` for one point and a plane exit (k), floats."""
    F, k, n = o.F, o.k, o.n
    v = _refract1((P[0] - F[0], P[1] - F[1]), NP, 1.0 / n)
    r1 = math.sqrt((P[0] - F[0]) * (P[0] - F[0]) + (P[1] - F[1]) * (P[1] - F[1]))
    t = (o.L - r1 + (P[0] * k[0] + P[1] * k[1])) / (n - (v[0] * k[0] + v[1] * k[1]))
    t = t if t > 0.0 else math.nan
    return (P[0] + t * v[0], P[1] + t * v[1]), _unit1(n * v[0] - k[0], n * v[1] - k[1])


def _back_plane1(Q, NQ, o: _Optics):
    """:func:`_back` for one point and a plane exit (k), floats."""
    F, k, n = o.F, o.k, o.n
    vb = _refract1((-k[0], -k[1]), NQ, 1.0 / n)
    K = o.L + (Q[0] * k[0] + Q[1] * k[1])
    w = (Q[0] - F[0], Q[1] - F[1])
    s = _root1(1.0 - n * n, w[0] * vb[0] + w[1] * vb[1] + n * K, w[0] * w[0] + w[1] * w[1] - K * K, K, n)
    P = (Q[0] + s * vb[0], Q[1] + s * vb[1])
    d = _unit1(P[0] - F[0], P[1] - F[1])
    return P, _unit1(d[0] + n * vb[0], d[1] + n * vb[1])
