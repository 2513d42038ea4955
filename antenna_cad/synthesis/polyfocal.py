"""Polyfocal constrained lenses (seed-001 §1, §2): the lines of fixed electrical length that join an
entry surface to an exit surface, solved so that every design focus is imaged perfectly.

Frame (stated once): seed-001 Ch.1/Ch.2 — **z** the lens axis (feeds at z < 0, output toward +z),
**y** transverse in the 2-D section, **x** the second transverse axis of 3-D lenses (2-D lenses lie in
x = 0). Lengths are in the seed's normalised units (λ = 1 in Ch.1, D = 1 in Ch.2); the kind adapter
scales them to millimetres. ``l`` is the electrical (free-space-equivalent) line length, defined up
to a common constant (seed-001 §1.1): here l = 0 on the central line.

Solutions
---------
* ``two_planes_2d`` — §1.2/§1.3: two- to four-focal lenses with two symmetry planes (entry point
  (y, −z), exit point (y, z), y1 = y2). Four and three foci: the two equations (1.5) solved for (z, l)
  by Newton with continuation in y from the centre (digest branch note), cross-checked against the
  explicit (1.6) (the root sign that matches is the reported branch). Two foci: the one equation
  (1.2) with the line law of designs (a) equal lengths, (b) straight lines of phase index n_w,
  (c) flat surfaces.
* ``plane_wave_trifocal_2d`` — §1.5: the equal-line-length trifocal lens (foci F, F1, F2 → plane
  waves), the quadratic (1.23)–(1.24) stepped in z2 along both solution families through the axis.
* ``five_focal_3d`` — §2.4: the one-symmetry-plane five-focal lens with plane-wave output, explicit
  in (x1, y2): (2.49) → (2.47) corrected → the 3×3 linear system for (x2, z2, l).

Every solution carries its eikonal residuals: for each design focus the spread of the path
|F − r1| + l + (|r2 − F'| or −k·r2) over all lines (near machine precision for exact solutions).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from antenna_cad.synthesis.checks import DesignError

NEWTON_TOL = 1e-13
NEWTON_MAX_IT = 40


@dataclass(frozen=True)
class Focus:
    """A design focus (seed-001 (1.1)/(2.1)): input point ``point``; output point ``image`` or, for a
    plane-wave output, the output direction ``direction`` (unit vector)."""
    point: np.ndarray
    image: np.ndarray | None = None
    direction: np.ndarray | None = None

    def path(self, r1: np.ndarray, l: np.ndarray, r2: np.ndarray) -> np.ndarray:
        """Eikonal through every line: |F − r1| + l + |r2 − F'| (or − k·r2 for a plane wave)."""
        out = np.linalg.norm(r1 - self.point, axis=-1) + l
        if self.image is not None:
            return out + np.linalg.norm(r2 - self.image, axis=-1)
        return out - r2 @ self.direction


@dataclass(frozen=True)
class ConstrainedLens:
    """Lines i: entry point r1[i], exit point r2[i] (rows (x, y, z)), electrical length l[i]."""
    r1: np.ndarray
    r2: np.ndarray
    l: np.ndarray
    foci: tuple[Focus, ...]
    aperture: float                   # D (entry aperture), normalised units
    dimensions: int                   # 2 or 3
    branch: str                       # which solution family was taken, and why
    notes: tuple[str, ...] = field(default=())

    def residuals(self) -> np.ndarray:
        """Peak-to-peak eikonal spread per design focus (0 for a perfect focus)."""
        return np.array([np.ptp(f.path(self.r1, self.l, self.r2)) for f in self.foci])

    def shifted(self, dz: float) -> "ConstrainedLens":
        """The output half (exit surface and images) moved by dz along z: a lens of axial thickness dz
        with the same foci (seed-001 §1.1/§2.1; a plane wave's path changes by a per-focus constant)."""
        move = np.array([0.0, 0.0, dz])
        foci = tuple(Focus(f.point, None if f.image is None else f.image + move, f.direction) for f in self.foci)
        return ConstrainedLens(self.r1, self.r2 + move, self.l, foci, self.aperture, self.dimensions,
                               self.branch, self.notes)

    def take(self, mask) -> "ConstrainedLens":
        return ConstrainedLens(self.r1[mask], self.r2[mask], self.l[mask], self.foci, self.aperture,
                               self.dimensions, self.branch, self.notes)


def _pt(y, z, x=0.0) -> np.ndarray:
    return np.array([x, y, z], dtype=float)


def newton(fun, x0, field_name: str, what: str) -> np.ndarray:
    """Newton's method with a central-difference Jacobian; failure → DesignError naming the field."""
    x = np.asarray(x0, dtype=float)
    for _ in range(NEWTON_MAX_IT):
        r = np.asarray(fun(x), dtype=float)
        if not np.all(np.isfinite(r)):
            break
        if np.max(np.abs(r)) < NEWTON_TOL:
            return x
        h = 1e-7 * np.maximum(1.0, np.abs(x))
        jac = np.column_stack([(np.asarray(fun(x + e)) - np.asarray(fun(x - e))) / (2 * e[k])
                               for k, e in enumerate(np.diag(h))])
        try:
            step = np.linalg.solve(jac, r)
        except np.linalg.LinAlgError:
            break
        x = x - step
        if np.max(np.abs(step)) < 1e-15 * max(1.0, float(np.max(np.abs(x)))):
            r = np.asarray(fun(x), dtype=float)
            if np.max(np.abs(r)) < 1e-11:
                return x
    raise DesignError(field_name, f"Newton solution of {what} did not converge (no real solution "
                                  "for these foci; change this parameter)")


# --- §1.2/§1.3: two symmetry planes ------------------------------------------------------------

@dataclass(frozen=True)
class SymFocus:
    """F at distance f from the surface centre A = (0, −z0), angle ``angle`` (rad) from the axis."""
    f: float
    angle: float


def _pair_sum(s: SymFocus, y, z, z0):
    """Left side of (1.2)/(1.5): the two paths of the pair ±angle, minus 2f."""
    t = (s.f * np.cos(s.angle) + z0 - z) ** 2
    c = s.f * np.sin(s.angle)
    return np.sqrt(t + (c - y) ** 2) + np.sqrt(t + (c + y) ** 2) - 2 * s.f


def explicit_16(f1: SymFocus, f3: SymFocus, z0: float, dl):
    """(1.6): both roots (z_plus, z_minus) and y² for a line length l − l0 = dl (seed-001 §1.3)."""
    ca, cb = f1.f * np.cos(f1.angle), f3.f * np.cos(f3.angle)
    s1, s3 = 2 * f1.f - dl, 2 * f3.f - dl
    L = f1.f**2 * np.sin(f1.angle) ** 2 / s1**2 - f3.f**2 * np.sin(f3.angle) ** 2 / s3**2
    M = 4 * f1.f**2 * np.sin(f1.angle) ** 2 / s1**2 - 1
    P = (ca - cb) * M / (2 * L) - 2 * ca
    Q = f1.f**2 - s1**2 / 4 - (f1.f - f3.f) * dl * M / (4 * L)
    disc = np.sqrt(np.maximum(P**2 - 4 * Q, 0.0))
    zp, zm = z0 - (P + disc) / 2, z0 - (P - disc) / 2
    y2 = lambda z: (2 * (ca - cb) * (z0 - z) + (f1.f - f3.f) * dl) / (4 * L)   # noqa: E731
    return (zp, y2(zp)), (zm, y2(zm))


def two_planes_2d(foci: list[SymFocus], z0: float, aperture: float, y: np.ndarray,
                  law: str = "equal_length", n_w: float = 1.0) -> ConstrainedLens:
    """Seed-001 §1.2/§1.3 for the half-aperture points ``y ≥ 0`` (mirrored to −y). ``foci``: one
    (bifocal, with ``law``), or two (F1 at ±α — α = 0 for the trifocal lens — and F3 at ±β)."""
    y = np.asarray(y, dtype=float)
    z, dl = np.empty_like(y), np.empty_like(y)
    if len(foci) == 1:
        s = foci[0]
        if law == "flat":
            z[:] = z0
            dl[:] = -_pair_sum(s, y, z0, z0)
        else:
            k = 0.0 if law == "equal_length" else n_w
            for i, yi in enumerate(y):
                guess = z[i - 1] if i else z0
                (z[i],) = newton(lambda v: [_pair_sum(s, yi, v[0], z0) + k * 2 * (v[0] - z0)], [guess],
                                 "design.foci", f"(1.2) at y = {yi:g}")
            dl = k * 2 * (z - z0)
        branch = f"single solution of (1.2), design {law}"
    else:
        s1, s3 = foci
        prev = np.array([z0, 0.0])
        velocity = np.zeros(2)
        for i, yi in enumerate(y):
            sol = newton(lambda v: [_pair_sum(s1, yi, v[0], z0) + v[1], _pair_sum(s3, yi, v[0], z0) + v[1]],
                         prev + velocity, "design.foci", f"(1.5) at y = {yi:g}")
            velocity = (sol - prev) if i else np.zeros(2)
            prev = sol
            z[i], dl[i] = sol
        branch = _branch_16(s1, s3, z0, y, z, dl)
    full_y = np.concatenate([-y[::-1], y[y > 0] if y[0] == 0 else y])
    keep = slice(1, None) if y[0] == 0 else slice(None)
    full_z = np.concatenate([z[::-1], z[keep]])
    full_l = np.concatenate([dl[::-1], dl[keep]])
    r1 = np.column_stack([np.zeros(len(full_y)), full_y, -full_z])
    r2 = np.column_stack([np.zeros(len(full_y)), full_y, full_z])
    pts = []
    for s in foci:
        for sg in (1.0, -1.0):
            c, u = s.f * np.sin(s.angle) * sg, z0 + s.f * np.cos(s.angle)
            pts.append(Focus(_pt(c, -u), image=_pt(-c, u)))
            if s.angle == 0.0:
                break
    return ConstrainedLens(r1, r2, full_l, tuple(pts), aperture, 2, branch)


def _branch_16(s1, s3, z0, y, z, dl) -> str:
    """Which root of (1.6) each Newton point matches ("+"/"−"), and where l turns (seed-001 §1.3)."""
    signs = []
    for yi, zi, li in zip(y[1:], z[1:], dl[1:]):
        (zp, _), (zm, _) = explicit_16(s1, s3, z0, li)
        signs.append("+" if abs(zp - zi) <= abs(zm - zi) else "−")
    turn = np.flatnonzero(np.diff(dl) < 0)
    where = f"; l turns at y ≈ {y[turn[0]]:.4g} (l − l0 = {dl[turn[0]]:.4g})" if turn.size else ""
    runs = [signs[0]] + [b for a, b in zip(signs, signs[1:]) if a != b] if signs else []
    return ("Newton in y from the centre (z0, l0); explicit (1.6) root " + " then ".join(f"'{r}'" for r in runs)
            + where)


# --- §1.5: equal-line-length trifocal lens, plane-wave output --------------------------------

@dataclass(frozen=True)
class Trifocal15:
    f: float          # central focal distance (from the entry vertex)
    f1: float         # side focal distance
    alpha: float      # side focus angle (rad)
    d: float          # axial thickness

    def z1_roots(self, z2):
        """(1.23)–(1.24): both roots z1 for exit abscissa z2 (NaN where complex)."""
        f, f1, a, d = self.f, self.f1, self.alpha, self.d
        W = f1 + (z2 - d / 2) * np.cos(a)
        k = f1**2 * np.sin(a) ** 2 / W**2
        g = (f + z2 - d / 2) ** 2
        A, B = k, 2 * f1 * np.cos(a) - 2 * f * (1 - k)
        C = f1**2 - f**2 + g - W**2 + k * (f**2 - g)
        disc = B**2 - 4 * A * C
        root = np.sqrt(np.where(disc >= 0, disc, np.nan))
        return -d / 2 + (-B + root) / (2 * A), -d / 2 + (-B - root) / (2 * A)

    def family(self, s, direction: float):
        """The family through the axis point: z2 = d/2 + direction·s, the z1 root that is −d/2 at s = 0.
        Returns (y1, z1, y2, z2)."""
        z2 = self.d / 2 + direction * np.asarray(s, dtype=float)
        zp, zm = self.z1_roots(z2)
        zp0, _ = self.z1_roots(self.d / 2)
        z1 = zp if abs(zp0 + self.d / 2) < 1e-12 else zm
        y1 = np.sqrt((self.f + z2 - self.d / 2) ** 2 - (self.f + z1 + self.d / 2) ** 2)   # (1.21)
        y2 = self.f1 * y1 / (self.f1 + (z2 - self.d / 2) * np.cos(self.alpha))         # (1.22)
        return y1, z1, y2, z2

    def foci(self) -> tuple[Focus, ...]:
        f, f1, a, d = self.f, self.f1, self.alpha, self.d
        return (Focus(_pt(0.0, -d / 2 - f), direction=_pt(0.0, 1.0)),
                Focus(_pt(-f1 * np.sin(a), -d / 2 - f1 * np.cos(a)), direction=_pt(np.sin(a), np.cos(a))),
                Focus(_pt(f1 * np.sin(a), -d / 2 - f1 * np.cos(a)), direction=_pt(-np.sin(a), np.cos(a))))


def plane_wave_trifocal_2d(t: Trifocal15, aperture: float, y2: np.ndarray, direction: float) -> ConstrainedLens:
    """Seed-001 §1.5 lens on the family ``direction`` (+1: z2 increasing away from the axis, −1:
    decreasing) at the exit ordinates ``y2 ≥ 0`` (mirrored). The aperture D of a plane-wave lens is
    its radiating (exit) aperture, |y2| ≤ D/2 (the seed does not say; the entry aperture is smaller).
    Raises DesignError if that family does not reach the aperture edge with y2 increasing."""
    half = aperture / 2
    ys = lambda s: t.family(s, direction)[2]     # noqa: E731
    grid = np.linspace(0.0, 4 * t.d + aperture, 4001)
    y_grid = ys(grid)
    reach = np.flatnonzero(np.isfinite(y_grid) & (y_grid >= half))
    if reach.size == 0 or not np.all(np.diff(y_grid[: reach[0] + 1]) > 0):
        raise DesignError("design.foci", f"the §1.5 family with z2 {'in' if direction > 0 else 'de'}creasing "
                                         "does not reach the aperture edge monotonically")
    s_edge = brentq(lambda s: ys(s) - half, 0.0, grid[reach[0]], xtol=1e-15)
    s = np.array([0.0 if v <= 0 else s_edge if v >= half else brentq(lambda q: ys(q) - v, 0.0, s_edge, xtol=1e-15)
                  for v in y2])
    Y1, Z1, Y2, Z2 = t.family(s, direction)
    sign = np.concatenate([-np.ones(len(s)), np.ones(len(s))])
    order = np.concatenate([np.arange(len(s))[::-1], np.arange(len(s))])
    keep = ~((sign < 0) & (np.asarray(y2)[order] == 0))
    r1 = np.column_stack([np.zeros(len(sign)), sign * Y1[order], Z1[order]])[keep]
    r2 = np.column_stack([np.zeros(len(sign)), sign * Y2[order], Z2[order]])[keep]
    branch = f"(1.24) family with z2 {'increasing' if direction > 0 else 'decreasing'} away from the axis"
    return ConstrainedLens(r1, r2, np.zeros(len(r1)), t.foci(), aperture, 2, branch)


# --- §2.4: five foci, one symmetry plane, plane-wave output ------------------------------------

@dataclass(frozen=True)
class FiveFocal:
    """Seed-001 §2.4 foci: F1/F2 (f1, α, γ = φ, π − φ), F3/F4 (f3, β, ξ, π − ξ), F5 (f5, ψ, π/2);
    angles in radians; γ from Oy (F = f (sinθ sinγ, sinθ cosγ, −cosθ))."""
    f1: float
    f3: float
    f5: float
    alpha: float
    beta: float
    phi: float
    xi: float
    psi: float

    def angles(self):
        a, b, p, q = self.alpha, self.beta, self.phi, self.xi
        return ((self.f1, a, p), (self.f1, a, np.pi - p), (self.f3, b, q), (self.f3, b, np.pi - q),
                (self.f5, self.psi, np.pi / 2))

    def foci(self) -> tuple[Focus, ...]:
        out = []
        for f, th, g in self.angles():
            u = np.array([np.sin(th) * np.sin(g), np.sin(th) * np.cos(g), -np.cos(th)])
            out.append(Focus(f * u, direction=-u))
        return tuple(out)

    def solve(self, x1, y2):
        """(2.49) → (2.47) corrected → 3×3 linear system. Returns r1, r2 (N×3) and l; NaN rows where
        the quadratic (2.48) has no real root."""
        f1, f3, f5, a, b = self.f1, self.f3, self.f5, self.alpha, self.beta
        x1, y2 = np.broadcast_arrays(np.asarray(x1, float), np.asarray(y2, float))
        sa, sb = np.sin(a) * np.sin(self.phi), np.sin(b) * np.sin(self.xi)
        z1, rho = self._entry(x1, y2)
        y1 = rho * y2
        F5 = f5 * np.array([np.sin(self.psi), 0.0, -np.cos(self.psi)])
        R5 = np.sqrt((x1 - F5[0]) ** 2 + y1**2 + (z1 - F5[2]) ** 2)
        # rows: −l + z2 cosθ − x2 s = rhs   (unknowns x2, z2, l)
        mat = np.array([[-sa, np.cos(a), -1.0], [-sb, np.cos(b), -1.0], [-np.sin(self.psi), np.cos(self.psi), -1.0]])
        rhs = np.stack([f1 * rho - f1, f3 * rho - f3, R5 - f5], axis=-1)
        sol = np.linalg.solve(mat, rhs[..., None])[..., 0]
        r1 = np.stack([x1, y1, z1], axis=-1)
        r2 = np.stack([sol[..., 0], y2, sol[..., 1]], axis=-1)
        return r1, r2, sol[..., 2]

    def _entry(self, x1: np.ndarray, y2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(z1, ρ) of the entry point for (x1, y2): (2.49), the root '+', then (2.47) corrected (y1 = ρ·y2)."""
        f1, f3, a, b = self.f1, self.f3, self.alpha, self.beta
        sa, sb = np.sin(a) * np.sin(self.phi), np.sin(b) * np.sin(self.xi)
        den = f1**2 - f3**2
        A1 = -2 * (f1 * sa - f3 * sb) / den
        B1 = 2 * (f1 * np.cos(a) - f3 * np.cos(b)) / den
        C1 = -(np.sin(a) ** 2 * np.cos(self.phi) ** 2 - np.sin(b) ** 2 * np.cos(self.xi) ** 2) / den
        M1 = 2 * f1 * np.cos(a) + B1 * (y2**2 - f1**2)
        N1 = (f1**2 + x1**2 - 2 * x1 * f1 * sa - y2**2 * np.sin(a) ** 2 * np.cos(self.phi) ** 2
              + (y2**2 - f1**2) * (1 + A1 * x1 + C1 * y2**2))
        disc = M1**2 - 4 * N1
        z1 = -M1 / 2 + np.sqrt(np.where(disc >= 0, disc, np.nan)) / 2
        rho2 = 1 + A1 * x1 + B1 * z1 + C1 * y2**2
        return z1, np.sqrt(np.where(rho2 >= 0, rho2, np.nan))

    def y2_for(self, x1: np.ndarray, y1: np.ndarray) -> np.ndarray:
        """Invert y1(x1, y2) = ρ·y2 (monotone in y2) at every point: the bracket [0, ±h] grown by 1.25
        from h = |y1| until y1 is passed, then bisection to the last bit; DesignError naming the first
        point whose y1 is not reached."""
        x1, y1 = np.asarray(x1, float), np.asarray(y1, float)
        g = lambda v: self._entry(x1, v)[1] * v - y1       # noqa: E731
        s = np.sign(y1)
        hi = np.abs(y1)
        found, lost = y1 == 0, np.zeros(y1.shape, bool)
        with np.errstate(invalid="ignore"):
            for _ in range(60):
                gv = g(s * hi)
                found |= np.isfinite(gv) & (np.sign(gv) == s)
                if found.all():
                    break
                hi = np.where(found, hi, hi * 1.25)
                lost = ~found & ~np.isfinite(g(s * hi))
                if lost.any():
                    break
            if not found.all():
                i = int(np.flatnonzero(lost if lost.any() else ~found)[0])
                raise DesignError("design.aperture", f"the five-focal solution (2.47)–(2.49) has no real point "
                                  f"at x1 = {x1[i]:.4g}, y1 = {y1[i]:.4g} (aperture too large for these foci)")
            lo, hi = np.zeros_like(y1), s * hi           # g(lo) has the sign −s, g(hi) the sign s
            for _ in range(1100):
                mid = lo + (hi - lo) / 2
                if np.all((mid == lo) | (mid == hi)):
                    break
                up = np.sign(g(mid)) == s
                hi, lo = np.where(up, mid, hi), np.where(up, lo, mid)
        return np.where(y1 == 0, 0.0, hi)


def five_focal_3d(ff: FiveFocal, aperture: float, xy1: np.ndarray) -> ConstrainedLens:
    """Seed-001 §2.4 lens at entry points (x1, y1) (rows of ``xy1``)."""
    y2 = ff.y2_for(xy1[:, 0], xy1[:, 1])
    r1, r2, l = ff.solve(xy1[:, 0], y2)
    if not np.all(np.isfinite(l)):
        raise DesignError("design.aperture", "the five-focal solution is complex inside the aperture")
    return ConstrainedLens(r1, r2, l, ff.foci(), aperture, 3,
                           "explicit (2.49) root '+' (through the centre, z1 = 0 at x1 = y2 = 0), "
                           "(2.47) with the corrected C1, 3×3 linear solve for (x2, z2, l)")
