"""The mesher's work bounded before it starts (triangles estimated from area, curvature and
tolerance; refused above the limit), and its /dev/shm scratch folders named by process and
cleaned when their process is gone."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from antenna_cad.export import mesh
from antenna_cad.geometry import kernel
from antenna_cad.synthesis.checks import DesignError


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
