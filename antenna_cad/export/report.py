"""report.html: one self-contained page per build, shaped like a design review (DESIGN.md "Output folder").

Verdicts first (what to buy, whether to sand, the test zone, every failure or warning), then the key
figures, the assembly in 3-D, the verification plots before their tables, the checks, the cut list,
the files and the spec; long tables are collapsed (``<details>``, opened for print). Names, units,
rounding and statuses follow :mod:`antenna_cad.export.present`, the rules the terminal shares.

The page carries everything inline — plots as SVG, pictures as base64 PNG, the 3-D view's scripts
and glb (:mod:`antenna_cad.export.view3d`), CSS in the head, no network — so it opens the same
offline, from a mail attachment or a USB stick.
"""

from __future__ import annotations

import base64
import html
from dataclasses import dataclass
from pathlib import Path

import yaml

from antenna_cad import __version__
from antenna_cad.export import present
from antenna_cad.export.forked import Job
from antenna_cad.export.gltf import MERGE_ABOVE, View, glb_bytes, merged
from antenna_cad.export.page_parts import page as html_page
from antenna_cad.export.plots import assembly_png, plot_svg
from antenna_cad.export.view3d import VIEWER_CSS, licence_note, viewer_html
from antenna_cad.fabrication.cutlist import FIELDS as CUT_FIELDS
from antenna_cad.verification import Table, Verification

REPORT_HTML, REPORT_PDF = "report.html", "report.pdf"
OPEN_ROWS = 12                 # tables longer than this are collapsed
REPORT_CSS = """
.verdicts td:first-child{font-weight:600;white-space:nowrap}.badge.skip,tr.skip td:nth-child(2){background:#dde8f6}
.legend span.item{white-space:nowrap;margin-right:1.1em}.swatch{display:inline-block;width:1.1em;height:.9em;
margin:0 .25em -.1em 0;border:1px solid #777}details{margin:.5em 0}summary{cursor:pointer;color:#245}
@media print{details::details-content{content-visibility:visible;display:contents}summary{list-style:none}
#v3d canvas{height:420px}}
"""
OPEN_FOR_PRINT = ("<script>addEventListener('beforeprint',()=>document.querySelectorAll('details')"
                  ".forEach(d=>d.open=true))</script>")


@dataclass(frozen=True)
class ReportContent:
    """What both the page and the workshop PDF show, gathered once."""
    name: str
    kind: str
    frequency_ghz: float
    status: str
    verdicts: tuple[present.Verdict, ...]
    figures: dict
    checks: tuple
    verification: Verification
    views_png: bytes
    view_legend: dict[str, str]          # material -> colour
    view_parts: int
    viewer: str                          # the 3-D view's HTML (page only)
    cut_rows: tuple[tuple, ...]
    totals_kg: dict[str, float]
    boards: dict[str, int]
    files: tuple[tuple[str, object], ...]   # (path, solid volume or "")
    spec_yaml: str


def report_content(out: Path, spec, figures, checks, verification, fab, parts, view: View) -> ReportContent:
    """Collect the report of the build in folder ``out`` (the files written so far, plus the
    report's own files and the manifest)."""
    written = [p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()]
    volumes = {p.get("file"): p["volume_mm3"] for p in parts}
    files = sorted(set(written) | {REPORT_HTML, REPORT_PDF, "manifest.json"})
    png, legend, count = _pictures(view)
    return ReportContent(
        spec.name, spec.kind, spec.frequency_ghz, present.overall(checks),
        tuple(present.verdicts(checks, fab.boards, fab.totals_kg)), dict(figures), tuple(checks), verification,
        png, legend, count, _viewer(view),
        tuple(tuple(getattr(r, f) for f in CUT_FIELDS) for r in fab.rows),
        dict(fab.totals_kg), dict(fab.boards), tuple((f, volumes.get(f, "")) for f in files),
        yaml.safe_dump(spec.model_dump(mode="json"), sort_keys=False, allow_unicode=True))


def write_report(out: Path, spec, figures, checks, verification, fab, parts, view: View) -> None:
    """Write report.html and report.pdf of one build into folder ``out``: the PDF in a child process
    beside the page (:mod:`antenna_cad.export.forked`; same bytes as one after the other)."""
    from antenna_cad.export.report_pdf import write_report_pdf
    content = report_content(out, spec, figures, checks, verification, fab, parts, view)
    pdf = Job(write_report_pdf, (out / REPORT_PDF, content))
    try:
        write_report_html(out / REPORT_HTML, content)
    except BaseException:
        pdf.finish(wait=False)
        raise
    pdf.finish()


def write_report_html(path: Path, r: ReportContent) -> None:
    png = base64.b64encode(r.views_png).decode("ascii")
    pictures = (f'{r.viewer}<details><summary>Static views (front, side, top, isometric)</summary>'
                f'<figure class="picture" id="views"><img alt="assembly views" src="data:image/png;base64,{png}">'
                f'<figcaption>{r.view_parts} parts to make. {legend_html(r.view_legend)}</figcaption></figure></details>')
    totals = (_table(("material", "mass_kg"), sorted(r.totals_kg.items()))
              + _table(("material", "boards"), sorted(r.boards.items())))
    sections = [
        ("verdicts", "Verdicts", _verdicts(r.verdicts)),
        ("summary", "Key figures", _table(("figure", "value"), present.figure_rows(r.figures))),
        ("pictures", "Assembly", pictures),
        ("verification", "As-built verification", _verification(r.verification)),
        ("checks", "Checks", _checks_table(r.checks)),
        ("cutlist", "Cut list", totals + _collapsed(_table(CUT_FIELDS, r.cut_rows, "cutlist-table"),
                                                   len(r.cut_rows), "pieces")),
        ("files", "Files", _collapsed(_table(("file", "volume_mm3"), r.files), len(r.files), "files", force=True)),
        ("spec", "Spec", f"<details><summary>the resolved spec (YAML)</summary><pre>{html.escape(r.spec_yaml)}</pre>"
                         "</details>"),
    ]
    counts = {s: sum(c.status == s for c in r.checks) for s in present.STATUS_ORDER}
    tally = ", ".join(f"{n} {present.STATUS_LABEL[s]}" for s, n in counts.items() if n)
    page = html_page(f"{r.name} — antenna_cad report", r.name,
                     f"{html.escape(r.kind)} · {r.frequency_ghz:g} GHz · antenna_cad {__version__} · overall "
                     f"<span class='badge {r.status}'>{present.STATUS_LABEL[r.status]}</span> ({tally}) · "
                     f"workshop copy: {REPORT_PDF}", sections, REPORT_CSS + VIEWER_CSS)
    foot = f"<footer><p><small>{licence_note()}</small></p></footer>{OPEN_FOR_PRINT}"
    path.write_text(page.replace("</body>", foot + "</body>"), encoding="utf-8")


def legend_html(legend: dict[str, str]) -> str:
    """Swatch and name kept on one line per material (they never wrap apart)."""
    items = "".join(f'<span class="item"><span class="swatch" style="background:{c}"></span>{html.escape(m)}</span>'
                    for m, c in legend.items())
    return f'<span class="legend">{items}</span>'


def _verdicts(verdicts) -> str:
    rows = "".join(f'<tr class="{v.status}"><td>{html.escape(v.question)}</td><td>{present.STATUS_LABEL[v.status]}</td>'
                   f"<td>{html.escape(v.answer)}</td></tr>" for v in verdicts)
    return f'<table class="verdicts"><tbody>{rows}</tbody></table>' if rows else "<p>Nothing to decide.</p>"


def _checks_table(checks) -> str:
    rows = "".join(f'<tr class="{c.status}"><td>{html.escape(c.name)}</td><td>{present.STATUS_LABEL[c.status]}</td>'
                   f"<td>{html.escape(present.check_value(c))}</td><td>{html.escape(c.message)}</td></tr>"
                   for c in present.by_urgency(checks))
    return ("<table><thead><tr><th>check</th><th>status</th><th>value</th><th>detail</th></tr></thead>"
            f"<tbody>{rows}</tbody></table>")


def _table(columns, rows, css_id: str = "") -> str:
    """A table whose headings carry units and whose numbers are rounded by :mod:`present`."""
    head = "".join(f"<th>{html.escape(present.column_label(str(c)))}</th>" for c in columns)
    body = "".join("<tr>" + "".join(
        f'<td class="num">{html.escape(present.cell_text(str(c), v))}</td>'
        if isinstance(v, (int, float)) and not isinstance(v, bool) else f"<td>{html.escape(present.cell_text(str(c), v))}</td>"
        for c, v in zip(columns, row)) + "</tr>" for row in rows)
    ident = f' id="{css_id}"' if css_id else ""
    return f"<table{ident}><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _collapsed(table: str, rows: int, what: str, force: bool = False) -> str:
    """``table`` in a closed ``<details>`` when longer than :data:`OPEN_ROWS` rows (or ``force``)."""
    if rows <= OPEN_ROWS and not force:
        return table
    return f"<details><summary>{rows} {what}</summary>{table}</details>"


def _verification(v) -> str:
    parts = [f'<figure class="plot" id="plot-{p.name}">{plot_svg(p)}'
             f"<figcaption>{html.escape(p.caption or p.title)}</figcaption></figure>" for p in v.plots]
    if v.figures:
        parts.append(f"<h3>As-built figures</h3>" + _collapsed(
            _table(("figure", "value"), present.figure_rows(dict(sorted(v.figures.items())))), len(v.figures), "figures"))
    parts += [_named_table(t) for t in v.tables]
    return "".join(parts) or "<p>No as-built verification for this kind.</p>"


def _named_table(t: Table) -> str:
    caption = f"<figcaption>{html.escape(t.caption)}</figcaption>" if t.caption else ""
    return (f'<figure class="table" id="table-{t.name}"><h3>{html.escape(t.title)}</h3>'
            f'{_collapsed(_table(t.columns, t.rows), len(t.rows), "rows")}{caption}</figure>')


def _viewer(view: View) -> str:
    """The 3-D view: the build's glb, or above :data:`~antenna_cad.export.gltf.MERGE_ABOVE` parts the
    parts merged per group and material (a few draw calls instead of thousands)."""
    if len(view.parts) <= MERGE_ABOVE:
        return viewer_html(view.glb, list(view.parts))
    shown = merged(list(view.parts))
    return viewer_html(glb_bytes(shown), shown)


def _pictures(view: View) -> tuple[bytes, dict[str, str], int]:
    """Orthographic and isometric views of the parts to make (all parts when none is marked so),
    less the model's cutaway (a sphere's front hemispheres, so its shells show as rings): the
    PNG, the material colours and the part count."""
    parts = [p for p in view.parts if p.fabricated] or list(view.parts)
    parts = [p for p in parts if not p.cutaway] or parts
    shown = {p.material for p in parts}
    legend = {m: c for m, c in view.colours.items() if m in shown}
    return assembly_png([(p.mesh, p.colour) for p in parts]), legend, len(parts)
