"""Kinber's bifocal lens completed (seed-001 §3.1): the central-segment curvatures a2, b2 from C²
continuity at the junctions, and the segment heights h1 (= h2) chosen for the least RMS over the
view angle.

The method of steps makes both surfaces C¹ by construction; a2 and b2 are "found numerically from
continuity of the second derivatives at the junctions B and C" (digest §3.1). Here the curvature of
the first constructed segment at its junction (the derivative of the Snell slopes of the points just
beyond it, a quadratic fit over JUNCTION_SPAN) must equal the parabola's 2·a2 (surface 1, at C,
y = h1) and 2·b2 (surface 2, at B, y = h2).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from antenna_cad.synthesis.bifocal import kinber_focal_circle_rms, kinber_lens
from antenna_cad.synthesis.checks import DesignError

JUNCTION_POINTS = 201       # points per central segment for the curvature estimate
JUNCTION_SPAN = 0.01        # y range (D = 1) beyond the junction fitted for the curvature


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


def optimise_h(n, a0, b0, rho1, rho2, h_range, x_axis, half_view_deg, a2_guess=1.0):
    """Symmetric point-image lens: h1 = h2 in ``h_range`` minimising the max RMS (3.10) over ±half view
    on the focal circle through F1, F2 crossing the axis at ``x_axis``, each h with its C² a2 = −b2.
    Returns (h, a2, max RMS)."""
    guess = [a2_guess]

    def worst(h):
        a2, _, _ = solve_c2(n, a0, h, b0, h, rho1, rho2, None, guess[0])
        guess[0] = a2
        lens = kinber_lens(n, a0, a2, h, b0, -a2, h, rho1, rho2)
        return float(np.max(kinber_focal_circle_rms(lens, x_axis, half_view_deg, 11)[1]))

    fit = minimize_scalar(worst, bounds=h_range, method="bounded", options={"xatol": 1e-4})
    a2, _, _ = solve_c2(n, a0, fit.x, b0, fit.x, rho1, rho2, None, guess[0])
    return float(fit.x), a2, float(fit.fun)
