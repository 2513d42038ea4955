"""The mirror-lens design value (seed-004): exact profiles, series, astigmatism, σ against the field
angle, the closed meridional section of the body in mm, and the physics checks.

Frame (seed-004 §1): feed (focus) at the origin, +z into the body, the beam leaves toward −z.
Synthesis runs in units of D (:mod:`antenna_cad.synthesis.aplanatic`); ``section_mm`` and the
figures are scaled to the aperture diameter in mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from antenna_cad.raytrace.mirror_lens import Body, FieldScan, body_from_profiles, field_scan, trace
from antenna_cad.synthesis.aplanatic import (TARGET_RADII, Optimum, Profiles, SeriesCoefficients, astigmatism_exact,
                                             astigmatism_series, feed_on_surface_series, optimize_target,
                                             series_coefficients, synthesize_profiles)
from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.collimator import wavelength_mm

FIELD_STEPS = 9                     # field angles of the σ study, 0 … field_half_angle
CHECK_RAYS = 400
EXACT_LIMIT = 1e-9                  # units of D (or rad): the synthesis against a forward trace
AXIS_LIMIT = {False: 1e-6, True: 1e-5}     # |exact − series| near the axis (§7.3 item 3), f0 > 0 / f0 = 0


@dataclass(frozen=True)
class MirrorLensDesign:
    diameter_mm: float
    frequency_ghz: float
    profiles: Profiles
    series: SeriesCoefficients | None       # f0 > 0
    R2R4: tuple[float, float] | None        # feed on the surface
    optimum: Optimum | None
    scan: FieldScan
    checks: tuple[Check, ...]

    @property
    def n(self) -> float:
        return self.profiles.n

    @property
    def wavelength_mm(self) -> float:
        return wavelength_mm(self.frequency_ghz)

    @property
    def feed_half_angle_rad(self) -> float:
        """Illumination half-angle asin(r_ap/γ) (in the dielectric for a feed on the surface)."""
        return math.asin(0.5 / self.profiles.gamma)

    def body(self, tan_delta: float = 0.0) -> Body:
        return body_from_profiles(self.profiles, tan_delta)

    def front_series(self, r: np.ndarray) -> np.ndarray:
        """Truncated series of the front face (units of D): f0 + f2 r² + f4 r⁴; for the feed on the
        surface the lens points of the R2/R4 mirror series (§2.4, L221–225) at the same exit radii."""
        if self.series is not None:
            return self.series.front(r)
        p, (R2, R4) = self.profiles, self.R2R4
        a = np.arcsin(np.asarray(r) / p.gamma)
        rr, dr = p.d0 + R2 * a**2 + R4 * a**4, 2 * R2 * a + 4 * R4 * a**3
        mu = 2 * np.arctan(dr / rr) - a
        t = (2 * p.n * p.d0 - rr * (p.n + np.cos(a))) / (p.n - np.cos(mu))
        return rr * np.cos(a) - t * np.cos(mu)

    def mirror_series(self, R: np.ndarray) -> np.ndarray:
        """Truncated mirror series Z(R) (units of D); for the feed on the surface the polar series
        r(α) = d0 + R2 α² + R4 α⁴ at the polar angle of R on the exact mirror."""
        if self.series is not None:
            return self.series.mirror(R)
        p, (R2, R4) = self.profiles, self.R2R4
        a = np.interp(R, p.R_b, p.alpha)
        return (p.d0 + R2 * a**2 + R4 * a**4) * np.cos(a)

    def face_samples_mm(self, face: str, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(r, z, dz/dr) of ``count`` cosine-spaced samples (denser at axis and rim) of the front face
        or the mirror, in mm: what the CAD splines interpolate and the as-built trace re-reads."""
        p, D = self.profiles, self.diameter_mm
        r, z, dz = (p.s, p.f, p.df) if face == "front" else (p.R_b, p.Z_b, p.dF)
        u = (1 - np.cos(np.linspace(0.0, np.pi, count))) / 2
        k = np.unique(np.searchsorted(r, r[0] + u * (r[-1] - r[0])).clip(0, len(r) - 1))
        return r[k] * D, z[k] * D, dz[k]

    def section_mm(self) -> np.ndarray:
        """Closed meridional section of the body (r ≥ 0, z) in mm: axis → front face → side wall →
        mirror → axis (the last point repeats the first)."""
        p, D = self.profiles, self.diameter_mm
        front = np.stack([p.s, p.f], -1)
        mirror = np.stack([p.R_b, p.Z_b], -1)[::-1]
        return np.concatenate([front, mirror, front[:1]]) * D

    @property
    def z_range_mm(self) -> tuple[float, float]:
        p = self.profiles
        lo, hi = min(p.f.min(), p.Z_b.min()), max(p.f.max(), p.Z_b.max())
        return float(lo) * self.diameter_mm, float(hi) * self.diameter_mm

    @property
    def body_radius_mm(self) -> float:
        return float(max(self.profiles.s[-1], self.profiles.R_b[-1])) * self.diameter_mm

    def volume_mm3(self) -> float:
        """Pappus: 2π × (section area × centroid radius), the dense marched polygon (exact to ~h²)."""
        r, z = self.section_mm().T
        cross = r[:-1] * z[1:] - r[1:] * z[:-1]
        return float(abs(np.sum((r[:-1] + r[1:]) * cross)) / 6 * 2 * math.pi)

    def mirror_area_mm2(self) -> float:
        """Area of the metallised back face, 2π ∫ R √(1 + F′²) dR."""
        p = self.profiles
        g = p.R_b * np.sqrt(1 + p.dF**2)
        return float(2 * math.pi * np.sum((g[1:] + g[:-1]) / 2 * np.diff(p.R_b))) * self.diameter_mm**2

    def max_radius_in_mm(self, z_lo: float, z_hi: float) -> float:
        """Largest body radius with z in [z_lo, z_hi] (mm): on the section's boundary, including
        where its edges cross the two planes."""
        ring = self.section_mm()
        r, z = ring.T
        best = r[(z >= z_lo) & (z <= z_hi)].tolist()
        for plane in (z_lo, z_hi):
            a, b = z[:-1] - plane, z[1:] - plane
            k = np.nonzero(a * b < 0)[0]
            best += (r[k] + (r[k + 1] - r[k]) * a[k] / (a[k] - b[k])).tolist()
        return float(max(best)) if best else 0.0

    def rim_difference(self) -> tuple[float, float]:
        """Exact minus truncated series at the rim (units of D): front at r = 0.5, mirror at R_B(rim)."""
        p = self.profiles
        return (float(p.f[-1] - self.front_series(p.s[-1])), float(p.Z_b[-1] - self.mirror_series(p.R_b[-1])))


def _synthesis_checks(p: Profiles, design: MirrorLensDesign) -> list[Check]:
    """Forward 3-D trace of the synthesized surfaces (seed-004 §7.3 item 1) and the series near the axis."""
    a = np.arcsin(np.linspace(1e-3, 0.999 * p.s[-1], CHECK_RAYS) / p.gamma)
    ray = trace(design.body(), (0.0, 0.0, 0.0), np.stack([np.sin(a), 0 * a, np.cos(a)], -1))
    if not ray.ok.all():
        raise DesignError("design.gamma", "the synthesized surfaces lose rays inside the aperture "
                          f"({int((~ray.ok).sum())} of {CHECK_RAYS}); change gamma or d0")
    direction = float(np.max(np.hypot(ray.exit_dir[:, 0], ray.exit_dir[:, 1])))     # sin of the angle to −z
    path = float(np.max(np.abs(ray.opl + ray.exit_point[:, 2] - p.L0)))
    sine = float(np.max(np.abs(ray.exit_point[:, 0] - p.gamma * np.sin(a))))
    near = p.s <= 0.1
    axis = float(np.max(np.abs(p.f[near] - design.front_series(p.s[near]))))
    series = Check("series_near_axis", "pass" if axis <= AXIS_LIMIT[p.feed_on_surface] else "warn", axis,
                   AXIS_LIMIT[p.feed_on_surface], "D", f"front face, exact − truncated series for r ≤ 0.1 D: {axis:.3g} D "
                   "(seed-004 §7.3 item 3; a warning: the series is for seeding and checks only, the body is exact)")
    return [Check.upper("exit_direction_error", direction, EXACT_LIMIT, "rad",
                        "forward trace: exit ray against −z (seed-004 §2.2)"),
            Check.upper("path_length_error", path, EXACT_LIMIT, "D", "forward trace: eikonal against L0"),
            Check.upper("sine_condition_error", sine, EXACT_LIMIT, "D", "forward trace: r_C − γ sin α, eq. (1)"),
            series]


def synthesize_mirror_lens(*, diameter_mm: float, frequency_ghz: float, n: float, f0: float, d0: float,
                           gamma: float | None, optimize: dict | None = None,
                           field_half_angle_deg: float = 20.0) -> MirrorLensDesign:
    """Exact body (seed-004 §2.2 / §2.4), its series, an optional γ from the target A (21), and the
    σ study over the field; raises DesignError naming the parameter to change."""
    optimum = None
    if optimize is not None:
        if f0 == 0.0:
            raise DesignError("design.optimize", "the target A (21) optimisation is defined for f0 > 0; "
                              "give gamma for feed_on_surface (seed-004 §3.5: (21) does not give γ = 0.572)")
        lo, hi = optimize["gamma_min"], optimize["gamma_max"]
        free = ("f0", "gamma") if optimize.get("free_f0") else ("gamma",)
        bounds = {"gamma": (lo, hi), "f0": (optimize.get("f0_min", 0.05), optimize.get("f0_max", 0.95))}
        optimum = optimize_target(n, f0, d0, 0.5 * (lo + hi), free=free, mode=optimize["mode"], bounds=bounds)
        f0, d0, gamma = float(optimum.f0), float(optimum.d0), float(optimum.gamma)
    p = synthesize_profiles(n, f0, d0, gamma)
    if p.Z_b[-1] <= p.f[-1]:
        raise DesignError("design.d0", f"the mirror rim (z {p.Z_b[-1]:.4f} D) is not behind the front rim "
                          f"(z {p.f[-1]:.4f} D): the body closes on itself; increase d0")
    series = series_coefficients(n, f0, d0, gamma) if f0 > 0 else None
    R2R4 = feed_on_surface_series(n, d0, gamma) if f0 == 0 else None
    angles = np.linspace(0.0, field_half_angle_deg, FIELD_STEPS)
    body = body_from_profiles(p)
    try:
        scan = field_scan(body, angles)
    except ValueError as exc:
        raise DesignError("design.field_half_angle_deg", f"{exc}; reduce the field angle") from None
    design = MirrorLensDesign(diameter_mm, frequency_ghz, p, series, R2R4, optimum, scan, ())
    return MirrorLensDesign(diameter_mm, frequency_ghz, p, series, R2R4, optimum, scan,
                            tuple(_synthesis_checks(p, design)))


def astigmatism_rows(design: MirrorLensDesign, radii=(0.15, 0.25, 0.35, 0.45)) -> list[tuple]:
    """(r, L_X, L_Y exact, L_X, L_Y series (19) or None) — units of D."""
    lx, ly = astigmatism_exact(design.profiles, radii)
    if design.series is not None:
        sx, sy = astigmatism_series(design.series, radii)
    else:
        sx = sy = [None] * len(radii)
    return [(r, a, b, c, d) for r, a, b, c, d in zip(radii, lx, ly, sx, sy)]


def target_value(design: MirrorLensDesign) -> float:
    """A of eq. (21) on the exact geometry."""
    lx, ly = astigmatism_exact(design.profiles, TARGET_RADII)
    return float(np.sum(np.abs(lx - ly)))
