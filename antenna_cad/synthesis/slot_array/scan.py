"""Dispersion of the slotted guides and the harmonic (frequency-scan) relation (seed-003 §3.1, §8.3)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.slot_array.common import C_MM_GHZ, _lower


def wavenumber_per_mm(f_ghz):
    """Free-space k = 2π/λ0 (rad/mm)."""
    return 2.0 * np.pi * np.asarray(f_ghz, dtype=float) / C_MM_GHZ


def guide_gamma_per_mm(f_ghz, width_mm: float, eps_r: float):
    """TE10 propagation constant γ (rad/mm) of a filled guide, NaN below cut-off (seed-003 §3.1)."""
    k = wavenumber_per_mm(f_ghz)
    g2 = eps_r * k**2 - (np.pi / width_mm) ** 2
    return np.sqrt(np.where(g2 > 0.0, g2, np.nan))


def guide_wavelength_mm(f_ghz, width_mm: float, eps_r: float):
    return 2.0 * np.pi / guide_gamma_per_mm(f_ghz, width_mm, eps_r)


def harmonic_direction_cosine(f_ghz, width_mm: float, eps_r: float, period_mm: float,
                              m: int = -1):
    """Direction cosine along the guide, (γ + 2πm/p)/k, of spatial harmonic m (seed-003 §3.1).

    For m = −1 this is cos β of eq. (3.1): cos β = (γp − 2π)/(kp). The harmonic radiates
    where its magnitude is ≤ 1.
    """
    k = wavenumber_per_mm(f_ghz)
    return (guide_gamma_per_mm(f_ghz, width_mm, eps_r) + 2.0 * np.pi * m / period_mm) / k


def broadside_frequency_ghz(width_mm: float, eps_r: float, period_mm: float) -> float:
    """Frequency where the −1st harmonic is broadside, γp = 2π, i.e. p = λg (seed-003 §3.1)."""
    k2 = ((2.0 * np.pi / period_mm) ** 2 + (np.pi / width_mm) ** 2) / eps_r
    return float(np.sqrt(k2) * C_MM_GHZ / (2.0 * np.pi))


def period_for_angle_mm(f_ghz: float, width_mm: float, eps_r: float,
                        beta_rad: float = np.pi / 2) -> float:
    """Slot period giving the −1st harmonic at angle β from the guide axis at ``f_ghz``.

    From (3.1): p = 2π/(γ − k cos β); broadside (β = π/2) gives p = λg.
    """
    g = float(guide_gamma_per_mm(f_ghz, width_mm, eps_r))
    if not np.isfinite(g):
        raise DesignError("band.design_ghz", f"{f_ghz:.4g} GHz is below the TE10 cut-off of the "
                          f"{width_mm:.4g} mm guide (eps_r {eps_r:.4g})")
    return float(2.0 * np.pi / (g - float(wavenumber_per_mm(f_ghz)) * np.cos(beta_rad)))


def ideal_gain_dbi(width_mm: float, length_mm: float, f_ghz: float,
                   aperture_efficiency: float = 1.0) -> float:
    """4πS/λ² · КИП in dBi (seed-003 §3.9, R12)."""
    lam = C_MM_GHZ / f_ghz
    return float(10.0 * np.log10(aperture_efficiency * 4.0 * np.pi * width_mm * length_mm / lam**2))


def _mode_check(name: str, mode: str, cutoff_ghz: float, max_ghz: float, fix: str) -> Check:
    """Warn when a higher mode's cut-off lies below the band maximum (seed-003 §8.3)."""
    inside = cutoff_ghz < max_ghz
    return Check(name, "warn" if inside else "pass", float(cutoff_ghz), float(max_ghz), "GHz",
                 f"{mode} cut-off {cutoff_ghz:.4g} GHz "
                 + (f"is inside the band (max {max_ghz:.4g} GHz): reduce {fix}" if inside
                    else f"above the band maximum {max_ghz:.4g} GHz"))


@dataclass(frozen=True)
class ScanFigures:
    """Harmonic bookkeeping over the band (seed-003 §3.1, §8.3).

    ``frequencies_ghz`` is the sampled band; per frequency: ``cos_beta`` of the −1st harmonic,
    ``theta_rad`` its angle from broadside (NaN where it does not radiate), ``n_guide`` = γ/k.
    """
    frequencies_ghz: np.ndarray
    cos_beta: np.ndarray
    theta_rad: np.ndarray
    n_guide: np.ndarray
    design_ghz: float
    period_mm: float
    broadside_ghz: float
    beta_design_rad: float
    n_guide_design: float
    guide_wavelength_design_mm: float
    te10_cutoff_ghz: float
    te20_cutoff_ghz: float
    te01_cutoff_ghz: float
    checks: tuple[Check, ...]


def scan_figures(*, min_ghz: float, max_ghz: float, design_ghz: float, width_mm: float,
                 height_mm: float, eps_r: float, period_mm: float,
                 layer_heights_mm: Sequence[tuple[str, float, float]] = (),
                 n_freq: int = 161) -> ScanFigures:
    """Frequency-scan relation over the band with the mode/harmonic checks of seed-003 §8.3.

    ``layer_heights_mm``: (name, height_mm, refractive index) of each parallel-plate layer; a
    warning is raised when its first higher mode (cut-off c/(2hn)) is below ``max_ghz``.
    """
    if not (0 < min_ghz <= design_ghz <= max_ghz):
        raise DesignError("band", f"need 0 < min_ghz <= design_ghz <= max_ghz "
                          f"(got {min_ghz}, {design_ghz}, {max_ghz})")
    f = np.linspace(min_ghz, max_ghz, n_freq)
    k = wavenumber_per_mm(f)
    gam = guide_gamma_per_mm(f, width_mm, eps_r)
    cb = harmonic_direction_cosine(f, width_mm, eps_r, period_mm, -1)
    theta = np.where(np.abs(cb) <= 1.0, np.arcsin(np.clip(cb, -1, 1)), np.nan)
    sq = np.sqrt(eps_r)
    fc10 = C_MM_GHZ / (2 * width_mm * sq)
    fc20 = C_MM_GHZ / (width_mm * sq)
    fc01 = C_MM_GHZ / (2 * height_mm * sq)
    fb = broadside_frequency_ghz(width_mm, eps_r, period_mm)
    checks = [
        _lower("te10_cutoff_margin", min_ghz - fc10, 0.0, "GHz",
               f"band minimum above TE10 cut-off ({fc10:.4g} GHz) of waveguide.width_mm"),
        _mode_check("te20_in_band", "TE20", fc20, max_ghz, "waveguide.width_mm"),
        _mode_check("te01_in_band", "TE01", fc01, max_ghz, "waveguide.height_mm"),
    ]
    for name, h, n_idx in layer_heights_mm:
        fpp = C_MM_GHZ / (2 * h * n_idx)
        checks.append(_mode_check("parallel_plate_" + name, f"{name}: first higher "
                                  "parallel-plate mode", fpp, max_ghz, "layer_height_mm"))
    rad = np.abs(cb) <= 1.0
    checks.append(Check("minus1_radiates", "pass" if rad.all() else ("warn" if rad.any() else "fail"),
                        float(np.mean(rad)), 1.0, "",
                        f"−1st harmonic radiates over {100 * np.mean(rad):.0f} % of the band"))
    for m, name in ((0, "harmonic_0_radiates"), (-2, "harmonic_m2_radiates")):
        cm = harmonic_direction_cosine(f, width_mm, eps_r, period_mm, m)
        fx = f[np.isfinite(cm) & (np.abs(cm) < 1.0)]
        checks.append(Check(name, "warn" if fx.size else "pass", float(fx.size / f.size), 0.0, "",
                            (f"harmonic {m} is fast (radiates) at {fx.min():.4g}–{fx.max():.4g} GHz"
                             " inside the band: extra beams unless the slot pattern cancels it"
                             " (slots.period_mm, band)") if fx.size else
                            f"harmonic {m} does not radiate in the band"))
    checks.append(Check("broadside_frequency", "warn" if min_ghz <= fb <= max_ghz else "pass",
                        fb, max_ghz, "GHz",
                        f"broadside (p = λg, 'normal effect' S11 peak) at {fb:.4g} GHz"
                        + (" inside the band" if min_ghz <= fb <= max_ghz else " outside the band")))
    cbd = float(harmonic_direction_cosine(design_ghz, width_mm, eps_r, period_mm, -1))
    if abs(cbd) > 1.0:
        raise DesignError("slots.period_mm", f"−1st harmonic does not radiate at design "
                          f"{design_ghz:.4g} GHz (cos β = {cbd:.4g})")
    gd = float(guide_gamma_per_mm(design_ghz, width_mm, eps_r))
    return ScanFigures(f, cb, theta, gam / k, float(design_ghz), float(period_mm), fb,
                       float(np.arccos(cbd)), gd / float(wavenumber_per_mm(design_ghz)),
                       2 * np.pi / gd, fc10, fc20, fc01, tuple(checks))
