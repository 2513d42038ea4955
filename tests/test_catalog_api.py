"""The bundled recipes (make-lens recipes / new) and the Python API (antenna_cad.api)."""

from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from antenna_cad import api
from antenna_cad.catalog import KIND_RECIPES, CatalogError, recipes, starting_spec, sweeps
from antenna_cad.cli import app
from antenna_cad.spec import SPEC_MODELS, parse_spec

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()


def test_every_recipe_file_is_listed_with_its_kind_and_one_line():
    listed = {r.name: r for r in recipes()}
    assert set(listed) == {p.stem for p in (ROOT / "recipes").glob("*.yaml")}
    for r in listed.values():
        assert r.kind == yaml.safe_load(r.text)["kind"]
        assert 10 < len(r.summary) <= 100 and "\n" not in r.summary
    assert sweeps() == sorted(p.stem for p in (ROOT / "recipes" / "sweeps").glob("*.yaml"))


@pytest.mark.parametrize("kind", sorted(SPEC_MODELS))
def test_new_spec_of_every_kind_is_a_valid_spec_of_that_kind(kind):
    assert set(KIND_RECIPES) == set(SPEC_MODELS)
    name, text = starting_spec(kind, "first-try")
    spec = parse_spec(yaml.safe_load(text))
    assert (name, spec.name, spec.kind) == ("first-try", "first-try", kind)
    assert text.startswith("# first-try: a") and "yaml-language-server" not in text


def test_new_spec_from_a_recipe_keeps_its_name_by_default():
    name, text = starting_spec("luneburg-layup-200")
    assert name == "luneburg-layup-200" and parse_spec(yaml.safe_load(text)).fabrication.method == "sheet_layup"


@pytest.mark.parametrize("source,name,message", [
    ("horn", None, "horn: no such recipe or kind"),
    ("collimator", "My Lens", "My Lens: a spec name is lower-case"),
])
def test_new_spec_refuses_unknown_sources_and_bad_names(source, name, message):
    with pytest.raises(CatalogError, match=message):
        starting_spec(source, name)


def test_cli_new_writes_once_and_never_overwrites(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    first = runner.invoke(app, ["new", "mirror_lens", "dish"])
    assert first.exit_code == 0, first.output
    written = (tmp_path / "dish.yaml").read_text(encoding="utf-8")
    assert runner.invoke(app, ["validate", "dish.yaml"]).exit_code == 0
    again = runner.invoke(app, ["new", "collimator", "dish"])
    assert again.exit_code == 2 and "dish.yaml: exists" in again.output
    assert (tmp_path / "dish.yaml").read_text(encoding="utf-8") == written
    bad = runner.invoke(app, ["new", "horn"])
    assert bad.exit_code == 2 and "no such recipe or kind" in bad.output and sorted(tmp_path.iterdir()) == [
        tmp_path / "dish.yaml"]


def test_cli_recipes_lists_one_line_per_recipe():
    result = runner.invoke(app, ["recipes"])
    assert result.exit_code == 0
    lines = result.output.splitlines()
    assert [line.split()[0] for line in lines[:-1]] == [r.name for r in recipes()]
    assert lines[-1].startswith("sweeps: collimator-trade")


def test_load_from_a_recipe_name_a_file_and_a_dict_agree(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)               # no file of the recipe's name here
    by_name = api.load("ptfe-lens-120mm")
    by_file = api.load(ROOT / "recipes" / "ptfe-lens-120mm.yaml")
    by_dict = api.load(yaml.safe_load((ROOT / "recipes" / "ptfe-lens-120mm.yaml").read_text(encoding="utf-8")))
    assert by_name == by_file == by_dict
    with pytest.raises(api.SpecError, match="cannot read|No such file|not found"):
        api.load("no-such-recipe.yaml")


def test_with_changes_sets_dotted_fields_and_revalidates():
    spec = api.with_changes("xps-collimator-0.5m", {"design.focal_length_mm": 3000, "fabrication.kerf_mm": 1})
    assert (spec.design.focal_length_mm, spec.fabrication.kerf_mm, spec.design.diameter_mm) == (3000, 1, 500)
    with pytest.raises(api.SpecError, match="design.focal_length_mm: must be ≥ 1"):
        api.with_changes(spec, {"design.focal_length_mm": -4})
    with pytest.raises(api.SpecError, match="design.focal_lenght_mm"):
        api.with_changes(spec, {"design.focal_lenght_mm": 3000})


def test_validate_then_build_returns_the_build_as_objects(tmp_path):
    checked = api.validate("ptfe-lens-120mm", tmp_path)
    assert checked.status in ("pass", "warn") and checked.checks
    result = api.build(checked, tmp_path)
    assert result.out_dir == tmp_path / "ptfe-lens-120mm" and result.kind == "collimator"
    assert result.manifest["figures"] == pytest.approx(result.figures)
    assert [p.label for p in result.parts] == [p["label"] for p in result.manifest["parts"]]
    lens = next(p for p in result.parts if p.label == "lens")
    assert lens.stl is not None and lens.stl.is_file() and lens.volume_mm3 > 0
    assert result.path("report.html").is_file()
    assert result.check(checked.checks[0].name).name == checked.checks[0].name
    with pytest.raises(KeyError, match="not among"):
        result.path("nothing.txt")
    worst = "fail" if any(c.status == "fail" for c in result.checks) else (
        "warn" if any(c.status == "warn" for c in result.checks) else "pass")
    assert result.status == worst
    again = api.read_build(result.out_dir)
    assert (again.figures, again.verified, again.checks, again.parts, again.files) == (
        result.figures, result.verified, result.checks, result.parts, result.files)


def test_build_refuses_an_output_folder_that_is_not_a_build(tmp_path):
    (tmp_path / "ptfe-lens-120mm").mkdir()
    (tmp_path / "ptfe-lens-120mm" / "notes.txt").write_text("mine")
    with pytest.raises(api.OutputError, match="not a make-lens build"):
        api.build("ptfe-lens-120mm", tmp_path)
    assert [p.name for p in (tmp_path / "ptfe-lens-120mm").iterdir()] == ["notes.txt"]
