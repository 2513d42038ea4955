"""report.html: one self-contained page per build (DESIGN.md "Output folder"; issue 6).

The page carries everything inline — plots as SVG, pictures as base64 PNG, CSS in the head, no
scripts and no network — so it opens the same offline, from a mail attachment or a USB stick.
"""

from __future__ import annotations

import base64
import html
from dataclasses import dataclass
from pathlib import Path

import yaml
from matplotlib import colormaps
from matplotlib.colors import to_hex

from antenna_cad import __version__
from antenna_cad.export.forked import Job
from antenna_cad.export.mesh import picture_meshes
from antenna_cad.export.page_parts import page as html_page, table as _table
from antenna_cad.export.plots import assembly_png, plot_svg
from antenna_cad.fabrication.cutlist import FIELDS as CUT_FIELDS
from antenna_cad.verification import Table, Verification

PALETTE = ("#9ecae1", "#fdae6b", "#a1d99b", "#bcbddc", "#fdd0a2", "#c7e9c0", "#dadaeb", "#c6dbef",
           "#fcbba1", "#d9d9d9")
METAL = "#9a9a9a"
GRADE_MAP = colormaps["viridis_r"]             # low εr light, high εr dark
REPORT_HTML, REPORT_PDF = "report.html", "report.pdf"
PICTURE_FACETS = 200.0         # chord tolerance of the pictures = model size / this


@dataclass(frozen=True)
class ReportContent:
    """What both the page and the workshop PDF show, gathered once."""
    name: str
    kind: str
    frequency_ghz: float
    status: str
    figures: dict
    checks: tuple
    verification: Verification
    views_png: bytes
    view_legend: dict[str, str]          # material -> colour
    view_parts: int
    cut_rows: tuple[tuple, ...]
    totals_kg: dict[str, float]
    boards: dict[str, int]
    files: tuple[tuple[str, object], ...]   # (path, solid volume or "")
    spec_yaml: str


def report_content(out: Path, spec, figures, checks, verification, model, fab, parts) -> ReportContent:
    """Collect the report of the build in folder ``out`` (the files written so far, plus the
    report's own files and the manifest)."""
    written = [p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()]
    volumes = {p.get("file"): p["volume_mm3"] for p in parts}
    files = sorted(set(written) | {REPORT_HTML, REPORT_PDF, "manifest.json"})
    png, legend, count = _pictures(model)
    return ReportContent(
        spec.name, spec.kind, spec.frequency_ghz, _overall(checks), dict(figures), tuple(checks), verification,
        png, legend, count, tuple(tuple(getattr(r, f) for f in CUT_FIELDS) for r in fab.rows),
        dict(fab.totals_kg), dict(fab.boards), tuple((f, volumes.get(f, "")) for f in files),
        yaml.safe_dump(spec.model_dump(mode="json"), sort_keys=False))


def write_report(out: Path, spec, figures, checks, verification, model, fab, parts) -> None:
    """Write report.html and report.pdf of one build into folder ``out``: the PDF in a child process
    beside the page (:mod:`antenna_cad.export.forked`; same bytes as one after the other)."""
    from antenna_cad.export.report_pdf import write_report_pdf
    content = report_content(out, spec, figures, checks, verification, model, fab, parts)
    pdf = Job(write_report_pdf, (out / REPORT_PDF, content))
    try:
        write_report_html(out / REPORT_HTML, content)
    except BaseException:
        pdf.finish(wait=False)
        raise
    pdf.finish()


def write_report_html(path: Path, r: ReportContent) -> None:
    legend = " · ".join(f'<span style="background:{c};padding:0 .6em">&nbsp;</span> {html.escape(m)}'
                        for m, c in r.view_legend.items())
    png = base64.b64encode(r.views_png).decode("ascii")
    pictures = (f'<figure class="picture" id="views"><img alt="assembly views" src="data:image/png;base64,{png}">'
                f"<figcaption>{r.view_parts} parts; {legend}</figcaption></figure>")
    cutlist = (f'<div class="scroll">{_table(CUT_FIELDS, r.cut_rows, "cutlist-table")}</div>'
               f'{_table(("material", "mass kg"), sorted(r.totals_kg.items()))}'
               f'{_table(("material", "boards"), sorted(r.boards.items()))}')
    sections = [
        ("summary", "Key figures", _table(("figure", "value"), sorted(r.figures.items()))),
        ("checks", "Checks", _checks_table(r.checks)),
        ("verification", "As-built verification", _verification(r.verification)),
        ("pictures", "Assembly", pictures),
        ("cutlist", "Cut list", cutlist),
        ("files", "Files", f'<div class="scroll">{_table(("file", "solid volume mm³"), r.files)}</div>'),
        ("spec", "Spec", f"<pre>{html.escape(r.spec_yaml)}</pre>"),
    ]
    page = html_page(f"{r.name} — antenna_cad report", r.name,
                     f"kind <b>{r.kind}</b> · {r.frequency_ghz:g} GHz · antenna_cad {__version__} · overall "
                     f"<span class='badge {r.status}'>{r.status}</span> · workshop copy: {REPORT_PDF}", sections)
    path.write_text(page, encoding="utf-8")


def _overall(checks) -> str:
    statuses = {c.status for c in checks}
    return "fail" if "fail" in statuses else ("warn" if "warn" in statuses else "pass")


def _checks_table(checks) -> str:
    rows = "".join(f'<tr class="{c.status}"><td>{html.escape(c.name)}</td><td>{c.status}</td>'
                   f"<td>{html.escape(c.message)}</td></tr>" for c in checks)
    return f"<table><thead><tr><th>check</th><th>status</th><th>detail</th></tr></thead><tbody>{rows}</tbody></table>"


def _verification(v) -> str:
    parts = [_table(("figure", "value"), sorted(v.figures.items()))] if v.figures else []
    parts += [_named_table(t) for t in v.tables]
    parts += [f'<figure class="plot" id="plot-{p.name}">{plot_svg(p)}'
              f"<figcaption>{html.escape(p.caption or p.title)}</figcaption></figure>" for p in v.plots]
    return "".join(parts) or "<p>No as-built verification for this kind.</p>"


def _named_table(t: Table) -> str:
    caption = f"<figcaption>{html.escape(t.caption)}</figcaption>" if t.caption else ""
    return (f'<figure class="table" id="table-{t.name}"><h3>{html.escape(t.title)}</h3>'
            f'<div class="scroll">{_table(t.columns, t.rows)}</div>{caption}</figure>')


def _pictures(model) -> tuple[bytes, dict[str, str], int]:
    """Orthographic and isometric views of the parts to make (all parts when none is marked so),
    less the model's cutaway (a sphere's front hemispheres, so its shells show as rings): the
    PNG, the material colours and the part count. Graded materials (three or more dielectrics)
    are coloured along a sequential map by εr, so the grades read in order."""
    parts = [p for p in model.parts if p.role == "fabricated"] or list(model.parts)
    parts = [p for p in parts if p.label not in model.cutaway] or parts
    materials = sorted({p.material.name: p.material for p in parts}.items(), key=lambda nm: (nm[1].eps_r, nm[0]))
    dielectrics = [name for name, m in materials if not _is_metal(m)]
    graded = len(dielectrics) >= 3
    colour = {name: METAL if _is_metal(m) else
              (to_hex(GRADE_MAP(0.15 + 0.7 * dielectrics.index(name) / (len(dielectrics) - 1))) if graded
               else PALETTE[dielectrics.index(name) % len(PALETTE)])
              for name, m in materials}
    bb = parts[0].shape.bounding_box()
    for p in parts[1:]:
        bb.add(p.shape.bounding_box())
    tol = max(bb.diagonal / PICTURE_FACETS, 0.05)
    meshes = list(zip(picture_meshes([p.shape for p in parts], tol, [p.prism for p in parts]), [colour[p.material.name] for p in parts]))
    return assembly_png(meshes), colour, len(parts)


def _is_metal(material) -> bool:
    """Conductors are carried as εr = 1, tanδ = 0 materials (kinds/slot_array.py)."""
    return material.eps_r == 1.0 and material.tan_delta == 0.0
