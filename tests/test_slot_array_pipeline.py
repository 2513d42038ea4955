"""End-to-end build of the slot_array kind (seed-003) through the pipeline and the CLI."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
import yaml

from antenna_cad.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
X_RECIPE = ROOT / "recipes" / "x-slot-array-ellipse.yaml"
KA_RECIPE = ROOT / "recipes" / "ka-slot-array-two-mirror.yaml"
ML_RECIPE = ROOT / "recipes" / "ka-slot-array-mirror-lens.yaml"


@pytest.fixture(scope="module")
def x_build(tmp_path_factory):
    from antenna_cad.pipeline import build
    from antenna_cad.registry import synthesize
    spec = load_spec(X_RECIPE)
    design, _ = synthesize(spec)
    return spec, design, build(spec, tmp_path_factory.mktemp("slot"))


@pytest.mark.parametrize("recipe", [X_RECIPE, KA_RECIPE, ML_RECIPE])
def test_recipes_validate_and_synthesise(recipe):
    from antenna_cad.registry import synthesize
    spec = load_spec(recipe)
    design, checks = synthesize(spec)
    assert spec.kind == "slot_array"
    assert not [c for c in checks if c.status == "fail"]
    if recipe is KA_RECIPE:
        assert 3000 <= design.slots.count <= 3400 and spec.array.count == 40


def test_x_build_outputs(x_build):
    spec, design, result = x_build
    files = set(result.files)
    guides = spec.array.count
    assert {f"{spec.name}.step", "slots.csv", "cutlist.csv", "manifest.json",
            f"templates/{spec.name}-templates.pdf"} <= files
    for g in range(guides):
        assert f"stl/waveguide-{g:02d}.stl" in files and f"stl/core-{g:02d}.stl" in files
        assert f"templates/top-{g:02d}.dxf" in files
    assert {"templates/plate-0.dxf", "templates/plate-1.dxf", "templates/mirror-1.dxf",
            "stl/mirror-1.stl", "stl/horn-3.stl"} <= files
    assert not [c for c in result.checks if c.status == "fail"]
    assert {c.name: c for c in result.checks}["model_slot_count"].status == "pass"


def test_step_reimport_parts_and_labels(x_build):
    from build123d import import_step
    spec, design, result = x_build
    top = import_step(str(result.out_dir / f"{spec.name}.step"))
    groups = {g.label: [c.label for c in g.children] for g in top.children}
    n = spec.array.count
    expected_fab = {f"{kind}-{g:02d}" for g in range(n) for kind in ("waveguide", "top", "core", "load")} \
        | {"plate-0", "plate-1", "mirror-1"} | {f"horn-{k}" for k in range(1, spec.feeds.count + 1)}
    assert set(groups) == {"fabricated"}
    assert set(groups["fabricated"]) == expected_fab


def test_waveguide_body_stl_watertight(x_build):
    import trimesh
    _, _, result = x_build
    for label in ("waveguide-00", "top-00", "top-09", "core-09", "load-09", "horn-1", "plate-1"):
        mesh = trimesh.load(result.out_dir / "stl" / f"{label}.stl")
        mesh.merge_vertices()
        assert mesh.is_watertight, label
    import json
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    assert all(p["valid"] and p["watertight"] for p in manifest["parts"])


def test_slots_csv_matches_synthesis(x_build):
    _, design, result = x_build
    with open(result.out_dir / "slots.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == design.slots.count
    assert {"guide", "slot", "x_mm", "y_mm", "length_mm", "width_mm", "offset_mm"} <= set(rows[0])
    assert abs(float(rows[5]["length_mm"]) - float(design.slots.length_mm[5])) < 1e-3


def test_dxf_audit_and_slot_count(x_build):
    import ezdxf
    spec, design, result = x_build
    for g in (0, spec.array.count // 2):
        doc = ezdxf.readfile(result.out_dir / "templates" / f"top-{g:02d}.dxf")
        auditor = doc.audit()
        assert not auditor.has_errors
        cut = [e for e in doc.modelspace() if e.dxf.layer == "CUT"]
        assert len(cut) == 1 + int((design.slots.guide_index == g).sum())   # outline + slots
        assert doc.units == ezdxf.units.MM
    doc = ezdxf.readfile(result.out_dir / "templates" / "plate-1.dxf")
    assert not doc.audit().has_errors
    assert len([e for e in doc.modelspace() if e.dxf.layer == "CUT"]) == 2   # outline + coupling slot


def test_bad_spec_fails_slot_check_cli_exit_2(tmp_path):
    from typer.testing import CliRunner

    from antenna_cad.cli import app
    data = yaml.safe_load(X_RECIPE.read_text())
    data["slots"]["width_mm"] = 9.0           # slots wider than the broad wall allows
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data))
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code == 2
    assert "slots.width_mm" in result.output


def test_bad_beamformer_params_name_the_field(tmp_path):
    from antenna_cad.spec import SpecError, parse_spec
    data = yaml.safe_load(X_RECIPE.read_text())
    del data["beamformer"]["focal_separation_mm"]
    with pytest.raises(SpecError, match="beamformer.focal_separation_mm"):
        parse_spec(data)


@pytest.mark.slow
def test_ka_build_and_step_under_20_s(tmp_path):
    from antenna_cad.pipeline import build
    spec = load_spec(KA_RECIPE)
    spec = spec.model_copy(update={"outputs": spec.outputs.model_copy(update={"stl": False, "templates": False})})
    result = build(spec, tmp_path)
    s = result.seconds
    assert s["synthesize"] + s["model"] + s["fabricate"] + s["step"] < 20.0
