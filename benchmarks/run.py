"""Every recipe end to end, split by stage, with import time and peak memory; scaling series with
fitted exponents; the naive baseline; the budgets. Not a unit test: run it on a quiet
machine and read the load average it records.

    PYTHONPATH=. python benchmarks/run.py [--runs 3] [--recipe NAME ...] [--series] [--naive [--naive-guides N]]
                                          [--large]
                                          [--compare OLD.json] [--before OLD_CHECKOUT] [--no-fail]

Each recipe runs in a fresh interpreter, so its import time and peak RSS are its own; the stage
times are the median of ``--runs`` builds in that process after imports. Writes
``benchmarks/results.md`` (table, machine, date, commit, budgets) and ``benchmarks/results.json``
(to compare commits: ``--compare OLD.json`` adds the before/after table with its figures). Exits 1 when a
scaling exponent exceeds 1.1 or a budget is missed, naming the stage (``--no-fail``: report only).
"""

from __future__ import annotations

import argparse
import datetime as dt
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CAD_MODULES = ("build123d", "OCP", "trimesh", "manifold3d", "ezdxf", "matplotlib")
WRITERS = ("antenna_cad.export.report", "antenna_cad.export.report_pdf", "antenna_cad.export.mesh",
           "antenna_cad.export.step", "antenna_cad.fabrication.templates", "ezdxf")
DEFAULT_RECIPE = "xps-collimator-0.5m.yaml"     # the README's first build: its validate is timed too
EXPONENT_LIMIT = 1.1
BUDGET = {"recipe_s": 10.0, "peak_mb": 500.0, "cli_s": 1.0, "naive_speedup": 20.0, "large_luneburg_s": 60.0}
RECIPE_BUDGET_S = {name: 60.0 for name in (          # printed lattice lenses: "under a minute" (their guides)
    "luneburg-printed-120mm-pla", "graded-trifocal-160mm-printed", "mirror-lens-346mm-printed",
    "xps-collimator-printed-300mm-pla", "luneburg-printed-gyroid-40mm-pla")}
NOT_BUDGETED = ("fullwave",)        # the full-wave stage has its own budget (its issue): reported apart
CLI_PROBE = """
import atexit, sys, time
atexit.register(lambda: sys.stderr.write("\\nCAD-MODULES:" + ",".join(
    m for m in %r if m in sys.modules) + "\\n"))
sys.argv = ["make-lens", *sys.argv[1:]]
if sys.argv[1] == "validate":        # time the rules' work (pipeline.prepare) and the packages it imports
    import antenna_cad.pipeline as pipeline
    plain = pipeline.prepare
    def prepare(spec):
        before, start = {m.split(".")[0] for m in sys.modules}, time.perf_counter()
        try:
            return plain(spec)
        finally:
            new = sorted(m for m in {m.split(".")[0] for m in sys.modules} - before - {"antenna_cad"}
                         if not m.startswith("_") and m not in sys.stdlib_module_names)
            sys.stderr.write("\\nPREPARE:%%.3f:%%s\\n" %% (time.perf_counter() - start, ",".join(new)))
    pipeline.prepare = prepare
from antenna_cad.cli import main
main()
""" % (CAD_MODULES,)


# ---------------------------------------------------------------- children (one interpreter each)

def _imports() -> float:
    start = time.perf_counter()
    import antenna_cad.geometry.kernel  # noqa: F401  (the CAD kernel's import measured apart from the build)
    import antenna_cad.pipeline  # noqa: F401
    for writer in WRITERS:        # imported by the pipeline at use (validate stays light): measured here
        try:
            __import__(writer)
        except ImportError:       # an older tree (--before) without that module
            pass
    return time.perf_counter() - start


def _peak_mb(who: str = "self") -> float:
    """Peak RSS of this process, or (``children``) of its largest child (STEP or template writer)."""
    import resource
    return resource.getrusage(resource.RUSAGE_CHILDREN if who == "children" else resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _cpu_s() -> float:
    """CPU seconds of this process and its finished children (less sensitive to load than wall time)."""
    import resource
    return sum(resource.getrusage(w).ru_utime + resource.getrusage(w).ru_stime
               for w in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))


def _build(spec) -> tuple[dict[str, float], dict]:
    from antenna_cad.pipeline import build
    with tempfile.TemporaryDirectory(prefix="antenna_cad-bench-") as out:
        result = build(spec, Path(out))
        manifest = json.loads((result.out_dir / "manifest.json").read_text(encoding="utf-8"))
    items = {"parts": len(manifest.get("parts", [])), "sheets": len(manifest.get("sheets", [])),
             "pieces": len(manifest.get("pieces", [])), "slots": result.figures.get("slot_count", 0)}
    return dict(result.seconds), items


def child_recipe(recipe: str, runs: int) -> dict:
    import why
    import_s = _imports()
    import_mb = why.rss_mb()
    from antenna_cad.spec import load_spec
    per_run: list[dict[str, float]] = []
    cpu = []
    for _ in range(runs):
        start, cpu_start = time.perf_counter(), _cpu_s()
        spec = load_spec(recipe)
        load_s = time.perf_counter() - start
        seconds, items = _build(spec)
        per_run.append({"load": load_s} | seconds)
        cpu.append(_cpu_s() - cpu_start)
    stages = {k: statistics.median(run[k] for run in per_run) for k in per_run[0]}
    result = {"import_s": import_s, "import_mb": import_mb, "stages": stages, "items": items,
              "peak_mb": _peak_mb(), "runs": runs, "child_peak_mb": _peak_mb("children"),
              "cpu_s": statistics.median(cpu)}
    budgeted = _budgeted(stages)
    if sum(budgeted.values()) > BUDGET["recipe_s"]:        # over budget: one profiled build says why
        slowest = max(budgeted, key=budgeted.get)
        result["slowest_why"] = why.stage_reason(why.stage_profiles(load_spec(recipe)), slowest)
    return result


def _budgeted(stages: dict[str, float]) -> dict[str, float]:
    """The stages the recipe budget counts (the full-wave stage has its own)."""
    return {k: v for k, v in stages.items() if not k.startswith(NOT_BUDGETED)}


def _variant(recipe: str, changes: dict, outputs: dict):
    """The recipe with dotted-path changes applied to its YAML data, parsed like a spec file."""
    import yaml

    from antenna_cad.spec import parse_spec
    data = yaml.safe_load((ROOT / "recipes" / recipe).read_text(encoding="utf-8"))
    for path, value in (changes | {f"outputs.{k}": v for k, v in outputs.items()}).items():
        node = data
        *parents, leaf = path.split(".")
        for key in parents:
            node = node.setdefault(key, {})
        node[leaf] = value
    return parse_spec(data, recipe)


SERIES = {   # name: (recipe, dotted field, values, item counted, outputs, fixed changes)
    # the beam former at twice the recipe's scale (slot line 16 mm off) holds 80 guides (6,400 slots)
    "slots": ("ka-slot-array-two-mirror.yaml", "array.count", [10, 20, 40, 80], "slots",
              {"stl": True, "templates": True, "report": False},
              {"beamformer.scale_mm": 400.0, "beamformer.slot_line_offset_mm": 16.0}),
    # 10 mm dowels: the 20 mm default does not fit the smallest disc of the 5 mm layup; the full-wave
    # stage off (its own budget; with Meep installed `auto` ran it for one new geometry: 127 s at 5 mm)
    "sheets": ("xps-collimator-0.5m.yaml", "fabrication.sheet_thickness_mm", [100.0, 50.0, 20.0, 10.0, 5.0],
               "sheets", {"stl": True, "templates": True, "report": False},
               {"fabrication.dowel_diameter_mm": 10.0, "verification.full_wave": "off"}),
}
LUNEBURG_SERIES = [(5, 400.0), (10, 1000.0), (20, 2000.0), (20, 3000.0)]   # layers, D mm (10 mm sheets)


def _luneburg_spec(layers: int, diameter_mm: float, templates: bool):
    from antenna_cad.spec import parse_spec
    return parse_spec({
        "name": "bench", "kind": "luneburg", "frequency_ghz": 10.0, "material": "polystyrene",
        "design": {"diameter_mm": diameter_mm, "law": "classic", "layers": {"count": layers}},
        "fabrication": {"method": "sheet_layup", "sheet_thickness_mm": 10.0, "kerf_mm": 0.5,
                        "board": {"width_mm": 1200, "length_mm": 2400}},
        "outputs": {"templates": templates, "report": False}}, "luneburg-series")


def child_series(name: str) -> dict:
    _imports()
    rows = []
    if name == "shells_x_sheets":
        _lift_limits()
        for layers, diameter in LUNEBURG_SERIES:
            seconds, items = _build(_luneburg_spec(layers, diameter, templates=False))
            rows.append({"value": f"{layers} layers, D {diameter:.0f} mm", "items": items["pieces"],
                         "seconds": sum(seconds.values()), "stages": seconds})
            print(json.dumps(rows[-1]), file=sys.stderr, flush=True)      # progress: long rows
        return {"item": "pieces", "rows": rows}
    recipe, field, values, item, outputs, fixed = SERIES[name]
    for value in values:
        seconds, items = _build(_variant(recipe, fixed | {field: value}, outputs))
        rows.append({"value": value, "items": items[item], "seconds": sum(seconds.values()), "stages": seconds})
    return {"item": item, "rows": rows}


def child_naive(guides: int) -> dict:
    _imports()
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import naive

    from antenna_cad.registry import adapter
    spec = _variant("ka-slot-array-two-mirror.yaml", {}, {})
    design = adapter(spec.kind).synthesize(spec)
    lids = naive.slotted_lids(design, spec.fabrication.broad_wall_mm, guides or None)
    if guides:      # the naive cost is linear in the guides (checked on twice as many): extrapolated
        twice = naive.slotted_lids(design, spec.fabrication.broad_wall_mm, 2 * guides)
        exponent = float(np.log(twice[0] / lids[0]) / np.log(twice[2] / lids[2]))
        naive_all = twice[0] * lids[4] / twice[2]
        extrapolated = {"what": f"slotted lids, all {lids[4]} slots: naive extrapolated from {lids[2]} and "
                                f"{twice[2]} slots (exponent {exponent:.2f}), ours measured",
                        "naive_s": naive_all, "ours_s": lids[3], "items": lids[4], "speedup": naive_all / lids[3],
                        "naive_exponent": exponent}
    col = _variant("xps-collimator-0.5m.yaml", {"fabrication.sheet_thickness_mm": 10.0}, {})
    kind = adapter(col.kind)
    col_design = kind.synthesize(col)
    layup, panels = kind.plan(col, col_design)
    model = kind.model(col, col_design, layup, panels)
    sheets = naive.layup_sheets(layup, model.part("lens").shape)
    mesh = naive.node_loop_mesh([p.shape for p in model.parts], col.outputs.mesh_tolerance_mm)
    row = lambda what, r: {"what": what, "naive_s": r[0], "ours_s": r[1], "items": r[2], "speedup": r[0] / r[1]}
    rows = [row("slotted lids, Ka two-mirror (slots)", lids),
            row("collimator sheets, 10 mm boards (sheets)", sheets),
            row("meshing the collimator's parts (triangles)", mesh)]
    return {"rows": ([extrapolated] if guides else []) + rows}


def _lift_limits() -> None:
    """The large layups (up to ~30,000 ring pieces) are above the build's hard limits
    (antenna_cad.limits, a guard against unit slips), lifted here: this measures speed, not the guard."""
    from antenna_cad import limits
    limits.LIMITS = {k: limits.Limit(v.what, v.field, v.soft, 10**7) for k, v in limits.LIMITS.items()}


def child_large() -> dict:
    """The D/λ = 100 layup with its templates (limits lifted, :func:`_lift_limits`)."""
    _imports()
    _lift_limits()
    cpu_start = _cpu_s()
    seconds, items = _build(_luneburg_spec(20, 100 * 299.792458 / 10.0, templates=True))
    return {"stages": seconds, "items": items, "peak_mb": _peak_mb(), "child_peak_mb": _peak_mb("children"),
            "cpu_s": _cpu_s() - cpu_start}


# ---------------------------------------------------------------- parent

def _run_child(*args: str, root: Path = ROOT) -> dict:
    """One child in a fresh interpreter; ``root``: the source tree it imports (``--before``: an older
    checkout, whose own run.py answers)."""
    env = os.environ | {"PYTHONPATH": str(root) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    cpu = _children_cpu_s()
    done = subprocess.run([sys.executable, str(root / "benchmarks" / "run.py"), "--child", *args],
                          capture_output=True, text=True, env=env)
    if done.returncode:
        raise SystemExit(f"benchmark child {args} failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1]) | {"cpu_s": _children_cpu_s() - cpu}


def _children_cpu_s() -> float:
    """CPU seconds (user + system) of the finished children and theirs (imports and builds of a
    recipe child, its forked report writer included): steadier than wall time on a loaded machine."""
    times = os.times()
    return times.children_user + times.children_system


def _cli_timing(args: list[str], root: Path = ROOT) -> dict:
    cpu, start = _children_cpu_s(), time.perf_counter()
    done = subprocess.run([sys.executable, "-c", CLI_PROBE, *args], capture_output=True, text=True, cwd=root,
                          env=os.environ | {"PYTHONPATH": str(root)})
    wall = time.perf_counter() - start
    cad = [line.split(":", 1)[1] for line in done.stderr.splitlines() if line.startswith("CAD-MODULES:")]
    prepare = [line.split(":")[1:] for line in done.stderr.splitlines() if line.startswith("PREPARE:")]
    return {"args": " ".join(args), "seconds": wall, "cpu_s": _children_cpu_s() - cpu, "exit": done.returncode,
            "cad_modules": [m for m in (cad[-1].split(",") if cad else []) if m],
            "prepare_s": float(prepare[-1][0]) if prepare else None,
            "prepare_imports": [m for m in prepare[-1][1].split(",") if m] if prepare else []}


def fitted_exponent(items: list[float], seconds: list[float]) -> tuple[float, float]:
    """(slope of log cost over log items by least squares, slope of the last step)."""
    x, y = np.log(np.asarray(items, float)), np.log(np.asarray(seconds, float))
    return float(np.polyfit(x, y, 1)[0]), float((y[-1] - y[-2]) / (x[-1] - x[-2]))


def _commit(root: Path) -> str:
    return subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                          cwd=root).stdout.strip()


def _machine() -> dict:
    cpu = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                if line.startswith("model name")), platform.processor())
    mem_kb = next(int(line.split()[1]) for line in Path("/proc/meminfo").read_text().splitlines()
                  if line.startswith("MemTotal"))
    commit = _commit(ROOT)
    dirty = subprocess.run(["git", "status", "--porcelain", "--", "antenna_cad"], capture_output=True,
                           text=True, cwd=ROOT).stdout.strip()
    return {"cpu": cpu, "cores": os.cpu_count(), "memory_gb": round(mem_kb / 2**20, 1),
            "python": platform.python_version(), "platform": platform.platform(),
            "date": dt.datetime.now(dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "commit": commit + ("-dirty" if dirty else ""), "load_average_start": os.getloadavg()[0],
            "fullwave": _fullwave_state()}


def _fullwave_state() -> str:
    """Whether the builds' full-wave stage could run (Meep found by the interpreter the builds use)."""
    from antenna_cad.fullwave.solver import meep_python
    return "on (Meep found; each recipe's verification.full_wave and budget_s decide)" if meep_python() else \
        "off (Meep hidden or not installed: the fast model only)"


def _budget_rows(results: dict) -> list[dict]:
    rows = []
    for name, r in results["recipes"].items():
        budgeted = _budgeted(r["stages"])
        total = sum(budgeted.values())
        slowest = max(budgeted, key=budgeted.get)
        reason = f": {r['slowest_why']}" if r.get("slowest_why") else ""
        rows.append({"what": f"{name}: after imports", "value": total, "limit": RECIPE_BUDGET_S.get(name, BUDGET["recipe_s"]),
                     "unit": "s",
                     "why": f"slowest stage {slowest} {budgeted[slowest]:.2f} s{reason}"})
        peak = max(r["peak_mb"], r.get("child_peak_mb", 0.0))
        rows.append({"what": f"{name}: peak RSS (largest process)", "value": peak, "limit": BUDGET["peak_mb"],
                     "unit": "MB", "why": f"main {r['peak_mb']:.0f} MB, of it {r.get('import_mb', float('nan')):.0f} MB "
                                          f"right after imports; largest child {r.get('child_peak_mb', 0.0):.0f} MB"})
    for c in results["cli"]:
        work = ("" if c.get("prepare_s") is None else
                f"; the rules' work (synthesis, fabrication plan) {c['prepare_s']:.2f} s, importing "
                f"{', '.join(c['prepare_imports']) or 'nothing new'}; the rest start-up (Python, CLI, spec models, numpy)")
        rows.append({"what": f"make-lens {c['args']}", "value": c["seconds"], "limit": BUDGET["cli_s"], "unit": "s",
                     "why": f"CAD modules imported: {', '.join(c['cad_modules']) or 'none'}{work}"})
        if c["cad_modules"]:
            rows.append({"what": f"make-lens {c['args']}: CAD imports", "value": len(c["cad_modules"]),
                         "limit": 0, "unit": "modules", "why": ", ".join(c["cad_modules"])})
    if "naive" in results:
        lids = results["naive"]["rows"][0]
        rows.append({"what": "speed-up over per-slot booleans", "value": lids["speedup"],
                     "limit": BUDGET["naive_speedup"], "unit": "×", "why": lids["what"], "at_least": True})
        if lids.get("naive_exponent", 1.0) > EXPONENT_LIMIT:
            rows.append({"what": "naive baseline linear (extrapolation valid)", "value": lids["naive_exponent"],
                         "limit": EXPONENT_LIMIT, "unit": "", "why": "naive cost not linear in the slots"})
    if "large" in results:
        stages = results["large"]["stages"]
        slowest = max(stages, key=stages.get)
        rows.append({"what": "Luneburg D/λ 100, 20 layers, 10 mm sheets", "value": sum(stages.values()),
                     "limit": BUDGET["large_luneburg_s"], "unit": "s",
                     "why": f"slowest stage {slowest} {stages[slowest]:.1f} s; {results['large']['items']['pieces']} "
                            f"pieces; cpu {results['large'].get('cpu_s', float('nan')):.1f} s; peak "
                            f"{results['large']['peak_mb']:.0f} MB"})
    for row in rows:
        row["ok"] = row["value"] >= row["limit"] if row.get("at_least") else row["value"] <= row["limit"]
    return rows


def _markdown(results: dict) -> str:
    m = results["machine"]
    stages = sorted({s for r in results["recipes"].values() for s in r["stages"]},
                    key=lambda s: (s != "load", list(STAGE_ORDER).index(s) if s in STAGE_ORDER else 99, s))
    lines = ["# Benchmark results", "",
             f"Machine: {m['cpu']}, {m['cores']} cores, {m['memory_gb']} GB, Python {m['python']}; "
             f"{m['date']}; commit {m['commit']}; load average at start {m['load_average_start']:.2f}.",
             f"Full-wave stage: {m.get('fullwave', 'not recorded')}; with it on and off side by side: the last section "
             "(benchmarks/fullwave_budget.py).",
             f"Command: `PYTHONPATH=. python benchmarks/run.py {' '.join(results['argv'])}`. "
             "Seconds after imports, median of the runs in one process; import and peak RSS per fresh interpreter.",
             "`step`, `templates`: the waits for the STEP file and the templates, written by child processes "
             "beside STL, cut list and report; `cpu`: CPU seconds of the build (process and children); "
             "`child MB`: the largest child's peak RSS.",
             "", "| recipe | " + " | ".join(stages) + " | total | cpu | import | peak MB | child MB | slowest |",
             "|---|" + "---:|" * (len(stages) + 5) + "---|"]
    for name, r in results["recipes"].items():
        st = r["stages"]
        slowest = max(st, key=st.get)
        lines.append(f"| {name} | " + " | ".join(f"{st.get(s, 0):.2f}" for s in stages)
                     + f" | {sum(st.values()):.2f} | {r.get('cpu_s', float('nan')):.2f} | {r['import_s']:.2f} "
                     f"| {r['peak_mb']:.0f} | {r.get('child_peak_mb', 0):.0f} | {slowest} |")
    lines += ["", "| command | seconds | cpu | exit | CAD modules imported |", "|---|---:|---:|---:|---|"]
    lines += [f"| make-lens {c['args']} | {c['seconds']:.2f} | {c.get('cpu_s', float('nan')):.2f} | {c['exit']} "
              f"| {', '.join(c['cad_modules']) or 'none'} |" for c in results["cli"]]
    for name, s in results.get("series", {}).items():
        lines += ["", f"Scaling series `{name}` (cost per {s['item'][:-1]}); fitted exponent {s['exponent']:.2f}, "
                  f"last step {s['last_exponent']:.2f} (limit {EXPONENT_LIMIT})", "",
                  f"| value | {s['item']} | seconds | ms per item |", "|---|---:|---:|---:|"]
        lines += [f"| {r['value']} | {r['items']} | {r['seconds']:.2f} | {1e3 * r['seconds'] / r['items']:.2f} |"
                  for r in s["rows"]]
    if "naive" in results:
        lines += ["", "Naive baseline, same run (benchmarks/naive.py)", "",
                  "| what | items | naive s | ours s | speed-up |", "|---|---:|---:|---:|---:|"]
        lines += [f"| {r['what']} | {r['items']} | {r['naive_s']:.2f} | {r['ours_s']:.3f} | {r['speedup']:.0f}× |"
                  for r in results["naive"]["rows"]]
    if "before" in results:
        lines += _side_by_side(results)
    lines += ["", "Budgets", "", "| budget | value | limit | ok | note |", "|---|---:|---:|---|---|"]
    lines += [f"| {b['what']} | {b['value']:.2f} {b['unit']} | {b['limit']:g} {b['unit']} | "
              f"{'yes' if b['ok'] else '**no**'} | {b['why']} |" for b in results["budgets"]]
    return "\n".join(lines) + "\n"


def _side_by_side(results: dict) -> list[str]:
    """The before/after tables of a ``--before`` run (each pair measured back to back) or of a
    ``--compare`` run (the older JSON's figures as they were measured then)."""
    old = results["before"]
    how = (f"the before figures from {old['from']}" if "from" in old
           else "each recipe run in both trees back to back")
    lines = ["", f"Before (commit {old['commit']}) and after (commit {results['machine']['commit']}), {how} "
             "(load average at the start of each run; MB: the largest process, build or forked writer)", "",
             "| recipe | load | before s | after s | before / after | CPU s before | CPU s after | before MB | "
             "after MB | slowest stage before | slowest stage after |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|"]
    for name, r in results["recipes"].items():
        if name not in old["recipes"]:
            continue
        b = old["recipes"][name]
        tb, ta = sum(_budgeted(b["stages"]).values()), sum(_budgeted(r["stages"]).values())
        sb, sa = (max(_budgeted(x["stages"]), key=x["stages"].get) for x in (b, r))
        mb, ma = (max(x["peak_mb"], x.get("child_peak_mb", 0.0)) for x in (b, r))
        lines.append(f"| {name} | {b.get('load', 0):.1f}/{r.get('load', 0):.1f} | {tb:.2f} | {ta:.2f} | "
                     f"{tb / ta:.2f}× | {b.get('cpu_s', 0):.1f} | {r.get('cpu_s', 0):.1f} | {mb:.0f} | {ma:.0f} | "
                     f"{sb} {b['stages'][sb]:.2f} s | {sa} {r['stages'][sa]:.2f} s |")
    earlier = {c["args"]: c for c in old["cli"]}
    lines += ["", "| command | before s | after s | CPU s before | CPU s after | CAD modules before | CAD modules after |",
              "|---|---:|---:|---:|---:|---|---|"]
    lines += [f"| make-lens {a['args']} | {b['seconds']:.2f} | {a['seconds']:.2f} | {b.get('cpu_s', float('nan')):.2f} | "
              f"{a.get('cpu_s', float('nan')):.2f} | {', '.join(b['cad_modules']) or 'none'} | "
              f"{', '.join(a['cad_modules']) or 'none'} |"
              for a in results["cli"] for b in [earlier.get(a["args"])] if b is not None]
    return lines


STAGE_ORDER = ("load", "synthesize", "model", "fabricate", "verify", "step", "stl", "templates", "report",
               "manifest")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--child", nargs="+", help=argparse.SUPPRESS)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--recipe", action="append", default=[], help="recipe file name (default: every recipe)")
    parser.add_argument("--series", action="store_true", help="scaling series with fitted exponents")
    parser.add_argument("--naive", action="store_true", help="naive baseline beside ours")
    parser.add_argument("--naive-guides", type=int, default=0,
                        help="per-slot booleans on the first N guides only (default: all 40; ~15 s a guide)")
    parser.add_argument("--large", action="store_true", help="the D/λ = 100 Luneburg layup with templates")
    parser.add_argument("--compare", type=Path, help="an older results.json: its figures as the before column of "
                        "the before/after table")
    parser.add_argument("--before", type=Path, help="an older checkout (git worktree) run side by side: each "
                        "recipe and command there, then here, so both see the same load")
    parser.add_argument("--no-fail", action="store_true", help="report missed budgets without exit 1")
    args = parser.parse_args()
    if args.child:
        kind, *rest = args.child
        value = {"recipe": lambda: child_recipe(rest[0], int(rest[1])), "series": lambda: child_series(rest[0]),
                 "naive": lambda: child_naive(int(rest[0])), "large": child_large}[kind]()
        print(json.dumps(value))
        return 0

    recipes = args.recipe or sorted(p.name for p in (ROOT / "recipes").glob("*.yaml"))
    results: dict = {"machine": _machine(), "argv": sys.argv[1:], "recipes": {}, "cli": []}
    before = args.before.resolve() if args.before else None
    if before:
        results["before"] = {"commit": _commit(before), "recipes": {}, "cli": []}
    elif args.compare:          # an earlier run's JSON: its own date and load, not measured back to back
        old = json.loads(args.compare.read_text(encoding="utf-8"))
        results["before"] = {"commit": old["machine"]["commit"], "recipes": old["recipes"], "cli": old["cli"],
                             "from": f"{args.compare.name} ({old['machine']['date']}, load "
                                     f"{old['machine']['load_average_start']:.2f})"}
    for name in recipes:
        print(f"recipe {name} …", file=sys.stderr, flush=True)
        if before and (before / "recipes" / name).is_file():
            load = os.getloadavg()[0]
            results["before"]["recipes"][Path(name).stem] = _run_child(
                "recipe", str(before / "recipes" / name), str(args.runs), root=before) | {"load": load}
        load = os.getloadavg()[0]
        results["recipes"][Path(name).stem] = _run_child("recipe", str(ROOT / "recipes" / name),
                                                         str(args.runs)) | {"load": load}
    probes = [["--help"]] + [["validate", "--fast", f"recipes/{r}"] for r in dict.fromkeys([*recipes, DEFAULT_RECIPE])]
    for probe in probes:
        if before:
            results["before"]["cli"].append(_cli_timing(probe, before))
        results["cli"].append(_cli_timing(probe))
    failures = []
    if args.series:
        results["series"] = {}
        for name in (*SERIES, "shells_x_sheets"):
            print(f"series {name} …", file=sys.stderr, flush=True)
            s = _run_child("series", name)
            s["exponent"], s["last_exponent"] = fitted_exponent([r["items"] for r in s["rows"]],
                                                                [r["seconds"] for r in s["rows"]])
            results["series"][name] = s
            if s["exponent"] > EXPONENT_LIMIT:
                failures.append(f"SCALING: {name} grows with exponent {s['exponent']:.2f} > {EXPONENT_LIMIT}")
    if args.naive:
        print("naive baseline …", file=sys.stderr, flush=True)
        results["naive"] = _run_child("naive", str(args.naive_guides))
    if args.large:
        print("large Luneburg layup …", file=sys.stderr, flush=True)
        results["large"] = _run_child("large")
    results["machine"]["load_average_end"] = os.getloadavg()[0]
    results["budgets"] = _budget_rows(results)
    failures += [f"BUDGET: {b['what']} {b['value']:.2f} {b['unit']} vs {b['limit']:g} ({b['why']})"
                 for b in results["budgets"] if not b["ok"]]
    (ROOT / "benchmarks" / "results.json").write_text(json.dumps(results, indent=1) + "\n", encoding="utf-8")
    (ROOT / "benchmarks" / "results.md").write_text(_markdown(results), encoding="utf-8")
    import fullwave_budget                  # the full-wave on/off table, measured by its own script: kept
    fullwave_budget.keep_section()
    print(_markdown(results))
    for line in failures:
        print(line, file=sys.stderr)
    return 1 if failures and not args.no_fail else 0


if __name__ == "__main__":
    sys.exit(main())
