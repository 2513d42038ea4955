"""The quiet zone of a beam off the lens axis (a feed off the axis: the scan edge of a collimator, the
foci of a bifocal lens), on the meridional cut.

Such a feed breaks the lens's symmetry of revolution; the as-built trace and the patterns carry it as
the meridional cut E(y) taken constant across x (the sagittal aberration is not traced), and so does
this zone. A plane z of the zone is judged over the zone's disc the way a probe scan along the
meridian is, each sample weighted by the chord 2·√(ρ² − y²) of the disc through it (the area it
stands for): the phase with its piston and its linear tilt removed (a tilt only points the beam — the
AUT sees a plane wave from the beam's direction, which is what the range simulates), peak-to-peak and
weighted RMS; the amplitude (dB) fitted by a + b·y + c·y² (the beam's own slope across the zone is
part of the taper), its taper the symmetric part c·ρ² (edge minus centre, the mean of both edges), its
ripple the largest deviation from the fit; the largest centred diameter within the limits after the
tilt over the disc is removed. A beam far enough off the axis leaves part of the disc in its shadow
(GO: no ray there; diffraction: a field ``SHADOW_DB`` or more below the disc's peak): those samples
carry no phase, and the amplitude figures show the shadow.

Fields on a plane z behind the stack (the cut, signed y):
* GO: each ray straight on from its exit point (:func:`go_cut`);
* the fast model: the ideal lens's GO field on the plane at the back of the stack propagated by the
  2-D angular spectrum (:func:`antenna_cad.radiation.testzone.propagate_line`), times, for a stepped
  stack, the thin screen exp(i·k0(n−1)Δd(|y|)) of its excess foam (seed-000 §7.3) lit by a plane wave
  at the beam's angle, its departure from unity diffracted by the same angular spectrum
  (:func:`cut_stack_ratio`).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from antenna_cad.quietzone.stats import PlaneFigures, levels_db
from antenna_cad.radiation.aperture import trapezoid_weights
from antenna_cad.radiation.testzone import propagate_line

SAMPLES_PER_WAVELENGTH = 20      # samples of the cut and of the screen
SHADOW_DB = -20.0                # a sample this far below the disc's peak is in the shadow: no phase


def cut_y_mm(radius_mm: float, wavelength_mm: float) -> np.ndarray:
    """Uniform samples −radius … radius, centre included, at ``SAMPLES_PER_WAVELENGTH`` per λ."""
    half = int(SAMPLES_PER_WAVELENGTH * radius_mm / wavelength_mm) + 1
    return np.linspace(-radius_mm, radius_mm, 2 * half + 1)


def _weights(y: np.ndarray, disc_mm: float) -> np.ndarray:
    return np.sqrt(np.maximum((disc_mm / 2) ** 2 - y * y, 0.0)) * trapezoid_weights(y)


def residual_phase_deg(y_mm, field, disc_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """(y inside the disc and lit, phase in deg with the chord-weighted piston and tilt removed), unwrapped
    outward from the sample nearest the centre; samples in the shadow (``SHADOW_DB`` below the disc's peak)
    carry no phase and are left out."""
    y, e = np.asarray(y_mm, float), np.asarray(field, complex)
    inside = np.abs(y) <= disc_mm / 2 * (1 + 1e-12)
    inside &= np.abs(e) > 10 ** (SHADOW_DB / 20) * np.abs(e[inside]).max(initial=0.0)
    if not inside.any():                                   # the whole disc in the shadow
        return np.zeros(0), np.zeros(0)
    yi, ei = y[inside], e[inside]
    c = int(np.argmin(np.abs(yi)))
    ph = np.degrees(np.angle(ei / ei[c]))
    ph = np.concatenate([np.unwrap(ph[c::-1], period=360.0)[::-1], np.unwrap(ph[c:], period=360.0)[1:]])
    w = _weights(yi, disc_mm)
    fit = np.polynomial.polynomial.polyfit(yi, ph, 1, w=np.sqrt(w))
    return yi, ph - np.polynomial.polynomial.polyval(yi, fit)


def _largest_diameter_mm(y: np.ndarray, lv: np.ndarray, y_lit: np.ndarray, ph: np.ndarray, amplitude_db: float,
                         phase_deg: float) -> float:
    """Twice the largest ρ such that over |y| ≤ ρ the amplitude and the (detilted) phase each span at most
    twice their limit (a shadow inside ρ fails the amplitude)."""
    rho = np.unique(np.abs(y))
    a_lo, a_hi = _spans(np.abs(y), lv, rho)
    p_lo, p_hi = _spans(np.abs(y_lit), ph, rho)
    ok = (a_hi - a_lo <= 2 * amplitude_db) & (p_hi - p_lo <= 2 * phase_deg)
    bad = np.nonzero(~ok)[0]
    last = len(rho) - 1 if len(bad) == 0 else bad[0] - 1
    return 2 * float(rho[last]) if last >= 0 else 0.0


def _spans(distance: np.ndarray, values: np.ndarray, rho: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(min, max) of ``values`` over the samples with distance ≤ each of the increasing ``rho``."""
    o = np.argsort(distance, kind="stable")
    lo, hi = np.minimum.accumulate(values[o]), np.maximum.accumulate(values[o])
    k = np.searchsorted(distance[o], rho, side="right") - 1
    inf = np.full(len(rho), np.inf)
    return np.where(k >= 0, lo[np.maximum(k, 0)], inf), np.where(k >= 0, hi[np.maximum(k, 0)], -inf)


def cut_plane_figures(y_mm, field, disc_mm: float, z_mm: float, amplitude_db: float,
                      phase_deg: float) -> PlaneFigures:
    """Figures of the cut E(y) over the disc |y| ≤ disc/2 (module docstring); the samples must span it."""
    y, e = np.asarray(y_mm, float), np.asarray(field, complex)
    y_lit, ph = residual_phase_deg(y, e, disc_mm)
    inside = np.abs(y) <= disc_mm / 2 * (1 + 1e-12)
    if len(y_lit) < 2 or not np.abs(e[inside]).max() > 0:  # the beam misses the zone: nothing is within limits
        return PlaneFigures(float(z_mm), float(disc_mm), math.inf, math.inf, math.inf, -math.inf, math.inf, 0.0)
    yi, lv = y[inside], levels_db(e[inside])
    w, wl = _weights(yi, disc_mm), _weights(y_lit, disc_mm)
    rho = disc_mm / 2
    basis = np.stack([np.ones_like(yi), yi / rho, (yi / rho) ** 2], 1)
    sw = np.sqrt(w)
    coef = np.linalg.lstsq(basis * sw[:, None], lv * sw, rcond=None)[0]
    ripple = lv - basis @ coef
    return PlaneFigures(float(z_mm), float(disc_mm), float(np.ptp(ph)), float(np.sqrt(np.sum(wl * ph**2) / np.sum(wl))),
                        float(np.max(np.abs(ripple))), float(coef[2]), float(np.ptp(lv)),
                        _largest_diameter_mm(yi, lv, y_lit, ph, amplitude_db, phase_deg))


def go_cut(y_mm, dz, dy, amplitude, path_mm, z_exit_mm: float, z_mm: float, wavelength_mm: float,
           y_out_mm: np.ndarray) -> np.ndarray:
    """GO field on the plane ``z_mm`` at ``y_out_mm`` (zero outside the rays): exit rays (position y on
    the plane ``z_exit_mm``, direction (dz, dy), amplitude, optical path) each carried straight on."""
    t = (z_mm - z_exit_mm) / np.asarray(dz, float)
    y, path = np.asarray(y_mm, float) + t * np.asarray(dy, float), np.asarray(path_mm, float) + t
    o = np.argsort(y)
    y, path, amp = y[o], path[o], np.asarray(amplitude, float)[o]
    k = 2 * math.pi / wavelength_mm
    a = np.interp(y_out_mm, y, amp, left=0.0, right=0.0)
    return a * np.exp(1j * k * np.interp(y_out_mm, y, path))


def cut_fast_fields(y_mm: np.ndarray, ideal_field: np.ndarray, wavelength_mm: float, distances_mm: np.ndarray,
                    y_out_mm: np.ndarray, beam_sin: float,
                    screens: dict[str, tuple[Callable, float, float, float]]) -> dict[str, np.ndarray]:
    """[plane, y] the fast model's cut of the ideal lens and of each stepped variant; ``ideal_field`` on
    the uniform ``y_mm`` at the back of the stack; ``beam_sin``: sin of the beam's angle to the axis;
    ``screens``: variant → (excess foam Δd(r), n, lens radius, screen-to-back-of-stack distance)."""
    ideal = np.array([propagate_line(y_mm, ideal_field, wavelength_mm, d, y_out_mm) for d in distances_mm])
    out = {"ideal": ideal}
    for name, (excess, n, radius, lead) in screens.items():
        out[name] = ideal * cut_stack_ratio(excess, n, radius, wavelength_mm, lead, distances_mm, y_out_mm, beam_sin)
    return out


def cut_stack_ratio(excess: Callable, n: float, radius_mm: float, wavelength_mm: float, lead_mm: float,
                    distances_mm: np.ndarray, y_out_mm: np.ndarray, beam_sin: float) -> np.ndarray:
    """[plane, y] a stepped stack's cut over the ideal lens's by the fast model: the thin screen of its
    excess foam Δd(|y|) ``lead_mm`` before the back of the stack, lit by a plane wave at the beam's angle:
    1 + what the screen's departure from unity diffracts to each plane, over that plane wave there."""
    y = cut_y_mm(radius_mm, wavelength_mm / 2)
    k = 2 * math.pi / wavelength_mm
    kz = k * math.sqrt(1.0 - beam_sin**2)
    departure = np.exp(1j * k * (n - 1.0) * excess(np.abs(y))) - 1.0          # k0(n−1)Δd, seed-000 §7.3
    tilt_in, tilt_out = np.exp(1j * k * beam_sin * y), np.exp(1j * k * beam_sin * np.asarray(y_out_mm, float))
    out = []
    for d in lead_mm + np.asarray(distances_mm, float):
        spread = propagate_line(y, departure * tilt_in, wavelength_mm, d, y_out_mm)
        out.append(1.0 + spread / (tilt_out * np.exp(1j * kz * d)))
    return np.array(out)
