"""Printed lattice lenses: fabrication time (lattice mesh, trimming, pins, 3MF/STL bytes) and mesh size
against the number of cells, with the fitted exponents (linear: ≈ 1), then the recipe's whole build
(full-wave off) in a fresh interpreter, with its peak RSS. ``--gyroid``: the same for the sheet-gyroid
recipe (its level-set points, the volume error) and the Ø120 mm gyroid's estimated cost. Not a unit
test: read the load average.

    PYTHONPATH=. python benchmarks/printed_lattice.py [--sizes 60 90 120 150] [--no-build]
    PYTHONPATH=. python benchmarks/printed_lattice.py --gyroid --sizes 20 30 40 --no-build
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from antenna_cad.kinds.luneburg import fabricate, synthesize
from antenna_cad.printed.lattice import gyroid_edge_mm, gyroid_grid_points
from antenna_cad.spec import load_spec, parse_spec

ROOT = Path(__file__).resolve().parents[1]
RECIPE = ROOT / "recipes" / "luneburg-printed-120mm-pla.yaml"
GYROID = ROOT / "recipes" / "luneburg-printed-gyroid-40mm-pla.yaml"
BUILD_LIMIT_S = 60.0


def fabrication_row(diameter_mm: float, recipe: Path = RECIPE) -> dict:
    data = load_spec(recipe).model_dump(mode="json")
    data["design"]["diameter_mm"] = diameter_mm
    spec = parse_spec(data)
    design = synthesize(spec)
    start = time.perf_counter()
    fab = fabricate(spec, design, None, ())
    seconds = time.perf_counter() - start
    fig = fab.figures
    edge = gyroid_edge_mm(spec.fabrication.cell_mm, fab.fill.fill_range)
    return {"diameter_mm": diameter_mm, "cells": fab.lens.cells, "triangles": int(fig["printed_triangles"]),
            "seconds": seconds, "bytes": sum(len(v) for v in fab.files.values()),
            "volume_error": fig["printed_volume_error"],
            "points": gyroid_grid_points("sphere", diameter_mm / 2, diameter_mm / 2, edge)}


def build_row(recipe: Path = RECIPE) -> dict:
    """The recipe's build in a fresh interpreter: wall time, CPU time, peak RSS (of the build)."""
    env = dict(os.environ, ANTENNA_CAD_MEEP_PYTHON="/usr/bin/false", PYTHONPATH=str(ROOT))
    code = ("import resource,sys,time;from antenna_cad.api import build;t=time.perf_counter();"
            f"build({str(recipe)!r}, sys.argv[1]);w=time.perf_counter()-t;"
            "r=resource.getrusage(resource.RUSAGE_SELF);"
            "print(w, r.ru_utime+r.ru_stime, r.ru_maxrss/1024)")
    with tempfile.TemporaryDirectory() as out:
        run = subprocess.run([sys.executable, "-c", code, out], capture_output=True, text=True, env=env, check=True)
    wall, cpu, peak = map(float, run.stdout.split()[-3:])
    return {"wall_s": wall, "cpu_s": cpu, "peak_mb": peak}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", type=float, nargs="+", default=[60.0, 90.0, 120.0, 150.0])
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--gyroid", action="store_true", help="the sheet-gyroid recipe (sizes: small, e.g. 20 30 40)")
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    rows = [fabrication_row(d, GYROID if args.gyroid else RECIPE) for d in args.sizes]
    print(f"{'D mm':>6} {'cells':>7} {'triangles':>10} {'s':>7} {'µs/cell':>8} {'tri/cell':>8} {'MB out':>7} "
          f"{'vol err':>8} {'LS points':>10}")
    for r in rows:
        print(f"{r['diameter_mm']:6.0f} {r['cells']:7d} {r['triangles']:10d} {r['seconds']:7.2f} "
              f"{1e6 * r['seconds'] / r['cells']:8.1f} {r['triangles'] / r['cells']:8.1f} {r['bytes'] / 1e6:7.1f} "
              f"{r['volume_error']:+8.2%} {r['points']:10d}")
    cells = np.log([r["cells"] for r in rows])
    for what in ("seconds", "triangles"):
        slope = np.polyfit(cells, np.log([r[what] for r in rows]), 1)[0]
        print(f"exponent of {what} vs cells: {slope:.2f}")
    if args.gyroid:
        per_point = rows[-1]["seconds"] / rows[-1]["points"]
        tri_per_point = rows[-1]["triangles"] / 2 / rows[-1]["points"]
        big = gyroid_grid_points("sphere", 60.0, 60.0, gyroid_edge_mm(3.6, (0.381, 0.855)))
        print(f"{1e6 * per_point:.1f} µs and {tri_per_point:.2f} triangles per level-set point: a Ø120 mm PLA gyroid "
              f"at 12 GHz (cell 3.6 mm, 0.4 mm walls and gaps) has {big / 1e6:.0f} M points per hemisphere: "
              f"~{big * per_point / 60:.0f} min and ~{big * tri_per_point / 1e6:.0f} M triangles")
    if args.no_build:
        return 0
    b = build_row()
    ok = b["wall_s"] <= BUILD_LIMIT_S
    print(f"{RECIPE.name}: build {b['wall_s']:.1f} s wall (limit {BUILD_LIMIT_S:g} s: {'ok' if ok else 'OVER'}), "
          f"{b['cpu_s']:.1f} s CPU, peak {b['peak_mb']:.0f} MB")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
