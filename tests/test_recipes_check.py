"""Every recipe, built twice: byte-identical files and ``make-lens check`` passes
on the build (item 2: gmsh re-reads the STEP with the manifest's solids, names and volumes, the
STL/DXF/SVG/PDF readers agree with the manifest). Slow: full builds of every recipe, twice (the first shared with the other slow tests)."""

from pathlib import Path

import pytest

from antenna_cad.export.check import check_build
from antenna_cad.pipeline import build
from antenna_cad.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
RECIPES = sorted((ROOT / "recipes").glob("*.yaml"))


@pytest.mark.slow
@pytest.mark.parametrize("recipe", RECIPES, ids=[r.stem for r in RECIPES])
def test_recipe_is_reproducible_and_passes_check(recipe, tmp_path, recipe_build):
    first = recipe_build(recipe).out_dir
    second = build(load_spec(recipe), tmp_path).out_dir
    files = sorted(p.relative_to(first) for p in first.rglob("*") if p.is_file())
    assert files == sorted(p.relative_to(second) for p in second.rglob("*") if p.is_file())
    differ = [str(f) for f in files if (first / f).read_bytes() != (second / f).read_bytes()]
    assert not differ, f"{len(differ)} of {len(files)} files differ between two builds: {differ[:5]}"
    failed = [f for f in check_build(first) if not f.ok]
    assert not failed, "; ".join(f"{f.file} {f.check}: {f.message}" for f in failed[:5])
