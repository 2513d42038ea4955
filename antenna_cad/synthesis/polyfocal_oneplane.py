"""Four-focal 2-D constrained lens with one symmetry plane and finite foci (seed-001 §1.4).

Frame as :mod:`~antenna_cad.synthesis.polyfocal` (z the axis, y transverse, lens centre O, l = 0 on
the central line). The foci are two mirror pairs at distances from O: F1/F2 at (f1, ±α) with images
F1'/F2' at (f1', ∓α), F3/F4 at (f3, ±β) with F3'/F4' at (f3', ∓β) (F_i' = −(f_i'/f_i)·F_i). With
f_i ≠ f_i' the surfaces are no mirror images: for each entry ordinate y1 the unknowns are z1, z2, y2
and l, fixed by the four eikonal equations (1.1). The thesis reduces them to (1.12)–(1.14), singular
on the axis (0/0 in P_i); as its digest advises, the four equations are solved directly by Newton with
continuation in y1 from the axis, and the reduction — with the corrected (1.11) (sin²β in P3) — is
evaluated on the solution as a cross-check (:func:`reduction_residuals`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.synthesis.polyfocal import ConstrainedLens, Focus, _pt, newton

START = 1e-3          # first continuation step off the axis, in units of D


@dataclass(frozen=True)
class FinitePair:
    """A mirror pair of foci at distance ``f`` from O and angle ±``angle`` (rad) to the axis, imaged
    at distance ``f_image`` on the other side (seed-001 §1.1, §1.4)."""
    f: float
    f_image: float
    angle: float

    def foci(self) -> tuple[Focus, Focus]:
        s, c = np.sin(self.angle), np.cos(self.angle)
        return tuple(Focus(_pt(sg * self.f * s, -self.f * c), image=_pt(-sg * self.f_image * s, self.f_image * c))
                     for sg in (1.0, -1.0))


def _residuals(foci: tuple[Focus, ...], targets: np.ndarray, y1: float, v: np.ndarray) -> np.ndarray:
    z1, z2, y2, l = v
    r1, r2 = _pt(y1, z1), _pt(y2, z2)
    return np.array([np.linalg.norm(f.point - r1) + l + np.linalg.norm(r2 - f.image) for f in foci]) - targets


def one_plane_2d(p1: FinitePair, p3: FinitePair, aperture: float, y1: np.ndarray) -> ConstrainedLens:
    """Seed-001 §1.4 lens at the entry ordinates ``y1 ≥ 0`` (mirrored to −y1: y2, z1, z2 and l are odd,
    even, even, even in y1). Newton on (1.1) from the axis (0, 0, 0, 0), a quadratic extrapolation of
    the last three points as each start; DesignError naming design.foci where it fails."""
    foci = p1.foci() + p3.foci()
    targets = np.array([p.f + p.f_image for p in (p1, p1, p3, p3)])
    y1 = np.asarray(y1, dtype=float)
    ys = np.union1d([0.0, START * aperture, 2 * START * aperture], y1)
    sols = [np.zeros(4)]
    for i, yi in enumerate(ys[1:], start=1):
        if i == 1:
            guess = np.array([0.0, 0.0, yi, 0.0])           # y2 = y1 when f' = f (§1.2)
        else:
            guess = _extrapolate(ys[max(0, i - 3):i], sols[max(0, i - 3):i], yi)
        sols.append(newton(lambda v: _residuals(foci, targets, yi, v), guess, "design.foci",
                           f"(1.1) with one symmetry plane at y1 = {yi:g}"))
    sol = np.array(sols)[np.isin(ys, y1)]
    keep = slice(1, None) if y1[0] == 0 else slice(None)
    sign = np.concatenate([-np.ones(len(y1)), np.ones(len(sol[keep]))])
    rows = np.concatenate([sol[::-1], sol[keep]])
    ys1 = np.concatenate([y1[::-1], y1[keep]]) * sign
    r1 = np.column_stack([np.zeros(len(rows)), ys1, rows[:, 0]])
    r2 = np.column_stack([np.zeros(len(rows)), sign * rows[:, 2], rows[:, 1]])
    return ConstrainedLens(r1, r2, rows[:, 3], foci, aperture, 2,
                           "Newton on the four equations (1.1) in (z1, z2, y2, l), continuation in y1 from the axis")


def _extrapolate(xs: np.ndarray, values: list[np.ndarray], x: float) -> np.ndarray:
    """Lagrange polynomial through the last points (two or three), evaluated at x."""
    out = np.zeros_like(values[0])
    for j, (xj, vj) in enumerate(zip(xs, values)):
        w = np.prod([(x - xk) / (xj - xk) for k, xk in enumerate(xs) if k != j])
        out = out + w * vj
    return out


def reduction_residuals(p1: FinitePair, p3: FinitePair, lens: ConstrainedLens) -> np.ndarray:
    """|z1 − Q1| and |z2 − Q2| of the thesis reduction (1.12)–(1.13) on the lens's off-axis points, with
    P_i = S_i² y1² f_i² / Y_i² + sin²θ_i · Y_i² / S_i², S_i = f_i + f_i' − l, Y_i = y1 f_i + y2 f_i' (1.10),
    the corrected (1.11) (sin²β) and P_i' with y2² f_i'² (1.13)."""
    off = np.abs(lens.r1[:, 1]) > 1e-6 * lens.aperture
    y1, z1, y2, z2, l = lens.r1[off, 1], lens.r1[off, 2], lens.r2[off, 1], lens.r2[off, 2], lens.l[off]

    def p_terms(p):
        s, y = p.f + p.f_image - l, y1 * p.f + y2 * p.f_image
        tail = np.sin(p.angle) ** 2 * y**2 / s**2
        return s**2 * y1**2 * p.f**2 / y**2 + tail, s**2 * y2**2 * p.f_image**2 / y**2 + tail

    (P1, P1i), (P3, P3i) = p_terms(p1), p_terms(p3)
    ca, cb = np.cos(p1.angle), np.cos(p3.angle)
    q1 = (p3.f**2 - p1.f**2 + P1 - P3) / (2 * (p1.f * ca - p3.f * cb))
    q2 = (p3.f_image**2 - p1.f_image**2 + P1i - P3i) / (2 * (p3.f_image * cb - p1.f_image * ca))
    return np.concatenate([np.abs(z1 - q1), np.abs(z2 - q2)])

