"""The polyfocal kind end to end (seed-001 §1.3, §2.4): recipes → channels, surfaces, line table,
templates, σ against the field angle; read back from the written files."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest
import trimesh

from antenna_cad import pipeline
from antenna_cad.registry import adapter
from antenna_cad.spec import load_spec

RECIPES = Path(__file__).resolve().parents[1] / "recipes"
FOUR = RECIPES / "polyfocal-fourfocal-2d-60deg.yaml"
FIVE = RECIPES / "polyfocal-fivefocal-3d-w.yaml"


def test_recipes_synthesize_exactly_with_their_line_tables():
    for path in (FOUR, FIVE):
        spec = load_spec(path)
        kind = adapter("polyfocal")
        design = kind.synthesize(spec)
        assert all(c.status != "fail" for c in design.checks), path.name
        assert design.dense.residuals().max() / design.dense.aperture < 1e-9
        np.testing.assert_allclose(design.index * design.length_mm, design.electrical_mm, rtol=1e-12)
        figures = kind.summary(spec, design, None)
        assert any("sigma_over_D_at_" in k for k in figures)


def test_aperture_field_is_plain_arrays():
    spec = load_spec(FOUR)
    kind = adapter("polyfocal")
    design = kind.synthesize(spec)
    pos, amp, phase, image = kind.aperture_field(design, design.elements, 10.0)
    assert pos.shape == (len(amp), 3) and phase.shape == amp.shape and image.shape == (3,)
    assert np.all(amp > 0) and amp.max() == pytest.approx(1.0)


def _check_build(path: Path, tmp_path: Path) -> dict:
    spec = load_spec(path)
    res = pipeline.build(spec, tmp_path)
    manifest = json.loads((res.out_dir / "manifest.json").read_text())
    statuses = {c["name"]: c["status"] for c in manifest["checks"]}
    assert "fail" not in statuses.values(), statuses
    assert statuses["channel_electrical_length"] == "pass" and statuses["as_built_sigma"] == "pass"
    rows = list(csv.DictReader((res.out_dir / "lines.csv").open()))
    channels = [p for p in manifest["parts"] if p["label"].startswith("channel-")]
    assert len(rows) == len(channels) == manifest["figures"]["element_count"]
    for part in manifest["parts"]:
        assert part["valid"] and part["bodies_watertight"], part["label"]   # septa: plates touching the walls
        assert trimesh.load(res.out_dir / part["file"], force="mesh").volume > 0, part["label"]
    h = spec.design.lines.plate_spacing_mm
    for row, part in zip(rows, channels):            # channel solid ↔ table: n · V/(a·h) = l_electrical
        read = part["volume_mm3"] / (float(row["width_mm"]) * h) * float(row["phase_index"])
        assert read == pytest.approx(float(row["l_electrical_mm"]), rel=1e-6)
    assert (res.out_dir / f"{spec.name}.step").stat().st_size > 0
    return manifest


@pytest.mark.slow
def test_fourfocal_recipe_builds(tmp_path):
    manifest = _check_build(FOUR, tmp_path)
    assert (tmp_path / "polyfocal-fourfocal-2d-60deg" / "templates" / "section.dxf").exists()
    fig = manifest["figures"]
    assert fig["foci_count"] == 4 and fig["element_count"] == 41
    assert fig["elements_sigma_over_D_max"] < fig["seed_60deg_trifocal_sigma_over_D_max"]
    assert {p["label"] for p in manifest["parts"]} >= {"septa", "plate-top", "plate-bottom"}


@pytest.mark.slow
def test_fivefocal_recipe_builds(tmp_path):
    manifest = _check_build(FIVE, tmp_path)
    assert manifest["figures"]["foci_count"] == 5
    assert {p["label"] for p in manifest["parts"]} >= {"entry-surface", "exit-surface"}
