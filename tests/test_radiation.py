"""Radiation models against closed forms and the seed digest."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize, special

from antenna_cad.radiation.aperture import (beam_figures, bor_aperture, directivity_dbi, grid_aperture, line_cut,
                                            pattern_figures)
from antenna_cad.radiation.distortion import Aut, aut_cuts, integral_errors, thresholds
from antenna_cad.radiation.testzone import largest_test_zone, propagate_bor, propagate_line

LAM = 30.0


# ------------------------------------------------------------------ apertures against closed forms

def test_uniform_circular_aperture():
    """HPBW 1.029 λ/D, first sidelobe −17.57 dB, directivity (πD/λ)² (D = 40 λ)."""
    D = 40 * LAM
    r = np.linspace(0.0, D / 2, 801)
    pf = pattern_figures(bor_aperture(r, np.ones_like(r), LAM))
    assert pf.beam.hpbw_deg == pytest.approx(math.degrees(1.029 * LAM / D), rel=2e-4)
    assert pf.beam.sll_db == pytest.approx(-17.57, abs=0.01)
    assert pf.directivity_dbi == pytest.approx(10 * math.log10((math.pi * D / LAM) ** 2), abs=1e-3)
    assert pf.beam.theta_deg == pytest.approx(0.0, abs=1e-6)


def _lambda_n(n: int, x: np.ndarray) -> np.ndarray:
    """Λ_n(x) = 2^n n! J_n(x)/x^n (Λ_n(0) = 1)."""
    x = np.where(np.abs(x) < 1e-12, 1e-12, x)
    return 2**n * math.factorial(n) * special.jv(n, x) / x**n


@pytest.mark.parametrize("pedestal, p", [(0.0, 1), (0.0, 2), (0.3, 1), (0.5, 2)])
def test_parabolic_on_pedestal(pedestal, p):
    """A = C + (1−C)(1 − (r/R)²)^p against its closed-form pattern C·Λ1 + (1−C)/(p+1)·Λ_{p+1}
    (half-power and first-sidelobe found on the closed form independently) and the closed-form
    taper efficiency; C = 0, p = 1 and 2 also against the textbook 72.6 / 84.2 λ/D deg, −24.6 /
    −30.6 dB, 0.75 / 0.56."""
    C, R = pedestal, 20 * LAM
    r = np.linspace(0.0, R, 801)
    pf = pattern_figures(bor_aperture(r, C + (1 - C) * (1 - (r / R) ** 2) ** p, LAM))
    k = 2 * math.pi / LAM

    def closed(u):
        x = k * R * np.asarray(u, float)
        return C * _lambda_n(1, x) + (1 - C) / (p + 1) * _lambda_n(p + 1, x)

    f0 = closed(0.0)
    half = optimize.brentq(lambda u: closed(u) ** 2 - 0.5 * f0**2, 1e-6, 3 / (k * R))
    u = np.linspace(1e-4, 0.2, 40001)
    f = np.abs(closed(u))
    first_min = np.argmax(np.diff(f) > 0)
    sll = 20 * math.log10(f[first_min:].max() / f0)
    eta = (C + (1 - C) / (p + 1)) ** 2 / (C**2 + 2 * C * (1 - C) / (p + 1) + (1 - C) ** 2 / (2 * p + 1))
    assert pf.beam.hpbw_deg == pytest.approx(2 * math.degrees(math.asin(half)), rel=1e-4)
    assert pf.beam.sll_db == pytest.approx(sll, abs=0.01)
    assert pf.efficiency.taper == pytest.approx(eta, abs=1e-4)
    if C == 0.0:
        textbook = {1: (72.6, -24.6, 0.75), 2: (84.2, -30.6, 0.56)}[p]
        assert pf.beam.hpbw_deg * 2 * R / LAM == pytest.approx(textbook[0], abs=0.2)     # deg per λ/D
        assert pf.beam.sll_db == pytest.approx(textbook[1], abs=0.05)
        assert pf.efficiency.taper == pytest.approx(textbook[2], abs=5e-3)


def test_uniform_line_aperture_is_a_sinc():
    L = 30 * LAM
    y = np.linspace(-L / 2, L / 2, 1201)
    cut = line_cut(y, np.ones_like(y), LAM)
    u = np.linspace(-0.3, 0.3, 301)
    assert np.allclose(np.abs(cut(u)), np.abs(L * np.sinc(L * u / LAM)), atol=1e-4 * L)
    b = beam_figures(cut)
    assert b.hpbw_deg == pytest.approx(math.degrees(2 * math.asin(0.44295 * LAM / L)), rel=2e-4)
    assert b.sll_db == pytest.approx(-13.26, abs=0.01)


def test_tilted_line_aperture_points_the_beam():
    """A linear phase e^{jk y sin θ0} (fields arrive by the optical path, e^{−jωt}) points the beam to θ0."""
    L, theta0 = 20 * LAM, 12.0
    y = np.linspace(-L / 2, L / 2, 801)
    b = beam_figures(line_cut(y, np.exp(1j * 2 * math.pi / LAM * y * math.sin(math.radians(theta0))), LAM))
    assert b.theta_deg == pytest.approx(theta0, abs=1e-6)


def test_body_of_revolution_and_grid_agree():
    """The Hankel path and the 2-D direct sums give the same disc (grid λ/8)."""
    R = 8 * LAM
    r = np.linspace(0.0, R, 401)
    field = lambda rho: 0.4 + 0.6 * (1 - (rho / R) ** 2)            # noqa: E731
    bor = pattern_figures(bor_aperture(r, field(r), LAM))
    g = np.linspace(-R, R, 2 * int(8 * R / LAM) + 1)
    X, Y = np.meshgrid(g, g)
    rho = np.hypot(X, Y)
    grid = pattern_figures(grid_aperture(g, g, np.where(rho <= R, field(np.minimum(rho, R)), 0.0), LAM, math.pi * R**2))
    assert grid.beam.hpbw_deg == pytest.approx(bor.beam.hpbw_deg, rel=0.01)
    assert grid.beam.sll_db == pytest.approx(bor.beam.sll_db, abs=0.2)
    assert grid.directivity_dbi == pytest.approx(bor.directivity_dbi, abs=0.05)


def test_phase_error_lowers_directivity_by_its_phase_efficiency():
    """A random-free quadratic error: η_phase = |⟨e^{jφ}⟩|² over the aperture, exact."""
    R = 15 * LAM
    r = np.linspace(0.0, R, 1201)
    phi = math.radians(90.0) * (r / R) ** 2
    pf = pattern_figures(bor_aperture(r, np.exp(1j * phi), LAM))
    mean = np.trapezoid(np.exp(1j * phi) * 2 * r, r) / R**2
    assert pf.efficiency.phase == pytest.approx(abs(mean) ** 2, rel=1e-4)
    assert pf.directivity_dbi == pytest.approx(directivity_dbi(pf.efficiency, math.pi * R**2, LAM))


# ------------------------------------------------------------------ propagation and the test zone

def test_disc_on_axis_field_is_rayleigh_sommerfeld():
    """Uniform disc, exact on-axis field e^{jkz} − z/√(z²+a²)·e^{jk√(z²+a²)} (the hardest case:
    the edge wave focuses on the axis) to 2 % at λ/40 sampling."""
    a, k = 300.0, 2 * math.pi / LAM
    r = np.linspace(0.0, a, int(40 * a / LAM) + 1)
    for z in (100.0, 1000.0):
        exact = np.exp(1j * k * z) - z / math.hypot(z, a) * np.exp(1j * k * math.hypot(z, a))
        assert abs(propagate_bor(r, np.ones_like(r), LAM, z, np.array([0.0]))[0] - exact) < 0.02


def test_gaussian_beam_spreads_as_paraxial_optics():
    w0, z = 10 * LAM, 50 * LAM
    zr = math.pi * w0**2 / LAM
    w = w0 * math.sqrt(1 + (z / zr) ** 2)
    r = np.linspace(0.0, 4 * w0, 600)
    e = propagate_bor(r, np.exp(-(r / w0) ** 2), LAM, z, np.array([0.0, w0]))
    assert abs(e[0]) == pytest.approx(w0 / w, rel=2e-3)
    assert abs(e[1] / e[0]) == pytest.approx(math.exp(-(w0 / w) ** 2), rel=3e-3)
    y = np.linspace(-4 * w0, 4 * w0, 1201)
    e = propagate_line(y, np.exp(-(y / w0) ** 2), LAM, z, np.array([0.0, w0]))
    assert abs(e[0]) == pytest.approx(math.sqrt(w0 / w), rel=2e-3)
    assert abs(e[1] / e[0]) == pytest.approx(math.exp(-(w0 / w) ** 2), rel=3e-3)


def test_test_zone_of_a_known_ripple():
    """Amplitude 1 − (y/300)² with a 30° tilt (removed): ±1 dB is reached where it is 2 dB down;
    a cubic phase: the zone ends inside the 11.25° point of the raw cubic."""
    y = np.linspace(-500.0, 500.0, 2001)
    amp = 1 - (y / 300.0) ** 2
    tz = largest_test_zone(y, amp * np.exp(1j * np.radians(30 * y / 500)), amplitude_db=1.0, phase_deg=90.0)
    edge = 300.0 * math.sqrt(1 - 10 ** (-2 / 20))               # −2 dB p-p = ±1 dB
    assert tz.diameter_mm == pytest.approx(2 * edge, abs=1.0)
    cubic = np.exp(1j * np.radians(11.25 * (y / 100.0) ** 3))
    tz = largest_test_zone(y, cubic, amplitude_db=1.0, phase_deg=11.25)
    assert 100.0 < tz.diameter_mm / 2 < 160.0                    # the tilt fit absorbs part of the cubic


# ------------------------------------------------------------------ seed-000 (1.19)–(1.24)

DIGEST_SUM = (1.32e-3, 5.3e-4, 1.5e-4, 4.4e-5)       # seed-000 §5.3 [OURS], k = 0..3
TABLE_1_6_SUM = (9.524e-4, 3.801e-4, 1.093e-4, 3.056e-5)


@pytest.mark.parametrize("k", range(4))
def test_quadratic_threshold_sum_pattern(k):
    """The 22.5° quadratic threshold of the sum pattern, 1-D AUT: the digest's reproduction of
    Table 1.6 (its conventions) to 5 %, and the table itself at the documented ≈ 1.4× (the seed's
    conventions are unrecoverable, §5.3: Tables 1.6/1.7 are not regression targets)."""
    s, _ = thresholds(Aut(LAM, 1000.0, False, k), LAM)
    assert s.total == pytest.approx(DIGEST_SUM[k], rel=0.05)
    assert 1.3 < s.total / TABLE_1_6_SUM[k] < 1.5
    assert s.main + s.side == pytest.approx(s.total)


def test_integral_errors_vanish_for_the_ideal_field_and_ignore_gain():
    aut = Aut(600.0, 600.0, True, 1)
    x, y = aut.grid(LAM)
    ideal = aut_cuts(aut, x, y, np.ones((len(y), len(x))), LAM)
    scaled = aut_cuts(aut, x, y, 0.3 * np.ones((len(y), len(x))), LAM)
    for a, b, diff in zip(scaled, ideal, (False, True)):
        assert integral_errors(a, b, diff).total < 1e-20


def test_difference_pattern_threshold_grows_with_the_error():
    aut = Aut(LAM, 900.0, False, 0)
    small, large = thresholds(aut, LAM, 10.0)[1], thresholds(aut, LAM, 22.5)[1]
    assert 0 < small.total < large.total < thresholds(aut, LAM, 45.0)[1].total
