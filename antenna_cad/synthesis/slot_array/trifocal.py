"""Point-by-point (marching) construction of the trifocal beam formers (seed-003 §3.6; §3.7 uses the
same equations with refraction, n₂ = n).

Thesis frame (x, z) (seed-003 §2.6, rows 3.2/3.3): z is the axis, the foci F1 = (x1, z1), F = (0, z_F),
F2 = (−x1, z1) lie at z < 0 (x1 < 0; erratum §7.7). A ray from focus j meets the *first surface*
(mirror 1) at P, is reflected (or refracted into index n₂) toward the *guide curve* (mirror 2) at Q
and enters the guide that starts there; the guides are transmission lines along the axis with phase
term T(x) = n_w t(x). At broadside (β = 90°) the three eikonals are

    Ψ_j(x) = |F_j P_j| + n₂ |P_j Q(x)| + T(x) − s_j x = const_j,   s_1 = sin α, s_F = 0, s_2 = −sin α.

Subtracting the F equation removes T, so the surfaces do not depend on β, n_w or t_B. Along the guide
curve dΨ_j/dx = 0 with dL_j = n₂ e_j·dQ gives n₂ (e_j − e_F)·(1, z′) = s_j (e_j: arriving unit rays)
and T′ = −n₂ e_F·(1, z′): the guide-curve slope is fixed by the arriving rays (so the initial guide
parabola must have that slope at B: the C¹ condition), and the F2 ray that must reach a known guide
point is fixed too, which makes the new first-surface point explicit (:func:`first_from_guide`). The
new guide point is where an F1 ray from the known first surface meets an F ray from the newest
first-surface segment with Ψ_1 = const_1 (:func:`guide_from_surface`: one scalar brentq root per
point, followed continuously from the previous one). Segments are smooth functions of their parameter
between the joins of the surfaces they are built on (only C¹ there), frozen piecewise as Chebyshev
interpolants (:class:`Segment`, :class:`Piecewise`). :func:`assemble_former` turns a finished march into
the :class:`BeamFormer` of either former. Never the garbled closed forms (3.18)/(3.24).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial

import numpy as np
from scipy.optimize import brentq

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.beamformer import (BeamFormer, _assemble_symmetric, trace_mirror_lens,
                                                         trace_two_mirror)
from antenna_cad.synthesis.slot_array.common import N_SIGMA_RAYS
from antenna_cad.synthesis.slot_array.curves import _make_curve, _rms

class MarchError(DesignError):
    """The march cannot continue (no real root, folded or crossing segments)."""


def _norm(x: float, z: float) -> float:
    return math.hypot(x, z)


def _unit2(x: float, z: float) -> tuple[float, float]:
    r = math.hypot(x, z)
    return x / r, z / r


def _normal(slope: float) -> tuple[float, float]:
    return _unit2(-slope, 1.0)


def _redirect(dx: float, dz: float, slope: float, n2: float) -> tuple[float, float]:
    """Reflect (n2 = 1) or refract from air into index n2 (vector laws) at a surface of ``slope``."""
    nx, nz = _normal(slope)
    c = dx * nx + dz * nz
    if n2 == 1.0:
        return dx - 2 * c * nx, dz - 2 * c * nz
    if c > 0:
        nx, nz, c = -nx, -nz, -c
    mu = 1.0 / n2
    k = 1.0 - mu * mu * (1.0 - c * c)
    f = mu * -c - math.sqrt(k)
    return mu * dx + f * nx, mu * dz + f * nz


def _slope_between(ix: float, iz: float, ox: float, oz: float, n2: float) -> float:
    """Slope of the surface that turns unit direction i (air) into unit o (index n2): normal ∥ i − n2 o."""
    vx, vz = ix - n2 * ox, iz - n2 * oz
    return -vx / vz


def _meet(px, pz, ax, az, qx, qz, bx, bz) -> tuple[float, float]:
    """(a, b) with P + a·A = Q + b·B."""
    det = -ax * bz + bx * az
    rx, rz = qx - px, qz - pz
    return (-rx * bz + bx * rz) / det, (ax * rz - az * rx) / det


def land_on_parabola(P, e, c0: float, c2: float) -> float:
    """Smallest s > 0 with P + s e on z = c0 + c2 x² (NaN if the ray misses)."""
    px, pz = P
    ex, ez = e
    a, b, c = c2 * ex * ex, 2 * c2 * px * ex - ez, c2 * px * px + c0 - pz
    if abs(a) < 1e-15:
        s = -c / b
        return s if s > 0 else math.nan
    disc = b * b - 4 * a * c
    if disc < 0:
        return math.nan
    roots = [r for r in ((-b - math.sqrt(disc)) / (2 * a), (-b + math.sqrt(disc)) / (2 * a)) if r > 1e-12]
    return min(roots) if roots else math.nan


@dataclass(frozen=True)
class Foci:
    """Normalised design data: F1 (x < 0), F on the axis, beam sine s_1 = sin α, index n₂ of the
    second medium, and the constants c_1 = c_2 and c_F of the eikonals (T = 0 at B)."""
    F1: tuple[float, float]
    F: tuple[float, float]
    s1: float
    n2: float
    c1: float
    cF: float

    @property
    def F2(self) -> tuple[float, float]:
        return -self.F1[0], self.F1[1]


class Segment:
    """A constructed segment as a smooth function of its parameter u ∈ [u0, u1]: ``f(u)`` returns a
    vector of numbers (point, slope, …). It is frozen as a Chebyshev interpolant on ``nodes``
    points (machine precision for the smooth maps of the march; the error at the mid-nodes is
    measured and kept in ``interp_error``)."""

    breaks = ()

    def __init__(self, f, u0: float, u1: float, nodes: int = 49):
        k = np.arange(nodes)
        self.u0, self.u1 = float(u0), float(u1)
        self.u = 0.5 * (u0 + u1) - 0.5 * (u1 - u0) * np.cos(np.pi * k / (nodes - 1))
        self.u[0], self.u[-1] = self.u0, self.u1          # end nodes exactly at the ends
        self.values = np.array([f(x) for x in self.u])
        self._w = np.where((k == 0) | (k == nodes - 1), 0.5, 1.0) * (-1.0) ** k
        mid = 0.5 * (self.u[:-1] + self.u[1:])[:: max(1, nodes // 6)]
        self.interp_error = float(np.max(np.abs(np.array([f(x) for x in mid]) - self(mid))))

    def __call__(self, u):
        if np.ndim(u) == 0:                 # one parameter (the root finders): 1-D arithmetic
            d = float(u) - self.u
            hit = np.flatnonzero(d == 0)
            if hit.size:
                return self.values[hit[:1]]
            c = self._w / d
            return ((c @ self.values) / c.sum())[None]
        u = np.atleast_1d(np.asarray(u, float))
        d = u[:, None] - self.u[None, :]
        exact = d == 0
        d[exact] = 1.0
        c = self._w[None, :] / d
        out = (c @ self.values) / c.sum(axis=1)[:, None]
        hit = exact.any(axis=1)
        out[hit] = self.values[np.argmax(exact[hit], axis=1)]
        return out


class Piecewise:
    """Segments of one map joined end to end at ``breaks`` of its parameter: a map of the march is smooth
    between the joins of the segments it is built on and only C¹ across them, so each smooth piece is
    frozen on its own (same interface as :class:`Segment`)."""

    def __init__(self, f, u0: float, u1: float, breaks=()):
        span = u1 - u0
        cuts = [float(u0), *sorted(float(b) for b in breaks if u0 + 1e-9 * span < b < u1 - 1e-9 * span), float(u1)]
        self.pieces = [Segment(f, a, b) for a, b in zip(cuts[:-1], cuts[1:])]
        self.u0, self.u1, self.cuts, self.breaks = float(u0), float(u1), np.array(cuts), tuple(cuts[1:-1])
        self.values = np.concatenate([p.values[1 if k else 0:] for k, p in enumerate(self.pieces)])
        self.interp_error = max(p.interp_error for p in self.pieces)

    def __call__(self, u):
        if np.ndim(u) == 0:
            return self.pieces[min(max(int(np.searchsorted(self.cuts, u, side="right")) - 1, 0),
                                   len(self.pieces) - 1)](u)
        u = np.atleast_1d(np.asarray(u, float))
        k = np.clip(np.searchsorted(self.cuts, u, side="right") - 1, 0, len(self.pieces) - 1)
        out = np.empty((u.size, self.values.shape[1]))
        for i, piece in enumerate(self.pieces):
            if np.any(k == i):
                out[k == i] = piece(u[k == i])
        return out


def _root(g, lo: float, hi: float, field: str, what: str, n: int = 24) -> float:
    """The root of g on [lo, hi] nearest a sign change found on an n-point scan (brentq)."""
    us = np.linspace(lo, hi, n)
    gs = np.array([g(u) for u in us])
    ok = np.isfinite(gs)
    for i in range(n - 1):
        if ok[i] and abs(gs[i]) < 1e-11:
            return float(us[i])
        if ok[i] and ok[i + 1] and gs[i] * gs[i + 1] <= 0:
            return float(brentq(g, us[i], us[i + 1], xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200))
    if ok[-1] and abs(gs[-1]) < 1e-11:
        return float(us[-1])
    best = np.nanmin(np.abs(gs)) if ok.any() else math.nan
    raise MarchError(field, f"the march cannot continue: no real root {what} (smallest residual {best:.3g} D); "
                     "the initial-segment parameters do not admit a trifocal surface there")


def guide_from_initial(fo: Foci, S0: Segment, g0: float, g2: float, x_b: float, field: str) -> Segment:
    """Initial guide-curve segment z = g0 + g2 x² on |x| ≤ |x_B| with T and the arriving F-ray
    direction from the F rays through the initial first-surface segment ``S0`` (root on x_P)."""
    F, n2 = fo.F, fo.n2

    def ray(xp):
        x, z, s = S0(xp)[0]
        e = _unit2(*_redirect(*_unit2(x - F[0], z - F[1]), s, n2))
        a = land_on_parabola((x, z), e, g0, g2)
        return (x, z), e, a

    def f(xq):
        def miss(xp):
            p, e, a = ray(xp)
            return p[0] + a * e[0] - xq
        p, e, a = ray(_root(miss, S0.u0, S0.u1, field, f"for the F ray to x = {xq:.4g} D", n=5))
        qx, qz = p[0] + a * e[0], p[1] + a * e[1]
        return [qx, qz, 2 * g2 * qx, fo.cF - _norm(p[0] - F[0], p[1] - F[1]) - n2 * a, e[0], e[1]]
    return Segment(f, -abs(x_b), abs(x_b))


def first_from_guide(fo: Foci, G: Segment, field: str) -> Segment:
    """New first-surface segment from the F2 condition on guide segment G (explicit): the arriving
    F2 direction e₂ follows from dΨ₂/dx = 0, n₂(e₂ − e_F)·(1, z′) = s₂; N lies back along e₂ where
    |F2 N| + n₂|N Q| = const_2 − T − s₂ x; its slope from the reflection/refraction law."""
    F2, n2, s2 = fo.F2, fo.n2, -fo.s1

    def f(u):
        qx, qz, zs, T, efx, efz = G(u)[0]
        tx, tz = _unit2(1.0, zs)
        nx, nz = -tz, tx
        ct = (efx + efz * zs + s2 / n2) * tx
        if abs(ct) >= 1.0:
            raise MarchError(field, f"no F2 ray reaches the guide curve at x = {qx:.4g} D (|cos| = {abs(ct):.3g} > 1)")
        st = math.copysign(math.sqrt(1.0 - ct * ct), efx * nx + efz * nz)
        ex, ez = ct * tx + st * nx, ct * tz + st * nz
        vx, vz = qx - F2[0], qz - F2[1]
        K = fo.c1 - T + s2 * qx
        ev, vv = ex * vx + ez * vz, vx * vx + vz * vz
        if n2 == 1.0:
            roots = [(K * K - vv) / (2.0 * (K - ev))]
        else:
            a, b, c = 1.0 - n2 * n2, 2.0 * (K * n2 - ev), vv - K * K
            disc = b * b - 4 * a * c
            roots = sorted([(-b - math.sqrt(disc)) / (2 * a), (-b + math.sqrt(disc)) / (2 * a)]) if disc >= 0 else []
        for r in roots:
            Nx, Nz = qx - r * ex, qz - r * ez
            ix, iz = _unit2(Nx - F2[0], Nz - F2[1])
            if 0 < r < K / n2 and (n2 == 1.0 or ix * ex + iz * ez > 1.0 / n2):
                return [Nx, Nz, _slope_between(ix, iz, ex, ez, n2)]
        raise MarchError(field, f"no first-surface point for the F2 ray to x = {qx:.4g} D of the guide curve")
    return Piecewise(f, G.u0, G.u1, G.breaks)


def in_x(S: Segment, field: str) -> Segment:
    """``S`` re-parametrised by its own x (values[:, 0] monotone in u), frozen again; a segment whose x
    is not monotone between its nodes is a fold (:class:`MarchError` naming ``field``)."""
    x0, x1 = S.values[0, 0], S.values[-1, 0]

    def f(x):
        if (x - x0) * (x1 - x0) <= 0:
            return S.values[0]
        if (x - x1) * (x0 - x1) <= 0:
            return S.values[-1]
        g = lambda u: S(u)[0][0] - x
        if g(S.u0) * g(S.u1) > 0:
            raise MarchError(field, f"the first surface folds back near x = {x:.4g} D: crossing segments")
        return S(brentq(g, S.u0, S.u1, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200))[0]
    return Piecewise(f, min(x0, x1), max(x0, x1), [S(b)[0][0] for b in S.breaks])


class Surface:
    """The first surface known so far (right half): segments parametrised by x, joined end to end."""

    def __init__(self, first: Segment):
        self.segs = [first]

    @property
    def x1(self) -> float:
        return self.segs[-1].u1

    def __call__(self, x: float):
        gaps = [max(seg.u0 - x, x - seg.u1, 0.0) for seg in self.segs]
        k = len(gaps) - 1 - int(np.argmin(gaps[::-1]))
        if gaps[k] > 1e-7:                      # joins are checked to 1e-7 D in :func:`construct`
            raise ValueError(f"x = {x} outside the known first surface")
        seg = self.segs[k]
        return seg(min(max(x, seg.u0), seg.u1))[0]


def guide_from_surface(fo: Foci, surf: Surface, p0: float, field: str) -> tuple[Segment, float]:
    """New guide-curve segment: for F1-ray sources P at x = p ≥ p0 on the known first surface, the
    point N on the newest first-surface segment whose F ray meets the F1 ray from P where
    Ψ_1 = const_1 (scalar brentq root); T from Ψ_F; exact slopes. The segment ends at the p whose N
    is the end of the newest segment. Returns (segment over p, that end p)."""
    F1, F, n2, s1 = fo.F1, fo.F, fo.n2, fo.s1
    new = surf.segs[-1]

    def at(p, xn):
        px, pz, sp = surf(p)
        e1 = _unit2(*_redirect(*_unit2(px - F1[0], pz - F1[1]), sp, n2))
        nx, nz, sn = new(xn)[0]
        ef = _unit2(*_redirect(*_unit2(nx - F[0], nz - F[1]), sn, n2))
        a, b = _meet(px, pz, *e1, nx, nz, *ef)
        if not (a > 0 and b > 0):
            return math.nan, None
        mx, mz = px + a * e1[0], pz + a * e1[1]
        T = fo.cF - _norm(nx - F[0], nz - F[1]) - n2 * b
        g = _norm(px - F1[0], pz - F1[1]) + n2 * a + T - s1 * mx - fo.c1
        return g, (mx, mz, T, e1, ef)

    g = lambda p, v: at(p, v)[0]

    def local_root(p, n_guess, w):
        """Root of g(p, ·) nearest ``n_guess`` (bracket grown both ways from it)."""
        lo, hi = max(n_guess - w, new.u0), min(n_guess + w, new.u1)
        for _ in range(60):
            glo, ghi = g(p, lo), g(p, hi)
            for end, gv in ((lo, glo), (hi, ghi)):      # a root on the segment's end (p at a join), or
                if end in (new.u0, new.u1) and abs(gv) < 1e-11:   # rounded to just outside it
                    return float(end)
            if math.isfinite(glo) and math.isfinite(ghi) and glo * ghi <= 0:
                return float(brentq(lambda v: g(p, v), lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200))
            if lo <= new.u0 and hi >= new.u1:
                break
            w *= 2.0
            lo, hi = max(n_guess - w, new.u0), min(n_guess + w, new.u1)
        raise MarchError(field, f"the march cannot continue: no real root for the F1 ray from x = {p:.4g} D "
                         "(the F ray that must meet it is not on the known first surface)")

    # continuation from (p0, new.u0) (the end of the previous guide segment) to N = new.u1
    span = new.u1 - new.u0
    ps, ns = [p0], [new.u0]
    dp = (surf.x1 - p0) / 400.0
    while True:
        p = ps[-1] + dp
        if p > surf.x1:
            raise MarchError(field, "the march cannot continue: the F1-ray sources run past the known first surface")
        ge = g(p, new.u1)
        if math.isfinite(ge) and ge * g(ps[-1], new.u1) <= 0:           # N reaches the segment end
            p1 = float(brentq(lambda q: g(q, new.u1), ps[-1], p, xtol=1e-15, rtol=4 * np.finfo(float).eps))
            break
        n = local_root(p, ns[-1] + (ns[-1] - ns[-2] if len(ns) > 1 else 0.0), max(abs(ns[-1] - ns[-2]) if len(ns) > 1 else 0.0, 1e-4 * span))
        if n < ns[-1]:
            raise MarchError(field, f"the first surface is used backwards near x = {n:.4g} D (fold)")
        ps.append(p), ns.append(n)
        dn = ns[-1] - ns[-2]
        dp *= 0.5 if dn > span / 40 else (2.0 if dn < span / 400 else 1.0)
    track_p, track_n = np.array(ps + [p1]), np.array(ns + [new.u1])

    def f(p):
        k = int(np.clip(np.searchsorted(track_p, p) - 1, 0, len(track_p) - 2))
        t = (p - track_p[k]) / (track_p[k + 1] - track_p[k])
        guess = track_n[k] + t * (track_n[k + 1] - track_n[k])
        xn = local_root(p, guess, max(track_n[k + 1] - track_n[k], 1e-6 * span))
        mx, mz, T, e1, ef = at(p, xn)[1]
        dx, dz = n2 * (e1[0] - ef[0]), n2 * (e1[1] - ef[1])
        return [mx, mz, (s1 - dx) / dz, T, ef[0], ef[1]]
    breaks = [b for seg in surf.segs for b in seg.breaks] + [seg.u1 for seg in surf.segs[:-1]]   # under F1 sources
    for b in new.breaks:                                                          # joins under the F-ray points N
        k = int(np.clip(np.searchsorted(track_n, b), 1, len(track_n) - 1))
        w = max(track_n[k] - track_n[k - 1], 1e-6 * span)
        breaks.append(brentq(lambda q: local_root(q, b, w) - b, track_p[k - 1], track_p[k], xtol=1e-15,
                             rtol=4 * np.finfo(float).eps))
    return Piecewise(f, p0, p1, breaks), p1


def _monotone_x(seg: Segment, what: str, field: str) -> None:
    dx = np.diff(seg.values[:, 0])
    if not (np.all(dx > 0) or np.all(dx < 0)):
        raise MarchError(field, f"the {what} folds back (x not monotone) near x = "
                         f"{seg.values[np.argmin(np.abs(dx)), 0]:.4g} D: crossing segments")


def construct(fo: Foci, S0: Segment, g0: float, g2: float, x_b: float, *, half_width: float,
              margin: float, max_steps: int, field: str, join_tol: float = 1e-7) -> tuple[Surface, list]:
    """The march (module docstring): alternate the explicit F2 step (new first-surface segment on the
    newest guide segment) and the F1/F step (new guide segment) until the guide curve, with all
    three eikonals holding on it, covers x ≤ half_width + margin. Right half; x → −x gives the rest.
    A new first-surface segment must start where the known surface ends (within ``join_tol``):
    otherwise the initial segments are incompatible (the slope of the initial guide parabola at B
    differs from the one the eikonals require) and a :class:`MarchError` names ``field``."""
    G = [guide_from_initial(fo, S0, g0, g2, x_b, field)]
    surf = Surface(S0)
    p = S0.u0
    need = half_width + margin
    for _ in range(max_steps):
        raw = first_from_guide(fo, G[-1], field)
        _monotone_x(raw, "first surface", field)
        start = raw.values[0] if abs(raw.values[0, 0] - surf.x1) < abs(raw.values[-1, 0] - surf.x1) else raw.values[-1]
        gap = math.hypot(start[0] - surf.x1, start[1] - surf(surf.x1)[1])
        if gap > join_tol:
            raise MarchError(field, f"the new first-surface segment starts {gap:.3g} D away from the known "
                             f"surface end x = {surf.x1:.4g} D: the initial segments are incompatible "
                             "(the initial guide parabola's slope at B differs from the one the three "
                             "eikonals require)")
        if raw.values[:, 0].max() <= surf.x1 + join_tol:
            raise MarchError(field, f"the new first-surface segment runs back over the known surface from x = "
                             f"{surf.x1:.4g} D (fold)")
        surf.segs.append(in_x(raw, field))
        if G[-1].values[:, 0].max() >= need:
            return surf, G
        Gk, p = guide_from_surface(fo, surf, p, field)
        _monotone_x(Gk, "guide curve", field)
        G.append(Gk)
    raise MarchError(field, f"the guide curve did not reach |x| = {need:.3g} D in {max_steps} steps "
                     f"(reached {G[-1].values[:, 0].max():.4g} D)")


def _sample(seg: Segment, n: int) -> np.ndarray:
    return seg(np.linspace(seg.u0, seg.u1, n))


def assemble_former(kind: str, fo: Foci, surf: Surface, G: list, first0, guide0: tuple[float, float], *,
                    half_width: float, n_seg: int, scale_mm: float, params: dict, flip: bool = False) -> BeamFormer:
    """The :class:`BeamFormer` of a finished march (both trifocal formers), scaled to mm.

    ``first0``: (x, z, slope) samples of the initial first-surface segment; ``guide0`` = (g0, g2) of the
    initial guide parabola (its exact values replace the interpolated ones). ``kind`` trifocal_two_mirror:
    mirrors (first surface, guide curve); trifocal_mirror_lens: lens = first surface (index fo.n2), mirror =
    guide curve. ``flip`` maps the thesis's z to −y (§3.7: the foci lie on the far side of the lens, the
    guides run back from the mirror, +y in this package). ``eikonal(x_mm, j)`` is the design path from
    focus j (0: F1, 1: F, 2: F2) to the guide curve at x: c_j + s_j x − T(x); ``params['T_curve']``
    holds T(x) = n_w t(x) (mm) for the slot line.
    """
    ys = -1.0 if flip else 1.0
    g0, g2 = guide0
    m1 = [tuple(first0)] + [tuple(_sample(s, n_seg).T) for s in surf.segs[1:]]
    g = [_sample(s, n_seg) for s in G]
    m2 = [(v[:, 0], v[:, 1], v[:, 2]) for v in g]
    m2[0] = (m2[0][0], g0 + g2 * m2[0][0] ** 2, 2 * g2 * m2[0][0])
    tt = [(v[:, 0], v[:, 3], -fo.n2 * (v[:, 4] + v[:, 5] * v[:, 2])) for v in g]
    sc = float(scale_mm)
    lens = kind == "trifocal_mirror_lens"
    flipped = lambda segs: [(x, ys * z, ys * s) for x, z, s in segs]
    first = _assemble_symmetric(flipped(m1), "lens" if lens else "mirror_1", "layer1" if lens else "layer1-layer2", sc)
    guide = _assemble_symmetric(flipped(m2), "mirror" if lens else "mirror_2",
                                "layer1-layer2" if lens else "layer2-layer3", sc)
    T = _assemble_symmetric(tt, "T", "guides", 1.0)
    T = _make_curve("T", "guides", T.points_mm[:, 0] * sc, T.points_mm[:, 1] * sc, T.slopes)
    s = np.array([fo.s1, 0.0, -fo.s1])
    const = np.array([fo.c1, fo.cF, fo.c1]) * sc
    foci = np.array([fo.F1, fo.F, fo.F2]) * np.array([1.0, ys]) * sc
    dirs = np.stack([s, np.sqrt(1 - s**2)], -1)

    def eikonal(x_mm, j):
        x = np.asarray(x_mm, float)
        return const[j] + s[j] * x - T.y_at(x)

    if lens:
        trace, mirrors, lenses = partial(trace_mirror_lens, first, guide, fo.n2), (guide,), (first,)
    else:
        trace, mirrors, lenses = partial(trace_two_mirror, first, guide), (first, guide), ()
    from antenna_cad.synthesis.slot_array.slot_line import traced_eikonal_mm   # noqa: E402 (cycle)
    xs = np.linspace(-half_width, half_width, N_SIGMA_RAYS) * sc
    bf0 = BeamFormer(kind, mirrors, lenses, foci, dirs, np.zeros(3), np.zeros(3), sc, guide,
                     np.empty((0, 2)), np.zeros(2), eikonal, trace, {})
    sig = np.array([_rms(traced_eikonal_mm(bf0, j, xs) - eikonal(xs, j)) for j in range(3)])
    yc = (fo.F1[0] ** 2 + fo.F1[1] ** 2 - fo.F[1] ** 2) / (2 * (fo.F1[1] - fo.F[1]))   # circle through the foci
    R = abs(fo.F[1] - yc) * sc
    lim = 1.6 * abs(math.atan2(fo.F1[0], abs(fo.F1[1] - yc)))
    phi = np.linspace(-lim, lim, 121)
    up = ys * (1.0 if fo.F[1] > yc else -1.0)
    centre = np.array([0.0, ys * yc]) * sc
    locus = centre + np.stack([R * np.sin(phi), up * R * np.cos(phi)], -1)
    errors = max(sg.interp_error for sg in surf.segs[1:] + G)
    params = params | {"alpha_rad": math.asin(fo.s1), "beam_angle_rad": math.asin(fo.s1), "steps": len(G) - 1,
                       "interp_error": errors, "guide_half_width": float(G[-1].values[:, 0].max()), "T_curve": T,
                       "construction": (fo, surf, G)}
    return BeamFormer(kind, mirrors, lenses, foci, dirs, sig, sig / sc, sc, guide, locus, centre, eikonal, trace, params)


def grid_then_bounded(objective, grid: np.ndarray, xatol: float, fail: DesignError) -> tuple[float, float]:
    """(argument, value) of the least ``objective`` (§3.8): the best point of ``grid``, refined by a
    bounded scalar search between its neighbours; ``fail`` when no grid point scores below 1 (no
    march covers the aperture)."""
    from scipy.optimize import minimize_scalar
    scores = [objective(v) for v in grid]
    k = int(np.argmin(scores))
    if scores[k] >= 1.0:
        raise fail
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    res = minimize_scalar(objective, bounds=(lo, hi), method="bounded", options={"xatol": xatol})
    return (float(res.x), float(res.fun)) if res.fun < scores[k] else (float(grid[k]), float(scores[k]))
