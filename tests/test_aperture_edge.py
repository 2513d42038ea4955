"""The GO aperture reaches the rim: a uniform aperture resampled from a trace that stops just inside
it keeps its closed-form efficiency, directivity and beamwidth; and the seed-000 §7.4 reference cases
on the traced aperture itself (case 11: flat on focus for any D, f, εr; case 13: the ∥ and ⊥
amplitudes of XPS differ by at most 0.3 %)."""

import math

import numpy as np
import pytest
from scipy.special import j1
from scipy.optimize import brentq

from antenna_cad.asbuilt.lens import Lens, trace_lens
from antenna_cad.asbuilt.patterns import exit_field, resampled
from antenna_cad.radiation.aperture import bor_aperture, pattern_figures
from antenna_cad.raytrace.collimator import front_face, trace_collimator
from antenna_cad.raytrace.trace2d import Interface, transmitted_amplitude
from antenna_cad.synthesis.collimator import thickness_mm

LAM = 299.792458 / 10.0


def _uniform(R: float, reach: float):
    """A uniform, flat-phase trace over |y| ≤ reach·R, resampled onto the aperture and revolved."""
    y = np.linspace(-reach * R, reach * R, 1201)
    grid, e = resampled(y, np.ones_like(y), np.zeros_like(y), R, LAM)
    half = grid >= 0
    return grid, e, bor_aperture(grid[half], e[half], LAM, R)


def test_uniform_aperture_traced_to_0999_R_keeps_its_closed_forms():
    """Uniform disc Ø500 mm at λ 30 mm: η_taper = 1 (within 1e-4), D = (πD/λ)² (within 0.001 dB),
    HPBW = 2·asin(x½/(kR)) with J1(x)/x at half power, x½ = 1.6163 (within 0.05 %)."""
    R = 250.0
    _, _, ap = _uniform(R, 0.999)
    pf = pattern_figures(ap)
    assert pf.efficiency.taper == pytest.approx(1.0, abs=1e-4)
    assert pf.efficiency.phase == pytest.approx(1.0, abs=1e-6)
    assert pf.directivity_dbi == pytest.approx(20 * math.log10(math.pi * 2 * R / LAM), abs=1e-3)
    x_half = brentq(lambda x: (2 * j1(x) / x) ** 2 - 0.5, 1.0, 2.5)
    hpbw = math.degrees(2 * math.asin(x_half / (2 * math.pi / LAM * R)))
    assert pf.beam.hpbw_deg == pytest.approx(hpbw, rel=5e-4)


def test_a_shadow_wider_than_half_a_wavelength_stays_dark():
    """Only the tracer's aim margin is held to the rim: a trace that stops 2 λ short leaves zeros."""
    R = 250.0
    grid, e, _ = _uniform(R, 1 - 2 * LAM / R)
    assert np.all(e[np.abs(grid) > R - 2 * LAM + 1e-9] == 0)
    assert np.all(np.abs(e[np.abs(grid) < R - 2 * LAM - 1e-9]) == 1)


def _collimator(D: float, f: float, eps_r: float, gap: float = 100.0) -> Lens:
    n = eps_r ** 0.5
    back = thickness_mm(D, f, n)
    return Lens(radius_mm=D / 2, eps_r=eps_r, tan_delta=0.0, wavelength_mm=LAM, budget_deg=22.5,
                antenna_z_mm=back + gap, feed=(-f, 0.0),
                faces=lambda m: (front_face(f, n, m), Interface.plane(back, 1.0)))


@pytest.mark.parametrize("D, f, eps_r", [(500, 4000, 1.047), (1000, 6000, 1.047), (1100, 25000, 1.047),
                                         (120, 300, 2.08), (300, 400, 1.3)])
def test_case_11_on_focus_flat_to_the_rim(D, f, eps_r):
    """Seed-000 §7.4 case 11 for any D, f, εr: traced to the rim, the on-focus p-p phase is < 0.01°,
    and so is the phase of the resampled aperture field the patterns use (rim included)."""
    lens = _collimator(D, f, eps_r)
    tr = trace_collimator(focal_length_mm=f, n=lens.n, diameter_mm=D, back_z_mm=float(lens.back_z(0.0)),
                          antenna_z_mm=lens.antenna_z_mm, wavelength_mm=LAM, margin=1.0)
    assert tr.y_mm.max() == pytest.approx(D / 2, abs=1e-6)
    assert tr.peak_to_peak_deg() < 0.01
    ef = exit_field(lens, lens.faces(lens.n), lens.feed, float(lens.back_z(0.0)))
    lit = np.abs(ef.field) > 0
    assert lit[0] and lit[-1]                                      # the rim samples are lit
    assert np.ptp(np.unwrap(np.angle(ef.field[lit]))) < math.radians(0.01)


def test_case_13_parallel_and_perpendicular_amplitudes_of_xps():
    """Seed-000 §7.4 case 13 (§4.4, L1109): XPS lens f 6 m, D 1 m — the ∥ and ⊥ transmitted amplitudes
    differ by at most 0.3 % over the aperture (the digest reproduces 0.27 %; the rim sets it)."""
    lens = _collimator(1000.0, 6000.0, 1.047)
    tr, keep = trace_lens(lens, lens.faces(lens.n), lens.feed)
    perp, par = (transmitted_amplitude(tr, LAM, 0.0, pol)[keep] for pol in ("perp", "par"))
    diff = np.max(np.abs(par - perp) / perp)
    assert 0.002 < diff <= 0.003
