"""The inputs a hostile-input review found crashing, hanging or slipping through, now each one clean line (exit 2
naming the field); numerical failures named; resource limits; the CLI's argument forms."""

import warnings
from pathlib import Path

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from antenna_cad.cli import _with_command, app
from antenna_cad.limits import LIMITS, Limit, counts
from antenna_cad.synthesis.checks import DesignError, solving

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()


def _spec(tmp_path: Path, recipe: str, path: str, value) -> Path:
    data = yaml.safe_load((ROOT / "recipes" / f"{recipe}.yaml").read_text())
    node = data
    keys = path.split(".")
    for k in keys[:-1]:
        node = node[k]
    node[keys[-1]] = value
    spec = tmp_path / "case.yaml"
    spec.write_text(yaml.safe_dump(data))
    return spec


@pytest.mark.parametrize("recipe,path,value,expected", [
    ("bifocal-kinber-160mm", "design.kinber.b2", 1e-320, "design.kinber.b2: must be 0 or at least 1e-09"),   # LinAlgError
    ("xps-collimator-0.5m", "design.diameter_mm", 1e-300, "design.diameter_mm: must be ≥ 1"),   # ZeroDivisionError
    ("ka-slot-array-two-mirror", "beamformer.scale_mm", 5e-324, "beamformer.scale_mm: must be ≥ 1"),   # spline error
    ("luneburg-classic-5", "frequency_ghz", 1e-310, "frequency_ghz: must be ≥ 0.1"),   # math domain error
    ("luneburg-classic-5", "design.layers.count", 1000000, "design.layers.count: must be ≤ 100"),   # hang
    ("xps-collimator-0.5m", "outputs.mesh_tolerance_mm", 1e-308, "outputs.mesh_tolerance_mm: must be ≥ 0.001"),
    ("xps-collimator-0.5m", "fabrication.sheet_thickness_mm", 5e-05, "fabrication.sheet_thickness_mm: must be ≥ 0.5"),
    ("xps-collimator-0.5m", "design.aut.diameter_mm", float("inf"), "design.aut.diameter_mm: must be a finite"),
    ("luneburg-classic-5", "design.grades", [1.5] * 300, "design.grades: List should have at most 200 items"),
    ("xps-collimator-0.5m", "fabrication.sheet_thickness_mm", 1,            # build used to refuse it after 9 s
     "fabrication.dowel_diameter_mm: 20 mm dowels do not fit"),
])
def test_issue_cases_are_one_clean_line(tmp_path, recipe, path, value, expected):
    spec = _spec(tmp_path, recipe, path, value)
    result = runner.invoke(app, ["validate", str(spec)])
    assert result.exit_code == 2 and result.exception is None or isinstance(result.exception, SystemExit)
    assert result.output.splitlines() == [f"{spec}: {expected}" + result.output.split(expected, 1)[1].rstrip("\n")]


def test_numerical_failure_names_the_block_and_prints_no_warning(recwarn):
    with pytest.raises(DesignError) as err:
        with solving("design", "synthesis"):
            np.log(np.zeros(3))                  # a RuntimeWarning, silenced
            np.linalg.solve(np.zeros((2, 2)), np.ones(2))
    assert err.value.field == "design"
    assert "LinAlgError" in str(err.value) and "change design" in str(err.value) and "\n" not in str(err.value)
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]
    with warnings.catch_warnings():
        warnings.simplefilter("error")           # numpy warnings would raise here if not silenced
        with solving("design", "synthesis"):
            np.divide(1.0, np.zeros(2))


def test_resource_limits_warn_then_refuse():
    limit = Limit("sheets", "fabrication.sheet_thickness_mm", soft=60, hard=400)
    assert limit.check(60) == []
    (warn,) = limit.check(104)
    assert warn.status == "warn" and "104 sheets" in warn.message and "fabrication.sheet_thickness_mm" in warn.message
    with pytest.raises(DesignError) as err:
        limit.check(401)
    assert err.value.field == "fabrication.sheet_thickness_mm" and "limit of 400" in str(err.value)
    assert set(LIMITS) == {"sheets", "shells", "slots", "pieces", "drawings", "pages", "triangles", "cells", "gyroid_points"}


def test_counts_read_plans_of_any_kind():
    class Layup:
        sheets = [1, 2, 3]

    class Design:
        layers = (1, 2)

    class Fab:
        rows, drawings = [1] * 5, [1] * 4
    assert counts(Design(), Layup(), Fab()) == {"sheets": 3, "shells": 2, "pieces": 5, "drawings": 4}


@pytest.mark.parametrize("args,expected", [
    (["spec.yaml"], ["build", "spec.yaml"]),
    (["-o", "out", "spec.yaml"], ["build", "-o", "out", "spec.yaml"]),
    (["spec.yaml", "--out", "out"], ["build", "spec.yaml", "--out", "out"]),
    (["build", "-o", "out", "spec.yaml"], ["build", "-o", "out", "spec.yaml"]),
    (["validate", "spec.yaml"], ["validate", "spec.yaml"]),
    (["--version"], ["--version"]),
    ([], []),
])
def test_spec_alone_means_build_with_options_anywhere(args, expected):
    assert _with_command(args) == expected


def test_schema_prints_to_stdout_and_help_lists_exit_codes(tmp_path):
    result = runner.invoke(app, ["schema"])
    assert result.exit_code == 0 and result.output.startswith("{") and '"title": "antenna_cad lens spec"' in result.output
    assert list(tmp_path.iterdir()) == []
    out = tmp_path / "s.json"
    assert runner.invoke(app, ["schema", "-o", str(out)]).exit_code == 0 and out.read_text() == result.output
    helptext = runner.invoke(app, ["--help"]).output
    assert all(code in helptext for code in ("0 built", "1 built, but a check failed", "2 bad spec", "130 interrupted"))
