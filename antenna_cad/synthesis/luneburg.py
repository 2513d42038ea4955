"""Multilayer Luneburg lens synthesis: continuous laws, layer splits, foam grades, GO tracing.

Pure physics (numpy/scipy only). Source: seed-002 (Kuzmin 2004), digest
``reference/seed-002.md``; section numbers below refer to that digest.

Frame (DESIGN.md): lens centre at the origin, +Z is the beam direction. The feed (focus) sits
on the axis at ``z = -b`` where ``b = focal_distance_mm`` is measured from the lens centre
(seed-002 §1: "focus brought outside", ``b >= R``). Lengths are in mm at the interfaces, angles
in radians, frequencies in GHz.

Contents

* continuous laws ε(r) (seed-002 §2.1): classic ``2 - (r/R)^2``; generalised (focus outside,
  Luneburg/Morgan ω integral); homogeneous outer shell (Abel inversion of the core sweep);
* the three splits of §2.2 (equal ε, equal n, equal thickness; layer value at the radial
  midpoint) and the geometric ladder of the experimental cylinder (§2.2, L320);
* the minimum layer count rule (§2.3), the foam effective-medium relations and the effective
  loss tangent (§2.7), nearest-grade selection from a list of available foams;
* an exact, vectorized GO tracer through concentric homogeneous shells (§2.1b) giving exit
  points/directions, optical paths, aperture phase error and focus spread, and the GO aperture
  efficiency of a cos^q feed (§2.5).

Cylinder (parallel-plate) lens: between two conducting plates the TEM mode (E normal to the
plates) propagates with index √εr for any plate spacing, and the in-plane rays obey the same
invariant ``r·n·sinψ = k`` in concentric rings as meridional rays do in concentric spheres. The
2-D section of the cylinder is therefore exactly the meridional section of the sphere, and the
same tracer and the same layer laws apply; only the aperture is a line (efficiency integrals
are 1-D) and the height must keep higher-order parallel-plate modes cut off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Callable, Literal, Sequence

import numpy as np
from scipy import integrate, optimize
from scipy.interpolate import CubicSpline

from antenna_cad.synthesis.checks import Check, DesignError

C_MM_GHZ = 299.792458  # speed of light: λ[mm] = C_MM_GHZ / f[GHz]

Law = Literal["classic", "generalized", "outer_shell"]
Split = Literal["equal_eps", "equal_n", "equal_thickness", "ladder"]
Shape = Literal["sphere", "cylinder"]

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

        def dth(t: float) -> float:
            r = rt + span * t * t
            n = L.n(r)
            q = r * r * n * n - kk * kk
            if q <= 0.0:
                return 0.0
            return 2.0 * span * t * kk / (r * math.sqrt(q))

        def dl(t: float) -> float:
            r = rt + span * t * t
            n = L.n(r)
            q = r * r * n * n - kk * kk
            if q <= 0.0:
                return 0.0
            return 2.0 * span * t * n * n * r / math.sqrt(q)

        if kk > 0:
            theta += 2.0 * integrate.quad(dth, 0.0, 1.0, epsabs=1e-13, epsrel=1e-12, limit=200)[0]
        else:
            theta = np.pi  # k = 0: straight through the centre
        path += 2.0 * integrate.quad(dl, 0.0, 1.0, epsabs=1e-13, epsrel=1e-12, limit=200)[0]
        th[j], pl[j] = theta, path
    return th, pl


# --------------------------------------------------------------------------------------------
# Layer count rule (seed-002 §2.3) and foam effective medium (seed-002 §2.7)
# --------------------------------------------------------------------------------------------

def min_layer_count(d_over_lambda: float) -> int:
    """N = int(4.34·log2(D/λ) − 8.75), ``int`` read as truncation (seed-002 §2.3).

    Meaningful for D/λ ≳ 5; returns ≤ 0 for D/λ ≤ 4 (callers clamp)."""
    return int(4.34 * math.log2(d_over_lambda) - 8.75)


def fill_factor(eps_eff, base_eps_r: float) -> np.ndarray:
    """Volume fraction of solid polymer d = (n'_eff − 1)/(n' − 1), Robinson's law (4) (§2.7)."""
    e = np.asarray(eps_eff, dtype=float)
    return (np.sqrt(e) - 1.0) / (math.sqrt(base_eps_r) - 1.0)


def effective_tan_delta(eps_eff, base_eps_r: float, base_tan_delta: float) -> np.ndarray:
    """tanδ_eff = n'/√ε'_eff · (√ε'_eff − 1)/(n' − 1) · tanδ (seed-002 §2.7)."""
    e = np.asarray(eps_eff, dtype=float)
    nb = math.sqrt(base_eps_r)
    return nb / np.sqrt(e) * (np.sqrt(e) - 1.0) / (nb - 1.0) * base_tan_delta


def foam_density(eps_eff, base_eps_r: float, base_density_kg_m3: float) -> np.ndarray:
    """Foam density = d · ρ_solid (air mass neglected; buoyancy cancels it when weighed)."""
    return fill_factor(eps_eff, base_eps_r) * base_density_kg_m3


def nearest_grade(eps_target: float, grades: Sequence[float]) -> tuple[int, float, float]:
    """Nearest available grade: ``(index, eps_grade, eps_grade − eps_target)``."""
    g = np.asarray(grades, dtype=float)
    i = int(np.argmin(np.abs(g - eps_target)))
    return i, float(g[i]), float(g[i] - eps_target)


# --------------------------------------------------------------------------------------------
# GO aperture efficiency (seed-002 §2.5)
# --------------------------------------------------------------------------------------------

@lru_cache(maxsize=8)
def _leggauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    return np.polynomial.legendre.leggauss(n)


def feed_q_for_edge_taper(edge_taper_db: float, b_over_R: float) -> float:
    """Exponent q of a cos^q θ amplitude feed whose level toward the rim, θe = asin(R/b), is
    ``edge_taper_db`` (negative dB). seed-002 §2.5 rule: −10 … −15 dB."""
    ce = math.sqrt(1.0 - 1.0 / b_over_R**2)
    if ce <= 0.0:
        raise DesignError("design.focal_distance_ratio",
                          "b/R = 1: the rim is at 90° from the feed; a cos^q feed has no finite q "
                          "for a given edge taper (use feed_q)")
    return edge_taper_db / (20.0 * math.log10(ce))


def go_efficiency(b_over_R: float, q: float, shape: Shape = "sphere",
                  n_points: int = 400) -> tuple[float, float]:
    """GO taper and spillover efficiencies of a cos^q θ (amplitude, zero behind) feed.

    Sine condition ρ = b·sinθ and power conservation give A(ρ) ∝ F(θ)/√cosθ (§2.5).
    Sphere: η_t = |∫A ρdρ|² / (R²/2 ∫|A|²ρdρ), η_s = ∫_0^θe |F|² sinθ dθ / ∫_0^{π/2} |F|² sinθ dθ.
    Cylinder (line aperture, 2-D): η_t = |∫A dρ|² / (R ∫|A|² dρ), η_s = ∫_0^θe |F|² dθ / ∫_0^{π/2} |F|² dθ.
    Gauss–Legendre in θ; returns ``(eta_taper, eta_spill)``.
    """
    b = float(b_over_R)
    te = math.asin(1.0 / b)
    x, w = _leggauss(n_points)
    th = 0.5 * te * (x + 1.0)
    wt = 0.5 * te * w
    c = np.cos(th)
    F = c**q
    A = F / np.sqrt(c)
    rho = b * np.sin(th)
    drho = b * c * wt  # dρ = b cosθ dθ
    xf = 0.5 * (np.pi / 2) * (x + 1.0)
    wf = 0.5 * (np.pi / 2) * w
    if shape == "sphere":
        eta_t = (np.sum(A * rho * drho) ** 2) / (0.5 * np.sum(A**2 * rho * drho))
        eta_s = np.sum(F**2 * np.sin(th) * wt) / np.sum(np.cos(xf) ** (2 * q) * np.sin(xf) * wf)
    elif shape == "cylinder":
        eta_t = (np.sum(A * drho) ** 2) / (1.0 * np.sum(A**2 * drho))
        eta_s = np.sum(F**2 * wt) / np.sum(np.cos(xf) ** (2 * q) * wf)
    else:
        raise ValueError(f"unknown shape {shape!r}")
    return float(eta_t), float(eta_s)


# --------------------------------------------------------------------------------------------
# GO tracer through concentric homogeneous shells (seed-002 §2.1b)
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class LayeredTrace:
    """Rays from the feed at (x, z) = (0, −b) through the shells, meridional plane x–z.

    Rays with impact parameter k leave the feed at θ = asin(k/b) toward +x. For the sphere the
    3-D ray at azimuth ψ is this one rotated about +Z; for the cylinder this *is* the ray.
    All arrays have one entry per ray; lengths in mm, angles in rad. Invalid rays (miss the
    lens, or exit not toward +Z) carry NaN in the aperture fields.
    """

    impact_mm: np.ndarray          # k: ray invariant = distance of the air ray from the centre
    launch_angle_rad: np.ndarray   # θ from +Z at the feed
    entry_xz_mm: np.ndarray        # (n, 2)
    exit_xz_mm: np.ndarray         # (n, 2)
    exit_dir_xz: np.ndarray        # (n, 2) unit
    exit_tilt_rad: np.ndarray      # angle of the exit ray from +Z (0 = ideal)
    sweep_rad: np.ndarray          # polar-angle sweep inside the lens, Θ
    sweep_error_rad: np.ndarray    # Θ − [π + asin(k/b) − 2 asin(k/R)]
    optical_path_inside_mm: np.ndarray
    optical_path_mm: np.ndarray    # feed → aperture plane z = aperture_z_mm along the ray
    boresight_path_mm: np.ndarray  # feed → exit point + (aperture_z − z_exit): boresight phase path
    aperture_x_mm: np.ndarray      # where the ray crosses the aperture plane
    focus_miss_mm: np.ndarray      # reverse trace: signed miss of the focus by the ray entering parallel at k
    axial_focus_mm: np.ndarray     # reverse trace: distance from centre where it crosses the axis (NaN if it does not)
    turning_layer: np.ndarray      # deepest layer reached (0 = core): turning point or reflection
    tir: np.ndarray                # ray reflected totally at an inner interface
    valid: np.ndarray
    aperture_z_mm: float
    focal_distance_mm: float
    radius_mm: float


def trace_shells(r_outer_mm, eps_r, focal_distance_mm: float, impact_mm=None,
                 n_rays: int = 512, aperture_z_mm: float | None = None) -> LayeredTrace:
    """Exact GO trace through concentric homogeneous shells (seed-002 §2.1b), vectorized.

    ``r_outer_mm``/``eps_r``: per layer, innermost first (layer i fills r_{i−1} < r < r_i, r_0 = 0).
    In layer i a ray is the straight line at distance p_i = k/n_i from the centre; it sweeps
    Δφ_i = acos(p_i/r_i) − acos(p_i/r_{i−1}) (or acos(p_i/r_i) at the turning layer) with optical
    path n_i(√(r_i²−p_i²) − √(r_{i−1}²−p_i²)); inbound and outbound legs are mirror images, so
    Θ = 2ΣΔφ_i, L = 2ΣΔL_i. A ray that cannot enter a denser-outside inner layer is totally
    reflected there (flagged ``tir``; GO phase of the reflection ignored). Fresnel losses ignored.
    Default rays: ``n_rays`` midpoints uniform in k over (0, R); ``aperture_z_mm`` defaults to R.
    """
    ro = np.asarray(r_outer_mm, dtype=float)
    eps = np.asarray(eps_r, dtype=float)
    if ro.ndim != 1 or ro.shape != eps.shape or ro.size == 0:
        raise ValueError("r_outer_mm and eps_r must be 1-D of equal, non-zero length")
    if np.any(np.diff(ro) <= 0) or ro[0] <= 0:
        raise DesignError("design.layers", "layer radii must increase strictly from > 0")
    if np.any(eps < 1.0):
        i = int(np.argmin(eps))
        raise DesignError("design.layers", f"layer {i + 1} has εr = {eps[i]:.4g} < 1")
    R = float(ro[-1])
    b = float(focal_distance_mm)
    if b < R:
        raise DesignError("design.focal_distance_ratio", f"feed inside the lens: b = {b:g} mm < R = {R:g} mm")
    if impact_mm is None:
        k = (np.arange(n_rays) + 0.5) * (R / n_rays)
    else:
        k = np.atleast_1d(np.asarray(impact_mm, dtype=float))
    zap = R if aperture_z_mm is None else float(aperture_z_mm)
    n = np.sqrt(eps)
    ri = np.concatenate([[0.0], ro[:-1]])
    M = ro.size
    p = k[:, None] / n[None, :]                      # (rays, layers)
    hits = k < R
    reached = np.zeros_like(p, dtype=bool)
    below = p < ri[None, :]                          # reaches the layer's inner boundary
    tir = np.zeros(k.shape, dtype=bool)
    reached[:, M - 1] = hits
    for j in range(M - 1, 0, -1):
        enters = p[:, j - 1] < ro[j - 1]
        reached[:, j - 1] = reached[:, j] & below[:, j] & enters
        tir |= reached[:, j] & below[:, j] & ~enters
    through = reached & below                        # passes the inner boundary of the layer
    with np.errstate(invalid="ignore"):
        ac_o = np.arccos(np.clip(p / ro[None, :], -1.0, 1.0))
        ac_i = np.where(through, np.arccos(np.clip(np.divide(p, ri[None, :], out=np.ones_like(p),
                                                             where=ri[None, :] > 0), -1.0, 1.0)), 0.0)
    dphi = np.where(reached, ac_o - ac_i, 0.0)
    dl = np.where(reached, n[None, :] * (np.sqrt(np.maximum(ro[None, :] ** 2 - p**2, 0.0))
                                         - np.where(through, np.sqrt(np.maximum(ri[None, :] ** 2 - p**2, 0.0)), 0.0)),
                  0.0)
    theta = 2.0 * dphi.sum(axis=1)
    Lin = 2.0 * dl.sum(axis=1)
    turning = np.where(hits, np.argmax(reached, axis=1), -1)   # deepest layer reached

    kk = np.minimum(k, R)
    acR = np.arccos(kk / R)
    phi_in = np.arccos(kk / b) - acR                 # position angle from −Z toward +x
    phi_out = phi_in + theta
    phi_c = phi_out - acR                            # closest approach of the exit line
    e_r = lambda ph: np.stack([np.sin(ph), -np.cos(ph)], axis=-1)
    entry = R * e_r(phi_in)
    exit_ = R * e_r(phi_out)
    d = np.stack([np.cos(phi_c), np.sin(phi_c)], axis=-1)
    tilt = phi_c - np.pi / 2
    req = np.pi + np.arcsin(kk / b) - 2.0 * np.arcsin(kk / R)
    air_in = np.sqrt(b * b - kk * kk) - np.sqrt(R * R - kk * kk)
    valid = hits & (d[:, 1] > 1e-9)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(valid, (zap - exit_[:, 1]) / d[:, 1], np.nan)
    opl = air_in + Lin + t
    xap = exit_[:, 0] + t * d[:, 0]
    # reverse trace: parallel ray at impact k from +Z; its exit line has closest-approach angle
    # φc' = π/2 + 2 acos(k/R) − Θ; miss of the focus = k − b cos φc'; axis crossing k / cos φc'.
    phc_r = np.pi / 2 + 2.0 * acR - theta
    miss = np.where(hits, kk - b * np.cos(phc_r), np.nan)
    with np.errstate(divide="ignore", invalid="ignore"):
        axial = np.where(hits & (np.cos(phc_r) > 1e-12), kk / np.cos(phc_r), np.nan)
    nanv = lambda a: np.where(hits[:, None] if a.ndim == 2 else hits, a, np.nan)
    return LayeredTrace(
        impact_mm=k, launch_angle_rad=np.arcsin(kk / b), entry_xz_mm=nanv(entry),
        exit_xz_mm=nanv(exit_), exit_dir_xz=nanv(d), exit_tilt_rad=nanv(tilt),
        sweep_rad=nanv(theta), sweep_error_rad=nanv(theta - req), optical_path_inside_mm=nanv(Lin),
        optical_path_mm=np.where(valid, opl, np.nan),
        boresight_path_mm=np.where(hits, air_in + Lin + (zap - exit_[:, 1]), np.nan),
        aperture_x_mm=np.where(valid, xap, np.nan),
        focus_miss_mm=miss, axial_focus_mm=axial, turning_layer=turning, tir=tir & hits,
        valid=valid, aperture_z_mm=zap, focal_distance_mm=b, radius_mm=R)


def trace_layered_sphere(layers: Sequence, focal_distance_mm: float, impact_mm=None,
                         n_rays: int = 512, aperture_z_mm: float | None = None) -> LayeredTrace:
    """:func:`trace_shells` for a sequence of objects with ``r_outer_mm`` and ``eps_r``
    (e.g. :class:`Layer`, innermost first) — the as-built stage passes the chosen grades.
    Also valid for the parallel-plate cylinder (same 2-D physics, see module docstring)."""
    return trace_shells([L.r_outer_mm for L in layers], [L.eps_r for L in layers],
                        focal_distance_mm, impact_mm=impact_mm, n_rays=n_rays,
                        aperture_z_mm=aperture_z_mm)


@dataclass(frozen=True)
class ApertureFigures:
    """Stepped-lens GO figures. "Core" figures use the rays with k <= rim_fraction·R; "full"
    ones every ray. The rim sliver holds rays that skim thin outer layers at grazing incidence,
    where GO gives errors of many wavelengths that do not shrink with the layer count (seed-002
    §2.1b: GO exaggerates the few-layer problem; layers thinner than λ are not resolved)."""

    rim_fraction: float
    phase_error_pp_deg: float      # core
    phase_error_rms_deg: float     # core, area weighted, piston removed
    phase_error_pp_full_deg: float
    phase_error_rms_full_deg: float
    focus_spread_mm: float         # core: max |miss| of the design focus by reversed parallel rays
    focus_spread_rms_mm: float     # core, area weighted
    focus_spread_full_mm: float
    axial_focus_min_mm: float      # core: axis crossings of reversed parallel rays (ideal: b)
    axial_focus_max_mm: float
    max_exit_tilt_rad: float       # core
    phase_efficiency: float        # full aperture: |Σ A e^{jφ} w|² / |Σ A w|², cos^q feed
    invalid_rays: int


def aperture_figures(trace: LayeredTrace, frequency_ghz: float, feed_q: float,
                     shape: Shape = "sphere", rim_fraction: float = 0.95) -> ApertureFigures:
    """Aperture phase error at the design frequency and focus spread from a trace.

    Phase φ = 360°·(P − mean)/λ with P = ``boresight_path_mm`` (field phase on the exit surface
    referred to the +Z plane wavefront, i.e. its phase in the boresight far field), piston
    removed; RMS and mean weighted by aperture area (w = k for the sphere, 1 for the cylinder's
    line aperture). The continuous law has φ ≡ 0 and zero focus miss (verified in the tests),
    so these figures are directly "stepped vs continuous". The phase efficiency weights the
    rays with the ideal GO amplitude A = cos^q θ/√cosθ (§2.5) over the whole aperture.
    """
    lam = C_MM_GHZ / frequency_ghz
    R = trace.radius_mm
    k_all = trace.impact_mm
    hit = np.isfinite(trace.boresight_path_mm)
    core = hit & (k_all <= rim_fraction * R)

    def phase_stats(sel):
        k = k_all[sel]
        w = k if shape == "sphere" else np.ones_like(k)
        P = trace.boresight_path_mm[sel]
        ph = 360.0 * (P - np.sum(w * P) / np.sum(w)) / lam
        return ph, w, float(np.ptp(ph)), float(math.sqrt(np.sum(w * ph**2) / np.sum(w)))

    ph_f, w_f, pp_f, rms_f = phase_stats(hit)
    _, _, pp_c, rms_c = phase_stats(core)
    th = np.arcsin(k_all[hit] / trace.focal_distance_mm)
    A = np.cos(th) ** (feed_q - 0.5)
    eff = abs(np.sum(A * w_f * np.exp(1j * np.radians(ph_f)))) ** 2 / np.sum(A * w_f) ** 2
    miss = trace.focus_miss_mm
    wm = k_all[core] if shape == "sphere" else np.ones(int(core.sum()))
    ax = trace.axial_focus_mm[core]
    ax = ax[np.isfinite(ax)]
    return ApertureFigures(
        rim_fraction=float(rim_fraction),
        phase_error_pp_deg=pp_c, phase_error_rms_deg=rms_c,
        phase_error_pp_full_deg=pp_f, phase_error_rms_full_deg=rms_f,
        focus_spread_mm=float(np.max(np.abs(miss[core]))),
        focus_spread_rms_mm=float(math.sqrt(np.sum(wm * miss[core] ** 2) / np.sum(wm))),
        focus_spread_full_mm=float(np.max(np.abs(miss[hit]))),
        axial_focus_min_mm=float(ax.min()) if ax.size else float("nan"),
        axial_focus_max_mm=float(ax.max()) if ax.size else float("nan"),
        max_exit_tilt_rad=float(np.max(np.abs(trace.exit_tilt_rad[core]))),
        phase_efficiency=float(eff), invalid_rays=int(np.sum(~trace.valid)))


# --------------------------------------------------------------------------------------------
# Layer splits (seed-002 §2.2)
# --------------------------------------------------------------------------------------------

def _split(L: _Law, count: int, split: str, ladder: dict | None) -> tuple[np.ndarray, np.ndarray]:
    """Outer radii (R = 1) and design εr of each layer, innermost first (seed-002 §2.2)."""
    shell = L.law == "outer_shell"
    if split == "ladder":
        if shell:
            raise DesignError("design.layers.split",
                              "the ladder split spans the whole lens; it cannot be combined with "
                              "law 'outer_shell'")
        if not ladder or "eps_outer" not in ladder or "ratio" not in ladder:
            raise DesignError("design.layers.ladder", "split 'ladder' needs {eps_outer, ratio}")
        e_out, ratio = float(ladder["eps_outer"]), float(ladder["ratio"])
        if not e_out >= 1.0:
            raise DesignError("design.layers.ladder.eps_outer", f"must be >= 1, got {e_out:g}")
        if not ratio > 1.0:
            raise DesignError("design.layers.ladder.ratio",
                              f"εi/εi+1 must be > 1 (permittivity grows inward), got {ratio:g}")
        eps = e_out * ratio ** np.arange(count - 1, -1, -1, dtype=float)
        levels = 0.5 * (eps[:-1] + eps[1:])  # r_i where ε(r) = (εi + εi+1)/2 (L320)
        e0 = L.eps_centre
        if levels.size and levels[0] >= e0:
            raise DesignError("design.layers.ladder",
                              f"boundary level (ε1+ε2)/2 = {levels[0]:.4g} is above the law's "
                              f"centre value ε(0) = {e0:.4g}: no radius has it; lower eps_outer, "
                              "ratio or count")
        radii = np.array([L.r_of_eps(x) for x in levels] + [1.0])
        return radii, eps
    M = count - 1 if shell else count
    a = L.a
    if split == "equal_eps":
        lv = L.eps_centre - (L.eps_centre - L.eps_edge) * np.arange(1, M) / M
        inner = [L.r_of_eps(x) for x in lv]
    elif split == "equal_n":
        n0, na = math.sqrt(L.eps_centre), L.ns
        lv = n0 - (n0 - na) * np.arange(1, M) / M
        inner = [L.r_of_n(x) for x in lv]
    elif split == "equal_thickness":
        inner = list(a * np.arange(1, M) / M)
    else:
        raise DesignError("design.layers.split",
                          f"unknown split {split!r} (equal_eps | equal_n | equal_thickness | ladder)")
    radii = np.array(inner + [a])
    r_in = np.concatenate([[0.0], radii[:-1]])
    eps = np.array([L.eps(0.5 * (r0 + r1)) for r0, r1 in zip(r_in, radii)])  # radial midpoint
    if shell:
        radii = np.append(radii, 1.0)
        eps = np.append(eps, L.ns**2)
    return radii, eps


def layer_split(count: int, split: Split = "equal_eps", law: Law = "classic", b_over_R: float = 1.0,
                outer: OuterShell | dict | None = None, ladder: dict | None = None
                ) -> tuple[np.ndarray, np.ndarray]:
    """Layer outer radii r_i/R and design εi (innermost first) for ``count`` physical layers.

    ``equal_eps``/``equal_n``: the law's range from its centre value to its edge value ε(a⁻) is cut
    in equal steps, r_j = ε⁻¹(ε(0) − jΔ), and each layer takes the law at its radial midpoint;
    ``equal_thickness``: r_j = a·j/M (seed-002 §2.2). With ``outer_shell`` the last layer is the
    homogeneous shell a < r < R and the graded part has count − 1 layers (§2.2 interpretation
    notes). ``ladder``: εi = eps_outer·ratio^(count−i), r_i where ε(r) = (εi + εi+1)/2 (L320).
    """
    L = _validated_law(law, b_over_R, outer)
    minimum = 2 if law == "outer_shell" and split != "ladder" else 1
    if int(count) != count or count < minimum:
        raise DesignError("design.layers.count", f"need an integer >= {minimum}, got {count!r}")
    radii, eps = _split(L, int(count), split, ladder)
    if np.any(np.diff(radii) <= 0.0) or radii[0] <= 0.0:
        raise DesignError("design.layers", f"layer radii not strictly increasing: {np.round(radii, 6)}")
    if np.any(eps < 1.0):
        raise DesignError("design.layers", f"a layer has εr = {eps.min():.4g} < 1")
    return radii, eps


# --------------------------------------------------------------------------------------------
# The design record and the synthesis entry point
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Layer:
    """One homogeneous layer (index 1 = core). ``eps_r`` is the realised value (nearest grade
    when a grade list is given, else the design value); ``tan_delta`` is §2.7's tanδ_eff of it."""

    index: int
    r_inner_mm: float
    r_outer_mm: float
    eps_r: float
    tan_delta: float
    eps_r_design: float
    fill_factor: float
    density_kg_m3: float | None = None
    grade: int | None = None       # index into the grade list, None for an ideal grade

    @property
    def thickness_mm(self) -> float:
        return self.r_outer_mm - self.r_inner_mm


@dataclass(frozen=True)
class LuneburgDesign:
    diameter_mm: float
    frequency_ghz: float
    shape: str                      # "sphere" | "cylinder"
    height_mm: float | None         # cylinder plate spacing
    law: str
    focal_distance_ratio: float     # b/R
    focal_distance_mm: float        # b, from the lens centre; feed at z = −b
    outer_shell: OuterShell | None
    split: str
    layer_count_rule: int           # seed-002 §2.3 (may be ≤ 0 for D/λ ≤ 4)
    layers: tuple[Layer, ...]       # innermost first
    feed_q: float                   # cos^q θ amplitude feed used for the efficiency
    edge_taper_db: float | None     # feed level toward the rim (None for b/R = 1: rim at 90°)
    efficiency_taper: float         # GO, ideal (continuous) lens, seed-002 §2.5
    efficiency_spillover: float
    efficiency: float               # taper × spillover
    efficiency_with_phase: float    # × phase efficiency of the stepped lens' GO aperture phase
    rim_fraction: float             # "core" figures use rays with k <= rim_fraction·R
    phase_error_pp_deg: float       # stepped lens, core, at frequency_ghz, piston removed
    phase_error_rms_deg: float      # core, area weighted
    phase_error_pp_full_deg: float  # whole aperture (rim sliver included)
    phase_error_rms_full_deg: float
    focus_spread_mm: float          # core: max miss of the design focus by reversed parallel rays
    focus_spread_rms_mm: float      # core, area weighted
    focus_spread_full_mm: float     # whole aperture
    axial_focus_min_mm: float       # range of axis crossings of reversed parallel rays (ideal: b)
    axial_focus_max_mm: float
    max_exit_tilt_rad: float
    axial_loss_db: float            # GO dielectric loss along the axial ray (§2.7, §5.3-6)
    checks: tuple[Check, ...] = field(default_factory=tuple)

    @property
    def radius_mm(self) -> float:
        return 0.5 * self.diameter_mm

    @property
    def wavelength_mm(self) -> float:
        return C_MM_GHZ / self.frequency_ghz

    def layer_table(self) -> list[dict]:
        """One row per layer for reports."""
        return [dict(index=L.index, r_inner_mm=L.r_inner_mm, r_outer_mm=L.r_outer_mm,
                     thickness_mm=L.thickness_mm, eps_r_design=L.eps_r_design, eps_r=L.eps_r,
                     eps_error=L.eps_r - L.eps_r_design, tan_delta=L.tan_delta,
                     fill_factor=L.fill_factor, density_kg_m3=L.density_kg_m3, grade=L.grade)
                for L in self.layers]


def optimum_feed_q(b_over_R: float, shape: Shape = "sphere") -> float:
    """q of the cos^q θ feed that maximises the GO η_taper·η_spill (§2.5: a flat maximum).
    Degenerate for b/R = 1 (q = 1/2 gives a uniform aperture with no spillover in GO)."""
    res = optimize.minimize_scalar(lambda q: -np.prod(go_efficiency(b_over_R, q, shape)),
                                   bounds=(0.2, 30.0), method="bounded", options=dict(xatol=1e-4))
    return float(res.x)


def synthesize_luneburg(*, diameter_mm: float, frequency_ghz: float,
                        focal_distance_ratio: float = 1.0, law: Law = "classic",
                        layer_count: int | None = None, split: Split = "equal_eps",
                        ladder: dict | None = None, outer_shell: OuterShell | dict | None = None,
                        base_eps_r: float, base_tan_delta: float,
                        base_density_kg_m3: float | None = None,
                        grades: Sequence[float] | None = None,
                        shape: Shape = "sphere", height_mm: float | None = None,
                        edge_taper_db: float = -10.0, feed_q: float | None = None,
                        n_rays: int = 512, rim_fraction: float = 0.95) -> LuneburgDesign:
    """Synthesize a multilayer Luneburg lens (seed-002).

    ``layer_count=None`` is ``auto``: the §2.3 rule N = int(4.34 log2(D/λ) − 8.75), clamped to
    the minimum the law needs; an explicit count below the rule gives a warning Check.
    Each layer's εr is realised either by the nearest of ``grades`` (its error is reported) or
    by an ideal foam of the base polymer (fill factor, density from §2.7). The stepped lens is
    traced (§2.1b) with the realised εr; the phase error and focus spread are relative to the
    continuous law, which is exact (uniform phase, zero spread). The feed is cos^q θ: ``feed_q``
    or, if None, the q giving ``edge_taper_db`` toward the rim (§2.5 rule −10…−15 dB); for
    b/R = 1 (rim at 90°, rule inapplicable) q = 1 with a warning Check. Figures marked "core"
    use rays with k <= ``rim_fraction``·R (see :class:`ApertureFigures`).
    """
    if not diameter_mm > 0:
        raise DesignError("design.diameter_mm", f"must be > 0, got {diameter_mm:g}")
    if not frequency_ghz > 0:
        raise DesignError("frequency_ghz", f"must be > 0, got {frequency_ghz:g}")
    if shape not in ("sphere", "cylinder"):
        raise DesignError("design.shape", f"unknown shape {shape!r} (sphere | cylinder)")
    if shape == "cylinder" and not (height_mm is not None and height_mm > 0):
        raise DesignError("design.height_mm", f"a cylinder lens needs a plate spacing > 0, got {height_mm!r}")
    if not base_eps_r > 1.0:
        raise DesignError("material.eps_r", f"base polymer εr must be > 1, got {base_eps_r:g}")
    if not base_tan_delta >= 0.0:
        raise DesignError("material.tan_delta", f"must be >= 0, got {base_tan_delta:g}")
    Lw = _validated_law(law, focal_distance_ratio, outer_shell)
    if isinstance(outer_shell, dict):
        outer_shell = OuterShell(**outer_shell)
    R = 0.5 * diameter_mm
    lam = C_MM_GHZ / frequency_ghz
    rule = min_layer_count(diameter_mm / lam)
    minimum = 2 if law == "outer_shell" else 1
    checks: list[Check] = []
    count = max(rule, minimum) if layer_count is None else layer_count
    radii, eps_d = layer_split(count, split, law, focal_distance_ratio, outer_shell, ladder)
    checks.append(Check("layer_count_vs_rule", "warn" if count < rule else "pass", float(count),
                        float(rule), "",
                        f"{count} layers; seed-002 §2.3 minimum for D/λ = {diameter_mm / lam:.3g} "
                        f"is {rule}" + (" — add layers" if count < rule else "")))
    if eps_d.max() > base_eps_r:
        raise DesignError("material.eps_r",
                          f"a layer needs εr = {eps_d.max():.4g} but the solid base polymer has only "
                          f"{base_eps_r:.4g}")
    # realisation: nearest grade or ideal foam (seed-002 §2.7)
    if grades is not None:
        g = np.asarray(grades, dtype=float)
        if g.size == 0 or np.any(g < 1.0) or np.any(g > base_eps_r):
            raise DesignError("material.grades",
                              f"grade εr must lie in [1, {base_eps_r:g}] (solid base), got {list(g)}")
        pick = [nearest_grade(e, g) for e in eps_d]
        idx = [p[0] for p in pick]
        eps_r = np.array([p[1] for p in pick])
        err = np.abs(eps_r - eps_d)
        step = np.min(np.abs(np.diff(eps_d))) if eps_d.size > 1 else np.inf
        lim = 0.5 * step
        dup = sum(1 for i in range(1, len(idx)) if idx[i] == idx[i - 1])
        checks.append(Check("grade_eps_error", "warn" if (err.max() > lim or dup) else "pass",
                            float(err.max()), float(lim), "",
                            f"largest |εr(grade) − εr(design)| = {err.max():.4g} (half the smallest "
                            f"layer step {lim:.4g})" + (f"; {dup} adjacent layers share a grade" if dup else "")))
    else:
        idx = [None] * len(eps_d)
        eps_r = eps_d.copy()
    tand = effective_tan_delta(eps_r, base_eps_r, base_tan_delta)
    ff = fill_factor(eps_r, base_eps_r)
    dens = (foam_density(eps_r, base_eps_r, base_density_kg_m3) if base_density_kg_m3 is not None
            else [None] * len(eps_r))
    r_in = np.concatenate([[0.0], radii[:-1]])
    layers = tuple(Layer(i + 1, float(R * r_in[i]), float(R * radii[i]), float(eps_r[i]),
                         float(tand[i]), float(eps_d[i]), float(ff[i]),
                         None if dens[i] is None else float(dens[i]), idx[i])
                   for i in range(len(radii)))
    b_mm = focal_distance_ratio * R
    # feed and GO efficiency (§2.5)
    if feed_q is not None:
        if not feed_q > 0:
            raise DesignError("feed.q", f"cos^q feed exponent must be > 0, got {feed_q:g}")
        q = float(feed_q)
    elif focal_distance_ratio > 1.0 + 1e-12:
        q = feed_q_for_edge_taper(edge_taper_db, focal_distance_ratio)
    else:
        q = 1.0
        checks.append(Check("feed_model", "warn", q, q, "",
                            "b/R = 1 puts the rim at 90° from the feed, so the −10…−15 dB edge rule "
                            "(seed-002 §2.5) cannot fix the feed; a cos θ feed (q = 1) is assumed — "
                            "give feed_q"))
    ce = math.sqrt(max(1.0 - 1.0 / focal_distance_ratio**2, 0.0))
    taper = 20.0 * q * math.log10(ce) if ce > 0 else None
    if taper is not None:
        ok = -15.0 - 1e-9 <= taper <= -10.0 + 1e-9
        checks.append(Check("feed_edge_taper", "pass" if ok else "warn", taper, -10.0, "dB",
                            f"feed level toward the rim {taper:.3g} dB (seed-002 §2.5 rule: −10 … −15 dB)"))
    eta_t, eta_s = go_efficiency(focal_distance_ratio, q, shape)
    # stepped-lens trace (§2.1b)
    tr = trace_layered_sphere(layers, b_mm, n_rays=n_rays)
    fig = aperture_figures(tr, frequency_ghz, q, shape, rim_fraction)
    checks.append(Check("aperture_phase_error_rms",
                        "warn" if fig.phase_error_rms_deg > 22.5 else "pass",
                        fig.phase_error_rms_deg, 22.5, "deg",
                        f"GO aperture phase error of the stepped lens within {rim_fraction:g}·R "
                        f"{fig.phase_error_rms_deg:.3g}° RMS, {fig.phase_error_pp_deg:.3g}° p-p (λ/16 = 22.5° RMS guide; GO overstates "
                        "few-layer errors, seed-002 §2.1b)"))
    core = tr.impact_mm <= rim_fraction * R
    n_back, n_tir = int(np.sum(core & ~tr.valid)), int(np.sum(core & tr.tir))
    if n_back or n_tir:
        checks.append(Check("ray_trace_anomalies", "warn", float(n_back + n_tir), 0.0, "rays",
                            f"{n_back} core rays leave away from +Z, {n_tir} are totally reflected "
                            "inside the lens (non-monotone layers?)"))
    if shape == "cylinder":
        hmax = lam / (2.0 * math.sqrt(float(eps_r.max())))
        checks.append(Check.upper("parallel_plate_single_mode", float(height_mm), hmax, "mm",
                                  "plate spacing vs TM1 cutoff λ/(2√εmax) in the core"))
    thick = np.array([L.thickness_mm for L in layers])
    loss_db = float(20.0 * math.log10(math.e) * np.sum(np.pi / lam * np.sqrt(eps_r) * tand * 2.0 * thick))
    return LuneburgDesign(
        diameter_mm=float(diameter_mm), frequency_ghz=float(frequency_ghz), shape=shape,
        height_mm=None if height_mm is None else float(height_mm), law=law,
        focal_distance_ratio=float(focal_distance_ratio), focal_distance_mm=float(b_mm),
        outer_shell=outer_shell if law == "outer_shell" else None, split=split,
        layer_count_rule=rule, layers=layers, feed_q=q, edge_taper_db=taper,
        efficiency_taper=eta_t, efficiency_spillover=eta_s, efficiency=eta_t * eta_s,
        efficiency_with_phase=eta_t * eta_s * fig.phase_efficiency,
        rim_fraction=fig.rim_fraction,
        phase_error_pp_deg=fig.phase_error_pp_deg, phase_error_rms_deg=fig.phase_error_rms_deg,
        phase_error_pp_full_deg=fig.phase_error_pp_full_deg,
        phase_error_rms_full_deg=fig.phase_error_rms_full_deg,
        focus_spread_mm=fig.focus_spread_mm, focus_spread_rms_mm=fig.focus_spread_rms_mm,
        focus_spread_full_mm=fig.focus_spread_full_mm,
        axial_focus_min_mm=fig.axial_focus_min_mm, axial_focus_max_mm=fig.axial_focus_max_mm,
        max_exit_tilt_rad=fig.max_exit_tilt_rad, axial_loss_db=loss_db, checks=tuple(checks))
