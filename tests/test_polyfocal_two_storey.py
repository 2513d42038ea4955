"""The two-storey lens–mirror antenna (seed-001 §1.5 Realisation): the §1.5 equal-line lens folded by
U-bends — equal guide lengths and perfect foci recomputed from the line table and the solids with the
seed's own focus positions, the layout's walls and refusals, and a build read back from its files."""

from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

from antenna_cad import pipeline
from antenna_cad.registry import adapter
from antenna_cad.spec import load_spec
from antenna_cad.synthesis.checks import DesignError

RECIPE = Path(__file__).resolve().parents[1] / "recipes" / "polyfocal-two-storey-60ghz.yaml"
F, F1, ALPHA, D_THICK = 1.0, 0.6213, np.radians(56.5), 0.2       # the thesis' 120° design (§1.5)


def _spec(tmp_path: Path, **changes) -> Path:
    data = yaml.safe_load(RECIPE.read_text())
    for path, value in changes.items():
        node = data
        *head, last = path.split("__")
        for key in head:
            node = node[key]
        node[last] = value
    out = tmp_path / "spec.yaml"
    out.write_text(yaml.safe_dump(data))
    return out


def _seed_foci(unit: float):
    """F, F1, F2 and their output directions (seed-001 §1.5, Fig. 11), folded by the mirror (z → −z)."""
    z0 = -D_THICK / 2
    pts = [(0.0, z0 - F), (-F1 * np.sin(ALPHA), z0 - F1 * np.cos(ALPHA)), (F1 * np.sin(ALPHA), z0 - F1 * np.cos(ALPHA))]
    dirs = [(0.0, -1.0), (np.sin(ALPHA), -np.cos(ALPHA)), (-np.sin(ALPHA), -np.cos(ALPHA))]
    return [(np.array(p) * unit, np.array(k)) for p, k in zip(pts, dirs)]


def _table_lengths(rows, h: float, septum: float) -> np.ndarray:
    """Each guide's centre line from the table's positions alone: slanted run to the kink, axial run to
    the bend, the bend (π·(h + septum)/2), the layer-2 run back to the folded exit."""
    col = lambda k: np.array([float(r[k]) for r in rows])       # noqa: E731
    slanted = np.hypot(col("y2_mm") - col("y1_mm"), col("z_kink_mm") - col("z1_mm"))
    return (slanted + col("z_bend_mm") - col("z_kink_mm") + np.pi * (h + septum) / 2
            + col("z_bend_mm") - col("z_exit_folded_mm"))


def test_recipe_layout_is_equal_length_and_pins_the_code_figures():
    spec = load_spec(RECIPE)
    kind = adapter("polyfocal")
    design = kind.synthesize(spec)
    assert all(c.status == "pass" for c in design.checks), [c for c in design.checks if c.status != "pass"]
    ts = design.mirror
    assert np.ptp(ts.total) < 1e-12 * ts.total.max()
    assert np.all(np.diff(ts.y1) > 0) and np.all(np.diff(ts.y2) > 0)
    fig = kind.summary(spec, design, None)
    # the thesis gives no numbers for the realisation: these are the code's (stated in the docs)
    assert fig["guide_count"] == 21
    assert fig["line_length_mm"] == pytest.approx(124.564, abs=2e-3)
    assert fig["layer1_wall_min_mm"] == pytest.approx(0.581, abs=2e-3)
    assert fig["kink_angle_max_deg"] == pytest.approx(13.23, abs=0.02)
    assert fig["bend_radius_mm"] == pytest.approx(1.44)
    assert fig["design_foci_sigma_over_D_max"] < 1e-12


@pytest.mark.parametrize("pitch, words", [(4.3, "guides cross"), (4.6, "wall is")])
def test_walls_too_thin_or_crossing_are_refused(tmp_path, pitch, words):
    spec = load_spec(_spec(tmp_path, design__lines__pitch_mm=pitch))
    with pytest.raises(DesignError) as err:
        adapter("polyfocal").synthesize(spec)
    assert err.value.field == "design.lens_mirror.guide_width_mm" and words in err.value.message


def test_refusal_is_one_line_exit_2_and_writes_nothing(tmp_path):
    path = _spec(tmp_path, design__lines__pitch_mm=4.6)
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, "-m", "antenna_cad", "build", str(path), "-o", str(out)],
                         capture_output=True, text=True, env={"ANTENNA_CAD_MEEP_PYTHON": "/usr/bin/false",
                                                              "PYTHONPATH": str(RECIPE.parents[1])})
    assert run.returncode == 2, run.stderr
    lines = [ln for ln in (run.stdout + run.stderr).splitlines() if ln.strip()]
    assert len(lines) == 1 and "design.lens_mirror.guide_width_mm" in lines[0] and "Traceback" not in run.stderr
    assert not out.exists()


@pytest.mark.parametrize("changes, field", [
    (dict(design__lens_mirror__mouth_height_mm=1.5), "mouth_height_mm"),
    (dict(design__lens_mirror__band_ghz=[75.0, 45.0]), "band_ghz"),
    (dict(design__lens_mirror__guide_width_mm=4.8), "guide_width_mm"),
    (dict(design__lens_mirror__horn_aperture_mm=3.0), "horn_aperture_mm"),
    (dict(design__output="foci", design__symmetry="two_planes",
          design__foci=[{"f": 1.0, "angle_deg": 20.0}]), "design.lens_mirror"),
])
def test_spec_rules(tmp_path, changes, field):
    with pytest.raises(Exception) as err:
        load_spec(_spec(tmp_path, **changes))
    assert field in str(err.value)


def test_build_reads_back_equal_lengths_and_perfect_foci(tmp_path):
    """A small variant (D = 40 mm, 7 guides, 4.5 mm horns: wider ones stand in front of the entry surface)
    built end to end; lengths and foci from its files."""
    path = _spec(tmp_path, design__unit_mm=40.0, design__lines__pitch_mm=6.0,
                 design__lens_mirror__horn_aperture_mm=4.5, name="two-storey-small")
    spec = load_spec(path)
    res = pipeline.build(spec, tmp_path / "out")
    manifest = json.loads((res.out_dir / "manifest.json").read_text())
    statuses = {c["name"]: c["status"] for c in manifest["checks"]}
    assert "fail" not in statuses.values(), statuses
    rows = list(csv.DictReader((res.out_dir / "lines.csv").open()))
    m, ln = spec.design.lens_mirror, spec.design.lines
    from_table = _table_lengths(rows, ln.plate_spacing_mm, m.septum_mm)
    guides = [p for p in manifest["parts"] if p["label"].startswith("guide-")]
    from_solids = np.array([p["volume_mm3"] for p in guides]) / (m.guide_width_mm * ln.plate_spacing_mm)
    assert len(rows) == len(guides) == 7
    np.testing.assert_allclose(from_table, float(rows[0]["l_total_mm"]), atol=5e-6)
    np.testing.assert_allclose(from_solids, from_table, rtol=1e-7)
    p1 = np.array([[float(r["y1_mm"]), float(r["z1_mm"])] for r in rows])
    exit_ = np.array([[float(r["y2_mm"]), float(r["z_exit_folded_mm"])] for r in rows])
    for point, k in _seed_foci(spec.design.unit_mm):
        path_mm = np.linalg.norm(p1 - point, axis=1) + from_solids - exit_ @ k
        assert np.ptp(path_mm) < 2e-5, point          # 1e-6 mm table rounding
    labels = {p["label"] for p in manifest["parts"]}
    assert {"block-lower", "block-upper", "cover"} <= labels
    assert all(p["valid"] for p in manifest["parts"] if not p["label"].startswith("guide-"))
    assert (res.out_dir / "templates").exists() and list((res.out_dir / "templates").glob("layer-1*"))


def test_a_shifted_bend_fails_the_readback(tmp_path):
    """The solids' checks can fail: one guide's bend moved 0.1 mm breaks the equal-length read-back."""
    from dataclasses import replace

    from antenna_cad.geometry.two_storey import build_model
    from antenna_cad.kinds.polyfocal_mirror import foci_mm
    from antenna_cad.materials import Material
    spec = load_spec(_spec(tmp_path, design__unit_mm=40.0, design__lines__pitch_mm=6.0,
                           design__lens_mirror__horn_aperture_mm=4.5))
    design = adapter("polyfocal").synthesize(spec)
    ts = design.mirror
    zm = ts.zm.copy()
    zm[1] += 0.1
    bad = replace(ts, zm=zm)
    air, metal = Material("air", 1, 0, 1.2, ""), Material("al", 1, 0, 2700, "")
    model = build_model(bad, air, metal, 2.0, 5.0, foci_mm(design), design.aperture_mm)
    status = {c.name: c.status for c in model.checks}
    assert status["guide_length_readback_spread"] == "fail" and status["two_storey_focus_spread"] == "fail"


def test_horns_in_front_of_the_entry_surface_are_refused(tmp_path):
    spec = load_spec(_spec(tmp_path, design__lens_mirror__horn_aperture_mm=25.0))
    with pytest.raises(DesignError) as err:
        adapter("polyfocal").synthesize(spec)
    assert err.value.field == "design.lens_mirror.horn_aperture_mm" and "in front of the entry surface" in err.value.message


def test_setback_moves_the_bends_out_or_is_refused(tmp_path):
    """A short setback keeps every layer-2 run ≥ a guide width by moving the bends out, lengths equal;
    with the exit vertex over the entry vertex the edge guides must run so far that they cross."""
    ts = adapter("polyfocal").synthesize(load_spec(_spec(tmp_path, design__lens_mirror__setback_mm=10.0))).mirror
    assert ts.l2.min() == pytest.approx(ts.p.guide_width) and np.ptp(ts.total) < 1e-12 * ts.total.max()
    assert (ts.zk - ts.z1).min() > 10.0 + 1.0                # the layer-2 run binds, not the clearance
    assert ts.total.max() == pytest.approx(49.064, abs=2e-3)                 # the code's value
    with pytest.raises(DesignError) as err:
        adapter("polyfocal").synthesize(load_spec(_spec(tmp_path, design__lens_mirror__setback_mm=0.0)))
    assert err.value.field == "design.lens_mirror.guide_width_mm"
