"""report.pdf: the workshop copy of the report — the same content as report.html on A4 pages.

Text pages in a monospaced font (figures, checks, tables, cut list, files), the verification plots
two to a page and the assembly views; matplotlib's PdfPages with fixed metadata (reproducible).
Files in folders are counted per folder and type (report.html lists every file), so a layup of
thousands of templates stays printable.
"""

from __future__ import annotations

import io
import math
import re
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.image  # noqa: E402
from matplotlib.backends.backend_pdf import PdfPages  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.font_manager import FontProperties  # noqa: E402
from matplotlib.patches import Patch, PathPatch  # noqa: E402
from matplotlib.textpath import TextPath  # noqa: E402
from matplotlib.transforms import Affine2D  # noqa: E402

from antenna_cad import __version__  # noqa: E402
from antenna_cad.export import present  # noqa: E402
from antenna_cad.export.plots import STYLE, draw_plot  # noqa: E402
from antenna_cad.fabrication.cutlist import FIELDS as CUT_FIELDS  # noqa: E402
from antenna_cad.fabrication.vector_pdf import spelled  # noqa: E402

A4_INCH = (8.27, 11.69)
MARGIN = 0.05                        # of the page width / height, each side
TEXT_TOP = 0.945                     # first text line, fraction of the page height
COURIER_ADVANCE_EM = 0.6             # every Courier glyph (PDF standard font metrics)
TEXT_SIZES_PT = (6.5, 5.0)           # preferred size; smallest before lines wrap
LINE_SPACING = 1.25
GREEK = "εδ"                         # drawn as outlines: the standard fonts have no Greek ("εr", not "er")
POWER = re.compile(r" × 10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)")
UNSUPERSCRIPT = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")
CUT_COLUMNS = ("part", "material", "board", "board_x_mm", "board_y_mm", "rotated", "width_mm", "height_mm",
               "thickness_mm", "mass_kg", "assembly_order")


def write_report_pdf(path: Path, r) -> None:
    """``r``: the ReportContent of export/report.py."""
    metadata = {"Title": f"{r.name} report", "Creator": "antenna_cad", "Producer": "antenna_cad",
                "CreationDate": None}
    head = [f"{r.name} — {r.kind}, {r.frequency_ghz:g} GHz, antenna_cad {__version__}, overall "
            f"{present.STATUS_LABEL[r.status]}", "", "Verdicts"]
    head += [f"{present.STATUS_LABEL[d.status]:8}  {d.question}: {d.answer}" for d in r.verdicts] + ["", "Key figures"]
    checks = [f"{present.STATUS_LABEL[c.status]:8}  {c.name} — {present.check_value(c)}: {c.message}"
              for c in present.by_urgency(r.checks)]
    v = r.verification
    verification = (format_table(("figure", "value"), present.figure_rows(dict(sorted(v.figures.items()))))
                    if v.figures else [])
    for t in v.tables:
        verification += ["", t.title] + format_table(t.columns, t.rows)
    cut = [CUT_FIELDS.index(c) for c in CUT_COLUMNS]
    cutlist = format_table(CUT_COLUMNS, [[row[i] for i in cut] for row in r.cut_rows])
    cutlist += ([""] + format_table(("material", "mass kg"), sorted(r.totals_kg.items())) + [""]
                + format_table(("material", "boards"), sorted(r.boards.items())))
    with matplotlib.rc_context(STYLE), PdfPages(path, metadata=metadata) as pdf:
        _text_pages(pdf, "Verdicts, key figures and checks",
                    head + format_table(("figure", "value"), present.figure_rows(r.figures)) + ["", "Checks"] + checks)
        if verification:
            _text_pages(pdf, "As-built verification", verification)
        for k in range(0, len(v.plots), 2):
            fig = Figure(figsize=A4_INCH)
            for j, plot in enumerate(v.plots[k:k + 2]):
                draw_plot(fig.add_subplot(2, 1, j + 1), plot)
            fig.tight_layout(pad=2.0)
            pdf.savefig(fig)
        fig = Figure(figsize=A4_INCH)
        ax = fig.add_axes((0.03, 0.2, 0.94, 0.7))
        ax.imshow(matplotlib.image.imread(io.BytesIO(r.views_png), format="png"))
        ax.axis("off")
        fig.text(MARGIN, 0.95, spelled(f"{r.name}: assembly ({r.view_parts} parts)"), fontsize=10)
        fig.legend(handles=[Patch(facecolor=c, edgecolor="#444", label=spelled(m)) for m, c in r.view_legend.items()],
                   loc="lower left", bbox_to_anchor=(MARGIN, 0.03), ncols=2, fontsize=7, frameon=False)
        pdf.savefig(fig)
        _text_pages(pdf, "Cut list", cutlist)
        _text_pages(pdf, "Files", format_table(("file", "volume_mm3"), _files_by_folder(r.files)))


def _files_by_folder(files) -> list[tuple]:
    """Top-level files one per line; each folder one line: its file count per type."""
    top = [(f, v) for f, v in files if "/" not in f]
    folders: dict[str, dict[str, int]] = {}
    for f, _ in files:
        if "/" in f:
            folder, name = f.split("/", 1)
            kinds, ext = folders.setdefault(folder, {}), name.rsplit(".", 1)[-1]
            kinds[ext] = kinds.get(ext, 0) + 1
    return top + [(f"{folder}/ ({sum(k.values())} files: "
                   + ", ".join(f"{n} .{ext}" for ext, n in sorted(k.items())) + ")", "")
                  for folder, k in sorted(folders.items())]


def format_table(columns, rows) -> list[str]:
    """Fixed-width text lines of a table: headings with units, numbers rounded and right-aligned
    (:mod:`antenna_cad.export.present`)."""
    cells = [[pdf_text(present.column_label(str(c))) for c in columns]] + [
        [pdf_text(present.cell_text(str(c), v)) for c, v in zip(columns, row)] for row in rows]
    numeric = [any(isinstance(row[i], (int, float)) and not isinstance(row[i], bool) for row in rows)
               for i in range(len(columns))]
    widths = [max(len(row[i]) for row in cells) for i in range(len(columns))]
    lines = ["  ".join(c.rjust(w) if num else c.ljust(w) for c, w, num in zip(row, widths, numeric)).rstrip()
             for row in cells]
    return [lines[0], "-" * len(lines[0])] + lines[1:]


def _text_pages(pdf: PdfPages, heading: str, lines: list[str]) -> None:
    """Pages of monospaced text in the PDF standard fonts (Courier, Helvetica): no glyph
    embedding, 40× faster than embedded DejaVu; characters they lack are spelled out. Courier's
    fixed advance sizes the text so the longest line fits the page width (down to 5 pt); lines
    still longer wrap with an indent, so nothing runs past the page edge."""
    lines = [pdf_text(line) for line in lines]
    size, width = text_layout(lines)
    rows = [row for line in lines for row in (textwrap.wrap(line, width, subsequent_indent="    ",
                                                            drop_whitespace=False) or [""])]
    per_page = math.floor((TEXT_TOP - MARGIN) * A4_INCH[1] * 72 / (LINE_SPACING * size))
    with matplotlib.rc_context({"pdf.use14corefonts": True}):
        for start in range(0, max(len(rows), 1), per_page):
            fig = Figure(figsize=A4_INCH)
            _heading(fig, heading)
            page = rows[start:start + per_page]
            if any(c in GREEK for row in page for c in row):
                _lines_with_greek(fig, page, size)
            else:
                fig.text(MARGIN, TEXT_TOP, "\n".join(page), family="monospace",
                         weight="medium", fontsize=size, va="top", linespacing=LINE_SPACING)
            pdf.savefig(fig)


def _heading(fig: Figure, heading: str, size: float = 12.0) -> None:
    """A page heading in bold Helvetica; one holding a :data:`GREEK` letter is drawn whole as outlines
    (DejaVu Sans Bold), so "εr" reads εr, not "er"."""
    if not any(c in GREEK for c in heading):
        fig.text(MARGIN, 0.965, spelled(heading), fontsize=size, weight="bold")
        return
    path = TextPath((0, 0), heading, size=size, prop=FontProperties(family="DejaVu Sans", weight="bold"))
    place = Affine2D().scale(1 / 72).translate(MARGIN * A4_INCH[0], 0.965 * A4_INCH[1]) + fig.dpi_scale_trans
    fig.add_artist(PathPatch(path, transform=place, facecolor="black", linewidth=0))


def pdf_text(text: str) -> str:
    """``text`` in the characters the page can show: :func:`spelled`, except the :data:`GREEK` letters
    (drawn by :func:`_lines_with_greek`); powers of ten as ``2.5e-5``, thin spaces as spaces."""
    text = POWER.sub(lambda m: "e" + m.group(1).translate(UNSUPERSCRIPT), text).replace("\u202f", " ")
    kept = str.maketrans({c: chr(i + 1) for i, c in enumerate(GREEK)})
    back = str.maketrans({chr(i + 1): c for i, c in enumerate(GREEK)})
    return spelled(text.translate(kept)).translate(back)


def _lines_with_greek(fig: Figure, rows: list[str], size: float) -> None:
    """A page of monospaced ``rows`` one line at a time on a fixed pitch, each :data:`GREEK` letter drawn
    as its outline (DejaVu Sans Mono) in the blank left for it in the Courier line."""
    pitch_in = LINE_SPACING * size / 72
    glyphs = {c: TextPath((0, 0), c, size=size, prop=FontProperties(family="DejaVu Sans Mono")) for c in GREEK}
    for k, row in enumerate(rows):
        y_in = TEXT_TOP * A4_INCH[1] - size / 72 - k * pitch_in          # the baseline
        fig.text(MARGIN, y_in / A4_INCH[1], "".join(" " if c in GREEK else c for c in row), family="monospace",
                 weight="medium", fontsize=size, va="baseline")
        for col, c in ((i, c) for i, c in enumerate(row) if c in GREEK):
            x_in = MARGIN * A4_INCH[0] + col * COURIER_ADVANCE_EM * size / 72
            place = Affine2D().scale(1 / 72).translate(x_in, y_in) + fig.dpi_scale_trans
            fig.add_artist(PathPatch(glyphs[c], transform=place, facecolor="black", linewidth=0))


def text_layout(lines: list[str]) -> tuple[float, int]:
    """(font size pt, characters per line) for monospaced ``lines`` within the page margins."""
    usable_pt = (1 - 2 * MARGIN) * A4_INCH[0] * 72
    longest = max((len(line) for line in lines), default=1) or 1
    size = max(TEXT_SIZES_PT[1], min(TEXT_SIZES_PT[0], usable_pt / (COURIER_ADVANCE_EM * longest)))
    size = math.floor(size * 10) / 10
    return size, math.floor(usable_pt / (COURIER_ADVANCE_EM * size))
