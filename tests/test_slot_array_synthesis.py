"""Tests of the seed-003 slot-array synthesis (antenna_cad/synthesis/slot_array/).

Reference values and tolerances live in tests/data/slot_array_reference.csv (seed-003 §5 / §8.4)
and tests/data/slot_array_table_1_1.csv (Table 1.1, seed-003 §3.2).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

from antenna_cad.synthesis import slot_array as sa
from antenna_cad.synthesis.checks import DesignError

DATA = Path(__file__).parent / "data"


def _read_csv(name):
    with open(DATA / name) as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith("#")))


REF = {(r["case"], r["quantity"]): (float(r["expected"]), float(r["tolerance"]), r["unit"])
       for r in _read_csv("slot_array_reference.csv")}


def ref(case, quantity):
    return REF[(case, quantity)]


def assert_ref(case, quantity, got):
    exp, tol, unit = ref(case, quantity)
    if unit.endswith("_rel"):
        assert abs(got - exp) <= tol * abs(exp), f"{case} {quantity}: got {got}, expected {exp} ±{tol * 100}%"
    else:
        assert abs(got - exp) <= tol, f"{case} {quantity}: got {got}, expected {exp} ±{tol} {unit}"


# --- recipes (seed-003 §2.3/§2.5 Ka band, §2.4 X band) ---------------------------------------

R8_PARAMS = dict(a0=.25, a2=-.01, h1=.005, b0=-.25, b2=.1, h2=.055, rho1=1.2)
R9_PARAMS = dict(lens_a2=-.15, lens_vertex=.42, x0=.06, p1=.8325, p2=3.0, f0=1.4, n=np.sqrt(2.2))

KA = dict(min_ghz=22, max_ghz=38, design_ghz=30, guide_width_mm=5.0, guide_height_mm=1.6,
          fill_eps_r=2.2, wall_mm=0.0, count=40, pitch_mm=5.0, length_mm=172.0,
          layout="longitudinal_4", slot_width_mm=0.4, period_mm=8.6,
          taper_law="sin", taper_eta=0.9,
          beamformer_type="bifocal_two_mirror", beamformer_params=R8_PARAMS, scale_mm=200.0,
          slot_line_offset_mm=8.0, layer_height_mm=1.6, coupling_slot_mm=1.1,
          feed_count=7, feed_throat_mm=(7.2, 1.6), feed_aperture_mm=(16.0, 1.6),
          feed_length_mm=30.0)

KA_ML = dict(KA, beamformer_type="bifocal_mirror_lens", beamformer_params=R9_PARAMS,
             coupling_slot_mm=1.2, feed_aperture_mm=(21.0, 1.6), feed_count=5)

TABLE_3_1 = [6.6, 7.8, 8.4, 8.8, 9.1, 9.4, 9.6, 9.8, 9.9, 10.2, 10.5, 10.4]   # seed-003 §2.4
XB = dict(min_ghz=8.5, max_ghz=11.5, design_ghz=10.0, guide_width_mm=15.0, guide_height_mm=5.0,
          fill_eps_r=2.25, wall_mm=0.5, count=18, pitch_mm=16.0, length_mm=282.0,
          layout="longitudinal_pair", slot_width_mm=1.5, period_mm=23.5, lengths_mm=TABLE_3_1,
          beamformer_type="single_mirror",
          beamformer_params=dict(minor_semi_axis_mm=245.0, focal_separation_mm=75.0),
          scale_mm=300.0, slot_line_offset_mm=18.0, layer_height_mm=5.0, coupling_slot_mm=5.0,
          feed_count=5, feed_throat_mm=(23.0, 10.0), feed_aperture_mm=(53.0, 5.0),
          feed_length_mm=210.0)


@pytest.fixture(scope="module")
def ka():
    return sa.synthesize_slot_array(**KA)


@pytest.fixture(scope="module")
def xb():
    return sa.synthesize_slot_array(**XB)


@pytest.fixture(scope="module")
def r7():
    return sa.bifocal_two_mirror(a0=.25, a2=-.25, h1=.1, b0=-.25, b2=.25, h2=.1, rho1=1.2,
                                 rho2=1.2)


@pytest.fixture(scope="module")
def r8():
    return sa.bifocal_two_mirror(**R8_PARAMS)


@pytest.fixture(scope="module")
def r9():
    return sa.bifocal_mirror_lens(**R9_PARAMS)


# --- R1/R2: dispersion and the harmonic relation (§3.1) -------------------------------------

def test_r1_minus_first_harmonic_angle_x_band():
    cb = sa.harmonic_direction_cosine(10.0, 15.0, 2.25, 23.5, -1)
    assert_ref("R1", "beta_10ghz", np.degrees(np.arccos(cb)))
    assert_ref("R1", "half_guide_wavelength_10ghz", sa.guide_wavelength_mm(10.0, 15.0, 2.25) / 2)


def test_r2_broadside_frequency():
    fb = sa.broadside_frequency_ghz(15.0, 2.25, 23.5)
    assert_ref("R2", "broadside_loaded", fb)
    assert_ref("R2", "broadside_unloaded", fb)
    # at the broadside frequency the -1st harmonic is broadside (γp = 2π)
    assert abs(sa.harmonic_direction_cosine(fb, 15.0, 2.25, 23.5)) < 1e-12


def test_ka_scan_angles_over_band():
    assert_ref("R2b", "broadside_ka_p8.6", sa.broadside_frequency_ghz(5.0, 2.2, 8.6))
    sc = sa.scan_figures(min_ghz=22, max_ghz=38, design_ghz=30, width_mm=5, height_mm=1.6,
                         eps_r=2.2, period_mm=8.6, n_freq=9)
    np.testing.assert_allclose(sc.frequencies_ghz, np.arange(22, 39, 2))
    for f, th in zip(sc.frequencies_ghz, np.degrees(sc.theta_rad)):
        assert_ref("R2b", f"theta_{int(f)}ghz", th)


def test_auto_period_is_guide_wavelength_at_broadside():
    p = sa.period_for_angle_mm(30.0, 5.0, 2.2)
    assert abs(p - sa.guide_wavelength_mm(30.0, 5.0, 2.2)) < 1e-12
    p20 = sa.period_for_angle_mm(30.0, 5.0, 2.2, beta_rad=np.radians(110))
    assert abs(np.degrees(np.arccos(sa.harmonic_direction_cosine(30.0, 5.0, 2.2, p20))) - 110) < 1e-9


def test_mode_checks_flag_te20_inside_band():
    # seed-003 §3.1/§8.3: 4 mm guide, eps_eq 3.2, TE20 at ≈41.9 GHz < 45 GHz -> warn
    sc = sa.scan_figures(min_ghz=23, max_ghz=45, design_ghz=30, width_mm=4.0, height_mm=1.6,
                         eps_r=3.2, period_mm=4.6)
    c = {c.name: c for c in sc.checks}
    assert abs(sc.te20_cutoff_ghz - 41.9) < 0.05
    assert c["te20_in_band"].status == "warn"
    ok = sa.scan_figures(min_ghz=22, max_ghz=38, design_ghz=30, width_mm=5.0, height_mm=1.6,
                         eps_r=2.2, period_mm=8.6)
    assert {c.name: c for c in ok.checks}["te20_in_band"].status == "pass"
    assert abs(ok.te10_cutoff_ghz - 20.2) < 0.05 and abs(ok.te20_cutoff_ghz - 40.4) < 0.05
    with pytest.raises(DesignError, match="slots.period_mm"):
        sa.scan_figures(min_ghz=22, max_ghz=38, design_ghz=22, width_mm=5.0, height_mm=1.6,
                        eps_r=2.2, period_mm=4.0)


def test_parallel_plate_layer_check():
    sc = sa.scan_figures(min_ghz=22, max_ghz=38, design_ghz=30, width_mm=5, height_mm=1.6,
                         eps_r=2.2, period_mm=8.6, layer_heights_mm=[("layer1", 4.5, 1.0)])
    c = {c.name: c for c in sc.checks}["parallel_plate_layer1"]
    assert c.status == "warn" and "33.31 GHz" in c.message   # c/(2·4.5 mm) = 33.31 GHz


# --- R3: taper (1.1), corrected (§3.2, erratum §7.1) ------------------------------------------

def test_r3_table_1_1_slot_lengths():
    rows = _read_csv("slot_array_table_1_1.csv")
    L1 = np.array([float(r["L1_mm"]) for r in rows])
    got = sa.taper_slot_lengths_mm(20, 172 / 20, 172.0, "sin", eta=0.9)
    assert np.max(np.abs(got - L1)) <= 0.005, np.abs(got - L1)


@pytest.mark.parametrize("law", ["sin", "cos_pedestal", "exp"])
def test_taper_leaves_one_minus_eta_in_the_load(law):
    # power left at y = L: exp(-2∫α dy) must equal 1 − η for every law
    L, eta = 172.0, 0.85
    y = np.linspace(0, L, 20001)
    a = sa.taper_alpha_np_per_m(y, L, law, eta) * 1e-3        # Np/mm
    integral = np.sum(0.5 * (a[1:] + a[:-1]) * np.diff(y))
    assert abs(np.exp(-2 * integral) - (1 - eta)) < 1e-6


# --- R4–R6: elliptic mirror and slot line (§3.5) ----------------------------------------------

def test_r4_ellipse_mirror():
    bf = sa.ellipse_mirror(245.0, 75.0, 150.0)
    assert_ref("R4", "r0", bf.params["r0_mm"])
    assert_ref("R4", "alpha", np.degrees(bf.params["alpha_rad"]))
    m = bf.mirrors[0]
    assert_ref("R4", "sag_150", float(m.y_at(150.0)))
    assert_ref("R4", "sag_150", float(m.y_at(-150.0)))
    assert abs(float(m.y_at(0.0))) < 1e-12                       # passes through O
    # both foci on the ellipse's focal line, r + r' = 2 r0 at every point
    p = m.points_mm
    r = np.linalg.norm(p[:, None, :] - bf.foci_mm[None], axis=-1).sum(axis=1)
    assert np.max(np.abs(r - 2 * bf.params["r0_mm"])) < 1e-9


def test_r5_slot_line_at_broadside_is_mirror_shifted():
    fb = sa.broadside_frequency_ghz(15.0, 2.25, 23.5)
    d = sa.synthesize_slot_array(**dict(XB, design_ghz=fb))
    t0 = XB["slot_line_offset_mm"]
    assert np.max(np.abs(d.slots.t_mm - t0)) < 1e-9
    xs = d.slot_line.points_mm[:, 0]
    mirror_y = d.beamformer.mirrors[0].y_at(xs)
    assert np.max(np.abs(d.slot_line.points_mm[:, 1] - (mirror_y + t0))) < 1e-9


def test_r6_slot_line_at_10ghz_and_phase_coherence(xb):
    sc = xb.scan
    bf = xb.beamformer
    t = sa.slot_line_t_mm(bf, np.array([-150.0, 150.0]), sc.n_guide_design,
                          np.cos(sc.beta_design_rad), 0.0)
    assert_ref("R6", "t_minus_t0_150", t[0])
    assert_ref("R6", "t_minus_t0_150", t[1])
    assert np.all(xb.phase_spread_wavelengths < 1e-3)
    assert [c.status for c in xb.checks if c.name.startswith("slot_phase")] == ["pass", "pass"]


def test_phase_coherence_can_fail_with_wrong_guide_index(xb):
    # the erratum §7.8 point: using √ε instead of n = γ/k in t(x) breaks coherence
    sc, bf, sl = xb.scan, xb.beamformer, xb.slots
    cb = np.cos(sc.beta_design_rad)
    t_bad = sa.slot_line_t_mm(bf, sl.guide_x_mm, np.sqrt(2.25), cb, 18.0)
    y_ref = sl.guide_entry_y_mm + t_bad
    spread = sa.slot_phase_spread(bf, sl.guide_x_mm, y_ref, sc.n_guide_design, cb,
                                  sa.C_MM_GHZ / 10.0)
    assert np.all(spread > 1e-3)


# --- R7–R9: bifocal constructions (§3.3, §3.4) -----------------------------------------------

def _assert_smooth(curve, tol=1e-3):
    x, y = curve.points_mm[:, 0], curve.points_mm[:, 1]
    fd = np.gradient(y, x)
    assert np.all(np.diff(x) > 0)
    assert np.max(np.abs(fd - curve.slopes)[2:-2]) < tol        # §8.3 C¹: stored vs numerical


def test_r7_symmetric_two_mirror(r7):
    F1 = r7.foci_mm[0]
    assert_ref("R7", "F1_x", F1[0])
    assert_ref("R7", "F1_y", F1[1])
    assert_ref("R7", "l0", r7.params["l0"])
    m1, m2 = r7.mirrors
    for x in ("0.0", "0.2", "0.4", "0.5"):
        assert_ref("R7", f"y1_{x}", float(m1.y_at(float(x))))
    # identical mirrors (point symmetry): mirror 2 = −mirror 1, point by point
    np.testing.assert_allclose(m2.points_mm, -m1.points_mm[::-1], atol=1e-9, rtol=0)
    assert np.all(r7.sigma_norm < 1e-6)
    assert m1.x_range_mm[1] >= 0.6 and r7.params["iterations"] == 4
    _assert_smooth(m1)
    _assert_smooth(m2)


def test_r8_plane_front_two_mirror(r8):
    F1 = r8.foci_mm[0]
    assert_ref("R8", "F1_x", F1[0])
    assert_ref("R8", "F1_y", F1[1])
    assert_ref("R8", "beam_angle", np.degrees(r8.params["beam_angle_rad"]))
    m1, m2 = r8.mirrors
    for x in ("0.3", "0.5"):
        assert_ref("R8", f"y1_{x}", float(m1.y_at(float(x))))
        assert_ref("R8", f"y2_{x}", float(m2.y_at(float(x))))
    assert np.all(r8.sigma_norm < 1e-6)
    _assert_smooth(m1)
    _assert_smooth(m2)


def test_r9_mirror_lens(r9):
    F1 = r9.foci_mm[0]
    assert_ref("R9", "F1_x", F1[0])
    assert_ref("R9", "F1_y", F1[1])
    assert_ref("R9", "delta", np.degrees(r9.params["delta_rad"]))
    assert_ref("R9", "initial_mirror_half_width", r9.params["initial_mirror_half_width"])
    mir, lens = r9.mirrors[0], r9.lenses[0]
    for x in ("0.1", "0.3", "0.5"):
        assert_ref("R9", f"mirror_y_{x}", float(mir.y_at(float(x))))
        assert_ref("R9", f"lens_y_{x}", float(lens.y_at(float(x))))
    assert abs(float(mir.y_at(0.0))) < 1e-12                     # mirror passes through O
    assert np.all(r9.sigma_norm < 1e-6)
    assert r9.params["min_lens_thickness_mm"] > 0.25             # ≈0.29 at the edge (§3.4)
    _assert_smooth(mir)
    _assert_smooth(lens)


def _plane_sigma(bf, mirror2):
    """Independent trace F1 -> mirror 1 -> ``mirror2`` -> plane front; RMS path error."""
    m1 = bf.mirrors[0]
    x = np.linspace(-0.5, 0.5, 50)
    P = np.stack([x, m1.y_at(x)], -1)
    e = sa.reflect(P - bf.foci_mm[0], sa._normal_from_slope(m1.slope_at(x)))
    Q, ok = sa.intersect_rays_with_curve(P, e, mirror2)
    assert ok.all()
    tot = np.linalg.norm(P - bf.foci_mm[0], axis=-1) + np.linalg.norm(Q - P, axis=-1) \
        - Q @ bf.beam_dirs[0]
    return float(np.sqrt(np.mean((tot - bf.params["l0"]) ** 2)))


def test_sigma_detects_a_perturbed_mirror(r8):
    # σ must be able to fail: tilt the right half of mirror 2 by 1e-4 -> σ far above 1e-6
    m2 = r8.mirrors[1]
    assert _plane_sigma(r8, m2) < 1e-9
    p = m2.points_mm.copy()
    p[:, 1] += 1e-4 * np.clip(p[:, 0], 0, None)
    bad = sa.Curve(m2.name, m2.layer, p, m2.tangents)
    assert _plane_sigma(r8, bad) > 1e-6


def test_two_mirror_with_focal_output_is_rejected_for_arrays():
    with pytest.raises(DesignError, match="rho2"):
        sa.synthesize_slot_array(**dict(KA, beamformer_params=dict(R8_PARAMS, rho2=1.2)))


# --- R12 -------------------------------------------------------------------------------------

def test_r12_ideal_gain():
    assert_ref("R12", "ideal_gain", sa.ideal_gain_dbi(200.0, 172.0, 30.0))
    assert_ref("R12", "gain_kip_0.5", sa.ideal_gain_dbi(200.0, 172.0, 30.0, 0.5))


# --- full designs: Ka two-mirror recipe, mirror-lens, X-band single mirror -------------------

def test_ka_recipe_slot_count_and_layout(ka):
    s = ka.slots
    assert s.count == 40 * 20 * 4 == 3200                          # 172/8.6 = 20 cells
    assert s.n_cells == 20 and len(s.guide_x_mm) == 40
    for arr in (s.guide_index, s.cell_index, s.slot_in_cell, s.x_mm, s.y_mm, s.length_mm,
                s.width_mm, s.offset_mm, s.angle_rad):
        assert arr.shape == (3200,)
    np.testing.assert_allclose(s.guide_x_mm, (np.arange(40) - 19.5) * 5.0)
    np.testing.assert_allclose(s.x_mm - s.guide_x_mm[s.guide_index], s.offset_mm)
    # first slot of each cell has the taper length L1 (Table 1.1 within 0.005 mm)
    L1 = np.array([float(r["L1_mm"]) for r in _read_csv("slot_array_table_1_1.csv")])
    first = s.slot_in_cell == 0
    got = s.length_mm[first].reshape(40, 20)
    assert np.max(np.abs(got - L1[None, :])) <= 0.005
    # the slot line: y of cell 0 / slot 0 = mirror 2 at the guide axis + t
    y0 = s.y_mm[first & (s.cell_index == 0)]
    np.testing.assert_allclose(y0, ka.beamformer.guide_curve.y_at(s.guide_x_mm) + s.t_mm,
                               atol=1e-12)
    assert all(c.status != "fail" for c in ka.checks)


def test_ka_recipe_sigma_and_phase_coherence(ka):
    assert np.all(ka.beamformer.sigma_norm < 1e-6)
    assert np.all(ka.phase_spread_wavelengths < 1e-3)
    # the phase coherence holds for every slot of a given position in the cell (modulo λ)
    s, sc = ka.slots, ka.scan
    cb = np.cos(sc.beta_design_rad)
    for j in range(4):
        sel = s.slot_in_cell == j
        spread = sa.slot_phase_spread(ka.beamformer, s.guide_x_mm[s.guide_index[sel]], s.y_mm[sel],
                                      sc.n_guide_design, cb, sa.C_MM_GHZ / 30.0)
        assert np.all(spread < 1e-3)


def test_mirror_lens_array_case():
    d = sa.synthesize_slot_array(**KA_ML)
    assert d.beamformer.type == "bifocal_mirror_lens" and len(d.beamformer.lenses) == 1
    assert np.all(d.beamformer.sigma_norm < 1e-6)
    assert np.all(d.phase_spread_wavelengths < 1e-3)
    assert abs(np.degrees(d.figures["beam_azimuth_rad"]) - 23.92) < 0.01
    assert d.slots.count == 3200


def test_x_band_single_mirror_layout(xb):
    s = xb.slots
    assert s.count == 18 * 12 * 2
    off = s.offset_mm.reshape(18, 12, 2)
    np.testing.assert_allclose(off[..., 0], 3.75)                 # a/4 (§2.4)
    np.testing.assert_allclose(off[..., 1], -3.75)
    dy = np.diff(s.y_mm.reshape(18, 12, 2), axis=-1)[..., 0]
    assert np.max(np.abs(dy - 13.4)) < 0.05                       # λg/2 at 10 GHz
    np.testing.assert_allclose(s.length_mm.reshape(18, 12, 2)[0, :, 0], TABLE_3_1)
    assert np.all(xb.beamformer.sigma_norm < 1e-6)
    # seed placement: feeds on the circle of radius r0 about O (L786), aimed at O, one 53 mm
    # aperture apart
    f = sa.synthesize_slot_array(**dict(XB, feed_placement="circle")).feeds
    r = np.linalg.norm(f.aperture_centres_mm, axis=-1)
    np.testing.assert_allclose(r, 247.853, atol=1e-3)
    chord = np.linalg.norm(np.diff(f.aperture_centres_mm, axis=0), axis=-1)
    np.testing.assert_allclose(chord, 53.0, atol=1e-9)
    np.testing.assert_allclose(f.aim, -f.aperture_centres_mm / r[:, None], atol=1e-12)


def test_curves_have_unit_tangents(ka):
    for c in ka.beamformer.mirrors + ka.beamformer.lenses + (ka.slot_line,):
        np.testing.assert_allclose(np.linalg.norm(c.tangents, axis=-1), 1.0, atol=1e-12)
        assert np.all(c.tangents[:, 0] > 0)


# --- manufacturability checks ----------------------------------------------------------------

def test_slots_outside_wall_fail_with_field_and_number():
    with pytest.raises(DesignError) as e:
        sa.synthesize_slot_array(**dict(KA, slot_offset_mm=2.3))
    assert e.value.field == "slots.width_mm"
    assert "2.5 mm" in e.value.message and "limit 2.3 mm" in e.value.message
    d = sa.synthesize_slot_array(**dict(KA, slot_offset_mm=2.3), strict=False)
    c = {c.name: c for c in d.checks}["slots_inside_wall"]
    assert c.status == "fail" and abs(c.value - 2.5) < 1e-12


def test_overlapping_slots_fail():
    # X band: slot 2 of cell m (y + 13.4 mm) and slot 1 of cell m+1 (y + 23.5 mm) are 10.1 mm
    # apart while their half-lengths add up to 10.45 mm; at ±3.75 mm offsets they clear each
    # other across the guide (web 6 mm). With offsets ±0.5 mm (width 1.5 mm) they overlap.
    with pytest.raises(DesignError) as e:
        sa.synthesize_slot_array(**dict(XB, slot_offset_mm=0.5))
    assert e.value.field == "slots.period_mm" and "OVERLAP" in e.value.message
    # a web that exists but is below the minimum also fails, with the number
    d = sa.synthesize_slot_array(**dict(XB, min_web_mm=7.0), strict=False)
    c = {c.name: c for c in d.checks}["slot_web"]
    assert c.status == "fail" and c.value == pytest.approx(6.0, abs=1e-9)


def test_coupling_slot_clearance_fails_for_thesis_d2():
    # §2.4: d1 = 5 mm coupling slot, d2 = 7.8 mm to the first slot line. With t0 = d1 + d2 the
    # 10 GHz slot line (t − t0 = −4.95 mm at the outer guide) runs into the coupling slot.
    with pytest.raises(DesignError) as e:
        sa.synthesize_slot_array(**dict(XB, slot_line_offset_mm=12.8))
    assert e.value.field == "beamformer.slot_line_offset_mm"
    assert "guide 0" in e.value.message or "guide 17" in e.value.message
    d = sa.synthesize_slot_array(**dict(XB, slot_line_offset_mm=12.8), strict=False)
    c = {c.name: c for c in d.checks}["coupling_slot_clearance"]
    assert c.status == "fail" and -4.6 < c.value < -4.3
    ok = {c.name: c for c in sa.synthesize_slot_array(**XB).checks}["coupling_slot_clearance"]
    assert ok.status == "pass" and ok.value > 0


def test_web_function_geometry():
    # two guides, hand-made slots: distances are rectangle gaps
    lay = sa.build_slot_layout(layout="longitudinal_pair", guide_x_mm=[0.0], guide_entry_y_mm=[0.0],
                               t_mm=[0.0], n_cells=1, period_mm=20.0, width_mm=1.0,
                               dy=np.array([0.0, 3.0]), off=np.array([2.0, -2.0]),
                               lengths=np.array([[4.0, 4.0]]), ang=np.zeros(2))
    w = sa.slot_webs_mm(lay)
    assert w[0, 0] == pytest.approx(3.0)       # |Δx| 4 − 1 = 3 ; Δy 3 − 4 < 0 -> 3
    lay2 = sa.build_slot_layout(layout="longitudinal_pair", guide_x_mm=[0.0], guide_entry_y_mm=[0.0],
                                t_mm=[0.0], n_cells=1, period_mm=20.0, width_mm=1.0,
                                dy=np.array([0.0, 3.0]), off=np.array([0.2, -0.2]),
                                lengths=np.array([[4.0, 4.0]]), ang=np.zeros(2))
    assert sa.slot_webs_mm(lay2)[0, 0] == pytest.approx(-0.6)   # overlap: max(−0.6, −1)


def test_auto_period_design(ka):
    d = sa.synthesize_slot_array(**dict(KA, period_mm=None, slot_line_offset_mm=9.0))
    lg = sa.guide_wavelength_mm(30.0, 5.0, 2.2)
    assert d.slots.period_mm == pytest.approx(lg, abs=1e-12)          # 9.117 mm
    assert d.slots.n_cells == int(172.0 // lg) == 18
    assert abs(np.cos(d.scan.beta_design_rad)) < 1e-12                 # broadside at 30 GHz
    assert d.scan.broadside_ghz == pytest.approx(30.0, abs=1e-9)
    assert np.all(d.phase_spread_wavelengths < 1e-3)


def test_band_below_te10_cutoff_is_an_error():
    with pytest.raises(DesignError) as e:
        sa.synthesize_slot_array(**dict(KA, min_ghz=19.0))
    assert e.value.field == "waveguide.width_mm" and "20.21 GHz" in e.value.message


def test_coupling_slot_edge_is_normal_offset(ka):
    g, e = ka.beamformer.guide_curve, ka.coupling_slot_edge
    # every edge point is at distance d from the mirror curve (dense sampling of the mirror)
    xs = np.linspace(*g.x_range_mm, 200001)
    mp = np.stack([xs, g.y_at(xs)], -1)
    for p in e.points_mm[::25]:
        assert np.min(np.linalg.norm(mp - p, axis=-1)) == pytest.approx(1.1, abs=1e-4)
    assert np.all(e.points_mm[:, 1] > g.y_at(e.points_mm[:, 0]))


@pytest.mark.parametrize("case", ["KA", "KA_ML", "XB"])
def test_feed_placement(case):
    kw = {"KA": KA, "KA_ML": KA_ML, "XB": XB}[case]
    circ = sa.synthesize_slot_array(**dict(kw, feed_placement="circle"))
    opt = sa.synthesize_slot_array(**kw)
    f, bf = opt.feeds, opt.beamformer
    n = kw["feed_count"]
    assert f.aperture_centres_mm.shape == (n, 2)
    # symmetric about x = 0, adjacent apertures exactly one H-plane aperture apart
    np.testing.assert_allclose(f.aperture_centres_mm[::-1] * [-1, 1], f.aperture_centres_mm,
                               atol=1e-9)
    chord = np.linalg.norm(np.diff(f.aperture_centres_mm, axis=0), axis=-1)
    np.testing.assert_allclose(chord, kw["feed_aperture_mm"][0], atol=1e-9)
    aim_pt = {"KA": [0, 0.25 * 200], "KA_ML": [0, 0.42 * 200], "XB": [0, 0]}[case]
    np.testing.assert_allclose(f.aim, sa._unit(np.array(aim_pt, float) - f.aperture_centres_mm),
                               atol=1e-12)
    # circle placement: every feed on the circle through the design foci about O
    R = np.linalg.norm(bf.foci_mm[0])
    np.testing.assert_allclose(np.linalg.norm(circ.feeds.aperture_centres_mm, axis=-1), R,
                               atol=1e-9)
    # optimal radii never do worse than the circle (the centre feed has the same polar angle)
    k = n // 2
    assert f.phase_rms_wavelengths[k] <= circ.feeds.phase_rms_wavelengths[k] + 1e-9
    assert np.all(np.isfinite(f.phase_rms_wavelengths))
    assert np.nanmax(f.phase_rms_wavelengths) < 0.02
    # beams scan in azimuth, in opposite order to the feed positions, symmetric
    az = f.azimuth_rad
    assert np.all(np.diff(az) < 0) and np.allclose(az, -az[::-1], atol=1e-9)


def test_design_foci_have_zero_feed_aberration(ka):
    sl, sc, bf = ka.slots, ka.scan, ka.beamformer
    rms, s = sa.feed_phase_errors(bf, bf.foci_mm, sl.guide_x_mm, sl.t_mm, sc.n_guide_design,
                                  np.cos(sc.beta_design_rad), sa.C_MM_GHZ / 30.0)
    assert np.all(rms < 1e-9)
    np.testing.assert_allclose(s, bf.beam_dirs[:, 0], atol=1e-12)
    # a point off the focal arc is aberrated (the metric can fail)
    rms_off, _ = sa.feed_phase_errors(bf, bf.foci_mm[0] * 0.9, sl.guide_x_mm, sl.t_mm,
                                      sc.n_guide_design, np.cos(sc.beta_design_rad), 10.0)
    assert rms_off[0] > 1e-3


def test_focal_output_eikonal_matches_trace(r7):
    # for rho2 finite the design eikonal to mirror 2 is l0 − |Q F3|; the trace must agree
    x = np.linspace(-0.45, 0.45, 11)
    for j in range(2):
        np.testing.assert_allclose(sa.traced_eikonal_mm(r7, j, x), r7.eikonal(x, j), atol=1e-9)


def test_transverse_3_layout():
    # seed-003 §2.2 variant (a): p 6.56, a 4, w 0.44, s 2.43/2.45/2.42, d1 1.66, d2 1.62 mm
    dy, off, L, ang = sa.cell_pattern("transverse_3", n_cells=10, period_mm=6.56,
                                      guide_width_mm=4.0, lengths_mm=(2.43, 2.45, 2.42),
                                      transverse_spacings_mm=(1.66, 1.62))
    lay = sa.build_slot_layout(layout="transverse_3", guide_x_mm=[0.0, 5.0],
                               guide_entry_y_mm=[0.0, 1.0], t_mm=[5.0, 5.0], n_cells=10,
                               period_mm=6.56, width_mm=0.44, dy=dy, off=off, lengths=L, ang=ang)
    assert lay.count == 60
    hx, hy = lay.half_extents_mm()
    np.testing.assert_allclose(hx, lay.length_mm / 2)            # transverse: length across
    np.testing.assert_allclose(hy, 0.22)
    assert sa.check_slots_in_wall(lay, 4.0, 0.2).status == "pass"    # 1.225 <= 1.8
    assert sa.check_slots_in_wall(lay, 4.0, 0.8).status == "fail"    # 1.225 >  1.2
    web = sa.check_slot_webs(lay, 0.3)
    assert web.status == "pass" and web.value == pytest.approx(1.62 - 0.44)
    with pytest.raises(DesignError, match="slots.lengths_mm"):
        sa.cell_pattern("transverse_3", n_cells=10, period_mm=6.56, guide_width_mm=4.0,
                        lengths_mm=(2.43, 2.45))


def test_bad_beamformer_parameters_raise():
    with pytest.raises(DesignError, match="beamformer"):
        sa.bifocal_two_mirror(**dict(R8_PARAMS, h1=0.0))
    # the mirror–lens construction diverges near |x| ≈ 0.54 (§3.4): a wider aperture fails
    with pytest.raises(DesignError, match="diverges"):
        sa.bifocal_mirror_lens(**R9_PARAMS, half_width=0.7)
    with pytest.raises(DesignError, match="beamformer.type"):
        sa.synthesize_slot_array(**dict(KA, beamformer_type="no_such_former"))
    with pytest.raises(DesignError, match="slots.lengths_mm"):
        sa.synthesize_slot_array(**dict(XB, lengths_mm=None))
