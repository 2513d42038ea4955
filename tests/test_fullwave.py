"""Full-wave check: the Meep runner against analytic fields, its convergence, the cache, the
fast sub-wavelength model against the stored Meep table, and the verdict plumbing.

Tests that need Meep (Debian python3-meep; the ``meep`` fixture of tests/conftest.py) run in CI
(CI=true: a missing Meep fails them) and are skipped elsewhere with "Meep not found, install python3-meep"."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.aperture import aperture_stats, difference_stats, phase_stats
from antenna_cad.fullwave.deck import make_deck
from antenna_cad.fullwave.runner import feed_fields
from antenna_cad.spec.common import VerificationSpec
from tests.fullwave_cases import CASES, case_lens

TABLE = Path(__file__).parent / "data" / "fullwave_table.csv"
FAST_WORST_RMS_ERROR_DEG = 1.1      # README "Full-wave check": worst |fast − Meep| RMS over the table
LAM = 30.0                          # 10 GHz


@pytest.fixture(autouse=True)
def cache(fullwave_cache):
    return fullwave_cache


def _free_deck(parts, resolution, feed_z_lambda=-100.0, radius_lambda=6.0, pattern="dipole"):
    return make_deck(parts, frequency_ghz=10.0, resolution=resolution, feed_z_mm=feed_z_lambda * LAM,
                     feed_pattern=pattern, feed_q=2.0, radius_mm=radius_lambda * LAM, plane_offset_lambda=2.0,
                     field_map=False)


def test_huygens_sheet_reproduces_the_analytic_feed_in_free_space(meep):
    """The sheet 1.5 λ in front of 'the lens' (an empty one) against the feed's analytic field 3.5 λ
    further on: ≤ 1° p-p, ≤ 0.05 dB over 0.5 λ ≤ r ≤ 0.9 R; the back lobe ≥ 20 dB down (the sign of M)."""
    slab = [{"label": "nothing", "eps_r": 1.0, "polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]}]
    for pattern in ("dipole", "cos_q"):
        deck = _free_deck(slab, 12.0, pattern=pattern)
        out, = solver.run_decks([deck], meep)
        r = out["r_mm"]
        dz = (deck["plane_z_mm"] - deck["feed"]["z_mm"]) / LAM
        exact = feed_fields(r / LAM, np.full_like(r, dz), 2 * np.pi, pattern, 2.0)[0]
        p2p, _ = difference_stats(r, out["er"], exact, LAM, 6.0 * LAM)
        ratio = np.abs(out["er"] / exact)
        sel = (r >= 0.5 * LAM) & (r <= 5.4 * LAM)
        assert p2p <= 1.0, pattern
        assert np.ptp(20 * np.log10(ratio[sel])) <= 0.1, pattern
    back = dict(deck, plane_z_mm=deck["sheet_z_mm"] - 0.6 * LAM + 0.1)
    out_back, = solver.run_decks([back], meep)
    assert 20 * np.log10(np.abs(out["er"][sel]).mean() / np.abs(out_back["er"][sel]).mean()) >= 20


def test_uniform_slab_matches_plane_wave_slab_theory(meep):
    """A slab εr 1.2, 1.25 λ thick, lit from 400 λ (locally a plane wave): its field over the empty run's
    near the axis equals the slab's transmission e^{−ik0d}/(cos δ − i(n + 1/n)/2·sin δ), δ = nk0d, within
    1.5° (of 43°: the Yee grid's dispersion, (kΔ)²/24 of the extra path, is ≈ 1° at 16 px/λ) and 0.1 dB."""
    eps, d = 1.2, 1.25 * LAM
    slab = [{"label": "slab", "eps_r": eps, "polygon": [[0, 0], [20 * LAM, 0], [20 * LAM, d], [0, d]]}]
    air = [dict(slab[0], eps_r=1.0)]
    with_slab, empty = solver.run_decks([_free_deck(p, 16.0, feed_z_lambda=-400.0) for p in (slab, air)], meep, 2)
    r = with_slab["r_mm"]
    sel = (r >= 0.5 * LAM) & (r <= 2.0 * LAM)
    got = np.mean(with_slab["er"][sel] / empty["er"][sel])
    n, k0 = eps ** 0.5, 2 * np.pi / LAM
    delta = n * k0 * d
    theory = np.exp(-1j * k0 * d) / (np.cos(delta) - 0.5j * (n + 1 / n) * np.sin(delta))
    assert np.degrees(np.angle(got / theory)) == pytest.approx(0.0, abs=1.5)
    assert 20 * np.log10(abs(got) / abs(theory)) == pytest.approx(0.0, abs=0.1)


@pytest.mark.slow
def test_stepped_minus_ideal_converges_between_two_resolutions(meep):
    """εr 1.3, D 300 mm, F 900 mm, 10 mm sheets (10 λ): stepped − ideal at 10 and 16 px/λ within 0.5°."""
    lens = case_lens(1.3, 300.0, 900.0, 10.0, 10.0)
    stats = []
    for res in (10.0, 16.0):
        settings = VerificationSpec(resolution_px_per_lambda=res)
        ideal, stepped = solver.run_decks([lens.deck(v, settings, False) for v in ("ideal", "stepped")], meep, 2)
        stats.append(difference_stats(ideal["r_mm"], stepped["er"], ideal["er"], LAM, lens.radius_mm))
    (p10, r10), (p16, r16) = stats
    assert abs(p10 - p16) <= 0.5 and abs(r10 - r16) <= 0.5, stats
    assert r16 > 0.5          # the staircase is seen at all


def test_cache_reuses_an_unchanged_deck(meep, tmp_path):
    deck = _free_deck([], 8.0, radius_lambda=3.0)
    first, = solver.run_decks([deck], meep)
    assert not first["cached"] and solver.estimate_s([deck]) == 0.0
    again, twin = solver.run_decks([deck, dict(deck)], meep)
    assert again["cached"] and twin["cached"] and np.array_equal(again["er"], first["er"])
    assert list((tmp_path / "cache").glob("*.npz"))


def _table():
    with TABLE.open(encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def test_meep_table_covers_the_issue_range():
    rows = _table()
    eps = [float(r["eps_r"]) for r in rows]
    f_d = [float(r["focal_length_mm"]) / float(r["diameter_mm"]) for r in rows]
    sheets = [float(r["sheet_mm"]) for r in rows]
    assert len(rows) >= 8 and min(eps) <= 1.03 and max(eps) >= 1.3
    assert min(f_d) <= 2.0 and max(f_d) >= 10.0 and min(sheets) <= 10 and max(sheets) >= 100
    assert all(r["method"].startswith("meep") for r in rows)


@pytest.mark.parametrize("row", _table(), ids=lambda r: f"eps{r['eps_r']}-D{r['diameter_mm']}-t{r['sheet_mm']}")
def test_fast_model_against_the_meep_table(row):
    """The fast model's stepped − ideal RMS within FAST_WORST_RMS_ERROR_DEG of Meep's on every row,
    and much nearer than the thin screen where zones are sub-wavelength."""
    case = tuple(float(row[k]) for k in ("eps_r", "diameter_mm", "focal_length_mm", "sheet_mm", "frequency_ghz"))
    lens = case_lens(*case)
    r = np.linspace(0.0, lens.radius_mm, 600)
    _, rms = phase_stats(r, lens.fast_difference_deg("stepped", 2.0, r), lens.wavelength_mm, lens.radius_mm)
    meep_rms, thin_rms = float(row["meep_diff_rms_deg"]), float(row["thin_screen_rms_deg"])
    assert abs(rms - meep_rms) <= FAST_WORST_RMS_ERROR_DEG
    assert abs(rms - meep_rms) < abs(thin_rms - meep_rms)


def test_fast_model_keeps_uniform_excess_and_averages_a_sub_wavelength_grating():
    """Uniform excess foam: exactly the thin screen. A sawtooth of period λ/3 (evanescent orders): only
    its mean survives 2 λ on, the ripple < 5 % of the thin screen's."""
    from antenna_cad.fullwave.fastmodel import fast_phase, thin_screen_deg
    n, radius = 1.1, 20 * LAM
    r = np.linspace(2 * LAM, 16 * LAM, 300)
    uniform = fast_phase(lambda x: np.full_like(x, 50.0), n, LAM, radius, 2 * LAM, r)
    assert np.abs(uniform - thin_screen_deg(50.0, n, LAM)).max() < 1e-6
    saw = fast_phase(lambda x: 40.0 * ((x / (LAM / 3)) % 1.0), n, LAM, radius, 2 * LAM, r)
    assert np.ptp(saw) < 0.05 * thin_screen_deg(40.0, n, LAM)
    assert np.mean(saw) == pytest.approx(thin_screen_deg(20.0, n, LAM), rel=0.05)


def test_aperture_stats_of_known_fields():
    r = np.linspace(0, 300, 1001)
    quad = np.exp(1j * np.radians(10 * (r / 270) ** 2)) * np.exp(-(r / 400) ** 2)
    st = aperture_stats(r, quad, LAM, 300.0)
    assert st.p2p_deg == pytest.approx(10 * (1 - (0.5 * LAM / 270) ** 2), rel=1e-3)
    assert st.taper_db == pytest.approx(20 * np.log10(np.exp(-(270 / 400) ** 2) / np.exp(-(LAM / 400) ** 2)), abs=0.05)
    assert -0.05 < st.phase_efficiency_db < 0


# ------------------------------------------------------------------ the stage in the pipeline

ROOT = Path(__file__).resolve().parents[1]


def _recipe(**verification):
    import yaml
    data = yaml.safe_load((ROOT / "recipes" / "xps-collimator-0.5m.yaml").read_text())
    data["outputs"] = {"step": False, "stl": False, "templates": False, "report": False}
    data["verification"] = verification
    return data


def _verify(data):
    from antenna_cad.registry import adapter
    from antenna_cad.spec import parse_spec
    spec = parse_spec(data)
    kind = adapter(spec.kind)
    design = kind.synthesize(spec)
    layup, panels = kind.plan(spec, design)
    return kind.verify(spec, design, layup, kind.fabricate(spec, design, layup, panels))


def test_without_meep_verdicts_follow_the_fast_model_and_say_why():
    v = _verify(_recipe())
    note = next(c for c in v.checks if c.name == "full_wave")
    assert "skipped: Meep not found, install python3-meep" in note.message and "fast sub-wavelength" in note.message
    assert note.status == "skip"                                         # a stage that did not run is not a pass
    assert not any(k.startswith("fullwave_") for k in v.figures)
    sanding = next(c for c in v.checks if c.name == "unsanded_step_phase_error")
    assert "quiet zone" in sanding.message and "fast sub-wavelength model" in sanding.message
    assert sanding.value == pytest.approx(v.figures["stack_zone_fabricated_on_axis_p2p_deg"])   # over the zone
    assert f"on one plane {v.figures['model_fabricated_on_axis_p2p_deg']:.1f}°" in sanding.message  # kept beside
    assert sanding.value < v.figures["fabricated_on_axis_p2p_deg"]          # GO is the pessimist here
    deck = json.loads(v.files["fullwave/stepped.json"])
    assert deck["frequency_ghz"] == 10.0 and deck["resolution_px_per_lambda"] == 16.0
    assert deck["feed"] == {"z_mm": -4000.0, "pattern": "dipole", "q": 1.0}
    assert {p["eps_r"] for p in deck["parts"]} == {1.047} and len(deck["parts"]) == 7      # one per 50 mm sheet
    assert all(p["polygon"][2][1] - p["polygon"][0][1] == pytest.approx(50.0) for p in deck["parts"])
    assert "runner.py stepped.json stepped.npz" in v.files["fullwave/rerun.sh"]


def test_the_budget_stops_the_runs_and_the_verdicts_keep_the_fast_model(meep):
    """``on`` with budget_s 3 s: Meep starts on the default lens (tens of seconds of runs) and is stopped;
    the check warns naming what was cut, the verdicts follow the fast model, no full-wave figures."""
    v = _verify(_recipe(full_wave="on", budget_s=3))
    checks = {c.name: c for c in v.checks}
    note, edge = checks["full_wave"], checks["full_wave_scan_edge"]
    assert note.status == "warn" and "0 of 2 runs" in note.message, note.message
    assert "cut at budget_s 3 s: ideal, stepped, fabricated did not finish" in note.message
    assert "from the fast sub-wavelength model" in note.message and "cut by the budget" in note.message
    assert "fast sub-wavelength model" in checks["unsanded_step_phase_error"].message
    assert edge.status == "warn" and "no scan-edge figures" in edge.message
    assert v.figures["fullwave_runs_cut"] == 2.0 and not any(k.endswith("_on_axis_p2p_deg") and k.startswith("fullwave")
                                                             for k in v.figures)
    assert not list(solver.cache_dir().glob("*.npz"))


def test_auto_over_budget_says_so_and_on_without_meep_is_an_error(monkeypatch, tmp_path):
    from typer.testing import CliRunner
    import yaml
    from antenna_cad.cli import app
    monkeypatch.setattr(solver, "meep_python", lambda: "/usr/bin/python3")
    v = _verify(_recipe(budget_s=1))
    note = next(c for c in v.checks if c.name == "full_wave")
    assert "skipped: estimated" in note.message and "> budget_s 1 s" in note.message
    assert note.status == "skip"
    monkeypatch.setattr(solver, "meep_python", lambda: None)
    spec = tmp_path / "on.yaml"
    spec.write_text(yaml.safe_dump(_recipe(full_wave="on")))
    result = CliRunner().invoke(app, ["build", str(spec), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and "verification.full_wave: on, but Meep not found" in result.output
    assert not (tmp_path / "out" / "xps-collimator-0.5m").exists()


@pytest.mark.parametrize("block, message", [
    ({"full_wave": "maybe"}, "verification.full_wave: must be 'auto', 'on' or 'off'"),
    ({"resolution_px_per_lambda": 4}, "verification.resolution_px_per_lambda: must be ≥ 6"),
    ({"plane_offset_lambda": 1}, "verification.plane_offset_lambda: must be ≥ 2"),
    ({"budget": 10}, "verification.budget: unknown key"),
])
def test_verification_block_errors_name_the_field(block, message):
    from antenna_cad.spec import SpecError, parse_spec
    with pytest.raises(SpecError) as err:
        parse_spec(_recipe(**block), "spec.yaml")
    assert any(line.startswith(f"spec.yaml: {message}") for line in err.value.lines), err.value.lines


@pytest.mark.slow
def test_default_recipe_full_wave_figures_deck_and_plots(meep, tmp_path):
    from antenna_cad.pipeline import build
    from antenna_cad.spec import parse_spec
    data = _recipe()
    data["outputs"]["report"] = True
    result = build(parse_spec(data), tmp_path)
    figures = json.loads((result.out_dir / "manifest.json").read_text())["verification"]["figures"]
    for lens in ("ideal", "stepped", "fabricated"):
        for k in ("p2p_deg", "rms_deg", "taper_db", "phase_efficiency_db"):
            assert np.isfinite(figures[f"fullwave_{lens}_on_axis_{k}"])
    for k in ("fullwave_stepped_minus_ideal_p2p_deg", "fullwave_stepped_minus_ideal_rms_deg",
              "fullwave_resolution_px_per_lambda", "fullwave_seconds"):
        assert np.isfinite(figures[k])
    # the staircase of sub-wavelength zones: full-wave well below GO and the thin screen (table row)
    assert figures["fullwave_stepped_minus_ideal_rms_deg"] < 0.5 * figures["stepped_on_axis_rms_deg"]
    assert {"ideal.json", "stepped.json", "fabricated.json", "rerun.sh", "runner.py"} <= \
        {p.name for p in (result.out_dir / "fullwave").iterdir()}
    html = (result.out_dir / "report.html").read_text()
    assert all(f'id="plot-fullwave-{n}"' in html for n in ("aperture-phase", "aperture-amplitude", "field-map"))
    again = build(parse_spec(data), tmp_path)          # unchanged geometry: every run from the cache
    first, second = (next(c.message for c in r.checks if c.name == "full_wave") for r in (result, again))
    assert "2 of 2 runs (" in first and "from the cache" not in first           # fabricated = as cut: one run
    assert "2 of 2 runs (2 from the cache" in second
    cost = again.verified                              # the rebuild spent nothing; the solver time it saved beside it
    assert result.verified["fullwave_cached_solver_seconds"] == 0.0 < cost["fullwave_cached_solver_seconds"]
    assert cost["fullwave_seconds"] < cost["fullwave_cached_solver_seconds"]


@pytest.mark.slow
def test_meep_converges_to_the_mie_series_behind_a_small_luneburg_sphere(meep):
    """A 5-shell Luneburg sphere, D = 4 λ, εi = 2 − (ri/R)² at mid-shell, lit by a plane wave (the
    Huygens sheet of a feed 10⁵ λ away): Meep's co-polar field over the empty run's, on the plane 2 λ
    behind the sphere, against the exact multilayer-sphere series (scattnlay) over 0.5 λ ≤ r ≤ 1.8 λ.
    The dense core needs a fine grid: measured 1.7 dB / 13.5° worst at 16 px/λ, 0.96 dB / 8.1° at 24."""
    from antenna_cad.fullwave.mie import mie_field, shell_parts
    R = 2 * LAM
    radii = R * np.arange(1, 6) / 5
    eps = 2 - ((radii - R / 10) / R) ** 2
    errors = []
    for res in (16.0, 24.0):
        decks = [make_deck(parts, frequency_ghz=10.0, resolution=res, feed_z_mm=-1e5 * LAM, feed_pattern="dipole",
                           feed_q=1.0, radius_mm=2 * R, plane_offset_lambda=2.0, field_map=False)
                 for parts in (shell_parts(radii, eps), [dict(p, eps_r=1.0) for p in shell_parts(radii, eps)])]
        sphere, empty = solver.run_decks(decks, meep, 2)
        r = sphere["r_mm"]
        sel = (r >= 0.5 * LAM) & (r <= 0.9 * R)
        z = decks[0]["plane_z_mm"]
        exact = mie_field(radii, eps, LAM, np.column_stack([r[sel], 0 * r[sel], np.full(sel.sum(), z)]))[:, 0]
        ratio = sphere["er"][sel] / empty["er"][sel] / (exact / np.exp(2j * np.pi * z / LAM))
        errors.append((np.abs(20 * np.log10(np.abs(ratio))).max(), np.abs(np.degrees(np.angle(ratio / ratio.mean()))).max()))
    (db16, deg16), (db24, deg24) = errors
    assert db24 < db16 and deg24 < deg16, errors
    assert db24 < 1.2 and deg24 < 10.0, errors
