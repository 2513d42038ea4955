"""1:1 cutting templates: DXF (layers CUT / MARK / TEXT, mm), SVG (mm) and a tiled A4 PDF.

A :class:`Drawing` is the one description of a template; the DXF is written from it with ezdxf,
the SVG is rendered from that DXF by ezdxf's drawing add-on at scale 1 (``fit_page=False``), and
the PDF draws the same polylines with matplotlib on A4 pages at exactly 1 mm = 1 mm, tiled with
overlap, registration crosses, page ids and a 100 mm check bar on every page (DESIGN.md pitfalls).
"""

from __future__ import annotations

import io
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import ezdxf
import ezdxf.bbox
import matplotlib
from ezdxf.addons.drawing import Frontend, RenderContext, layout, svg
from shapely.geometry import Polygon, box

matplotlib.use("Agg")
from matplotlib.backends.backend_pdf import PdfPages  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

_EZDXF_MARKER = re.compile(r"(\d+\.\d+\.\d+) @ \d{4}-\d\d-\d\dT[\d:.]+\+00:00")
MM_PER_INCH = 25.4
A4_MM = (210.0, 297.0)
PAGE_MARGIN_MM = 10.0
HEADER_MM, FOOTER_MM = 12.0, 18.0
OVERLAP_MM = 10.0
CHECK_BAR_MM = 100.0
TEXT_HEIGHT_MM = 6.0
LAYERS = {"CUT": 1, "MARK": 5, "TEXT": 7}      # DXF colour indices: red, blue, black/white


@dataclass
class Drawing:
    """A template in drawing coordinates (mm). ``cut`` rings are tool paths; ``marks`` open polylines."""
    label: str
    cut: list[list[tuple[float, float]]] = field(default_factory=list)
    marks: list[list[tuple[float, float]]] = field(default_factory=list)
    texts: list[tuple[str, float, float, float]] = field(default_factory=list)   # text, x, y, height

    def add_polygon(self, poly: Polygon) -> None:
        for ring in [poly.exterior, *poly.interiors]:
            self.cut.append([(round(x, 4), round(y, 4)) for x, y in ring.coords[:-1]])

    def add_cross(self, x: float, y: float, size: float) -> None:
        self.marks.append([(x - size, y), (x + size, y)])
        self.marks.append([(x, y - size), (x, y + size)])

    def bounds(self) -> tuple[float, float, float, float]:
        pts = [p for ring in self.cut + self.marks for p in ring]
        pts += [(x, y) for _, x, y, _ in self.texts]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        return min(xs), min(ys), max(xs), max(ys)

    def add_check_bar(self, x: float, y: float) -> None:
        """A 100 mm bar with 10 mm ticks: measure it on the print to confirm 1:1."""
        self.marks.append([(x, y), (x + CHECK_BAR_MM, y)])
        for k in range(11):
            tick = 6.0 if k in (0, 5, 10) else 3.0
            self.marks.append([(x + 10 * k, y), (x + 10 * k, y + tick)])
        self.texts.append(("100 mm check bar", x, y - 8.0, 4.0))


def dxf_document(drawing: Drawing) -> ezdxf.document.Drawing:
    doc = ezdxf.new("R2010", setup=True)
    doc.units = ezdxf.units.MM
    doc.header["$INSUNITS"] = ezdxf.units.MM
    doc.header["$MEASUREMENT"] = 1
    for name, color in LAYERS.items():
        doc.layers.add(name, color=color)
    msp = doc.modelspace()
    for ring in drawing.cut:
        msp.add_lwpolyline(ring, close=True, dxfattribs={"layer": "CUT"})
    for line in drawing.marks:
        msp.add_lwpolyline(line, close=False, dxfattribs={"layer": "MARK"})
    for text, x, y, h in drawing.texts:
        msp.add_text(text, height=h, dxfattribs={"layer": "TEXT"}).set_placement((x, y))
    return doc


def write_dxf(doc: ezdxf.document.Drawing, path: Path) -> None:
    """Save with fixed metadata so the bytes are reproducible: ezdxf's option fixes the header
    dates and GUIDs; its "version @ time" marker in the metadata dictionary is pinned here, and the
    CLASSES section (whose order depends on what ezdxf did first in the process) is sorted."""
    doc.classes.add_required_classes(doc.dxfversion)
    doc.classes.classes = dict(sorted(doc.classes.classes.items()))
    previous = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        stream = io.StringIO()
        doc.write(stream)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = previous
    text = _EZDXF_MARKER.sub(r"\1 @ 2000-01-01T00:00:00+00:00", stream.getvalue())
    path.write_bytes(text.encode(doc.output_encoding))


def write_svg(doc: ezdxf.document.Drawing, path: Path) -> None:
    """True-scale SVG: page = DXF extents (text included) + 10 mm margins, scale 1, no fit-to-page."""
    size = ezdxf.bbox.extents(doc.modelspace()).size
    m = PAGE_MARGIN_MM
    page = layout.Page(size.x + 2 * m, size.y + 2 * m, layout.Units.mm,
                       margins=layout.Margins.all(m))
    backend = svg.SVGBackend()
    Frontend(RenderContext(doc), backend).draw_layout(doc.modelspace())
    settings = layout.Settings(fit_page=False, scale=1.0)
    path.write_text(backend.get_string(page, settings=settings), encoding="utf-8")


def tile_windows(drawing: Drawing) -> tuple[list[tuple[int, int, float, float]], float, float]:
    """Tile origins (row, col, x, y) covering the drawing; only tiles that hold something."""
    x0, y0, x1, y1 = drawing.bounds()
    win_w = A4_MM[0] - 2 * PAGE_MARGIN_MM
    win_h = A4_MM[1] - 2 * PAGE_MARGIN_MM - HEADER_MM - FOOTER_MM
    step_w, step_h = win_w - OVERLAP_MM, win_h - OVERLAP_MM
    cols = max(1, math.ceil((x1 - x0 - OVERLAP_MM) / step_w))
    rows = max(1, math.ceil((y1 - y0 - OVERLAP_MM) / step_h))
    geometry = [Polygon(r) for r in drawing.cut if len(r) >= 3]
    tiles = []
    for r in range(rows):
        for c in range(cols):
            wx, wy = x0 + c * step_w, y1 - win_h - r * step_h
            window = box(wx, wy, wx + win_w, wy + win_h)
            if any(window.intersects(g.exterior) or g.contains(window) for g in geometry) or not geometry:
                tiles.append((r, c, wx, wy))
    return tiles, win_w, win_h


def write_tiled_pdf(drawings: list[Drawing], path: Path, title: str) -> int:
    """All drawings at 1:1 on A4 portrait pages with overlap; returns the page count."""
    pages = 0
    metadata = {"Title": title, "Creator": "antenna_cad", "Producer": "antenna_cad",
                "CreationDate": None}
    with PdfPages(path, metadata=metadata) as pdf:
        for drawing in drawings:
            tiles, win_w, win_h = tile_windows(drawing)
            x0, _, _, y1 = drawing.bounds()
            cut_lines = [ring + ring[:1] for ring in drawing.cut]
            for k, (r, c, wx, wy) in enumerate(tiles, start=1):
                fig = Figure(figsize=(A4_MM[0] / MM_PER_INCH, A4_MM[1] / MM_PER_INCH))
                page = fig.add_axes((0, 0, 1, 1))
                page.set_xlim(0, A4_MM[0])
                page.set_ylim(0, A4_MM[1])
                page.axis("off")
                left, bottom = PAGE_MARGIN_MM, PAGE_MARGIN_MM + FOOTER_MM
                ax = fig.add_axes((left / A4_MM[0], bottom / A4_MM[1], win_w / A4_MM[0], win_h / A4_MM[1]))
                ax.set_xlim(wx, wx + win_w)
                ax.set_ylim(wy, wy + win_h)
                ax.set_aspect("equal", adjustable="box")
                ax.axis("off")
                ax.add_collection(LineCollection(cut_lines, colors="red", linewidths=0.5))
                ax.add_collection(LineCollection(drawing.marks, colors="blue", linewidths=0.4))
                for text, tx, ty, h in drawing.texts:
                    ax.text(tx, ty, text, fontsize=h / 25.4 * 72 * 0.7, clip_on=True)
                _registration_crosses(ax, x0, y1, wx, wy, win_w, win_h)
                page.add_patch(matplotlib.patches.Rectangle((left, bottom), win_w, win_h, fill=False,
                                                            linewidth=0.3, edgecolor="grey"))
                page.text(left, A4_MM[1] - PAGE_MARGIN_MM - 5,
                          f"{title} · {drawing.label} · tile row {r + 1} col {c + 1} · page {k}/{len(tiles)}"
                          " · print at 100 % (actual size)", fontsize=7)
                bar_y = PAGE_MARGIN_MM + 8
                bar = [[(left, bar_y), (left + CHECK_BAR_MM, bar_y)]] + [
                    [(left + 10 * t, bar_y), (left + 10 * t, bar_y + (4 if t % 5 == 0 else 2))] for t in range(11)]
                page.add_collection(LineCollection(bar, colors="black", linewidths=0.6))
                page.text(left + CHECK_BAR_MM + 4, bar_y, "100 mm check bar: measure it", fontsize=6,
                          va="center")
                pdf.savefig(fig)
                pages += 1
    return pages


def _registration_crosses(ax, x0, y1, wx, wy, win_w, win_h) -> None:
    """Crosses at the centres of the overlap strips: the same model points on neighbouring pages."""
    step_w, step_h = win_w - OVERLAP_MM, win_h - OVERLAP_MM
    half = OVERLAP_MM / 2
    xs = [x0 + half + k * step_w for k in range(-1, 400) if wx <= x0 + half + k * step_w <= wx + win_w]
    ys = [y1 - half - k * step_h for k in range(-1, 400) if wy <= y1 - half - k * step_h <= wy + win_h]
    crosses = [seg for x in xs for y in ys for seg in ([(x - 4, y), (x + 4, y)], [(x, y - 4), (x, y + 4)])]
    ax.add_collection(LineCollection(crosses, colors="black", linewidths=0.4))
