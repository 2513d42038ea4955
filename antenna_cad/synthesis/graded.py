"""Layered graded-index medium n²(y) of seed-001 §3.2 and exact ray paths through it.

Frame (seed-001 Ch.3): **x** the lens axis (left → right), **y** transverse; the index depends on
|y| only. Layer 0 (|y| ≤ h_0): n² = n0² − m y² (3.11); layer i ≥ 1 (h_{i−1} ≤ |y| ≤ h_i):
n² = no_i² + q_i u + m_i u², u = |y| − h_{i−1}, with n² and dn²/dy continuous at h_{i−1} (C¹, the seed's
continuity rule). Every layer here has m_i < 0, so n² = N − k (w − c)² with k = −m_i > 0, w = |y|
(w = y in layer 0): a ray is an exact sinusoid w − c = Y sin ψ, x = x_ref + (a/√k) ψ,
Y² = (N − a²)/k, with the ray invariant a = n cos(angle to x) conserved (digest §3.2). The optical
path over dψ is a dx + √k Y² cos²ψ dψ — the digest's corrected layer integrals
(ΔL = a Δx + ∫ sqrt(n² − a²) dy) in closed form, replacing the garbled (3.28)–(3.29).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

TWO_PI = 2 * np.pi


class LeavesMedium(Exception):
    """A ray reached the top of the known layers (the construction must add a layer first)."""


@dataclass
class Layer:
    lo: float           # |y| range [lo, hi] (layer 0: −hi … hi)
    hi: float
    N: float            # n² = N + p (w − c)²
    p: float
    c: float

    def n2(self, w):
        return self.N + self.p * (np.asarray(w) - self.c) ** 2


@dataclass
class Medium:
    n0: float
    m: float
    layers: list[Layer] = field(default_factory=list)

    def __post_init__(self):
        if not self.layers:
            self.layers = [Layer(0.0, np.inf, self.n0**2, -self.m, 0.0)]

    def copy(self) -> "Medium":
        """An independent copy (the construction tries layers on copies)."""
        return Medium(self.n0, self.m, [Layer(L.lo, L.hi, L.N, L.p, L.c) for L in self.layers])

    @property
    def top(self) -> float:
        return self.layers[-1].hi

    def close_top(self, h: float) -> None:
        """End the outermost layer at |y| = h."""
        self.layers[-1].hi = h

    def add_layer(self, m_i: float) -> None:
        """Layer above the current top with curvature m_i ≠ 0, C¹ with the layer below (3.11)."""
        below, h = self.layers[-1], self.layers[-1].hi
        e = float(below.n2(h))
        s = 2 * below.p * (h - below.c)                  # dn²/dw at h
        c = h - s / (2 * m_i)
        self.layers.append(Layer(h, np.inf, e - m_i * (h - c) ** 2, m_i, c))

    def layer_of(self, w: float, outward: bool) -> int:
        """Layer holding |y| = w; on a boundary, the one the ray is heading into."""
        for i, L in enumerate(self.layers):
            if w < L.hi or (w == L.hi and not outward):
                return i
        raise LeavesMedium()

    def n(self, y) -> np.ndarray:
        w = np.abs(np.asarray(y, dtype=float))
        out = np.full(w.shape, np.nan)
        for L in self.layers:
            sel = (w >= L.lo) & (w <= L.hi)
            out[sel] = np.sqrt(L.n2(w[sel]))
        return out

    def n2_at(self, y: float) -> float:
        """n² at one y, on floats (:meth:`n` squared: the last layer holding |y| decides a boundary)."""
        w, n2 = abs(float(y)), math.nan
        for L in self.layers:
            if L.lo <= w <= L.hi:
                d = w - L.c
                n2 = L.N + L.p * (d * d)
        return math.sqrt(n2) ** 2 if n2 >= 0 else math.nan


def _laws(m):
    """f, f' and ∫ of the path integrand (increasing in ψ) of the three ray shapes, from ``m`` (math or numpy)."""
    return {"sin": (m.sin, m.cos, lambda q: q / 2 + m.sin(2 * q) / 4),
            "sinh": (m.sinh, m.cosh, lambda q: q / 2 + m.sinh(2 * q) / 4),
            "cosh": (m.cosh, m.sinh, lambda q: m.sinh(2 * q) / 4 - q / 2)}


_LAWS, _LAWS_NP = _laws(math), _laws(np)      # floats (fast); numpy where math overflows (inf/NaN as before)


@dataclass
class Segment:
    """One layer crossing: u = w − c = su·Y·f(ψ), f = sin (p < 0), sinh or cosh (p > 0, n² − a² at
    u = 0 positive or negative); ψ = ψ0 + σ·rate·(x − x0), rate = √|p|/a."""
    x0: float
    psi0: float
    psi1: float
    L: Layer
    sign: float          # y = sign·w (layer ≥ 1); 0 for layer 0 (y = w)
    Y: float
    a: float
    path0: float
    kind: str = "sin"
    sigma: float = 1.0
    su: float = 1.0

    def __post_init__(self):
        self.rate = _rate(self.L.p, self.a)
        self.x1 = self.x0 + (self.psi1 - self.psi0) * self.sigma / self.rate

    def at(self, x: float):
        """(y, dy/dx, path) at x (a float: math on floats, this is the construction's inner loop)."""
        try:
            return self._at(x, _LAWS[self.kind], math.sqrt)
        except (OverflowError, ValueError):
            with np.errstate(all="ignore"):
                return self._at(x, _LAWS_NP[self.kind], np.sqrt)

    def _at(self, x, laws, sqrt):
        f, df, g = laws
        psi = self.psi0 + self.sigma * (x - self.x0) * self.rate
        w = self.L.c + self.su * self.Y * f(psi)
        dw = self.su * self.Y * df(psi) * self.rate * self.sigma
        path = self.path0 + self.a * (x - self.x0) + sqrt(abs(self.L.p)) * self.Y**2 * abs(g(psi) - g(self.psi0))
        s = 1.0 if self.sign == 0 else self.sign
        return s * w, s * dw, path

    def y(self, x: np.ndarray) -> np.ndarray:
        """y at an array of x (the formula of :meth:`at`)."""
        psi = self.psi0 + self.sigma * (x - self.x0) * self.rate
        return (1.0 if self.sign == 0 else self.sign) * (self.L.c + self.su * self.Y * _LAWS_NP[self.kind][0](psi))


def _rate(p: float, a: float) -> float:
    """dψ/dx = √|p| / a on floats (numpy's quotient, inf/NaN, for a = 0)."""
    return math.sqrt(abs(p)) / a if a else float(np.sqrt(abs(p)) / np.float64(a))


def _sign(v: float) -> float:
    """np.sign on a float without the numpy scalar (the tracer's inner loop)."""
    return 1.0 if v > 0 else -1.0 if v < 0 else float(np.sign(v))


def _start(L: Layer, a: float, u: float, du_up: bool):
    """(kind, Y, ψ0, σ, su) of the ray at u = w − c moving with du/dx sign ``du_up``."""
    return _floats_first(_start_in, L, a, u, du_up)


def _crossings(kind, Y, su, psi0, sigma, v):
    """ψ values ahead of ψ0 (in the direction σ) where f(ψ) = v/(su·Y)."""
    return _floats_first(_crossings_in, kind, Y, su, psi0, sigma, v)


def _floats_first(fn, *args):
    """``fn(math, …)``: the tracer's scalar steps on floats; where math refuses (NaN, ±inf, overflow:
    a ray grazing a boundary) the same steps in numpy, whose NaN means "no crossing"."""
    try:
        return fn(math, *args)
    except (ValueError, OverflowError, ZeroDivisionError):
        with np.errstate(all="ignore"):
            return fn(np, *args)


def _start_in(m, L: Layer, a: float, u: float, du_up: bool):
    K = L.N - a * a                                   # n² − a² at u = 0
    if L.p < 0:
        Y = m.sqrt(max(K / -L.p, u * u))
        s = min(max(u / Y, -1.0), 1.0) if Y > 0 else 0.0
        return "sin", Y, (m.asin(s) if du_up else m.pi - m.asin(s)), 1.0, 1.0
    if K > 0:
        Y = m.sqrt(K / L.p)
        return "sinh", Y, m.asinh(u / Y), (1.0 if du_up else -1.0), 1.0
    Y = m.sqrt(max(-K / L.p, 0.0))
    Y = min(Y, abs(u)) if Y > 0 else abs(u)
    q = m.acosh(max(abs(u) / Y, 1.0)) if Y > 0 else 0.0
    su = 1.0 if u >= 0 else -1.0
    return "cosh", Y, (q if du_up == (su > 0) else -q), 1.0, su


def _crossings_in(m, kind, Y, su, psi0, sigma, v):
    t = v / (su * Y) if Y > 0 else m.inf
    if kind == "sin":
        if abs(t) > 1:
            return []
        base = m.asin(t)
        out = []
        for cand in (base, m.pi - base):
            cand = cand + TWO_PI * m.ceil((psi0 + 1e-12 - cand) / TWO_PI)
            out.append(cand if cand > psi0 + 1e-12 else cand + TWO_PI)
        return out
    if kind == "sinh":
        q = m.asinh(t)
        return [q] if (q - psi0) * sigma > 1e-12 else []
    if t < 1:
        return []
    q = m.acosh(t)
    return [c for c in (-q, q) if c > psi0 + 1e-12]


class Ray:
    """A ray in the medium from (x, y) with invariant a, heading +x, dy/dx sign ``up``; lazily split
    into sinusoid segments up to ``x_max``."""

    def __init__(self, medium: Medium, x: float, y: float, a: float, up: float, x_max: float):
        self.medium, self.a, self.segments, self.left = medium, a, [], False
        try:
            with np.errstate(invalid="ignore", divide="ignore"):     # a ray grazing a boundary: NaN → no crossing
                self._extend(x, y, up, 0.0, x_max)
        except LeavesMedium:
            if not self.segments:
                raise
            self.left = True                 # traced up to where it leaves the known layers

    def _extend(self, x, y, up, path, x_max):
        med = self.medium
        for _ in range(200):
            outward = (up > 0) == (y >= 0) if y != 0 else True
            i = med.layer_of(abs(y), outward)
            L = med.layers[i]
            sign = 0.0 if i == 0 else (1.0 if y > 0 or (y == 0 and up > 0) else -1.0)
            w = y if i == 0 else abs(y)
            dw_up = up > 0 if i == 0 else outward
            kind, Y, psi0, sigma, su = _start(L, self.a, w - L.c, dw_up)
            ahead = [q for b in ([-L.hi, L.hi] if i == 0 else [L.lo, L.hi]) if math.isfinite(b)
                     for q in _crossings(kind, Y, su, psi0, sigma, b - L.c)]
            rate = _rate(L.p, self.a)
            limit = psi0 + sigma * (x_max - x) * rate
            psi1 = min(ahead + [limit], key=lambda q: (q - psi0) * sigma)
            seg = Segment(x, psi0, psi1, L, sign, Y, self.a, path, kind, sigma, su)
            self.segments.append(seg)
            if seg.x1 >= x_max * (1 - 1e-15) - 1e-12:
                return
            y_end, dy, path = seg.at(seg.x1)
            x, up = seg.x1, (_sign(dy) if dy != 0 else up)
            y = _sign(y_end) * (L.hi if abs(abs(y_end) - L.hi) < 1e-9 else L.lo)   # snap onto the boundary
        raise RuntimeError("ray: too many layer crossings")

    def at(self, x: float):
        """(y, unit direction (dx, dy), optical path from the start) at x."""
        y, dy, path = self.state(x)
        return y, np.array([1.0, dy]) / np.hypot(1.0, dy), path

    def state(self, x: float):
        """(y, dy/dx, optical path) at x: floats, for the root finders."""
        return self._segment(x).at(x)

    def y_at(self, x: float) -> float:
        return self._segment(x).at(x)[0]

    def _segment(self, x: float) -> Segment:
        for k, seg in enumerate(self.segments):
            if x <= seg.x1 or (k == len(self.segments) - 1 and x <= seg.x1 + 1e-9):
                return seg
        raise ValueError("x beyond the traced range")

    def ys(self, xs: np.ndarray) -> np.ndarray:
        """y at an increasing array of x within the traced range (vectorized :meth:`at`)."""
        out = np.empty(len(xs))
        lo = 0
        for k, seg in enumerate(self.segments):
            hi = len(xs) if k == len(self.segments) - 1 else int(np.searchsorted(xs, seg.x1, side="right"))
            with np.errstate(invalid="ignore"):
                out[lo:hi] = seg.y(xs[lo:hi])
            lo = hi
        return out

    @property
    def x_end(self) -> float:
        return self.segments[-1].x1
