"""Bifocal (two-surface) homogeneous dielectric lens collimator — synthesis and GO verification.

Sources: seed-000 (Nikulina 2021) §1.3, §2.3–§2.8, §5.8–§5.9, §7.4 and seed-001 (Ngiem 2018) §3.1
(Kinber's method of steps). Cited below as ``seed-000 §x`` / ``seed-001 §x`` (the published sources
are listed in the README).

Frame (stated once, used everywhere in this module)
--------------------------------------------------
A 2-D meridional section. **z** is the optical axis (the seeds' *x*), pointing from the feeds toward
the antenna under test (AUT); **y** is transverse (the seeds' *y*; the radial coordinate r for a revolved
lens, the width coordinate for a cylindrical one). **Origin: on the axis in the plane of the feeds**
(seed-000 §1.3). The two perfect foci are ``O1 = (0, +a)`` and ``O2 = (0, −a)``; a feed at O1 gives a plane
front leaving in direction ``u1 = (cos α, −sin α)`` (toward −y), O2 gives ``u2 = (cos α, +sin α)``. The
zero-thickness lens edge is ``A1 = (X_B, ±Y_B)`` and the AUT aperture is the plane ``z = c``. Points are
stored as ``(z, y)`` rows in **millimetres**; angles are radians inside this module. Both surfaces are
even in y; arrays hold the full profile (−Y_B … +Y_B), sorted by y.

Constructions
-------------
* ``"nikulina"`` — seed-000 §3.2 made well posed (digest §2.7): Snell's law at every chain point makes
  each step closed form; the single free parameter ρ1 (illuminated vertex) is found by shooting so that
  the two surfaces meet (zero thickness) at the rim y = Y_B. The equal-edge ellipse (3.1)–(3.7) then puts
  that rim at z = X_B. The point chain is joined by C¹ cubic Hermite profiles (slopes from the Snell
  normals), the smooth representation handed to CAD.
* ``"kinber"`` — seed-001 §3.1: central parabolic segments of both surfaces, foci from (3.1), then
  alternating segment images (3.2)–(3.9) until the aperture is covered. Plane output (ρ2 = ∞) is the
  digest's derived form. :func:`kinber_lens` is the faithful construction from the seed's own
  parameters (a0, a2, h1, b0, b2, h2, ρ1, ρ2); ``synthesize_bifocal(construction="kinber")`` fits its
  central segments to the spec's foci and tilt (see :func:`synthesize_bifocal`).

Modules: the shared closed-form steps are :mod:`.bifocal_steps`, Kinber's construction and its RMS
:mod:`.kinber`, the verification trace and defocus study :mod:`.bifocal_trace`, the solid figures
(face splines, volume, slab radius) :mod:`.bifocal_solids`; their public names are re-exported here.

The single-surface hyperbolic comparison lens (seed-000 §2.1, (1.9) corrected, (1.1)) and its scan-range
study are the shared :mod:`antenna_cad.raytrace.collimator`.

3-D shape: the synthesis is the 2-D section (seed-000 §7.2 leaves the 3-D form open). ``cylindrical``
extrudes it (exact in every section); ``revolved`` turns it about the axis, which smears the two foci
into a ring of radius a — the design is then exact only for feeds in the meridional plane.
"""


from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from scipy.optimize import brentq, least_squares

from antenna_cad.raytrace.snell import refract
from antenna_cad.raytrace.trace2d import Interface
from antenna_cad.synthesis.bifocal_solids import face_spline, lens_volume_mm3, max_radius_in
from antenna_cad.synthesis.bifocal_steps import (_back_plane1, _fwd_plane1, _hermite, _mirror, _Optics,
                                                 _symmetric_profile, _unit)
from antenna_cad.synthesis.bifocal_trace import (C0_MM_PER_NS, DefocusStudy, _design_focus_eikonal,
                                                 aperture_phase, defocus_study, trace_bifocal)
from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.kinber import (KinberLens, KinberView, kinber_focal_circle_rms, kinber_lens,
                                          kinber_rms, resolve_kinber)

__all__ = [
    "BifocalDesign", "KinberLens", "DefocusStudy", "equal_edge_ellipse", "thin_ray_rho2",
    "polar_polynomial", "synthesize_bifocal", "kinber_lens", "trace_bifocal", "aperture_phase",
    "defocus_study", "kinber_rms", "kinber_focal_circle_rms", "face_spline", "lens_volume_mm3",
    "max_radius_in", "C0_MM_PER_NS",
]


# --------------------------------------------------------------------------------------------------
# Closed forms: equal-edge ellipse (3.1)–(3.7), thin-ray start (3.64), polynomial surfaces (1.11)
# --------------------------------------------------------------------------------------------------

def equal_edge_ellipse(edge_x_mm: float, edge_y_mm: float, beam_tilt_rad: float | None = None,
                       focus_offset_mm: float | None = None) -> tuple[float, float, float]:
    """Return ``(s_mm, a_mm, alpha_rad)`` of the equal-edge ellipse through A1 = (X_B, Y_B).

    seed-000 §2.3: ``X_B² + Y_B² cos²α = a² ctg²α`` (1.10)/(3.1); ``s = −X_B + sqrt(X_B² + Y_B² cos²α)``
    (3.7, "+" root); ``a = (s² + Y_B² cos²α)/(2 s ctg α)`` (3.6), which equals ``(X_B + s)·tg α``.
    Give exactly one of α and a; the other is solved (α from a by root finding, (3.5) holds then).
    """
    xb, yb = float(edge_x_mm), float(edge_y_mm)
    if not xb > 0.0:
        raise DesignError("design.edge_x_mm", f"(3.8) needs 0 < X_B; got {xb:.6g} mm")
    if not yb > 0.0:
        raise DesignError("design.edge_y_mm", f"aperture half-size Y_B must be > 0; got {yb:.6g} mm")
    if beam_tilt_rad is None and focus_offset_mm is None:
        raise DesignError("design", "give beam_tilt_deg or focus_offset_mm (the other is solved by (3.6))")
    if beam_tilt_rad is not None:
        alpha = float(beam_tilt_rad)
        if not 0.0 < alpha < np.pi / 2:
            raise DesignError("design.beam_tilt_deg",
                              f"(3.5) needs 0 < α < 90°; got {np.degrees(alpha):.6g}°")
    else:
        a_req = float(focus_offset_mm)
        if not a_req > 0.0:
            raise DesignError("design.focus_offset_mm", f"focus offset a must be > 0; got {a_req:.6g} mm")
        g = lambda al: np.sqrt(xb**2 + yb**2 * np.cos(al) ** 2) * np.tan(al) - a_req  # noqa: E731
        alpha = brentq(g, 1e-12, np.pi / 2 - 1e-9, xtol=1e-15, rtol=1e-15)
    c2 = np.cos(alpha) ** 2
    s = -xb + np.sqrt(xb**2 + yb**2 * c2)                                  # (3.7)
    a = (s**2 + yb**2 * c2) / (2.0 * s / np.tan(alpha))                    # (3.6)
    arg = np.sqrt(2.0 * xb * s + s**2) / yb                                # (3.5) argument
    if not (s > 0.0 and arg <= 1.0 + 1e-12):
        raise DesignError("design.beam_tilt_deg", f"(3.5) needs 0 < sqrt(2X_B s + s²)/Y_B ≤ 1; got {arg:.6g}")
    return float(s), float(a), float(alpha)


def thin_ray_rho2(rho1_mm: float, edge_x_mm: float, edge_y_mm: float, a_mm: float,
                  alpha_rad: float, n: float) -> float:
    """Thin-ray start point ρ2(ρ1), seed-000 §2.5 eq. (3.64) (c cancels; k2/k1 = n)."""
    xb, yb, a, al = edge_x_mm, edge_y_mm, a_mm, alpha_rad
    num = (np.hypot(xb, yb - a) - xb * np.cos(al) + yb * np.sin(al) - np.hypot(rho1_mm, a) + n * rho1_mm)
    return float(num / (n - np.cos(al)))


def polar_polynomial(rho0: float, A: float, B: float, theta: np.ndarray) -> np.ndarray:
    """Seed-000 (1.11): ``ρ(θ) = ρ0 (1 + A θ² + B θ⁴)``, θ in radians about the origin."""
    theta = np.asarray(theta, float)
    return rho0 * (1.0 + A * theta**2 + B * theta**4)


def _fit_polar(points: np.ndarray) -> tuple[tuple[float, float, float], float]:
    """Least-squares (1.11) fit to (z, y) points; returns ((ρ0, A, B), max |Δρ| in the same unit)."""
    rho = np.hypot(points[:, 0], points[:, 1])
    th = np.arctan2(np.abs(points[:, 1]), points[:, 0])
    M = np.stack([np.ones_like(th), th**2, th**4], axis=-1)
    coef, *_ = np.linalg.lstsq(M, rho, rcond=None)
    resid = float(np.max(np.abs(M @ coef - rho)))
    return (float(coef[0]), float(coef[1] / coef[0]), float(coef[2] / coef[0])), resid


# --------------------------------------------------------------------------------------------------
# The design record
# --------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class BifocalDesign:
    """A synthesized bifocal lens in the module frame (z axial from the feed plane, y transverse, mm).

    ``illuminated_mm`` / ``shadow_mm``: (N, 2) constructed points (z, y), full even profile sorted by y,
    ending at the rim ±Y_B; ``*_normals``: unit normals there; ``*_slopes``: dz/dy. The smooth CAD
    representation is the C¹ cubic Hermite profile through these points (:meth:`profile`,
    :meth:`polyline`). ``poly_*`` are the seed's (1.11) coefficients (ρ_ν in mm, A_ν, B_ν with θ in
    radians), least-squares fitted; ``poly_fit_residual_mm`` is the max radial deviation of that fit.
    ``residual_path_error_mm``: peak-to-peak eikonal error of an exact trace through the Hermite
    profiles from (O1, O2) to their plane fronts (or, for a point-image Kinber lens, to the image
    points ``image_points_mm``; ``exit_directions`` are then the chief rays' directions ω_B).
    """

    construction: str
    shape: str
    eps_r: float
    n: float
    edge_x_mm: float                 # X_B (rim position; Kinber: illuminated surface at y = Y_B)
    edge_y_mm: float                 # Y_B (aperture half-size)
    s_mm: float                      # (3.7)
    focus_offset_mm: float           # a
    beam_tilt_rad: float             # α
    antenna_x_mm: float              # c
    rho1_mm: float                   # illuminated vertex z
    rho2_mm: float                   # shadow vertex z
    thickness_mm: float              # ρ2 − ρ1
    edge_thickness_mm: float         # 0 for nikulina
    path_constant_mm: float          # L = |O1 P| + n|PQ| − u1·Q  (c-free eikonal)
    foci_mm: np.ndarray              # (2, 2): O1, O2 as (z, y)
    exit_directions: np.ndarray      # (2, 2): u1, u2
    illuminated_mm: np.ndarray
    illuminated_normals: np.ndarray
    illuminated_slopes: np.ndarray
    shadow_mm: np.ndarray
    shadow_normals: np.ndarray
    shadow_slopes: np.ndarray
    poly_illuminated: tuple[float, float, float]
    poly_shadow: tuple[float, float, float]
    poly_fit_residual_mm: float
    residual_path_error_mm: tuple[float, float]
    checks: tuple[Check, ...]
    params: dict = field(default_factory=dict)     # construction-specific inputs/outputs
    image_points_mm: np.ndarray | None = None      # (2, 2) O1', O2' of a point-image Kinber lens (else plane fronts)
    view: KinberView | None = None                 # Kinber: σ (3.10) over the view angle (D = 1)

    # -- smooth representation -------------------------------------------------------------------
    def profile(self, surface: Literal["illuminated", "shadow"], y_mm: np.ndarray) -> np.ndarray:
        """z (mm) of the C¹ Hermite profile at transverse positions ``y_mm``."""
        pts = self.illuminated_mm if surface == "illuminated" else self.shadow_mm
        sl = self.illuminated_slopes if surface == "illuminated" else self.shadow_slopes
        return _hermite(pts[:, 1], pts[:, 0], sl)(np.asarray(y_mm, float))

    def polyline(self, surface: Literal["illuminated", "shadow"], num: int = 401) -> np.ndarray:
        """Dense (z, y) polyline of one face from −Y_B to +Y_B (both faces share the rim points)."""
        y = np.linspace(-self.edge_y_mm, self.edge_y_mm, num)
        return np.stack([self.profile(surface, y), y], axis=-1)

    def interfaces(self, which: Literal["spline", "polynomial"] = "spline") -> tuple[Interface, Interface]:
        """The two faces as :class:`Interface` objects for :func:`antenna_cad.raytrace.trace2d.trace`."""
        if which == "spline":
            a = self.illuminated_mm
            b = self.shadow_mm
            return (Interface.from_points(a[:, 1], a[:, 0], self.n, self.illuminated_slopes),
                    Interface.from_points(b[:, 1], b[:, 0], 1.0, self.shadow_slopes))
        th_max = 1.3 * np.arctan2(self.edge_y_mm, self.edge_x_mm)
        th = np.linspace(-th_max, th_max, 4001)
        out = []
        for coef, n_after in ((self.poly_illuminated, self.n), (self.poly_shadow, 1.0)):
            r = polar_polynomial(*coef, th)
            out.append(Interface.from_points(r * np.sin(th), r * np.cos(th), n_after))
        return out[0], out[1]


# --------------------------------------------------------------------------------------------------
# Nikulina chain (seed-000 §3.2 with the digest's §2.7 completion)
# --------------------------------------------------------------------------------------------------

def _nikulina_chain(rho1: float, o: _Optics, max_steps: int = 1500):
    """C = (ρ1, 0) → G → mirror → B → mirror → H → … (digest §2.7 steps 1–4), run until a step fails
    (no root, TIR, or the faces would cross) or stalls at the rim. Returns (illuminated points,
    normals, shadow points, normals) as the chain produced them (alternating signs of y). The links
    shrink with the foci's separation; a chain longer than ``max_steps`` (the recipes need ≤ 250) is
    refused rather than solved for minutes."""
    mirror = lambda p: (p[0], -p[1])  # noqa: E731
    finite = lambda p: math.isfinite(p[0]) and math.isfinite(p[1])  # noqa: E731
    ill_p, ill_n = [(float(rho1), 0.0)], [(-1.0, 0.0)]
    sh_p, sh_n = [], []
    G, NG = _fwd_plane1(ill_p[0], ill_n[0], o)          # the steps on floats: one point at a time
    if finite(G):
        sh_p.append(G)
        sh_n.append(NG)
        for _ in range(max_steps):
            B, NB = _back_plane1(mirror(G), mirror(NG), o)
            if not finite(B) or abs(B[1]) - abs(ill_p[-1][1]) <= 1e-13 * abs(B[0]):
                break
            ill_p.append(B)
            ill_n.append(NB)
            G, NG = _fwd_plane1(mirror(B), mirror(NB), o)
            if not finite(G) or abs(G[1]) - abs(sh_p[-1][1]) <= 1e-13 * abs(G[0]):
                break
            sh_p.append(G)
            sh_n.append(NG)
        else:
            raise DesignError("design.beam_tilt_deg", f"the Nikulina construction needs more than {max_steps} "
                              "face segments (the foci are too close for this aperture); increase "
                              "beam_tilt_deg or focus_offset_mm")
    return (np.array(ill_p), np.array(ill_n), np.array(sh_p).reshape(-1, 2), np.array(sh_n).reshape(-1, 2))


def _closure(rho1: float, o: _Optics, xb: float) -> float:
    """Shooting function: farthest z the illuminated chain reaches, minus X_B. Below the closing ρ1
    the faces fold over before the rim; above it the illuminated face overshoots X_B; at the root the
    chain converges onto A1 = (X_B, Y_B) (the only zero-thickness point with equal eikonals, §2.3)."""
    ip = _nikulina_chain(rho1, o)[0]
    return float(np.max(ip[:, 0]) - xb)


def _solve_rho1(o: _Optics, xb: float, lo: float, hi: float, num: int = 60) -> float:
    grid = np.linspace(lo, hi, num + 2)[1:-1]
    vals = np.array([_closure(r, o, xb) for r in grid])
    for i in range(len(grid) - 1):
        if vals[i] < 0.0 <= vals[i + 1]:
            return float(brentq(_closure, grid[i], grid[i + 1], args=(o, xb), xtol=1e-13 * hi,
                                rtol=1e-15, maxiter=300))
    return np.nan


def _edge_normals(o1: _Optics, A1: np.ndarray, N1g: np.ndarray, N2g: np.ndarray):
    """Normals of both faces at the zero-thickness rim A1 (the digest's formalised Gent–Sternberg
    condition, seed-000 §2.8): ``d_k − n t_k ∥ N1`` and ``n t_k − u_k ∥ N2`` for both feeds k."""
    n = o1.n
    F = [o1.F, _mirror(o1.F)]
    U = [o1.k, _mirror(o1.k)]
    D = [_unit(A1 - f) for f in F]
    cr = lambda p, q: p[0] * q[1] - p[1] * q[0]  # noqa: E731
    ang = lambda v: np.arctan2(v[1], v[0])  # noqa: E731
    t0 = [refract(d[None], N1g[None], 1.0, n)[0][0] for d in D]
    x0 = np.array([ang(N1g), ang(N2g), ang(t0[0]), ang(t0[1])])

    def res(x):
        N1 = np.array([np.cos(x[0]), np.sin(x[0])])
        N2 = np.array([np.cos(x[1]), np.sin(x[1])])
        T = [np.array([np.cos(x[2]), np.sin(x[2])]), np.array([np.cos(x[3]), np.sin(x[3])])]
        return [cr(D[0] - n * T[0], N1), cr(D[1] - n * T[1], N1), cr(n * T[0] - U[0], N2),
                cr(n * T[1] - U[1], N2)]

    sol = least_squares(res, x0, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    N1 = np.array([np.cos(sol.x[0]), np.sin(sol.x[0])])
    N2 = np.array([np.cos(sol.x[1]), np.sin(sol.x[1])])
    return N1, N2, float(np.max(np.abs(sol.fun)))


def _rim_guess(pts: np.ndarray, nrm: np.ndarray, yb: float, cut: float = 1e-4) -> np.ndarray:
    """Start of the rim-normal solve: the normal of the chord through the two chain points closest
    to the rim (folded to y ≥ 0). The system has other roots; the last chain point's own normal
    led least squares to a steep one depending on the BLAS kernel (rim slope 64 vs 1.08). A chain
    with fewer than two such points (a design about to be refused) keeps its last normal."""
    y, z = np.abs(pts[:, 1]), pts[:, 0]
    keep = np.isfinite(y) & np.isfinite(z) & (y < (1.0 - cut) * yb)
    if keep.sum() < 2:
        return _mirror(nrm[-1]) if pts[-1, 1] < 0 else nrm[-1]
    order = np.argsort(y[keep])
    (y0, y1), (z0, z1) = y[keep][order][-2:], z[keep][order][-2:]
    return _unit(np.array([1.0, -(z1 - z0) / (y1 - y0)]))


def _rim_profile(pts, nrm, A1, N_edge, yb, cut=1e-4):
    """Even Hermite data from chain points (folded to y ≥ 0, kept for y < (1−cut)·Y_B) plus the rim A1."""
    fy = np.abs(pts[:, 1]) < (1.0 - cut) * yb
    p = np.concatenate([pts[fy], A1[None]])
    m = np.concatenate([nrm[fy], N_edge[None]])
    return _symmetric_profile(p, m)


# --------------------------------------------------------------------------------------------------
# Synthesis entry point
# --------------------------------------------------------------------------------------------------

def _finish_profile(y: np.ndarray, z: np.ndarray, sl: np.ndarray, yb: float
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cut a full even Hermite profile at ±Y_B, adding the rim points."""
    spl = _hermite(y, z, sl)
    der = spl.derivative()
    inside = np.abs(y) < yb * (1 - 1e-9)
    ye = np.concatenate([[-yb], y[inside], [yb]])
    return ye, spl(ye), np.concatenate([[der(-yb)], sl[inside], [der(yb)]])


def _design_checks(n, xb, yb, a, al, c, rho1, rho2, y_dense, z_ill, z_sh, zero_rim=True) -> list[Check]:
    """Realizability conditions (3.8)–(3.15) as corrected in seed-000 §2.3; raise on the first failure."""
    act = a / np.tan(al)
    tg = np.tan(al)
    checks: list[Check] = []

    def need(name, value, limit, unit, what, field_, rule):
        chk = Check.upper(name, value, limit, unit, what)
        checks.append(chk)
        if chk.status == "fail":
            raise DesignError(field_, f"{rule}: {chk.message}")

    # (3.14): a < ρ1·n  (refraction at the illuminated vertex is possible)
    need("bifocal_3_14_vertex_refraction", a / (rho1 * n), 1.0, "", "a/(ρ1·n) at the illuminated vertex",
         "design.focus_offset_mm", "(3.14) needs a < ρ1·n")
    # (3.8): 0 < ρ1 < a·ctgα < ρ2 < c ; 0 < X_B < c
    if not zero_rim:        # Kinber lens: the equal-edge ellipse relations do not apply
        need("bifocal_shadow_vertex_before_antenna", rho2, c, "mm",
             f"shadow vertex vs antenna plane c (move antenna_x_mm beyond {rho2:.1f} mm)",
             "design.antenna_x_mm", "needs ρ2 < c")
        reach = float(np.max(z_sh + abs(tg) * np.abs(y_dense)))
        need("bifocal_3_15_shadow_before_front", reach, c, "mm", "max(z + |tgα||y|) of the shadow face vs c",
             "design.antenna_x_mm", "(3.15) needs c > z + |tgα|·|y| on the shadow face")
        tmin = float(np.min(z_sh - z_ill))
        need("bifocal_positive_thickness", -tmin, 0.0, "mm", "negative of the minimum thickness",
             "design", "faces must not cross inside the aperture")
        return checks
    need("bifocal_3_8_rho1_inside_ellipse", rho1, act, "mm", "illuminated vertex ρ1 vs a·ctgα",
         "design.focus_offset_mm", "(3.8) needs ρ1 < a·ctgα")
    need("bifocal_3_8_rho2_outside_ellipse", act, rho2, "mm", "a·ctgα vs shadow vertex ρ2",
         "design.focus_offset_mm", "(3.8) needs a·ctgα < ρ2")
    need("bifocal_3_8_edge_before_antenna", xb, c, "mm", "edge X_B vs antenna plane c",
         "design.antenna_x_mm", "(3.8) needs X_B < c")
    need("bifocal_3_8_shadow_vertex_before_antenna", rho2, c, "mm",
         f"shadow vertex ρ2 vs antenna plane c (move antenna_x_mm beyond {rho2:.1f} mm)",
         "design.antenna_x_mm", "(3.8) needs ρ2 < c")
    # (3.11)/(3.12) corrected: A1P1 > 0  ⇔  X_B < c + Y_B·tgα
    need("bifocal_3_12_edge_ray_forward", xb, c + yb * tg, "mm", "X_B vs c + Y_B·tgα",
         "design.antenna_x_mm", "(3.11)/(3.12) corrected needs X_B < c + Y_B·tgα")
    # (3.15) robust form: c > z + |tgα|·|y| for every shadow point
    reach = float(np.max(z_sh + abs(tg) * np.abs(y_dense)))
    need("bifocal_3_15_shadow_before_front", reach, c, "mm", "max(z + |tgα||y|) of the shadow face vs c",
         "design.antenna_x_mm", "(3.15) needs c > z + |tgα|·|y| on the shadow face")
    # (3.8) interpretation: illuminated face inside the edge ellipse, shadow face outside
    inner = np.abs(y_dense) < yb * (1 - 1e-6)
    e_ill = float(np.max((np.sqrt(z_ill**2 + y_dense**2 * np.cos(al) ** 2) - act)[inner]))
    e_sh = float(np.max((act - np.sqrt(z_sh**2 + y_dense**2 * np.cos(al) ** 2))[inner]))
    need("bifocal_3_8_illuminated_inside_ellipse", e_ill, 0.0, "mm",
         "illuminated face outside the equal-edge ellipse by", "design", "(3.8)")
    need("bifocal_3_8_shadow_outside_ellipse", e_sh, 0.0, "mm",
         "shadow face inside the equal-edge ellipse by", "design", "(3.8)")
    # positive thickness everywhere inside the rim
    tmin = float(np.min((z_sh - z_ill)[inner]))
    need("bifocal_positive_thickness", -tmin, 0.0, "mm", "negative of the minimum thickness",
         "design", "faces must not cross inside the aperture")
    return checks


def synthesize_bifocal(*, edge_y_mm: float, eps_r: float, edge_x_mm: float | None = None,
                       focus_offset_mm: float | None = None, beam_tilt_deg: float | None = None,
                       antenna_x_mm: float | None = None,
                       shape: Literal["revolved", "cylindrical"] = "revolved",
                       construction: Literal["nikulina", "kinber"] = "nikulina",
                       kinber: dict | None = None, antenna_clearance_mm: float = 100.0,
                       ) -> BifocalDesign:
    """Synthesize a bifocal collimator lens (frame and units: module docstring).

    Inputs follow the spec's ``design`` block: rim ``(edge_x_mm, edge_y_mm) = (X_B, Y_B)``, focus offset
    ``a`` and/or tilt ``α`` (give one; if both, they must agree with (3.6) to 0.5 %), the AUT plane
    ``antenna_x_mm = c`` (None → ``antenna_clearance_mm`` beyond the lens's (3.15) limit).

    ``construction="nikulina"`` (default): seed-000 §3.2 with the §2.7 completion; ρ1 by shooting for
    zero thickness at the rim.

    ``construction="kinber"``: seed-001 §3.1 plane-output lens from the seed's own central-segment
    parameters ``kinber = {a0, a2, h1, b0, b2, h2 (None → A–O–B collinearity), rho1}`` in units of the
    aperture D (the seed normalises D = 1), scaled by ``D = 2·edge_y_mm``. The foci (hence a), the tilt
    α = ω_B and the rim position are *outputs* (``edge_x_mm``, ``focus_offset_mm``, ``beam_tilt_deg`` are
    ignored); the rim has a finite thickness. Fitting Kinber's central segments to a zero-thickness
    rim at a given (X_B, a, α) was tried and is unstable near the rim (segments fold over), so it is not
    offered: use ``nikulina`` for that.
    Raises :class:`DesignError` naming the violated realizability condition (3.5)–(3.15).
    """
    eps_r = float(eps_r)
    if not eps_r > 1.0:
        raise DesignError("material.eps_r", f"a decelerating lens needs εr > 1; got {eps_r:.6g}")
    n = float(np.sqrt(eps_r))
    yb = float(edge_y_mm)
    if construction == "kinber":
        return _kinber_design(n, eps_r, yb, kinber or {}, shape, antenna_x_mm, antenna_clearance_mm)
    if construction != "nikulina":
        raise DesignError("design.construction", f"must be 'nikulina' or 'kinber'; got {construction!r}")
    if edge_x_mm is None:
        raise DesignError("design.edge_x_mm", "the nikulina construction needs the rim position X_B")
    xb = float(edge_x_mm)
    if beam_tilt_deg is not None:
        s, a, al = equal_edge_ellipse(xb, yb, beam_tilt_rad=np.radians(beam_tilt_deg))
        if focus_offset_mm is not None and abs(focus_offset_mm - a) > 5e-3 * a:
            raise DesignError("design.focus_offset_mm",
                              f"(3.6) with α = {beam_tilt_deg:.6g}° needs a = {a:.6g} mm; got "
                              f"{focus_offset_mm:.6g} mm (give only one of a, α)")
    else:
        s, a, al = equal_edge_ellipse(xb, yb, focus_offset_mm=focus_offset_mm)
    u1 = np.array([np.cos(al), -np.sin(al)])
    O1 = np.array([0.0, a])
    A1 = np.array([xb, yb])
    L = float(np.linalg.norm(A1 - O1) - A1 @ u1)         # (3.19)–(3.20) with c removed
    o = _Optics(O1, n, L, k=u1)
    act = a / np.tan(al)
    params: dict = {}
    lo = max(a / n, 1e-6 * act)                            # (3.14) lower bound
    rho1 = _solve_rho1(o, xb, lo, act)
    if not np.isfinite(rho1):
        raise DesignError("design", "(3.8)/(3.14): no illuminated vertex ρ1 in (a/n, a·ctgα) = "
                          f"({lo:.1f}, {act:.1f}) mm closes the point chain at the rim A1 "
                          "(TIR or the faces never meet) — change a, α or the edge")
    ip, inn, sp, sn = _nikulina_chain(rho1, o)
    N1e, N2e, edge_res = _edge_normals(o, A1, _rim_guess(ip, inn, yb), _rim_guess(sp, sn, yb))
    yi, zi, si = _rim_profile(ip, inn, A1, N1e, yb)
    ys, zs, ss = _rim_profile(sp, sn, A1, N2e, yb)
    rim_gap = float(min(np.hypot(*(np.abs(ip[-1]) - A1)), np.hypot(*(np.abs(sp[-1]) - A1))))
    edge_t = 0.0
    params.update(chain_points_illuminated=len(ip), chain_points_shadow=len(sp),
                  chain_rim_gap_mm=rim_gap, edge_normal_residual=edge_res)

    return _assemble("nikulina", shape, eps_r, n, yb, s, a, al, L, float(rho1), (yi, zi, si),
                     (ys, zs, ss), edge_t, params, antenna_x_mm, antenna_clearance_mm, zero_rim=True)


def _assemble(construction, shape, eps_r, n, yb, s, a, al, L, rho1, ill_h, sh_h, edge_t, params,
              antenna_x_mm, clearance, zero_rim, images=None) -> BifocalDesign:
    """Common tail: realizability checks, (1.11) fit, design record, exact-trace residuals."""
    if shape not in ("revolved", "cylindrical"):
        raise DesignError("design.shape", f"must be 'revolved' or 'cylindrical'; got {shape!r}")
    yi, zi, si = ill_h
    ys, zs, ss = sh_h
    rho2 = float(_hermite(ys, zs, ss)(0.0))
    ill = np.stack([zi, yi], -1)
    sh = np.stack([zs, ys], -1)
    nrm = lambda sl: _unit(np.stack([np.ones_like(sl), -sl], -1))  # noqa: E731
    y_dense = np.linspace(-yb, yb, 801)
    z_ill_d = _hermite(yi, zi, si)(y_dense)
    z_sh_d = _hermite(ys, zs, ss)(y_dense)
    if antenna_x_mm is None:
        c = float(np.max(z_sh_d + abs(np.tan(al)) * np.abs(y_dense))) + clearance
    else:
        c = float(antenna_x_mm)
    checks = _design_checks(n, float(zi[-1]), yb, a, al, c, rho1, rho2, y_dense, z_ill_d, z_sh_d,
                            zero_rim)
    if images is not None:          # a point image beyond the lens (seed-001 §3.1, finite ρ2)
        gap = float(np.min(images[:, 0]) - np.max(z_sh_d))
        checks.append(Check.upper("kinber_image_beyond_lens", -gap, 0.0, "mm",
                                  "shadow face beyond the image points O1', O2' by (z)"))
        if checks[-1].status == "fail":
            raise DesignError("design.kinber.rho2", f"the image points lie inside the lens: {checks[-1].message}")
    checks.append(Check.upper("bifocal_rim_closure", params["chain_rim_gap_mm"], 1e-2 * yb, "mm",
                              "closest approach of the constructed points to the rim",
                              warn_margin=0.99e-2 * yb))
    pi_, ri = _fit_polar(ill)
    ps_, rs = _fit_polar(sh)
    O1 = np.array([0.0, a])
    u1 = np.array([np.cos(al), -np.sin(al)])
    design = BifocalDesign(
        construction=construction, shape=shape, eps_r=eps_r, n=n, edge_x_mm=float(zi[-1]),
        edge_y_mm=yb, s_mm=s, focus_offset_mm=a, beam_tilt_rad=al, antenna_x_mm=c,
        rho1_mm=float(rho1), rho2_mm=rho2, thickness_mm=rho2 - float(rho1), edge_thickness_mm=edge_t,
        path_constant_mm=L, foci_mm=np.array([O1, _mirror(O1)]),
        exit_directions=np.array([u1, _mirror(u1)]),
        illuminated_mm=ill, illuminated_normals=nrm(si), illuminated_slopes=si,
        shadow_mm=sh, shadow_normals=nrm(ss), shadow_slopes=ss,
        poly_illuminated=pi_, poly_shadow=ps_, poly_fit_residual_mm=max(ri, rs),
        residual_path_error_mm=(np.nan, np.nan), checks=tuple(checks), params=params, image_points_mm=images)
    res = tuple(float(np.ptp(_design_focus_eikonal(design, k))) for k in (0, 1))
    chk = Check.upper("bifocal_design_focus_path_error", max(res), 1e-6 * 2 * yb, "mm",
                      "peak-to-peak eikonal error at the design foci (exact trace)")
    if chk.status == "fail" or not np.isfinite(max(res)):
        raise DesignError("design", f"{chk.message} — the {construction} construction did not give a "
                          "focusing lens for this spec (faces fold or rays leave the aperture); change "
                          "a, α, the edge or εr")
    checks.append(chk)
    return _replace(design, residual_path_error_mm=res, checks=tuple(checks))


def _kinber_design(n, eps_r, yb, kp, shape, antenna_x_mm, clearance) -> BifocalDesign:
    """Seed-001 §3.1 lens from normalised parameters (D = 1; :func:`resolve_kinber`: C² a2/b2, h
    optimised over the view, plane or point output), scaled to D = 2·Y_B and moved into this
    module's frame (feed plane z = 0 through the foci). A point-image lens (finite ρ2) records its
    image points O1', O2' (the seed's F2', F1' in this frame's orientation)."""
    need = ("a0", "a2", "h1", "b0", "b2", "rho1")
    missing = [k for k in need if k not in kp]
    if missing:
        raise DesignError("design.kinber", f"missing Kinber parameters {missing} (seed-001 §3.1 table)")
    lens, kp, view = resolve_kinber(n, kp)
    scale = 2.0 * yb
    shift = np.array([lens.F1[0], 0.0])
    a = abs(float(lens.F1[1])) * scale
    al = lens.omega_B_rad
    if not 0.0 < al < np.pi / 2:
        raise DesignError("design.kinber", f"output direction ω_B = {np.degrees(al):.4g}° is not in (0, 90°)")
    P1 = (lens.surface1 - shift) * scale
    P2 = (lens.surface2 - shift) * scale
    ill_h = _finish_profile(P1[:, 1], P1[:, 0], lens.slopes1, yb)
    sh_h = _finish_profile(P2[:, 1], P2[:, 0], lens.slopes2, yb)
    images = None
    if lens.F1p is None:
        L = scale * (lens.L + lens.k[0] * lens.F1[0])
    else:
        L = scale * lens.L
        o1p = _mirror((lens.F1p - shift) * scale)
        images = np.array([o1p, _mirror(o1p)])
    rho1 = float(_hermite(*ill_h)(0.0))
    params = {f"kinber_{k}": float(kp[k]) for k in need + ("h2",)}
    params.update(kinber_rho2=float(kp["rho2"]) if kp.get("rho2") is not None else None,
                  kinber_segments=lens.segments, chain_rim_gap_mm=0.0,
                  kinber_omega_B_deg=float(np.degrees(al)), kinber_alpha_A_deg=float(np.degrees(lens.alpha_A_rad)))
    edge_t = float(sh_h[1][-1] - ill_h[1][-1])
    design = _assemble("kinber", shape, eps_r, n, yb, float("nan"), a, al, L, rho1, ill_h, sh_h, edge_t,
                       params, antenna_x_mm, clearance, zero_rim=False, images=images)
    return _replace(design, view=view)


def _replace(d: BifocalDesign, **kw) -> BifocalDesign:
    from dataclasses import replace
    return replace(d, **kw)
