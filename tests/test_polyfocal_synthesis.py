"""Polyfocal constrained lenses (seed-001 §1, §2): exactness of every solution, the digest's
reference values, the branch choice, σ (1.4) orderings and named errors."""

import numpy as np
import pytest

from antenna_cad.spec import SpecError, parse_spec
from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.polyfocal import (FiveFocal, SymFocus, Trifocal15, explicit_16, five_focal_3d,
                                             plane_wave_trifocal_2d, two_planes_2d)
from antenna_cad.synthesis.polyfocal_analysis import seed_comparison, sigma_scan

rad = np.radians
FOUR_60 = [SymFocus(25.0, rad(11.7)), SymFocus(22.925, rad(27.9))]
Y = np.linspace(0.0, 12.5, 51)
EXAMPLES_24 = {1: (1, 1.001, 1.002, 18.1, 28.6, -0.5, 0.1, 0.3), 2: (1, 1.094, 1.091, 23.8, 29.8, 30, -18, 14.4),
               3: (1, 1.118, 1.007, 11.66, 27.8, 10, -5, 2)}


def _five(k):
    p = EXAMPLES_24[k]
    return FiveFocal(*p[:3], *rad(np.array(p[3:])))


def _disc(pitch=0.05):
    g = np.arange(-0.5, 0.5 + 1e-9, pitch)
    x, y = np.meshgrid(g, g)
    inside = x**2 + y**2 <= 0.25
    return np.column_stack([x[inside], y[inside]])


def test_four_focal_profile_matches_digest_values():
    lens = two_planes_2d(FOUR_60, 5.0, 25.0, Y)
    assert lens.residuals().max() < 1e-9 * 25
    for y, z, dl in ((10.0, 7.207746, 0.296119), (12.5, 8.317370, 0.064412)):   # digest §1.3 [OURS], 1e-5
        i = int(np.argmin(np.abs(lens.r2[:, 1] - y)))
        assert lens.r2[i, 2] == pytest.approx(z, abs=1e-5)
        assert lens.l[i] == pytest.approx(dl, abs=1e-5)


def test_newton_solution_is_the_explicit_16_and_reports_the_branch_switch():
    lens = two_planes_2d(FOUR_60, 5.0, 25.0, Y)
    half = lens.r2[:, 1] > 0
    for (_, y, z), dl in zip(lens.r2[half], lens.l[half]):
        (zp, yp2), (zm, ym2) = explicit_16(*FOUR_60, 5.0, dl)
        assert min(abs(zp - z), abs(zm - z)) < 1e-9
        assert min(abs(yp2 - y * y) if abs(zp - z) < 1e-9 else np.inf,
                   abs(ym2 - y * y) if abs(zm - z) < 1e-9 else np.inf) < 1e-8
    assert "'+' then '−'" in lens.branch                      # digest: '+' from the centre, '−' past the turn
    turn = float(lens.branch.split("l − l0 = ")[1].rstrip(")"))
    assert turn == pytest.approx(0.30, abs=0.01)              # digest: l turns at l − l0 ≈ 0.30


def test_bifocal_designs_are_exact_and_equal_lines_give_the_ellipse():
    s = SymFocus(25.0, rad(17.5))
    eq = two_planes_2d([s], 5.0, 25.0, Y, "equal_length")
    y, z = eq.r2[:, 1], eq.r2[:, 2]
    c = s.f * np.cos(s.angle)
    assert np.max(np.abs(y**2 / s.f**2 + (z - 5.0 - c) ** 2 / c**2 - 1.0)) < 1e-9     # digest §1.2 (a) [OURS]
    for law, n_w in (("equal_length", 1.0), ("straight", 0.5), ("flat", 1.0)):
        lens = two_planes_2d([s], 5.0, 25.0, Y, law, n_w)
        assert lens.residuals().max() < 1e-9 * 25, law


def test_trifocal_and_fourfocal_beat_bifocal_as_the_seed_says():
    bi, tri, four = (s.max for s in seed_comparison())
    assert four < tri < bi
    assert 1.5 / 2 <= tri / four <= 1.5 * 2                    # seed L319: ≈ 1.5× at 60°, factor 2


def test_straight_focal_line_is_about_a_hundred_times_worse():
    y = Y
    opt = sigma_scan(two_planes_2d([SymFocus(25, 0.0), SymFocus(20.95, rad(41.5))], 5.0, 25.0, y), 45, 31).max
    f3 = 25.0 / np.cos(rad(40.2))                               # f3 = f1 cos α / cos β, α = 0
    line = sigma_scan(two_planes_2d([SymFocus(25, 0.0), SymFocus(f3, rad(40.2))], 5.0, 25.0, y), 45, 31).max
    assert 50 <= line / opt <= 200                              # seed L331: two orders of magnitude


def test_plane_wave_trifocal_family_choice():
    t = Trifocal15(1.0, 0.8953, rad(26.5), 0.2)                 # seed-001 §1.5, 60° view
    lens = plane_wave_trifocal_2d(t, 1.0, np.linspace(0, 0.5, 41), -1.0)
    assert lens.residuals().max() < 1e-9
    assert "decreasing" in lens.branch
    assert np.all(np.diff(lens.r2[:, 1]) > 0) and np.all(np.diff(lens.r1[:, 1]) > 0)
    with pytest.raises(DesignError, match="design.foci"):
        plane_wave_trifocal_2d(t, 1.0, np.linspace(0, 0.5, 11), 1.0)
    assert sigma_scan(lens, 30.0, 13).max < 1e-4                # digest [OURS]: order 1e-5 over ±30°


@pytest.mark.parametrize("k", [1, 3])
def test_five_focal_explicit_solution_is_exact(k):
    lens = five_focal_3d(_five(k), 1.0, _disc())
    assert lens.residuals().max() < 1e-9
    assert lens.shifted(0.4).residuals().max() < 1e-9          # thickness by translation (§2.1)


def test_five_focal_printed_c1_is_the_erratum():
    """(2.47) with the printed factor 2 in C1 breaks the focusing equations (digest erratum 10)."""
    ff = _five(3)
    lens = five_focal_3d(ff, 1.0, _disc(0.1))
    a, b, p, q = ff.alpha, ff.beta, ff.phi, ff.xi
    c1 = -(np.sin(a) ** 2 * np.cos(p) ** 2 - np.sin(b) ** 2 * np.cos(q) ** 2) / (ff.f1**2 - ff.f3**2)
    y2 = lens.r2[:, 1]
    rho = np.divide(lens.r1[:, 1], y2, out=np.ones_like(y2), where=y2 != 0)
    printed = lens.r1.copy()
    printed[:, 1] = y2 * np.sqrt(rho**2 + c1 * y2**2)                  # C1 → 2·C1
    spread = max(np.ptp(f.path(printed, lens.l, lens.r2)) for f in lens.foci)
    assert spread > 1e-3 and lens.residuals().max() < 1e-9


def test_five_focal_example_2_outside_its_domain_is_a_named_error():
    with pytest.raises(DesignError, match="design.aperture"):
        five_focal_3d(_five(2), 1.0, _disc(0.1))


def test_newton_failure_names_the_field():
    with pytest.raises(DesignError, match="design.foci"):
        two_planes_2d([SymFocus(25.0, rad(22.3))], 5.0, 25.0, Y, "straight", 0.9)


def _spec(**design):
    base = {"dimensions": "2d", "symmetry": "two_planes", "output": "foci",
            "foci": [{"f": 25, "angle_deg": 11.7}, {"f": 22.925, "angle_deg": 27.9}], "unit_mm": 10,
            "aperture": 25, "thickness": 10,
            "lines": {"type": "parallel_plate", "pitch_mm": 6, "phase_index": 1.7, "plate_spacing_mm": 2}}
    return {"name": "t", "kind": "polyfocal", "frequency_ghz": 30, "material": "polystyrene",
            "fabrication": {"method": "machined_metal"}, "design": base | design}


def test_spec_rejects_unsupported_cases_and_bad_numbers():
    parse_spec(_spec())
    with pytest.raises(SpecError, match="design.symmetry"):
        parse_spec(_spec(dimensions="3d", output="foci"))
    with pytest.raises(SpecError, match="design.foci"):
        parse_spec(_spec(foci=[{"f": 1}, {"f": 2}, {"f": 3}]))
    with pytest.raises(SpecError, match="angle_deg"):
        parse_spec(_spec(foci=[{"f": 25, "angle_deg": 95}]))
    with pytest.raises(SpecError, match="unit_mm"):
        parse_spec(_spec(unit_mm=float("inf")))
