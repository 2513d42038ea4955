"""A machine profile in its own YAML file (``fabrication.cam.machine: <file>.yaml``): read relative to
the spec's folder when the spec is loaded, put inline (so the manifest and the check see it), and
refused in one line naming the field, the file and the profile's key, exit 2, nothing written."""

import re
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from antenna_cad.cam.plan import machine_of
from antenna_cad.cli import app
from antenna_cad.pipeline import prepare
from antenna_cad.spec import SpecError, load_spec, parse_spec

ROOT = Path(__file__).resolve().parents[1]
PROFILE = {"name": "shop-4axis", "kind": "hotwire", "axes": "XYUV", "feed_mode": "inverse_time", "span_mm": 1250,
           "min_span_mm": 180, "travel_mm": [1300, 1200], "heat_on": "M3 S{power}", "dwell_s": 3}


def _folder(tmp_path: Path, profile: dict, machine: str = "machines/shop.yaml") -> Path:
    data = yaml.safe_load((ROOT / "recipes/xps-collimator-0.5m-taper.yaml").read_text())
    data["fabrication"]["cam"] = {"machine": machine, "feed_mm_min": 300}
    data["outputs"] = {"step": False, "stl": False, "templates": False}
    (tmp_path / "machines").mkdir()
    (tmp_path / "machines/shop.yaml").write_text(yaml.safe_dump(profile))
    (tmp_path / "lens.yaml").write_text(yaml.safe_dump(data))
    return tmp_path / "lens.yaml"


def test_a_profile_file_is_read_relative_to_the_spec_and_cuts_with_its_values(tmp_path):
    spec = load_spec(_folder(tmp_path, PROFILE))
    m = machine_of(spec.fabrication.cam)
    assert (m.name, m.span_mm, m.min_span_mm, m.travel_mm, m.dwell_s) == ("shop-4axis", 1250, 180, (1300, 1200), 3)
    entries = [e for e in prepare(spec).fab.cam.entries if "faces" in e]
    assert entries and {e["machine"] for e in entries} == {"shop-4axis"}
    assert {e["tower_span_mm"] for e in entries} == {180.0}               # 50 mm foam: the towers' closest


@pytest.mark.parametrize("change, message", [
    ({"span_mm": -5}, r"fabrication\.cam\.machine: machines/shop\.yaml: span_mm: must be ≥ 0 \(got -5\)"),
    ({"speed": 3}, r"fabrication\.cam\.machine: machines/shop\.yaml: speed: unknown key"),
    ({"kind": None}, r"fabrication\.cam\.machine: machines/shop\.yaml: kind: "),
])
def test_a_bad_profile_file_is_refused_by_field_in_one_line(tmp_path, change, message):
    with pytest.raises(SpecError) as err:
        load_spec(_folder(tmp_path, PROFILE | change))
    assert len(err.value.lines) == 1 and err.value.lines[0].startswith(str(tmp_path / "lens.yaml"))
    assert re.search(message, err.value.lines[0]), err.value.lines[0]


def test_a_missing_profile_file_exits_2_and_writes_nothing(tmp_path):
    spec = _folder(tmp_path, PROFILE, machine="machines/none.yml")
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["build", str(spec), "-o", str(out)])
    assert result.exit_code == 2
    assert "fabrication.cam.machine: machines/none.yml: cannot read it" in result.output
    assert "Traceback" not in result.output and not out.exists()


def test_a_profile_file_in_a_document_without_a_folder_is_refused():
    data = yaml.safe_load((ROOT / "recipes/xps-collimator-0.5m-taper.yaml").read_text())
    data["fabrication"]["cam"] = {"machine": "shop.yaml"}
    with pytest.raises(SpecError, match=r"fabrication\.cam\.machine: the profile file shop\.yaml is read when"):
        parse_spec(data)
