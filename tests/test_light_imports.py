"""``make-lens --help`` and ``make-lens validate --fast`` load no CAD, DXF or plotting library:
they answer in about a second because OCP (~1 s), trimesh, manifold3d, ezdxf and
matplotlib are imported where a build uses them. Checked in a fresh interpreter by the modules it
holds after the command, not by a timing."""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("build123d", "OCP", "trimesh", "manifold3d", "ezdxf", "matplotlib")
PROBE = """
import sys
sys.argv = ["make-lens", *sys.argv[1:]]
from antenna_cad.cli import main
try:
    main()
except SystemExit as stop:
    code = stop.code
print("LOADED:" + ",".join(m for m in %r if m in sys.modules), "EXIT:%%s" %% code)
""" % (HEAVY,)
ONE_PER_KIND = ["xps-collimator-0.5m", "bifocal-dielectric-160mm", "luneburg-layup-200", "ka-slot-array-two-mirror",
                "mirror-lens-346mm", "polyfocal-fourfocal-2d-60deg"]


def _loaded(*args: str) -> tuple[list[str], str]:
    run = subprocess.run([sys.executable, "-c", PROBE, *args], cwd=ROOT, capture_output=True, text=True,
                         timeout=300)
    line = run.stdout.strip().splitlines()[-1]
    loaded, code = line.removeprefix("LOADED:").split(" EXIT:")
    return [m for m in loaded.split(",") if m], code


def test_help_loads_no_cad_library():
    assert _loaded("--help") == ([], "0")


@pytest.mark.parametrize("recipe", ONE_PER_KIND)
def test_validate_loads_no_cad_library(recipe):
    assert _loaded("validate", "--fast", f"recipes/{recipe}.yaml") == ([], "0")


@pytest.mark.slow
@pytest.mark.parametrize("recipe", sorted(p.stem for p in (ROOT / "recipes").glob("*.yaml")
                                          if p.stem not in ONE_PER_KIND))
def test_validate_every_recipe_loads_no_cad_library(recipe):
    assert _loaded("validate", "--fast", f"recipes/{recipe}.yaml") == ([], "0")


def test_full_validate_builds_the_solid_model():
    """Without --fast, validate builds the solid model (its triangle limits): it loads OCP."""
    loaded, code = _loaded("validate", "recipes/ptfe-lens-120mm.yaml")
    assert code == "0" and "OCP" in loaded


def test_probe_sees_a_build_import_them(tmp_path):
    """The probe can fail: a build does load the CAD libraries — OCP itself, never build123d (its
    import alone cost ~165 MB and ~2 s)."""
    loaded, code = _loaded("build", "recipes/ptfe-lens-120mm.yaml", "-o", str(tmp_path))
    assert code == "0" and {"OCP", "trimesh"} <= set(loaded) and "build123d" not in loaded
