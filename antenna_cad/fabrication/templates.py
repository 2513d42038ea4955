"""1:1 cutting templates: DXF (layers CUT / MARK / TEXT, mm), SVG (mm) and a tiled A4 PDF.

A :class:`Drawing` is the one description of a template; the DXF (its entities in an empty
document ezdxf writes once), the SVG and the PDF are written directly from it (ezdxf's SVG
rendering and matplotlib's PDF pages cost 80 ms per drawing and 90 ms per page;
benchmarks/template_speed.py). The PDF holds each drawing
once and places it on A4 pages at exactly 1 mm = 1 mm: small ones nested several to a page,
larger ones tiled with overlap and registration crosses (:mod:`page_layout`), a page line and a
100 mm check bar on every page (DESIGN.md pitfalls). The writers drop near-duplicate vertices
(:func:`thinned`), which plotter and laser drivers read as extra moves.
"""

from __future__ import annotations

import html
import io
import math
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import Polygon

from antenna_cad.fabrication.vector_pdf import (PT_PER_MM, VectorPdf, num, nums, polylines_ops, text_ops, text_width,
                                                wrap_text)

_EZDXF_MARKER = re.compile(r"(\d+\.\d+\.\d+) @ \d{4}-\d\d-\d\dT[\d:.]+\+00:00")
A4_MM = (210.0, 297.0)
PAGE_MARGIN_MM = 10.0
HEADER_MM, FOOTER_MM = 12.0, 18.0              # header: the page line (two rows at most)
WINDOW_MM = (A4_MM[0] - 2 * PAGE_MARGIN_MM, A4_MM[1] - 2 * PAGE_MARGIN_MM - HEADER_MM - FOOTER_MM)  # per tile
OVERLAP_MM = 10.0
CHECK_BAR_MM = 100.0
TEXT_HEIGHT_MM = 6.0
MIN_TEXT_MM = 2.5                                # no text smaller (cap height), on drawings and pages
TITLE_HEIGHT_MM = 3.0
TITLE_WIDTH_MM = (60.0, 180.0)                   # a title block's width: the drawing's, within these
MIN_VERTEX_STEP_MM = 0.01                        # closer vertices are one (plotters read them as moves)
_THIN_MM = MIN_VERTEX_STEP_MM + 0.0015             # ... as written: 3-decimal SVG/PDF numbers move a step 1.4 µm
LAYERS = {"CUT": 1, "MARK": 5, "TEXT": 7}      # DXF colour indices: red, blue, black/white
SVG_COLOURS = {"CUT": "red", "MARK": "blue"}
LINE_WIDTH_MM = {"CUT": 0.18, "MARK": 0.14}
CAP_HEIGHT_EM = 0.72                             # Helvetica: DXF text height is the cap height
PAGE_LINE_PT = MIN_TEXT_MM / CAP_HEIGHT_EM * PT_PER_MM     # header and footer text: MIN_TEXT_MM caps
TITLE_LEADING = 1.5                              # title lines: baseline step / cap height


BulgePath = list[tuple[float, float, float]]     # closed path: vertex x, y and the DXF bulge to the next
Points = list[tuple[float, float]] | np.ndarray      # a polyline's vertices


@dataclass
class Drawing:
    """A template in drawing coordinates (mm). ``cut`` rings are tool paths (polylines within the
    template chord tolerance, drawn in SVG and PDF); ``arcs`` maps a ``cut`` index to the same
    path with true circular arcs (DXF bulges), written to the DXF instead when present;
    ``marks`` are open polylines; ``title`` the title block (also among ``texts``, wrapped);
    ``bar`` the check bar's marks (a slice) and text index: the PDF prints its own on every page
    instead. A polyline is a list of (x, y) or an (n, 2) array (large drawings: the writers
    format arrays in bulk); the writers drop near-duplicate vertices (:meth:`paths`)."""
    label: str
    cut: list[Points] = field(default_factory=list)
    arcs: dict[int, BulgePath] = field(default_factory=dict)
    marks: list[Points] = field(default_factory=list)
    texts: list[tuple[str, float, float, float]] = field(default_factory=list)   # text, x, y, cap height
    title: list[str] = field(default_factory=list)
    title_texts: set[int] = field(default_factory=set)                         # their indices in texts
    bar: tuple[slice, int] | None = None
    pieces_named: bool = False                   # its maker named every piece (``piece_labels``)
    _paths: tuple | None = field(default=None, repr=False, compare=False)

    def add_title(self, lines: list[str], x: float, y: float, height: float = TITLE_HEIGHT_MM) -> None:
        """Title block above (x, y), the baseline of its last row; each line wrapped to the
        drawing's width (within :data:`TITLE_WIDTH_MM`: a block fits one tile, nested or tiled)."""
        x0, _, x1, _ = self.bounds()
        width = min(max(x1 - x, TITLE_WIDTH_MM[0]), TITLE_WIDTH_MM[1])
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
        cut, arcs, _ = self.paths()
        boxes = [bulge_bounds(arcs[k]) if k in arcs else _points_box(ring) for k, ring in enumerate(cut)]
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
        """A 100 mm bar with 10 mm ticks: measure it on the print to confirm 1:1 (DXF and SVG;
        the PDF has one on every page)."""
        first = len(self.marks)
        self.marks.append([(x, y), (x + CHECK_BAR_MM, y)])
        for k in range(11):
            tick = 6.0 if k in (0, 5, 10) else 3.0
            self.marks.append([(x + 10 * k, y), (x + 10 * k, y + tick)])
        self.bar = (slice(first, len(self.marks)), len(self.texts))
        self.texts.append(("100 mm check bar", x, y - 8.0, 4.0))

    def paths(self) -> tuple[list[Points], dict[int, BulgePath], list[Points]]:
        """(cut, arcs, marks) as the writers draw them: without vertices nearer than
        :data:`MIN_VERTEX_STEP_MM` to the one before (remembered while no path is added)."""
        key = (len(self.cut), len(self.arcs), len(self.marks))
        if self._paths is None or self._paths[0] != key:
            self._paths = (key, ([thinned(r, True) for r in self.cut],
                                 {k: thinned_bulges(p) for k, p in self.arcs.items()},
                                 [thinned(m, False) for m in self.marks]))
        return self._paths[1]

    def page_items(self) -> tuple[list[Points], list[tuple[int, tuple[str, float, float, float]]]]:
        """The marks and (index, text) the PDF draws: all but the check bar."""
        _, _, marks = self.paths()
        if self.bar is None:
            return marks, self.page_texts()
        cut, _ = self.bar
        return marks[:cut.start] + marks[cut.stop:], self.page_texts()

    def page_texts(self) -> list[tuple[int, tuple[str, float, float, float]]]:
        """(index, text) of the texts the PDF draws: all but the check bar's."""
        skip = self.bar[1] if self.bar else -1
        return [(k, t) for k, t in enumerate(self.texts) if k != skip]

    def page_extents(self) -> tuple[float, float, float, float]:
        """Extents of what the PDF draws (cut paths, marks, texts; no check bar)."""
        cut, _, _ = self.paths()
        marks, texts = self.page_items()
        boxes = [_points_box(ring) for ring in cut + marks if len(ring)]
        boxes += [(x, y, x + text_box(t, h)[0], y + h) for _, (t, x, y, h) in texts]
        return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes),
                max(b[3] for b in boxes))


def thinned(points: Points, closed: bool, tol: float = _THIN_MM) -> Points:
    """``points`` without the vertices nearer than ``tol`` to the last one kept (a closed path:
    nor its last vertices near the first; an open one keeps its end); unchanged when none is."""
    a = np.asarray(points, dtype=float)[:, :2] if len(points) else np.zeros((0, 2))
    if len(a) < 2:
        return points
    near = np.hypot(*np.diff(a, axis=0).T) < tol
    if not near.any() and not (closed and math.dist(a[-1], a[0]) < tol):
        return points
    kept = _kept(a, closed, tol)
    return points[kept] if isinstance(points, np.ndarray) else [points[k] for k in kept]


def thinned_bulges(path: BulgePath, tol: float = _THIN_MM) -> BulgePath:
    """A closed bulge path thinned as :func:`thinned`; the segment joining two kept vertices
    takes the bulge of the longest of the segments it replaces (the others are the tiny ones)."""
    a = np.array([(x, y) for x, y, _ in path])
    if len(a) < 2 or thinned(a, True, tol) is a:
        return path
    kept = _kept(a, True, tol)
    out = []
    for j, k in zip(kept, kept[1:] + [len(path)]):
        longest = max(range(j, k), key=lambda i: math.dist(a[i], a[(i + 1) % len(a)]))
        out.append((path[j][0], path[j][1], path[longest][2]))
    return out


def _kept(a: np.ndarray, closed: bool, tol: float) -> list[int]:
    """Indices of the vertices kept by :func:`thinned`."""
    kept = [0]
    for k in range(1, len(a)):
        if math.dist(a[k], a[kept[-1]]) >= tol:
            kept.append(k)
    if closed:
        while len(kept) > 2 and math.dist(a[kept[-1]], a[0]) < tol:
            kept.pop()
    elif kept[-1] != len(a) - 1:                      # an open line keeps its end point
        kept[-1:] = [kept[-1], len(a) - 1] if len(kept) == 1 else [len(a) - 1]
    return kept


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
    4,500 templates of a 3 m Luneburg layup; tests read these files back with ezdxf."""
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

    cut, arcs, marks = drawing.paths()
    for k, ring in enumerate(cut):
        lwpolyline("CUT", arcs.get(k, ring), True)
    for line in marks:
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
    cut, _, marks = drawing.paths()
    for layer, closed, lines in (("CUT", True, cut), ("MARK", False, marks)):
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


def write_tiled_pdf(drawings: Iterable[Drawing], path: Path, title: str) -> int:
    """All drawings at 1:1 on A4 portrait pages; returns the page count. Small drawings are nested
    several to a page, larger ones tiled with overlap (:mod:`page_layout`). Each drawing's lines
    are one Form XObject (a tiled one's with registration crosses at the centres of the overlap
    strips, the same model points on neighbouring pages) that a page clips to the drawing's
    window and scales by exactly 72/25.4 pt per mm. Texts are set in page space, never clipped,
    each whole inside its window. What repeats is written once: the window frame, the check bar
    and their labels are one form placed on every page, so a page is a few hundred bytes (a 3 m
    Luneburg layup has 10⁵ pages)."""
    from antenna_cad.fabrication.page_layout import layout
    with VectorPdf(path, A4_MM, title) as pdf:
        furniture = pdf.add_form(_furniture(), (0.0, 0.0, A4_MM[0] * PT_PER_MM, A4_MM[1] * PT_PER_MM))
        tiled: dict[int, int] = {}                      # a tiled drawing's form, by drawing index
        for placements in layout(drawings):
            forms = []
            for p in placements:
                if p.tile is None:
                    forms.append(pdf.add_form(_form_content(p.drawing, None), _padded(p.window, 1.0)))
                    continue
                if p.index not in tiled:
                    tiled[p.index] = pdf.add_form(_form_content(p.drawing, p), _padded(p.drawing.page_extents(), 10.0))
                forms.append(tiled[p.index])
            line = _page_line(title, placements, pdf.page_count + 1)
            pdf.add_page(_page_content(placements, forms, furniture, line), (furniture, *sorted(set(forms))))
        return pdf.page_count


def _page_line(title: str, placements, page: int) -> str:
    """The header: title, page number, what the page holds; parts listed while two rows hold them."""
    names = "; ".join(p.name for p in placements)
    line = f"{title} · page {page} · {names} · print at 100 % (actual size)"
    if len(placements) > 1 and len(wrap_text(line, WINDOW_MM[0] * PT_PER_MM, PAGE_LINE_PT)) > 2:
        line = f"{title} · page {page} · {len(placements)} parts, each named inside its outline · print at 100 %"
    return line


def _form_content(drawing: Drawing, tile) -> bytes:
    """The drawing's cut paths (red) and marks (blue), without its check bar; a tiled drawing's
    (``tile``: any of its placements) also black registration crosses at the centres of its
    grid's overlap strips."""
    cut, _, _ = drawing.paths()
    marks, _ = drawing.page_items()
    ops = [f"1 J 1 j {num(LINE_WIDTH_MM['CUT'])} w 1 0 0 RG\n", polylines_ops(cut, closed=True),
           f"{num(LINE_WIDTH_MM['MARK'])} w 0 0 1 RG\n", polylines_ops(marks, closed=False)]
    if tile is not None:
        ops += ["0 0 0 RG\n", polylines_ops(_crosses(drawing.page_extents(), tile.tile), closed=False)]
    return "".join(ops).encode()


def _crosses(extents: tuple[float, float, float, float], tile) -> list[list[tuple[float, float]]]:
    """Registration crosses of a tiled drawing: on the centre lines of its grid's overlap strips,
    where they cross each other and the middle of each tile (cut to ``extents``) they border."""
    step_w, step_h = WINDOW_MM[0] - OVERLAP_MM, WINDOW_MM[1] - OVERLAP_MM
    x0, y0, x1, y1 = extents
    cols, rows = math.ceil((x1 - tile.x0) / step_w), math.ceil((tile.y1 - y0) / step_h)
    strip_x = [tile.x0 + c * step_w + OVERLAP_MM / 2 for c in range(1, cols)]
    strip_y = [tile.y1 - r * step_h - OVERLAP_MM / 2 for r in range(1, rows)]
    mid_x = [(max(x0, tile.x0 + c * step_w) + min(x1, tile.x0 + c * step_w + WINDOW_MM[0])) / 2 for c in range(cols)]
    mid_y = [(max(y0, tile.y1 - r * step_h - WINDOW_MM[1]) + min(y1, tile.y1 - r * step_h)) / 2 for r in range(rows)]
    points = sorted({(x, y) for x in strip_x for y in strip_y + mid_y} | {(x, y) for x in mid_x for y in strip_y})
    return [seg for x, y in points for seg in ([(x - 4, y), (x + 4, y)], [(x, y - 4), (x, y + 4)])]


def _page_content(placements, forms: list[int], furniture: int, line: str) -> bytes:
    """Page-space operators in points: per placement its window clipped on the page holding the
    drawing's form at 1:1, its texts and (on a shared page) a dashed grey frame; the frame and
    check bar (``furniture``); the page line."""
    k = PT_PER_MM
    out = []
    for p, form in zip(placements, forms):
        left, bottom = PAGE_MARGIN_MM + p.at[0], PAGE_MARGIN_MM + FOOTER_MM + p.at[1]
        wx, wy, wx1, wy1 = p.window
        clip = f"{num(left * k)} {num(bottom * k)} {num((wx1 - wx) * k)} {num((wy1 - wy) * k)} re"
        out.append(f"q {clip} W n {k:.9f} 0 0 {k:.9f} {num((left - wx) * k)} {num((bottom - wy) * k)} cm "
                   f"/X{form} Do Q\n".encode())
        if len(placements) > 1:                          # where to cut the page apart: a light frame a part
            out.append(f"q 0.2 w 0.7 G [2 2] 0 d {clip} S Q\n".encode())
        out += [text_ops(text, (left + x) * k, (bottom + y) * k, size / CAP_HEIGHT_EM * k)
                for text, x, y, size in p.texts]
    out.append(f"/X{furniture} Do 0 g\n".encode())
    top = (A4_MM[1] - PAGE_MARGIN_MM) * k
    for i, row in enumerate(wrap_text(line, WINDOW_MM[0] * k, PAGE_LINE_PT)):
        out.append(text_ops(row, PAGE_MARGIN_MM * k, top - PAGE_LINE_PT * (1 + 1.25 * i), PAGE_LINE_PT))
    return b"".join(out)


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
                                            bar_y - 3, PAGE_LINE_PT)


def _padded(box: tuple[float, float, float, float], pad: float) -> tuple[float, float, float, float]:
    return box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad
