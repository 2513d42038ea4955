"""``make-lens``: thin Typer front end over ``pipeline.build`` (no logic here).

    make-lens SPEC [-o OUT]      build everything into OUT/<name>/ (default exports/)
    make-lens validate SPEC      check the spec and its physics, write nothing
    make-lens schema [-o FILE]   write the JSON Schema of specs
    make-lens sweep SWEEP [-o OUT] [--scheduler tcp://HOST:PORT] [--workers N]
                                 run a design sweep on dask into OUT/<sweep name>/
    make-lens --version
"""

from __future__ import annotations

import sys
from pathlib import Path

import typer
from rich.console import Console
from rich.table import Table

from antenna_cad import __version__

app = typer.Typer(add_completion=False, no_args_is_help=True,
                  help="Physics spec of a microwave antenna → STEP/STL, 1:1 templates, cut list.")
out_console = Console()
err_console = Console(stderr=True, soft_wrap=True)
COMMANDS = {"build", "validate", "schema", "sweep"}
STATUS_STYLE = {"pass": "green", "warn": "yellow", "fail": "red"}


def _version(value: bool) -> None:
    if value:
        out_console.print(f"make-lens (antenna_cad) {__version__}")
        raise typer.Exit()


@app.callback()
def _root(version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                       help="Show the version and exit.")) -> None:
    """make-lens SPEC builds a spec; see the commands below."""


def _load(spec_path: Path):
    """Spec + synthesis, or a clean exit 2 naming the field and the rule."""
    from antenna_cad.registry import synthesize
    from antenna_cad.spec import SpecError, load_spec
    from antenna_cad.synthesis.checks import DesignError
    try:
        spec = load_spec(spec_path)
        _, checks = synthesize(spec)
    except SpecError as exc:
        for line in exc.lines:
            err_console.print(line, markup=False, highlight=False)
        raise typer.Exit(2)
    except DesignError as exc:
        err_console.print(f"{spec_path}: {exc}", markup=False, highlight=False)
        raise typer.Exit(2)
    return spec, checks


def _checks_table(checks) -> Table:
    table = Table(title="checks", show_lines=False)
    for col in ("check", "status", "value", "limit"):
        table.add_column(col)
    for c in checks:
        table.add_row(c.name, f"[{STATUS_STYLE[c.status]}]{c.status}[/]", f"{c.value:.4g} {c.unit}",
                      f"{c.limit:.4g} {c.unit}")
    return table


@app.command()
def validate(spec_path: Path = typer.Argument(..., metavar="SPEC", help="spec YAML")) -> None:
    """Validate a spec and run its synthesis checks; writes nothing."""
    spec, checks = _load(spec_path)
    out_console.print(_checks_table(checks))
    out_console.print(f"{spec_path}: valid {spec.kind} spec '{spec.name}'")


@app.command()
def build(spec_path: Path = typer.Argument(..., metavar="SPEC", help="spec YAML"),
          out: Path = typer.Option(Path("exports"), "-o", "--out", help="output root folder")) -> None:
    """Build STEP/STL, templates, cut list, report.html and manifest into OUT/<name>/."""
    from rich.progress import Progress

    from antenna_cad.pipeline import build as run_build
    from antenna_cad.synthesis.checks import DesignError
    spec, _ = _load(spec_path)
    try:
        with Progress(console=err_console, transient=True) as bar:
            task = bar.add_task(f"building {spec.name}", total=1.0)
            result = run_build(spec, out, lambda stage, f: bar.update(task, completed=f,
                                                                      description=f"{spec.name}: {stage}"))
    except DesignError as exc:
        err_console.print(f"{spec_path}: {exc}", markup=False, highlight=False)
        raise typer.Exit(2)
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


@app.command()
def schema(out: Path = typer.Option(Path("schemas/lens-spec.schema.json"), "-o", "--out")) -> None:
    """Write the JSON Schema of lens specs."""
    from antenna_cad.spec import json_schema_text
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json_schema_text(), encoding="utf-8")
    out_console.print(f"wrote {out}")


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


def main() -> None:
    """Console entry: ``make-lens SPEC`` means ``make-lens build SPEC``."""
    args = sys.argv[1:]
    if args and not args[0].startswith("-") and args[0] not in COMMANDS:
        sys.argv.insert(1, "build")
    app()
