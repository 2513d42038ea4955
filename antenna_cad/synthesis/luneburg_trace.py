"""Exact, vectorized GO tracer through concentric homogeneous shells (seed-002 §2.1b): exit
points/directions, optical paths, aperture phase error and focus spread, and the aperture figures.
Pure physics (numpy/scipy); re-exported by :mod:`antenna_cad.synthesis.luneburg`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, Sequence

import numpy as np

from antenna_cad.synthesis.checks import DesignError

C_MM_GHZ = 299.792458  # speed of light: λ[mm] = C_MM_GHZ / f[GHz]

Shape = Literal["sphere", "cylinder"]

# --------------------------------------------------------------------------------------------
# GO tracer through concentric homogeneous shells (seed-002 §2.1b)
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class LayeredTrace:
    """Rays from the feed at (x, z) = (0, −b) through the shells, meridional plane x–z.

    Rays with impact parameter k leave the feed at θ = asin(k/b) toward +x. For the sphere the
    3-D ray at azimuth ψ is this one rotated about +Z; for the cylinder this *is* the ray.
    All arrays have one entry per ray; lengths in mm, angles in rad. Invalid rays (miss the
    lens, or exit not toward +Z) carry NaN in the aperture fields.
    """

    impact_mm: np.ndarray          # k: ray invariant = distance of the air ray from the centre
    launch_angle_rad: np.ndarray   # θ from +Z at the feed
    entry_xz_mm: np.ndarray        # (n, 2)
    exit_xz_mm: np.ndarray         # (n, 2)
    exit_dir_xz: np.ndarray        # (n, 2) unit
    exit_tilt_rad: np.ndarray      # angle of the exit ray from +Z (0 = ideal)
    sweep_rad: np.ndarray          # polar-angle sweep inside the lens, Θ
    sweep_error_rad: np.ndarray    # Θ − [π + asin(k/b) − 2 asin(k/R)]
    optical_path_inside_mm: np.ndarray
    optical_path_mm: np.ndarray    # feed → aperture plane z = aperture_z_mm along the ray
    boresight_path_mm: np.ndarray  # feed → exit point + (aperture_z − z_exit): boresight phase path
    aperture_x_mm: np.ndarray      # where the ray crosses the aperture plane
    focus_miss_mm: np.ndarray      # reverse trace: signed miss of the focus by the ray entering parallel at k
    axial_focus_mm: np.ndarray     # reverse trace: distance from centre where it crosses the axis (NaN if it does not)
    turning_layer: np.ndarray      # deepest layer reached (0 = core): turning point or reflection
    tir: np.ndarray                # ray reflected totally at an inner interface
    valid: np.ndarray
    aperture_z_mm: float
    focal_distance_mm: float
    radius_mm: float


def trace_shells(r_outer_mm, eps_r, focal_distance_mm: float, impact_mm=None,
                 n_rays: int = 512, aperture_z_mm: float | None = None) -> LayeredTrace:
    """Exact GO trace through concentric homogeneous shells (seed-002 §2.1b), vectorized.

    ``r_outer_mm``/``eps_r``: per layer, innermost first (layer i fills r_{i−1} < r < r_i, r_0 = 0).
    In layer i a ray is the straight line at distance p_i = k/n_i from the centre; it sweeps
    Δφ_i = acos(p_i/r_i) − acos(p_i/r_{i−1}) (or acos(p_i/r_i) at the turning layer) with optical
    path n_i(√(r_i²−p_i²) − √(r_{i−1}²−p_i²)); inbound and outbound legs are mirror images, so
    Θ = 2ΣΔφ_i, L = 2ΣΔL_i. A ray that cannot enter a denser-outside inner layer is totally
    reflected there (flagged ``tir``; GO phase of the reflection ignored). Fresnel losses ignored.
    Default rays: ``n_rays`` midpoints uniform in k over (0, R); ``aperture_z_mm`` defaults to R.
    """
    ro = np.asarray(r_outer_mm, dtype=float)
    eps = np.asarray(eps_r, dtype=float)
    if ro.ndim != 1 or ro.shape != eps.shape or ro.size == 0:
        raise ValueError("r_outer_mm and eps_r must be 1-D of equal, non-zero length")
    if np.any(np.diff(ro) <= 0) or ro[0] <= 0:
        raise DesignError("design.layers", "layer radii must increase strictly from > 0")
    if np.any(eps < 1.0):
        i = int(np.argmin(eps))
        raise DesignError("design.layers", f"layer {i + 1} has εr = {eps[i]:.4g} < 1")
    R = float(ro[-1])
    b = float(focal_distance_mm)
    if b < R:
        raise DesignError("design.focal_distance_ratio", f"feed inside the lens: b = {b:g} mm < R = {R:g} mm")
    if impact_mm is None:
        k = (np.arange(n_rays) + 0.5) * (R / n_rays)
    else:
        k = np.atleast_1d(np.asarray(impact_mm, dtype=float))
    zap = R if aperture_z_mm is None else float(aperture_z_mm)
    n = np.sqrt(eps)
    ri = np.concatenate([[0.0], ro[:-1]])
    M = ro.size
    p = k[:, None] / n[None, :]                      # (rays, layers)
    hits = k < R
    reached = np.zeros_like(p, dtype=bool)
    below = p < ri[None, :]                          # reaches the layer's inner boundary
    tir = np.zeros(k.shape, dtype=bool)
    reached[:, M - 1] = hits
    for j in range(M - 1, 0, -1):
        enters = p[:, j - 1] < ro[j - 1]
        reached[:, j - 1] = reached[:, j] & below[:, j] & enters
        tir |= reached[:, j] & below[:, j] & ~enters
    through = reached & below                        # passes the inner boundary of the layer
    with np.errstate(invalid="ignore"):
        ac_o = np.arccos(np.clip(p / ro[None, :], -1.0, 1.0))
        ac_i = np.where(through, np.arccos(np.clip(np.divide(p, ri[None, :], out=np.ones_like(p),
                                                             where=ri[None, :] > 0), -1.0, 1.0)), 0.0)
    dphi = np.where(reached, ac_o - ac_i, 0.0)
    dl = np.where(reached, n[None, :] * (np.sqrt(np.maximum(ro[None, :] ** 2 - p**2, 0.0))
                                         - np.where(through, np.sqrt(np.maximum(ri[None, :] ** 2 - p**2, 0.0)), 0.0)),
                  0.0)
    theta = 2.0 * dphi.sum(axis=1)
    Lin = 2.0 * dl.sum(axis=1)
    turning = np.where(hits, np.argmax(reached, axis=1), -1)   # deepest layer reached

    kk = np.minimum(k, R)
    acR = np.arccos(kk / R)
    phi_in = np.arccos(kk / b) - acR                 # position angle from −Z toward +x
    phi_out = phi_in + theta
    phi_c = phi_out - acR                            # closest approach of the exit line
    e_r = lambda ph: np.stack([np.sin(ph), -np.cos(ph)], axis=-1)
    entry = R * e_r(phi_in)
    exit_ = R * e_r(phi_out)
    d = np.stack([np.cos(phi_c), np.sin(phi_c)], axis=-1)
    tilt = phi_c - np.pi / 2
    req = np.pi + np.arcsin(kk / b) - 2.0 * np.arcsin(kk / R)
    air_in = np.sqrt(b * b - kk * kk) - np.sqrt(R * R - kk * kk)
    valid = hits & (d[:, 1] > 1e-9)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(valid, (zap - exit_[:, 1]) / d[:, 1], np.nan)
    opl = air_in + Lin + t
    xap = exit_[:, 0] + t * d[:, 0]
    # reverse trace: parallel ray at impact k from +Z; its exit line has closest-approach angle
    # φc' = π/2 + 2 acos(k/R) − Θ; miss of the focus = k − b cos φc'; axis crossing k / cos φc'.
    phc_r = np.pi / 2 + 2.0 * acR - theta
    miss = np.where(hits, kk - b * np.cos(phc_r), np.nan)
    with np.errstate(divide="ignore", invalid="ignore"):
        axial = np.where(hits & (np.cos(phc_r) > 1e-12), kk / np.cos(phc_r), np.nan)
    nanv = lambda a: np.where(hits[:, None] if a.ndim == 2 else hits, a, np.nan)
    return LayeredTrace(
        impact_mm=k, launch_angle_rad=np.arcsin(kk / b), entry_xz_mm=nanv(entry),
        exit_xz_mm=nanv(exit_), exit_dir_xz=nanv(d), exit_tilt_rad=nanv(tilt),
        sweep_rad=nanv(theta), sweep_error_rad=nanv(theta - req), optical_path_inside_mm=nanv(Lin),
        optical_path_mm=np.where(valid, opl, np.nan),
        boresight_path_mm=np.where(hits, air_in + Lin + (zap - exit_[:, 1]), np.nan),
        aperture_x_mm=np.where(valid, xap, np.nan),
        focus_miss_mm=miss, axial_focus_mm=axial, turning_layer=turning, tir=tir & hits,
        valid=valid, aperture_z_mm=zap, focal_distance_mm=b, radius_mm=R)


def trace_layered_sphere(layers: Sequence, focal_distance_mm: float, impact_mm=None,
                         n_rays: int = 512, aperture_z_mm: float | None = None) -> LayeredTrace:
    """:func:`trace_shells` for a sequence of objects with ``r_outer_mm`` and ``eps_r``
    (e.g. :class:`Layer`, innermost first) — the as-built stage passes the chosen grades.
    Also valid for the parallel-plate cylinder (same 2-D physics, see module docstring)."""
    return trace_shells([L.r_outer_mm for L in layers], [L.eps_r for L in layers],
                        focal_distance_mm, impact_mm=impact_mm, n_rays=n_rays,
                        aperture_z_mm=aperture_z_mm)


@dataclass(frozen=True)
class ApertureFigures:
    """Stepped-lens GO figures. "Core" figures use the rays with k <= rim_fraction·R; "full"
    ones every ray. The rim sliver holds rays that skim thin outer layers at grazing incidence,
    where GO gives errors of many wavelengths that do not shrink with the layer count (seed-002
    §2.1b: GO exaggerates the few-layer problem; layers thinner than λ are not resolved)."""

    rim_fraction: float
    phase_error_pp_deg: float      # core
    phase_error_rms_deg: float     # core, area weighted, piston removed
    phase_error_pp_full_deg: float
    phase_error_rms_full_deg: float
    focus_spread_mm: float         # core: max |miss| of the design focus by reversed parallel rays
    focus_spread_rms_mm: float     # core, area weighted
    focus_spread_full_mm: float
    axial_focus_min_mm: float      # core: axis crossings of reversed parallel rays (ideal: b)
    axial_focus_max_mm: float
    max_exit_tilt_rad: float       # core
    phase_efficiency: float        # full aperture: |Σ A e^{jφ} w|² / |Σ A w|², cos^q feed
    invalid_rays: int


def aperture_figures(trace: LayeredTrace, frequency_ghz: float, feed_q: float,
                     shape: Shape = "sphere", rim_fraction: float = 0.95) -> ApertureFigures:
    """Aperture phase error at the design frequency and focus spread from a trace.

    Phase φ = 360°·(P − mean)/λ with P = ``boresight_path_mm`` (field phase on the exit surface
    referred to the +Z plane wavefront, i.e. its phase in the boresight far field), piston
    removed; RMS and mean weighted by aperture area (w = k for the sphere, 1 for the cylinder's
    line aperture). The continuous law has φ ≡ 0 and zero focus miss (verified in the tests),
    so these figures are directly "stepped vs continuous". The phase efficiency weights the
    rays with the ideal GO amplitude A = cos^q θ/√cosθ (§2.5) over the whole aperture.
    """
    lam = C_MM_GHZ / frequency_ghz
    R = trace.radius_mm
    k_all = trace.impact_mm
    hit = np.isfinite(trace.boresight_path_mm)
    core = hit & (k_all <= rim_fraction * R)

    def phase_stats(sel):
        k = k_all[sel]
        w = k if shape == "sphere" else np.ones_like(k)
        P = trace.boresight_path_mm[sel]
        ph = 360.0 * (P - np.sum(w * P) / np.sum(w)) / lam
        return ph, w, float(np.ptp(ph)), float(math.sqrt(np.sum(w * ph**2) / np.sum(w)))

    ph_f, w_f, pp_f, rms_f = phase_stats(hit)
    _, _, pp_c, rms_c = phase_stats(core)
    th = np.arcsin(k_all[hit] / trace.focal_distance_mm)
    A = np.cos(th) ** (feed_q - 0.5)
    eff = abs(np.sum(A * w_f * np.exp(1j * np.radians(ph_f)))) ** 2 / np.sum(A * w_f) ** 2
    miss = trace.focus_miss_mm
    wm = k_all[core] if shape == "sphere" else np.ones(int(core.sum()))
    ax = trace.axial_focus_mm[core]
    ax = ax[np.isfinite(ax)]
    return ApertureFigures(
        rim_fraction=float(rim_fraction),
        phase_error_pp_deg=pp_c, phase_error_rms_deg=rms_c,
        phase_error_pp_full_deg=pp_f, phase_error_rms_full_deg=rms_f,
        focus_spread_mm=float(np.max(np.abs(miss[core]))),
        focus_spread_rms_mm=float(math.sqrt(np.sum(wm * miss[core] ** 2) / np.sum(wm))),
        focus_spread_full_mm=float(np.max(np.abs(miss[hit]))),
        axial_focus_min_mm=float(ax.min()) if ax.size else float("nan"),
        axial_focus_max_mm=float(ax.max()) if ax.size else float("nan"),
        max_exit_tilt_rad=float(np.max(np.abs(trace.exit_tilt_rad[core]))),
        phase_efficiency=float(eff), invalid_rays=int(np.sum(~trace.valid)))
