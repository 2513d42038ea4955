"""``make-lens``: thin Typer front end over :mod:`antenna_cad.api` (no logic here).

    make-lens SPEC [-o OUT] [-q|-v]  build everything into OUT/<name>/ (default exports/)
    make-lens build SPEC [-o OUT] [--scheduler tcp://HOST:PORT]
                                     the same; options may come before or after SPEC; the
                                     full-wave runs on the dask scheduler's workers
    make-lens validate SPEC          every rule a build applies (the solid model in memory); writes nothing
    make-lens validate --fast SPEC   the rules before CAD only, in about a second
    make-lens schema [-o FILE]       the JSON Schema of specs (stdout unless -o)
    make-lens check OUT              re-read every file of a build folder with independent readers
    make-lens sweep SWEEP [-o OUT] [--scheduler tcp://HOST:PORT|tls://HOST:PORT] [--workers N] [-q|-v]
                                     run a design sweep on dask into OUT/<sweep name>/
    make-lens kerf coupon|table      hot-wire kerf calibration (antenna_cad.kerf_cli)
    make-lens recipes                list the bundled recipes (one line each)
    make-lens new KIND|RECIPE [NAME] write NAME.yaml: a commented starting spec
    make-lens --version
"""

from __future__ import annotations

import os
import sys
import time
import warnings
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager
from pathlib import Path

import typer
from rich.table import Table

from antenna_cad import __version__
from antenna_cad.console import (NORMAL, QUIET, STATUS_STYLE, VERBOSE, BuildProgress, SweepProgress, checks_table,
                                 seconds_table, stderr_console, stdout_console, summary_table)
from antenna_cad.interrupt import graceful, hold_if_stopping
from antenna_cad.kerf_cli import kerf_app

EXIT_CODES = ("Exit codes: 0 built/valid (checks pass or warn); 1 built, but a check failed; "
              "2 bad spec, design or output folder (one line per problem: file: field: rule) — nothing written; "
              "130 interrupted (Ctrl-C; the previous build is kept; after the swap: 0, the new build is in place).")
app = typer.Typer(add_completion=False, no_args_is_help=True, rich_markup_mode=None,
                  help="Physics spec of a microwave antenna → STEP/STL, 1:1 templates, cut list.\n\n" + EXIT_CODES)
err_console = stderr_console()
COMMANDS = {"build", "validate", "schema", "check", "sweep", "kerf", "recipes", "new"}
VALUE_OPTIONS = {"-o", "--out", "--scheduler", "--workers"}
QUIET_OPTION = typer.Option(False, "-q", "--quiet", help="no progress, no tables: only the last line and errors")
VERBOSE_OPTION = typer.Option(False, "-v", "--verbose", help="every progress report as a line, and stage times")


def _mode(quiet: bool, verbose: bool) -> str:
    if quiet and verbose:
        _fail(["--quiet and --verbose: choose one"])
    return QUIET if quiet else (VERBOSE if verbose else NORMAL)


app.add_typer(kerf_app, name="kerf")        # hot-wire kerf calibration (antenna_cad.kerf_cli)


def _version(value: bool) -> None:
    if value:
        stdout_console().print(f"make-lens (antenna_cad) {__version__}")
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


def _load(spec_path: Path, out: Path | None = None, solids: bool = False):
    """Spec, output folder check (when building), then everything before writing (api.validate);
    or a clean exit 2 naming the field and the rule."""
    from antenna_cad import api
    try:
        checked = api.validate(spec_path, out, solids)
        return checked.spec, checked
    except api.SpecError as exc:
        _fail(exc.lines)
    except api.DesignError as exc:
        _fail([f"{spec_path}: {exc}"])
    except api.OutputError as exc:
        _fail([str(exc)])


@app.command(epilog=EXIT_CODES)
def validate(spec_path: Path = typer.Argument(..., metavar="SPEC", help="spec YAML (or a bundled recipe's name)"),
             fast: bool = typer.Option(False, "--fast", help="the rules before CAD only (about a second, no CAD "
                                       "library loaded): not the solid model and its STL triangle limits")) -> None:
    """Check the spec and run every rule a build applies (synthesis, layup, limits, fabrication
    plan, the solid model and the STL triangles it needs); writes nothing."""
    # numpy is not imported yet: its BLAS in one thread (a thread pool costs more than it saves on
    # validate's small problems — 100× on a busy 2-core machine for one 400×400 eigvalsh)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    spec, plan = _load(spec_path, solids=not fast)
    stdout_console().print(checks_table(plan.checks))
    failed = [c.name for c in plan.checks if c.status == "fail"]
    if failed:                      # as build: exit 1 when a check fails
        stdout_console().print(f"{spec_path}: {spec.kind} spec '{spec.name}' fails its checks: {', '.join(failed)}")
        raise typer.Exit(1)
    stdout_console().print(f"{spec_path}: valid {spec.kind} spec '{spec.name}'")


@app.command(epilog=EXIT_CODES)
def build(spec_path: Path = typer.Argument(..., metavar="SPEC", help="spec YAML (or a bundled recipe's name)"),
          out: Path = typer.Option(Path("exports"), "-o", "--out", help="output root folder"),
          scheduler: str = typer.Option(None, "--scheduler", help="running dask scheduler (tcp://HOST:PORT or "
                                        "tls://HOST:PORT) whose workers run the full-wave runs"),
          quiet: bool = QUIET_OPTION, verbose: bool = VERBOSE_OPTION) -> None:
    """Build STEP/STL, templates, cut list, report and manifest into OUT/<name>/. Progress on stderr:
    a bar on a terminal, else a line per stage start and end and a heartbeat every 10 s."""
    from antenna_cad.api import DesignError, OutputError, build as run_build
    mode, started = _mode(quiet, verbose), time.monotonic()
    spec, checked = _load(spec_path, out)          # a bad spec: its one line, before any progress line
    with _full_wave_cluster(scheduler), BuildProgress(spec.name, mode, started=started) as progress:
        try:
            result = run_build(checked, out, progress)
        except DesignError as exc:
            _fail([f"{spec_path}: {exc}"])
        except OutputError as exc:
            _fail([str(exc)])
    console = stdout_console()
    if mode != QUIET:
        console.print(summary_table(result))
        console.print(checks_table(result.checks))
    if mode == VERBOSE:
        console.print(seconds_table(result.seconds))
    console.print(f"{len(result.files)} files in {result.out_dir} "
                  f"({sum(result.seconds.values()):.1f} s after imports) — overall: "
                  f"[{STATUS_STYLE[result.status]}]{result.status}[/]")
    if result.status == "fail":
        raise typer.Exit(1)


@contextmanager
def _full_wave_cluster(scheduler: str | None) -> Iterator[None]:
    """With ``--scheduler``: the build's full-wave runs go to its workers (an unusable address: one line,
    exit 2; tls:// needs the certificates a sweep file names, so only tcp:// here)."""
    if not scheduler:
        yield
        return
    from antenna_cad.fullwave.solver import on_cluster
    from antenna_cad.sweep import SweepError
    from antenna_cad.sweep.execute import check_address, connect
    with ExitStack() as stack:
        try:
            if check_address(scheduler) == "tls":
                raise SweepError(f"--scheduler: {scheduler}: a build connects by tcp:// only (tls:// with make-lens "
                                 "sweep, whose file names the certificates)")
            client = stack.enter_context(connect(scheduler))
        except SweepError as exc:
            _fail([str(exc)])
        with on_cluster(client):
            yield


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
    err_console.print(f"wrote {out}", markup=False, highlight=False)


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
    console = stdout_console()
    console.print(table)
    failed = [f for f in findings if not f.ok]
    console.print(f"{len(findings) - len(failed)} of {len(findings)} checks passed"
                      + (": failed " + "; ".join(f"{f.file} {f.check}" for f in failed[:10]) if failed else ""))
    if failed:
        raise typer.Exit(1)


@app.command()
def sweep(sweep_path: Path = typer.Argument(..., metavar="SWEEP", help="sweep YAML"),
          out: Path = typer.Option(Path("exports"), "-o", "--out", help="output root folder"),
          scheduler: str = typer.Option(None, "--scheduler",
                                        help="running dask scheduler, tcp://HOST:PORT or tls://HOST:PORT"),
          workers: int = typer.Option(None, "--workers", min=1, help="local worker processes (default: one per core)"),
          quiet: bool = QUIET_OPTION, verbose: bool = VERBOSE_OPTION) -> None:
    """Run a design sweep (axes over spec fields) on dask: table, Pareto front, index.html in OUT/<name>/.
    An interrupted sweep keeps its rows and resumes where it stopped on the next run."""
    from antenna_cad.spec import SpecError
    from antenna_cad.sweep import SweepError, SweepInterrupted, run_sweep
    mode = _mode(quiet, verbose)
    if scheduler and workers:
        _fail(["--workers: only for a local cluster (not with --scheduler)"])
    try:
        with SweepProgress(sweep_path.name, mode) as progress, graceful():
            result = run_sweep(sweep_path, out, scheduler, workers, progress)
    except SpecError as exc:
        _fail(exc.lines)
    except SweepError as exc:
        _fail([str(exc)])
    except SweepInterrupted as stop:
        err_console.print(f"interrupted: {stop.rows} rows done are in {stop.path} (index.html and pareto.csv "
                          "for them beside it); run the same command again to resume", markup=False, highlight=False)
        raise typer.Exit(130)
    counts = {s: sum(r["status"] == s for r in result.rows) for s in ("ok", "invalid", "failed")}
    shown = ["variant", *result.axes, *result.objectives]
    front = Table(title=f"Pareto front ({len(result.front)} of {counts['ok']} ok variants)")
    for col in shown:
        front.add_column(col.rsplit(".", 1)[-1])
    for row in result.front:
        front.add_row(*(f"{row[c]:.4g}" if isinstance(row[c], float) else str(row[c]) for c in shown))
    console = stdout_console()
    if mode != QUIET:
        console.print(front)
    console.print(f"{len(result.rows)} variants ({result.unique} computed, {counts['ok']} ok, {counts['invalid']} "
                  f"invalid, {counts['failed']} failed) in {result.seconds:.1f} s → {result.out_dir}/index.html"
                  + (f" ({result.resumed} rows kept from the interrupted run)" if result.resumed else ""))


@app.command("recipes")
def list_recipes() -> None:
    """List the recipes shipped with the package, one line each (build one: make-lens NAME)."""
    from antenna_cad.catalog import recipes, sweeps
    for r in recipes():
        stdout_console().print(f"{r.name:37} {r.kind:12} {r.summary}", markup=False, highlight=False, soft_wrap=True)
    stdout_console().print(f"sweeps: {', '.join(sweeps())} (run one: make-lens sweep FILE)", markup=False, soft_wrap=True)


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
