"""The make-lens command: CliRunner for behaviour, one real subprocess run of the console script."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import trimesh
import yaml
from typer.testing import CliRunner

from antenna_cad import __version__
from antenna_cad.cli import app
from antenna_cad.synthesis.collimator import lens_volume_mm3, profile_z_mm

ROOT = Path(__file__).resolve().parents[1]
PTFE = ROOT / "recipes" / "ptfe-lens-120mm.yaml"
runner = CliRunner()


def test_version():
    result = runner.invoke(app, ["--version"])
    assert result.exit_code == 0 and __version__ in result.output


def test_validate_good_recipe_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["validate", str(ROOT / "recipes" / "xps-collimator-0.5m.yaml")])
    assert result.exit_code == 0, result.output
    assert "valid collimator spec" in result.output and "rim_incidence_vs_tir" in result.output
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("edit,expected", [
    ({"design": {"diameter_mm": 500, "focal_length_mm": -4}}, "design.focal_length_mm: must be ≥ 1 (got -4)"),
    ({"material": {"eps_r": 1.0, "tan_delta": 0.0, "density_kg_m3": 30}},
     "material.eps_r: a decelerating lens needs εr > 1"),
])
def test_bad_spec_exit_2_names_field_nothing_written(tmp_path, edit, expected):
    data = yaml.safe_load((ROOT / "recipes" / "xps-collimator-0.5m.yaml").read_text()) | edit
    spec = tmp_path / "bad.yaml"
    spec.write_text(yaml.safe_dump(data))
    out = tmp_path / "out"
    for args in (["validate", str(spec)], ["build", str(spec), "-o", str(out)]):
        result = runner.invoke(app, args)
        assert result.exit_code == 2
        assert f"{spec}: {expected}" in result.output
        assert "Traceback" not in result.output
    assert not out.exists()


def test_console_script_builds_machined_lens(tmp_path):
    exe = shutil.which("make-lens") or str(Path(sys.executable).parent / "make-lens")
    # the first build runs with an empty cache folder, as on a fresh machine (ezdxf builds its font cache)
    fresh = dict(os.environ, XDG_CACHE_HOME=str(tmp_path / "cache"))
    done = subprocess.run([exe, str(PTFE), "-o", str(tmp_path)], capture_output=True, text=True, timeout=600,
                          env=fresh)
    assert done.returncode == 0, done.stderr
    assert "overall: pass" in done.stdout          # the full-wave stages did not run (Meep hidden): skipped
    out = tmp_path / "ptfe-lens-120mm"
    manifest = json.loads((out / "manifest.json").read_text())
    assert {c["name"] for c in manifest["checks"] if c["status"] != "pass"} == {"full_wave", "full_wave_scan_edge"}
    assert [p["label"] for p in manifest["parts"]] == ["lens"]
    f, n, d = 300.0, 2.08 ** 0.5, manifest["figures"]["thickness_mm"]
    assert manifest["parts"][0]["volume_mm3"] == pytest.approx(lens_volume_mm3(f, n, d), rel=1e-6)
    mesh = trimesh.load(out / "stl" / "lens.stl", force="mesh")
    assert mesh.is_watertight and mesh.volume == pytest.approx(lens_volume_mm3(f, n, d), rel=2e-3)
    doc = ezdxf.readfile(out / "templates" / "profile.dxf")
    assert not doc.audit().has_errors
    pts = np.array([p[:2] for e in doc.modelspace().query("LWPOLYLINE[layer=='CUT']") for p in e.get_points()])
    front = pts[pts[:, 1] < d - 1e-6]
    # profile gauge points lie on the synthesized profile (chord tolerance 0.002 mm)
    assert np.max(np.abs(front[:, 1] - profile_z_mm(np.abs(front[:, 0]), f, n))) < 1e-3
    rerun = subprocess.run([exe, str(PTFE), "-o", str(tmp_path / "again")], capture_output=True, text=True,
                           timeout=600)
    assert rerun.returncode == 0
    again = json.loads((tmp_path / "again" / "ptfe-lens-120mm" / "manifest.json").read_text())
    assert again["files"] == manifest["files"]         # byte-identical across processes
