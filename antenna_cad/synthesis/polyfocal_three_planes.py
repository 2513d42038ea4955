"""3-D constrained lens with three symmetry planes (seed-001 §2.2): variant 1, (2.2)–(2.3), and
variant 2, the "rhombus", (2.4)–(2.9).

Variant 1: four foci in the yz plane, F1/F2 at (f1, ±α) and F3/F4 at (f3, ±β); variant 2: F3/F4 in the
xz plane instead (the foci's projections form a rhombus). Distances from the surface centres
A = (0, 0, −z0) and B = (0, 0, z0) as §1.2–§1.3, each imaged at the point-symmetric F_i' = −F_i. The
symmetry makes the line through the lens parallel to the axis: entry (x, y, −z), exit (x, y, z), and
the two pair equations (2.2) (with the corrected f3 cos β in the second) or (2.4) fix z and the line
length l at every (x, y). They are (1.5) with the other transverse coordinate's square added to each
squared distance, so in variant 1 the plane x = 0 holds the 2-D two-plane lens. Solved for all points at once by Newton's method on (z, l) with
continuation along each point's ray from the lens centre; the thesis' explicit (2.3) (its inputs are
(x, l)) is evaluated on the solution as a cross-check (:func:`explicit_23_residuals`).
"""

from __future__ import annotations

import numpy as np

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.polyfocal import ConstrainedLens, Focus, SymFocus

STEPS = 24                # continuation steps along each ray
NEWTON_IT = 40


def _front(s: SymFocus, azimuth: float, z0: float) -> np.ndarray:
    """The focus at distance f from A = (0, 0, −z0), angle θ to the axis, azimuth from Oy (2.1)."""
    return np.array([s.f * np.sin(s.angle) * np.sin(azimuth), s.f * np.sin(s.angle) * np.cos(azimuth),
                     -z0 - s.f * np.cos(s.angle)])


def _partner(p: np.ndarray, sx: float) -> np.ndarray:
    """The pair's second focus: the entry-side point whose path to (x, y, −z) equals the exit path to
    −F through (sx·x, y, z) — the mirror of F in y (sx = −1, or F in the yz plane) or in x (F in xz)."""
    return np.array([-sx * p[0], -p[1], p[2]])


def _pair(p: np.ndarray, q: np.ndarray, f: float, x, y, z):
    """(2.2)/(2.4)/(2.34) for one pair, minus 2f: the paths from F and its partner to (x, y, −z)."""
    return (np.sqrt((p[0] - x) ** 2 + (p[1] - y) ** 2 + (p[2] + z) ** 2)
            + np.sqrt((q[0] - x) ** 2 + (q[1] - y) ** 2 + (q[2] + z) ** 2) - 2 * f)


def three_planes_3d(f1: SymFocus, f3: SymFocus, z0: float, aperture: float, xy: np.ndarray,
                    rhombus: bool = False, azimuths: tuple[float, float] = (0.0, 0.0)) -> ConstrainedLens:
    """Seed-001 §2.2 at the points (x, y) (rows of ``xy``): variant 1, or variant 2 (``rhombus``: F3/F4
    in the xz plane); with ``azimuths`` (φ, ξ) ≠ 0 the §2.3 (d) trapezoid, whose lines cross the axis
    plane x = 0 (exit x2 = −x1, (2.34)). DesignError naming design.aperture where the continuation
    loses the solution."""
    xy = np.asarray(xy, dtype=float)
    sx = -1.0 if any(azimuths) else 1.0
    fronts = (_front(f1, azimuths[0], z0), _front(f3, np.pi / 2 if rhombus else azimuths[1], z0))
    pairs = [(p, _partner(p, sx), s.f) for p, s in zip(fronts, (f1, f3))]
    z, dl = np.full(len(xy), z0), np.zeros(len(xy))
    for t in np.linspace(1.0 / STEPS, 1.0, STEPS):
        x, y = xy[:, 0] * t, xy[:, 1] * t
        for _ in range(NEWTON_IT):
            r1, r3 = (_pair(*pr, x, y, z) + dl for pr in pairs)
            if max(np.max(np.abs(r1)), np.max(np.abs(r3))) < 1e-13:
                break
            h = 1e-7
            d1, d3 = ((_pair(*pr, x, y, z + h) - _pair(*pr, x, y, z - h)) / (2 * h) for pr in pairs)
            det = d1 - d3                                     # rows [d1, 1], [d3, 1]
            z, dl = z - (r1 - r3) / det, dl - (d1 * r3 - d3 * r1) / det
        bad = ~(np.maximum(*(np.abs(_pair(*pr, x, y, z) + dl) for pr in pairs)) < 1e-10)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise DesignError("design.aperture", f"the symmetric 3-D solution is lost at x = {x[k]:.4g}, y = "
                              f"{y[k]:.4g} (no real solution there for these foci; reduce the aperture)")
    r1 = np.column_stack([xy, -z])
    r2 = np.column_stack([sx * xy[:, 0], xy[:, 1], z])
    foci = []
    for p, q, _ in pairs:
        for point in ((p, q) if np.linalg.norm(p - q) > 0 else (p,)):
            foci.append(Focus(point, image=-point))
    eq = "(2.34)" if sx < 0 else "(2.4)" if rhombus else "(2.2)"
    return ConstrainedLens(r1, r2, dl, tuple(foci), aperture, 3,
                           f"Newton on the two pair equations {eq} in (z, l), continuation along each ray")


def explicit_23_residuals(f1: SymFocus, f3: SymFocus, z0: float, lens: ConstrainedLens) -> np.ndarray:
    """|z − z(2.3)| and |y² − y²(2.3)| on the lens's points off the centre: (2.3) with inputs (x, l), the
    nearer of its two roots (the branch caveat of (1.6)), z the exit side's from its centre (z − z0)."""
    x, y, z, l = lens.r2[:, 0], lens.r2[:, 1], lens.r2[:, 2] - z0, lens.l
    ca, cb = f1.f * np.cos(f1.angle), f3.f * np.cos(f3.angle)
    s1, s3 = 2 * f1.f - l, 2 * f3.f - l
    L = f1.f**2 * np.sin(f1.angle) ** 2 / s1**2 - f3.f**2 * np.sin(f3.angle) ** 2 / s3**2
    M = 4 * f1.f**2 * np.sin(f1.angle) ** 2 / s1**2 - 1
    P = (ca - cb) * M / (2 * L) - 2 * ca
    Q = f1.f**2 + x**2 - s1**2 / 4 - l * (f1.f - f3.f) * M / (4 * L)
    disc = np.sqrt(np.maximum(P**2 - 4 * Q, 0.0))
    roots = np.stack([-(P + disc) / 2, -(P - disc) / 2])
    z23 = roots[np.argmin(np.abs(roots - z), axis=0), np.arange(len(z))]
    y23 = (-2 * z23 * (ca - cb) + l * (f1.f - f3.f)) / (4 * L)
    return np.concatenate([np.abs(z23 - z), np.abs(y23 - y**2)])


def rhombus_27_28_residuals(f1: SymFocus, f3: SymFocus, z0: float, lens: ConstrainedLens) -> np.ndarray:
    """|y1² − (J z1 + T)| (2.7) and |z1² + M z1 + N| (2.8) on the rhombus lens's entry points, z1 from
    the entry surface's centre (z1 = z_entry + z0)."""
    x1, y1, z1, l = lens.r1[:, 0], lens.r1[:, 1], lens.r1[:, 2] + z0, lens.l
    a, b, g1, g3 = f1.angle, f3.angle, f1.f, f3.f
    s1, s3 = 2 * g1 - l, 2 * g3 - l
    J = (g1 * np.cos(a) - g3 * np.cos(b)) * s1**2 / (2 * g1**2 * np.sin(a) ** 2)
    T = ((4 * (g1**2 - g3**2) + s3**2 - s1**2 + 16 * x1**2 * g3**2 * np.sin(b) ** 2 / s3**2) * s1**2
         / (16 * g1**2 * np.sin(a) ** 2))
    M = J + 2 * g3 * np.cos(b)
    N = T + g3**2 + x1**2 - s3**2 / 4 - 4 * x1**2 * g3**2 * np.sin(b) ** 2 / s3**2
    return np.concatenate([np.abs(y1**2 - (J * z1 + T)), np.abs(z1**2 + M * z1 + N)])
