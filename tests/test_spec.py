"""Spec validation: every recipe validates; bad specs name the field and the rule; schema is current."""

from pathlib import Path

import pytest
import yaml

from antenna_cad.spec import SPEC_MODELS, SpecError, json_schema_text, load_spec, parse_spec

ROOT = Path(__file__).resolve().parents[1]
RECIPES = sorted((ROOT / "recipes").glob("*.yaml"))
GOOD = yaml.safe_load((ROOT / "recipes" / "xps-collimator-0.5m.yaml").read_text())


def test_schema_file_is_current():
    assert (ROOT / "schemas" / "lens-spec.schema.json").read_text() == json_schema_text(), \
        "schema drifted: run `make-lens schema`"


@pytest.mark.parametrize("recipe", RECIPES, ids=[r.name for r in RECIPES])
def test_every_recipe_validates(recipe):
    spec = load_spec(recipe)
    assert spec.name == recipe.stem


def _with(path: str, value):
    data = yaml.safe_load(yaml.safe_dump(GOOD))
    node = data
    keys = path.split(".")
    for k in keys[:-1]:
        node = node[k]
    node[keys[-1]] = value
    return data


@pytest.mark.parametrize("path,value,expected", [
    ("design.focal_length_mm", -4, "s.yaml: design.focal_length_mm: must be ≥ 1 (got -4)"),
    ("design.colour", "red", "s.yaml: design.colour: unknown key (not allowed here)"),
    ("design.diameter_mm", "big", "s.yaml: design.diameter_mm: must be a number, not a string"),
    ("fabrication.pedestal_height_mm", 30, "s.yaml: fabrication.pedestal_height_mm: must be ≥ 50 (got 30)"),
    ("fabrication.kerf_mm", -1, "s.yaml: fabrication.kerf_mm: must be ≥ 0 (got -1)"),
    ("material", "unobtainium", "s.yaml: material: unknown material 'unobtainium'"),
    ("material", {"eps_r": 0.5, "tan_delta": 0, "density_kg_m3": 30}, "s.yaml: material.eps_r: must be ≥ 1"),
    ("fabrication.pedestal_width_mm", 600, "s.yaml: fabrication.pedestal_width_mm: must be < design.diameter_mm"),
    ("name", "Bad Name", "s.yaml: name: must match the pattern"),
    ("kind", "teapot", "s.yaml: kind: must be one of"),
])
def test_bad_spec_names_field_and_rule(path, value, expected):
    with pytest.raises(SpecError) as err:
        parse_spec(_with(path, value), "s.yaml")
    assert any(line.startswith(expected) for line in err.value.lines), err.value.lines


def test_all_problems_reported_at_once():
    data = _with("design.focal_length_mm", 0)
    data["fabrication"]["kerf_mm"] = -2
    with pytest.raises(SpecError) as err:
        parse_spec(data, "s.yaml")
    assert len(err.value.lines) == 2


def test_yaml_syntax_error(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: [unclosed\n")
    with pytest.raises(SpecError, match=r"bad.yaml: line 2, column 1: YAML syntax: .*line 1, column 7"):
        load_spec(bad)


BILLION_LAUGHS = "".join(f"{c}: &{c} [{', '.join([f'*{p}'] * 9) if p else '1, 1, 1, 1, 1, 1, 1, 1, 1'}]\n"
                         for p, c in zip([""] + list("abcdefgh"), "abcdefghi"))


@pytest.mark.parametrize("text,expected", [
    (BILLION_LAUGHS, "line 5, column 4: expands to more than 20000 values"),
    ("a: " + "[" * 500 + "]" * 500, "line 1, column 35: nested deeper than 32 levels"),
    ("a: &a [*a]\n", "line 1, column 4: an alias refers to its own anchor"),
    ("name: x\nkind: collimator\nname: y\n", "line 3, column 1: duplicate key 'name' (first at line 1)"),
    ("? [a, b]\n: 1\n", "line 1, column 3: a key must be a plain value"),
    (b"name: ok\nmaterial: \xe9\n", "line 2: not UTF-8 text (byte 0xe9)"),
    ("kind: [a, b]\n", f"kind: must be one of {', '.join(sorted(SPEC_MODELS))} (got ['a', 'b'])"),
    ("a: [" + "1, " * 2500 + "1]\n", "line 1, column 4: more than 2000 items"),
    ("#" * 300_000, "file size: more than 256 KiB"),
    ("name: a\x01b\n", "line 1: control character #x0001 is not allowed in YAML"),
])
def test_hostile_yaml_one_clean_line(tmp_path, text, expected):
    bad = tmp_path / "bad.yaml"
    (bad.write_bytes if isinstance(text, bytes) else bad.write_text)(text)
    with pytest.raises(SpecError) as err:
        load_spec(bad)
    assert err.value.lines == [f"{bad}: {expected}" + err.value.lines[0].split(expected, 1)[1]]


def test_merge_keys_may_override(tmp_path):
    from antenna_cad.spec.reader import read_yaml
    p = tmp_path / "m.yaml"
    p.write_text("base: &b {x: 1, y: 2}\nuse: {<<: *b, y: 3}\n")
    assert read_yaml(p)["use"] == {"x": 1, "y": 3}


@pytest.mark.parametrize("path,value,expected", [
    ("fabrication.method", "sheet-layup", "fabrication.method: must be one of 'sheet_layup', 'solid', 'printed' (got 'sheet-layup')"),
    ("design.aut.diameter_mm", float("inf"), "design.aut.diameter_mm: must be a finite number"),
    ("design.diameter_mm", float("nan"), "design.diameter_mm: must be a finite number"),
    ("design.aut", {"diameter_mm": "x" * 500}, "(got 'xxxxxxxx"),
])
def test_enum_and_non_finite_errors_are_short(path, value, expected):
    with pytest.raises(SpecError) as err:
        parse_spec(_with(path, value), "s.yaml")
    assert expected in err.value.lines[0] and len(err.value.lines[0]) < 200


@pytest.mark.parametrize("kind", sorted(SPEC_MODELS))
def test_every_number_has_a_physical_range(kind):
    """spec.bounds: every number and list of every kind is bounded (new kinds adopt it by declaring bounds)."""
    from antenna_cad.spec.bounds import unbounded_fields
    assert unbounded_fields(SPEC_MODELS[kind]) == []


def test_denormal_is_refused_with_its_field():
    with pytest.raises(SpecError) as err:
        parse_spec(_with("fabrication.kerf_mm", 1e-300), "s.yaml")
    assert err.value.lines == ["s.yaml: fabrication.kerf_mm: must be 0 or at least 1e-09 in magnitude (got 1e-300)"]
