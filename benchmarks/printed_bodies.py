"""Printed lens bodies (graded lens, mirror-lens body): fabrication time (cells sorted, inner lattice,
trimmed boundary and skin, parts, 3MF/STL bytes) against the number of cells, CPU and wall, then each
recipe's whole build (full-wave off) in a fresh interpreter with its peak RSS. Not a unit test: the
machine is shared, so read the CPU times and the load average.

    PYTHONPATH=. python benchmarks/printed_bodies.py [--scales 0.5 0.75 1] [--no-build]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

from antenna_cad.spec import load_spec, parse_spec

sys.path.insert(0, str(Path(__file__).parent))
from printed_lattice import build_row  # noqa: E402  (the same fresh-interpreter build, another recipe)

ROOT = Path(__file__).resolve().parents[1]
RECIPES = {"mirror_lens": ROOT / "recipes" / "mirror-lens-346mm-printed.yaml",
           "graded": ROOT / "recipes" / "graded-trifocal-160mm-printed.yaml"}


def fabrication_row(kind: str, scale: float = 1.0) -> dict:
    """The kind's fabricate() on its recipe (the mirror-lens body scaled by ``scale``, its cell kept):
    cells, triangles, CPU and wall seconds."""
    from importlib import import_module
    mod = import_module(f"antenna_cad.kinds.{kind}")
    data = load_spec(RECIPES[kind]).model_dump(mode="json", exclude_none=True)
    for key in ("diameter_mm", "f0_mm", "d0_mm") if scale != 1.0 else ():
        data["design"][key] *= scale
    spec = parse_spec(data)
    design = mod.synthesize(spec)
    wall, cpu = time.perf_counter(), time.process_time()
    fab = mod.fabricate(spec, design, None, ())
    return {"kind": kind, "cell_mm": spec.fabrication.cell_mm, "cells": fab.lens.cells,
            "triangles": int(fab.figures["printed_triangles"]), "cpu_s": time.process_time() - cpu,
            "wall_s": time.perf_counter() - wall, "mb_out": sum(len(v) for v in fab.files.values()) / 1e6}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--scales", type=float, nargs="+", default=[0.5, 0.75, 1.0])
    ap.add_argument("--no-build", action="store_true")
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    rows = [fabrication_row("mirror_lens", x) for x in args.scales] + [fabrication_row("graded")]
    print(f"{'kind':>12} {'cell mm':>8} {'cells':>8} {'triangles':>10} {'CPU s':>7} {'wall s':>7} {'µs/cell':>8} {'MB out':>7}")
    for r in rows:
        print(f"{r['kind']:>12} {r['cell_mm']:8.2f} {r['cells']:8d} {r['triangles']:10d} {r['cpu_s']:7.1f} "
              f"{r['wall_s']:7.1f} {1e6 * r['cpu_s'] / r['cells']:8.1f} {r['mb_out']:7.1f}")
    if not args.no_build:
        for kind, recipe in RECIPES.items():
            b = build_row(recipe)
            print(f"{recipe.name}: build {b['wall_s']:.1f} s wall, {b['cpu_s']:.1f} s CPU, peak RSS {b['peak_mb']:.0f} MB "
                  f"(load average {os.getloadavg()[0]:.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
