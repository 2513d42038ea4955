"""1:1 cutting templates: DXF (layers CUT / MARK / TEXT, mm), SVG (mm) and a tiled A4 PDF.

A :class:`Drawing` is the one description of a template; the DXF (its entities in an empty
document ezdxf writes once), the SVG and the PDF are written directly from it (ezdxf's SVG
rendering and matplotlib's PDF pages cost 80 ms per drawing and 90 ms per page;
benchmarks/template_speed.py). The PDF holds each drawing
once and tiles it onto A4 pages at exactly 1 mm = 1 mm, with overlap, registration crosses, page
ids and a 100 mm check bar on every page (DESIGN.md pitfalls).
"""

from __future__ import annotations

import html
import io
import math
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import cache, lru_cache
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import Polygon

from antenna_cad.fabrication.vector_pdf import (PT_PER_MM, VectorPdf, num, nums, polylines_ops, text_ops, text_width,
                                                wrap_text)

_EZDXF_MARKER = re.compile(r"(\d+\.\d+\.\d+) @ \d{4}-\d\d-\d\dT[\d:.]+\+00:00")
A4_MM = (210.0, 297.0)
PAGE_MARGIN_MM = 10.0
HEADER_MM, FOOTER_MM = 26.0, 18.0              # header: page line + the drawing's title block
WINDOW_MM = (A4_MM[0] - 2 * PAGE_MARGIN_MM, A4_MM[1] - 2 * PAGE_MARGIN_MM - HEADER_MM - FOOTER_MM)  # per tile
OVERLAP_MM = 10.0
CHECK_BAR_MM = 100.0
TEXT_HEIGHT_MM = 6.0
LAYERS = {"CUT": 1, "MARK": 5, "TEXT": 7}      # DXF colour indices: red, blue, black/white
SVG_COLOURS = {"CUT": "red", "MARK": "blue"}
LINE_WIDTH_MM = {"CUT": 0.18, "MARK": 0.14}
CAP_HEIGHT_EM = 0.72                             # Helvetica: DXF text height is the cap height
HEADER_PT = (7.0, 6.0, 4.0)                      # page line; title block preferred and smallest size
TITLE_LEADING = 1.5                              # title lines: baseline step / cap height


BulgePath = list[tuple[float, float, float]]     # closed path: vertex x, y and the DXF bulge to the next
Points = list[tuple[float, float]] | np.ndarray      # a polyline's vertices
HeaderRow = tuple[str, float, float]             # text, baseline depth below the top margin pt, size pt


@dataclass
class Drawing:
    """A template in drawing coordinates (mm). ``cut`` rings are tool paths (polylines within the
    template chord tolerance, drawn in SVG and PDF); ``arcs`` maps a ``cut`` index to the same
    path with true circular arcs (DXF bulges), written to the DXF instead when present;
    ``marks`` are open polylines; ``title`` the title block (also among ``texts``, wrapped; the
    PDF repeats it in the header of every tile instead). A polyline is a list of (x, y) or an
    (n, 2) array (large drawings: the writers format arrays in bulk)."""
    label: str
    cut: list[Points] = field(default_factory=list)
    arcs: dict[int, BulgePath] = field(default_factory=dict)
    marks: list[Points] = field(default_factory=list)
    texts: list[tuple[str, float, float, float]] = field(default_factory=list)   # text, x, y, cap height
    title: list[str] = field(default_factory=list)
    title_texts: set[int] = field(default_factory=set)                         # their indices in texts

    def add_title(self, lines: list[str], x: float, y: float, height: float = TEXT_HEIGHT_MM) -> None:
        """Title block above (x, y), the baseline of its last row; each line wrapped to the
        drawing's width (at least one tile's) so it stays on the drawing."""
        x0, _, x1, _ = self.bounds()
        width = max(x1 - x, WINDOW_MM[0])
        rows = [row for line in lines for row in wrap_text(line, width, height / CAP_HEIGHT_EM)]
        self.title += lines
        for k, row in enumerate(rows):
            self.title_texts.add(len(self.texts))
            self.texts.append((row, x, y + (len(rows) - 1 - k) * TITLE_LEADING * height, height))

    def add_polygon(self, poly: Polygon, arcs: list[BulgePath] | None = None) -> None:
        """The polygon's rings as cut paths; ``arcs``: their exact versions, in the same order."""
        rings = [poly.exterior, *poly.interiors]
        if arcs is not None and len(arcs) != len(rings):
            raise ValueError(f"{self.label}: {len(arcs)} arc paths for {len(rings)} polygon rings")
        for k, ring in enumerate(rings):
            if arcs is not None:
                self.arcs[len(self.cut)] = arcs[k]
            self.cut.append(np.round(shapely.get_coordinates(ring)[:-1], 4))

    def add_cross(self, x: float, y: float, size: float) -> None:
        self.marks.append([(x - size, y), (x + size, y)])
        self.marks.append([(x, y - size), (x, y + size)])

    def bounds(self) -> tuple[float, float, float, float]:
        boxes = [_points_box(ring) for ring in self.cut + self.marks]
        if self.texts:
            boxes.append(_points_box([(x, y) for _, x, y, _ in self.texts]))
        return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes),
                max(b[3] for b in boxes))

    def cut_bounds(self) -> tuple[float, float, float, float]:
        """Bounding box of the CUT paths: of their true arcs where the DXF has them (bulge arcs
        reach past their chords), else of the polylines."""
        boxes = [bulge_bounds(self.arcs[k]) if k in self.arcs else _points_box(ring)
                 for k, ring in enumerate(self.cut)]
        return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes),
                max(b[3] for b in boxes))

    def extents(self, bounds: tuple[float, float, float, float] | None = None) -> tuple[float, float, float, float]:
        """``bounds`` (pass them when already computed) grown by the texts' boxes (Helvetica
        advance widths)."""
        x0, y0, x1, y1 = bounds or self.bounds()
        for text, x, y, size in self.texts:
            x1 = max(x1, x + text_box(text, size)[0])
            y1 = max(y1, y + size)
        return x0, y0, x1, y1

    def add_check_bar(self, x: float, y: float) -> None:
        """A 100 mm bar with 10 mm ticks: measure it on the print to confirm 1:1."""
        self.marks.append([(x, y), (x + CHECK_BAR_MM, y)])
        for k in range(11):
            tick = 6.0 if k in (0, 5, 10) else 3.0
            self.marks.append([(x + 10 * k, y), (x + 10 * k, y + tick)])
        self.texts.append(("100 mm check bar", x, y - 8.0, 4.0))


def _points_box(points) -> tuple[float, float, float, float]:
    if isinstance(points, np.ndarray):
        (x0, y0), (x1, y1) = points.min(axis=0).tolist(), points.max(axis=0).tolist()
        return x0, y0, x1, y1
    xs, ys = zip(*points)
    return min(xs), min(ys), max(xs), max(ys)


def bulge_bounds(path: BulgePath) -> tuple[float, float, float, float]:
    """Exact bounding box of a closed path of lines and bulge arcs (DXF LWPOLYLINE semantics:
    bulge = tan(sweep / 4), positive counter-clockwise)."""
    pts = [(x, y) for x, y, _ in path]
    for (x0, y0, b), (x1, y1, _) in zip(path, path[1:] + path[:1]):
        if abs(b) < 1e-12:
            continue
        sweep = 4 * math.atan(b)
        chord = math.hypot(x1 - x0, y1 - y0)
        r = chord / (2 * abs(math.sin(sweep / 2)))
        mx, my = (x0 + x1) / 2, (y0 + y1) / 2
        d = r * math.cos(sweep / 2) * (1 if b > 0 else -1)      # centre offset, left of the chord if ccw
        cx, cy = mx - d * (y1 - y0) / chord, my + d * (x1 - x0) / chord
        a0 = math.atan2(y0 - cy, x0 - cx)
        for q in range(4):                                        # axis extremes the arc sweeps over
            t = q * math.pi / 2
            rel = (t - a0) % (2 * math.pi) if b > 0 else (a0 - t) % (2 * math.pi)
            if rel <= abs(sweep):
                pts.append((cx + r * math.cos(t), cy + r * math.sin(t)))
    return _points_box(pts)


def text_box(text: str, cap_height: float) -> tuple[float, float]:
    """(width, height) mm of a drawing text: Helvetica advance and cap height."""
    return text_width(text, cap_height / CAP_HEIGHT_EM), cap_height


def write_dxf(drawing: Drawing, path: Path) -> None:
    """The drawing as a DXF R2010 file (mm; layers CUT, MARK, TEXT)."""
    path.write_bytes(dxf_text(drawing).encode("utf-8"))


def dxf_text(drawing: Drawing) -> str:
    """The DXF text of a drawing: ezdxf's empty document (:func:`_dxf_frame`) with the drawing's
    entities written into its ENTITIES section, group code by group code as ezdxf writes them
    (LWPOLYLINE: 10/20 per vertex, 42 for a non-zero bulge; TEXT at its insertion point), on
    handles from the document's handle seed up. ezdxf itself took 12 ms a file, a minute for the
    4,500 templates of a 3 m Luneburg layup (issue 16); tests read these files back with ezdxf."""
    head, seed, middle, owner, tail = _dxf_frame()
    out: list[str] = []
    handle = seed

    def entity(kind: str, layer: str, subclass: str) -> None:
        nonlocal handle
        out.append(f"  0\n{kind}\n  5\n{handle:X}\n330\n{owner}\n100\nAcDbEntity\n  8\n{layer}\n100\n{subclass}\n")
        handle += 1

    def lwpolyline(layer: str, points, closed: bool) -> None:
        entity("LWPOLYLINE", layer, "AcDbPolyline")
        out.append(f" 90\n{len(points)}\n 70\n{int(closed)}\n")
        for x, y, *bulge in np.asarray(points, dtype=float).tolist():
            out.append(f" 10\n{x}\n 20\n{y}\n" + (f" 42\n{bulge[0]}\n" if bulge and bulge[0] else ""))

    for k, ring in enumerate(drawing.cut):
        lwpolyline("CUT", drawing.arcs.get(k, ring), True)
    for line in drawing.marks:
        lwpolyline("MARK", line, False)
    for text, x, y, h in drawing.texts:
        x, y, h = float(x), float(y), float(h)
        entity("TEXT", "TEXT", "AcDbText")
        out.append(f" 10\n{x}\n 20\n{y}\n 30\n0.0\n 40\n{h}\n  1\n{text}\n 11\n{x}\n 21\n{y}\n 31\n0.0\n"
                   "100\nAcDbText\n")
    return f"{head}{handle:X}{middle}{''.join(out)}{tail}"


@cache
def _dxf_frame() -> tuple[str, int, str, str, str]:
    """ezdxf's empty R2010 document (mm, layers CUT/MARK/TEXT), written once with fixed metadata
    so the bytes are reproducible (header dates and GUIDs fixed, its "version @ time" marker
    pinned, the CLASSES section sorted: its order depends on what ezdxf did first in the
    process), cut as (text up to the $HANDSEED value, first free handle, text from there to the
    ENTITIES section's content, the modelspace's owner handle, the rest)."""
    import ezdxf            # at use: validating a spec builds drawings but writes no DXF
    doc = ezdxf.new("R2010", setup=False)
    doc.units = ezdxf.units.MM
    doc.header["$INSUNITS"] = ezdxf.units.MM
    doc.header["$MEASUREMENT"] = 1
    for name, color in LAYERS.items():
        doc.layers.add(name, color=color)
    owner = doc.modelspace().block_record_handle
    doc.classes.add_required_classes(doc.dxfversion)
    doc.classes.classes = dict(sorted(doc.classes.classes.items()))
    previous = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        stream = io.StringIO()
        doc.write(stream)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = previous
    text = stream.getvalue()
    tail = text.rfind("CREATED_BY_EZDXF")                  # the markers sit in the last dictionary
    text = text[:tail] + _EZDXF_MARKER.sub(r"\1 @ 2000-01-01T00:00:00+00:00", text[tail:])
    seed = re.search(r"\n\$HANDSEED\n  5\n([0-9A-F]+)\n", text)
    entities = text.index("\n  2\nENTITIES\n") + len("\n  2\nENTITIES\n")
    return text[:seed.start(1)], int(seed.group(1), 16), text[seed.end(1):entities], owner, text[entities:]


def write_svg(drawing: Drawing, path: Path) -> tuple[float, float]:
    """True-scale SVG written from the drawing (1 user unit = 1 mm, y up as in the DXF): page =
    extents with texts + 10 mm margins, width/height in mm, CUT red, MARK blue, TEXT black.
    Returns the page (width, height) mm as written."""
    x0, y0, x1, y1 = drawing.extents()
    m = PAGE_MARGIN_MM
    w, h = x1 - x0 + 2 * m, y1 - y0 + 2 * m
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{num(w)}mm" height="{num(h)}mm" '
           f'viewBox="{num(x0 - m)} {num(-y1 - m)} {num(w)} {num(h)}">',
           f"<title>{html.escape(drawing.label)}</title>",
           '<g fill="none" stroke-linejoin="round" transform="scale(1 -1)">']
    for layer, closed, lines in (("CUT", True, drawing.cut), ("MARK", False, drawing.marks)):
        tag = "polygon" if closed else "polyline"
        out.append(f'<g id="{layer}" stroke="{SVG_COLOURS[layer]}" stroke-width="{LINE_WIDTH_MM[layer]}">')
        lines = [line for line in lines if len(line)]
        if lines:                                    # all of a layer's points formatted in one pass
            counts = np.array([len(line) for line in lines])
            ends = np.full(int(counts.sum()), " ", dtype="<U32")
            ends[np.cumsum(counts) - 1] = f'"/>\n<{tag} points="'
            text = nums(np.concatenate([np.asarray(line, dtype=float)[:, :2] for line in lines]), ",", ends)
            out.append(f'<{tag} points="{text[:-len(ends[-1])]}"/>')
        out.append("</g>")
    out.append('</g><g id="TEXT" fill="black" font-family="Helvetica, Arial, sans-serif">')
    out += [f'<text x="{num(x)}" y="{num(-y)}" font-size="{num(size / CAP_HEIGHT_EM)}">{html.escape(text)}</text>'
            for text, x, y, size in drawing.texts]
    out.append("</g></svg>\n")
    path.write_text("\n".join(out), encoding="utf-8")
    return float(num(w)), float(num(h))


def tile_windows(drawing: Drawing, bounds: tuple[float, float, float, float]) -> list[tuple[int, int, float, float]]:
    """Tile origins (row, col, x, y) over the drawing's extents (``bounds`` grown by the text
    boxes); only tiles that hold a cut path or a text other than the title block (repeated in
    every header), so a table set beside or below the outline gets its own page instead of
    being pushed onto the outline."""
    x0, y0, x1, y1 = drawing.extents(bounds)
    win_w, win_h = WINDOW_MM
    step_w, step_h = win_w - OVERLAP_MM, win_h - OVERLAP_MM
    cols = max(1, math.ceil((x1 - x0 - OVERLAP_MM) / step_w))
    rows = max(1, math.ceil((y1 - y0 - OVERLAP_MM) / step_h))
    geometry = [Polygon(r) for r in drawing.cut if len(r) >= 3]
    texts = [(x, y, x + w, y + h) for i, (text, x, y, size) in enumerate(drawing.texts)
             if i not in drawing.title_texts for w, h in [text_box(text, size)]]
    origins = [(r, c, x0 + c * step_w, y1 - win_h - r * step_h) for r in range(rows) for c in range(cols)]
    if not (geometry or texts):
        return origins
    windows = shapely.box(*np.array([(wx, wy, wx + win_w, wy + win_h) for _, _, wx, wy in origins]).T)
    holds = np.zeros(len(origins), dtype=bool)
    if geometry:
        outlines = np.array([g.exterior for g in geometry], dtype=object)
        polygons = np.array(geometry, dtype=object)
        shapely.prepare(outlines)
        shapely.prepare(polygons)
        holds |= (shapely.intersects(outlines[None, :], windows[:, None])
                  | shapely.contains(polygons[None, :], windows[:, None])).any(axis=1)
    if texts:
        holds |= shapely.intersects(shapely.box(*np.array(texts).T)[None, :], windows[:, None]).any(axis=1)
    return [o for o, keep in zip(origins, holds) if keep]


def write_tiled_pdf(drawings: Iterable[Drawing], path: Path, title: str) -> int:
    """All drawings at 1:1 on A4 portrait pages with overlap; returns the page count. Each
    drawing's lines are one Form XObject (with registration crosses at the centres of the overlap
    strips, the same model points on neighbouring pages); a page clips it to its window and scales
    it by exactly 72/25.4 pt per mm. Texts are set in page space, never clipped: the header and
    the drawing's title block on every tile, each other text whole on the tile that holds its
    start (or the nearest), moved inside the window where it would cross its edge. What repeats
    is written once and placed on every page: the window frame and the check bar (one form for
    the file) and each drawing's title block (a form per drawing), so a page is a few hundred
    bytes (a 3 m Luneburg layup has 10⁵ pages, issue 16)."""
    with VectorPdf(path, A4_MM, title) as pdf:
        page = (0.0, 0.0, A4_MM[0] * PT_PER_MM, A4_MM[1] * PT_PER_MM)
        furniture = pdf.add_form(_furniture(), page)
        for drawing in drawings:
            bounds = drawing.bounds()
            tiles = tile_windows(drawing, bounds)
            form = pdf.add_form(_form_content(drawing, bounds), _padded(drawing.extents(bounds), 10.0))
            placed = _texts_by_tile(drawing, tiles)
            blocks: dict[tuple, int] = {}
            for k, (r, c, wx, wy) in enumerate(tiles, start=1):
                header = (f"{title} · {drawing.label} · tile row {r + 1} col {c + 1} · page {k}/{len(tiles)}"
                          " · print at 100 % (actual size)")
                first, rows = header_lines([header] + drawing.title)
                if rows not in blocks:
                    blocks[rows] = pdf.add_form(_header_ops(rows), page)
                pdf.add_page(_page_content(form, furniture, blocks[rows], wx, wy, first, placed[k - 1]),
                             (form, furniture, blocks[rows]))
        return pdf.page_count


def _texts_by_tile(drawing: Drawing, tiles) -> list[list[tuple[str, float, float, float]]]:
    """Per tile, the drawing's non-title texts at window positions (mm from the window's lower
    left): each on every tile whose window holds its whole box, at its true place; a text no
    window holds whole goes on the one tile needing the least shift to hold it (ties: the first),
    shifted inside — never on a tile where the shift would move it onto other lines."""
    win_w, win_h = WINDOW_MM
    placed: list[list[tuple[str, float, float, float]]] = [[] for _ in tiles]
    wxs = np.array([t[2] for t in tiles], dtype=float)
    wys = np.array([t[3] for t in tiles], dtype=float)
    for i, (text, x, y, size) in enumerate(drawing.texts):
        if i in drawing.title_texts:
            continue
        w, h = text_box(text, size)
        dx, dy = x - wxs, y - wys                        # all tiles at once (the same float operations)
        px = np.minimum(np.maximum(dx, 0.5), win_w - w - 0.5)
        py = np.minimum(np.maximum(dy, 0.5), win_h - h - 0.5)
        whole = np.flatnonzero((px == dx) & (py == dy)).tolist()
        if not whole:
            shifts = [math.hypot(a - b, c - d) for a, b, c, d in zip(px.tolist(), dx.tolist(), py.tolist(), dy.tolist())]
            whole = [min(range(len(tiles)), key=shifts.__getitem__)]
        for k in whole:
            placed[k].append((text, float(px[k]), float(py[k]), size))
    return placed


def _form_content(drawing: Drawing, bounds: tuple[float, float, float, float]) -> bytes:
    x0, y0, x1, y1 = bounds
    step_w, step_h = WINDOW_MM[0] - OVERLAP_MM, WINDOW_MM[1] - OVERLAP_MM
    half = OVERLAP_MM / 2
    xs = x0 + half + step_w * np.arange(-1, math.ceil((x1 - x0) / step_w) + 2)
    ys = y1 - half - step_h * np.arange(-1, math.ceil((y1 - y0) / step_h) + 2)
    crosses = [seg for x in xs for y in ys for seg in ([(x - 4, y), (x + 4, y)], [(x, y - 4), (x, y + 4)])]
    ops = [f"1 J 1 j {num(LINE_WIDTH_MM['CUT'])} w 1 0 0 RG\n"]
    ops.append(polylines_ops(drawing.cut, closed=True))
    ops.append(f"{num(LINE_WIDTH_MM['MARK'])} w 0 0 1 RG\n")
    ops.append(polylines_ops(drawing.marks, closed=False))
    ops.append("0 0 0 RG\n")
    ops.append(polylines_ops(crosses, closed=False))
    return "".join(ops).encode()


def _page_content(form: int, furniture: int, block: int, wx: float, wy: float, first, texts) -> bytes:
    """Page-space operators in points: clipped window holding the drawing's form at 1:1, the
    frame and check bar (``furniture``), the title block (``block``), the page line ``first``
    and the tile's texts."""
    k = PT_PER_MM
    left, bottom = PAGE_MARGIN_MM, PAGE_MARGIN_MM + FOOTER_MM
    window = f"{num(left * k)} {num(bottom * k)} {num(WINDOW_MM[0] * k)} {num(WINDOW_MM[1] * k)} re"
    content = (f"q {window} W n {k:.9f} 0 0 {k:.9f} {num((left - wx) * k)} {num((bottom - wy) * k)} cm "
               f"/X{form} Do Q\n/X{furniture} Do /X{block} Do 0 g\n").encode() + _header_ops(first)
    for text, x, y, size in texts:
        content += text_ops(text, (left + x) * k, (bottom + y) * k, size / CAP_HEIGHT_EM * k)
    return content


def _furniture() -> bytes:
    """What every page holds: the window frame, the 100 mm check bar and its label."""
    k = PT_PER_MM
    left, bottom = PAGE_MARGIN_MM, PAGE_MARGIN_MM + FOOTER_MM
    window = f"{num(left * k)} {num(bottom * k)} {num(WINDOW_MM[0] * k)} {num(WINDOW_MM[1] * k)} re"
    ops = [f"0.3 w 0.5 G {window} S\n0 G 0 g 0.6 w\n"]
    bar_y = (PAGE_MARGIN_MM + 8) * k
    x_bar = [left * k + 10 * t * k for t in range(11)]
    ops.append(f"{num(x_bar[0])} {num(bar_y)} m {num(x_bar[-1])} {num(bar_y)} l S\n")
    ops += [f"{num(x)} {num(bar_y)} m {num(x)} {num(bar_y + (4 if t % 5 == 0 else 2) * k)} l S\n"
            for t, x in enumerate(x_bar)]
    return "".join(ops).encode() + text_ops("100 mm check bar: measure it", (left + CHECK_BAR_MM + 4) * k,
                                            bar_y - 2, 6)


def _header_ops(rows) -> bytes:
    """Header rows (:func:`header_lines`) set below the page's top margin."""
    left, top = PAGE_MARGIN_MM * PT_PER_MM, (A4_MM[1] - PAGE_MARGIN_MM) * PT_PER_MM
    return b"".join(text_ops(text, left, top - y, size) for text, y, size in rows)


def header_lines(lines: list[str]) -> tuple[tuple[HeaderRow, ...], tuple[HeaderRow, ...]]:
    """(text, baseline depth below the page's top margin pt, size pt) of the page line's rows and
    of the title block's, wrapped to the window width; the title shrinks (to 4 pt) to fit the
    header."""
    first = wrap_text(lines[0], WINDOW_MM[0] * PT_PER_MM, HEADER_PT[0])
    out = tuple((row, HEADER_PT[0] * (1 + 1.25 * i), HEADER_PT[0]) for i, row in enumerate(first))
    return out, _title_rows(tuple(lines[1:]), len(first))


@lru_cache(maxsize=64)
def _title_rows(title: tuple[str, ...], first_rows: int) -> tuple[HeaderRow, ...]:
    """The title block's header rows below ``first_rows`` rows of page line (the same on every
    tile of a drawing: wrapped once, not per page)."""
    width = WINDOW_MM[0] * PT_PER_MM
    room = (HEADER_MM - 1.0) * PT_PER_MM - 1.25 * HEADER_PT[0]
    size = HEADER_PT[1]
    while True:
        rows = [row for line in title for row in wrap_text(line, width, size)]
        if len(rows) * 1.2 * size <= room - 1.25 * HEADER_PT[0] * (first_rows - 1) or size <= HEADER_PT[2]:
            break
        size -= 0.5
    depth = HEADER_PT[0] * (1 + 1.25 * (first_rows - 1)) + 0.25 * HEADER_PT[0]
    return tuple((row, depth + 1.2 * size * (i + 1), size) for i, row in enumerate(rows))


def _padded(box: tuple[float, float, float, float], pad: float) -> tuple[float, float, float, float]:
    return box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad
