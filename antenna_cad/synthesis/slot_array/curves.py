"""Synthesised 2-D curves (points + tangents), ray–curve intersection and normal offsets."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.common import _unit


@dataclass(frozen=True)
class Curve:
    """A synthesised 2-D curve y(x) as points with unit tangents (pointing to +x).

    ``layer`` names the parallel-plate layer the curve bounds; CAD fits a C¹ spline through
    ``points_mm`` with ``tangents``. :meth:`y_at` / :meth:`slope_at` evaluate the cubic Hermite
    interpolant through the same data.
    """
    name: str
    layer: str
    points_mm: np.ndarray     # (N, 2) x, y in mm, x strictly increasing
    tangents: np.ndarray      # (N, 2) unit tangents

    @property
    def slopes(self) -> np.ndarray:
        return self.tangents[:, 1] / self.tangents[:, 0]

    @cached_property
    def _splines(self) -> tuple[CubicHermiteSpline, CubicHermiteSpline]:
        spl = CubicHermiteSpline(self.points_mm[:, 0], self.points_mm[:, 1], self.slopes)
        return spl, spl.derivative()

    def y_at(self, x_mm):
        return self._splines[0](np.asarray(x_mm, dtype=float))

    def slope_at(self, x_mm):
        return self._splines[1](np.asarray(x_mm, dtype=float))

    @property
    def x_range_mm(self) -> tuple[float, float]:
        return float(self.points_mm[0, 0]), float(self.points_mm[-1, 0])


def _make_curve(name: str, layer: str, x, y, slope, scale: float = 1.0) -> Curve:
    x = np.asarray(x, float)
    order = np.argsort(x, kind="stable")
    x, y, s = x[order], np.asarray(y, float)[order], np.asarray(slope, float)[order]
    keep = np.concatenate([[True], np.diff(x) > 1e-12 * max(1.0, np.abs(x).max())])
    x, y, s = x[keep], y[keep], s[keep]
    t = _unit(np.stack([np.ones_like(s), s], axis=-1))
    return Curve(name, layer, np.stack([x, y], axis=-1) * scale, t)


def intersect_rays_with_curve(origin: np.ndarray, direction: np.ndarray, curve: Curve,
                              iterations: int = 30) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised Newton solve of origin + s·direction on the curve. Returns (points, ok)."""
    spl, dspl = curve._splines
    o = np.asarray(origin, float)
    d = _unit(np.asarray(direction, float))
    s = (spl(o[:, 0]) - o[:, 1]) / d[:, 1]
    x0, x1 = curve.x_range_mm
    scale = max(1.0, abs(x1 - x0))
    for _ in range(iterations):
        x = o[:, 0] + s * d[:, 0]
        g = spl(x) - (o[:, 1] + s * d[:, 1])
        dg = dspl(x) * d[:, 0] - d[:, 1]
        s = s - g / dg
        if np.max(np.abs(g)) < 1e-14 * scale:
            break
    p = o + s[:, None] * d
    g = spl(p[:, 0]) - p[:, 1]
    ok = (np.abs(g) < 1e-9 * max(1.0, abs(x1 - x0))) & (p[:, 0] >= x0) & (p[:, 0] <= x1) & (s > 0)
    return p, ok


def _rms(v: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(v))))


def offset_curve(curve: Curve, distance_mm: float, name: str) -> Curve:
    """Normal offset of ``curve`` by ``distance_mm`` toward +y (the coupling-slot far edge, §8.1
    item 5). Tangents are unchanged; raises if the offset self-intersects (x not increasing)."""
    t = curve.tangents
    nrm = np.stack([-t[:, 1], t[:, 0]], -1)               # +y side for tangents toward +x
    p = curve.points_mm + distance_mm * nrm
    if not np.all(np.diff(p[:, 0]) > 0):
        raise DesignError("beamformer.coupling_slot_mm", f"offset {distance_mm:.4g} mm of "
                          f"{curve.name} self-intersects")
    return Curve(name, curve.layer, p, t.copy())
