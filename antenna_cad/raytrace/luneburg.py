"""Feed fans through Luneburg lenses and their aperture figures (seed-002 §2.1b, §2.5).

A feed on the focal circle of radius b, scanned by ``scan_rad`` from −Z, radiates a cos^q θ
amplitude pattern toward the lens centre (beam direction u = (cos α, sin α) in (z, y)). The
meridional fan is sampled uniformly over the aperture on both sides of the feed axis, each ray
weighted by the feed power it carries (sphere: cos^2q θ · |sin θ| dθ, half an annulus per ray;
cylinder: cos^2q θ dθ). Each ray is traced by a ``tracer(origins,
directions) -> MediaTrace`` (:mod:`media` or :mod:`graded`). The aperture field is taken on the
exit surface and referred to the plane u·p = 2R along the beam (phase OPL_exit + 2R − u·p_exit at
s = v·p_exit: the field that radiates the main beam, as the design's own figures of seed-002
§2.1b), so tilted rim rays do not cross on their way to the plane. Rays that do not leave
forward within the aperture |s| ≤ R (trapped along the surface, or out through a boss below the
rim) are lost power. From the optical paths: the
aperture phase with its linear tilt removed
(``verification.detrended``; the tilt is a beam squint), its p-p and RMS, the Ruze loss
exp(−σ²), the GO efficiency spillover × taper × phase, the amplitude taper, and the feed move
along its own axis that minimises the RMS (focus shift).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy import optimize

from antenna_cad.raytrace.media import MediaTrace, trace_media
from antenna_cad.verification import detrended

Tracer = Callable[[np.ndarray, np.ndarray], MediaTrace]
SURFACE_GAP_MM = 1e-3


def launch_angles(b_over_R: float, q: float, shape: str, n_rays: int) -> tuple[np.ndarray, np.ndarray]:
    """Launch angles θ = asin(k/b) at ``n_rays`` midpoints uniform in the impact parameter
    k ∈ (−R, R) (uniform over the aperture, so the rim is resolved), and each ray's share of the
    feed power: |F|² |sin θ| dθ (sphere, half an annulus per ray) or |F|² dθ (cylinder), F = cos^q θ."""
    k = (np.arange(n_rays) + 0.5) / n_rays * 2.0 - 1.0                       # in units of R
    th = np.arcsin(k / b_over_R)
    dtheta = 2.0 / n_rays / np.sqrt(b_over_R**2 - k**2)
    w = np.cos(th) ** (2 * q) * dtheta * (np.abs(np.sin(th)) if shape == "sphere" else 1.0)
    return th, w / w.sum()


@dataclass(frozen=True)
class Fan:
    theta_rad: np.ndarray      # launch angle from the feed axis (signed)
    weight: np.ndarray         # share of the power the feed sends into the lens
    impact_mm: np.ndarray      # distance of the launched ray's line from the lens centre
    s_mm: np.ndarray           # exit point along v = (−sin α, cos α)
    opl_mm: np.ndarray         # feed → exit point, then along u to the plane u·p = 2R
    ok: np.ndarray
    trace: MediaTrace
    feed_zy_mm: np.ndarray


def feed_fan(tracer: Tracer, radius_mm: float, b_mm: float, q: float, shape: str, *, scan_rad: float = 0.0,
             n_rays: int = 96, axial_mm: float = 0.0, lateral_mm: float = 0.0) -> Fan:
    """Trace the feed fan. The feed sits at −(b + axial)·u + lateral·v; the fan is aimed as for
    the nominal feed (the feed's own axis does not turn with a small position error). A feed on
    the surface (b = R) is placed ``SURFACE_GAP_MM`` outside it, so its rays refract into the
    outer layer as from any feed in air."""
    u = np.array([math.cos(scan_rad), math.sin(scan_rad)])
    v = np.array([-u[1], u[0]])
    feed = -(max(b_mm, radius_mm + SURFACE_GAP_MM) + axial_mm) * u + lateral_mm * v
    th, w = launch_angles(b_mm / radius_mm, q, shape, n_rays)
    dirs = np.stack([np.cos(scan_rad + th), np.sin(scan_rad + th)], axis=1)
    tr = tracer(np.tile(feed, (len(th), 1)), dirs)
    s = tr.exit_zy @ v
    ok = tr.ok & (tr.direction @ u > 0) & (np.linalg.norm(tr.exit_zy - feed, axis=1) > 0) & \
        (np.abs(s) <= radius_mm * (1 + 1e-9))
    opl = tr.exit_opl + (2.0 * radius_mm - tr.exit_zy @ u)
    impact = np.abs(feed[0] * dirs[:, 1] - feed[1] * dirs[:, 0])
    return Fan(th, w, impact, np.where(ok, s, np.nan), np.where(ok, opl, np.nan), ok, tr, feed)


TAPER_BINS = 10
CORE = 0.95
RUZE_DB_PER_RAD2 = 10 * math.log10(math.e)


@dataclass(frozen=True)
class FanFigures:
    phase_pp_deg: float        # core
    phase_rms_deg: float       # core, power weighted
    phase_rms_full_deg: float  # every ray that reaches the aperture
    gain_loss_db: float        # Ruze of the core RMS: −10 log10 exp(−σ²)
    efficiency: float          # spillover × ideal taper × phase |⟨e^{jφ}⟩|² (core) × power kept
    amplitude_taper_db: float  # power density in the outer tenth of the aperture radius vs the inner tenth
    lost_fraction: float       # feed power in rays that do not leave the lens forward
    squint_deg: float          # the removed linear phase tilt as a beam squint
    phase_deg: np.ndarray      # detrended, per kept core ray (sorted by s)
    s_mm: np.ndarray


def _flat_phase(s: np.ndarray, w: np.ndarray, phase_deg: np.ndarray) -> np.ndarray:
    """Phase with the linear tilt (``verification.detrended``) and the weighted mean removed."""
    flat = detrended(s, phase_deg)
    return flat - np.sum(w * flat) / w.sum()


def _rms(w: np.ndarray, flat: np.ndarray) -> float:
    return float(math.sqrt(np.sum(w * flat**2) / w.sum()))


def fan_figures(fan: Fan, wavelength_mm: float, radius_mm: float, shape: str, taper_efficiency: float,
                spillover: float) -> FanFigures:
    """Aperture figures of a traced fan (module docstring), power weighted. Phase figures cover
    the core: rays launched at the inner ``CORE``·R of the lens (impact parameter), as the
    design's own figures — rays launched into the rim sliver skim thin outer layers at grazing
    incidence, where GO gives errors of many wavelengths that do not shrink with the layer count
    and fold back across the aperture (``phase_rms_full_deg`` keeps them). The taper is the power
    density (weighted CDF over |s|) on the outer and inner of ``TAPER_BINS`` equal annuli (strips
    for the cylinder): stepped lenses fold their GO aperture and leave sub-λ gaps, so single ray
    tubes would be noise."""
    ok = fan.ok
    order = np.argsort(fan.s_mm[ok])
    s, w = fan.s_mm[ok][order], fan.weight[ok][order]
    core = fan.impact_mm[ok][order] <= CORE * radius_mm
    phase = np.degrees(2 * np.pi * fan.opl_mm[ok][order] / wavelength_mm)
    flat = _flat_phase(s[core], w[core], phase[core])
    tilt = np.radians(np.polyfit(s[core], phase[core], 1)[0]) * wavelength_mm / (2 * np.pi)   # d(path)/ds
    sigma = np.radians(_rms(w[core], flat))
    kept = float(w.sum() / fan.weight.sum())
    eta_phase = abs(np.sum(w[core] * np.exp(1j * np.radians(flat))) / w[core].sum()) ** 2
    by_r = np.argsort(np.abs(s))
    r = np.minimum(np.abs(s), radius_mm)[by_r]
    cum = np.cumsum(w[by_r]) - 0.5 * w[by_r]
    edges = np.linspace(0.0, radius_mm, TAPER_BINS + 1)
    cdf = np.interp(edges, np.concatenate([[0.0], r, [radius_mm]]), np.concatenate([[0.0], cum, [w.sum()]]))
    density = np.diff(cdf) / (np.diff(edges**2) if shape == "sphere" else np.diff(edges))
    taper = 10 * math.log10(max(density[-1], 1e-300) / max(density[0], 1e-300))
    return FanFigures(float(np.ptp(flat)), float(math.degrees(sigma)), _rms(w, _flat_phase(s, w, phase)),
                      float(RUZE_DB_PER_RAD2 * sigma**2), float(spillover * taper_efficiency * eta_phase * kept),
                      taper, 1.0 - kept, float(math.degrees(math.asin(max(-1.0, min(1.0, tilt))))), flat, s[core])


def added_phase_rms(fan: Fan, delta_opl_mm: np.ndarray, wavelength_mm: float, radius_mm: float) -> float:
    """Power-weighted RMS (deg) of an optical-path change over the fan's core aperture, linear
    tilt removed (a squint, not a loss). For a first-order perturbation the rays stay put, so the
    change is compared ray by ray; independent errors add their Ruze losses."""
    ok = fan.ok & np.isfinite(delta_opl_mm) & (fan.impact_mm <= CORE * radius_mm)
    w = fan.weight[ok]
    return _rms(w, _flat_phase(fan.s_mm[ok], w, np.degrees(2 * np.pi * delta_opl_mm[ok] / wavelength_mm)))


def feed_move_opl(fan: Fan, axial_mm: float, lateral_mm: float) -> np.ndarray:
    """First-order optical-path change of each ray when the feed moves ``axial_mm`` away from
    the lens along its axis and ``lateral_mm`` across it: −δ·t̂ at the source (Hamilton's
    characteristic: ∂L/∂source = −n t̂), t̂ = cos θ·u + sin θ·v the ray's launch direction."""
    return axial_mm * np.cos(fan.theta_rad) - lateral_mm * np.sin(fan.theta_rad)


def focus_shift(fan: Fan, wavelength_mm: float, radius_mm: float) -> float:
    """Feed move along its axis (mm, + away from the lens) that minimises the core phase RMS, to
    first order: the move adds a·cos θ to each ray (:func:`feed_move_opl`), so the weighted,
    tilt-free variance is a quadratic in a with a closed-form minimum. Callers trace the fan
    again there to report the RMS actually reached."""
    ok = fan.ok & (fan.impact_mm <= CORE * radius_mm)
    s, w = fan.s_mm[ok], fan.weight[ok]
    phase = _flat_phase(s, w, np.degrees(2 * np.pi * fan.opl_mm[ok] / wavelength_mm))
    basis = _flat_phase(s, w, np.degrees(2 * np.pi * np.cos(fan.theta_rad[ok]) / wavelength_mm))
    return float(-np.sum(w * phase * basis) / np.sum(w * basis * basis))


OPL_BATCH = 10_000       # straight segments traced at a time by first_order_opl


def first_order_opl(medium, trace: MediaTrace, extend_mm: float = 0.0) -> np.ndarray:
    """Optical path change when ``medium`` replaces the medium ``trace`` went through: ∫n ds in
    ``medium`` along the traced (unperturbed) polylines minus their own optical path — exact to
    first order in the index change (Fermat). The polylines are continued ``extend_mm`` in air
    along their last direction (where ``medium`` may still hold material). All segments of all
    rays go through ``medium`` as straight lines, in batches of ``OPL_BATCH``. Used for sheet staircases finer than
    the Fresnel zone, whose risers do not act as GO facets, and for tolerance perturbations."""
    points = np.concatenate([trace.points, (trace.end + extend_mm * trace.direction)[None]])
    start, seg = points[:-1].reshape(-1, 2), np.diff(points, axis=0).reshape(-1, 2)
    length = np.linalg.norm(seg, axis=1)
    move = np.flatnonzero(length > 0)
    opl = np.zeros(len(length))
    for i in range(0, len(move), OPL_BATCH):        # batches bound the tracer's per-segment arrays
        m = move[i:i + OPL_BATCH]
        opl[m] = trace_media(medium, start[m], seg[m] / length[m, None], stop_mm=length[m], straight=True).opl
    return opl.reshape(len(points) - 1, -1).sum(axis=0) - extend_mm - trace.opl
