"""Exact 2-D GO tracing through piecewise-homogeneous media, vectorized over rays.

Frame as :mod:`antenna_cad.raytrace.trace2d`: points and directions are ``(z, y)`` pairs, z along
the axis, y transverse. A medium answers two questions for arrays of rays: the refractive index
at points (:meth:`index`) and the distance to the next boundary along a ray with the boundary
normal there (:meth:`next_hit`); it also states its ``size`` (a radius holding it) and its
number of ``boundaries`` (the event budget). :func:`trace_media` walks every ray from boundary to boundary:
straight segments, vector Snell where the index changes (:mod:`antenna_cad.raytrace.snell`,
seed-000 §2.7), mirror reflection where it is total, optical path Σ n·length. Fresnel losses
are ignored. Two media:

* :class:`Shells` — concentric homogeneous shells about the origin (a multilayer Luneburg sphere
  in a meridional plane, seed-002 §2.1b, or the rings of a parallel-plate cylinder lens), with an
  optional homogeneous rectangle outside them (a feed boss);
* :class:`Staircase` — a stack of flat sheets z_k ≤ z ≤ z_{k+1}, each made of concentric rings
  (|y| between ring radii) of their own index: a sheet layup in a plane through its axis, where
  the spherical shell boundaries become staircases of sheet faces and ring edges.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.raytrace.snell import reflect, refract

NUDGE = 1e-9          # relative to the medium's size: how far past a boundary its far side is sampled


@dataclass(frozen=True)
class MediaTrace:
    """Result of :func:`trace_media`. ``points[e]`` is where every ray is after event e
    (``points[0]``: origins; a ray that has left the medium repeats its last point).
    ``direction``/``opl`` are at the last point; ``exit_zy``/``exit_opl`` where the ray last
    passed from a dielectric into air (its exit from the lens); ``ok`` is False for rays still
    inside after the event budget."""

    points: np.ndarray       # (E+1, N, 2)
    direction: np.ndarray    # (N, 2)
    opl: np.ndarray          # (N,)
    ok: np.ndarray           # (N,) bool
    exit_zy: np.ndarray      # (N, 2)
    exit_opl: np.ndarray     # (N,)

    @property
    def end(self) -> np.ndarray:
        return self.points[-1]


def _first_positive(t: np.ndarray, tiny: float) -> np.ndarray:
    """Smallest entry > tiny along the last axis (inf if none; NaN entries are no hit)."""
    return np.min(np.where(t > tiny, t, np.inf), axis=-1)


@dataclass(frozen=True)
class Shells:
    """Shell i fills radii[i−1] ≤ r < radii[i] (radii[−1] = 0) with index ``n[i]``; air (1)
    beyond the last radius, except inside ``boss`` = (z_min, z_max, y_min, y_max, n) there."""

    radii: np.ndarray
    n: np.ndarray
    boss: tuple[float, float, float, float, float] | None = None

    @property
    def boundaries(self) -> int:
        return len(self.radii) + (0 if self.boss is None else 3)

    @property
    def size(self) -> float:
        return float(self.radii[-1]) if self.boss is None else float(
            max(self.radii[-1], np.hypot(max(abs(self.boss[0]), abs(self.boss[1])),
                                         max(abs(self.boss[2]), abs(self.boss[3])))))

    def index(self, p: np.ndarray) -> np.ndarray:
        r = np.hypot(p[:, 0], p[:, 1])
        j = np.searchsorted(self.radii, r, side="right")
        out = np.concatenate([self.n, [1.0]])[j]
        if self.boss is not None:
            z0, z1, y0, y1, nb = self.boss
            inside = (j == len(self.radii)) & (p[:, 0] >= z0) & (p[:, 0] <= z1) & (p[:, 1] >= y0) & (p[:, 1] <= y1)
            out = np.where(inside, nb, out)
        return out

    def next_hit(self, p: np.ndarray, d: np.ndarray, tiny: float) -> tuple[np.ndarray, np.ndarray]:
        b = np.sum(p * d, axis=1)[:, None]
        c = np.sum(p * p, axis=1)[:, None] - self.radii[None, :] ** 2
        disc = b * b - c
        root = np.sqrt(np.where(disc >= 0, disc, np.nan))
        t = _first_positive(np.concatenate([-b - root, -b + root], axis=1), tiny)
        hit = p + np.where(np.isfinite(t), t, 0.0)[:, None] * d
        normal = hit / np.maximum(np.linalg.norm(hit, axis=1, keepdims=True), 1e-300)
        if self.boss is None:
            return t, normal
        z0, z1, y0, y1, _ = self.boss
        with np.errstate(divide="ignore", invalid="ignore"):
            tz = (np.array([z0, z1])[None, :] - p[:, :1]) / d[:, :1]
            ty = (np.array([y0, y1])[None, :] - p[:, 1:]) / d[:, 1:]
        yz = p[:, 1:] + tz * d[:, 1:]
        zy = p[:, :1] + ty * d[:, :1]
        tz = np.where((yz >= y0) & (yz <= y1), tz, np.inf)
        ty = np.where((zy >= z0) & (zy <= z1), ty, np.inf)
        tb_z, tb_y = _first_positive(tz, tiny), _first_positive(ty, tiny)
        tb = np.minimum(tb_z, tb_y)
        use = tb < t
        normal = np.where(use[:, None], np.where((tb_z <= tb_y)[:, None], [1.0, 0.0], [0.0, 1.0]), normal)
        return np.where(use, tb, t), normal


@dataclass(frozen=True)
class Staircase:
    """Sheet k spans ``z_edges[k] ≤ z ≤ z_edges[k+1]``; within it, |y| between ``breaks[k, i−1]``
    and ``breaks[k, i]`` (breaks[k, −1] = 0) has index ``n[k, i]``; rows are padded with +inf
    breaks, and |y| beyond a sheet's last finite break, or z outside the stack, is air (1).
    ``slopes[k, i]``: d(break)/dz within the sheet, the break being ``breaks[k, i]`` at its front
    face z_edges[k] — a taper-cut ring's edge is a cone, a straight line in this plane (all zero:
    vertical ring edges)."""

    z_edges: np.ndarray      # (K+1,)
    breaks: np.ndarray       # (K, M) increasing per row, +inf padded
    n: np.ndarray            # (K, M + 1), n[k, M] = 1 (beyond the padding)
    slopes: np.ndarray | None = None    # (K, M), zero where padded; None: all zero

    @staticmethod
    def from_rings(z_edges, rings: list[list[tuple[float, float, float]]]) -> "Staircase":
        """``rings[k]``: (r_inner, r_outer, n) of sheet k, non-overlapping; gaps between them are air."""
        return Staircase.from_cones(z_edges, [[((a, a), (b, b), n) for a, b, n in sheet] for sheet in rings])

    @staticmethod
    def from_cones(z_edges, rings) -> "Staircase":
        """``rings[k]``: ((inner front, inner back), (outer front, outer back), n) of sheet k, its
        edges straight from its front face to its back face, non-overlapping; gaps are air."""
        z_edges = np.asarray(z_edges, float)
        rows = []
        for k, sheet in enumerate(rings):
            t = z_edges[k + 1] - z_edges[k]
            edges, slopes, ns = [], [], []
            for inner, outer, n in sorted(sheet):
                last = edges[-1] if edges else (0.0, 0.0)
                if max(inner[0] - last[0], inner[1] - last[1]) > 1e-12:      # air gap before this ring
                    edges.append(tuple(inner))
                    ns.append(1.0)
                edges.append(tuple(outer))
                ns.append(n)
            rows.append(([e[0] for e in edges], [(e[1] - e[0]) / t for e in edges], ns))
        M = max(1, max(len(e) for e, _, _ in rows))
        breaks, slope = np.full((len(rows), M), np.inf), np.zeros((len(rows), M))
        n = np.ones((len(rows), M + 1))
        for k, (edges, ds, ns) in enumerate(rows):
            breaks[k, :len(edges)], slope[k, :len(ds)], n[k, :len(ns)] = edges, ds, ns
        return Staircase(z_edges, breaks, n, slope if slope.any() else None)

    @property
    def boundaries(self) -> int:
        return int(np.isfinite(self.breaks).sum()) + len(self.z_edges)

    @property
    def size(self) -> float:
        back = self.breaks + (0.0 if self.slopes is None else self.slopes * np.diff(self.z_edges)[:, None])
        finite = np.where(np.isfinite(self.breaks), np.maximum(self.breaks, back), 0.0)
        return float(np.hypot(finite.max(), np.abs(self.z_edges).max()))

    def _radii(self, kc: np.ndarray, z: np.ndarray) -> np.ndarray:
        """The breaks of sheets ``kc`` at depths ``z`` (one row per point)."""
        if self.slopes is None:
            return self.breaks[kc]
        return self.breaks[kc] + self.slopes[kc] * (z - self.z_edges[kc])[:, None]

    def _cell(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        k = np.searchsorted(self.z_edges, p[:, 0], side="right") - 1
        inside = (k >= 0) & (k < len(self.z_edges) - 1)
        kc = np.clip(k, 0, len(self.z_edges) - 2)
        j = np.sum(self._radii(kc, p[:, 0]) <= np.abs(p[:, 1])[:, None], axis=1)
        return k, kc, np.where(inside, j, -1)

    def index(self, p: np.ndarray) -> np.ndarray:
        _, kc, j = self._cell(p)
        return np.where(j >= 0, self.n[kc, np.maximum(j, 0)], 1.0)

    def next_hit(self, p: np.ndarray, d: np.ndarray, tiny: float) -> tuple[np.ndarray, np.ndarray]:
        """Distance to the next sheet face or ring edge, and the normal there. The edges of the
        ray's cell, on its side σ of the axis, are y = σ(b + s(z − z_k)) (the central cell's lower
        one is its upper one mirrored across the axis); the ray meets one where it closes on it,
        p_y + t d_y = σ(b + s(p_z + t d_z − z_k)); the edge's normal is (−σs, 1)/√(1 + s²)."""
        q = p + tiny * d                                  # the cell the ray is travelling through
        k, kc, j = self._cell(q)
        inside = j >= 0
        K = len(self.z_edges) - 1
        with np.errstate(divide="ignore", invalid="ignore"):
            face = np.where(d[:, 0] > 0, self.z_edges[np.clip(k + 1, 0, K)], self.z_edges[np.clip(k, 0, K)])
            face = np.where(k < 0, np.where(d[:, 0] > 0, self.z_edges[0], np.nan), face)
            face = np.where(k >= K, np.where(d[:, 0] < 0, self.z_edges[-1], np.nan), face)
            tz = (face - p[:, 0]) / d[:, 0]
            side = np.where(q[:, 1] != 0, np.sign(q[:, 1]), np.sign(d[:, 1]))
            jc = np.maximum(j, 0)
            padded = np.concatenate([self.breaks, np.full((K, 1), np.inf)], axis=1)
            tilt = np.zeros_like(padded) if self.slopes is None else np.concatenate([self.slopes, np.zeros((K, 1))], 1)
            central = jc == 0
            upper = (side, jc, 1.0)                                            # (σ, edge, the cell below it: +1)
            lower = (np.where(central, -side, side), np.where(central, 0, jc - 1), np.where(central, 1.0, -1.0))
            hits = []
            for sigma, edge, below in (upper, lower):
                b, s = padded[kc, edge], tilt[kc, edge]
                closing = below * (sigma * d[:, 1] - s * d[:, 0])             # > 0: the ray gains on the edge
                t = (sigma * (b + s * (p[:, 0] - self.z_edges[kc])) - p[:, 1]) / (d[:, 1] - sigma * s * d[:, 0])
                hits.append((np.where(inside & (closing > 0) & np.isfinite(t) & (t > 0), t, np.inf), sigma * s))
        (t_up, ds_up), (t_low, ds_low) = hits
        ty = np.minimum(t_up, t_low)
        ds = np.where(t_up <= t_low, ds_up, ds_low)
        tz = np.where(np.isfinite(tz) & (tz > 0), tz, np.inf)
        across_z = tz <= ty
        edge_normal = np.stack([-ds, np.ones_like(ds)], axis=1) / np.sqrt(1.0 + ds * ds)[:, None]
        normal = np.where(across_z[:, None], [1.0, 0.0], edge_normal)
        return np.where(across_z, tz, ty), normal


def trace_media(medium, origins: np.ndarray, directions: np.ndarray, max_events: int | None = None,
                stop_mm: np.ndarray | None = None, straight: bool = False) -> MediaTrace:
    """Trace rays through ``medium`` until they leave it for good (in air, beyond the medium's
    size and moving away, or with no boundary ahead), or after ``stop_mm`` of travel.
    ``straight``: no refraction (the optical path of a given straight segment)."""
    p = np.array(origins, float, ndmin=2)
    d = np.array(directions, float, ndmin=2)
    d = d / np.linalg.norm(d, axis=1, keepdims=True)
    size = medium.size
    tiny = NUDGE * size
    budget = max_events or 64 + 4 * medium.boundaries
    n_cur = medium.index(p + tiny * d)
    opl = np.zeros(len(p))
    active = np.ones(len(p), bool)
    left = np.full(len(p), np.inf) if stop_mm is None else np.array(stop_mm, float)
    pts = [p.copy()]
    exit_zy, exit_opl = p.copy(), opl.copy()
    for _ in range(budget):
        t, normal = medium.next_hit(p, d, tiny)
        gone = (n_cur == 1.0) & (np.sum(p * p, axis=1) > size * size) & (np.sum(p * d, axis=1) >= 0)
        t = np.where(gone, np.inf, t)                    # nothing more to meet: run out ``left`` in air
        active &= (np.isfinite(t) | np.isfinite(left)) & (left > 0)
        if not active.any():
            break
        step = np.where(active, np.minimum(t, left), 0.0)
        left = left - step
        p = p + step[:, None] * d
        opl = opl + n_cur * step
        if straight:
            n_cur = medium.index(p + tiny * d)
            pts.append(p.copy())
            continue
        n_next = medium.index(p + tiny * d)
        change = active & (n_next != n_cur)
        d_new, ok = refract(d, normal, n_cur, n_next)
        tir = change & ~ok
        d = np.where((change & ok)[:, None], d_new, np.where(tir[:, None], reflect(d, normal), d))
        n_cur = np.where(change & ok, n_next, n_cur)
        leave = change & ok & (n_next == 1.0)
        exit_zy = np.where(leave[:, None], p, exit_zy)
        exit_opl = np.where(leave, opl, exit_opl)
        pts.append(p.copy())
    return MediaTrace(np.array(pts), d, opl, ~active, exit_zy, exit_opl)
