"""``make-lens``: thin Typer front end over :mod:`antenna_cad.api` (no logic here).

    make-lens SPEC [-o OUT]          build everything into OUT/<name>/ (default exports/)
    make-lens build SPEC [-o OUT]    the same; options may come before or after SPEC
    make-lens validate SPEC          every rule a build applies, before any CAD work; writes nothing
    make-lens schema [-o FILE]       the JSON Schema of specs (stdout unless -o)
    make-lens check OUT              re-read every file of a build folder with independent readers
    make-lens sweep SWEEP [-o OUT] [--scheduler tcp://HOST:PORT] [--workers N]
                                     run a design sweep on dask into OUT/<sweep name>/
    make-lens recipes                list the bundled recipes (one line each)
    make-lens new KIND|RECIPE [NAME] write NAME.yaml: a commented starting spec
    make-lens --version
"""

from __future__ import annotations

import os
import sys
import warnings
from pathlib import Path

import typer
from rich.console import Console
from rich.table import Table

from antenna_cad import __version__
from antenna_cad.interrupt import hold_if_stopping

EXIT_CODES = ("Exit codes: 0 built/valid (checks pass or warn); 1 built, but a check failed; "
              "2 bad spec, design or output folder (one line per problem: file: field: rule) — nothing written; "
              "130 interrupted (Ctrl-C; the previous build is kept).")
app = typer.Typer(add_completion=False, no_args_is_help=True, rich_markup_mode=None,
                  help="Physics spec of a microwave antenna → STEP/STL, 1:1 templates, cut list.\n\n" + EXIT_CODES)
out_console = Console()
err_console = Console(stderr=True, soft_wrap=True)
COMMANDS = {"build", "validate", "schema", "check", "sweep", "recipes", "new"}
VALUE_OPTIONS = {"-o", "--out", "--scheduler", "--workers"}
STATUS_STYLE = {"pass": "green", "warn": "yellow", "fail": "red"}


def _version(value: bool) -> None:
    if value:
        out_console.print(f"make-lens (antenna_cad) {__version__}")
        raise typer.Exit()


@app.callback()
def _root(version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                       help="Show the version and exit.")) -> None:
    """make-lens SPEC builds a spec; see the commands below."""


def _fail(lines: list[str]) -> None:
    hold_if_stopping()          # an error caused by Ctrl-C removing the build's temporary folder
    for line in lines:
        err_console.print(line, markup=False, highlight=False)
    raise typer.Exit(2)


def _load(spec_path: Path, out: Path | None = None):
    """Spec, output folder check (when building), then everything before CAD (api.validate);
    or a clean exit 2 naming the field and the rule."""
    from antenna_cad import api
    try:
        checked = api.validate(spec_path, out)
        return checked.spec, checked
    except api.SpecError as exc:
        _fail(exc.lines)
    except api.DesignError as exc:
        _fail([f"{spec_path}: {exc}"])
    except api.OutputError as exc:
        _fail([str(exc)])


def _checks_table(checks) -> Table:
    table = Table(title="checks", show_lines=False)
    for col in ("check", "status", "value", "limit", "message"):
        table.add_column(col, overflow="fold")
    for c in checks:
        table.add_row(c.name, f"[{STATUS_STYLE[c.status]}]{c.status}[/]", f"{c.value:.4g} {c.unit}",
                      f"{c.limit:.4g} {c.unit}", c.message)
    return table


@app.command(epilog=EXIT_CODES)
def validate(spec_path: Path = typer.Argument(..., metavar="SPEC", help="spec YAML (or a bundled recipe's name)")) -> None:
    """Check the spec and run every rule a build applies (synthesis, layup, limits, fabrication
    plan) before any CAD work; writes nothing."""
    # numpy is not imported yet: its BLAS in one thread (a thread pool costs more than it saves on
    # validate's small problems — 100× on a busy 2-core machine for one 400×400 eigvalsh)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    spec, plan = _load(spec_path)
    out_console.print(_checks_table(plan.checks))
    out_console.print(f"{spec_path}: valid {spec.kind} spec '{spec.name}'")


@app.command(epilog=EXIT_CODES)
def build(spec_path: Path = typer.Argument(..., metavar="SPEC", help="spec YAML (or a bundled recipe's name)"),
          out: Path = typer.Option(Path("exports"), "-o", "--out", help="output root folder")) -> None:
    """Build STEP/STL, templates, cut list, report and manifest into OUT/<name>/."""
    from rich.progress import Progress

    from antenna_cad.api import DesignError, OutputError, build as run_build
    spec, checked = _load(spec_path, out)
    try:
        with Progress(console=err_console, transient=True) as bar:
            task = bar.add_task(f"building {spec.name}", total=1.0)
            result = run_build(checked, out, lambda stage, f: bar.update(task, completed=f,
                                                                      description=f"{spec.name}: {stage}"))
    except DesignError as exc:
        _fail([f"{spec_path}: {exc}"])
    except OutputError as exc:
        _fail([str(exc)])
    out_console.print(_summary_table(result))
    out_console.print(_checks_table(result.checks))
    out_console.print(f"{len(result.files)} files in {result.out_dir} "
                      f"({sum(result.seconds.values()):.1f} s after imports) — overall: "
                      f"[{STATUS_STYLE[result.status]}]{result.status}[/]")
    if result.status == "fail":
        raise typer.Exit(1)


HEADLINE_SUFFIXES = ("_p2p_deg", "_rms_deg", "_gain_loss_db")   # as-built figures for the terminal


def _summary_table(result) -> Table:
    table = Table(title=f"{result.name} ({result.kind})")
    table.add_column("figure")
    table.add_column("value", justify="right")
    headline = [(f"as-built {k}", v) for k, v in result.verified.items() if k.endswith(HEADLINE_SUFFIXES)]
    for key, value in list(result.figures.items()) + headline:
        table.add_row(key, f"{value:.6g}" if isinstance(value, float) else str(value))
    for material, count in result.boards.items():
        table.add_row(f"boards {material}", str(count))
    for label, kg in result.masses_kg.items():
        table.add_row(f"mass {label} kg", f"{kg:.3f}")
    return table


@app.command(epilog=EXIT_CODES)
def schema(out: Path | None = typer.Option(None, "-o", "--out", help="write to FILE instead of stdout")) -> None:
    """Print the JSON Schema of lens specs (or write it to -o FILE)."""
    from antenna_cad.spec import json_schema_text
    text = json_schema_text()
    if out is None:
        sys.stdout.write(text)
        return
    try:
        out.write_text(text, encoding="utf-8")
    except OSError as exc:
        _fail([f"{out}: cannot write ({exc.strerror})"])
    err_console.print(f"wrote {out}")


def _with_command(args: list[str]) -> list[str]:
    """``make-lens [options] SPEC [options]`` means ``make-lens build …``."""
    i = 0
    while i < len(args):
        if args[i] in VALUE_OPTIONS:
            i += 2
        elif args[i].startswith("-"):
            i += 1
        else:
            return args if args[i] in COMMANDS else ["build", *args]
    return args


@app.command()
def check(folder: Path = typer.Argument(..., metavar="OUT", help="a build folder (holding manifest.json)")) -> None:
    """Re-read every file of a build with independent readers; exit 1 naming what failed."""
    from antenna_cad.export.check import CheckError, check_build
    try:
        findings = check_build(folder)
    except CheckError as exc:
        err_console.print(str(exc), markup=False, highlight=False)
        raise typer.Exit(2)
    table = Table(title=f"check {folder}")
    for col in ("check", "files", "status", "result (first failure, else last file)"):
        table.add_column(col)
    for name in dict.fromkeys(f.check for f in findings):
        group = [f for f in findings if f.check == name]
        bad = [f for f in group if not f.ok]
        shown = (bad or group)[-1] if not bad else bad[0]
        table.add_row(name, str(len(group)), f"[red]FAIL {len(bad)}[/]" if bad else "[green]pass[/]",
                      f"{shown.file}: {shown.message}")
    out_console.print(table)
    failed = [f for f in findings if not f.ok]
    out_console.print(f"{len(findings) - len(failed)} of {len(findings)} checks passed"
                      + (": failed " + "; ".join(f"{f.file} {f.check}" for f in failed[:10]) if failed else ""))
    if failed:
        raise typer.Exit(1)


@app.command()
def sweep(sweep_path: Path = typer.Argument(..., metavar="SWEEP", help="sweep YAML"),
          out: Path = typer.Option(Path("exports"), "-o", "--out", help="output root folder"),
          scheduler: str = typer.Option(None, "--scheduler", help="running dask scheduler, tcp://HOST:PORT"),
          workers: int = typer.Option(None, "--workers", min=1, help="local worker processes (default: one per core)")
          ) -> None:
    """Run a design sweep (axes over spec fields) on dask: table, Pareto front, index.html in OUT/<name>/."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeElapsedColumn

    from antenna_cad.spec import SpecError
    from antenna_cad.sweep import SchedulerUnreachable, SweepInterrupted, run_sweep
    if scheduler and workers:
        err_console.print("--workers: only for a local cluster (not with --scheduler)", markup=False)
        raise typer.Exit(2)
    try:
        with Progress("{task.description}", BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                      console=err_console, transient=True) as bar:
            task = bar.add_task(f"sweep {sweep_path.name}", total=None)
            result = run_sweep(sweep_path, out, scheduler, workers, lambda done, total: bar.update(
                task, completed=done, total=total))
    except SpecError as exc:
        for line in exc.lines:
            err_console.print(line, markup=False, highlight=False)
        raise typer.Exit(2)
    except SchedulerUnreachable as exc:
        err_console.print(str(exc), markup=False, highlight=False)
        raise typer.Exit(2)
    except SweepInterrupted as stop:
        err_console.print(f"interrupted: {stop.rows} rows done are in {stop.path}", markup=False)
        raise typer.Exit(130)
    counts = {s: sum(r["status"] == s for r in result.rows) for s in ("ok", "invalid", "failed")}
    shown = ["variant", *result.axes, *result.objectives]
    front = Table(title=f"Pareto front ({len(result.front)} of {counts['ok']} ok variants)")
    for col in shown:
        front.add_column(col.rsplit(".", 1)[-1])
    for row in result.front:
        front.add_row(*(f"{row[c]:.4g}" if isinstance(row[c], float) else str(row[c]) for c in shown))
    out_console.print(front)
    out_console.print(f"{len(result.rows)} variants ({result.unique} computed, {counts['ok']} ok, "
                      f"{counts['invalid']} invalid, {counts['failed']} failed) in {result.seconds:.1f} s → "
                      f"{result.out_dir}/index.html")


@app.command("recipes")
def list_recipes() -> None:
    """List the recipes shipped with the package, one line each (build one: make-lens NAME)."""
    from antenna_cad.catalog import recipes, sweeps
    for r in recipes():
        out_console.print(f"{r.name:37} {r.kind:12} {r.summary}", markup=False, highlight=False, soft_wrap=True)
    out_console.print(f"sweeps: {', '.join(sweeps())} (run one: make-lens sweep FILE)", markup=False, soft_wrap=True)


@app.command(epilog=EXIT_CODES)
def new(source: str = typer.Argument(..., metavar="KIND|RECIPE", help="a kind (collimator, luneburg, …) or a recipe"),
        name: str = typer.Argument(None, metavar="[NAME]", help="the new spec's name (default my-<kind> or the recipe's)"),
        out: Path = typer.Option(None, "-o", "--out", help="file to write (default NAME.yaml here)")) -> None:
    """Write a commented starting spec from a kind or a bundled recipe; never overwrites a file."""
    from antenna_cad.api import CatalogError, new_spec
    try:
        name, text = new_spec(source, name)
    except CatalogError as exc:
        _fail([str(exc)])
    target = out or Path(f"{name}.yaml")
    try:
        with open(target, "x", encoding="utf-8") as fh:
            fh.write(text)
    except FileExistsError:
        _fail([f"{target}: exists; choose another NAME or -o FILE"])
    except OSError as exc:
        _fail([f"{target}: cannot write ({exc.strerror})"])
    err_console.print(f"wrote {target} — next: make-lens validate {target}", markup=False, highlight=False)


def main() -> None:
    """Console entry: ``make-lens SPEC`` means ``make-lens build SPEC``; no numpy/Python warning is
    printed (library stages report through checks)."""
    warnings.simplefilter("ignore")
    sys.argv[1:] = _with_command(sys.argv[1:])
    app()
