"""Aplanatic integral mirror-lens (seed-004): exact synthesis, power series, the feed-on-surface
variant, astigmatism and the optimisation of the seed's target A.

Frame and units (seed-004 §1): lengths in units of the aperture diameter D (exit radius 0.5);
the feed (focus) O at the origin, z the symmetry axis pointing from the feed into the body. The
refracting front face is z = f(r) (vertex z = f0), the mirror Z = F(R) (vertex f0 + d0); rays go
O → A (front) → B (mirror) → C (front) and leave parallel to the axis travelling toward −z. The
output wave is referred to the plane z = 0 through the focus; central eikonal L0 = 2 f0 + 2 n d0.

Pure numpy/scipy: no CAD imports.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicHermiteSpline, CubicSpline
from scipy.optimize import minimize, minimize_scalar

from antenna_cad.synthesis.checks import DesignError

STEP = 2e-4                 # marching step in units of D (seed-004 §2.2: h ≈ 2e-4)
SEED_RADIUS = 2e-3          # series seed of the delay ODE (seed-004 §2.2 step 2)
TARGET_RADII = (0.15, 0.25, 0.35)     # sample exit radii of the target A, eq. (21)
APERTURE_RADIUS = 0.5


# ------------------------------------------------------------------ power series, seed-004 §2.3

@dataclass(frozen=True)
class SeriesCoefficients:
    """f = f0 + f2 r² + f4 r⁴, F = f0 + d0 + F2 R² + F4 R⁴ and the auxiliaries of seed-004 §2.3,
    with the [FIX]es of §0: k3 the r_A³ coefficient of sin ξ (k3p the bracket k3′ used inside f4),
    v13's last term −v11(D2 − W2)/d0."""
    n: float
    f0: float
    d0: float
    gamma: float
    f2: float
    f4: float
    F2: float
    F4: float
    k1: float
    k3: float
    k3p: float
    D2: float
    W2: float
    RB1: float
    RB3: float
    rC1: float
    rC3: float

    def front(self, r):
        return self.f0 + self.f2 * r**2 + self.f4 * r**4

    def mirror(self, R):
        return self.f0 + self.d0 + self.F2 * R**2 + self.F4 * R**4


def series_coefficients(n: float, f0: float, d0: float, gamma: float) -> SeriesCoefficients:
    """Closed-form series of both generatrices, seed-004 eqs. (2)–(15) corrected (§0 items 1–3)."""
    if f0 <= 0:
        raise DesignError("design.f0", "the series of §2.3 needs f0 > 0 (use feed_on_surface for f0 = 0)")
    _check_index(n)
    if abs(gamma - f0) < 1e-9 or abs(gamma**3 - f0**3) < 1e-12:
        raise DesignError("design.gamma", f"γ = f0 = {f0:g} makes f2 singular (seed-004 §3.5); choose γ > f0")
    g = gamma
    f2 = (n * (g - f0) - d0) / (2 * d0 * (g - f0) * (n - 1))
    rC1, rC3 = g / f0, -g / f0**3 * (0.5 + f2 * f0)
    k1 = (1 / f0 + 2 * f2 * (1 - n)) / n
    k3p = ((-8 * f2**3 / 3 - (1 / 3 + f2 * f0) / f0**3 - (1 / f0 + 2 * f2) ** 3 / 6) / n
           + f2 * k1 / n * (1 / f0 + 2 * f2) + 4 * f2**3)
    dr1 = g / f0 - 1
    v11 = dr1 - d0 * k1
    OA2, ZC2, P2 = (1 + 2 * f0 * f2) / (2 * f0), g**2 * f2 / f0**2, dr1**2
    W2 = (OA2 + ZC2) / n
    dz2 = f2 * (g**2 / f0**2 - 1)
    Q2 = -dz2 - dr1 * k1
    D2 = (4 * d0 * W2 + P2 + 2 * d0 * (Q2 - W2)) / (4 * d0)
    v13 = rC3 + D2 * k1 - d0 * k3p - v11 * (D2 - W2) / d0
    v22 = dz2 + d0 * k1**2 / 2 + 2 * D2 - W2
    f4 = (g * f2 * (1 + 2 * f2 * f0)
          + f0**3 * n / (d0 * (n - 1)) * (v13 + n * v11 * v22 / ((n - 1) * d0))) / (4 * (g**3 - f0**3))
    k3 = 4 * f4 * (1 / n - 1) + k3p
    F2 = (n * (g**2 - f0**2) - 2 * d0 * g) / (4 * d0**2 * g)
    RB1, RB3 = 1 + d0 * k1, d0 * k3 - D2 * k1
    ZB2 = F2 * RB1**2
    BC2 = ((RB1 - rC1) ** 2 + 2 * d0 * (ZB2 - ZC2)) / (2 * d0**2)
    EU1 = (RB1 - rC1) / d0 + k1
    EU2 = (ZB2 - ZC2 - d0 * BC2) / d0 - k1**2 / 2
    EU3 = (RB3 - rC3 - BC2 * (RB1 - rC1)) / d0 + k3
    EW3 = EU3 / 2 - EU1 / 16 * (EU1**2 + 4 * EU2)
    F4 = F2**3 - (EW3 / 2 + F2 * RB3) / (2 * RB1**3)
    return SeriesCoefficients(n, f0, d0, g, f2, f4, F2, F4, k1, k3, k3p, D2, W2, RB1, RB3, rC1, rC3)


def _check_index(n: float) -> None:
    if n < 1.001:
        raise DesignError("material", f"the mirror-lens needs a refracting body: n = {n:.5g} (εr {n * n:.5g}) "
                          "must exceed 1.001")


# ------------------------------------------------------------------ exact synthesis, seed-004 §2.2

@dataclass(frozen=True)
class Profiles:
    """Both generatrices as sampled rays, one per exit radius ``s`` (= r_C). Front face: z = ``f``
    with slope ``df`` at r = s. Ray of that exit point: entry radius ``r_a`` at launch angle
    ``alpha`` (in air for f0 > 0, in the dielectric for the feed on the surface), mirror point
    (``R_b``, ``Z_b``) with mirror slope ``dF``; ``d`` = |AB|, ``t`` = |BC|."""
    n: float
    f0: float
    d0: float
    gamma: float
    s: np.ndarray
    f: np.ndarray
    df: np.ndarray
    r_a: np.ndarray
    alpha: np.ndarray
    R_b: np.ndarray
    Z_b: np.ndarray
    dF: np.ndarray
    d: np.ndarray
    t: np.ndarray

    @property
    def feed_on_surface(self) -> bool:
        return self.f0 == 0.0

    @property
    def L0(self) -> float:
        return 2 * self.f0 + 2 * self.n * self.d0

    def front_spline(self) -> CubicHermiteSpline:
        """z = f(r): C¹ Hermite through the marched points and their exact slopes."""
        return CubicHermiteSpline(self.s, self.f, self.df)

    def mirror_spline(self) -> CubicHermiteSpline:
        """Z = F(R) on the mirror locus with the slopes the reflection law gives."""
        return CubicHermiteSpline(self.R_b, self.Z_b, self.dF)

    def curvature_splines(self) -> tuple[CubicSpline, CubicSpline]:
        """f''(r) and F''(R): cubic splines of the exact slopes, differentiated."""
        return CubicSpline(self.s, self.df).derivative(), CubicSpline(self.R_b, self.dF).derivative()


class _History:
    """f and f' on the uniform grid marched so far; scalar cubic Hermite between nodes."""

    def __init__(self, h: float, size: int):
        self.h = h
        self.f = [0.0] * size            # floats (the march's scalar arithmetic), arrays at the end
        self.df = [0.0] * size

    def __call__(self, r: float) -> tuple[float, float]:
        h = self.h
        i = min(int(r / h), len(self.f) - 2)
        u = r / h - i
        f0, f1, m0, m1 = self.f[i], self.f[i + 1], self.df[i] * h, self.df[i + 1] * h
        u2, u3 = u * u, u * u * u
        val = (2 * u3 - 3 * u2 + 1) * f0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * f1 + (u3 - u2) * m1
        der = ((6 * u2 - 6 * u) * f0 + (3 * u2 - 4 * u + 1) * m0 + (-6 * u2 + 6 * u) * f1 + (3 * u2 - 2 * u) * m1) / h
        return val, der


def _ray(s: float, z_c: float, hist: _History, n: float, gamma: float, L0: float, r_guess: float):
    """The ray that leaves at exit radius s from the front face at height z_c (seed-004 §2.1):
    entry point on the history by the sine condition (1), refraction at A, segment d from equal
    path (7)–(8), direction of BC (9); returns (slope at C (10), r_A, α, B, dF at B, d, |BC|)."""
    r = r_guess
    for _ in range(50):                      # Newton on γ r/√(r² + f²) = s
        f, df = hist(r)
        rho = math.hypot(r, f)
        g = gamma * r / rho - s
        step = g / (gamma * (f * f - r * f * df) / rho**3)
        new = r - step
        if not 0.0 < new < s:                # safeguard: stay inside the history (0, s)
            new = 0.5 * (r + (s if new >= s else 0.0))
        step, r = r - new, new
        if abs(step) < 1e-16:
            break
    f, df = hist(r)
    rho = math.hypot(r, f)
    alpha = math.atan2(r, f)
    th = math.atan(df)
    arg = math.sin(alpha + th) / n
    xi = math.asin(arg) - th
    sx, cx = math.sin(xi), math.cos(xi)
    W = (L0 - rho - z_c) / n
    P2 = (s - r) ** 2 + (z_c - f) ** 2
    Q = (f - z_c) * cx + (r - s) * sx
    d = (W * W - P2) / (2 * (Q + W))
    bc = W - d
    Rb, Zb = r + d * sx, f + d * cx
    v1, v2 = (s - Rb) / bc, (z_c - Zb) / bc
    nr, nz = v1 - sx, v2 - cx                 # mirror normal ∥ v − u (reflection law)
    return -v1 / (1 / n + v2), r, alpha, Rb, Zb, -nr / nz, d, bc


def synthesize_profiles(n: float, f0: float, d0: float, gamma: float, step: float = STEP,
                        radius: float = APERTURE_RADIUS) -> Profiles:
    """Exact synthesis (seed-004 §2.2): the front face as a neutral delay ODE f'(s) = G(s, f(s);
    f|[0,s)) in the exit radius, seeded with the corrected series for s ≤ 2e-3 and marched with RK4;
    the mirror is the locus of B. f0 = 0 (feed on the surface) uses the ODE (16) instead."""
    if f0 == 0.0:
        return feed_on_surface_profiles(n, d0, gamma, radius)
    co = series_coefficients(n, f0, d0, gamma)
    L0 = 2 * f0 + 2 * n * d0
    if radius >= gamma:
        raise DesignError("design.gamma", f"γ = {gamma:g} must exceed the aperture radius {radius:g} "
                          "(r_C = γ sin α); increase gamma")
    count = int(round(radius / step))
    h = radius / count
    hist = _History(h, count + 1)
    seed = int(math.ceil(SEED_RADIUS / h))
    s = np.arange(count + 1) * h
    hist.f[: seed + 1] = co.front(s[: seed + 1]).tolist()
    hist.df[: seed + 1] = (2 * co.f2 * s[: seed + 1] + 4 * co.f4 * s[: seed + 1] ** 3).tolist()
    s, s_grid = s.tolist(), s
    r_prev = s[seed] * f0 / gamma

    def G(x, z):
        nonlocal r_prev
        out = _ray(x, z, hist, n, gamma, L0, r_prev)
        r_prev = out[1]
        return out[0]

    try:
        for i in range(seed, count):
            x, z = s[i], hist.f[i]
            k1 = hist.df[i]
            k2 = G(x + h / 2, z + h / 2 * k1)
            k3 = G(x + h / 2, z + h / 2 * k2)
            k4 = G(x + h, z + h * k3)
            hist.f[i + 1] = z + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            hist.df[i + 1] = G(x + h, hist.f[i + 1])
            if not math.isfinite(hist.f[i + 1]):
                raise ValueError
    except (ValueError, ZeroDivisionError, IndexError):
        raise DesignError("design.gamma", f"the exact synthesis breaks down at exit radius {s[i]:.3f} D "
                          f"(n {n:g}, f0 {f0:g}, d0 {d0:g}, γ {gamma:g}): total internal reflection or no "
                          "mirror point; change gamma or f0/d0") from None
    rays = [(0.0, 0.0, 0.0, f0 + d0, 0.0, d0, d0)]
    r_prev = s[1] * f0 / gamma
    for i in range(1, count + 1):
        rays.append(_ray(s[i], hist.f[i], hist, n, gamma, L0, r_prev)[1:])
        r_prev = rays[-1][0]
    r_a, alpha, Rb, Zb, dF, d, t = (np.array(c) for c in zip(*rays))
    f, df = np.array(hist.f), np.array(hist.df)
    finite = all(np.all(np.isfinite(a)) for a in (f, df, Rb, Zb, dF, d, t))
    if not finite or np.any(np.diff(Rb) <= 0) or np.any(d <= 0) or np.any(t <= 0):
        raise DesignError("design.gamma", f"the mirror generatrix folds over (n {n:g}, f0 {f0:g}, d0 {d0:g}, "
                          f"γ {gamma:g}); change gamma or d0")
    return Profiles(n, f0, d0, gamma, s_grid, f, df, r_a, alpha, Rb, Zb, dF, d, t)


# ------------------------------------------------------------------ feed on the surface, seed-004 §2.4

def _mu(alpha, r, n, d0, gamma):
    """Exit-ray angle μ from (17) in the stable form q = P(n−1)/(1 + √(1 − P²(n²−1)))."""
    P = (gamma - r) * np.sin(alpha) / (2 * n * d0 - r * (n + np.cos(alpha)))
    disc = 1 - P**2 * (n * n - 1)
    if np.any(disc < 0):
        raise ValueError("no real exit angle")
    return 2 * np.arctan(P * (n - 1) / (1 + np.sqrt(disc)))


def feed_on_surface_profiles(n: float, d0: float, gamma: float, radius: float = APERTURE_RADIUS,
                             samples: int = 2001) -> Profiles:
    """f0 = 0: the mirror as the polar curve r(α) of ODE (16), dr/dα = r tan((α + μ)/2), r(0) = d0,
    solved to rtol 1e-12; the lens points C from (17) and the lens-point relations (L203–207)."""
    _check_index(n)
    if radius >= gamma:
        raise DesignError("design.gamma", f"γ = {gamma:g} must exceed the aperture radius {radius:g}; increase gamma")
    a_max = math.asin(radius / gamma)

    def rhs(a, y):
        return y * np.tan((a + _mu(a, y[0], n, d0, gamma)) / 2)

    try:
        sol = solve_ivp(rhs, (0.0, a_max), [d0], method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    except ValueError:
        sol = None
    if sol is None or not sol.success:
        raise DesignError("design.gamma", f"the feed-on-surface ODE (16) has no solution up to the rim "
                          f"(n {n:g}, d0 {d0:g}, γ {gamma:g}); change gamma or d0")
    alpha = a_max * np.sin(np.linspace(0.0, np.pi / 2, samples))     # denser toward the rim
    r = sol.sol(alpha)[0]
    dr = r * np.tan((alpha + _mu(alpha, r, n, d0, gamma)) / 2)
    mu = _mu(alpha, r, n, d0, gamma)
    t = (2 * n * d0 - r * (n + np.cos(alpha))) / (n - np.cos(mu))
    x_c, z_c = r * np.sin(alpha) + t * np.sin(mu), r * np.cos(alpha) - t * np.cos(mu)
    Rb, Zb = r * np.sin(alpha), r * np.cos(alpha)
    dR, dZ = dr * np.sin(alpha) + r * np.cos(alpha), dr * np.cos(alpha) - r * np.sin(alpha)
    dF = dZ / dR
    # exit slope at C from the refraction law: inside direction v = (sin μ, −cos μ), outside (0, −1)
    v1, v2 = np.sin(mu), -np.cos(mu)
    df = -v1 / (1 / n + v2)
    if np.any(np.diff(x_c) <= 0) or np.any(np.diff(Rb) <= 0) or np.any(t <= 0):
        raise DesignError("design.gamma", f"the feed-on-surface profiles fold over (n {n:g}, d0 {d0:g}, "
                          f"γ {gamma:g}); change gamma or d0")
    return Profiles(n, 0.0, d0, gamma, x_c, z_c, df, np.zeros_like(alpha), alpha, Rb, Zb, dF, r, t)


def feed_on_surface_series(n: float, d0: float, gamma: float) -> tuple[float, float]:
    """R2, R4 of r(α) = d0 + R2 α² + R4 α⁴, seed-004 §2.4 (L211–217, verified as printed)."""
    C1 = d0 * (n - 1)
    C2 = (gamma - d0) / C1
    C3 = (n - 1) * C2 / 2
    R2 = (0.5 + C3) * d0 / 2
    Q1 = d0 / 2 - R2 * (n + 1)
    Q2 = (d0 - gamma - 6 * R2) / (6 * C1) - Q1 * (gamma - d0) / C1**2
    Q3 = (n - 1) * Q2 / 2 + (n - 1) ** 2 * (n + 1) * C2**3 / 8
    R4 = (d0 * (Q3 + 1 / 24 + C3 / 4 + C3**2 / 2) + R2 * (0.5 + C3)) / 4
    return R2, R4


# ------------------------------------------------------------------ astigmatism, seed-004 §3.2–§3.3

def _lx_ly(n, alpha, rho, omega, xi, Omega, d, t, R_b, f2nd, F2nd, *, A2Y=None, MY2=None):
    """L_X, L_Y of (19) from the ray's geometry (general coefficients of §3.2, [FIX] sin²φ)."""
    ca, cw, cW = np.cos(alpha), np.cos(omega), np.cos(Omega)
    cwa, cWx = np.cos(omega - alpha), np.cos(Omega - xi)
    root = np.sqrt(n * n - np.sin(omega) ** 2)
    A2X = (cw**2 / rho + root**2 / (n * d)) / (2 * cwa**2) + (ca - n * np.cos(xi)) / 2 * f2nd
    MX2 = cW**2 / (2 * cWx**2) * (1 / t + 1 / d) + F2nd * cW * cWx
    NX = -cW * root / (n * d * cwa * cWx)
    A1X = cw * ca / (rho * cwa)
    LX = ca**2 / (2 * rho) - MX2 * A1X**2 / (4 * A2X * MX2 - n * NX**2)
    if A2Y is None:
        A2Y = n * R_b / (2 * d * rho * np.sin(alpha))
    if MY2 is None:
        MY2 = 1 / (2 * d) + 1 / (2 * t) + np.sin(Omega - xi) * cW / R_b
    NY = -1 / d
    LY = 1 / (2 * rho) - MY2 / rho**2 / (4 * A2Y * MY2 - n * NY**2)
    return LX, LY


def astigmatism_exact(p: Profiles, r_exit) -> tuple[np.ndarray, np.ndarray]:
    """L_X, L_Y at exit radii ``r_exit``: the general formula of §3.2 on the exact ray geometry
    (f0 > 0), or eq. (20) of §3.3 on the ODE mirror (feed on the surface)."""
    r_exit = np.atleast_1d(np.asarray(r_exit, float))
    if p.feed_on_surface:
        return _astigmatism_on_surface(p, r_exit)
    ray = CubicSpline(p.s, np.stack([p.r_a, p.alpha, p.R_b, p.d, p.t]), axis=1)(r_exit)
    r_a, alpha, R_b, d, t = ray
    front, mirror = p.front_spline(), p.mirror_spline()
    f2nd, F2nd = p.curvature_splines()
    z_a = front(r_a)
    rho = np.hypot(r_a, z_a)
    omega = alpha + np.arctan(front.derivative()(r_a))
    xi = np.arcsin(np.sin(omega) / p.n) - (omega - alpha)
    Omega = xi + np.arctan(mirror.derivative()(R_b))
    return _lx_ly(p.n, alpha, rho, omega, xi, Omega, d, t, R_b, f2nd(r_a), F2nd(R_b))


def _astigmatism_on_surface(p: Profiles, r_exit: np.ndarray):
    """Eq. (20): L_X = cos²α / 2[r + t cosΩ/(cosΩ − 2K_B t)], L_Y = (1 − t/γ)/2r."""
    alpha = np.arcsin(r_exit / p.gamma)
    sp = CubicSpline(p.alpha, p.d)
    r, r1, r2 = sp(alpha), sp.derivative()(alpha), sp.derivative(2)(alpha)
    t = CubicSpline(p.alpha, p.t)(alpha)
    Omega = np.arctan(r1 / r)
    KB = (r**2 + 2 * r1**2 - r * r2) / (r**2 + r1**2) ** 1.5
    LX = np.cos(alpha) ** 2 / (2 * (r + t * np.cos(Omega) / (np.cos(Omega) - 2 * KB * t)))
    LY = (1 - t / p.gamma) / (2 * r)
    return LX, LY


def astigmatism_series(co: SeriesCoefficients, r_exit) -> tuple[np.ndarray, np.ndarray]:
    """L_X, L_Y of (19) with the paper's series substitutions (§3.2, r_A inversion [FIX])."""
    r = np.atleast_1d(np.asarray(r_exit, float))
    n = co.n
    r_a = r / co.rC1 - co.rC3 / co.rC1**4 * r**3
    rho = np.hypot(r_a, co.front(r_a))
    alpha = np.arcsin(r / co.gamma)
    t, d = co.d0 + (co.D2 - co.W2) * r_a**2, co.d0 - co.D2 * r_a**2
    omega = (1 + 2 * co.f2 * co.f0) * r_a / co.f0
    Omega = (co.k1 + 2 * co.F2 * co.RB1) * r_a
    xi = co.k1 * r_a
    R_b = co.RB1 * r_a + co.RB3 * r_a**3
    MY2 = (1 / d + 1 / t) / 2 + (2 * co.F2 + 4 * (co.F4 - co.F2**3) * co.RB1**2 * r_a**2) * np.cos(Omega)
    A2Y = n * (co.RB1 + co.RB3 * r_a**2) / (2 * d)
    return _lx_ly(n, alpha, rho, omega, xi, Omega, d, t, R_b, 2 * co.f2 + 12 * co.f4 * r_a**2,
                  2 * co.F2 + 12 * co.F4 * R_b**2, A2Y=A2Y, MY2=MY2)


def target_A(n: float, f0: float, d0: float, gamma: float, mode: str = "series",
             radii: tuple[float, ...] = TARGET_RADII) -> float:
    """Σ |L_X − L_Y| at the sample radii, eq. (21); ``mode`` series (19) or exact (marched geometry)."""
    if mode == "series":
        lx, ly = astigmatism_series(series_coefficients(n, f0, d0, gamma), radii)
    else:
        zone = min(APERTURE_RADIUS, max(radii) + 0.05)        # only the sampled zone needs to exist
        lx, ly = astigmatism_exact(synthesize_profiles(n, f0, d0, gamma, step=1e-3, radius=zone), radii)
    return float(np.sum(np.abs(lx - ly)))


@dataclass(frozen=True)
class Optimum:
    n: float
    f0: float
    d0: float
    gamma: float
    A: float
    mode: str


def optimize_target(n: float, f0: float, d0: float, gamma: float, *, free: tuple[str, ...] = ("gamma",),
                    mode: str = "series", bounds: dict[str, tuple[float, float]] | None = None,
                    length: float | None = None) -> Optimum:
    """Minimise A (21) over the ``free`` parameters among gamma, f0 and n (seed-004 §3.4), f0 + d0 =
    ``length`` held (default: the starting f0 + d0). Default bounds: γ ∈ [f0 + 0.05, 2·length],
    f0 ∈ [0.05, 0.95]·length, n ∈ [1.05, 4]. The free problem has degenerate zeros at γ → f0 and
    n → 1 (§3.5 item 2), so bounds matter; the published γ is reproduced in 1-D (γ, series mode)."""
    length = f0 + d0 if length is None else length
    start = {"gamma": gamma, "f0": f0, "n": n}
    lim = {"gamma": (f0 + 0.05, 2 * length), "f0": (0.05 * length, 0.95 * length), "n": (1.05, 4.0)}
    lim |= bounds or {}

    def unpack(x):
        v = dict(start) | dict(zip(free, x))
        return v["n"], v["f0"], length - v["f0"], v["gamma"]

    def A(x):
        try:
            return target_A(*unpack(x), mode=mode)
        except (DesignError, FloatingPointError, ValueError):
            return 1e3

    if free == ("gamma",):
        res = minimize_scalar(lambda g: A([g]), bounds=lim["gamma"], method="bounded",
                              options={"xatol": 1e-7 if mode == "series" else 1e-5})
        x = [res.x]
    else:
        res = minimize(A, [start[k] for k in free], method="Nelder-Mead", bounds=[lim[k] for k in free],
                       options={"xatol": 1e-7, "fatol": 1e-10, "maxiter": 4000})
        x = list(res.x)
    n_, f0_, d0_, g_ = unpack(x)
    return Optimum(n_, f0_, d0_, g_, A(x), mode)
