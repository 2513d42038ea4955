"""Seed-001 §1.4: the four-focal 2-D constrained lens with one symmetry plane and finite foci —
exact at its four foci, the thesis' reduction (1.9)–(1.13) (with the corrected (1.11)) holds on the
solution, f = f' gives back the two-plane lens, the RMS optimum against the thesis' RMS_min, the
spec path."""

from pathlib import Path

import numpy as np
import pytest

from antenna_cad.registry import adapter
from antenna_cad.spec import load_spec
from antenna_cad.synthesis.polyfocal import SymFocus, two_planes_2d
from antenna_cad.synthesis.polyfocal_analysis import sigma_scan
from antenna_cad.synthesis.polyfocal_oneplane import FinitePair, one_plane_2d, reduction_residuals

RECIPE = Path(__file__).resolve().parents[1] / "recipes" / "polyfocal-oneplane-2d-90deg.yaml"
Y = np.linspace(0.0, 0.5, 51)            # D = 1, 101 lines
rad = np.radians
# this project's re-optimisation (Nelder–Mead on the peak σ over ±45°, 19 angles, 101 lines) of
# (f3, f3', α°, β°) at the thesis' optimum f1' for each f1 (the thesis prints only f1, f1', RMS_min)
OPT = {(1.2, 4.5): (0.97711842, 3.90906246, 15.98006955, 42.64068748),
       (3.0, 93.8): (2.41913545, 94.39541241, 20.75386689, 43.82081786)}


def _peak(f1, f1i, f3, f3i, a, b):
    lens = one_plane_2d(FinitePair(f1, f1i, rad(a)), FinitePair(f3, f3i, rad(b)), 1.0, Y)
    return sigma_scan(lens, 45.0, 19).max


def test_exact_at_four_finite_foci_and_the_reduction_holds():
    p1, p3 = FinitePair(1.2, 4.5, rad(15.0)), FinitePair(1.1, 4.0, rad(35.0))
    lens = one_plane_2d(p1, p3, 1.0, Y)
    assert lens.residuals().max() < 1e-12
    assert reduction_residuals(p1, p3, lens).max() < 1e-9            # (1.12)–(1.13), corrected (1.11)
    assert np.all(lens.r2[:, 1] * lens.r1[:, 1] >= 0)                  # y2 on the side of y1


def test_equal_focal_distances_give_the_two_plane_lens():
    """f = f' on both pairs: the surfaces are mirror images (z2 = −z1, y2 = y1), the §1.3 lens."""
    lens = one_plane_2d(FinitePair(25.0, 25.0, rad(11.7)), FinitePair(22.925, 22.925, rad(27.9)), 25.0,
                        np.linspace(0, 12.5, 26))
    ref = two_planes_2d([SymFocus(25.0, rad(11.7)), SymFocus(22.925, rad(27.9))], 0.0, 25.0, np.linspace(0, 12.5, 26))
    np.testing.assert_allclose(lens.r1, ref.r1, atol=1e-9)
    np.testing.assert_allclose(lens.r2, ref.r2, atol=1e-9)
    np.testing.assert_allclose(lens.l, ref.l, atol=1e-9)


def test_recipe_synthesizes_exactly():
    spec = load_spec(RECIPE)
    kind = adapter("polyfocal")
    design = kind.synthesize(spec)
    assert all(c.status != "fail" for c in design.checks)
    assert design.dense.residuals().max() < 1e-9 and design.foci_sigma.max() < 1e-12
    assert len(np.unique(np.round(design.r1_mm[:, 1], 6))) == len(design.r1_mm)       # one channel per element
    fig = kind.summary(spec, design, None)
    assert fig["foci_count"] == 4
    assert fig["dense_lines_sigma_over_D_max"] == pytest.approx(6.343e-6, rel=1e-3)    # 401 lines


@pytest.mark.parametrize("foci, match", [
    ([{"f": 1.2, "angle_deg": 15.0, "f_image": 4.5}, {"f": 1.0, "angle_deg": 40.0}], "f_image"),
    ([{"f": 1.2, "angle_deg": 0.0, "f_image": 4.5}, {"f": 1.0, "angle_deg": 40.0, "f_image": 4.0}], "off the axis"),
])
def test_spec_rules_for_finite_foci(foci, match):
    import yaml

    from antenna_cad.spec import parse_spec
    data = yaml.safe_load(RECIPE.read_text())
    data["design"]["foci"] = foci
    with pytest.raises(Exception, match=match):
        parse_spec(data, "x.yaml")
    data["design"] |= {"symmetry": "two_planes", "foci": [{"f": 25.0, "angle_deg": 10.0, "f_image": 20.0}]}
    with pytest.raises(Exception, match="f_image"):
        parse_spec(data, "x.yaml")


@pytest.mark.parametrize("f1, f1i, thesis, ours", [(1.2, 4.5, 6.02e-6, 6.3324e-6), (3.0, 93.8, 1.05e-7, 1.0842e-7)])
def test_rms_min_against_the_thesis(f1, f1i, thesis, ours):
    """Seed-001 §1.4 (90° view, circular focal curves): RMS_min 6.02e-6 (f1 = 1.2, f1' = 4.5) and
    1.05e-7 (f1 = 3, f1' = 93.8). Ours, peak σ over ±45° at the re-optimised foci: 6.332e-6 (5 % above)
    and 1.084e-7 (3 % above), pinned rel 1e-3; within 10 % of the thesis (its line count, angle
    sampling and criterion are not printed)."""
    peak = _peak(f1, f1i, *OPT[f1, f1i])
    assert peak == pytest.approx(ours, rel=1e-3)
    assert thesis < peak < 1.1 * thesis


def test_rms_min_is_a_minimum():
    """f1 = 1.2: moving any of f3, f3', α, β off the optimum raises the peak σ."""
    best = _peak(1.2, 4.5, *OPT[1.2, 4.5])
    for k, step in enumerate((2e-3, 2e-2, 0.1, 0.1)):
        for sign in (-1.0, 1.0):
            x = list(OPT[1.2, 4.5])
            x[k] += sign * step
            assert _peak(1.2, 4.5, *x) > best
