"""Odd input that slipped through: numbers that are not numbers (YAML 1.1 booleans, base 60, hex,
quoted), on/off fields written unquoted, a named pipe as the spec, validate exiting 0 on a failed
check, the half-power search bracketing against the wrong peak, the as-built focus search stepping
past the lens, template pages counted before drawing."""

import os
from pathlib import Path

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from antenna_cad.cli import app
from antenna_cad.radiation.aperture import beam_figures
from antenna_cad.spec import SpecError, load_spec

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()
RECIPE = (ROOT / "recipes" / "xps-collimator-0.5m.yaml").read_text()


def _spec(tmp_path: Path, old: str, new: str) -> Path:
    assert old in RECIPE
    path = tmp_path / "case.yaml"
    path.write_text(RECIPE.replace(old, new, 1))
    return path


@pytest.mark.parametrize("token,got", [("on", "True"), ("4:00", "'4:00'"), ("0x78", "'0x78'"), ("'1e2'", "'1e2'"),
                                       ("yes", "True"), ("1_000", "'1_000'")])
def test_numeric_fields_refuse_booleans_and_strings(tmp_path, token, got):
    spec = _spec(tmp_path, "diameter_mm: 500\n", f"diameter_mm: {token}\n")
    result = runner.invoke(app, ["validate", str(spec)])
    assert result.exit_code == 2
    (line,) = result.output.splitlines()
    assert line.startswith(f"{spec}: design.diameter_mm: must be a number, not a ") and line.endswith(f"(got {got})")


def test_yaml_12_numbers_and_unquoted_on_off(tmp_path):
    spec = _spec(tmp_path, "diameter_mm: 500\n", "diameter_mm: 5e2\n")
    assert load_spec(spec).design.diameter_mm == 500.0
    spec.write_text(RECIPE + "verification: {full_wave: off}\n")
    assert load_spec(spec).verification.full_wave == "off"
    spec.write_text(RECIPE + "verification: {full_wave: on}\n")
    assert load_spec(spec).verification.full_wave == "on"
    spec.write_text(RECIPE + "verification: {budget_s: on}\n")
    with pytest.raises(SpecError, match="verification.budget_s: must be a number, not a boolean"):
        load_spec(spec)


def test_a_named_pipe_or_folder_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "fifo.yaml"
    os.mkfifo(fifo)
    for path, what in ((fifo, "a named pipe"), (tmp_path, "a folder")):
        result = runner.invoke(app, ["validate", str(path)])
        assert result.exit_code == 2
        assert result.output.strip() == f"{path}: file: {what}; a spec is a regular YAML text file"


def test_validate_exits_1_when_its_checks_fail(tmp_path):
    """A four-focal lens with phase_index 2.0 fails tem_single_mode: build exits 1, so does validate."""
    data = yaml.safe_load((ROOT / "recipes" / "polyfocal-fourfocal-2d-60deg.yaml").read_text())
    data["design"]["lines"]["phase_index"] = 2.0
    spec = tmp_path / "four.yaml"
    spec.write_text(yaml.safe_dump(data))
    result = runner.invoke(app, ["validate", str(spec)])
    assert result.exit_code == 1, result.output
    assert "fails its checks: " in result.output and "tem_single_mode" in result.output.splitlines()[-1]


class _Cut:
    """A Gaussian beam |F| = exp(−(u − u0)²/w²) sampled on a coarse grid whose nearest sample sits
    well below the true peak: the first sample under half the grid peak's power and the one before
    it are both under half the true peak's power."""

    def __init__(self, u0: float, w: float, grid: np.ndarray):
        self.u0, self.w, self.grid = u0, w, grid

    def u_grid(self) -> np.ndarray:
        return self.grid

    def __call__(self, u):
        return np.atleast_1d(np.exp(-((np.asarray(u, float) - self.u0) / self.w) ** 2)).astype(complex)


def test_half_power_bracket_uses_the_refined_peak():
    h = 0.1
    cut = _Cut(u0=0.04, w=0.1, grid=np.arange(-1.0, 1.0 + h / 2, h))
    beam = beam_figures(cut)
    edge = cut.w * np.sqrt(np.log(2) / 2)          # |F|² = 1/2 at u0 ± w·√(ln 2 / 2)
    assert beam.peak == pytest.approx(1.0, abs=1e-9)
    expected = np.degrees(np.arcsin(cut.u0 + edge) - np.arcsin(cut.u0 - edge))
    assert beam.hpbw_deg == pytest.approx(expected, rel=1e-8)


def test_template_pages_are_counted_before_drawing():
    from antenna_cad.limits import LIMITS, template_pages
    class Drawing:
        def __init__(self, w, h):
            self.box = (0.0, 0.0, w, h)

        def cut_bounds(self):
            return self.box

    assert template_pages([Drawing(100, 100)]) >= 1
    big = template_pages([Drawing(200_000, 200_000)])          # the 350,000-page ellipse template
    assert big > LIMITS["pages"].hard
    assert LIMITS["pages"].field == "outputs.templates"


def test_as_built_focus_search_stays_on_the_lens(tmp_path):
    """phase_error_budget_deg: 180 (the schema's maximum) puts the scan-edge feed 3 m off the axis
    of a Ø500 mm lens: the focus search stepped past the lens and polyfit got no ray."""
    from antenna_cad.pipeline import prepare
    from antenna_cad.registry import adapter
    spec = load_spec(_spec(tmp_path, "phase_error_budget_deg: 22.5", "phase_error_budget_deg: 180"))
    plan = prepare(spec)
    verification = adapter(spec.kind).verify(spec, plan.design, plan.layup, plan.fab)
    assert verification.checks and all(np.isfinite(v) for v in verification.figures.values() if isinstance(v, float))
