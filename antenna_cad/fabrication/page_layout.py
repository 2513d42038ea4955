"""Where the drawings go on the A4 pages of the tiled 1:1 PDF (DESIGN.md pitfalls: print at 1:1).

A drawing that fits one page window with :data:`MARGIN_MM` all round is *nested*: put whole,
beside others, on a shared page (shelf packing in drawing order: the rows of a page are filled
left to right, top to bottom, a row as tall as its tallest drawing). A larger drawing is *tiled*
over pages with :data:`OVERLAP_MM` overlap and registration crosses, its grid placed (among a
few shifts) to need the fewest tiles while keeping its content :data:`MARGIN_MM` inside. Pages
come as the drawings do (a generator), so a 10⁵-page layup is never held at once.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

import numpy as np
import shapely

from antenna_cad.fabrication.templates import OVERLAP_MM, WINDOW_MM, Drawing, text_box

MARGIN_MM = 5.0                                  # content to window frame, and to a nested neighbour
SHIFTS = (0.5, 0.0, 1.0)                         # grid shifts tried (share of the slack), best first on ties
Box = tuple[float, float, float, float]


@dataclass(frozen=True)
class Placement:
    """Part of a drawing on a page: ``window`` (x0, y0, x1, y1 mm in the drawing) shown with its
    lower left ``at`` (mm from the page window's lower left); ``tile`` (row, col, k, count) for a
    tiled drawing, None for a nested one (whole); ``index`` the drawing's place in the input;
    ``texts`` (text, x, y, cap height) mm from the window's lower left, each whole inside it."""
    drawing: Drawing
    index: int
    window: Box
    at: tuple[float, float]
    tile: tuple[int, int, int, int] | None
    texts: tuple[tuple[str, float, float, float], ...]


def layout(drawings: Iterable[Drawing]) -> Iterator[list[Placement]]:
    """The pages, each a list of placements: a tiled drawing's tiles a page each, as they come;
    nested drawings on the open shared page, which is given out when the next one no longer fits
    (and at the end)."""
    page: list[Placement] = []
    shelves: list[list[float]] = []              # per row: [depth of its top below the window top, height, x used]
    for index, d in enumerate(drawings):
        x0, y0, x1, y1 = box = _grown(d.page_extents(), MARGIN_MM)
        w, h = x1 - x0, y1 - y0
        if w > WINDOW_MM[0] or h > WINDOW_MM[1]:
            tiles = tile_windows(d, box)
            for (r, c, wx, wy, k, n), texts in zip(tiles, texts_by_tile(d, tiles)):
                yield [Placement(d, index, (wx, wy, wx + WINDOW_MM[0], wy + WINDOW_MM[1]), (0.0, 0.0), (r, c, k, n),
                                 tuple(texts))]
            continue
        spot = _shelf_spot(shelves, w, h)
        if spot is None:
            yield page
            page, shelves = [], []
            spot = _shelf_spot(shelves, w, h)
        texts = tuple((t, tx - x0, ty - y0, size) for _, (t, tx, ty, size) in d.page_items()[1])
        page.append(Placement(d, index, box, spot, None, texts))
    if page:
        yield page


def _shelf_spot(shelves: list[list[float]], w: float, h: float) -> tuple[float, float] | None:
    """Lower left (mm in the window) of a w × h box on the page's rows: the first row with room
    (the last row grows taller if the page has room below it), else a new row; None when full."""
    win_w, win_h = WINDOW_MM
    for k, row in enumerate(shelves):
        top, height, used = row
        last = k == len(shelves) - 1
        if used + w <= win_w + 1e-9 and (h <= height or (last and top + h <= win_h + 1e-9)):
            row[1], row[2] = max(height, h), used + w
            return used, win_h - top - h
    top = shelves[-1][0] + shelves[-1][1] if shelves else 0.0
    if top + h > win_h + 1e-9:
        return None
    shelves.append([top, h, w])
    return 0.0, win_h - top - h


def tile_windows(drawing: Drawing, box: Box | None = None) -> list[tuple[int, int, float, float, int, int]]:
    """Tiles (row, col, x, y of the window's lower left, k, count) over ``box`` (the drawing's
    PDF extents grown by the margin): the grid of fewest windows that hold a cut path or a text
    among a few shifts of it within its slack (a window holding neither is not printed)."""
    x0, y0, x1, y1 = box or _grown(drawing.page_extents(), MARGIN_MM)
    win_w, win_h = WINDOW_MM
    step_w, step_h = win_w - OVERLAP_MM, win_h - OVERLAP_MM
    cols = max(1, math.ceil((x1 - x0 - OVERLAP_MM) / step_w))
    rows = max(1, math.ceil((y1 - y0 - OVERLAP_MM) / step_h))
    slack_w, slack_h = cols * step_w + OVERLAP_MM - (x1 - x0), rows * step_h + OVERLAP_MM - (y1 - y0)
    grids = [[(r, c, x0 - fx * slack_w + c * step_w, y1 + fy * slack_h - win_h - r * step_h)
              for r in range(rows) for c in range(cols)] for fy in SHIFTS for fx in SHIFTS]
    holds = _holding(drawing, [o for grid in grids for o in grid]).reshape(len(grids), -1)
    best = int(np.argmin(holds.sum(axis=1)))
    kept = [o for o, keep in zip(grids[best], holds[best]) if keep]
    return [(*o, k, len(kept)) for k, o in enumerate(kept, start=1)]


def _holding(drawing: Drawing, origins) -> np.ndarray:
    """Per window origin (.., .., x, y): does it hold part of a cut path, a mark or a text the PDF
    prints (a window lying wholly inside a piece, blank, is not printed)."""
    cut, _, _ = drawing.paths()
    marks, texts = drawing.page_items()
    win_w, win_h = WINDOW_MM
    windows = shapely.box(*np.array([(wx, wy, wx + win_w, wy + win_h) for *_, wx, wy in origins]).T)
    lines = [shapely.linearrings(np.asarray(r, dtype=float)[:, :2]) for r in cut if len(r) >= 3]
    lines += [shapely.linestrings(np.asarray(m, dtype=float)[:, :2]) for m in marks if len(m) >= 2]
    lines += [shapely.box(x, y, x + w, y + h) for _, (text, x, y, size) in texts for w, h in [text_box(text, size)]]
    if not lines:
        return np.ones(len(origins), dtype=bool)
    tree = shapely.STRtree(lines)
    holds = np.zeros(len(origins), dtype=bool)
    holds[np.unique(tree.query(windows, predicate="intersects")[0])] = True
    return holds


def texts_by_tile(drawing: Drawing, tiles) -> list[list[tuple[str, float, float, float]]]:
    """Per tile, the drawing's printed texts at window positions (mm from the window's lower
    left): each on every tile whose window holds its whole box, at its true place; a text no
    window holds whole goes on the one tile needing the least shift to hold it (ties: the first),
    shifted inside — never on a tile where the shift would move it onto other lines."""
    win_w, win_h = WINDOW_MM
    placed: list[list[tuple[str, float, float, float]]] = [[] for _ in tiles]
    wxs = np.array([t[2] for t in tiles], dtype=float)
    wys = np.array([t[3] for t in tiles], dtype=float)
    for _, (text, x, y, size) in drawing.page_items()[1]:
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


def _grown(box: Box, pad: float) -> Box:
    return box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad
