"""σ (2.7) against field angle and the §3.8 optimisation of the beam formers (seed-003 §3.3 L486,
§3.8 L1182–1193; R10 of the digest): antenna_cad/synthesis/slot_array/fov.py and optimise.py."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.ellipse import ellipse_mirror
from antenna_cad.synthesis.slot_array.fov import THESIS_SIGMA_80, reference_curves, sigma_at
from antenna_cad.synthesis.slot_array.optimise import EVALUATIONS, OPTIMISED, THESIS_START, optimise

# Why the trifocal two-mirror value of the thesis is not reproduced (evidence in the README, "σ against
# field angle and the §3.8 optimisation"): the thesis's own parameter set admits no march and β_C is not
# given (test_trifocal.py); the best design the §3.8 search finds has σ(80°) = 6.0e-4, 7.5× the thesis's
# 0.8e-4, rising from 7e-6 near its outer beam (27.1°) to the edge of the field of view. The bar stays;
# strict xfail: the test fails the day the value is reached.
TRIFOCAL_NOT_REPRODUCED = pytest.mark.xfail(strict=True, reason="seed-003 §3.8: trifocal two-mirror σ(80°) "
                                            "= 0.8e-4 not reproduced (6.0e-4 at best; see README)")
# The trifocal mirror–lens (§3.7): the thesis's beam angle α = 29° admits no march; with O1 found by the
# search the beams sit at ±14° and σ(80°) = 1.0e-3 against the thesis's 1.2e-4 (README, "the trifocal
# mirror-lens beam former"). Same rule: the bar stays, strict xfail.
MIRROR_LENS_NOT_REPRODUCED = pytest.mark.xfail(strict=True, reason="seed-003 §3.8: trifocal mirror–lens σ(80°) "
                                               "= 1.2e-4 not reproduced (1.0e-3; see README)")
NOT_REPRODUCED = {"trifocal_two_mirror": TRIFOCAL_NOT_REPRODUCED, "trifocal_mirror_lens": MIRROR_LENS_NOT_REPRODUCED}


@pytest.fixture(scope="module")
def curves():
    return {c.name: c for c in reference_curves()}


def test_sigma_refers_to_the_central_ray():
    """(2.7): σ = √(Σ(L_i − L_0)²/N) with L_0 the central ray, not the mean path. A former whose paths
    carry a pure defocus error k·x² (x across the aperture, D = 1) has σ = k·√⟨x⁴⟩, not k·std(x²)."""
    ell = ellipse_mirror(0.8, 0.25, 0.5)
    k = 1e-3
    fake = replace(ell, trace=lambda src, x: (None, k * np.asarray(x) ** 2, np.ones(np.shape(x), bool), ()),
                   eikonal=lambda x, j: np.zeros(np.shape(x)))
    x = np.linspace(-0.5, 0.5, 50)
    sigma, tilt = sigma_at(fake, (0.0, 1.0), x)
    assert sigma == pytest.approx(k * math.sqrt(np.mean(x**4)), rel=1e-12) and abs(tilt) < 1e-15
    assert sigma / (k * np.std(x**2)) == pytest.approx(1.5, abs=0.01)


def test_design_foci_are_perfect_for_every_reference_former(curves):
    for name, c in curves.items():
        assert c.sigma.min() < 5e-5, name


R10_FORMERS = list(THESIS_SIGMA_80)       # the four formers of Fig. 3.15, all among the reference curves


@pytest.mark.parametrize("name", [pytest.param(n, marks=NOT_REPRODUCED[n]) if n in NOT_REPRODUCED else n
                                  for n in R10_FORMERS])
def test_r10_each_sigma_80_within_a_factor_2_of_the_thesis(curves, name):
    """R10: σ over the 80° field of view, each former optimised (§3.8), within ×2 of Fig. 3.15's value."""
    value = curves[name].sigma_fov()
    assert THESIS_SIGMA_80[name] / 2 < value < 2 * THESIS_SIGMA_80[name]


def test_r10_bifocal_formers_keep_the_thesis_order(curves):
    """R10 ordering among the bifocal formers: two-mirror (3.4e-4) below the ellipse (5.6e-4)."""
    assert curves["bifocal_two_mirror"].sigma_fov() < curves["single_mirror"].sigma_fov()


@TRIFOCAL_NOT_REPRODUCED
def test_r10_ordering_of_all_formers(curves):
    """R10: trifocal two-mirror < trifocal mirror–lens < bifocal two-mirror < ellipse (those built here)."""
    assert sorted(R10_FORMERS, key=lambda n: curves[n].sigma_fov()) == sorted(R10_FORMERS, key=THESIS_SIGMA_80.get)


def test_optimiser_improves_the_ellipse_deterministically():
    """§3.8 on the ellipse: from the §2.4 focal separation (dF/D = 0.25) the search runs to the
    upper bound of the thesis's dF/D range, σ(80°) falling ≈ 1.29×; twice the same answer."""
    params, hw = THESIS_START["single_mirror"]
    a, b = optimise("single_mirror", params, hw, evaluations=12), optimise("single_mirror", params, hw, evaluations=12)
    assert a == b
    assert a.found == pytest.approx((0.45,)) and a.sigma_found < a.sigma_start / 1.25
    assert a.found == pytest.approx(tuple(OPTIMISED["single_mirror"][k] for k in a.names))


def test_optimiser_rejects_formers_without_free_parameters_and_bad_starts():
    with pytest.raises(DesignError) as err:
        optimise("bifocal_mirror_lens", {}, 0.5)
    assert err.value.field == "beamformer.optimize"
    params, hw = THESIS_START["single_mirror"]
    with pytest.raises(DesignError, match="outside the search bounds"):
        optimise("single_mirror", params | {"focal_separation": 0.6}, hw)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["bifocal_two_mirror", "trifocal_two_mirror"])
def test_optimiser_reproduces_the_reference_parameters(name):
    """The stored optimised parameters of the report's reference formers are the search's result
    from the thesis's start (deterministic Nelder–Mead, same budget)."""
    params, hw = THESIS_START[name]
    opt = optimise(name, params, hw, evaluations=EVALUATIONS[name])
    assert opt.found == pytest.approx(tuple(OPTIMISED[name][k] for k in opt.names), rel=1e-6)
    assert opt.sigma_found < opt.sigma_start / 1.5


def test_trifocal_beams_are_perfect_and_the_curve_is_lowest_between_them(curves):
    """Issue 15: the three design beams are perfect (σ < 1e-7 with the source at each focus), the σ
    curve's only minima in the field of view are at the beams (0, ±α), and between the beams σ stays
    below its value at the edge of the field of view."""
    from antenna_cad.synthesis.slot_array.fov import reference_formers
    bf, hw = reference_formers()["trifocal_two_mirror"]
    x = np.linspace(-hw, hw, 50)
    assert max(sigma_at(bf, F, x)[0] for F in bf.foci_mm) < 1e-7
    alpha = math.degrees(bf.params["alpha_rad"])
    c = curves["trifocal_two_mirror"]
    inside = np.abs(c.angle_deg) <= 40
    a, s = c.angle_deg[inside], c.sigma[inside]
    minima = a[1:-1][(s[1:-1] < s[:-2]) & (s[1:-1] < s[2:])]
    step = np.max(np.diff(a))
    assert len(minima) == 3 and np.all(np.abs(np.sort(minima) - [-alpha, 0.0, alpha]) < step)
    assert s[np.abs(a) < alpha].max() < c.sigma_fov() / 1.5


def test_spec_optimize_searches_the_free_parameters_and_reports_them():
    """``beamformer.optimize: true`` on the X-band ellipse recipe: the focal separation found by the
    §3.8 search is used and reported with σ(80°) before and after; the mirror–lens former has no
    search and says so naming the field."""
    import yaml

    from antenna_cad.kinds.slot_array import synthesize
    from antenna_cad.spec.slot_array import SlotArraySpec
    raw = yaml.safe_load(open("recipes/x-slot-array-ellipse.yaml"))
    raw["beamformer"] |= {"optimize": True, "optimize_evaluations": 12}
    design = synthesize(SlotArraySpec.model_validate(raw))
    fig = design.figures
    D = raw["beamformer"]["scale_mm"]
    assert fig["optimised_focal_separation_start"] == pytest.approx(raw["beamformer"]["focal_separation_mm"] / D)
    assert fig["optimised_focal_separation"] == pytest.approx(0.45)
    assert design.beamformer.params["alpha_rad"] == pytest.approx(math.atan2(0.45 / 2, raw["beamformer"]["minor_semi_axis_mm"] / D))
    assert fig["optimised_sigma_fov80_found"] < fig["optimised_sigma_fov80_start"]
    raw = yaml.safe_load(open("recipes/ka-slot-array-mirror-lens.yaml"))
    raw["beamformer"]["optimize"] = True
    with pytest.raises(DesignError) as err:
        synthesize(SlotArraySpec.model_validate(raw))
    assert err.value.field == "beamformer.optimize"


def test_spec_optimize_on_the_trifocal_recipe_maps_c_and_beta_c():
    """The trifocal search's C and β_C (units of D, thesis frame) reach the built former."""
    import yaml

    from antenna_cad.kinds.slot_array import synthesize
    from antenna_cad.spec.slot_array import SlotArraySpec
    raw = yaml.safe_load(open("recipes/ka-slot-array-trifocal-two-mirror.yaml"))
    raw["beamformer"] |= {"optimize": True, "optimize_evaluations": 2}
    design = synthesize(SlotArraySpec.model_validate(raw))
    fig, bf = design.figures, design.beamformer
    assert (fig["optimised_c_x_start"], fig["optimised_beta_c_deg_start"]) == (-0.16, raw["beamformer"]["beta_c_deg"])
    assert fig["optimised_sigma_fov80_found"] <= fig["optimised_sigma_fov80_start"]
    assert math.degrees(bf.params["beta_c_rad"]) == pytest.approx(fig["optimised_beta_c_deg"], abs=1e-12)
    b0, b2 = bf.params["b0"], bf.params["b2"]                  # mirror 1 passes through the C found
    assert b0 + b2 * fig["optimised_c_x"] ** 2 == pytest.approx(fig["optimised_c_z"], abs=1e-12)
