"""Kinber's bifocal lens (seed-001 §3.1): the method of steps from the seed's central-segment
parameters, the RMS (3.10) over the view angle, the central-segment curvatures a2, b2 from C²
continuity at the junctions, and the segment heights h1 (= h2) chosen for the least RMS over the
view angle.

The method of steps makes both surfaces C¹ by construction; a2 and b2 are "found numerically from
continuity of the second derivatives at the junctions B and C" (digest §3.1). Here the curvature of
the first constructed segment at its junction (the derivative of the Snell slopes of the points just
beyond it, a quadratic fit over JUNCTION_SPAN) must equal the parabola's 2·a2 (surface 1, at C,
y = h1) and 2·b2 (surface 2, at B, y = h2).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.optimize import brentq, minimize, minimize_scalar

from antenna_cad.raytrace.snell import refract
from antenna_cad.raytrace.trace2d import Interface, trace
from antenna_cad.synthesis.bifocal_steps import _back, _fwd, _hermite, _mirror, _Optics, _symmetric_profile, _unit
from antenna_cad.synthesis.checks import DesignError

JUNCTION_POINTS = 201       # points per central segment for the curvature estimate
JUNCTION_SPAN = 0.01        # y range (D = 1) beyond the junction fitted for the curvature
SCAN_POINTS = 11            # source angles per σ evaluation inside the optimisations
H_NODES = 7                 # grid of h before its refinement


# --------------------------------------------------------------------------------------------------
# Kinber's method of steps (seed-001 §3.1)
# --------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class KinberLens:
    """Seed-001 §3.1 lens in the seed's own frame (x axis = our z, origin at the lens centre O,
    normalised units, D = aperture). ``F1`` below the axis; ``F1p`` its image point (None for a
    plane output, then ``k`` is the output direction ω_B)."""

    n: float
    aperture: float
    F1: np.ndarray
    F1p: np.ndarray | None
    k: np.ndarray | None
    omega_B_rad: float
    alpha_A_rad: float
    L: float
    surface1: np.ndarray            # (N, 2) full even profile (x, y), with slopes
    slopes1: np.ndarray
    surface2: np.ndarray
    slopes2: np.ndarray
    segments: int
    h2: float                       # surface-2 central half-height (given or from A–O–B collinearity)
    fold_y: float                   # smallest |y| of a segment whose image folds back (inf: none)

    def x1(self, y):
        return self._splines[0](np.asarray(y, float))

    def x2(self, y):
        return self._splines[1](np.asarray(y, float))

    @cached_property
    def _splines(self):
        """The two faces x(y) (Hermite through the points and slopes), built once per lens."""
        return (_hermite(self.surface1[:, 1], self.surface1[:, 0], self.slopes1),
                _hermite(self.surface2[:, 1], self.surface2[:, 0], self.slopes2))

    @cached_property
    def faces(self) -> tuple[Interface, Interface]:
        """The faces as tracer interfaces (glass after surface 1, air after surface 2), built once per lens."""
        return (Interface.from_points(self.surface1[:, 1], self.surface1[:, 0], self.n, self.slopes1),
                Interface.from_points(self.surface2[:, 1], self.surface2[:, 0], 1.0, self.slopes2))

    def focus_angle_deg(self) -> float:
        """"Angular position of the foci" as the digest reads it: the direction of F1' seen from the
        surface-2 vertex (b0, 0), or ω_B for a plane output."""
        if self.F1p is None:
            return float(np.degrees(self.omega_B_rad))
        b0 = float(self.x2(0.0))
        return float(np.degrees(np.arctan2(self.F1p[1], self.F1p[0] - b0)))


def _monotone(y: np.ndarray) -> bool:
    d = np.diff(y)
    return bool(np.all(d > 0) or np.all(d < 0))


def kinber_lens(n: float, a0: float, a2: float, h1: float, b0: float, b2: float, h2: float | None,
                rho1: float, rho2: float = np.inf, aperture: float = 1.0,
                points_per_segment: int = 41, max_segments: int = 400,
                allow_partial: bool = False, build_to: float = 1.02) -> KinberLens:
    """Kinber's exact stepwise bifocal synthesis, seed-001 §3.1, in the seed's frame.

    Central segments ``x1 = a0 + a2 y²`` (|y| ≤ h1) and ``x2 = b0 + b2 y²`` (|y| ≤ h2). If ``h2`` is None
    it is set by A–O–B collinearity (``x_B/h2 = −x_A/h1``). Foci from (3.1); F1 rays through the newest
    surface-1 segment give the next surface-2 segment (3.2)–(3.5); F2' rays through the newest
    surface-2 segment give the next surface-1 segment (3.6)–(3.9) (computed as the mirror image of the
    F1 backward step). ``rho2 = inf`` gives the plane-output lens (digest's derived form). A segment
    whose image is not monotone in y folds the surface (the steps overlap): ``fold_y`` records the
    smallest |y| where that happens (the seed's lens 1 folds at 0.427 D, before its edge).
    """
    if h2 is None:                     # b2 h² + (x_A/h1) h + b0 = 0, root with h > 0
        xa = a0 + a2 * h1**2
        cq = [b2, xa / h1, b0] if abs(b2) > 0 else [xa / h1, b0]
        roots = np.roots(cq)
        roots = roots[np.isreal(roots) & (roots.real > 0)].real
        if len(roots) == 0:
            raise DesignError("design.kinber.h2", "A–O–B collinearity has no positive h2")
        h2 = float(np.min(roots))
    y1 = np.linspace(-h1, h1, points_per_segment)
    y2 = np.linspace(-h2, h2, points_per_segment)
    s1 = np.stack([a0 + a2 * y1**2, y1], -1)
    n1 = _unit(np.stack([np.ones_like(y1), -2 * a2 * y1], -1))
    s2 = np.stack([b0 + b2 * y2**2, y2], -1)
    n2 = _unit(np.stack([np.ones_like(y2), -2 * b2 * y2], -1))
    A, NA, B, NB = s1[:1], n1[:1], s2[-1:], n2[-1:]
    v = _unit(B - A)
    d_out, ok_a = refract(-v, NA, n, 1.0)        # from A back toward F1 (in air)
    w, ok_b = refract(v, NB, n, 1.0)             # leaving B toward F1'
    if not (ok_a.all() and ok_b.all()):
        raise DesignError("design.kinber", "central ray A→B is totally reflected (3.1)")
    F1 = (A + rho1 * d_out)[0]
    omega_B = float(np.arctan2(w[0, 1], w[0, 0]))
    alpha_A = float(np.arctan2(v[0, 1], v[0, 0]))
    nab = n * float(np.linalg.norm(B - A))
    if np.isinf(rho2):
        k = w[0]
        L = rho1 + nab - float(B[0] @ k)
        o = _Optics(F1, n, L, k=k)
        F1p = None
    else:
        k = None
        F1p = (B + rho2 * w)[0]
        L = rho1 + nab + rho2
        o = _Optics(F1, n, L, Fp=F1p)
    surf1_p, surf1_n = [s1], [n1]
    surf2_p, surf2_n = [s2], [n2]
    last1, last1n, last2, last2n = s1, n1, s2, n2
    half = aperture / 2.0
    segs, fold_y = 0, np.inf
    for segs in range(1, max_segments + 1):
        q, qn = _fwd(last1, last1n, o)                                   # new surface-2 segment
        p, pn = _back(_mirror(last2), _mirror(last2n), o)                # F1 backward of mirror…
        p, pn = _mirror(p), _mirror(pn)                                  # …mirrored = F2' step
        good_q = np.all(np.isfinite(q), -1)
        good_p = np.all(np.isfinite(p), -1)
        if not (good_q.any() and good_p.any()):
            break
        surf2_p.append(q[good_q]); surf2_n.append(qn[good_q])
        surf1_p.append(p[good_p]); surf1_n.append(pn[good_p])
        for seg in (q[good_q], p[good_p]):
            if fold_y == np.inf and not _monotone(seg[:, 1]):
                fold_y = float(np.min(np.abs(seg[:, 1])))
        last1, last1n, last2, last2n = p[good_p], pn[good_p], q[good_q], qn[good_q]
        if (np.min(np.abs(surf1_p[-1][:, 1])) > build_to * half
                and np.min(np.abs(surf2_p[-1][:, 1])) > build_to * half) \
                or not (good_q.all() and good_p.all()):
            break
    P1 = np.concatenate(surf1_p); N1 = np.concatenate(surf1_n)
    P2 = np.concatenate(surf2_p); N2 = np.concatenate(surf2_n)
    ya, za, sa = _symmetric_profile(P1, N1)
    yb_, zb, sb = _symmetric_profile(P2, N2)
    if (ya[-1] < half or yb_[-1] < half) and not allow_partial:
        raise DesignError("design.kinber", f"the method of steps stopped at |y| = "
                          f"{min(ya[-1], yb_[-1]):.4g} before the aperture edge {half:.4g} (TIR or no root)")
    return KinberLens(n, aperture, F1, F1p, k, omega_B, alpha_A, L,
                      np.stack([za, ya], -1), sa, np.stack([zb, yb_], -1), sb, segs, float(h2), fold_y)


@dataclass(frozen=True)
class _Rays:
    """Rays from one point source traced exactly through both faces: optical path to the exit point
    Q on surface 2 for the N rays aimed uniformly in y at surface 1 (those inside the aperture on both
    faces) and for the central ray aimed at the surface-1 vertex."""
    opl: np.ndarray
    Q: np.ndarray
    opl0: float
    Q0: np.ndarray

    def sigma(self, image: np.ndarray | None = None, direction_rad: float | None = None) -> float:
        """RMS (3.10) ``sqrt(Σ (L_i − L_0)² / N)`` to a point image (``L = opl + |Q − S'|``) or a plane
        output of direction angle ω (``L = opl − k·Q``); L_0 the central ray, so σ includes piston."""
        if image is not None:
            e, e0 = np.linalg.norm(self.Q - image, axis=-1), float(np.linalg.norm(self.Q0 - image))
        else:
            k = np.array([np.cos(direction_rad), np.sin(direction_rad)])
            e, e0 = -(self.Q @ k), -float(self.Q0 @ k)
        return float(np.sqrt(np.mean((self.opl + e - self.opl0 - e0) ** 2)))


def _trace_source(lens: KinberLens, source: np.ndarray, n_rays: int = 100,
                  half_aperture: float | None = None) -> _Rays:
    h = lens.aperture / 2.0 if half_aperture is None else half_aperture
    s1, s2 = lens.faces
    S = np.asarray(source, float)
    yt = np.append(np.linspace(-h, h, n_rays), 0.0)          # the last: the central ray
    tgt = np.stack([lens.x1(yt), yt], -1)
    tr = trace(np.tile(S, (n_rays + 1, 1)), _unit(tgt - S), [s1, s2], 1.0)
    ok = tr.ok & (np.abs(tr.points[1][:, 1]) <= h) & (np.abs(tr.points[2][:, 1]) <= h)
    ok[-1] = False
    return _Rays(tr.opl[ok], tr.points[-1][ok], float(tr.opl[-1]), tr.points[-1][-1])


def kinber_rms(lens: KinberLens, source: np.ndarray, image: np.ndarray, n_rays: int = 100,
               half_aperture: float | None = None) -> float:
    """Eikonal RMS (3.10) of seed-001 §3.1 for a point source and a point image (seed frame):
    ``σ = sqrt(Σ (L_i − L_0)² / N)``, L_i = |S − P_i| + n|P_i Q_i| + |Q_i − S'| along exactly traced
    rays aimed uniformly in y at surface 1, L_0 the ray aimed at the surface-1 vertex (so σ includes
    piston, as in the seed). Rays leaving |y| > half_aperture (default D/2) on either face are dropped."""
    return _trace_source(lens, source, n_rays, half_aperture).sigma(np.asarray(image, float))


def focal_circle_source(lens: KinberLens, x_axis: float | None, phi_rad: float) -> np.ndarray:
    """The source on the focal circle through F1, F2 centred on the axis and crossing it at ``x_axis``
    (None: the circle centred on O, radius |OF1|), seen at angle φ from the surface-1 vertex
    (seed-001 §4.2: 2-D focal curves are circles through the design foci)."""
    F = lens.F1
    V = np.array([float(lens.x1(0.0)), 0.0])
    d = np.array([-np.cos(phi_rad), -np.sin(phi_rad)])
    if x_axis is not None and abs(F[0] - x_axis) < 1e-9:          # the straight focal line x = F1x
        return V + (F[0] - V[0]) / d[0] * d
    if x_axis is None:
        xc, R = 0.0, float(np.hypot(*F))
    else:
        xc = (F[0] ** 2 + F[1] ** 2 - x_axis**2) / (2.0 * (F[0] - x_axis))
        R = abs(x_axis - xc)
    w = V - np.array([xc, 0.0])
    bq = w @ d
    return V + (-bq + np.sqrt(bq * bq - (w @ w - R * R))) * d


def _best_image(rays: _Rays, guess: np.ndarray) -> float:
    """Least σ over point images: Gauss–Newton on the residuals L_i − L_0 (smooth in the image point
    S'; Jacobian −u_i + u_0, u the unit vectors from S' to Q), each step halved until σ decreases."""
    best = rays.sigma(image=guess)
    if not np.isfinite(best):
        return best
    p = np.asarray(guess, float)
    for _ in range(100):
        dq, dq0 = rays.Q - p, rays.Q0 - p
        e, e0 = np.hypot(dq[:, 0], dq[:, 1]), float(np.hypot(*dq0))
        step = np.linalg.lstsq(dq0 / e0 - dq / e[:, None], -(rays.opl + e - rays.opl0 - e0), rcond=None)[0]
        for _ in range(40):
            trial = rays.sigma(image=p + step)
            if trial <= best:
                break
            step = step / 2
        else:
            break
        p, best = p + step, trial
        if np.hypot(*step) <= 1e-13 * (1.0 + np.hypot(*p)):
            break
    return best


def _best_direction(rays: _Rays, guess: float) -> float:
    span = np.radians(3.0)
    fit = minimize_scalar(lambda w: rays.sigma(direction_rad=w), bounds=(guess - span, guess + span),
                          method="bounded", options={"xatol": 1e-10})
    return float(fit.fun)


def view_sigma(lens: KinberLens, half_view_deg: float, num: int = 21, x_axis: float | None = None,
               image: str = "best") -> tuple[np.ndarray, np.ndarray]:
    """σ (3.10) against the source angle over ±half the view angle, sources on the focal circle
    (:func:`focal_circle_source`). The image of an off-design source is not defined in the seed
    (digest §4.2); ``image="best"``: the point image (or, for a plane output, the output direction)
    that minimises σ, started from the conjugate the design foci map linearly;
    ``"point_symmetric"``: S' = −S, exact for the point-symmetric lens 1 (a0 = −b0, a2 = −b2, ρ1 = ρ2)."""
    phis = np.radians(np.linspace(-half_view_deg, half_view_deg, num))
    phi_f = float(np.arctan2(-lens.F1[1], float(lens.x1(0.0)) - lens.F1[0]))     # F1 seen from the vertex
    out = []
    for phi in phis:
        S = focal_circle_source(lens, x_axis, phi)
        rays = _trace_source(lens, S)
        if image == "point_symmetric":
            if lens.F1p is None:
                raise DesignError("design.kinber.rho2", "a point-symmetric image needs a finite rho2")
            out.append(rays.sigma(image=-S))
        elif lens.F1p is None:
            out.append(_best_direction(rays, lens.omega_B_rad * phi / phi_f))
        else:
            guess = np.array([lens.F1p[0], lens.F1p[1] * phi / phi_f])
            out.append(_best_image(rays, guess))
    return np.degrees(phis), np.array(out)


def kinber_focal_circle_rms(lens: KinberLens, x_axis: float, half_view_deg: float = 20.0,
                            num: int = 41) -> tuple[np.ndarray, np.ndarray]:
    """σ over the view on the focal circle crossing the axis at ``x_axis`` with the image S' = −S
    (the point-symmetric lens 1, seed-001 §3.1; the graded kind's comparison lens)."""
    return view_sigma(lens, half_view_deg, num, x_axis, image="point_symmetric")


def _curvature_beyond(lens_surface: np.ndarray, slopes: np.ndarray, h: float) -> float:
    y = lens_surface[:, 1]
    sel = (y > h + 1e-9) & (y < h + JUNCTION_SPAN)
    if sel.sum() < 4:
        raise DesignError("design.kinber.h1", "too few constructed points beyond the junction")
    return float(np.polyfit(y[sel] - h, slopes[sel], 2)[-2])


def c2_jumps(n, a0, a2, h1, b0, b2, h2, rho1, rho2=np.inf) -> np.ndarray:
    """Second-derivative jumps (x'' beyond − x'' of the parabola) at C (surface 1) and B (surface 2)."""
    lens = kinber_lens(n, a0, a2, h1, b0, b2, h2, rho1, rho2, points_per_segment=JUNCTION_POINTS,
                       max_segments=1, allow_partial=True)
    return np.array([_curvature_beyond(lens.surface1, lens.slopes1, h1) - 2 * a2,
                     _curvature_beyond(lens.surface2, lens.slopes2, h2) - 2 * b2])


def solve_c2(n, a0, h1, b0, h2, rho1, rho2=np.inf, b2=None, a2_guess=1.0) -> tuple[float, float, float]:
    """(a2, b2, residual jump at B): a2 making surface 1 C² at C for the given b2 — which makes
    surface 2 C² at B as well (the two jumps vanish together: one relation a2(b2), measured). With
    ``b2=None`` the lens must be symmetric (a0 = −b0, h1 = h2, ρ1 = ρ2) and b2 = −a2."""
    if b2 is None:
        if not (abs(a0 + b0) < 1e-12 and abs(h1 - h2) < 1e-12 and rho1 == rho2):
            raise DesignError("design.kinber.b2", "give b2: only a symmetric lens (a0 = −b0, h1 = h2, "
                              "ρ1 = ρ2) solves both curvatures from C² continuity")

        def jump(a2):
            return c2_jumps(n, a0, a2, h1, b0, -a2, h2, rho1, rho2)[0]
    else:
        def jump(a2):
            return c2_jumps(n, a0, a2, h1, b0, b2, h2, rho1, rho2)[0]
    lo, hi = a2_guess, a2_guess
    for _ in range(40):
        lo, hi = lo - 0.05 * (1 + abs(lo)), hi + 0.05 * (1 + abs(hi))
        try:
            if np.sign(jump(lo)) != np.sign(jump(hi)):
                break
        except DesignError:
            continue
    else:
        raise DesignError("design.kinber.a2", f"no a2 near {a2_guess:g} makes the surfaces C² at the junctions")
    a2 = float(brentq(jump, lo, hi, xtol=1e-12))
    b2 = -a2 if b2 is None else float(b2)
    return a2, b2, float(c2_jumps(n, a0, a2, h1, b0, b2, h2, rho1, rho2)[1])


def best_focal_axis(lens: KinberLens, half_view_deg: float, image: str = "best",
                    num: int = SCAN_POINTS) -> tuple[float, float]:
    """(x_axis, max σ): the focal circle through F1, F2 (its axis crossing x_axis) minimising the max σ
    over the view — the seed optimises its focal curves (digest §4.2). A grid over F1x − 0.3 … F1x + 0.1
    (D = 1, kept in front of the surface-1 vertex), then bounded refinement around the best node."""
    f1x, vertex = float(lens.F1[0]), float(lens.x1(0.0))

    def worst(x):
        with np.errstate(invalid="ignore"):
            w = float(np.max(view_sigma(lens, half_view_deg, num, float(x), image)[1]))
        return w if np.isfinite(w) else np.inf
    best = _grid_then_refine(worst, f1x - 0.3, min(f1x + 0.1, vertex - 0.05), 13, 1e-5)
    if best is None:
        raise DesignError("design.kinber.focal_axis_x", "no focal circle through F1, F2 gives a finite σ")
    return best


def _grid_then_refine(f, lo: float, hi: float, nodes: int, xatol: float) -> tuple[float, float] | None:
    """(x, f(x)) minimising f on [lo, hi]: the best of a grid, refined by bounded Brent between its
    neighbours (f may be inf where the design does not exist); None when f is inf on the grid."""
    grid = np.linspace(lo, hi, nodes)
    vals = [f(x) for x in grid]
    i = int(np.argmin(vals))
    if not np.isfinite(vals[i]):
        return None
    fit = minimize_scalar(f, bounds=(grid[max(i - 1, 0)], grid[min(i + 1, nodes - 1)]), method="bounded",
                          options={"xatol": xatol})
    return (float(fit.x), float(fit.fun)) if fit.fun <= vals[i] else (float(grid[i]), float(vals[i]))


def optimise_h(n, a0, b0, rho1, rho2, h_range, x_axis, half_view_deg, a2_guess=1.0, b2=None,
               image="point_symmetric"):
    """h1 = h2 = h in ``h_range`` minimising the max σ (3.10) over ±half view (seed-001 §3.1: "h1 and h2
    ... are optimised to minimise RMS over the view angle"), each h with its C² a2 (and b2 = −a2 when
    ``b2`` is None: the symmetric lens). The focal circle crosses the axis at ``x_axis``, or (None) at
    the best crossing for each h (:func:`best_focal_axis`). A lens that folds before the aperture edge
    (:func:`kinber_lens` ``fold_y``) is no candidate. Returns (h, a2, max σ)."""
    guess = [a2_guess]

    def lens_at(h):
        a2, b2_, _ = solve_c2(n, a0, h, b0, h, rho1, rho2, b2, guess[0])
        guess[0] = a2
        return a2, kinber_lens(n, a0, a2, h, b0, b2_, h, rho1, rho2)

    def worst(h):
        try:
            lens = lens_at(h)[1]
        except DesignError:
            return np.inf
        if lens.fold_y < lens.aperture / 2:
            return np.inf
        if x_axis is None:
            try:
                return best_focal_axis(lens, half_view_deg, image)[1]
            except DesignError:
                return np.inf
        with np.errstate(invalid="ignore"):
            w = float(np.max(view_sigma(lens, half_view_deg, SCAN_POINTS, x_axis, image)[1]))
        return w if np.isfinite(w) else np.inf

    best = _grid_then_refine(worst, h_range[0], h_range[1], H_NODES, 1e-4)
    if best is None:
        raise DesignError("design.kinber.h_range", f"no h in {tuple(h_range)} gives a lens that covers the aperture "
                          "without folding")
    return best[0], lens_at(best[0])[0], best[1]


VIEW_POINTS = 21            # source angles of the reported σ curve


@dataclass(frozen=True)
class KinberView:
    """σ (3.10) against the source angle over the view angle (D = 1, seed frame): sources on the focal
    circle crossing the axis at ``focal_axis_x`` (given, or optimised for the least max σ), images the
    best point image or output direction (:func:`view_sigma`)."""
    view_angle_deg: float
    angles_deg: np.ndarray
    sigma: np.ndarray
    focal_axis_x: float
    focal_axis_optimised: bool
    h_optimised: bool


def resolve_kinber(n: float, kp: dict) -> tuple[KinberLens, dict, KinberView]:
    """Seed-001 §3.1 lens from the spec's ``kinber`` block (D = 1): ``h1 = "optimise"`` chooses
    h1 = h2 in ``h_range`` for the least max σ over the view (:func:`optimise_h`); ``a2 = None`` solves
    a2 (and b2 = −a2 of a symmetric lens) from C² continuity; ``rho2 = None`` is the plane output.
    Returns the lens, the resolved parameters and the σ curve."""
    kp = dict(kp)
    rho2 = np.inf if kp.get("rho2") is None else float(kp["rho2"])
    half = float(kp.get("view_angle_deg", 40.0)) / 2.0
    x_axis = kp.get("focal_axis_x")
    h_opt = kp["h1"] == "optimise"
    if h_opt:
        guess = -kp["b2"] if kp.get("b2") is not None else 1.0
        h, kp["a2"], _ = optimise_h(n, kp["a0"], kp["b0"], kp["rho1"], rho2, tuple(kp["h_range"]), x_axis, half,
                                    guess, kp.get("b2"), "best")
        kp["h1"] = kp["h2"] = h
        kp["b2"] = -kp["a2"] if kp.get("b2") is None else kp["b2"]
    elif kp["a2"] is None:
        if kp.get("h2") is None:
            raise DesignError("design.kinber.h2", "required when a2 is solved from C² continuity (the "
                              "A–O–B collinearity would couple h2 to a2)")
        kp["a2"], kp["b2"], _ = solve_c2(n, kp["a0"], kp["h1"], kp["b0"], kp["h2"], kp["rho1"], rho2, kp["b2"],
                                         -kp["b2"] if kp["b2"] is not None else 1.0)
    elif kp["b2"] is None:
        raise DesignError("design.kinber.b2", "required when a2 is given")
    lens = kinber_lens(n, kp["a0"], kp["a2"], kp["h1"], kp["b0"], kp["b2"], kp.get("h2"), kp["rho1"], rho2)
    if lens.fold_y < lens.aperture / 2:
        raise DesignError("design.kinber", f"the method of steps folds at |y| = {lens.fold_y:.4g} D (a segment's "
                          "image reverses in y, so the steps overlap) before the aperture edge 0.5 D: these "
                          "parameters give no exact bifocal lens there; change h1, a2 or the focal distances")
    if kp.get("h2") is None:          # A–O–B collinearity: read h2 back from the central segment
        kp["h2"] = float(lens.h2)
    axis_opt = x_axis is None
    if axis_opt:
        x_axis = best_focal_axis(lens, half)[0]
    angles, sigma = view_sigma(lens, half, VIEW_POINTS, float(x_axis))
    if not np.all(np.isfinite(sigma)):
        raise DesignError("design.kinber.focal_axis_x", f"the focal circle crossing the axis at {x_axis:.4g} "
                          "leaves sources whose rays miss the lens; move it")
    return lens, kp, KinberView(2 * half, angles, sigma, float(x_axis), axis_opt, h_opt)
