"""Build-time benchmark of the collimator pipeline (imports excluded), per stage.

    python benchmarks/collimator_build.py [recipe ...]

Prints one row per recipe: seconds per stage and the total. Also a sheet-count sweep on the
default recipe (sheet thickness 100 → 10 mm) to show cost stays linear in sheets.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

from antenna_cad.pipeline import STAGES, build
from antenna_cad.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]


def run(spec) -> dict[str, float]:
    with tempfile.TemporaryDirectory() as tmp:
        return build(spec, Path(tmp)).seconds


def main(recipes: list[str]) -> None:
    print(f"{'recipe':34s} " + " ".join(f"{s:>9s}" for s in STAGES) + "     total")
    for recipe in recipes:
        seconds = run(load_spec(recipe))
        print(f"{Path(recipe).stem:34s} " + " ".join(f"{seconds.get(s, 0):9.2f}" for s in STAGES)
              + f" {sum(seconds.values()):9.2f}")
    base = load_spec(ROOT / "recipes" / "xps-collimator-0.5m.yaml")
    print("\nsheets  seconds  seconds/sheet   (default recipe, varying sheet thickness)")
    for t in (100.0, 50.0, 25.0, 10.0):
        spec = base.model_copy(update={"fabrication": base.fabrication.model_copy(
            update={"sheet_thickness_mm": t})})
        start = time.perf_counter()
        seconds = run(spec)
        sheets = -(-311.73 // t)
        print(f"{int(sheets):6d} {sum(seconds.values()):8.2f} {sum(seconds.values()) / sheets:13.3f}"
              f"   (wall {time.perf_counter() - start:.2f})")


if __name__ == "__main__":
    main(sys.argv[1:] or [str(p) for p in sorted((ROOT / "recipes").glob("*collimator*.yaml"))]
         + [str(ROOT / "recipes" / "ptfe-lens-120mm.yaml")])
