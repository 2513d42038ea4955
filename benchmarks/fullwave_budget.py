"""Build times with the full-wave stage on (Meep installed) and off (Meep hidden), per recipe: wall time,
the seconds the solver spent in the build, the budget, what the budget cut, and the progress lines the
build printed on stderr. Not a unit test.

    PYTHONPATH=. python benchmarks/fullwave_budget.py [--recipe NAME ...] [--burners N] [--logs DIR]
                                                      [--cache DIR] [--budget-s S]

Each build runs in a fresh interpreter (wall time includes its imports) with its stderr in
``DIR/<recipe>-{on,off}.log`` (``[elapsed] stage fraction detail`` lines from the progress callback).
The full-wave cache starts empty (``--cache``: a folder to reuse instead), so every run is a first
run on a machine whose throughput is unknown: the first build with Meep starts with the probe.
``--burners N`` keeps N busy-looping processes running during the builds (a loaded machine).
Writes ``benchmarks/results-fullwave.json`` and the full-wave section of ``benchmarks/results.md``.
"""

from __future__ import annotations

import argparse
import datetime as dt
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results-fullwave.json"
MARK_BEGIN, MARK_END = "<!-- full-wave on: benchmarks/fullwave_budget.py -->", "<!-- /full-wave on -->"
DRIVER = r"""
import json, sys, time
from pathlib import Path
start = time.perf_counter()
from antenna_cad.pipeline import build
from antenna_cad.spec import load_spec

def progress(stage, fraction, detail=""):
    sys.stderr.write(f"[{time.perf_counter() - start:7.1f} s] {stage} {fraction:4.0%} {detail}\n")
    sys.stderr.flush()

spec = load_spec(sys.argv[1])
if len(sys.argv) > 3:
    spec = spec.model_copy(update={"verification": spec.verification.model_copy(update={"budget_s": float(sys.argv[3])})})
t0 = time.perf_counter()
result = build(spec, Path(sys.argv[2]), progress)
t1 = time.perf_counter()
checks = [c for c in result.checks if c.name.startswith("full_wave")]
for c in checks:
    sys.stderr.write(f"check {c.name} {c.status}: {c.message}\n")
json.dump({"build_s": t1 - t0, "wall_s": t1 - start, "budget_s": spec.verification.budget_s,
           "mode": spec.verification.full_wave, "status": result.status,
           "figures": {k: v for k, v in result.verified.items() if k.endswith(("_seconds", "_runs_cut", "_runs"))},
           "checks": [{"name": c.name, "status": c.status, "message": c.message} for c in checks]}, sys.stdout)
"""


def _build(recipe: Path, logs: Path, meep: bool, cache: Path, budget_s: float | None) -> dict:
    env = os.environ | {"PYTHONPATH": str(ROOT), "ANTENNA_CAD_FULLWAVE_CACHE": str(cache)}
    if not meep:
        env["ANTENNA_CAD_MEEP_PYTHON"] = "/usr/bin/false"
    log = logs / f"{recipe.stem}-{'on' if meep else 'off'}.log"
    with tempfile.TemporaryDirectory() as out, log.open("w") as err:
        args = [sys.executable, "-c", DRIVER, str(recipe), out] + ([str(budget_s)] if budget_s else [])
        start = time.perf_counter()
        done = subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=err, text=True)
        elapsed = time.perf_counter() - start
    if done.returncode != 0:
        return {"error": f"exit {done.returncode} (see {log})", "wall_s": elapsed, "log": str(log)}
    row = json.loads(done.stdout) | {"process_s": elapsed, "log": str(log)}
    return row | {"progress": _progress(row)}


def _cut(row: dict) -> str:
    """What the budget cut, or why full-wave did not run, from the stage checks."""
    notes = []
    for c in row.get("checks", []):
        text = c["message"]
        for key in ("cut at budget_s", "skipped: ", "not run: "):
            if key in text:
                notes.append(f"{c['name']}: " + text[text.index(key):].split(";")[0].split(" (raise")[0])
                break
    return "; ".join(notes) or "nothing"


def section(results: dict) -> str:
    """The Markdown section of results.md: every recipe with full-wave on and off."""
    m = results["machine"]
    lines = [MARK_BEGIN, "## Build times with the full-wave stage on and off", "",
             f"{m['date']}; commit {m['commit']}; load average at start {m['load_average_start']:.2f}; "
             f"{m['burners']} CPU burners running; full-wave cache empty at the start (the first Meep build "
             "calibrates the throughput with a probe run). Command: "
             f"`PYTHONPATH=. python benchmarks/fullwave_budget.py {' '.join(results['argv'])}`.",
             "Wall: the whole `build` in a fresh interpreter (imports included). Solver: seconds the full-wave "
             "stages spent in the build (`fullwave_seconds` + `fullwave_scan_edge_seconds`). Over: wall with "
             "full-wave on minus wall with it off minus the budget (≤ 0: within the budget); the on and off builds run "
             "minutes apart on a shared machine, so `over` carries the load's noise on the rest of the build, while "
             "the solver column is the cap itself (budget_s plus at most the 0.2 s poll).", "",
             "| recipe | wall off s | wall on s | solver s | budget s | over s | status on | cut / not run |",
             "|---|---:|---:|---:|---:|---:|---|---|"]
    for name, r in results["recipes"].items():
        on, off = r["on"], r["off"]
        if "error" in on or "error" in off:
            lines.append(f"| {name} | {off.get('wall_s', 0):.1f} | {on.get('wall_s', 0):.1f} | | | | error | "
                         f"{on.get('error') or off.get('error')} |")
            continue
        if not on["checks"]:
            lines.append(f"| {name} | {on['process_s']:.1f} | (no full-wave stage) | | | | {on['status']} | |")
            continue
        f = on["figures"]
        solver = f.get("fullwave_seconds", 0.0) + f.get("fullwave_scan_edge_seconds", 0.0)
        over = on["process_s"] - off["process_s"] - on["budget_s"]
        lines.append(f"| {name} | {off['process_s']:.1f} | {on['process_s']:.1f} | {solver:.1f} | {on['budget_s']:g} "
                     f"| {over:+.1f} | {on['status']} | {_cut(on)} |")
    first = next(iter(results["recipes"].items()), None)
    if first and _progress(first[1]["on"]):
        lines += ["", f"Progress lines of `{first[0]}` with full-wave on (its stderr, redirected to a file):", "",
                  "```", *_progress(first[1]["on"]), "```"]
    return "\n".join(lines + ["", MARK_END]) + "\n"


def _progress(row: dict) -> list[str]:
    """The build's stderr lines (kept in the row, or read from its log while it exists)."""
    if "progress" not in row and Path(row.get("log", "/nonexistent")).is_file():
        row["progress"] = Path(row["log"]).read_text(encoding="utf-8").splitlines()
    return row.get("progress", [])


def write_section(results: dict) -> None:
    path = ROOT / "benchmarks" / "results.md"
    text = path.read_text(encoding="utf-8") if path.exists() else "# Benchmark results\n"
    if MARK_BEGIN in text:
        text = text[:text.index(MARK_BEGIN)] + text[text.index(MARK_END) + len(MARK_END) + 1:]
    path.write_text(text.rstrip("\n") + "\n\n" + section(results), encoding="utf-8")


def keep_section() -> None:
    """Put the last measured full-wave section back into a freshly written results.md."""
    if RESULTS.exists():
        results = json.loads(RESULTS.read_text(encoding="utf-8"))
        write_section(results)
        RESULTS.write_text(json.dumps(results, indent=1) + "\n", encoding="utf-8")   # with the progress lines read


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--recipe", nargs="*", default=None)
    parser.add_argument("--burners", type=int, default=0)
    parser.add_argument("--logs", type=Path, default=Path(tempfile.gettempdir()) / "fullwave-budget-logs")
    parser.add_argument("--cache", type=Path, default=None)
    parser.add_argument("--budget-s", type=float, default=None)
    args = parser.parse_args()
    args.logs.mkdir(parents=True, exist_ok=True)
    recipes = [ROOT / "recipes" / (r if r.endswith(".yaml") else r + ".yaml") for r in args.recipe] if args.recipe \
        else sorted((ROOT / "recipes").glob("*.yaml"))
    burners = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(args.burners)]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    results = {"argv": sys.argv[1:], "machine": {"date": dt.datetime.now(dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                                                  "commit": commit, "load_average_start": os.getloadavg()[0],
                                                  "burners": args.burners}, "recipes": {}}
    try:
        with tempfile.TemporaryDirectory(prefix="fullwave-cache-") as fresh:
            cache = args.cache or Path(fresh)
            for recipe in recipes:
                on = _build(recipe, args.logs, True, cache, args.budget_s)
                stage = "error" in on or on["checks"]                  # a kind without a full-wave stage: one build
                off = _build(recipe, args.logs, False, cache, args.budget_s) if stage else on
                results["recipes"][recipe.stem] = {"on": on, "off": off}
                print(f"{recipe.stem}: off {off.get('process_s', 0):.1f} s, on {on.get('process_s', 0):.1f} s, "
                      f"cut: {_cut(on)}", flush=True)
                RESULTS.write_text(json.dumps(results, indent=1) + "\n", encoding="utf-8")   # after each recipe
                write_section(results)
    finally:
        for b in burners:
            b.kill()
            b.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
