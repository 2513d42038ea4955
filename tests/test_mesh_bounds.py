"""The mesher's work bounded before it starts (triangles estimated from area, curvature and
tolerance; refused above the limit), and its /dev/shm scratch folders named by process and
cleaned when their process is gone."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from antenna_cad.cli import app
from antenna_cad.export import mesh
from antenna_cad.geometry import kernel
from antenna_cad.geometry.model import RingPrism, SlottedPrism
from antenna_cad.synthesis.checks import DesignError

ROOT = Path(__file__).resolve().parents[1]


def test_triangle_estimate_is_near_what_brepmesh_makes():
    ball = kernel.sphere(200.0)
    made = len(mesh.mesh_shape(ball, 0.05).faces)
    assert 0.5 <= mesh.estimate_triangles(ball, 0.05) / made <= 2.0
    can = kernel.cylinder(150.0, 80.0)                 # its two flat caps are not counted
    made = len(mesh.mesh_shape(can, 0.05).faces)
    assert 0.2 <= mesh.estimate_triangles(can, 0.05) / made <= 1.0


def test_a_part_over_the_triangle_limit_is_refused_before_meshing():
    big = kernel.sphere(7950.0)                       # the Ø15.9 m Luneburg sphere
    assert mesh.estimate_triangles(big, 0.001) > mesh.MAX_TRIANGLES
    with pytest.raises(DesignError) as err:
        mesh.mesh_shape(big, 0.001)
    assert err.value.field == "outputs.mesh_tolerance_mm"


@pytest.mark.skipif(not Path("/dev/shm").is_dir(), reason="no /dev/shm on this system")
def test_scratch_is_named_by_pid_and_stale_ones_are_removed():
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True, check=True).stdout.strip()
    stale = Path("/dev/shm") / f"{mesh.SCRATCH_PREFIX}{dead}-test"
    stale.mkdir()
    (stale / "0.stl").write_bytes(b"x" * 100)
    mesh._remove_stale.cache_clear()
    with mesh._scratch() as scratch:
        assert Path(scratch).name.startswith(f"{mesh.SCRATCH_PREFIX}{os.getpid()}-")
        assert not stale.exists()


@pytest.mark.parametrize("prism", [
    RingPrism(40.0, 120.0, 0.0, 20.0), RingPrism(0.0, 75.0, 5.0, 25.0),
    SlottedPrism(np.array([[0, 0], [200, 0], [200, 100], [0, 100]], float),
                 np.array([[50, 50, 16, 3, 0.0], [120, 40, 20, 4, 1.0]]), 0.0, 2.0)])
def test_prism_triangles_are_counted_exactly_without_meshing(prism):
    for tolerance in (0.05, 0.01):
        assert mesh.prism_triangles(prism, tolerance) == len(mesh.mesh_prism(prism, tolerance).faces)


def _scaled_sphere(tmp_path: Path, tolerance_mm: float) -> Path:
    """The Luneburg recipe scaled to Ø15.9 m (its five shells ~2 M triangles each at 0.05 mm)."""
    spec = yaml.safe_load((ROOT / "recipes" / "luneburg-classic-5.yaml").read_text())
    spec["design"]["diameter_mm"] = 15900
    spec["outputs"]["mesh_tolerance_mm"] = tolerance_mm
    path = tmp_path / "big.yaml"
    path.write_text(yaml.safe_dump(spec))
    return path


def test_validate_counts_the_triangles_a_build_would_mesh(tmp_path):
    """``validate`` builds the solid model in memory and estimates every part's STL: a warning above
    5 M triangles in all, a one-line refusal (exit 2, naming the part and the field) above 5 M a part
    — the same rules ``build`` applies before it meshes."""
    done = CliRunner().invoke(app, ["validate", str(_scaled_sphere(tmp_path, 0.05))])
    assert done.exit_code == 0, done.output
    assert "stl_triangles_count" in done.output and "warning" in done.output
    done = CliRunner().invoke(app, ["validate", str(_scaled_sphere(tmp_path, 0.001))])
    assert done.exit_code == 2
    assert done.output.count("\n") == 1 and "outputs.mesh_tolerance_mm: part shell-" in done.output
    assert list(tmp_path.iterdir()) == [tmp_path / "big.yaml"]             # nothing written
