"""The tolerance budget's εr and thickness terms as first-order perturbations along the rays of the
smooth lens, against a brute-force retrace of the perturbed smooth lens; the aperture efficiency of
fields with closed forms."""

import numpy as np
import pytest

from antenna_cad.asbuilt.lens import Lens, _scaled, trace_lens
from antenna_cad.quietzone.tolerance import added_figures, aperture_efficiency, efficiency_loss_db, \
    eps_r_added_deg, thickness_added_deg
from antenna_cad.raytrace.collimator import ApertureTrace, front_face
from antenna_cad.raytrace.trace2d import Interface
from antenna_cad.synthesis.collimator import profile_z_mm

EPS_R, R, F = 1.12, 210.0, 1500.0            # the lens of the quiet-zone study: Ø420 mm, F 1500 mm, 12 GHz
LAM = 299.792458 / 12.0
N = EPS_R ** 0.5
BACK = float(profile_z_mm(R, F, N)) + 5.0


def _lens() -> Lens:
    return Lens(radius_mm=R, eps_r=EPS_R, tan_delta=0.0, wavelength_mm=LAM, budget_deg=22.5,
                antenna_z_mm=BACK + 2 * LAM, feed=(-F, 0.0),
                faces=lambda n_lens: (front_face(F, N, n_lens), Interface.plane(BACK, 1.0)))


def _retraced_deg(lens: Lens, faces) -> tuple[np.ndarray, np.ndarray]:
    """(y, added phase deg) of the perturbed smooth lens retraced, against the nominal, on the nominal rays' y."""
    nominal, perturbed = (ApertureTrace.from_trace(*_traced(lens, m)) for m in (lens.faces(lens.n), faces))
    order = np.argsort(perturbed.y_mm)
    moved = np.interp(nominal.y_mm, perturbed.y_mm[order], perturbed.phase_deg()[order])
    return nominal.y_mm, moved - nominal.phase_deg()


def _traced(lens: Lens, medium):
    tr, keep = trace_lens(lens, medium, lens.feed)
    return tr, LAM, keep


@pytest.mark.parametrize("delta", [0.01, -0.01])
def test_eps_r_term_matches_a_retrace_of_the_perturbed_smooth_lens(delta):
    """εr ± 0.01: the first-order path change Δn·L along the smooth lens's rays gives the p-p and RMS of
    a brute-force retrace of the smooth lens with the new index within 2 % (measured: < 0.5 %)."""
    lens = _lens()
    tr, keep = trace_lens(lens, lens.faces(lens.n), lens.feed)
    y = tr.points[-1][keep, 1]
    first = added_figures(y, eps_r_added_deg(tr, keep, lens.n, delta, LAM))
    y_b, brute = _retraced_deg(lens, lens.faces((EPS_R + delta) ** 0.5))
    exact = added_figures(y_b, brute)
    assert first[0] > 1.0                       # a real figure: several degrees p-p
    assert first == pytest.approx(exact, rel=0.02)


@pytest.mark.parametrize("stretch_mm", [0.5, -0.5])
def test_thickness_term_matches_a_retrace_of_the_stretched_smooth_lens(stretch_mm):
    """Thickness ± 0.5 mm (the lens stretched about its front vertex): the faces moved along the rays
    against a retrace of the stretched lens, within 2 %."""
    lens = _lens()
    z0 = float(lens.front_z(0.0))
    eps = stretch_mm / (BACK - z0)
    tr, keep = trace_lens(lens, lens.faces(lens.n), lens.feed)
    y = tr.points[-1][keep, 1]
    first = added_figures(y, thickness_added_deg(tr, keep, 2, z0, eps, LAM))
    y_b, brute = _retraced_deg(lens, tuple(_scaled(f, z0, 1 + eps) for f in lens.faces(lens.n)))
    exact = added_figures(y_b, brute)
    assert first[0] > 0.1
    assert first == pytest.approx(exact, rel=0.02)


def test_added_figures_remove_tilt_and_piston_and_weight_by_area():
    y = np.linspace(-1.0, 1.0, 2001)
    assert added_figures(y, 3.0 + 5.0 * y) == pytest.approx((0.0, 0.0), abs=1e-9)
    p2p, rms = added_figures(y, 10.0 * y ** 2)
    # 10 ρ² over the unit disc: p-p 10; mean 5, area-weighted RMS 10·√(1/3 − 1/4) = 10/√12
    assert p2p == pytest.approx(10.0, rel=1e-3) and rms == pytest.approx(10 / 12 ** 0.5, rel=1e-3)


def test_aperture_efficiency_of_uniform_and_tapered_fields():
    """Uniform disc: 1; the parabolic taper 1 − ρ²: 3/4; (1 − ρ²)²: 5/9 (|∫|²/(A∫|E|²) in closed form);
    a uniform field with a quadratic phase of 30° p-p loses what the closed form says."""
    r = np.linspace(0.0, 1.0, 4001)
    assert aperture_efficiency(r, np.ones_like(r)) == pytest.approx(1.0, abs=1e-12)
    assert aperture_efficiency(r, 1 - r ** 2) == pytest.approx(0.75, rel=1e-6)
    assert aperture_efficiency(r, (1 - r ** 2) ** 2) == pytest.approx(5 / 9, rel=1e-6)
    a = np.radians(30.0)
    closed = abs((np.exp(1j * a) - 1) / (1j * a)) ** 2                     # ∫₀¹ e^{iau} du, u = ρ²
    assert efficiency_loss_db(r, np.ones_like(r), np.exp(1j * a * r ** 2)) == \
        pytest.approx(-10 * np.log10(closed), rel=1e-5)
