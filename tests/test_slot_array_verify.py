"""As-built trace of the slot array (antenna_cad/raytrace/slot_array.py; seed-003 §3.9)."""

from __future__ import annotations

import numpy as np
import pytest

from antenna_cad.raytrace import slot_array as rt
from antenna_cad.synthesis import slot_array as sa
from antenna_cad.verification import detrended
from tests.test_slot_array_synthesis import KA, KA_ML, XB

CASES = {"KA": KA, "KA_ML": KA_ML, "XB": XB}


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    d = sa.synthesize_slot_array(**CASES[request.param])
    s = d.slots
    cells = rt.Cells(s.guide_x_mm, s.slot_line_y_mm[:, None] + np.arange(s.n_cells)[None, :] * s.period_mm,
                     np.full(s.guide_x_mm.size, d.guide_width_mm), np.full(s.guide_x_mm.size, d.fill_eps_r))
    return request.param, d, cells


def test_design_foci_give_zero_slot_phase_error(case):
    # the synthesised beam former and slot line: both design foci coherent at the design frequency
    name, d, cells = case
    f = CASES[name]["design_ghz"]
    for j in range(2):
        fit = rt.trace_beam(d.beamformer, d.beamformer.foci_mm[j], cells, f)
        assert fit.rms_deg[0] < 1e-5 and fit.pp_deg[0] < 1e-5
        assert fit.azimuth_rad[0] == pytest.approx(np.arcsin(d.beamformer.beam_dirs[j][0]), abs=1e-9)
        assert fit.elevation_rad[0] == pytest.approx(np.pi / 2 - d.scan.beta_design_rad, abs=1e-9)


def test_traced_elevation_follows_the_harmonic_relation(case):
    # the fitted beam elevation over the band is the −1st harmonic of (3.1), sin θ = cos β
    name, d, cells = case
    p = CASES[name]
    f = np.linspace(p["min_ghz"], p["max_ghz"], 9)
    fit = rt.trace_beam(d.beamformer, d.feeds.aperture_centres_mm[0], cells, f)
    cb = sa.harmonic_direction_cosine(f, p["guide_width_mm"], p["fill_eps_r"], p["period_mm"], -1)
    visible = np.sin(fit.azimuth_rad) ** 2 + cb**2 < 1          # (u_x, u_y) inside the unit circle
    assert np.allclose(np.sin(fit.elevation_rad[visible]), cb[visible], atol=1e-9)
    assert np.all(np.isnan(fit.elevation_rad[np.abs(cb) >= 1]))
    assert np.isfinite(fit.elevation_rad[np.abs(cb) < 0.9]).all()


def test_perturbed_slot_line_gives_the_expected_phase_error(case):
    # δ(x) = A cos(2π·3x/span) along the guides: the wave travels n·δ further in the guide and the
    # radiated front is referred to cos β·δ, so the detrended error is k (n − cos β) δ, RMS over
    # three whole periods on the guide grid = k (n − cos β) A / √2 (orthogonal to 1 and x).
    name, d, cells = case
    f = CASES[name]["design_ghz"]
    span = cells.guide_x_mm.size * CASES[name]["pitch_mm"]
    A = 0.2
    delta = A * np.cos(2 * np.pi * 3 * cells.guide_x_mm / span)
    bent = rt.Cells(cells.guide_x_mm, cells.y_mm + delta[:, None], cells.width_mm, cells.eps_r)
    fit = rt.trace_beam(d.beamformer, d.beamformer.foci_mm[0], bent, f)
    k = float(sa.wavenumber_per_mm(f))
    per_mm = np.degrees(k * (d.scan.n_guide_design - np.cos(d.scan.beta_design_rad)))
    expected = per_mm * A / np.sqrt(2)
    assert fit.rms_deg[0] == pytest.approx(expected, rel=2e-3)
    assert fit.pp_deg[0] == pytest.approx(per_mm * np.ptp(delta), rel=2e-3)
    assert fit.ruze_loss_db[0] == pytest.approx(rt.DB_PER_NP2 * np.radians(expected) ** 2, rel=5e-3)


def test_common_eps_shift_moves_the_beam_by_the_guide_index_change():
    # all guides εr + Δ: sin θ moves by Δn = n(ε + Δ) − n(ε); the cells keep their place while the
    # front tilts, so the curved guide entry y_Q(x) (the mirror) leaves an error k Δn y_Q detrended
    d = sa.synthesize_slot_array(**XB)
    s = d.slots
    cells = rt.Cells(s.guide_x_mm, s.slot_line_y_mm[:, None] + np.arange(s.n_cells)[None, :] * s.period_mm,
                     np.full(s.guide_x_mm.size, 15.0), np.full(s.guide_x_mm.size, 2.25))
    fit0 = rt.trace_beam(d.beamformer, d.beamformer.foci_mm[0], cells, 10.0)
    fit1 = rt.trace_beam(d.beamformer, d.beamformer.foci_mm[0], cells.perturbed(d_eps_r=0.05), 10.0)
    n = lambda e: float(sa.guide_gamma_per_mm(10.0, 15.0, e) / sa.wavenumber_per_mm(10.0))
    dn = n(2.30) - n(2.25)
    assert np.sin(fit1.elevation_rad[0]) - np.sin(fit0.elevation_rad[0]) == pytest.approx(dn, rel=1e-9)
    yq = d.beamformer.guide_curve.y_at(s.guide_x_mm)
    expected = np.degrees(float(sa.wavenumber_per_mm(10.0)) * dn) * detrended(s.guide_x_mm, yq)
    assert fit1.rms_deg[0] == pytest.approx(np.sqrt(np.mean(expected**2)), rel=1e-6)
    assert fit1.rms_deg[0] > 1.0


def test_tolerance_effects_scale_and_name_every_tolerance():
    d = sa.synthesize_slot_array(**KA)
    s = d.slots
    cells = rt.Cells(s.guide_x_mm, s.slot_line_y_mm[:, None] + np.arange(s.n_cells)[None, :] * s.period_mm,
                     np.full(s.guide_x_mm.size, 5.0), np.full(s.guide_x_mm.size, 2.2))
    run = lambda scale: rt.tolerance_effects(d.beamformer, cells, d.feeds.aperture_centres_mm, d.feeds.aim, 30.0,
                                             eps_r_tol=0.02, width_tol_mm=0.02, feed_tol_mm=0.1, scale=scale)
    one, two = run(1.0), run(2.0)
    assert [e.name.split(",")[0] for e in one] == ["fill εr"] * 2 + ["guide width"] * 2 + ["feed position"] * 2
    for a, b in zip(one, two):
        assert b.loss_db > a.loss_db >= 0.0
    # a common εr shift of 0.02: the beam moves Δθ ≈ Δn / cos θ with Δn ≈ Δε / (2n)
    n = d.scan.n_guide_design
    theta = np.pi / 2 - d.scan.beta_design_rad
    assert abs(one[0].d_elevation_rad) == pytest.approx(0.02 / (2 * n) / np.cos(theta), rel=0.05)
    # the alternating spread: RMS error k Δn √(mean s²) along 172 mm of guide (Δn per guide ±)
    assert one[1].rms_deg > 10 * one[0].rms_deg


def test_cells_read_back_from_the_slot_table():
    from antenna_cad.fabrication.slot_array import slots_csv
    d = sa.synthesize_slot_array(**XB)
    cells = rt.cells_from_slot_table(slots_csv(d, np.zeros(d.slots.guide_x_mm.size)), 15.0, 2.25)
    s = d.slots
    assert np.allclose(cells.guide_x_mm, s.guide_x_mm, atol=1e-4)
    assert np.allclose(cells.y_mm, s.slot_line_y_mm[:, None] + np.arange(s.n_cells) * s.period_mm, atol=1e-4)
    assert cells.period_mm == pytest.approx(23.5, abs=1e-6)
