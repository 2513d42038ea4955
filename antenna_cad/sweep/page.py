"""index.html of a sweep: one self-contained page (inline SVG plots, CSS in the head, no scripts,
no network) with the summary, the Pareto front and its scatter, every figure against every axis,
the variants that failed and the whole table."""

from __future__ import annotations

import html
import itertools
import math
from pathlib import Path

from antenna_cad import __version__
from antenna_cad.export.page_parts import page as html_page, table
from antenna_cad.export.plots import STYLE, figure_svg, plt       # plt on the Agg backend
from antenna_cad.sweep.model import SweepSpec
from antenna_cad.sweep.results import PAGE, atomic_write

MAX_SERIES = 10         # lines per figure-vs-axis plot; more combinations of the other axes: points only
MAX_TICK_CHARS = 18


def _number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _short(v) -> str:
    text = "—" if v is None else (f"{v:g}" if isinstance(v, float) else str(v))
    return text if len(text) <= MAX_TICK_CHARS else text[:MAX_TICK_CHARS - 1] + "…"


def _figure(svg: str, ident: str, caption: str) -> str:
    return f'<figure class="plot" id="{ident}">{svg}<figcaption>{html.escape(caption)}</figcaption></figure>'


def axis_plot(rows: list[dict], figure: str, axis: str, others: list[str]) -> str:
    """``figure`` against ``axis`` over the ok rows: one line per combination of the other axes (points
    alone when there are more than MAX_SERIES); text-valued axes at evenly spaced ticks."""
    ok = [r for r in rows if _number(r.get(figure))]
    values = list(dict.fromkeys(r.get(axis) for r in ok))
    numeric = all(_number(v) for v in values)
    position = (lambda v: v) if numeric else {v: i for i, v in enumerate(values)}.get
    groups: dict[tuple, list[dict]] = {}
    for r in ok:
        groups.setdefault(tuple(r.get(o) for o in others), []).append(r)
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(5.4, 3.4))
        lines = len(groups) <= MAX_SERIES
        for combo, members in sorted(groups.items(), key=lambda kv: str(kv[0])):
            members.sort(key=lambda r: position(r.get(axis)))
            label = ", ".join(f"{o.rsplit('.', 1)[-1]}={_short(v)}" for o, v in zip(others, combo)) or None
            ax.plot([position(r.get(axis)) for r in members], [r[figure] for r in members],
                    ".-" if lines else ".", markersize=4, linewidth=1.0, label=label if lines else None)
        if not numeric:
            ax.set_xticks(range(len(values)), [_short(v) for v in values], rotation=20, fontsize=7)
        ax.set_xlabel(axis)
        ax.set_ylabel(figure)
        if lines and others:
            ax.legend(fontsize=6, loc="best")
        return figure_svg(fig)


def pareto_plot(rows: list[dict], front: list[dict], x: str, y: str, joined: bool) -> str:
    """Every ok variant in grey, the front in colour; ``joined`` (two objectives: the front is a
    curve in this plane) links the front in the order of ``x``."""
    pool = [r for r in rows if _number(r.get(x)) and _number(r.get(y))]
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(5.4, 3.8))
        ax.plot([r[x] for r in pool], [r[y] for r in pool], ".", color="0.65", label="variants")
        ordered = sorted(front, key=lambda r: r[x])
        ax.plot([r[x] for r in ordered], [r[y] for r in ordered], "o-" if joined else "o", color="#d62728",
                markersize=4, linewidth=1.0, label="Pareto front")
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        ax.legend(fontsize=7, loc="best")
        return figure_svg(fig)


def write_page(out_dir: Path, sweep: SweepSpec, base_source: str, cols: list[str], rows: list[dict],
               front: list[dict], unique: int) -> None:
    ok = [r for r in rows if r["status"] == "ok"]
    bad = [r for r in rows if r["status"] != "ok"]
    axes = [g[0] for g in sweep.axis_groups()]
    counts = {s: sum(r["status"] == s for r in rows) for s in ("ok", "invalid", "failed")}
    summary = table(("item", "value"), [
        ("mode", sweep.mode), ("base spec", base_source),
        ("axes", " × ".join(f"{' + '.join(g)} ({len(sweep.axis_values(g[0]))})" for g in sweep.axis_groups())),
        ("variants", len(rows)), ("computed (distinct resolved specs)", unique),
        *counts.items(),
        ("objectives", ", ".join(f"{k}: {v}" for k, v in sweep.objectives.items()) or "none")])
    objectives = list(sweep.objectives)
    joined = len(objectives) == 2
    scatters = "".join(_figure(pareto_plot(ok, front, x, y, joined), f"pareto-{x}-{y}",
                               f"{y} against {x}" + ("" if joined else " (front over all objectives, projected)"))
                       for x, y in itertools.combinations(objectives, 2))
    pareto = (f'<div class="scroll">{table(cols, [[r.get(c) for c in cols] for r in front], "pareto-table")}</div>'
              + scatters
              if objectives else "<p>No objectives in the sweep file.</p>")
    plots = "".join(
        _figure(axis_plot(ok, f, a, [o for o in axes if o != a]), f"plot-{f}-{a}", f"{f} against {a}")
        for f in sweep.figures if any(_number(r.get(f)) for r in ok) for a in axes) or "<p>No completed variant.</p>"
    failures = (table(("variant", "status", "error"), [(r["variant"], r["status"], r["error"]) for r in bad])
                if bad else "<p>Every variant completed.</p>")
    everything = f'<div class="scroll">{table(cols, [[r.get(c) for c in cols] for r in rows], "results-table")}</div>'
    sections = [("summary", "Summary", summary), ("pareto", f"Pareto front ({len(front)})", pareto),
                ("plots", "Figures against axes", plots), ("failures", f"Failed and invalid ({len(bad)})", failures),
                ("results", "All variants", everything)]
    page = html_page(f"{sweep.name} — antenna_cad sweep", sweep.name,
                     f"design sweep · antenna_cad {__version__} · tables: results.csv, results.parquet, pareto.csv",
                     sections, "figure.plot{display:inline-block;width:49%;vertical-align:top;margin:.4em 0}")
    atomic_write(out_dir / PAGE, page.encode("utf-8"))
