"""Frequency-scanning planar multibeam waveguide-slot arrays with curved slot lines (seed 003).

Pure physics (numpy/scipy only). Sources: ``shared/reference/seed-003.md`` (digest of Le Doan
Trinh, PhD thesis, MIPT 2020), cited below as "seed-003 §N".

Frame and units (one frame for everything this module returns)
----------------------------------------------------------------
* All layers are projected onto one plane. **x** runs across the guides, **y** along the guides,
  in the direction the wave travels in the radiating guides (away from the last mirror / coupling
  slot); **z** is the outward normal of the radiating (slotted) face, i.e. broadside = +Z, as in
  seed-003 §2.6 row "3.1". Layers are stacked in z; which layer a curve belongs to is named.
* The origin is the seed's own origin for each beam former: the mirror vertex O for the elliptic
  mirror (§3.5) and the mirror–lens system (§3.4); the centre O between the two mirrors for the
  two-mirror system (§3.3).
* Lengths are millimetres at every interface (``_mm``), frequencies GHz (``_ghz``), angles
  radians. Normalised constructions (D = 1) are scaled by ``scale_mm``.
* β is the angle of the −1st-harmonic ray from the guide axis (+y); broadside is β = π/2 and
  θ = π/2 − β is the elevation angle from broadside (seed-003 §3.1).

The guide wave model is the unloaded TE10 mode, γ = sqrt(ε k² − (π/a)²) (seed-003 §3.1). The
thesis's loaded (slotted) γ came from HFSS and is not available; the broadside frequency of a
slotted guide is ≈ 1 % lower (10.7 vs 10.80 GHz, §3.1).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property, partial
from typing import Callable, Sequence

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import minimize_scalar

from antenna_cad.raytrace.snell import reflect, refract
from antenna_cad.synthesis.checks import Check, DesignError

C_MM_GHZ = 299.792458  # speed of light, mm·GHz (λ0[mm] = C_MM_GHZ / f[GHz])
N_SIGMA_RAYS = 50       # rays for the RMS path error σ, seed-003 §3.3 eq. (2.7)
FEED_RMS_WARN = 1 / 16  # λ; RMS slot-phase aberration of a feed above this is reported (warn)

LAYOUTS = ("longitudinal_4", "longitudinal_pair", "transverse_3")
TAPER_LAWS = ("sin", "exp", "cos_pedestal", "uniform")
BEAMFORMERS = ("single_mirror", "bifocal_two_mirror", "bifocal_mirror_lens")


# --------------------------------------------------------------------------------------------
# small helpers
# --------------------------------------------------------------------------------------------

def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _normal_from_slope(slope: np.ndarray) -> np.ndarray:
    s = np.asarray(slope, dtype=float)
    return _unit(np.stack([-s, np.ones_like(s)], axis=-1))


def _slope_from_normal(nv: np.ndarray) -> np.ndarray:
    return -nv[..., 0] / nv[..., 1]


def _lower(name: str, value: float, limit: float, unit: str, what: str,
           warn_margin: float = 0.0) -> Check:
    """Pass when ``value >= limit + warn_margin``, warn inside the margin, fail below ``limit``."""
    if value < limit:
        status = "fail"
    elif value < limit + warn_margin:
        status = "warn"
    else:
        status = "pass"
    return Check(name, status, float(value), float(limit), unit,
                 f"{what}: {value:.4g} {unit} (minimum {limit:.4g} {unit})")


def raise_on_fail(checks: Sequence[Check], fields: dict[str, str] | None = None) -> None:
    """Raise :class:`DesignError` for the first failed check (field from ``fields[name]``)."""
    fields = fields or {}
    for c in checks:
        if c.status == "fail":
            raise DesignError(fields.get(c.name, c.name), c.message)


# --------------------------------------------------------------------------------------------
# §3.1 dispersion and the harmonic (frequency-scan) relation
# --------------------------------------------------------------------------------------------

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


# --------------------------------------------------------------------------------------------
# §3.2 leaky-wave amplitude taper, eq. (1.1) corrected (erratum §7.1)
# --------------------------------------------------------------------------------------------

def taper_alpha_np_per_m(y_mm, length_mm: float, law: str = "sin", eta: float = 0.9,
                         pedestal: float = 0.3):
    """Leaky-wave attenuation α(y) (Np/m) that radiates a prescribed |A(y)|² (seed-003 §3.2).

    α = ½|A|² / [η⁻¹ ∫₀ᴸ|A|² − ∫₀ʸ|A|²], η = radiated fraction (P_L = load power; erratum §7.1).
    Laws: ``sin`` |A|² = sin(πy/L) (Table 1.1, closed form as in the digest); ``cos_pedestal``
    |A| = pedestal + (1 − pedestal)·sin(πy/L) (Table 3.1 shape; pedestal not given in the seed);
    ``exp``/``uniform``: constant α = −ln(1 − η)/(2L), exponential field decay.
    """
    y = np.asarray(y_mm, dtype=float)
    L = float(length_mm)
    if not 0.0 < eta < 1.0:
        raise DesignError("slots.taper.eta", f"must be in (0, 1) (got {eta})")
    if law == "sin":
        num = np.sin(np.pi * y / L)
        den = (2 * L / np.pi) / eta - (L / np.pi) * (1.0 - np.cos(np.pi * y / L))
    elif law == "cos_pedestal":
        q = pedestal
        g = lambda u: (q * q * u + 2 * q * (1 - q) * (L / np.pi) * (1 - np.cos(np.pi * u / L))
                       + (1 - q) ** 2 * (u / 2 - L / (4 * np.pi) * np.sin(2 * np.pi * u / L)))
        num = (q + (1 - q) * np.sin(np.pi * y / L)) ** 2
        den = g(L) / eta - g(y)
    elif law in ("exp", "uniform"):
        return np.full_like(y, -np.log(1.0 - eta) / (2 * L) * 1e3)
    else:
        raise DesignError("slots.taper.law", f"unknown law {law!r} (use one of {TAPER_LAWS})")
    return 0.5e3 * num / den


def slot_length_from_alpha_mm(alpha_np_per_m, a0: float = 0.0078, b0: float = 2.01):
    """Invert the cell fit α(L1) = a0·exp(b0·L1) (28 GHz, set 1; seed-003 §3.2)."""
    return np.log(np.asarray(alpha_np_per_m, dtype=float) / a0) / b0


def taper_slot_lengths_mm(n_cells: int, period_mm: float, length_mm: float, law: str = "sin",
                          eta: float = 0.9, a0: float = 0.0078, b0: float = 2.01,
                          pedestal: float = 0.3) -> np.ndarray:
    """L1 of every cell, evaluated at the cell centres y = (m + ½)p (seed-003 §3.2, R3)."""
    y = (np.arange(n_cells) + 0.5) * period_mm
    return slot_length_from_alpha_mm(taper_alpha_np_per_m(y, length_mm, law, eta, pedestal), a0, b0)


# --------------------------------------------------------------------------------------------
# curves and ray tracing through them
# --------------------------------------------------------------------------------------------

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


# --------------------------------------------------------------------------------------------
# §3.5 elliptic mirror (bifocal single-mirror array)
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class BeamFormer:
    """A synthesised quasi-optical beam former, scaled to mm (frame: module docstring).

    ``mirrors``/``lenses``: curves (points + tangents). ``foci_mm``: design foci (K, 2) in the
    feed layer. ``beam_dirs``: (K, 2) unit direction in the xy-plane of the wave that focus k
    launches into the guides' layer: its x component is the azimuth direction cosine of the
    radiated beam. ``sigma_mm``: ray-traced RMS path error (2.7) per design focus (N = 50 rays
    over the aperture), ``sigma_norm`` the same divided by ``aperture_mm``. ``guide_curve`` is
    the curve along which the guides start (last mirror; its coupling slot is offset from it
    toward +y). ``eikonal``: callable (x_mm, focus index) -> design path length (mm) from the
    focus to the guide entry point on ``guide_curve``. ``trace``: (source, x of the launch point
    on the first surface) -> (end point on the last mirror, path, ok, vertices), through the
    curves it was built with (:func:`with_surfaces` swaps them for as-built ones). ``focal_locus``: points of the feed arc,
    ``params``: normalised construction figures (l0, δ, …).
    """
    type: str
    mirrors: tuple[Curve, ...]
    lenses: tuple[Curve, ...]
    foci_mm: np.ndarray
    beam_dirs: np.ndarray
    sigma_mm: np.ndarray
    sigma_norm: np.ndarray
    aperture_mm: float
    guide_curve: Curve
    focal_locus_mm: np.ndarray
    focal_locus_centre_mm: np.ndarray
    eikonal: Callable = field(repr=False)
    trace: Callable = field(repr=False)
    params: dict = field(default_factory=dict)


# Ray traces through the (interpolated) curves of a beam former. Each maps a source point and the
# x of the launch point on the first surface to (end point on the last mirror (N, 2), optical
# path (N,), ok (N,), vertices: the hit points in order, the end point last).

def trace_single_mirror(mirror: Curve, src, x_hit_mm):
    """Source → mirror point at x_hit (the mirror edge is the layer transition), §3.5."""
    xh = np.asarray(x_hit_mm, float)
    p = np.stack([xh, mirror.y_at(xh)], axis=-1)
    return p, np.linalg.norm(p - np.asarray(src, float), axis=-1), np.ones(xh.shape, bool), (p,)


def trace_two_mirror(mir1: Curve, mir2: Curve, src, x_hit_mm):
    """Source → mirror 1 at x_hit (reflection) → mirror 2, §3.3."""
    xh = np.asarray(x_hit_mm, float)
    P = np.stack([xh, mir1.y_at(xh)], -1)
    F = np.asarray(src, float)
    e = reflect(_unit(P - F), _normal_from_slope(mir1.slope_at(xh)))
    Q, ok = intersect_rays_with_curve(P, e, mir2)
    return Q, np.linalg.norm(P - F, axis=-1) + np.linalg.norm(Q - P, axis=-1), ok, (P, Q)


def trace_mirror_lens(lens: Curve, mirror: Curve, n: float, src, x_hit_mm):
    """Source → lens surface at x_hit (refraction into index n) → mirror, §3.4."""
    xh = np.asarray(x_hit_mm, float)
    K = np.stack([xh, lens.y_at(xh)], -1)
    F = np.asarray(src, float)
    e, ok1 = refract(_unit(K - F), _normal_from_slope(lens.slope_at(xh)), 1.0, n)
    Q, ok2 = intersect_rays_with_curve(K, _unit(e), mirror)
    return Q, np.linalg.norm(K - F, axis=-1) + n * np.linalg.norm(Q - K, axis=-1), ok1 & ok2, (K, Q)


def with_surfaces(bf: "BeamFormer", mirrors: Sequence[Curve], lenses: Sequence[Curve] = (),
                  lens_index: float | None = None) -> "BeamFormer":
    """The same beam former traced through other surfaces (the as-built curves, a perturbed lens
    index); foci, design eikonal and beam directions stay those of the design."""
    mirrors, lenses = tuple(mirrors), tuple(lenses)
    if bf.type == "single_mirror":
        trace = partial(trace_single_mirror, mirrors[0])
    elif bf.type == "bifocal_two_mirror":
        trace = partial(trace_two_mirror, *mirrors)
    else:
        n = bf.params["n"] if lens_index is None else float(lens_index)
        trace = partial(trace_mirror_lens, lenses[0], mirrors[0], n)
    return replace(bf, mirrors=mirrors, lenses=lenses, guide_curve=mirrors[-1], trace=trace)


def ellipse_mirror(minor_semi_axis_mm: float, focal_separation_mm: float,
                   half_width_mm: float, n_points: int = 201) -> BeamFormer:
    """Elliptic mirror of the bifocal single-mirror array (seed-003 §3.5, eqs. 3.5–3.6).

    b = r0 cos α (vertex O to the line of foci), c = 2 r0 sin α. The mirror
    x² cos²α + y² − 2 r0 y cos α = 0 passes through O and is concave toward the foci
    F, F′ = (∓r0 sin α, r0 cos α). Focus F (left) launches a wave with azimuth cosine +sin α.
    Eikonal from F to the mirror point A: FA = r0 + x sin α (r + r′ = 2r0, r − r′ = 2x sin α).
    """
    b, c = float(minor_semi_axis_mm), float(focal_separation_mm)
    if b <= 0 or c < 0:
        raise DesignError("beamformer.minor_semi_axis_mm", f"need b > 0, c >= 0 (got {b}, {c})")
    r0 = np.hypot(b, c / 2)
    alpha = np.arctan2(c / 2, b)
    if half_width_mm >= r0:
        raise DesignError("beamformer.minor_semi_axis_mm",
                          f"mirror half-width {half_width_mm:.4g} mm >= r0 {r0:.4g} mm")
    x = np.linspace(-half_width_mm, half_width_mm, n_points)
    root = np.sqrt(1.0 - (x / r0) ** 2)
    y = b * (1.0 - root)
    slope = b * x / (r0**2 * root)
    mirror = _make_curve("mirror", "layer1-layer2", x, y, slope)
    sa, ca = np.sin(alpha), np.cos(alpha)
    foci = np.array([[-r0 * sa, r0 * ca], [r0 * sa, r0 * ca]])
    dirs = np.array([[sa, 0.0], [-sa, 0.0]])   # azimuth cosines ±sin α (y part set by β)

    def eikonal(x_mm, j):
        return r0 + (1 if j == 0 else -1) * np.asarray(x_mm, float) * sa

    trace = partial(trace_single_mirror, mirror)
    sig = []
    xs = np.linspace(-half_width_mm, half_width_mm, N_SIGMA_RAYS)
    for j in range(2):
        sig.append(_rms(trace(foci[j], xs)[1] - eikonal(xs, j)))
    sig = np.array(sig)
    phi = np.linspace(-np.pi / 3, np.pi / 3, 121)
    locus = np.stack([r0 * np.sin(phi), r0 * np.cos(phi)], axis=-1)
    return BeamFormer("single_mirror", (mirror,), (), foci, dirs, sig, sig / (2 * half_width_mm),
                      2 * half_width_mm, mirror, locus, np.zeros(2), eikonal, trace,
                      {"r0_mm": float(r0), "alpha_rad": float(alpha)})


# --------------------------------------------------------------------------------------------
# §3.3 bifocal two-mirror beam former (Kinber-type point-by-point construction, vector form)
# --------------------------------------------------------------------------------------------

def _remaining_to_point(P, e, G, L):
    """t with |G − (P + t e)| = L − t (seed-003 §3.3, vector form)."""
    w = G - P
    return (np.sum(w * w, axis=-1) - L**2) / (2.0 * (np.sum(e * w, axis=-1) - L))


def _monotone_prefix(seg):
    """Keep the leading part of a new segment where x still increases (fold = divergence)."""
    x = seg[0]
    dx = np.diff(x)
    typical = np.median(dx[dx > 0]) if np.any(dx > 0) else 0.0
    bad = np.nonzero((dx <= 0) | (dx > 20.0 * typical))[0]      # fold or jump
    if bad.size == 0:
        return seg
    k = int(bad[0]) + 1
    return tuple(a[:k] for a in seg)


def _monotone(seg_x: np.ndarray, what: str, field_name: str) -> None:
    if not np.all(np.diff(seg_x) > 0):
        raise DesignError(field_name, f"{what}: construction folded back (x not increasing); "
                          f"the initial-segment parameters do not give a smooth surface")


def bifocal_two_mirror(*, a0: float, a2: float, h1: float, b0: float, b2: float, h2: float,
                       rho1: float, rho2: float = np.inf, half_width: float = 0.5,
                       margin: float = 0.1, n_seg: int = 41, max_iter: int = 60,
                       scale_mm: float = 1.0, field_prefix: str = "beamformer") -> BeamFormer:
    """Bifocal two-mirror, three-layer beam former (seed-003 §3.3, eqs. 2.1–2.7).

    Normalised (D = 1) inputs: initial segments y1 = a0 + a2 x² (|x| ≤ h1, mirror 1, layers 1→2)
    and y2 = b0 + b2 x² (|x| ≤ h2, mirror 2, layers 2→3). Central ray F1 → A(−h1) → B(+h2) →
    F3 (or a plane front when ``rho2`` is inf); its direction is taken from the coordinates of
    A and B (erratum §7.3). F2, F4 are mirror images. Step A: F1 rays on the newest mirror-1
    segment build the next mirror-2 segment; step B: F4 rays on the newest mirror-2 segment build
    the next mirror-1 segment; the left halves follow by x → −x symmetry. Stops when both mirrors
    cover |x| ≤ half_width + margin. All outputs are multiplied by ``scale_mm``.
    """
    fp = field_prefix
    if h1 <= 0 or h2 <= 0 or rho1 <= 0 or rho2 <= 0:
        raise DesignError(fp, f"h1, h2, rho1, rho2 must be > 0 (got {h1}, {h2}, {rho1}, {rho2})")
    plane = not np.isfinite(rho2)
    xs1 = np.linspace(-h1, h1, n_seg)
    xs2 = np.linspace(-h2, h2, n_seg)
    seg1 = (xs1, a0 + a2 * xs1**2, 2 * a2 * xs1)
    seg2 = (xs2, b0 + b2 * xs2**2, 2 * b2 * xs2)
    A = np.array([-h1, a0 + a2 * h1**2])
    B = np.array([h2, b0 + b2 * h2**2])
    eAB = _unit(B - A)
    d_in = reflect(eAB, _normal_from_slope(np.array(-2 * a2 * h1)))
    F1 = A - rho1 * d_in
    e_out = reflect(eAB, _normal_from_slope(np.array(2 * b2 * h2)))
    AB = float(np.linalg.norm(B - A))
    F2 = F1 * np.array([-1.0, 1.0])
    if plane:
        u3 = e_out
        u4 = u3 * np.array([-1.0, 1.0])
        l0 = rho1 + AB - float(u3 @ B)
        F3 = F4 = None
    else:
        F3 = B + rho2 * e_out
        F4 = F3 * np.array([-1.0, 1.0])
        l0 = rho1 + AB + rho2

    def step_a(seg):               # F1 rays on mirror 1 -> new mirror-2 points
        x, y, s = seg
        P = np.stack([x, y], -1)
        r1 = np.linalg.norm(P - F1, axis=-1)
        e = reflect(_unit(P - F1), _normal_from_slope(s))
        if plane:
            t = (l0 - r1 + P @ u3) / (1.0 - e @ u3)
            Q = P + t[:, None] * e
            eo = np.broadcast_to(u3, Q.shape)
        else:
            t = _remaining_to_point(P, e, F3, l0 - r1)
            Q = P + t[:, None] * e
            eo = _unit(F3 - Q)
        return Q[:, 0], Q[:, 1], _slope_from_normal(e - eo)

    def step_b(seg):               # F4 rays (or the reversed plane wave u4) on mirror 2 -> mirror 1
        x, y, s = seg
        M = np.stack([x, y], -1)
        if plane:
            d = np.broadcast_to(-u4, M.shape)
            L = l0 + M @ u4
        else:
            d = _unit(M - F4)
            L = l0 - np.linalg.norm(M - F4, axis=-1)
        e = reflect(d, _normal_from_slope(s))
        t = _remaining_to_point(M, e, F2, L)
        N = M + t[:, None] * e
        return N[:, 0], N[:, 1], _slope_from_normal(e - _unit(F2 - N))

    m1, m2 = [seg1], [seg2]
    need = half_width + margin
    for _ in range(max_iter):
        if m1[-1][0][-1] >= need and m2[-1][0][-1] >= need:
            break
        n2, n1 = step_a(m1[-1]), step_b(m2[-1])
        _monotone(n1[0], "mirror 1", fp)
        _monotone(n2[0], "mirror 2", fp)
        m1.append(n1)
        m2.append(n2)
    else:
        raise DesignError(fp, f"mirrors did not reach |x| = {need:.3g} in {max_iter} iterations "
                          f"(reached {m1[-1][0][-1]:.4g}, {m2[-1][0][-1]:.4g})")

    # the initial segments hold both halves; later segments only x > 0 (mirror them)
    mir1 = _assemble_symmetric(m1, "mirror_1", "layer1-layer2", scale_mm)
    mir2 = _assemble_symmetric(m2, "mirror_2", "layer2-layer3", scale_mm)

    sc = scale_mm
    foci = np.array([F1, F2]) * sc
    if plane:
        dirs = np.array([u3, u4])
    else:
        dirs = np.array([_unit(F3 - np.array([0, b0])), _unit(F4 - np.array([0, b0]))])

    trace = partial(trace_two_mirror, mir1, mir2)

    def eikonal(x_mm, j):
        """Design path focus j → point Q on mirror 2: l0 + u_j·Q (plane output) or
        l0 − |Q F_out| (focal output, F_out = F3 for F1, F4 for F2)."""
        x = np.asarray(x_mm, float)
        Q = np.stack([x, mir2.y_at(x)], -1)
        if plane:
            return l0 * sc + Q @ dirs[j]
        return l0 * sc - np.linalg.norm(Q - (F3 if j == 0 else F4) * sc, axis=-1)

    sig = []
    xs = np.linspace(-half_width, half_width, N_SIGMA_RAYS) * sc
    for j in range(2):
        Q, L, ok, _ = trace(foci[j], xs)
        if plane:
            tot = L - Q @ dirs[j]
            ref = l0 * sc
        else:
            F_out = (F3 if j == 0 else F4) * sc
            tot = L + np.linalg.norm(F_out - Q, axis=-1)
            ref = l0 * sc
        if not ok.all():
            raise DesignError(fp, f"focus {j + 1}: {int((~ok).sum())} of {ok.size} rays miss "
                              "mirror 2; increase the construction margin")
        sig.append(_rms(tot - ref))
    sig = np.array(sig)
    R = float(np.linalg.norm(F1)) * sc
    phi0 = np.arctan2(F1[0], -F1[1])
    phi = np.linspace(-max(2 * abs(phi0), np.pi / 3), max(2 * abs(phi0), np.pi / 3), 121)
    locus = np.stack([R * np.sin(phi), -R * np.cos(phi)], -1)
    params = {"l0": float(l0), "F1": F1.copy(), "iterations": len(m1) - 1, "plane_output": plane,
              "beam_angle_rad": float(np.arctan2(dirs[0][0], dirs[0][1]))}
    if not plane:
        params["F3"] = F3.copy()
    return BeamFormer("bifocal_two_mirror", (mir1, mir2), (), foci, dirs, sig, sig / sc,
                      sc, mir2, locus, np.zeros(2), eikonal, trace, params)


def _assemble_symmetric(segs, name, layer, scale):
    """Join the initial (symmetric) segment and the right-hand segments; mirror to the left."""
    x0, y0, s0 = segs[0]
    xr = np.concatenate([s[0] for s in segs[1:]]) if len(segs) > 1 else np.empty(0)
    yr = np.concatenate([s[1] for s in segs[1:]]) if len(segs) > 1 else np.empty(0)
    sr = np.concatenate([s[2] for s in segs[1:]]) if len(segs) > 1 else np.empty(0)
    x = np.concatenate([-xr[::-1], x0, xr])
    y = np.concatenate([yr[::-1], y0, yr])
    s = np.concatenate([-sr[::-1], s0, sr])
    return _make_curve(name, layer, x, y, s, scale)


# --------------------------------------------------------------------------------------------
# §3.4 bifocal mirror–lens beam former
# --------------------------------------------------------------------------------------------

def _transfer_up(e_in: np.ndarray, slope: np.ndarray, ratio: float | np.ndarray) -> np.ndarray:
    """Wave crossing a mirror-edge coupling slot into the other layer, travelling back (+y).

    Tangential phase is conserved: e_out·τ = ratio·(e_in·τ) with ratio = n_in/n_out
    (seed-003 §3.4, (2.10)/(2.12)/(2.15)); the normal part is taken with +y sign.
    """
    nrm = _normal_from_slope(slope)                     # has +y component
    tau = np.stack([nrm[..., 1], -nrm[..., 0]], -1)
    et = ratio * np.sum(e_in * tau, -1)
    if np.any(np.abs(et) > 1.0):
        raise DesignError("beamformer", "no transmitted wave at the mirror (|n sin| > 1)")
    return et[..., None] * tau + np.sqrt(1.0 - et**2)[..., None] * nrm


def bifocal_mirror_lens(*, lens_a2: float, lens_vertex: float, x0: float, p1: float, p2: float,
                        f0: float, n: float, half_width: float = 0.5, margin: float = 0.05,
                        n_seg: int = 41, max_iter: int = 80, scale_mm: float = 1.0,
                        field_prefix: str = "beamformer") -> BeamFormer:
    """Bifocal mirror–lens, two-layer beam former (seed-003 §3.4, eqs. 2.8–2.18, errata §7.4).

    Normalised inputs: initial lens input surface y = lens_vertex + lens_a2·x² on |x| ≤ x0;
    on-axis focus F(0, f0); lens index n; p1 = distance F1 → lens point A(−x0); p2 = reference
    distance to the output front. Step 0 builds the initial mirror through O from F (plane wave
    along +y, L0 = 2f0 + d(n − 1)); F1 follows by back-refraction of the ray A → D (D = right end
    of the initial mirror) and the output direction δ from the tangential law at D. Then
    alternately: F1 rays through the newest lens segment give the next mirror segment (2.13–2.15);
    the reversed plane wave of F2 on the *previous* mirror segment gives the next lens segment
    (2.16–2.18, C sign corrected).
    """
    fp = field_prefix
    if n <= 1 or x0 <= 0 or f0 <= lens_vertex or p1 <= 0:
        raise DesignError(fp, f"need n > 1, x0 > 0, f0 > lens vertex, p1 > 0 "
                          f"(got n={n}, x0={x0}, f0={f0}, p1={p1})")
    F = np.array([0.0, f0])
    xl = np.linspace(-x0, x0, n_seg)
    lens0 = (xl, lens_vertex + lens_a2 * xl**2, 2 * lens_a2 * xl)
    L0 = 2 * f0 + lens_vertex * (n - 1)
    K = np.stack([lens0[0], lens0[1]], -1)
    e, ok = refract(_unit(K - F), _normal_from_slope(lens0[2]), 1.0, n)
    e = _unit(e)
    cosb = -e[:, 1]
    KH = (L0 + K[:, 1] - f0 - np.linalg.norm(K - F, axis=-1)) / (n + cosb)
    H = K + KH[:, None] * e
    mir0 = (H[:, 0], H[:, 1], _slope_from_normal(n * e - np.array([0.0, 1.0])))
    _monotone(mir0[0], "initial mirror", fp)
    A = K[0]
    D = H[-1]
    eAD = _unit(D - A)
    back, ok = refract(-eAD, _normal_from_slope(np.array(lens0[2][0])), n, 1.0)
    F1 = A + p1 * _unit(back)
    u1 = _transfer_up(eAD, np.array(mir0[2][-1]), n)
    delta = float(np.arctan2(u1[0], u1[1]))
    l0 = float(np.linalg.norm(D - A))
    R0 = p1 + n * l0 + p2 - float(u1 @ D)
    F2 = F1 * np.array([-1.0, 1.0])
    u2 = u1 * np.array([-1.0, 1.0])

    def step_mirror(seg):          # F1 rays through lens points -> new mirror points
        x, y, s = seg
        M = np.stack([x, y], -1)
        e, ok = refract(_unit(M - F1), _normal_from_slope(s), 1.0, n)
        if not ok.all():
            raise DesignError(fp, "total reflection at the lens surface")
        e = _unit(e)
        l = (R0 - np.linalg.norm(M - F1, axis=-1) - p2 + M @ u1) / (n - e @ u1)
        N = M + l[:, None] * e
        return N[:, 0], N[:, 1], _slope_from_normal(n * e - u1)

    def step_lens(seg):            # reversed plane wave of F2 on mirror points -> new lens points
        x, y, s = seg
        P = np.stack([x, y], -1)
        e = _transfer_up(np.broadcast_to(-u2, P.shape), s, 1.0 / n)
        DP = p2 - P @ u2
        S = R0 - DP
        w = F2 - P
        a = n * n - 1.0
        bq = np.sum(e * w, -1) - n * S
        cq = S**2 - np.sum(w * w, -1)
        disc = bq * bq - a * cq
        if np.any(disc < 0):
            raise DesignError(fp, "lens construction has no solution (negative discriminant)")
        roots = np.stack([(-bq - np.sqrt(disc)) / a, (-bq + np.sqrt(disc)) / a], -1)
        good = (roots > 0) & ((S[:, None] - n * roots) > 0)
        l = np.where(good[:, 0], roots[:, 0], roots[:, 1])
        if not good.any(axis=1).all():
            raise DesignError(fp, "lens construction: no positive path root")
        Q = P + l[:, None] * e
        air = _unit(Q - F2)
        return Q[:, 0], Q[:, 1], _slope_from_normal(air + n * e)

    lenses, mirrors = [lens0], [mir0]
    need = half_width + margin
    for _ in range(max_iter):
        if lenses[-1][0][-1] >= need and mirrors[-1][0][-1] >= need:
            break
        nm = _monotone_prefix(step_mirror(lenses[-1]))
        nl = _monotone_prefix(step_lens(mirrors[-1]))
        mirrors.append(nm)
        lenses.append(nl)
        if len(nm[0]) < n_seg or len(nl[0]) < n_seg:   # construction diverges (§3.4): stop
            if min(nm[0][-1], nl[0][-1]) < half_width:
                raise DesignError(fp, f"construction diverges at |x| = "
                                  f"{min(nm[0][-1], nl[0][-1]):.4g} before covering the "
                                  f"half-aperture {half_width:.4g}")
            break
    else:
        raise DesignError(fp, f"surfaces did not reach |x| = {need:.3g} in {max_iter} iterations")
    sc = scale_mm
    mir = _assemble_symmetric(mirrors, "mirror", "layer1-layer2", sc)
    lens = _assemble_symmetric(lenses, "lens", "layer1", sc)
    foci = np.array([F1, F2]) * sc
    dirs = np.array([u1, u2])
    Rsc, p2sc = R0 * sc, p2 * sc

    trace = partial(trace_mirror_lens, lens, mir, n)

    def eikonal(x_mm, j):
        x = np.asarray(x_mm, float)
        Q = np.stack([x, mir.y_at(x)], -1)
        return Rsc - p2sc + Q @ dirs[j]

    sig = []
    xs = np.linspace(-half_width, half_width, N_SIGMA_RAYS) * sc
    for j in range(2):
        Q, L, ok, _ = trace(foci[j], xs)
        if not ok.all():
            raise DesignError(fp, f"focus {j + 1}: {int((~ok).sum())} rays miss the mirror")
        sig.append(_rms(L + p2sc - Q @ dirs[j] - Rsc))
    sig = np.array(sig)
    # lens thickness over the aperture (lens above mirror)
    xa = np.linspace(-half_width, half_width, 201) * sc
    thick = lens.y_at(xa) - mir.y_at(xa)
    Rl = float(np.linalg.norm(F1)) * sc
    phi0 = np.arctan2(-F1[0], F1[1])
    lim = max(2 * abs(phi0), np.pi / 3)
    phi = np.linspace(-lim, lim, 121)
    locus = np.stack([Rl * np.sin(phi), Rl * np.cos(phi)], -1)
    params = {"delta_rad": delta, "F1": F1.copy(), "R0": float(R0), "L0": float(L0),
              "iterations": len(lenses) - 1, "beam_angle_rad": delta, "n": float(n),
              "min_lens_thickness_mm": float(thick.min()),
              "initial_mirror_half_width": float(mir0[0][-1])}
    return BeamFormer("bifocal_mirror_lens", (mir,), (lens,), foci, dirs, sig, sig / sc, sc,
                      mir, locus, np.zeros(2), eikonal, trace, params)


# --------------------------------------------------------------------------------------------
# §3.5 (generalised) curved slot lines and their phase coherence
# --------------------------------------------------------------------------------------------

def slot_line_t_mm(bf: BeamFormer, x_mm, n_guide: float, cos_beta: float,
                   t0_mm: float) -> np.ndarray:
    """Distance t(x) along the guide from the guide entry (last mirror) to the slot-centre line.

    Coherence for both design foci j = 1, 2 (seed-003 §3.5, §3.6 convention-free form):
    Ψ_j = L_j(x) + n t − u_j·B = const, B = (x, y_Q(x) + t), u_j = (s_j, cos β), where L_j is
    the design eikonal from focus j to the guide entry Q(x) and n = γ/k (erratum §7.8). Adding
    the two equations (the x terms cancel for s_2 = −s_1) gives
    t = t0 + [L̄(0) − L̄(x) + cos β (y_Q(x) − y_Q(0))]/(n − cos β), L̄ = (L_1 + L_2)/2.
    For the ellipse L̄ = r0 and this is the corrected (3.7): t = t0 + y cos β/(n − cos β)
    (erratum §7.5); at broadside the line is the mirror shifted by t0 (R5).
    """
    x = np.asarray(x_mm, float)
    gc = bf.guide_curve
    lbar = lambda xx: 0.5 * (bf.eikonal(xx, 0) + bf.eikonal(xx, 1))
    num = (lbar(np.zeros(1))[0] - lbar(x)) + cos_beta * (gc.y_at(x) - float(gc.y_at(0.0)))
    return t0_mm + num / (n_guide - cos_beta)


def traced_rays(bf: BeamFormer, source, x_mm, iterations: int = 30) -> tuple[np.ndarray, tuple]:
    """Ray-traced path (mm) from a source to the guide entry point at x on the guide curve, and
    the ray vertices (hit points on each surface, the entry point last).

    ``source``: design-focus index (int) or a point (mm) in the feed layer. Independent of the
    construction: rays go through the interpolated curves with Snell / reflection; the launch
    point on the first surface is found by a vectorised secant search.
    """
    src = bf.foci_mm[source] if np.ndim(source) == 0 else np.asarray(source, float)
    x = np.asarray(x_mm, float)
    if bf.type == "single_mirror":
        _, L, _, vertices = bf.trace(src, x)
        return L, vertices
    tol = 1e-12 * bf.aperture_mm
    xh0 = x.copy()
    Q0 = bf.trace(src, xh0)[0]
    xh1 = x - (Q0[:, 0] - x)
    for _ in range(iterations):
        Q1 = bf.trace(src, xh1)[0]
        f0, f1 = Q0[:, 0] - x, Q1[:, 0] - x
        if np.max(np.abs(f1)) < tol:
            break
        den = np.where(np.abs(f1 - f0) > 0, f1 - f0, 1.0)
        xh2 = np.where(np.abs(f1) < tol, xh1, xh1 - f1 * (xh1 - xh0) / den)
        xh0, Q0, xh1 = xh1, Q1, xh2
    Q, L, ok, vertices = bf.trace(src, xh1)
    if not ok.all() or np.max(np.abs(Q[:, 0] - x)) > 1e-9 * bf.aperture_mm:
        raise DesignError("beamformer", "could not trace rays from the source to every guide "
                          "entry (source outside the usable field of view?)")
    return L, vertices


def traced_eikonal_mm(bf: BeamFormer, source, x_mm) -> np.ndarray:
    """Ray-traced path (mm) from a source to the guide entry at x (:func:`traced_rays`)."""
    return traced_rays(bf, source, x_mm)[0]


def feed_phase_errors(bf: BeamFormer, sources_mm, x_mm, t_mm, n_guide: float, cos_beta: float,
                      wavelength_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Aberration of the slot-line phase for arbitrary feed positions (seed-003 §3.9, (3.41)).

    For each source: Ψ(x_i) = L(x_i) + (n − cos β) t_i − cos β y_Q(x_i) at the slot line of every
    guide; a linear fit a + s·x removes the constant and the beam tilt. Returns
    (RMS residual in wavelengths, beam azimuth sin φ = s) per source. At a design focus the
    residual is zero and s equals the design azimuth cosine.
    """
    x = np.asarray(x_mm, float)
    t = np.asarray(t_mm, float)
    yq = bf.guide_curve.y_at(x)
    A = np.column_stack([np.ones_like(x), x])
    rms, az = [], []
    for src in np.atleast_2d(np.asarray(sources_mm, float)):
        psi = traced_eikonal_mm(bf, src, x) + (n_guide - cos_beta) * t - cos_beta * yq
        coef, *_ = np.linalg.lstsq(A, psi, rcond=None)
        rms.append(_rms(psi - A @ coef) / wavelength_mm)
        az.append(coef[1])
    return np.array(rms), np.array(az)


def slot_phase_spread(bf: BeamFormer, x_mm, y_ref_mm, n_guide: float, cos_beta: float,
                      wavelength_mm: float) -> np.ndarray:
    """Peak-to-peak spread (in wavelengths) of the radiated −1st-harmonic phase per focus.

    ``x_mm``, ``y_ref_mm``: cell reference points (slot-line point + m·p) on each guide. The path
    is ray-traced to the guide entry, n·(y − y_Q) inside the guide, minus u_j·r toward the beam
    (seed-003 §8.3 "phase coherence at the slots"), wrapped modulo λ.
    """
    x = np.asarray(x_mm, float)
    y = np.asarray(y_ref_mm, float)
    ux, inv = np.unique(x, return_inverse=True)
    yq = bf.guide_curve.y_at(ux)[inv]
    out = []
    for j in range(2):
        L = traced_eikonal_mm(bf, j, ux)[inv]
        psi = L + n_guide * (y - yq) - bf.beam_dirs[j][0] * x - cos_beta * y
        ph = 2 * np.pi * psi / wavelength_mm
        mean = np.angle(np.mean(np.exp(1j * ph)))
        dev = np.angle(np.exp(1j * (ph - mean)))
        out.append((dev.max() - dev.min()) / (2 * np.pi))
    return np.array(out)


# --------------------------------------------------------------------------------------------
# slot layout (per guide, per cell, per slot) and manufacturability checks (§8.1, §8.3)
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class SlotLayout:
    """Every slot of the array, flat arrays of equal length (frame: module docstring, mm).

    Per slot: ``guide_index`` (0 = most negative x), ``cell_index`` (0 = nearest the coupling
    slot), ``slot_in_cell``; centre ``x_mm``, ``y_mm``; ``length_mm`` (long side), ``width_mm``;
    ``offset_mm`` = x_mm − guide axis x (signed); ``angle_rad`` = angle of the long side from +y
    (0 longitudinal, π/2 transverse). Per guide: ``guide_x_mm`` (axis), ``guide_entry_y_mm``
    (on the last mirror), ``t_mm`` (entry → slot line), ``slot_line_y_mm``, ``guide_end_y_mm``
    (slot line + n_cells·period). Slots are rectangles length × width (round ends fit inside).
    """
    layout: str
    guide_index: np.ndarray
    cell_index: np.ndarray
    slot_in_cell: np.ndarray
    x_mm: np.ndarray
    y_mm: np.ndarray
    length_mm: np.ndarray
    width_mm: np.ndarray
    offset_mm: np.ndarray
    angle_rad: np.ndarray
    guide_x_mm: np.ndarray
    guide_entry_y_mm: np.ndarray
    t_mm: np.ndarray
    slot_line_y_mm: np.ndarray
    guide_end_y_mm: np.ndarray
    period_mm: float
    n_cells: int

    @property
    def count(self) -> int:
        return int(self.x_mm.size)

    def half_extents_mm(self) -> tuple[np.ndarray, np.ndarray]:
        """(half size across the guide, half size along the guide) of every slot."""
        c, s = np.abs(np.cos(self.angle_rad)), np.abs(np.sin(self.angle_rad))
        hl, hw = self.length_mm / 2, self.width_mm / 2
        return hl * s + hw * c, hl * c + hw * s

    def as_table(self) -> np.ndarray:
        """(N, 9) table: guide, cell, slot, x, y, length, width, offset, angle."""
        return np.column_stack([self.guide_index, self.cell_index, self.slot_in_cell, self.x_mm,
                                self.y_mm, self.length_mm, self.width_mm, self.offset_mm,
                                self.angle_rad])


def cell_pattern(layout: str, *, n_cells: int, period_mm: float, guide_width_mm: float,
                 lengths_mm=None, l2_mm=None, l2_ratio: float = 0.68, offset_mm=None,
                 pair_shift_mm: float | None = None,
                 transverse_spacings_mm: Sequence[float] = (1.66, 1.62)):
    """Slot pattern of one period: (dy (J,), offset (J,), lengths (n_cells, J), angle (J,)).

    * ``longitudinal_4`` (seed-003 §2.1, Fig. 1.9 lost — ASSUMED geometry): four slots at p/4
      spacing, offsets alternating +o, −o, +o, −o (o = ``offset_mm``, default a/4); the first has
      length L1 (``lengths_mm`` per cell, from the taper), the other three L2 (``l2_mm`` scalar or
      per cell, default ``l2_ratio``·L1; Table 1.1 upper rows have L2/L1 ≈ 0.68).
    * ``longitudinal_pair`` (seed-003 §2.4): two slots at ±o (default a/4) shifted
      ``pair_shift_mm`` (λg/2 at the design frequency) along the guide; length per cell.
    * ``transverse_3`` (seed-003 §2.2): three transverse slots on the axis at 0, d1, d1 + d2
      (centre spacings ``transverse_spacings_mm``), lengths s1..s3 (``lengths_mm``: 3 values).
    """
    a = guide_width_mm
    o = a / 4 if offset_mm is None else float(offset_mm)
    if layout == "longitudinal_4":
        L1 = np.broadcast_to(np.asarray(lengths_mm, float), (n_cells,))
        L2 = l2_ratio * L1 if l2_mm is None else np.broadcast_to(np.asarray(l2_mm, float), (n_cells,))
        lengths = np.column_stack([L1, L2, L2, L2])
        dy = np.arange(4) * period_mm / 4
        off = o * np.array([1.0, -1.0, 1.0, -1.0])
        ang = np.zeros(4)
    elif layout == "longitudinal_pair":
        L = np.broadcast_to(np.asarray(lengths_mm, float), (n_cells,))
        lengths = np.column_stack([L, L])
        dy = np.array([0.0, float(pair_shift_mm)])
        off = o * np.array([1.0, -1.0])
        ang = np.zeros(2)
    elif layout == "transverse_3":
        s = np.asarray(lengths_mm, float)
        if s.shape != (3,):
            raise DesignError("slots.lengths_mm", f"transverse_3 needs 3 lengths s1..s3 "
                              f"(got shape {s.shape})")
        d1, d2 = transverse_spacings_mm
        lengths = np.broadcast_to(s, (n_cells, 3))
        dy = np.array([0.0, d1, d1 + d2])
        off = np.zeros(3)
        ang = np.full(3, np.pi / 2)
    else:
        raise DesignError("slots.layout", f"unknown layout {layout!r} (use one of {LAYOUTS})")
    if np.any(np.asarray(lengths) <= 0) or not np.all(np.isfinite(lengths)):
        raise DesignError("slots.lengths_mm", f"slot lengths must be finite and > 0 "
                          f"(min {np.nanmin(lengths):.4g} mm)")
    return dy, off, np.asarray(lengths, float), ang


def build_slot_layout(*, layout: str, guide_x_mm, guide_entry_y_mm, t_mm, n_cells: int,
                      period_mm: float, width_mm: float, dy, off, lengths, ang) -> SlotLayout:
    """Broadcast the cell pattern over guides × cells (vectorised, linear in slot count)."""
    gx = np.asarray(guide_x_mm, float)
    gy = np.asarray(guide_entry_y_mm, float)
    t = np.asarray(t_mm, float)
    G, M, J = gx.size, n_cells, len(dy)
    line = gy + t
    gi = np.broadcast_to(np.arange(G)[:, None, None], (G, M, J))
    ci = np.broadcast_to(np.arange(M)[None, :, None], (G, M, J))
    si = np.broadcast_to(np.arange(J)[None, None, :], (G, M, J))
    y = line[:, None, None] + np.arange(M)[None, :, None] * period_mm + np.asarray(dy)[None, None, :]
    offs = np.broadcast_to(np.asarray(off)[None, None, :], (G, M, J))
    x = gx[:, None, None] + offs
    L = np.broadcast_to(lengths[None, :, :], (G, M, J))
    A = np.broadcast_to(np.asarray(ang)[None, None, :], (G, M, J))
    f = lambda v: np.ascontiguousarray(v).reshape(-1)
    return SlotLayout(layout, f(gi), f(ci), f(si), f(x), f(y), f(L), np.full(G * M * J, width_mm),
                      f(offs), f(A), gx, gy, t, line, line + M * period_mm, float(period_mm), M)


def check_slots_in_wall(slots: SlotLayout, guide_width_mm: float,
                        clearance_mm: float = 0.0) -> Check:
    """Every slot inside the broad wall: |offset| + half size across ≤ a/2 − clearance (§8.3)."""
    hx, _ = slots.half_extents_mm()
    ext = np.abs(slots.offset_mm) + hx
    k = int(np.argmax(ext))
    c = Check.upper("slots_inside_wall", float(ext[k]), guide_width_mm / 2 - clearance_mm, "mm",
                    f"slot reach from guide axis (guide {slots.guide_index[k]}, cell "
                    f"{slots.cell_index[k]}, slot {slots.slot_in_cell[k]}) vs a/2 − clearance")
    return c


def slot_webs_mm(slots: SlotLayout, neighbours: int = 4) -> np.ndarray:
    """Signed web between each slot and its next ``neighbours`` slots along the same guide.

    Rectangle distance: Euclidean gap when separated, negative penetration when overlapping.
    Returns (N, neighbours) with +inf where no neighbour exists.
    """
    order = np.lexsort((slots.y_mm, slots.guide_index))
    g = slots.guide_index[order]
    x, y = slots.x_mm[order], slots.y_mm[order]
    hx, hy = (h[order] for h in slots.half_extents_mm())
    n = x.size
    out = np.full((n, neighbours), np.inf)
    for k in range(1, neighbours + 1):
        i, j = np.arange(n - k), np.arange(k, n)
        same = g[i] == g[j]
        gx = np.abs(x[i] - x[j]) - (hx[i] + hx[j])
        gy = np.abs(y[i] - y[j]) - (hy[i] + hy[j])
        web = np.where((gx > 0) & (gy > 0), np.hypot(gx, gy), np.maximum(gx, gy))
        out[i, k - 1] = np.where(same, web, np.inf)
    res = np.empty_like(out)
    res[order] = out
    return res


def check_slot_webs(slots: SlotLayout, min_web_mm: float) -> Check:
    """No overlapping slots and a minimum metal web between neighbours on a guide (§8.3)."""
    webs = slot_webs_mm(slots)
    k, kk = np.unravel_index(int(np.argmin(webs)), webs.shape)
    w = float(webs[k, kk])
    what = ("slots OVERLAP" if w < 0 else "minimum web between slots") + \
        f" (guide {slots.guide_index[k]}, cell {slots.cell_index[k]}, slot {slots.slot_in_cell[k]})"
    return _lower("slot_web", w, min_web_mm, "mm", what)


def check_coupling_clearance(slots: SlotLayout, guide_curve: Curve, coupling_slot_mm: float,
                             min_gap_mm: float = 0.0) -> Check:
    """Gap along the guide from the coupling slot (strip of width d along the last mirror,
    on the guide side) to the nearest slot edge, ≥ ``min_gap_mm`` (§8.3; d2 = 7.8 mm in §2.4)."""
    hx, hy = slots.half_extents_mm()
    edge = offset_curve(guide_curve, coupling_slot_mm, "coupling_slot_edge")
    lo, hi = edge.x_range_mm
    gaps = []
    for sgn in (-1.0, 0.0, 1.0):               # slot corners and centre across the guide
        xe = np.clip(slots.x_mm + sgn * hx, lo, hi)
        gaps.append(slots.y_mm - hy - edge.y_at(xe))
    gap = np.minimum.reduce(gaps)
    k = int(np.argmin(gap))
    return _lower("coupling_slot_clearance", float(gap[k]), min_gap_mm, "mm",
                  f"gap from coupling slot to slot (guide {slots.guide_index[k]}, cell "
                  f"{slots.cell_index[k]}, slot {slots.slot_in_cell[k]})")


# --------------------------------------------------------------------------------------------
# feeds on the focal locus (§8.1 item 8)
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class FeedSet:
    """H-plane sectoral horns in the feed layer (seed-003 §8.1 item 8).

    Feeds are symmetric about x = 0, adjacent aperture centres exactly one H-plane aperture
    apart (chord). ``placement``: ``circle`` puts them on the circle through the design foci
    about ``locus_centre_mm`` (the seed's approximation of the focal curve, §3.3/§3.5);
    ``optimal`` moves each feed radially (polar angle about ``locus_centre_mm`` chained so the
    pitch stays one aperture) to the radius that minimises its RMS slot-phase aberration
    (:func:`feed_phase_errors`). ``aim`` (K, 2): unit vectors from each aperture centre to
    ``aim_point_mm`` (vertex of the first mirror/lens). The horn body extends from the aperture
    back along −aim by ``length_mm``; throat and aperture are (H-plane, E-plane) mm.
    ``phase_rms_wavelengths`` / ``azimuth_rad``: per feed, residual RMS aberration and beam
    azimuth at the design frequency (NaN where rays miss). ``locus_mm``: the focal locus used
    (circle points, or the optimal-radius locus sampled over the feeds' angular range).
    """
    aperture_centres_mm: np.ndarray
    aim: np.ndarray
    polar_angle_rad: np.ndarray
    radius_mm: np.ndarray
    phase_rms_wavelengths: np.ndarray
    azimuth_rad: np.ndarray
    locus_mm: np.ndarray
    locus_centre_mm: np.ndarray
    aim_point_mm: np.ndarray
    throat_mm: tuple[float, float]
    aperture_mm: tuple[float, float]
    length_mm: float
    placement: str


def place_feeds(bf: BeamFormer, *, count: int, throat_mm, aperture_mm, length_mm: float,
                aim_point_mm, objective: Callable | None = None, placement: str = "circle",
                radius_bounds: tuple[float, float] = (0.6, 1.4), n_locus: int = 9) -> FeedSet:
    """Place ``count`` feeds; ``objective(point_mm) -> (rms_λ, sin φ)`` scores a feed position."""
    if count < 1:
        raise DesignError("feeds.count", f"must be >= 1 (got {count})")
    if placement not in ("circle", "optimal"):
        raise DesignError("feeds.placement", f"use circle or optimal (got {placement!r})")
    c = np.asarray(bf.focal_locus_centre_mm, float)
    F = bf.foci_mm[0]
    R0 = float(np.linalg.norm(F - c))
    up = 1.0 if F[1] > c[1] else -1.0           # side of the foci relative to the centre
    ap = float(aperture_mm[0])
    if ap >= 2 * R0 * radius_bounds[0]:
        raise DesignError("feeds.aperture_mm", f"horn aperture {ap:.4g} mm too large for the "
                          f"focal circle (radius {R0:.4g} mm)")
    pos_of = lambda R, phi: c + np.array([R * np.sin(phi), up * R * np.cos(phi)])

    def score(p):
        if objective is None:
            return np.nan, np.nan
        try:
            r, z = objective(p)
            return float(r), float(np.arcsin(np.clip(z, -1, 1)))
        except DesignError:
            return np.nan, np.nan

    def best_radius(phi_of_R):
        if placement == "circle" or objective is None:
            return R0
        f = lambda R: np.nan_to_num(score(pos_of(R, phi_of_R(R)))[0], nan=1e3)
        res = minimize_scalar(f, bounds=(radius_bounds[0] * R0, radius_bounds[1] * R0),
                              method="bounded", options={"xatol": 1e-5 * R0})
        return float(res.x)

    right = []                                    # (R, phi) of feeds with phi >= 0
    if count % 2:
        right.append((best_radius(lambda R: 0.0), 0.0))
    else:
        phi1 = lambda R: float(np.arcsin(ap / (2 * R)))
        R = best_radius(phi1)
        right.append((R, phi1(R)))
    while 2 * len(right) - (count % 2) < count:
        Rp, php = right[-1]
        def phi_next(R, Rp=Rp, php=php):
            cosd = (R * R + Rp * Rp - ap * ap) / (2 * R * Rp)
            return php + float(np.arccos(np.clip(cosd, -1.0, 1.0)))
        R = best_radius(phi_next)
        right.append((R, phi_next(R)))
    Rs = np.array([r for r, _ in right])
    ph = np.array([p for _, p in right])
    if count % 2:
        Rs = np.concatenate([Rs[:0:-1], Rs])
        ph = np.concatenate([-ph[:0:-1], ph])
    else:
        Rs = np.concatenate([Rs[::-1], Rs])
        ph = np.concatenate([-ph[::-1], ph])
    pos = np.array([pos_of(R, p) for R, p in zip(Rs, ph)])
    aim = _unit(np.asarray(aim_point_mm, float) - pos)
    sc = np.array([score(p) for p in pos]).reshape(-1, 2)
    lim = max(float(np.abs(ph).max()), float(abs(np.arctan2(F[0] - c[0], up * (F[1] - c[1])))))
    lim = max(lim, np.radians(5.0))
    if placement == "optimal" and objective is not None:
        phis = np.linspace(-lim, lim, n_locus)
        half = [best_radius(lambda R, q=q: q) for q in phis[phis >= 0]]
        rl = np.concatenate([half[::-1][:-1] if phis.size % 2 else half[::-1], half])
        locus = np.array([pos_of(R, q) for R, q in zip(rl, phis)])
    else:
        phis = np.linspace(-lim, lim, 121)
        locus = np.array([pos_of(R0, q) for q in phis])
    return FeedSet(pos, aim, ph, Rs, sc[:, 0], sc[:, 1], locus, c,
                   np.asarray(aim_point_mm, float), (float(throat_mm[0]), float(throat_mm[1])),
                   (float(aperture_mm[0]), float(aperture_mm[1])), float(length_mm), placement)


# --------------------------------------------------------------------------------------------
# the design
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class SlotArrayDesign:
    """Complete synthesis result (frame and units: module docstring).

    ``slot_line``: Curve through the first-slot-line points (x, y_Q + t) over the guide array;
    ``coupling_slot_edge``: far edge of the coupling slot, the normal offset of
    ``beamformer.guide_curve`` (slot near edge) by ``coupling_slot_mm`` toward +y;
    ``figures``: scalar key figures (mm, GHz, dBi, rad); ``phase_spread_wavelengths``: peak-to-
    peak slot-phase spread per design focus (ray-traced); per-feed aberration and beam azimuth
    are in ``feeds``. ``termination``: ``matched_load`` (absorber wedge of ``load_length_mm``
    before the end wall) or ``short`` (end wall after the last cell, ``load_length_mm`` = 0).
    """
    scan: ScanFigures
    beamformer: BeamFormer
    slots: SlotLayout
    slot_line: Curve
    coupling_slot_edge: Curve
    feeds: FeedSet
    guide_width_mm: float
    guide_height_mm: float
    wall_mm: float
    fill_eps_r: float
    layer_height_mm: float
    coupling_slot_mm: float
    termination: str
    load_length_mm: float
    phase_spread_wavelengths: np.ndarray
    figures: dict
    checks: tuple[Check, ...]


_CHECK_FIELDS = {
    "slots_inside_wall": "slots.width_mm",
    "slot_web": "slots.period_mm",
    "coupling_slot_clearance": "beamformer.slot_line_offset_mm",
    "te10_cutoff_margin": "waveguide.width_mm",
    "minus1_radiates": "slots.period_mm",
    "guides_inside_aperture": "array.count",
    "lens_thickness": "beamformer",
}


def synthesize_slot_array(
        *, min_ghz: float, max_ghz: float, design_ghz: float,
        guide_width_mm: float, guide_height_mm: float, fill_eps_r: float, wall_mm: float,
        count: int, pitch_mm: float, length_mm: float,
        layout: str, slot_width_mm: float, period_mm: float | None = None,
        design_theta_rad: float = 0.0,
        taper_law: str = "sin", taper_eta: float = 0.9, taper_a0: float | None = None,
        taper_b0: float | None = None, taper_pedestal: float = 0.3,
        lengths_mm=None, l2_mm=None, l2_ratio: float = 0.68, slot_offset_mm: float | None = None,
        pair_shift_mm: float | None = None, transverse_spacings_mm=(1.66, 1.62),
        beamformer_type: str = "single_mirror", beamformer_params: dict | None = None,
        scale_mm: float | None = None, slot_line_offset_mm: float = 10.0,
        layer_height_mm: float = 1.6, coupling_slot_mm: float = 1.1,
        feed_count: int = 1, feed_throat_mm=(7.2, 1.6), feed_aperture_mm=(16.0, 1.6),
        feed_length_mm: float = 30.0, feed_placement: str = "optimal",
        wall_clearance_mm: float = 0.2, min_web_mm: float = 0.3, min_coupling_gap_mm: float = 0.0,
        termination: str = "matched_load", load_length_mm: float | None = None,
        strict: bool = True) -> SlotArrayDesign:
    """Synthesise a frequency-scanning planar multibeam waveguide-slot array (seed-003).

    Steps: period (given, or auto from (3.1) so that the −1st harmonic points at
    ``design_theta_rad`` from broadside at ``design_ghz``: broadside ⇒ p = λg); scan figures and
    mode/harmonic checks over the band (§3.1, §8.3); beam former (§3.3–§3.5) scaled to mm
    (``scale_mm`` = physical size of the normalised D = 1; default pitch·count); curved slot line
    t(x) at the design frequency (§3.5, erratum §7.5, guide index n = γ/k, erratum §7.8); slot
    lengths from the taper (1.1, erratum §7.1) unless ``lengths_mm`` is given; the slot layout;
    manufacturability checks. ``beamformer_params`` (normalised unless _mm):
    single_mirror: minor_semi_axis_mm, focal_separation_mm; bifocal_two_mirror: a0, a2, h1, b0,
    b2, h2, rho1 (rho2 = inf: plane output fronts are required to feed the guides);
    bifocal_mirror_lens: lens_a2, lens_vertex, x0, p1, p2, f0, n. ``slot_line_offset_mm`` is
    t0, the distance along the guide from the last mirror to the first slot line at x = 0.
    Slots: ``lengths_mm`` (per cell for the longitudinal layouts, s1..s3 for transverse_3),
    ``l2_mm``/``l2_ratio`` (other three slots of the 4-slot cell), ``slot_offset_mm`` (default
    a/4), ``pair_shift_mm`` (default λg/2), ``transverse_spacings_mm`` (d1, d2); see
    :func:`cell_pattern`. Feeds: ``feed_placement`` = optimal | circle (:func:`place_feeds`).
    Manufacturability limits: ``wall_clearance_mm``, ``min_web_mm``, ``min_coupling_gap_mm``.
    Far end (:func:`termination_check`): ``termination`` = matched_load (absorber wedge of
    ``load_length_mm``, default λg at ``min_ghz``) or short.
    With ``strict`` a failed check raises :class:`DesignError` naming the spec field and the
    number; with ``strict=False`` failures are returned in ``checks``.
    """
    bp = dict(beamformer_params or {})
    a, eps = float(guide_width_mm), float(fill_eps_r)
    if count < 1 or pitch_mm <= 0 or length_mm <= 0:
        raise DesignError("array", f"need count >= 1, pitch_mm > 0, length_mm > 0 "
                          f"(got {count}, {pitch_mm}, {length_mm})")
    if pitch_mm < a + 2 * wall_mm - 1e-9:
        raise DesignError("array.pitch_mm", f"pitch {pitch_mm:.4g} mm < guide width + 2 walls "
                          f"{a + 2 * wall_mm:.4g} mm")
    beta_design = np.pi / 2 - design_theta_rad
    if period_mm is None:
        period_mm = period_for_angle_mm(design_ghz, a, eps, beta_design)
    period_mm = float(period_mm)
    layers = [("layer1", layer_height_mm, 1.0)]
    if beamformer_type == "bifocal_mirror_lens":
        layers.append(("lens", layer_height_mm, float(bp.get("n", np.sqrt(2.2)))))
    scan = scan_figures(min_ghz=min_ghz, max_ghz=max_ghz, design_ghz=design_ghz, width_mm=a,
                        height_mm=guide_height_mm, eps_r=eps, period_mm=period_mm,
                        layer_heights_mm=layers)
    nw = scan.n_guide_design
    cb = float(np.cos(scan.beta_design_rad))
    lam = C_MM_GHZ / design_ghz

    span = count * pitch_mm
    guide_x = (np.arange(count) - (count - 1) / 2) * pitch_mm
    checks = list(scan.checks)
    if beamformer_type == "single_mirror":
        D = span if scale_mm is None else float(scale_mm)
        bf = ellipse_mirror(bp["minor_semi_axis_mm"], bp["focal_separation_mm"], D / 2)
        aim_point = np.zeros(2)
    elif beamformer_type == "bifocal_two_mirror":
        if np.isfinite(bp.get("rho2", np.inf)):
            raise DesignError("beamformer.rho2", "the guides need plane output fronts: rho2 must "
                              f"be inf (got {bp['rho2']})")
        D = span if scale_mm is None else float(scale_mm)
        keys = ("a0", "a2", "h1", "b0", "b2", "h2", "rho1")
        bf = bifocal_two_mirror(**{k: float(bp[k]) for k in keys}, half_width=0.5, scale_mm=D)
        aim_point = np.array([0.0, bp["a0"] * D])
    elif beamformer_type == "bifocal_mirror_lens":
        D = span if scale_mm is None else float(scale_mm)
        keys = ("lens_a2", "lens_vertex", "x0", "p1", "p2", "f0", "n")
        bf = bifocal_mirror_lens(**{k: float(bp[k]) for k in keys}, half_width=0.5, scale_mm=D)
        aim_point = np.array([0.0, bp["lens_vertex"] * D])
        checks.append(_lower("lens_thickness", bf.params["min_lens_thickness_mm"], 0.0, "mm",
                             "minimum lens thickness over the aperture"))
    else:
        raise DesignError("beamformer.type", f"unknown {beamformer_type!r} (use {BEAMFORMERS})")
    half_guides = np.abs(guide_x).max() + a / 2 + wall_mm
    x0c, x1c = bf.guide_curve.x_range_mm
    checks.append(Check.upper("guides_inside_aperture", float(half_guides), float(min(-x0c, x1c)),
                              "mm", "half-width of the guide array vs last-mirror half-width"))
    if strict:
        raise_on_fail(checks, _CHECK_FIELDS)

    # curved slot line at the design frequency
    t = slot_line_t_mm(bf, guide_x, nw, cb, slot_line_offset_mm)
    entry = bf.guide_curve.y_at(guide_x)
    n_cells = int(np.floor(length_mm / period_mm + 1e-9))
    if n_cells < 1:
        raise DesignError("array.length_mm", f"shorter than one period ({period_mm:.4g} mm)")

    # slot lengths
    if lengths_mm is None:
        if layout != "longitudinal_4" and (taper_a0 is None or taper_b0 is None):
            raise DesignError("slots.lengths_mm", f"layout {layout}: give lengths_mm or the cell "
                              "fit taper a0/b0 (the α(L1) fit of seed-003 §3.2 is for the Ka "
                              "4-longitudinal-slot cell only)")
        lengths_mm = taper_slot_lengths_mm(n_cells, period_mm, length_mm, taper_law, taper_eta,
                                           0.0078 if taper_a0 is None else taper_a0,
                                           2.01 if taper_b0 is None else taper_b0, taper_pedestal)
    elif layout != "transverse_3":
        lengths_mm = np.asarray(lengths_mm, float)
        if lengths_mm.ndim == 1 and lengths_mm.size != n_cells:
            raise DesignError("slots.lengths_mm", f"{lengths_mm.size} lengths for {n_cells} cells")
    if pair_shift_mm is None:
        pair_shift_mm = 0.5 * 2 * np.pi / float(guide_gamma_per_mm(design_ghz, a, eps))
    dy, off, lens_, ang = cell_pattern(layout, n_cells=n_cells, period_mm=period_mm,
                                       guide_width_mm=a, lengths_mm=lengths_mm, l2_mm=l2_mm,
                                       l2_ratio=l2_ratio, offset_mm=slot_offset_mm,
                                       pair_shift_mm=pair_shift_mm,
                                       transverse_spacings_mm=transverse_spacings_mm)
    slots = build_slot_layout(layout=layout, guide_x_mm=guide_x, guide_entry_y_mm=entry, t_mm=t,
                              n_cells=n_cells, period_mm=period_mm, width_mm=slot_width_mm,
                              dy=dy, off=off, lengths=lens_, ang=ang)
    mchecks = [check_slots_in_wall(slots, a, wall_clearance_mm),
               check_slot_webs(slots, min_web_mm),
               check_coupling_clearance(slots, bf.guide_curve, coupling_slot_mm,
                                        min_coupling_gap_mm)]
    # phase coherence at the cell reference points, every design focus (ray-traced)
    gx = np.repeat(guide_x, n_cells)
    gyref = (slots.slot_line_y_mm[:, None] + np.arange(n_cells)[None, :] * period_mm).reshape(-1)
    spread = slot_phase_spread(bf, gx, gyref, nw, cb, lam)
    for j, sp in enumerate(spread):
        mchecks.append(Check.upper(f"slot_phase_coherence_focus{j + 1}", float(sp), 1e-3,
                                   "λ", f"slot-phase spread for design focus {j + 1}"))
    for j, sg in enumerate(bf.sigma_norm):
        mchecks.append(Check.upper(f"sigma_design_focus{j + 1}", float(sg), 1e-6, "D",
                                   f"RMS path error σ at design focus {j + 1} (2.7)"))
    checks += mchecks
    if strict:
        raise_on_fail(checks, _CHECK_FIELDS)

    slot_line = _slot_line_curve(bf, span, nw, cb, slot_line_offset_mm)
    coupling_edge = offset_curve(bf.guide_curve, coupling_slot_mm, "coupling_slot_edge")
    objective = lambda p: tuple(v[0] for v in feed_phase_errors(bf, p, guide_x, t, nw, cb, lam))
    feeds = place_feeds(bf, count=feed_count, throat_mm=feed_throat_mm,
                        aperture_mm=feed_aperture_mm, length_mm=feed_length_mm,
                        aim_point_mm=aim_point, objective=objective, placement=feed_placement)
    feed_rms = feeds.phase_rms_wavelengths
    worst = float(np.nanmax(feed_rms)) if np.isfinite(feed_rms).any() else np.inf
    checks.append(Check("feed_phase_rms", "warn" if not worst <= FEED_RMS_WARN else "pass",
                        worst, FEED_RMS_WARN, "λ",
                        f"worst RMS slot-phase aberration over {feed_count} feed(s): {worst:.3g} λ"
                        + ("" if np.isfinite(feed_rms).all() else
                           f"; rays from {int((~np.isfinite(feed_rms)).sum())} feed(s) miss")))
    if termination == "matched_load" and load_length_mm is None:
        load_length_mm = float(guide_wavelength_mm(min_ghz, a, eps))
    load_length_mm = float(load_length_mm) if termination == "matched_load" else 0.0
    checks.append(termination_check(termination, load_length_mm,
                                     float(guide_wavelength_mm(min_ghz, a, eps)), taper_eta))
    figures = {
        "period_mm": period_mm, "n_cells": n_cells, "slot_count": slots.count,
        "broadside_ghz": scan.broadside_ghz, "beta_design_rad": scan.beta_design_rad,
        "n_guide_design": nw, "guide_wavelength_design_mm": scan.guide_wavelength_design_mm,
        "aperture_width_mm": span, "aperture_length_mm": n_cells * period_mm,
        "ideal_gain_dbi": ideal_gain_dbi(span, length_mm, design_ghz),
        "beam_azimuth_rad": float(np.arcsin(abs(bf.beam_dirs[0][0]))),
        "slot_line_sag_mm": float(t.max() - t.min()),
        "load_length_mm": load_length_mm, "load_power_fraction": 1.0 - taper_eta,
    }
    return SlotArrayDesign(scan, bf, slots, slot_line, coupling_edge, feeds, a,
                           float(guide_height_mm), float(wall_mm), eps, float(layer_height_mm),
                           float(coupling_slot_mm), termination, load_length_mm, spread, figures,
                           tuple(checks))


def termination_check(termination: str, load_length_mm: float, guide_wavelength_max_mm: float,
                      eta: float) -> Check:
    """The far end of a leaky-wave guide takes the 1 − η not radiated (seed-003 §3.2, (1.1)).

    ``matched_load``: an absorber wedge shorter than one guide wavelength at the band minimum
    reflects noticeably (warn). ``short``: the residual power reflects; the backward wave's −1st
    harmonic radiates at β' = π − β, a beam mirrored about broadside about 10·log10(1 − η) dB
    below the main beam (warn).
    """
    if termination == "short":
        return Check("termination", "warn", 1.0 - eta, 0.0, "",
                     f"short-circuit guide ends: the residual {100 * (1 - eta):.0f} % reflects and "
                     f"radiates a beam mirrored about broadside ≈ {10 * np.log10(1 - eta):.1f} dB "
                     "below the main beam (waveguide.termination: matched_load avoids it)")
    if termination != "matched_load":
        raise DesignError("waveguide.termination", f"use matched_load or short (got {termination!r})")
    short = load_length_mm < guide_wavelength_max_mm
    return Check("termination", "warn" if short else "pass", load_length_mm, guide_wavelength_max_mm,
                 "mm", f"matched-load wedge {load_length_mm:.4g} mm "
                 + ("shorter than" if short else "≥") + f" one guide wavelength at the band minimum "
                 f"({guide_wavelength_max_mm:.4g} mm); it takes {100 * (1 - eta):.0f} % of the input")


def _slot_line_curve(bf: BeamFormer, span_mm: float, n_guide: float, cos_beta: float,
                     t0_mm: float, n_points: int = 201) -> Curve:
    """First slot-centre line (x, y_Q(x) + t(x)) over the guide array, with tangents."""
    xs = np.linspace(-span_mm / 2, span_mm / 2, n_points)
    yl = lambda x: bf.guide_curve.y_at(x) + slot_line_t_mm(bf, x, n_guide, cos_beta, t0_mm)
    h = 1e-6 * span_mm
    return _make_curve("slot_line", "guides", xs, yl(xs), (yl(xs + h) - yl(xs - h)) / (2 * h))


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
