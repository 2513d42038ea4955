"""Full-wave stage of the Luneburg kind: the runner's point feed and graded sphere,
the sphere's variants as the runner sees them, the exact Mie focal gain, the stage on a small sphere
(Meep against Mie), and auto declining a large sphere with its reason (no Meep needed)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.mie import shell_parts
from antenna_cad.fullwave.runner import fill_fraction, graded_fill
from antenna_cad.fullwave.sphere import C_MM_GHZ, aperture_gain_dbi, fine_shells, mie_focal_gain_dbi
from antenna_cad.kinds import luneburg_fullwave
from antenna_cad.kinds.luneburg_fullwave import medium_parts
from antenna_cad.raytrace.media import Staircase

from tests.test_fullwave import _verify

LAM = 30.0


def _sphere(diameter_mm=120.0, **verification):
    """A small classic 5-shell sphere at 10 GHz (D = 4 λ), foam grades 1.2…2.0 (as built ≠ design)."""
    return {"name": "lune-small", "kind": "luneburg", "frequency_ghz": 10.0, "material": "polystyrene",
            "design": {"diameter_mm": diameter_mm, "law": "classic", "layers": {"count": 5, "split": "equal_eps"},
                       "grades": [1.2, 1.4, 1.6, 1.8, 2.0]},
            "fabrication": {"method": "shells"},
            "outputs": {"step": False, "stl": False, "templates": False, "report": False},
            "verification": verification}




def _note(v):
    return next(c for c in v.checks if c.name == "full_wave")


def test_graded_sphere_rasterizes_as_its_polygon():
    """The runner's per-pixel ε(r) of a uniform sphere equals the area fractions of its polygon
    (same sub-samples), and a two-zone table gives the two εr where each zone is whole."""
    edges_r, edges_z = np.linspace(0, 3, 31), np.linspace(-3, 3, 61)
    table = {"center_z": 0.0, "r": [0.0, 2.0, 2.0 + 1e-12], "eps_r": [1.5, 1.5, 1.0]}
    poly = fill_fraction(shell_parts([2.0], [1.5]), edges_r, edges_z) - 1.0
    np.testing.assert_allclose(graded_fill([table], edges_r, edges_z), poly, atol=0.02)
    two = {"center_z": 0.0, "r": [0.0, 1.0, 1.0 + 1e-9, 2.0, 2.0 + 1e-9], "eps_r": [2.0, 2.0, 1.5, 1.5, 1.0]}
    eps = 1.0 + graded_fill([two], edges_r, edges_z)
    assert eps[2, 30] == pytest.approx(2.0) and eps[14, 30] == pytest.approx(1.5) and eps[25, 30] == 1.0


def test_staircase_medium_becomes_ring_rectangles():
    st = Staircase.from_rings([-10.0, 0.0, 10.0], [[(0.0, 5.0, 1.4), (5.0, 9.0, 1.2)], [(3.0, 8.0, 1.1)]])
    parts = medium_parts(st, "stepped")
    assert [(p["eps_r"], p["polygon"][0][0], p["polygon"][1][0], p["polygon"][0][1], p["polygon"][2][1])
            for p in parts] == [(pytest.approx(1.96), 0.0, 5.0, -10.0, 0.0), (pytest.approx(1.44), 5.0, 9.0, -10.0, 0.0),
                                (pytest.approx(1.21), 3.0, 8.0, 0.0, 10.0)]


def test_taper_cut_rings_become_trapezoids():
    """A taper-cut ring's cones: its quadrilateral's corners are the cones at the two sheet faces
    (a disc's inner edge on the axis)."""
    st = Staircase.from_cones([-10.0, 0.0, 10.0], [[((0.0, 0.0), (4.0, 6.0), 1.4), ((4.0, 6.0), (8.0, 9.0), 1.2)],
                                                  [((0.0, 0.0), (6.0, 3.0), 1.1)]])
    assert [(round(p["eps_r"], 6), p["polygon"]) for p in medium_parts(st, "as_built")] == [
        (1.96, [[0.0, -10.0], [4.0, -10.0], [6.0, 0.0], [0.0, 0.0]]),
        (1.44, [[4.0, -10.0], [8.0, -10.0], [9.0, 0.0], [6.0, 0.0]]),
        (1.21, [[0.0, 0.0], [6.0, 0.0], [3.0, 10.0], [0.0, 10.0]])]


def test_mie_focal_gain_limits():
    """Gain of a dipole-fed lens by reciprocity, 1.5·|E(focus)|²: an air sphere gives the dipole's
    1.76 dBi; the continuous law (thin Mie shells, converged in their count) stays below the uniform
    aperture's (πD/λ)² and above the 5-shell lens of the same sphere."""
    assert mie_focal_gain_dbi([50.0], [1.0], LAM, 50.0) == pytest.approx(10 * np.log10(1.5), abs=1e-9)
    R = 3 * LAM
    law = lambda r: 2.0 - (np.asarray(r) / R) ** 2                      # noqa: E731
    ideal = mie_focal_gain_dbi(*fine_shells(law, R, LAM), LAM, R)
    finer = mie_focal_gain_dbi(R * np.arange(1, 241) / 240, law(R * (np.arange(240) + 0.5) / 240), LAM, R)
    radii = R * np.arange(1, 6) / 5
    shells = mie_focal_gain_dbi(radii, law(radii - R / 10), LAM, R)
    assert abs(ideal - finer) < 0.02 and shells < ideal < aperture_gain_dbi(R, LAM)


def test_auto_declines_a_large_sphere_and_says_why(monkeypatch, fullwave_cache):
    """D/λ = 100 with Meep 'present' (never started): the estimate exceeds the budget, the note says
    so with D/λ; no full-wave figures; the Mie figures are there; decks are still written."""
    monkeypatch.setattr(solver, "meep_python", lambda: "/nonexistent/python3")
    v = _verify(_sphere(diameter_mm=100 * C_MM_GHZ / 10.0))
    note = _note(v).message
    assert "skipped: estimated" in note and "> budget_s 120 s" in note and "D/λ = 100" in note, note
    assert not any(k.startswith("fullwave_") for k in v.figures)
    assert v.figures["mie_ideal_focal_gain_dbi"] < v.figures["aperture_gain_limit_dbi"]
    assert json.loads(v.files["fullwave/ideal.json"])["feed"] == {"kind": "point", "z_mm": -1498.96229, "pattern": "dipole"}
    monkeypatch.setattr(luneburg_fullwave, "MIE_MAX_D_LAMBDA", 2.0)       # as a sphere of D/λ > 200 would
    small = _verify(_sphere(budget_s=1))
    assert "Mie series not evaluated above D/λ = 2" in _note(small).message
    assert not any(k.startswith("mie_") for k in small.figures)


def test_cylinder_lens_is_not_run_and_says_why(monkeypatch):
    monkeypatch.setattr(solver, "meep_python", lambda: "/nonexistent/python3")
    data = _sphere()
    data["design"] |= {"shape": "cylinder", "height_mm": 10, "focal_distance_ratio": 1.2, "law": "generalized"}
    note = _note(_verify(data)).message
    assert "not a body of revolution" in note


def test_point_huygens_feed_radiates_forward(meep, fullwave_cache):
    """The point Huygens element (Er + Hφ) in free space: ≥ 30 dB more field 2.5 λ ahead than behind;
    the point dipole alone radiates both ways alike."""
    decks = [{"frequency_ghz": 10.0, "resolution_px_per_lambda": 10.0, "m": 1, "parts": [],
              "feed": {"kind": "point", "z_mm": 0.0, "pattern": p}, "plane_z_mm": 3 * LAM, "r_max_mm": 2 * LAM,
              "z_min_mm": -4 * LAM, "z_max_mm": 4 * LAM, "pml_r_lambda": 2.0, "pml_z_lambda": 2.0, "field_map": True}
             for p in ("dipole", "huygens")]
    ratios = []
    for out in solver.run_decks(decks, meep, 2):
        m, ext = out["map_abs"], out["map_extent_mm"]
        z = np.linspace(ext[2], ext[3], m.shape[1])
        ratios.append(20 * np.log10(m[2, np.argmin(abs(z - 2.5 * LAM))] / m[2, np.argmin(abs(z + 2.5 * LAM))]))
    assert abs(ratios[0]) < 0.5 and ratios[1] > 30, ratios


@pytest.mark.slow
def test_stage_on_a_small_sphere_against_mie(meep, fullwave_cache):
    """D = 4 λ, 16 px/λ: every variant's figures; Meep's plane-wave focal gain of the design shells
    within 1 dB of the exact multilayer series; the grades (as built) are a different run from the
    design shells; the decks and plots are there; a rebuild comes from the cache."""
    v = _verify(_sphere(full_wave="on"))
    f = v.figures
    for lens in ("ideal", "stepped", "fabricated"):
        for k in ("p2p_deg", "rms_deg", "taper_db", "phase_efficiency_db"):
            assert np.isfinite(f[f"fullwave_{lens}_on_axis_{k}"])
    assert abs(f["fullwave_shells_focal_gain_minus_mie_db"]) < 1.0, f
    assert next(c for c in v.checks if c.name == "fullwave_vs_mie").status == "pass"
    assert f["fullwave_stepped_minus_ideal_rms_deg"] > 0 and f["fullwave_fabricated_minus_ideal_rms_deg"] > 0
    assert f["fullwave_fabricated_minus_ideal_rms_deg"] != f["fullwave_stepped_minus_ideal_rms_deg"]
    assert f["mie_fabricated_focal_gain_dbi"] != f["mie_shells_focal_gain_dbi"]
    assert "5 of 5 runs (" in _note(v).message
    assert {"fullwave-aperture-phase", "fullwave-aperture-amplitude", "fullwave-focal-spot",
            "fullwave-field-map"} <= {p.name for p in v.plots}
    ideal = json.loads(v.files["fullwave/ideal.json"])
    assert ideal["parts"] == [] and ideal["graded"][0]["eps_r"][0] == 2.0 and ideal["graded"][0]["eps_r"][-1] == 1.0
    assert "5 of 5 runs (5 from the cache" in _note(_verify(_sphere(full_wave="on"))).message


def test_on_without_meep_is_an_error_naming_the_field(monkeypatch):
    from antenna_cad.synthesis.checks import DesignError
    monkeypatch.setattr(solver, "meep_python", lambda: None)
    with pytest.raises(DesignError, match="Meep not found"):
        _verify(_sphere(full_wave="on"))


@pytest.mark.slow
def test_classic_5_recipe_runs_its_stage_under_auto(meep, fullwave_cache, tmp_path):
    """luneburg-classic-5 (D = 10 λ) with the default verification block: auto runs (its estimate fits
    budget_s); the steps' error full-wave is well below GO's (the shells' zones average); Meep's focal
    gain within 1 dB of Mie; manifest figures, the fullwave/ decks and the report's four plots."""
    from pathlib import Path
    from antenna_cad.pipeline import build
    from antenna_cad.spec import load_spec
    spec = load_spec(Path(__file__).resolve().parents[1] / "recipes" / "luneburg-classic-5.yaml")
    spec = spec.model_copy(update={"outputs": spec.outputs.model_copy(update={"step": False, "stl": False,
                                                                              "templates": False})})
    result = build(spec, tmp_path / "out")
    assert "stage ran (estimated" in next(c.message for c in result.checks if c.name == "full_wave")
    figures = json.loads((result.out_dir / "manifest.json").read_text())["verification"]["figures"]
    assert figures["fullwave_stepped_minus_ideal_rms_deg"] < 0.5 * figures["stepped_axis_phase_rms_deg"]
    assert abs(figures["fullwave_shells_focal_gain_minus_mie_db"]) < 1.0
    assert {f"{n}.json" for n in ("ideal", "stepped", "fabricated", "plane_wave_shells", "plane_wave_empty")} <= \
        {p.name for p in (result.out_dir / "fullwave").iterdir()}
    html = (result.out_dir / "report.html").read_text()
    assert all(f'id="plot-fullwave-{n}"' in html for n in ("aperture-phase", "aperture-amplitude", "focal-spot",
                                                           "field-map"))
