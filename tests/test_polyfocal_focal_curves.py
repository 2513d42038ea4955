"""Focal curves of the polyfocal σ study (seed-001 §1.2, §2.4, §4): the bifocal axis point z_F
optimised as the seed does (its optimum table reproduced for z_F), the ranking of the three bifocal
designs, σ at the design foci and the σ-minimising focal sphere of a five-focal lens, the seed's
comparison lenses on their own 60° view."""

from pathlib import Path

import numpy as np
import pytest
import yaml

from antenna_cad.registry import adapter
from antenna_cad.spec import parse_spec
from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.polyfocal import SymFocus, two_planes_2d
from antenna_cad.synthesis.polyfocal_analysis import (axis_point_circle, best_direction, design_foci_sigma,
                                                      fitted_sphere, focal_sphere, optimal_axis_point, sigma_scan,
                                                      source_on)

RECIPES = Path(__file__).resolve().parents[1] / "recipes"
Y = np.linspace(0.0, 12.5, 51)          # f = D = 25 λ, 2z0 = 10 λ (seed-001 §1.2)
N_W = 0.4                               # §1.2 (b): n_w not printed; 0.4 reproduces its z_F (below)
# seed-001 §1.2 table: design → {half view: (α, z_F)}
TABLE = {"equal_length": {30: (17.5, -31.1), 45: (17.5, -31.1)},
         "straight": {30: (22.3, -30.5), 45: (33.0, -30.5)},
         "flat": {30: (20.6, -32.75), 45: (30.5, -34.0)}}


def _lens(law, alpha):
    return two_planes_2d([SymFocus(25.0, np.radians(alpha))], 5.0, 25.0, Y, law, N_W)


def _peak(lens, half, z_axis):
    return sigma_scan(lens, half, 41, sphere=(*axis_point_circle(lens, z_axis), "")).max


@pytest.mark.parametrize("law, half, ours, tol", [
    ("equal_length", 30, -31.093, 0.01),      # seed −31.1
    ("equal_length", 45, -31.072, 0.01),      # seed −31.1
    ("straight", 30, -30.533, 0.01),          # seed −30.5 (n_w = 0.4)
    ("straight", 45, -30.192, 0.01),          # seed −30.5: 0.31 λ apart
    ("flat", 30, -32.454, 0.01),              # seed −32.75: 0.30 λ apart
])
def test_optimised_axis_point_against_the_seed_table(law, half, ours, tol):
    """At the seed's α, the z_F of least peak σ is the seed's to 0.04 λ for (a) and (b) at 60°; 0.3 λ
    off for (b) at 90° and (c) at 60° (their criterion is not stated; pinned here). It is a minimum:
    z_F ± 0.1 λ and the seed's own z_F do no better."""
    alpha, seed = TABLE[law][half]
    lens = _lens(law, alpha)
    z = optimal_axis_point(lens, half)
    assert z == pytest.approx(ours, abs=tol)
    best = _peak(lens, half, z)
    assert best <= min(_peak(lens, half, z - 0.1), _peak(lens, half, z + 0.1), _peak(lens, half, seed)) + 1e-12


@pytest.mark.parametrize("half, expect", [(30, (5.991e-4, 7.636e-4, 1.237e-2)), (45, (3.301e-3, 6.255e-3, 1.647e-2))])
def test_bifocal_designs_rank_equal_lines_straight_flat(half, expect):
    """Seed-001 §1.2 (Fig. 4): RMS(a) < RMS(b) < RMS(c) at the seed's (α, z_F), for the 60° and 90°
    views; peak σ/D pinned (rel 1e-3)."""
    peaks = [_peak(_lens(law, TABLE[law][half][0]), half, TABLE[law][half][1]) for law in TABLE]
    assert peaks[0] < peaks[1] < peaks[2]
    assert peaks == pytest.approx(expect, rel=1e-3)


def test_min_norm_circle_is_not_the_focal_curve():
    """With one focus pair the least-squares circle is undetermined (lstsq returns the minimum-norm
    one); the optimised circle's peak σ is 7× lower for the seed's equal-line lens at 60°."""
    lens = _lens("equal_length", 17.5)
    loose = sigma_scan(lens, 30, 41).max
    tight = _peak(lens, 30, optimal_axis_point(lens, 30))
    assert tight == pytest.approx(5.885e-4, rel=1e-3) and loose / tight > 7


def _spec(path, **design):
    data = yaml.safe_load(path.read_text())
    data["design"] |= design
    return parse_spec(data, path.name)


def test_bifocal_spec_takes_or_optimises_z_f():
    """A bifocal spec: z_F given (``focal_axis_z``) is used and named in the caption; left out it is
    optimised; on the near arc it is refused naming the field."""
    bif = {"foci": [{"f": 25.0, "angle_deg": 17.5}], "view_angle_deg": 60, "line_law": "equal_length"}
    kind = adapter("polyfocal")
    given = kind.synthesize(_spec(RECIPES / "polyfocal-fourfocal-2d-60deg.yaml", **bif, focal_axis_z=-31.1))
    assert given.focal_axis_z == -31.1 and "z_F = -31.1" in given.focal[2]
    free = kind.synthesize(_spec(RECIPES / "polyfocal-fourfocal-2d-60deg.yaml", **bif))
    assert free.focal_axis_z == pytest.approx(-31.09, abs=0.02) and "optimised" in free.focal[2]
    assert free.scans[0].max <= given.scans[0].max
    with pytest.raises(DesignError) as err:
        kind.synthesize(_spec(RECIPES / "polyfocal-fourfocal-2d-60deg.yaml", **bif, focal_axis_z=-20.0))
    assert err.value.field == "design.focal_axis_z"
    with pytest.raises(Exception, match="design.focal_axis_z"):
        _spec(RECIPES / "polyfocal-fourfocal-2d-60deg.yaml", focal_axis_z=-31.1)


def test_seed_comparison_is_on_its_own_60_degree_view():
    """The seed's comparison lenses are scanned over ±30° whatever the user's view angle."""
    kind = adapter("polyfocal")
    wide = kind.synthesize(_spec(RECIPES / "polyfocal-fourfocal-2d-60deg.yaml", view_angle_deg=100))
    narrow = kind.synthesize(_spec(RECIPES / "polyfocal-fourfocal-2d-60deg.yaml", view_angle_deg=40))
    for a, b in zip(wide.comparison, narrow.comparison):
        assert a.angle_deg.max() == 30.0 and a.max == b.max
    tri, four = wide.comparison[1].max, wide.comparison[2].max
    assert 1.2 < tri / four < 1.4                     # seed-001 §1.3: four-focal ≈ 1.5× lower


@pytest.fixture(scope="module")
def five():
    spec = _spec(RECIPES / "polyfocal-fivefocal-3d-w.yaml")
    return spec, adapter("polyfocal").synthesize(spec)


def test_five_focal_sigma_at_the_design_foci_and_on_the_fitted_sphere(five):
    """The W lens (seed-001 §2.4 ex. 3) is exact at its five foci (σ ≤ 1e-12 D there, each with its
    own output direction). Its focal sphere is fitted by minimising the peak σ over the view: no
    worse than the least-squares sphere through the foci on the fit's angles."""
    spec, design = five
    assert design.foci_sigma.max() < 1e-12 and np.allclose(design_foci_sigma(design.dense), design.foci_sigma)
    lens = design.dense
    zc, radius = design.focal[:2]
    lsq = focal_sphere(np.array([f.point for f in lens.foci]))
    angles = np.radians(np.linspace(-30, 30, 9))

    def peak(sphere):
        return max(best_direction(lens, source_on(*sphere, a, az))[0] for a in angles for az in (0.0, np.pi / 2))

    assert peak((zc, radius)) <= peak(lsq)
    assert (zc, radius) == pytest.approx(fitted_sphere(lens, 30.0), abs=1e-9)
    fig = adapter("polyfocal").summary(spec, design, None)
    assert fig["design_foci_sigma_over_D_max"] < 1e-12
    assert fig["focal_radius_mm"] == pytest.approx(radius * spec.design.unit_mm)
