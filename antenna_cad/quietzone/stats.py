"""Figures of one plane of the quiet zone, over the whole disc including the axis.

A field E(r) of a body of revolution on increasing radii r (any spacing; GO rays or a propagated
field) is judged over the disc r ≤ ρ the way a probe scan is: the phase with its piston removed (the
tilt of a body of revolution on its axis is zero by symmetry), peak-to-peak and area-weighted RMS
(weight r·dr); the amplitude in dB split into a taper (the best area-weighted fit a + b·r², edge minus
centre) and a ripple (the largest deviation from that fit, ±); and the largest centred diameter over
which the amplitude and the phase stay within ± their limits about their mid-range (peak-to-peak ≤ 2×),
the definition the single-plane test zone used (seed-000 §4.1: 22.5° p-p).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.radiation.aperture import trapezoid_weights

DARK = 1e-6           # samples below this fraction of the peak amplitude carry no phase (a shadow)


@dataclass(frozen=True)
class PlaneFigures:
    """One plane ``z_mm`` (behind the back of the stack) over the disc of diameter ``disc_mm``."""
    z_mm: float
    disc_mm: float
    phase_p2p_deg: float
    phase_rms_deg: float
    amplitude_ripple_db: float
    amplitude_taper_db: float
    amplitude_p2p_db: float
    diameter_mm: float            # the largest centred diameter within the limits on this plane


def _unwrapped_deg(field: np.ndarray) -> np.ndarray:
    """Phase (deg) unwrapped outward from the axis, relative to the axis."""
    return np.degrees(np.unwrap(np.angle(field / field[0])))


def levels_db(field: np.ndarray) -> np.ndarray:
    """Amplitude in dB to the peak, floored at :data:`DARK`."""
    amp = np.abs(field)
    return 20 * np.log10(np.maximum(amp / amp.max(), DARK))


def largest_diameter_mm(r_mm, field, amplitude_db: float, phase_deg: float) -> float:
    """Twice the largest radius ρ such that over r ≤ ρ the amplitude (dB) and the phase each span at
    most twice their limit (± about mid-range)."""
    r, e = np.asarray(r_mm, float), np.asarray(field, complex)
    a, p = levels_db(e), _unwrapped_deg(e)
    span_a = np.maximum.accumulate(a) - np.minimum.accumulate(a)
    span_p = np.maximum.accumulate(p) - np.minimum.accumulate(p)
    ok = (span_a <= 2 * amplitude_db) & (span_p <= 2 * phase_deg)
    bad = np.nonzero(~ok)[0]
    last = len(r) - 1 if len(bad) == 0 else bad[0] - 1
    return 2 * float(r[last]) if last >= 0 else 0.0


def plane_figures(r_mm, field, disc_mm: float, z_mm: float, amplitude_db: float, phase_deg: float) -> PlaneFigures:
    """Figures of the field E(r) over the disc r ≤ disc/2 (module docstring); the samples must start on
    the axis (r = 0) and reach the disc's rim."""
    r, e = np.asarray(r_mm, float), np.asarray(field, complex)
    inside = r <= disc_mm / 2 * (1 + 1e-12)
    ri, ei = r[inside], e[inside]
    w = ri * trapezoid_weights(ri)
    ph = _unwrapped_deg(ei)
    ph -= np.sum(w * ph) / np.sum(w)
    lv = levels_db(ei)
    basis = np.stack([np.ones_like(ri), (ri / ri[-1]) ** 2], 1)
    sw = np.sqrt(w)
    coef = np.linalg.lstsq(basis * sw[:, None], lv * sw, rcond=None)[0]
    ripple = lv - basis @ coef
    return PlaneFigures(float(z_mm), float(disc_mm), float(np.ptp(ph)), float(np.sqrt(np.sum(w * ph**2) / np.sum(w))),
                        float(np.max(np.abs(ripple))), float(coef[1]), float(np.ptp(lv)),
                        largest_diameter_mm(r, e, amplitude_db, phase_deg))
