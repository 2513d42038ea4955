"""``make-lens kerf``: the hot-wire kerf calibration (thin Typer front end over
:mod:`antenna_cad.cam.coupon`).

    make-lens kerf coupon [-o FILE] [--grade xps] [--feeds 150,300,600] [--machine hotwire-4axis]
    make-lens kerf table GRADE FEED=WIDTH ...    the spec's kerf_table line from the measured squares
"""

from __future__ import annotations

import sys
from pathlib import Path

import typer

kerf_app = typer.Typer(add_completion=False, no_args_is_help=True, rich_markup_mode=None,
                       help="Hot-wire kerf calibration: cut a coupon, measure it, get the kerf table.")


def _exit(message: str) -> None:
    print(message, file=sys.stderr)
    raise typer.Exit(2)


@kerf_app.command()
def coupon(out: Path | None = typer.Option(None, "-o", "--out", help="write to FILE instead of stdout"),
           grade: str = typer.Option("xps", help="foam grade (the kerf table's key)"),
           feeds: str = typer.Option("150,300,600", help="three feeds, mm/min"),
           machine: str = typer.Option("hotwire-4axis", help="a built-in hot-wire profile")) -> None:
    """G-code cutting three squares at three feeds."""
    from antenna_cad.cam.coupon import coupon_program
    from antenna_cad.cam.machines import BUILT_IN
    try:
        values = tuple(float(f) for f in feeds.split(","))
    except ValueError:
        values = ()
    if len(values) != 3 or min(values) <= 0:
        _exit(f"--feeds: three positive feeds in mm/min, comma-separated (got {feeds!r})")
    if BUILT_IN.get(machine) is None or BUILT_IN[machine].kind != "hotwire":
        _exit(f"--machine: one of {', '.join(k for k, m in BUILT_IN.items() if m.kind == 'hotwire')} (got {machine!r})")
    text = coupon_program(BUILT_IN[machine], grade, values).text
    if out is None:
        sys.stdout.write(text)
    else:
        out.write_text(text, encoding="utf-8")


@kerf_app.command()
def table(grade: str = typer.Argument(..., help="foam grade"),
          measured: list[str] = typer.Argument(..., metavar="FEED=WIDTH", help="feed mm/min = measured square width mm")) -> None:
    """Print the ``kerf_table`` line for the spec's ``fabrication.cam`` block."""
    from antenna_cad.cam.coupon import kerf_rows
    try:
        pairs = {float(f): float(w) for f, w in (m.split("=") for m in measured)}
        rows = kerf_rows(pairs)
    except ValueError as exc:
        _exit(f"FEED=WIDTH: {exc}" if "coupon" in str(exc) else f"FEED=WIDTH: numbers like 300=39.2 (got {' '.join(measured)})")
    print(f"kerf_table: {{{grade}: {rows}}}".replace("'", ""))
