"""The quiet zone of a beam off the axis, on the meridional cut: per-plane statistics against closed
forms (a tilted plane wave, a quadratic phase and taper with the beam's own slope, a shadow), the GO
cut of parallel rays, the fast model's thin screen, and the figures of a collimator's scan-edge feed."""

import math

import numpy as np
import pytest

from antenna_cad.quietzone.cut import cut_plane_figures, cut_stack_ratio, cut_y_mm, go_cut

LAM = 30.0
K = 2 * math.pi / LAM


def test_a_tilted_plane_wave_is_a_perfect_zone():
    """A plane wave 5° off the axis: the tilt only points the beam — zero phase and amplitude figures,
    the whole disc within the limits."""
    y = cut_y_mm(300.0, LAM)
    e = np.exp(1j * (K * math.sin(math.radians(5.0)) * y + 0.7))
    p = cut_plane_figures(y, e, 400.0, 50.0, 0.5, 5.0)
    assert max(p.phase_p2p_deg, p.phase_rms_deg, p.amplitude_ripple_db, abs(p.amplitude_taper_db)) < 1e-9
    assert p.diameter_mm == pytest.approx(400.0)


def test_quadratic_phase_and_taper_on_the_cut_closed_forms():
    """φ = c·y², level a·y + b·y² dB, constant across x, over a disc of radius ρ: p-p cρ², disc-area RMS
    cρ²/4 (the chord weight √(1 − u²): ⟨u²⟩ = 1/4, ⟨u⁴⟩ = 1/8), taper bρ² whatever the slope a, ripple 0."""
    rho, c, a, b = 200.0, 1e-3, 4e-3, -2e-5
    y = np.linspace(-rho, rho, 8001)
    e = 10 ** ((a * y + b * y**2) / 20) * np.exp(1j * (K * 0.05 * y + np.radians(c * y**2)))
    p = cut_plane_figures(y, e, 2 * rho, 0.0, 1.0, 11.25)
    assert p.phase_p2p_deg == pytest.approx(c * rho**2, rel=1e-9)
    assert p.phase_rms_deg == pytest.approx(c * rho**2 / 4, rel=1e-4)
    assert p.amplitude_taper_db == pytest.approx(b * rho**2, rel=1e-9)
    assert p.amplitude_ripple_db < 1e-9
    assert p.diameter_mm == pytest.approx(2 * math.sqrt(2 * 11.25 / c), abs=0.2)   # phase span 2 × 11.25°


def test_a_shadow_carries_no_phase_and_fails_the_amplitude():
    """A beam lighting only y > −50 of a Ø400 disc: the phase figures come from the lit part (here flat),
    the amplitude figures show the shadow, and the largest centred diameter stops at its edge."""
    y = cut_y_mm(300.0, LAM)
    e = np.where(y > -50.0, 1.0, 0.0) * np.exp(1j * K * 0.1 * y)
    p = cut_plane_figures(y, e, 400.0, 0.0, 0.5, 5.0)
    assert p.phase_p2p_deg < 1e-9
    assert p.amplitude_p2p_db > 100
    assert p.diameter_mm == pytest.approx(100.0, abs=2 * LAM / 20)


def test_go_cut_of_parallel_rays_is_their_plane_wave():
    """Rays leaving y ∈ [−100, 100] at 3° with equal paths on their wavefront: on a plane 200 mm on, the
    field is that tilted plane wave over the shifted strip and zero outside it."""
    th = math.radians(3.0)
    y0 = np.linspace(-100.0, 100.0, 201)
    path = y0 * math.sin(th)                      # the wavefront's path difference on the exit plane
    y = np.linspace(-150.0, 150.0, 601)
    e = go_cut(y0, np.full_like(y0, math.cos(th)), np.full_like(y0, math.sin(th)), np.ones_like(y0), path, 0.0,
               200.0, LAM, y)
    shift = 200.0 * math.tan(th)
    lit = (y > -100 + shift + 1) & (y < 100 + shift - 1)
    expected = np.exp(1j * K * (y * math.sin(th) + 200.0 / math.cos(th) - shift * math.sin(th)))
    assert np.abs(e[lit] - expected[lit]).max() < 1e-9
    assert np.all(e[(y < -100 + shift - 1) | (y > 100 + shift + 1)] == 0)


def test_thin_screen_under_a_tilted_wave():
    """No excess foam: the ratio is 1 everywhere. A uniform excess Δd across the lens: near the centre and
    close behind the screen the ratio is the screen's phase k0(n−1)Δd, whatever the beam's angle."""
    y = cut_y_mm(150.0, LAM)
    for s in (0.0, math.sin(math.radians(4.0))):
        one = cut_stack_ratio(lambda r: 0 * r, 1.3, 250.0, LAM, 20.0, np.array([0.0, 100.0]), y, s)
        assert np.abs(one - 1).max() < 1e-12
        flat = cut_stack_ratio(lambda r: np.full_like(r, 2.0), 1.3, 250.0, LAM, 20.0, np.array([0.0]), y[np.abs(y) < 60], s)
        assert np.degrees(np.angle(flat)) == pytest.approx(360 / LAM * 0.3 * 2.0, abs=0.3)


def test_collimator_scan_edge_feed_gets_its_own_quiet_zone():
    """A machined PTFE collimator: the scan-edge feed's zone on the cut (GO and the fast model, named so),
    its own tables, plots and check beside the on-axis ones."""
    from antenna_cad.kinds import collimator as Kc
    from antenna_cad.spec import parse_spec
    spec = parse_spec({"name": "t", "kind": "collimator", "frequency_ghz": 15.0, "material": "ptfe",
                       "design": {"diameter_mm": 120, "focal_length_mm": 300, "aut": {"diameter_mm": 80},
                                  "test_zone": {"depth_mm": 60, "planes": 6}},
                       "fabrication": {"method": "solid"}, "verification": {"full_wave": "off"}})
    design = Kc.synthesize(spec)
    v = Kc.verify(spec, design, None, Kc.fabricate(spec, design, None, ()))
    f = v.figures
    for model in ("", "go_"):
        for fig in ("phase_p2p_deg", "phase_rms_deg", "amplitude_ripple_db", "amplitude_taper_db", "diameter_mm",
                    "cross_pol_db"):
            assert math.isfinite(f[f"quiet_zone_{model}ideal_edge_{fig}"])
    assert f["quiet_zone_go_ideal_edge_phase_p2p_deg"] < design.phase_error_budget_deg   # the scan edge's own budget
    check = next(c for c in v.checks if c.name == "quiet_zone_edge")
    assert check.message.startswith("feed edge: ") and "meridional cut" in check.message
    assert {"quiet-zone-phase-edge", "quiet-zone-amplitude-edge", "quiet-zone-map-edge"} <= {p.name for p in v.plots}
    assert {"quiet-zone-edge", "quiet-zone-planes-edge"} <= {t.name for t in v.tables}
    assert next(c for c in v.checks if c.name == "quiet_zone").message.count("meridional cut") == 0
