"""Single-surface dielectric lens collimator: hyperbolic illuminated face, flat shadow face.

Source: seed-000 (Nikulina 2021), digest ``reference/seed-000.md``.

Frame (DESIGN.md): +Z is the optical axis from the feed toward the antenna under test; the feed
(focus) is at z = −f, the lens vertex at z = 0, the flat shadow face at z = d. ``r`` is the
distance from the axis. All lengths are millimetres, angles radians unless the name says ``_deg``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.synthesis.checks import Check, DesignError

C0_MM_GHZ = 299.792458  # speed of light: λ0[mm] = C0_MM_GHZ / f[GHz]
TIR_WARN_MARGIN_DEG = 5.0


def wavelength_mm(frequency_ghz: float) -> float:
    return C0_MM_GHZ / frequency_ghz


def thickness_mm(diameter_mm: float, focal_length_mm: float, n: float) -> float:
    """Lens thickness d, seed-000 §2.1 eq. (1.1): sqrt(f²/(n+1)² + D²/(4(n²−1))) − f/(n+1)."""
    f, D = focal_length_mm, diameter_mm
    return float(np.sqrt(f**2 / (n + 1) ** 2 + D**2 / (4 * (n**2 - 1))) - f / (n + 1))


def profile_radius_mm(z_mm, focal_length_mm: float, n: float):
    """Profile r(z) of the illuminated face, seed-000 §2.1 eq. (1.9) corrected:
    r² = (n²−1)·z² + 2·(n−1)·f·z (the printed form drops the factor z)."""
    z = np.asarray(z_mm, dtype=float)
    return np.sqrt(np.maximum((n**2 - 1) * z**2 + 2 * (n - 1) * focal_length_mm * z, 0.0))


def profile_z_mm(r_mm, focal_length_mm: float, n: float):
    """Inverse profile z(r) = [−(n−1)f + sqrt((n−1)²f² + (n²−1)r²)]/(n²−1), seed-000 §2.1."""
    r = np.asarray(r_mm, dtype=float)
    f = focal_length_mm
    return (-(n - 1) * f + np.sqrt((n - 1) ** 2 * f**2 + (n**2 - 1) * r**2)) / (n**2 - 1)


def hyperbola_axes_mm(focal_length_mm: float, n: float) -> tuple[float, float, float]:
    """The profile as a conic: centre z_c = −f/(n+1), semi-axes A = f/(n+1) (along z) and
    B = A·sqrt(n²−1); (z − z_c)²/A² − r²/B² = 1 with the vertex branch at z = 0."""
    a = focal_length_mm / (n + 1)
    return -a, a, a * float(np.sqrt(n**2 - 1))


def surface_normal(z_mm, r_mm, focal_length_mm: float, n: float) -> np.ndarray:
    """Unit normals (z, r components) of the illuminated face, pointing into the lens (+z side)."""
    z = np.asarray(z_mm, dtype=float)
    r = np.asarray(r_mm, dtype=float)
    gz = 2 * (n**2 - 1) * z + 2 * (n - 1) * focal_length_mm
    nrm = np.stack([gz, -2 * r], axis=-1)
    return nrm / np.linalg.norm(nrm, axis=-1, keepdims=True)


def fermat_residual_mm(r_mm, focal_length_mm: float, n: float, d_mm: float):
    """Optical path from the focus to the flat face minus its axial value (ideally 0), §2.1:
    sqrt((f+z)²+r²) + n·(d−z) − (f + n·d)."""
    r = np.asarray(r_mm, dtype=float)
    z = profile_z_mm(r, focal_length_mm, n)
    f = focal_length_mm
    return np.hypot(f + z, r) + n * (d_mm - z) - (f + n * d_mm)


def thickness_tolerance_mm(n: float, wavelength: float, phase_budget_rad: float) -> float:
    """Machining tolerance |Δd| ≤ (ΔΦ/(4π))·λ0/(n−1), seed-000 §2.2 eq. (1.2)."""
    return phase_budget_rad / (4 * np.pi) * wavelength / (n - 1)


def dissipative_loss_db(n: float, tan_delta: float, d_mm: float, wavelength: float) -> float:
    """Body loss η = 27.3·n·tanδ·l_cp/λ0 with l_cp ≈ d/2, seed-000 §2.2 eq. (1.3)."""
    return 27.3 * n * tan_delta * (d_mm / 2) / wavelength


LOSS_LIMIT_DB = 3.0        # half the power absorbed: no lens, whatever the budget
LOSS_WARN_DB = 1.0


def loss_check(loss_db: float) -> Check:
    """Dissipative loss through the lens centre, seed-000 §2.2 eq. (1.3): a warning above 1 dB,
    a failure above 3 dB (a foam lens loses ~0.01–0.1 dB; a large tanδ is a typing error or the
    wrong material)."""
    return Check.upper("dissipative_loss", loss_db, LOSS_LIMIT_DB, "dB",
                       "dielectric loss through the lens centre (1.3)", warn_margin=LOSS_LIMIT_DB - LOSS_WARN_DB)


def reflection_loss_db(n: float) -> float:
    """Total reflection loss A ≈ 8.69·((n−1)/(n+1))², seed-000 §2.2 eq. (1.4)."""
    return 8.69 * ((n - 1) / (n + 1)) ** 2


def index_tolerance(wavelength: float, d_mm: float, phase_budget_rad: float) -> float:
    """Index tolerance |Δn| = (ΔΦ/(4π))·λ0/d, seed-000 §2.2 eq. (1.5)."""
    return phase_budget_rad / (4 * np.pi) * wavelength / d_mm


def permittivity_tolerance_pct(n: float, delta_n: float) -> tuple[float, float]:
    """(+Δε%, −Δε%) from (n±Δn)², seed-000 §2.2 eq. (1.6) as corrected in the digest
    (the printed ±Δε = |Δn|² does not reproduce Tables 1.3/1.4)."""
    eps = n**2
    return ((n + delta_n) ** 2 - eps) / eps * 100, (eps - (n - delta_n) ** 2) / eps * 100


def scan_limit_deg(wavelength: float, diameter_mm: float, focal_length_mm: float, n: float,
                   d_mm: float) -> float:
    """Max beam deflection for a π/2 cubic phase error, θ ≈ (λ0/D)·(f + n·d)/(2·n·d) rad,
    seed-000 §2.2 eq. (1.8). Values above 90° are outside the formula's validity."""
    return float(np.degrees(wavelength / diameter_mm * (focal_length_mm + n * d_mm) / (2 * n * d_mm)))


def path_difference_mm(diameter_mm: float, focal_length_mm: float) -> float:
    """Path difference Δl the lens corrects (edge vs centre ray from the focus), seed-000 §4.3
    (2.14): Δl·sqrt(1 + 2f/Δl) = D/2, i.e. Δl = sqrt(f² + D²/4) − f."""
    f = focal_length_mm
    return float(np.sqrt(f * f + diameter_mm**2 / 4) - f)


def path_difference_approx_mm(diameter_mm: float, focal_length_mm: float) -> float:
    """Δl ≈ D²/(8f), seed-000 §4.3 (2.15)."""
    return diameter_mm**2 / (8 * focal_length_mm)


def diameter_for_path_difference_mm(path_difference_mm: float, focal_length_mm: float) -> float:
    """D = 2·sqrt(Δl² + 2fΔl), (2.14) solved for D (the rows of seed-000 Tables 2.1–2.4)."""
    dl = path_difference_mm
    return float(2 * np.sqrt(dl * dl + 2 * focal_length_mm * dl))


def far_field_distance_mm(diameter_mm: float, wavelength: float) -> float:
    """Far-field distance 2D²/λ the collimator replaces, seed-000 §0 (L66)."""
    return 2 * diameter_mm**2 / wavelength


def rim_incidence_deg(diameter_mm: float, focal_length_mm: float, n: float, d_mm: float) -> float:
    """Angle of incidence at the rim (d, D/2) for a feed at the focus, seed-000 §2.1 eq. (2.24)."""
    f = focal_length_mm
    t1 = np.sqrt((n**2 - 1) * d_mm**2 + 2 * f * d_mm * (n - 1)) / (d_mm * (n**2 - 1) + f * (n - 1))
    t2 = (diameter_mm / 2) / (d_mm + f)
    return float(abs(np.degrees(np.arctan((t1 + t2) / (t1 * t2 - 1)))))


def rim_reachable(diameter_mm: float, focal_length_mm: float, n: float, d_mm: float) -> bool:
    """Whether the feed sees the rim (d, D/2) from outside the lens: the ray from the focus meets the
    face there on its feed side (direction · inward normal > 0), not after passing through the lens."""
    u = np.array([d_mm + focal_length_mm, diameter_mm / 2])
    return float(u @ surface_normal(d_mm, diameter_mm / 2, focal_length_mm, n)) > 0.0


def internal_rim_angle_deg(rim_incidence: float, n: float) -> float:
    """Refraction angle inside the lens at the rim, arcsin(sin θi / n): always below the critical angle
    arcsin(1/n), so the front face cannot totally reflect (the hyperbolic face then sends the ray
    along the axis to the flat face at normal incidence)."""
    return float(np.degrees(np.arcsin(np.sin(np.radians(rim_incidence)) / n)))


def rim_reflection_loss_db(rim_incidence: float, n: float) -> float:
    """Fresnel reflection loss of the rim ray at the front face, −10·log10(1 − |r⊥|²) (the
    perpendicular polarization, the larger)."""
    ci = np.cos(np.radians(rim_incidence))
    ct = np.sqrt(1.0 - (np.sin(np.radians(rim_incidence)) / n) ** 2)
    r = (ci - n * ct) / (ci + n * ct)
    return float(-10 * np.log10(1.0 - r * r))


def tir_angle_deg(n: float) -> float:
    """Critical angle arcsin(1/n) at the dielectric→air face, seed-000 §2.1 eq. (2.23)
    (the text calls it a Brewster angle: it is the TIR angle)."""
    return float(np.degrees(np.arcsin(1 / n)))


def edge_margin_mm(wavelength: float, antenna_distance_mm: float, c1: float = 0.5) -> float:
    """GO validity margin at the rim g = 2λ·sqrt(c1² + 2·c1·l_ant/λ), seed-000 §4.6 eq. (2.1)."""
    return 2 * wavelength * float(np.sqrt(c1**2 + 2 * c1 * antenna_distance_mm / wavelength))


def step_phase_error_deg(n: float, step_mm: float, wavelength: float) -> float:
    """Peak-to-peak phase error of unsanded stair steps k0·(n−1)·Δd, seed-000 §7.3 [OURS]."""
    return float(np.degrees(2 * np.pi / wavelength * (n - 1) * step_mm))


def lens_volume_mm3(focal_length_mm: float, n: float, d_mm: float) -> float:
    """Volume of the lens {r ≤ r(z), 0 ≤ z ≤ d}: V = π·[(n²−1)d³/3 + (n−1)·f·d²], seed-000 §7.3."""
    return float(np.pi * ((n**2 - 1) * d_mm**3 / 3 + (n - 1) * focal_length_mm * d_mm**2))


@dataclass(frozen=True)
class CollimatorDesign:
    """Synthesized single-surface collimator with its derived figures and checks (seed-000)."""
    diameter_mm: float
    focal_length_mm: float
    eps_r: float
    tan_delta: float
    frequency_ghz: float
    phase_error_budget_deg: float
    thickness_mm: float
    wavelength_mm: float
    thickness_tolerance_mm: float
    index_tolerance: float
    permittivity_tolerance_pct: tuple[float, float]
    dissipative_loss_db: float
    reflection_loss_db: float
    far_field_distance_mm: float
    scan_limit_deg: float
    rim_incidence_deg: float
    tir_angle_deg: float
    volume_mm3: float
    checks: tuple[Check, ...]

    @property
    def n(self) -> float:
        return self.eps_r ** 0.5

    def radius_at(self, z_mm):
        """Lens radius at axial position z (D/2 beyond the hyperbolic part, 0 before the vertex)."""
        z = np.clip(np.asarray(z_mm, dtype=float), 0.0, self.thickness_mm)
        return np.minimum(profile_radius_mm(z, self.focal_length_mm, self.n), self.diameter_mm / 2)

    def key_figures(self) -> dict[str, float]:
        return {k: float(v) for k, v in {
            "thickness_mm": self.thickness_mm,
            "wavelength_mm": self.wavelength_mm,
            "thickness_tolerance_mm": self.thickness_tolerance_mm,
            "permittivity_tolerance_plus_pct": self.permittivity_tolerance_pct[0],
            "permittivity_tolerance_minus_pct": self.permittivity_tolerance_pct[1],
            "dissipative_loss_db": self.dissipative_loss_db,
            "reflection_loss_db": self.reflection_loss_db,
            "far_field_distance_mm": self.far_field_distance_mm,
            "scan_limit_deg": self.scan_limit_deg,
            "rim_incidence_deg": self.rim_incidence_deg,
            "tir_angle_deg": self.tir_angle_deg,
            "lens_volume_mm3": self.volume_mm3,
        }.items()}


def _rim_check(rim: float, tir: float, n: float) -> Check:
    """Grazing incidence at the rim: a warning within TIR_WARN_MARGIN_DEG of the seed's critical angle
    (2.23) and beyond it, with the reflection loss; the internal angle shows there is no TIR."""
    status = "warn" if rim > tir - TIR_WARN_MARGIN_DEG else "pass"
    return Check("rim_incidence_vs_tir", status, rim, tir, "deg",
                 f"rim incidence (2.24): {rim:.2f}° vs critical {tir:.2f}° (2.23); inside the lens "
                 f"{internal_rim_angle_deg(rim, n):.2f}° (no total reflection); rim reflection loss "
                 f"{rim_reflection_loss_db(rim, n):.2f} dB" + ("; grazing incidence" if rim >= tir else ""))


def synthesize_collimator(*, diameter_mm: float, focal_length_mm: float, eps_r: float,
                          tan_delta: float, frequency_ghz: float,
                          phase_error_budget_deg: float = 22.5,
                          antenna_aperture_mm: float | None = None,
                          antenna_distance_mm: float | None = None) -> CollimatorDesign:
    """Synthesize the lens of seed-000 §2.1 and evaluate §2.2 figures and §7.3 checks.

    Raises DesignError when the feed cannot reach the rim (the face there turns away from it). A rim
    incidence (2.24) beyond the seed's critical angle (2.23) is grazing, not total reflection: the
    internal angle stays below it; it is a warning with the rim ray's reflection loss. An antenna
    under test larger than the lens minus the GO edge margin (2.1) is a warning.
    """
    if eps_r <= 1.0:
        raise DesignError("material.eps_r", f"a decelerating lens needs εr > 1 (got {eps_r})")
    n = eps_r ** 0.5
    lam = wavelength_mm(frequency_ghz)
    budget = np.radians(phase_error_budget_deg)
    d = thickness_mm(diameter_mm, focal_length_mm, n)
    dn = index_tolerance(lam, d, budget)
    rim = rim_incidence_deg(diameter_mm, focal_length_mm, n, d)
    tir = tir_angle_deg(n)
    if not rim_reachable(diameter_mm, focal_length_mm, n, d):
        raise DesignError("design.focal_length_mm", f"the feed cannot reach the rim: the face at r = "
                          f"{diameter_mm / 2:g} mm turns away from the focus; lengthen f or reduce D")
    checks = [_rim_check(rim, tir, n), loss_check(dissipative_loss_db(n, tan_delta, d, lam))]
    if antenna_aperture_mm is not None:
        g = edge_margin_mm(lam, antenna_distance_mm or 0.0)
        need = antenna_aperture_mm + 2 * g
        status = "warn" if need > diameter_mm else "pass"
        checks.append(Check("edge_margin", status, need, diameter_mm, "mm",
                            f"antenna aperture {antenna_aperture_mm:g} mm + 2·g ({g:.1f} mm, seed-000 "
                            f"eq. 2.1) = {need:.1f} mm vs lens diameter {diameter_mm:g} mm"
                            + ("; the antenna rim sees the lens edge diffraction" if status == "warn" else "")))
    return CollimatorDesign(
        diameter_mm=diameter_mm, focal_length_mm=focal_length_mm, eps_r=eps_r,
        tan_delta=tan_delta, frequency_ghz=frequency_ghz,
        phase_error_budget_deg=phase_error_budget_deg, thickness_mm=d, wavelength_mm=lam,
        thickness_tolerance_mm=thickness_tolerance_mm(n, lam, budget), index_tolerance=dn,
        permittivity_tolerance_pct=permittivity_tolerance_pct(n, dn),
        dissipative_loss_db=dissipative_loss_db(n, tan_delta, d, lam),
        reflection_loss_db=reflection_loss_db(n),
        far_field_distance_mm=far_field_distance_mm(diameter_mm, lam),
        scan_limit_deg=scan_limit_deg(lam, diameter_mm, focal_length_mm, n, d),
        rim_incidence_deg=rim, tir_angle_deg=tir,
        volume_mm3=lens_volume_mm3(focal_length_mm, n, d),
        checks=tuple(checks))
