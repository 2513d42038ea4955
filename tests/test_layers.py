"""Layers checked by a tool: the import-linter contracts of pyproject.toml hold, and the
tool sees the imports made inside functions (the kinds import geometry lazily)."""

import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LINT = shutil.which("lint-imports") or str(Path(sys.executable).parent / "lint-imports")


def _lint(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([LINT, "--no-cache", *args], cwd=ROOT, capture_output=True, text=True, timeout=300)


def test_layer_contracts_are_kept():
    run = _lint()
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-2000:]
    contracts = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]["contracts"]
    assert f"{len(contracts)} kept, 0 broken" in run.stdout


def test_linter_sees_function_level_imports(tmp_path):
    config = tmp_path / "probe.toml"
    config.write_text('[tool.importlinter]\nroot_packages = ["antenna_cad"]\ninclude_external_packages = true\n\n'
                      '[[tool.importlinter.contracts]]\nname = "probe: kinds without geometry"\ntype = "forbidden"\n'
                      'source_modules = ["antenna_cad.kinds.collimator"]\nforbidden_modules = ["antenna_cad.geometry"]\n')
    run = _lint("--config", str(config))
    assert run.returncode == 1 and "antenna_cad.kinds.collimator is not allowed to import antenna_cad.geometry" in run.stdout
