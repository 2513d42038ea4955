"""Solid figures of a bifocal lens for CAD and layup (pure numpy; the solids themselves live in
geometry/bifocal.py): the face splines, the exact lens volume and the largest lens radius in a slab.
Frame and units: :mod:`antenna_cad.synthesis.bifocal`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq

from antenna_cad.synthesis.bifocal_steps import _hermite

if TYPE_CHECKING:
    from antenna_cad.synthesis.bifocal import BifocalDesign



def face_spline(design: BifocalDesign, surface: Literal["illuminated", "shadow"]) -> CubicHermiteSpline:
    """The C¹ Hermite profile z(y) of one face (the same curve as :meth:`BifocalDesign.profile`)."""
    pts = design.illuminated_mm if surface == "illuminated" else design.shadow_mm
    sl = design.illuminated_slopes if surface == "illuminated" else design.shadow_slopes
    return _hermite(pts[:, 1], pts[:, 0], sl)


def _gauss_integral(fun, knots: np.ndarray, order: int = 4) -> float:
    """∫ fun over [knots[0], knots[-1]], Gauss–Legendre per knot interval (exact for piecewise
    polynomials of degree ≤ 2·order − 1 whose breaks are among the knots)."""
    x, w = np.polynomial.legendre.leggauss(order)
    a, b = knots[:-1, None], knots[1:, None]
    xs = 0.5 * (b - a) * x + 0.5 * (a + b)
    return float(np.sum(0.5 * (b - a) * w * fun(xs)))


def lens_volume_mm3(design: BifocalDesign, height_mm: float | None = None) -> float:
    """Exact volume of the lens between its Hermite faces: revolved ``2π∫₀^{Y_B} y (z_sh − z_ill) dy``,
    cylindrical ``h ∫_{−Y_B}^{Y_B} (z_sh − z_ill) dy`` (piecewise-polynomial integrands, Gauss exact)."""
    si, ss = face_spline(design, "illuminated"), face_spline(design, "shadow")
    knots = np.unique(np.concatenate([design.illuminated_mm[:, 1], design.shadow_mm[:, 1]]))
    if design.shape == "cylindrical":
        return float(height_mm) * _gauss_integral(lambda y: ss(y) - si(y), knots)
    knots = knots[knots >= 0.0]
    return 2.0 * np.pi * _gauss_integral(lambda y: y * (ss(y) - si(y)), knots)


def max_radius_in(design: BifocalDesign, z_lo_mm: float, z_hi_mm: float, num: int = 4001) -> float:
    """Largest |y| of the lens section within the slab z ∈ [z_lo, z_hi] (lens frame): the largest y ≥ 0
    with ``z_ill(y) ≤ z_hi`` and ``z_sh(y) ≥ z_lo`` (the lens chord at y meets the slab). Dense scan,
    then the boundary refined by root finding; exactly Y_B when the rim X_B lies in the slab.
    Returns 0 when the slab misses the lens."""
    si, ss = face_spline(design, "illuminated"), face_spline(design, "shadow")
    yb = design.edge_y_mm
    y = np.linspace(0.0, yb, num)
    good = (si(y) <= z_hi_mm) & (ss(y) >= z_lo_mm)
    if not good.any():
        return 0.0
    i = int(np.nonzero(good)[0][-1])
    if i == num - 1:
        return float(yb)
    g = lambda t: min(z_hi_mm - float(si(t)), float(ss(t)) - z_lo_mm)  # noqa: E731  ≥ 0 inside
    return float(brentq(g, y[i], y[i + 1], xtol=1e-12 * yb, rtol=1e-15))
