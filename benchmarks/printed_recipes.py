"""Every printed recipe's whole build from the command line (`python -m antenna_cad build`, full-wave
off, a fresh interpreter, imports included), ``--runs`` times, the recipes taken in turn so a change
of load falls on all of them: wall (min / median / max), CPU, peak RSS, the lattice's cells and
triangles, and the one-minute budget of a printed recipe. Prints a Markdown table. Not a unit test:
the machine is shared, so read the load averages it records.

    PYTHONPATH=. python benchmarks/printed_recipes.py [--runs 3] [RECIPE ...]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BUDGET_S = 60.0
TIME = "/usr/bin/time"


def printed_recipes() -> list[str]:
    return sorted(p.stem for p in (ROOT / "recipes").glob("*.yaml") if "method: printed" in p.read_text(encoding="utf-8"))


def one_build(name: str) -> dict:
    """Wall, user + system CPU and peak RSS of one CLI build (GNU time), and the manifest's lattice size."""
    env = dict(os.environ, ANTENNA_CAD_MEEP_PYTHON="/usr/bin/false", PYTHONPATH=str(ROOT))
    with tempfile.TemporaryDirectory(prefix="printed-bench-") as out:
        run = subprocess.run([TIME, "-f", "TIME %e %U %S %M", sys.executable, "-m", "antenna_cad", "build",
                              str(ROOT / "recipes" / f"{name}.yaml"), "-o", out],
                             capture_output=True, text=True, env=env, check=True)
        figures = json.loads((Path(out) / name / "manifest.json").read_text(encoding="utf-8"))["verification"]["figures"]
    wall, user, system, peak_kb = map(float, run.stderr.rsplit("TIME ", 1)[1].split()[:4])
    return {"wall_s": wall, "cpu_s": user + system, "peak_mb": peak_kb / 1024, "load": os.getloadavg()[0],
            "cells": int(figures["printed_cells"]), "triangles": int(figures["printed_triangles"])}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("recipes", nargs="*", help="recipe names (default: every printed recipe)")
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    names = args.recipes or printed_recipes()
    runs: dict[str, list[dict]] = {n: [] for n in names}
    for _ in range(args.runs):
        for name in names:
            runs[name].append(one_build(name))
            print(f"{name}: {runs[name][-1]['wall_s']:.1f} s", file=sys.stderr, flush=True)
    print(f"{os.cpu_count()} cores; {args.runs} runs each, recipes in turn; full-wave off\n")
    print("| recipe | cells | triangles | wall s (min / median / max) | CPU s (median) | peak RSS MB (max) "
          "| load average | under a minute |")
    print("|---|---:|---:|---|---:|---:|---|---|")
    for name, rs in runs.items():
        walls = [r["wall_s"] for r in rs]
        loads = [r["load"] for r in rs]
        print(f"| `{name}` | {rs[0]['cells']:,} | {rs[0]['triangles']:,} | {min(walls):.1f} / "
              f"{statistics.median(walls):.1f} / {max(walls):.1f} | {statistics.median(r['cpu_s'] for r in rs):.1f} | "
              f"{max(r['peak_mb'] for r in rs):.0f} | {min(loads):.1f}–{max(loads):.1f} | "
              f"{'yes' if statistics.median(walls) < BUDGET_S else 'no'} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
