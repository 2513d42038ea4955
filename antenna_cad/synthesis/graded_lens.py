"""Trifocal graded-index lens of seed-001 §3.2: layered synthesis and RMS aberration (3.10).

Frame of :mod:`antenna_cad.synthesis.graded` (x the axis, y transverse, D = 1). Foci: F = (−d1 − ρ, 0)
and F' = (d2 + ρ', 0) on the axis (approximate focus), F1/F2 and F1'/F2' exact. Construction (the
seed's algorithm, digest §3.2 steps 1–6):

1. Central rays from F through the initial segment x1 = −d1 + a2 y² + a4 y⁴ (y_A ≤ y ≤ −y_A), refracted
   (Snell) and traced through layer 1 (n² = n0² − m y²) to the point of equal eikonal
   ρ + n0 (d1 + d2) + ρ' — the initial segment of surface 2; h1 = the highest turning point.
2. The F1 ray from A (y_A) to B (the exit of the ray through C = −y_A) gives the side foci by Snell at
   A and B at distances ρ1, ρ1' and the reference eikonal ρ1 + L_AB + ρ1'.
3. Alternating images (Kinber's method of steps in the graded medium): F1 rays through the newest
   surface-1 segment give the next surface-2 segment, F2' rays (from the right) through the newest
   surface-2 segment give the next surface-1 segment; every point carries its Snell normal
   N ∝ n v − w (no interpolation in the construction).
4. When both surfaces wait for the medium above the top layer, a layer i is added: no_i, q_i from C¹
   continuity, m_i (either sign) from the central-focus eikonal (3.31) of the ray from F' through Q,
   the surface-2 point at the top boundary: it rises into the new layer, turns (3.27: the layer's
   top) and comes back down to the height of E, the surface-1 point whose F ray has the same
   invariant (3.25); the x offset to E is charged as a·Δx (the seed's approximation — that ray need
   not land at E, so the central focus is approximate).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq

from antenna_cad.raytrace.snell import refract
from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.graded import LeavesMedium, Medium, Ray

MAX_LAYERS = 60


def _unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def _flip(p):
    return np.array([-p[0], p[1]])


@dataclass
class Pt:
    p: np.ndarray        # (x, y)
    n: np.ndarray        # unit normal (either orientation)


@dataclass(frozen=True)
class GradedParams:
    n0: float
    m: float
    a2: float
    a4: float
    y_a: float
    rho: float
    rho_p: float
    rho1: float
    rho1_p: float
    d1: float
    d2: float
    aperture: float = 1.0
    points: int = 41          # points per initial segment


class Construction:
    def __init__(self, g: GradedParams):
        self.g = g
        self.medium = Medium(g.n0, g.m)
        self.F = np.array([-g.d1 - g.rho, 0.0])
        self.Fp = np.array([g.d2 + g.rho_p, 0.0])
        self.central = g.rho + g.n0 * (g.d1 + g.d2) + g.rho_p
        self.span = 4 * (g.d1 + g.d2)

    # --- rays ---------------------------------------------------------------------------------
    def _launch(self, src, pt: Pt, leftward: bool, medium=None):
        """Ray from ``src`` refracted into the lens at ``pt`` (frame flipped for leftward rays)."""
        med = medium or self.medium
        s, p, nrm = (_flip(src), _flip(pt.p), _flip(pt.n)) if leftward else (src, pt.p, pt.n)
        u = _unit(p - s)
        n_in = np.sqrt(med.n2_at(p[1]))
        v, ok = refract(u, nrm, 1.0, n_in)
        if not ok or v[0] <= 0:
            raise DesignError("design.n0", f"a ray cannot enter the lens at y = {p[1]:.4g} (total reflection)")
        return Ray(med, p[0], p[1], n_in * v[0], np.sign(v[1]) or 1.0, p[0] + self.span), s, p

    def image(self, src, dst, const, pts: list[Pt], leftward: bool) -> list[Pt]:
        """Points of the far surface where rays from ``src`` through ``pts`` reach eikonal ``const``
        towards ``dst``, with their Snell normals."""
        out = []
        d = _flip(dst) if leftward else dst
        for pt in pts:
            ray, s, p = self._launch(src, pt, leftward)
            rest = const - np.linalg.norm(p - s)

            def excess(x):
                y, _, path = ray.state(x)
                return path + math.hypot(x - d[0], y - d[1]) - rest

            if excess(ray.x_end) < 0:
                raise LeavesMedium() if ray.left else DesignError("design.d1", "a ray never reaches its eikonal")
            x = brentq(excess, p[0] + 1e-12, ray.x_end, xtol=1e-14)
            y, v, _ = ray.at(x)
            q = np.array([x, y])
            w = _unit(d - q)
            normal = _unit(np.sqrt(self.medium.n2_at(y)) * v - w)
            out.append(Pt(_flip(q), _flip(normal)) if leftward else Pt(q, normal))
        return out

    # --- the seed's steps ---------------------------------------------------------------------
    def surface1_initial(self) -> list[Pt]:
        g = self.g
        y = np.linspace(g.y_a, -g.y_a, g.points)
        x = -g.d1 + g.a2 * y**2 + g.a4 * y**4
        dx = 2 * g.a2 * y + 4 * g.a4 * y**3
        return [Pt(np.array([a, b]), _unit([1.0, -s])) for a, b, s in zip(x, y, dx)]

    def run(self):
        s1_seg = self.surface1_initial()
        s2_seg = self.image(self.F, self.Fp, self.central, s1_seg, False)          # step 1
        turning = []
        for pt in s1_seg:
            ray, _, _ = self._launch(self.F, pt, False)
            turning.append(max(seg.Y for seg in ray.segments))       # layer 1: c = 0, a sinusoid
        self.medium.close_top(max(turning))
        self._side_foci(s1_seg[0], s2_seg[-1])                                       # step 2
        self.surf1, self.surf2 = list(s1_seg), list(s2_seg)
        self._alternate()
        return self

    def _alternate(self):
        """Steps 3–6: every surface-1 point is imaged once by its F1 ray onto surface 2, every
        surface-2 point once by its F2' ray onto surface 1, in order of height; a ray that needs the
        medium above the top layer waits until the other surface has caught up, and when both wait a
        layer is added (step 4)."""
        edge = self.g.aperture / 2 * 1.02
        i1 = i2 = 1                        # images of A and D are B and C, already known
        for _ in range(100000):
            if self.surf1[-1].p[1] >= edge and self.surf2[-1].p[1] >= edge:
                return
            progressed = False
            for leftward in (False, True):
                surf, other, i = (self.surf1, self.surf2, i1) if not leftward else (self.surf2, self.surf1, i2)
                if i >= len(surf) or other[-1].p[1] >= edge:
                    continue
                src, dst = (self.F1, self.F1p) if not leftward else (self.F2p, self.F2)
                try:
                    (q,) = self.image(src, dst, self.c1, [surf[i]], leftward)
                except LeavesMedium:
                    continue
                if q.p[1] <= other[-1].p[1]:
                    raise DesignError("design.y_a", f"surface {'2' if not leftward else '1'} folds back at "
                                      f"y = {q.p[1]:.4g} (the construction is not monotonic)")
                other.append(q)
                i1, i2 = (i1 + 1, i2) if not leftward else (i1, i2 + 1)
                progressed = True
            if not progressed:
                if len(self.medium.layers) > MAX_LAYERS:
                    raise DesignError("design.m", f"more than {MAX_LAYERS} layers needed")
                self._add_layer(self.surf1, self.surf2)
        raise DesignError("design.y_a", "the alternating construction did not reach the aperture edge")

    def _side_foci(self, A: Pt, B: Pt):
        """Step 2: the layer-1 ray A → B, Snell at both ends, foci at ρ1 and ρ1' (3.19)–(3.21)."""
        g = self.g
        nA = np.sqrt(self.medium.n2_at(A.p[1]))

        def miss(alpha):
            ray = Ray(self.medium, A.p[0], A.p[1], nA * np.cos(alpha), 1.0, B.p[0] + 1e-9)
            if ray.x_end < B.p[0]:
                raise LeavesMedium()
            return ray.y_at(B.p[0]) - B.p[1]

        grid = np.linspace(1e-4, np.pi / 2 - 1e-3, 200)
        vals = []
        for al in grid:
            try:
                vals.append(miss(al))
            except LeavesMedium:
                break
        vals = np.array(vals)
        k = np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))
        if not k.size:
            raise DesignError("design.y_a", "no layer-1 ray joins A and B (3.19); change y_A or m")
        alpha = brentq(miss, grid[k[0]], grid[k[0] + 1], xtol=1e-15)
        ray = Ray(self.medium, A.p[0], A.p[1], nA * np.cos(alpha), 1.0, B.p[0] + 1e-9)
        _, vB, L_AB = ray.at(B.p[0])
        vA = np.array([np.cos(alpha), np.sin(alpha)])
        wA, okA = refract(-vA, A.n, nA, 1.0)
        wB, okB = refract(vB, B.n, np.sqrt(self.medium.n2_at(B.p[1])), 1.0)
        if not (okA and okB):
            raise DesignError("design.y_a", "the F1 ray A → B is totally reflected at a surface")
        self.F1 = A.p + g.rho1 * wA
        self.F1p = B.p + g.rho1_p * wB
        self.F2, self.F2p = self.F1 * [1, -1], self.F1p * [1, -1]
        self.c1 = g.rho1 + L_AB + g.rho1_p
        self.alpha_A = alpha

    def _invariant(self, src, pt: Pt, leftward: bool, medium: Medium | None = None) -> float:
        """a = n cos(angle to x) of the ray from ``src`` refracted into the lens at ``pt``."""
        n_in = np.sqrt((medium or self.medium).n2_at(pt.p[1]))
        v, ok = refract(_unit(pt.p - src), pt.n, 1.0, n_in)
        return float(n_in * abs(v[0]))

    def _add_layer(self, surf1, surf2):
        """Step 4 (3.25)–(3.31): the ray from F' through Q, the surface-2 point at the top boundary
        (invariant a_Q), rises
        into the new layer, turns at H, and comes back down to the height of E, the surface-1 point
        whose F-ray has the same invariant (3.25); m_i makes |QF'| + L(Q → height of E) + a_Q Δx + |FE|
        equal the central eikonal (the seed's approximation: the ray need not land at E)."""
        i = len(self.medium.layers)
        h = self.medium.top
        x2 = surface_spline(surf2)                 # Q at y = h (3.25): one step of extrapolation at most
        Q = Pt(np.array([float(x2(h)), h]), _unit([1.0, -float(x2.derivative()(h))]))
        x1 = surface_spline(surf1)
        slope = x1.derivative()
        a_q = self._invariant(self.Fp, Q, True)
        continued = _continued(self.medium)

        def a_e(y):
            pt = Pt(np.array([float(x1(y)), y]), _unit([1.0, -float(slope(y))]))
            return self._invariant(self.F, pt, False, continued)

        y_e = None
        for ys in (np.linspace(0.0, h, 200), np.linspace(h, 1.1 * h, 41)):    # surface 1 extrapolated
            av = np.array([a_e(y) for y in ys]) - a_q
            k = np.flatnonzero(np.sign(av[:-1]) != np.sign(av[1:]))
            if k.size:
                y_e = brentq(lambda y: a_e(y) - a_q, ys[k[-1]], ys[k[-1] + 1], xtol=1e-14)
                break
        if y_e is None:
            raise DesignError("design.m", f"layer {i + 1}: no surface-1 point E with the invariant of the "
                              "central ray through Q (3.25)")
        E = np.array([float(x1(y_e)), y_e])

        def trial(m_i):
            med = self.medium.copy()
            med.add_layer(m_i)
            ray, s, p = self._launch(self.Fp, Q, True, med)
            xs = np.linspace(p[0], ray.x_end, 400)
            yv = ray.ys(xs)
            top = int(np.argmax(yv))
            below = np.flatnonzero(yv[top:] < y_e)
            if not below.size or yv[top] <= med.layers[-2].hi:
                return np.nan, np.nan
            j = top + below[0]
            xr = brentq(lambda x: ray.y_at(x) - y_e, xs[j - 1], xs[j], xtol=1e-14)
            path = ray.at(xr)[2] + ray.a * (-E[0] - xr)
            return np.linalg.norm(p - s) + path + np.linalg.norm(E - self.F) - self.central, float(yv[top])

        ms = np.concatenate([-np.geomspace(200.0, 1e-3, 80), np.geomspace(1e-3, 200.0, 80)])
        vals = np.array([trial(m_i)[0] for m_i in ms])
        k = np.flatnonzero(np.isfinite(vals[:-1]) & np.isfinite(vals[1:]) & (np.sign(vals[:-1]) != np.sign(vals[1:])))
        for j in k:
            try:
                m_i = brentq(lambda v: trial(v)[0], ms[j], ms[j + 1], xtol=1e-14)
                break
            except ValueError:          # inside the bracket the ray stops turning in the layer (NaN)
                continue
        else:
            raise DesignError("design.m", f"no real m_{i + 1} makes the central focus of layer {i + 1} (3.31)")
        top = trial(m_i)[1]
        self.medium.add_layer(m_i)
        self.medium.close_top(top)


def _continued(medium: Medium) -> Medium:
    """A copy of ``medium`` whose top layer's law goes on above its top: E of (3.25) may lie a little
    above the top boundary, in the layer being added, whose law matches the top one's to first
    order there (C¹)."""
    out = medium.copy()
    out.layers[-1].hi = np.inf
    return out


def scalar_spline(spline: CubicHermiteSpline):
    """``spline`` at one float, on floats: the interval and the power sum of scipy's PPoly (the same
    bits; 20× less call overhead for the root finders)."""
    breaks, coef, last = spline.x.tolist(), spline.c.T.tolist(), len(spline.x) - 2

    def at(v: float) -> float:
        i = min(max(bisect.bisect_right(breaks, v) - 1, 0), last)
        dx, res, z = v - breaks[i], 0.0, 1.0
        for c in reversed(coef[i]):
            res, z = res + c * z, z * dx
        return res
    return at


def surface_spline(pts: list[Pt]) -> CubicHermiteSpline:
    """x(y) through the points and slopes of one surface, mirrored to −y (even surfaces)."""
    y = np.array([q.p[1] for q in pts])
    x = np.array([q.p[0] for q in pts])
    s = np.array([-q.n[1] / q.n[0] for q in pts])
    keep = y >= 0
    y, x, s = y[keep], x[keep], s[keep]
    order = np.argsort(y)
    y, x, s = y[order], x[order], s[order]
    y, idx = np.unique(y, return_index=True)
    x, s = x[idx], s[idx]
    yy = np.concatenate([-y[::-1], y[1:] if y[0] == 0 else y])
    xx = np.concatenate([x[::-1], x[1:] if y[0] == 0 else x])
    ss = np.concatenate([-s[::-1], s[1:] if y[0] == 0 else s])
    return CubicHermiteSpline(yy, xx, ss)
