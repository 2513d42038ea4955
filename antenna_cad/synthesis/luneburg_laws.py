"""Continuous Luneburg laws ε(r) and their ray sweeps (seed-002 §2.1): classic ``2 - (r/R)^2``,
generalised (focus outside, the Luneburg/Morgan ω integral) and the homogeneous outer shell (Abel
inversion of the core sweep). Internally R = 1 and ρ = r·n(r) is the ray invariant. Pure physics
(numpy/scipy); re-exported by :mod:`antenna_cad.synthesis.luneburg`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Literal

import numpy as np
from scipy import integrate, optimize
from scipy.interpolate import CubicSpline

from antenna_cad.synthesis.checks import DesignError

Law = Literal["classic", "generalized", "outer_shell"]

_QUAD = dict(epsabs=1e-14, epsrel=1e-13, limit=200)

# --------------------------------------------------------------------------------------------
# Continuous laws (seed-002 §2.1). Internally R = 1 and ρ = r·n(r) is the ray invariant.
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class OuterShell:
    """Homogeneous outer layer ``a < r < R`` of permittivity ``eps_r`` (seed-002 §2.1, Fig. 2)."""

    a_over_r: float
    eps_r: float


def _omega(rho: float, b: float) -> float:
    """ω(ρ,b) = (1/π)∫_ρ^1 asin(x/b)/√(x²-ρ²) dx, via x = √(ρ²+s²) (seed-002 §2.1)."""
    top = math.sqrt(max(1.0 - rho * rho, 0.0))
    if top == 0.0:
        return 0.0

    def f(s: float) -> float:
        x = math.sqrt(rho * rho + s * s)
        return 1.0 / b if x == 0.0 else math.asin(x / b) / x

    return integrate.quad(f, 0.0, top, **_QUAD)[0] / math.pi


def _g_shell(k: float, b: float, ns: float) -> float:
    """g(k) of the outer-shell inversion (seed-002 §2.1), rewritten without the cancelling
    arccos singularities: 2·acos(k/ρa) − Θc(k) = 2 asin k − asin(k/b) − 2 asin(k/ns)."""
    if k < 1e-7:  # series limit, avoids 0/0
        return 0.5 * (2.0 - 1.0 / b - 2.0 / ns)
    return (2.0 * math.asin(k) - math.asin(k / b) - 2.0 * math.asin(k / ns)) / (2.0 * k)


def _log_n_shell(rho: float, b: float, ns: float, rho_a: float) -> float:
    """ln n(ρ) = ln ns − (2/π)∫_ρ^ρa k g(k)/√(k²−ρ²) dk, with k = √(ρ²+s²) (seed-002 §2.1)."""
    top = math.sqrt(max(rho_a * rho_a - rho * rho, 0.0))
    if top == 0.0:
        return math.log(ns)
    val = integrate.quad(lambda s: _g_shell(math.sqrt(rho * rho + s * s), b, ns),
                         0.0, top, **_QUAD)[0]
    return math.log(ns) - 2.0 / math.pi * val


class _Law:
    """A continuous law with radius normalised to R = 1.

    ``a`` is the outer radius of the graded part (1 without a shell), ``ns`` the shell index
    (1 without a shell). ``log_n_rho(ρ)`` is ln n as a function of the invariant ρ = r·n on
    [0, ρa], ρa = a·ns; r(ρ) = ρ / n(ρ) (explicit), n(r) needs a root find.
    """

    def __init__(self, law: str, b: float, outer: OuterShell | None):
        self.law, self.b = law, float(b)
        if law == "outer_shell":
            assert outer is not None
            self.a, self.ns = float(outer.a_over_r), math.sqrt(outer.eps_r)
        else:
            self.a, self.ns = 1.0, 1.0
        self.rho_a = self.a * self.ns

    def log_n_rho(self, rho: float) -> float:
        if self.law == "classic":  # ρ = r√(2−r²) ⇒ r² = 1 − √(1−ρ²), n² = 2 − r²
            return 0.5 * math.log(1.0 + math.sqrt(max(1.0 - rho * rho, 0.0)))
        if self.law == "generalized":
            return _omega(rho, self.b)
        return _log_n_shell(rho, self.b, self.ns, self.rho_a)

    def r_of_rho(self, rho: float) -> float:
        return rho * math.exp(-self.log_n_rho(rho))

    def n(self, r: float) -> float:
        """Index at normalised radius r (shell value beyond a, 1 beyond R)."""
        if r > 1.0:
            return 1.0
        if r >= self.a:
            return self.ns
        if self.law == "classic":
            return math.sqrt(2.0 - r * r)
        if r == 0.0:
            return math.exp(self.log_n_rho(0.0))
        # ρ in [r, ρa] solves ρ·exp(−ln n(ρ)) = r
        rho = optimize.brentq(lambda p: self.r_of_rho(p) - r, r, self.rho_a,
                              xtol=1e-15, rtol=1e-15, maxiter=200)
        return rho / r

    def r_of_n(self, n_level: float) -> float:
        """Graded-part radius where n(r) = n_level, for n_level in [n(a⁻), n(0)]."""
        if self.law == "classic":
            return math.sqrt(max(2.0 - n_level * n_level, 0.0))
        target = math.log(n_level)
        lo, hi = 0.0, self.rho_a
        if target >= self.log_n_rho(0.0):
            return 0.0
        if target <= math.log(self.ns):
            return self.a
        rho = optimize.brentq(lambda p: self.log_n_rho(p) - target, lo, hi,
                              xtol=1e-15, rtol=1e-15, maxiter=200)
        return rho / n_level

    def eps(self, r: float) -> float:
        return self.n(r) ** 2

    def r_of_eps(self, eps_level: float) -> float:
        return self.r_of_n(math.sqrt(eps_level))

    @property
    def eps_centre(self) -> float:
        return math.exp(2.0 * self.log_n_rho(0.0))

    @property
    def eps_edge(self) -> float:
        """ε just inside the graded part's outer radius a (continuity with the shell)."""
        return self.ns ** 2


def _validated_law(law: str, b_over_R: float, outer: OuterShell | dict | None) -> _Law:
    if law not in ("classic", "generalized", "outer_shell"):
        raise DesignError("design.law", f"unknown law {law!r} (classic | generalized | outer_shell)")
    if not b_over_R >= 1.0:
        raise DesignError("design.focal_distance_ratio",
                          f"b/R must be >= 1 (focus on or outside the lens), got {b_over_R:g}")
    if law == "classic" and abs(b_over_R - 1.0) > 1e-12:
        raise DesignError("design.focal_distance_ratio",
                          f"law 'classic' focuses on the surface (b/R = 1), got b/R = {b_over_R:g}; "
                          "use law 'generalized'")
    if isinstance(outer, dict):
        outer = OuterShell(**outer)
    if law == "outer_shell":
        if outer is None:
            raise DesignError("design.outer_shell", "law 'outer_shell' needs {a_over_r, eps_r}")
        if not outer.eps_r >= 1.0:
            raise DesignError("design.outer_shell.eps_r",
                              f"shell permittivity must be >= 1, got {outer.eps_r:g}")
        if not 0.0 < outer.a_over_r < 1.0:
            raise DesignError("design.outer_shell.a_over_r",
                              f"must be in (0, 1), got {outer.a_over_r:g}")
        rho_a = outer.a_over_r * math.sqrt(outer.eps_r)
        if rho_a > 1.0:
            raise DesignError("design.outer_shell",
                              f"a·√εr = {rho_a:.4g} > 1: rays at the rim would enter the core and "
                              "the core law of seed-002 §2.1 does not exist")
    return _Law(law, b_over_R, outer if law == "outer_shell" else None)


def eps_profile(r_over_R, law: Law = "classic", b_over_R: float = 1.0,
                outer: OuterShell | dict | None = None) -> np.ndarray:
    """Continuous permittivity law ε(r/R) (seed-002 §2.1).

    * ``classic``: ε = 2 − (r/R)², focus on the surface (b/R = 1).
    * ``generalized``: n = exp ω(ρ, b), ρ = r·n, ω = (1/π)∫_ρ^1 asin(x/b)/√(x²−ρ²) dx (Luneburg,
      Morgan); solved for ρ per radius with brentq.
    * ``outer_shell``: homogeneous shell ``outer.eps_r`` on a < r < R; graded core from the
      Abel inversion of §2.1 with ε continuous at r = a (the digest's stated assumption).

    Returns ε for each r/R (1 outside the lens).
    """
    L = _validated_law(law, b_over_R, outer)
    r = np.asarray(r_over_R, dtype=float)
    if np.any(r < 0.0):
        raise ValueError("r_over_R must be >= 0")
    out = np.array([L.eps(float(x)) for x in r.ravel()])
    return out.reshape(r.shape)


@dataclass(frozen=True)
class TracedLaw:
    """The continuous law for ray tracing (mm): ``eps_of_r2(r²) -> (ε, dε/d(r²))`` of the graded
    core, continued smoothly past it (a tracer samples there inside its last step); the core
    radius and the homogeneous shell's εr outside it (1 without a shell)."""

    eps_of_r2: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
    core_mm: float
    shell_eps: float

    def eps(self, r_mm) -> np.ndarray:
        """ε(r) as built: the core law, then the shell."""
        r = np.asarray(r_mm, dtype=float)
        return np.where(r <= self.core_mm, self.eps_of_r2(r * r)[0], self.shell_eps)


def traced_law(law: Law, b_over_R: float, outer: OuterShell | dict | None, radius_mm: float,
               nodes: int = 256) -> TracedLaw:
    """:class:`TracedLaw` of a continuous law (seed-002 §2.1).

    Classic: ε = 2 − (r/R)² exactly. Otherwise the law is tabulated without root finding through
    the invariant ρ = r·n: at ρ_i = ρ_a·sin(π/2·i/nodes), ln n(ρ_i) by quadrature gives
    r_i = ρ_i/n_i, and ε is a cubic spline in r² (ε is smooth in r², also at the core's edge; max
    error 1e-9 for 256 nodes, b/R = 1.1–1.5), extrapolated past the core.
    """
    L = _validated_law(law, b_over_R, outer)
    R2 = radius_mm * radius_mm
    if L.law == "classic":
        return TracedLaw(lambda r2: (2.0 - np.asarray(r2) / R2, np.full(np.shape(r2), -1.0 / R2)), radius_mm, 1.0)
    rho = L.rho_a * np.sin(0.5 * np.pi * np.linspace(0.0, 1.0, nodes + 1))
    ln_n = np.array([L.log_n_rho(x) for x in rho])
    spline = CubicSpline((rho * np.exp(-ln_n)) ** 2 * R2, np.exp(2.0 * ln_n))
    slope = spline.derivative()
    return TracedLaw(lambda r2: (spline(np.asarray(r2, float)), slope(np.asarray(r2, float))),
                     L.a * radius_mm, L.ns**2)


# --------------------------------------------------------------------------------------------
# Exact continuous-law ray sweep (for checks and tests; seed-002 §2.1 "Check")
# --------------------------------------------------------------------------------------------

def required_sweep(k, b_over_R: float) -> np.ndarray:
    """Polar-angle sweep inside a lens of radius 1 that sends the ray of invariant k from the
    feed at b to a direction parallel to the axis: Θ = π + asin(k/b) − 2 asin k (seed-002 §2.1)."""
    k = np.asarray(k, dtype=float)
    return np.pi + np.arcsin(k / b_over_R) - 2.0 * np.arcsin(k)


def continuous_sweep(k, law: Law = "classic", b_over_R: float = 1.0,
                     outer: OuterShell | dict | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Sweep Θ(k) and internal optical path L(k) of the continuous law, by quadrature.

    Θ = 2∫_{r_t}^{1} k dr / (r√(r²n²−k²)), L = 2∫_{r_t}^{1} n² r dr / √(r²n²−k²) (R = 1), with
    the turning point r_t = k / n(ρ = k) explicit and r = r_t + (1−r_t)t² removing the
    inverse-square-root end singularity. The homogeneous shell of ``outer_shell`` is summed in
    closed form. Accuracy ~1e-10 (quad tolerance, brentq for n(r)). Slow (~0.1 s per ray):
    meant for verification, not for the design loop.
    """
    L = _validated_law(law, b_over_R, outer)
    ks = np.atleast_1d(np.asarray(k, dtype=float))
    th, pl = np.empty_like(ks), np.empty_like(ks)
    for j, kk in enumerate(ks):
        theta = 0.0
        path = 0.0
        top = 1.0
        if L.law == "outer_shell":
            ns, a = L.ns, L.a
            p = kk / ns
            theta += 2.0 * (math.acos(p) - (math.acos(p / a) if p < a else 0.0))
            path += 2.0 * ns * (math.sqrt(1.0 - p * p) - math.sqrt(max(a * a - p * p, 0.0)))
            top = a
            if kk >= L.rho_a:  # never enters the core
                th[j], pl[j] = theta, path
                continue
        rt = kk * math.exp(-L.log_n_rho(kk)) if kk > 0 else 0.0
        span = top - rt

        def radial(t: float) -> tuple[float, float, float]:
            """(r, n, r²n² − k²) at t, r = rt + span·t² (the substitution removes the turning-point pole)."""
            r = rt + span * t * t
            n = L.n(r)
            return r, n, r * r * n * n - kk * kk

        def dth(t: float) -> float:
            r, _, q = radial(t)
            return 2.0 * span * t * kk / (r * math.sqrt(q)) if q > 0.0 else 0.0

        def dl(t: float) -> float:
            r, n, q = radial(t)
            return 2.0 * span * t * n * n * r / math.sqrt(q) if q > 0.0 else 0.0

        if kk > 0:
            theta += 2.0 * integrate.quad(dth, 0.0, 1.0, epsabs=1e-13, epsrel=1e-12, limit=200)[0]
        else:
            theta = np.pi  # k = 0: straight through the centre
        path += 2.0 * integrate.quad(dl, 0.0, 1.0, epsabs=1e-13, epsrel=1e-12, limit=200)[0]
        th[j], pl[j] = theta, path
    return th, pl
