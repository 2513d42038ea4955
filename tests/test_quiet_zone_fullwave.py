"""The quiet zone from full-wave fields: one Meep run records the field over the zone's (r, z)
half-plane, and its planes agree with separate runs that each record one plane; a build's quiet-zone
figures then come from full-wave, named so, with the fast model and GO beside them."""

import math

import numpy as np
import pytest

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.deck import make_deck
from antenna_cad.fullwave.volume import VolumeField
from antenna_cad.quietzone.stats import plane_figures
from tests.fullwave_cases import case_lens, case_spec

LAM = 30.0


@pytest.fixture(autouse=True)
def cache(fullwave_cache):
    return fullwave_cache


def test_planes_between_grid_rows_keep_the_wave():
    """A converging wave sampled at 10 rows per λ: every plane read between the rows within 1e-3 of the
    exact field (the carrier e^{ik0z} taken out before interpolating), none outside the record."""
    k, r, z = 2 * math.pi / LAM, np.linspace(0.0, 150.0, 51), np.arange(0.0, 121.0, LAM / 10)

    def wave(zz):
        return np.exp(-((r[:, None] / (200.0 + zz)) ** 2)) * np.exp(1j * k * zz * (1 - 1e-3 * (r[:, None] / 100) ** 2))
    vol = VolumeField(r, z, wave(z[None, :]), LAM)
    planes = np.array([7.1, 44.0, 101.9])
    for zp, (rr, e) in zip(planes, vol.planes(planes)):
        assert np.max(np.abs(e - wave(np.array([zp]))[:, 0])) < 1e-3
    assert vol.covers(planes, 150.0) and not vol.covers(planes, 151.0) and not vol.covers([130.0], 10.0)


@pytest.mark.slow
def test_one_runs_planes_agree_with_single_plane_runs(meep):
    """εr 1.3, D 300 mm, F 900 mm at 10 GHz and 10 px/λ, the ideal lens: one run recording 2–6 λ behind
    it against two runs recording one plane each (2.37 λ and 5.81 λ, between grid rows) over the disc
    0.8 D, the axis included: phase p-p within 0.6°, RMS within 0.2°, amplitude ripple and taper within
    0.05 dB; their ratio's phase within 1° p-p (measured 0.4° and 0.3° over 0.9 R; its level, a constant
    0.5 dB, is no figure's business: every figure is relative to the plane's own)."""
    lens = case_lens(1.3, 300.0, 900.0, 10.0, 10.0)
    back = lens.plane_z_mm(0.0)

    def deck(offset, volume=None):
        return make_deck(lens.parts("ideal"), frequency_ghz=10.0, resolution=10.0, feed_z_mm=lens.feed_z_mm,
                         feed_pattern="dipole", feed_q=1.0, radius_mm=lens.radius_mm, plane_offset_lambda=offset,
                         field_map=False, volume_z_mm=volume)
    offsets = (2.37, 5.81)
    whole, *single = solver.run_decks([deck(2.0, (back + 2 * LAM, back + 6 * LAM)), *(deck(o) for o in offsets)],
                                      meep, 1)
    vol = VolumeField.from_run(whole)
    disc = 0.8 * 2 * lens.radius_mm
    for o, (r, e), one in zip(offsets, vol.planes(back + np.array(offsets) * LAM), single):
        a = plane_figures(r, e, disc, o * LAM, 1.0, 11.25)
        b = plane_figures(one["r_mm"], one["er"], disc, o * LAM, 1.0, 11.25)
        assert abs(a.phase_p2p_deg - b.phase_p2p_deg) <= 0.6, o
        assert abs(a.phase_rms_deg - b.phase_rms_deg) <= 0.2, o
        assert abs(a.amplitude_ripple_db - b.amplitude_ripple_db) <= 0.05, o
        assert abs(a.amplitude_taper_db - b.amplitude_taper_db) <= 0.05, o
        inside = r <= disc / 2
        ratio = np.degrees(np.angle(e[inside] / one["er"][: len(r)][inside]))
        assert np.ptp(ratio) <= 1.0, o


@pytest.mark.slow
def test_a_builds_quiet_zone_comes_from_full_wave(meep):
    """The same lens with 10 mm sheets, full-wave on at 8 px/λ and a 200 mm × 90 mm zone: the quiet-zone
    check names the full-wave model, the fast model's and GO's figures stand beside it, and the stack's
    own figure is the full-wave fabricated field over its ideal lens."""
    from antenna_cad.kinds import collimator
    spec = case_spec(1.3, 300.0, 900.0, 10.0, 10.0)
    spec = spec.model_copy(update={
        "verification": spec.verification.model_copy(update={"full_wave": "on", "resolution_px_per_lambda": 8.0}),
        "design": spec.design.model_copy(update={"test_zone": spec.design.test_zone.model_copy(
            update={"diameter_mm": 200.0, "depth_mm": 90.0})})})
    design = collimator.synthesize(spec)
    layup, panels = collimator.plan(spec, design)
    v = collimator.verify(spec, design, layup, collimator.fabricate(spec, design, layup, panels))
    check = next(c for c in v.checks if c.name == "quiet_zone")
    assert "full-wave (Meep" in check.message and "one run per lens over the zone's depth" in check.message
    f = v.figures
    for key in ("", "fast_", "go_"):
        assert np.isfinite(f[f"quiet_zone_{key}fabricated_on_axis_phase_p2p_deg"])
    assert f["quiet_zone_fabricated_on_axis_phase_p2p_deg"] != f["quiet_zone_fast_fabricated_on_axis_phase_p2p_deg"]
    assert "quiet_zone_fabricated_added_on_axis_phase_p2p_deg" in f
    rows = next(t for t in v.tables if t.name == "quiet-zone").rows
    assert any(r[0].startswith("full-wave (Meep") and r[0].endswith("fabricated / ideal") for r in rows)
    sanding = next(c for c in v.checks if c.name == "unsanded_step_phase_error")
    assert "one run per lens over the zone's depth" in sanding.message.split("vs budget")[0]
    assert sanding.value == pytest.approx(f["stack_zone_fabricated_on_axis_p2p_deg"])
