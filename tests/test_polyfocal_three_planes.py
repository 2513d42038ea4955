"""Seed-001 §2.2: the 3-D lens with three symmetry planes — variant 1 exact at its four foci, its
x = 0 section the 2-D two-plane lens, the thesis' explicit (2.3) holding on it; variant 2 (the
rhombus) exact with (2.7)–(2.8) holding; the spec paths."""

from pathlib import Path

import numpy as np
import pytest
import yaml

from antenna_cad.registry import adapter
from antenna_cad.spec import load_spec, parse_spec
from antenna_cad.synthesis.polyfocal import SymFocus, two_planes_2d
from antenna_cad.synthesis.polyfocal_design import grid_3d
from antenna_cad.synthesis.polyfocal_three_planes import explicit_23_residuals, rhombus_27_28_residuals, three_planes_3d

RECIPE = Path(__file__).resolve().parents[1] / "recipes" / "polyfocal-threeplanes-3d-60deg.yaml"
F1, F3 = SymFocus(25.0, np.radians(11.7)), SymFocus(23.875, np.radians(27.9))     # §2.2 example, 60°


def test_exact_and_the_explicit_solution_holds():
    lens = three_planes_3d(F1, F3, 5.0, 25.0, grid_3d(25.0, 25.0 / 24))
    assert lens.residuals().max() / 25.0 < 1e-13
    assert explicit_23_residuals(F1, F3, 5.0, lens).max() < 1e-8                  # (2.3), scale 25
    np.testing.assert_array_equal(lens.r1[:, :2], lens.r2[:, :2])                  # lines parallel to the axis
    np.testing.assert_allclose(lens.r1[:, 2], -lens.r2[:, 2])


def test_section_x0_is_the_two_plane_lens():
    y = np.linspace(0.0, 12.5, 11)
    lens = three_planes_3d(F1, F3, 5.0, 25.0, np.column_stack([0 * y, y]))
    ref = two_planes_2d([F1, F3], 5.0, 25.0, y)
    np.testing.assert_allclose(lens.r2[:, 2], ref.r2[-11:, 2], atol=1e-12)
    np.testing.assert_allclose(lens.l, ref.l[-11:], atol=1e-12)


def test_recipe_synthesizes_exactly_with_its_sigma():
    """The §2.2 example: exact at its foci (σ there ≤ 1e-12 D); peak σ/D over ±30° on the σ-fitted
    sphere pinned (rel 1e-3): 1.46e-2 (yz), 3.26e-2 (xz). The thesis says only that 3-D aberrations
    are about ten times the 2-D ones (its Fig. 18–19 values are unreadable)."""
    spec = load_spec(RECIPE)
    kind = adapter("polyfocal")
    design = kind.synthesize(spec)
    assert all(c.status != "fail" for c in design.checks)
    assert design.foci_sigma.max() < 1e-12 and spec.design.foci_count == 4
    assert [s.max for s in design.scans] == pytest.approx([1.4616e-2, 3.2636e-2], rel=1e-3)
    assert design.surfaces is not None and design.surfaces[0].shape == (17, 17, 3)


def test_foci_out_of_the_yz_plane_are_refused():
    data = yaml.safe_load(RECIPE.read_text())
    data["design"]["foci"][0] = {"position": [1.0, 5.0, -30.0]}
    with pytest.raises(Exception, match="yz plane"):
        parse_spec(data, "x.yaml")
    data["design"]["foci"][0] = {"f": 25.0, "angle_deg": 11.7, "azimuth_deg": 5}
    with pytest.raises(Exception, match="azimuth_deg"):
        parse_spec(data, "x.yaml")
    data["design"]["foci"][0] = {"position": [5.0, 0.0, -30.0]}       # first pair in the xz plane
    with pytest.raises(Exception, match="first pair in the yz plane"):
        parse_spec(data, "x.yaml")


RHOMBUS = RECIPE.parent / "polyfocal-rhombus-3d.yaml"


def test_rhombus_exact_and_its_reduction_holds():
    """§2.2 variant 2 example (D = 1, f1 = 1, f3 = 0.9, α = 14.2°, β = 23.7°) at zero thickness: exact,
    (2.7)–(2.8) hold."""
    f1, f3 = SymFocus(1.0, np.radians(14.2)), SymFocus(0.9, np.radians(23.7))
    lens = three_planes_3d(f1, f3, 0.0, 1.0, grid_3d(1.0, 1.0 / 24), rhombus=True)
    assert lens.residuals().max() < 1e-13
    assert rhombus_27_28_residuals(f1, f3, 0.0, lens).max() < 1e-12
    assert abs(lens.foci[2].point[1]) < 1e-15 and lens.foci[2].point[0] > 0       # F3 in the xz plane


def test_rhombus_recipe():
    """Exact at its foci; peak σ/D over ±15° on the σ-fitted sphere pinned (rel 1e-3): 1.061e-2 (yz),
    8.90e-3 (xz); the fitted radius 0.432 D (the thesis' R = 0.4 is for its zero-thickness lens and an
    unstated view: not comparable)."""
    spec = load_spec(RHOMBUS)
    design = adapter("polyfocal").synthesize(spec)
    assert all(c.status != "fail" for c in design.checks) and design.foci_sigma.max() < 1e-12
    assert [s.max for s in design.scans] == pytest.approx([1.0614e-2, 8.8997e-3], rel=1e-3)
    assert design.focal[1] == pytest.approx(0.432, abs=0.002)


def test_trapezoid_exact_and_237_holds():
    """§2.3 (d) example (D = 1, f1 = 1, f3 = 0.97, α 8.6°, β 28°, φ −0.5°, ξ 0.1°) at zero thickness:
    exact at its four foci, lines crossing x = 0 (x2 = −x1), and (2.37) y1² = (A z1 + B)/C holds."""
    rad = np.radians
    a, b, p, q, f1, f3 = rad(8.6), rad(28.0), rad(-0.5), rad(0.1), 1.0, 0.97
    lens = three_planes_3d(SymFocus(f1, a), SymFocus(f3, b), 0.0, 1.0, grid_3d(1.0, 1.0 / 24), azimuths=(p, q))
    assert lens.residuals().max() < 1e-13 and len(lens.foci) == 4
    np.testing.assert_array_equal(lens.r2[:, 0], -lens.r1[:, 0])
    x1, y1, z1, l = lens.r1[:, 0], lens.r1[:, 1], lens.r1[:, 2], lens.l
    A = 8 * (f1 * np.cos(a) - f3 * np.cos(b))
    B = (4 * (f1**2 - f3**2) + (2 * f3 - l) ** 2 - (2 * f1 - l) ** 2
         + 8 * x1 * (f3 * np.sin(b) * np.sin(q) - f1 * np.sin(a) * np.sin(p)))
    C = 16 * (f1**2 * np.sin(a) ** 2 * np.cos(p) ** 2 / (2 * f1 - l) ** 2
              - f3**2 * np.sin(b) ** 2 * np.cos(q) ** 2 / (2 * f3 - l) ** 2)
    assert np.abs(y1**2 - (A * z1 + B) / C).max() < 1e-12


def test_trapezoid_is_refused_by_the_spec_with_its_reason():
    """Its lines cross x = 0 (x2 = −x1): straight channels would intersect; the spec says so."""
    data = yaml.safe_load(RECIPE.read_text())
    data["design"] |= {"symmetry": "two_planes", "foci": [{"f": 25.0, "angle_deg": 8.6, "azimuth_deg": -0.5},
                                                          {"f": 24.25, "angle_deg": 28.0, "azimuth_deg": 0.1}]}
    with pytest.raises(Exception, match="crosses the plane x = 0"):
        parse_spec(data, "x.yaml")
