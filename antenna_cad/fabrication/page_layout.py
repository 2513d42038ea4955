"""Where the drawings go on the A4 pages of the tiled 1:1 PDF (DESIGN.md pitfalls: print at 1:1).

A drawing that fits one page window with :data:`MARGIN_MM` all round is *nested*: put whole,
beside others, on a shared page (shelf packing in drawing order: the rows of a page are filled
left to right, top to bottom, a row as tall as its tallest part). A larger drawing is *tiled*:
cut into windows with :data:`OVERLAP_MM` overlap and registration crosses, its last column and
row cut to its extents, so a narrow edge tile shares a page like a small drawing. Pages come as
the drawings do (a generator), so a 10⁵-page layup is never held at once.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
import shapely

from antenna_cad.fabrication.templates import OVERLAP_MM, WINDOW_MM, Drawing, text_box

MARGIN_MM = 5.0                                  # content to window frame, and to a nested neighbour
ALONE = 0.5                                      # a part above this share of the window gets a page of its own
Box = tuple[float, float, float, float]
Text = tuple[str, float, float, float]


class Tile(NamedTuple):
    """A tile of a tiled drawing: grid row and column, its number k of count, and the grid's
    upper left corner (drawing mm; the registration crosses sit at the overlap strips' centres)."""
    row: int
    col: int
    k: int
    count: int
    x0: float
    y1: float


@dataclass(frozen=True)
class Placement:
    """Part of a drawing on a page: ``window`` (x0, y0, x1, y1 mm in the drawing) shown with its
    lower left ``at`` (mm from the page window's lower left); ``tile`` for a tiled drawing, None
    for a nested one (whole); ``index`` the drawing's place in the input; ``texts`` (text, x, y,
    cap height) mm from the window's lower left, each whole inside it."""
    drawing: Drawing
    index: int
    window: Box
    at: tuple[float, float]
    tile: Tile | None
    texts: tuple[Text, ...]

    @property
    def name(self) -> str:
        t = self.tile
        return self.drawing.label + (f" tile {t.k}/{t.count} (row {t.row + 1} col {t.col + 1})" if t else "")


def layout(drawings: Iterable[Drawing]) -> Iterator[list[Placement]]:
    """The pages, each a list of placements, as the drawings come: a drawing that fits the window
    whole, or each tile of a larger one (cut to the drawing's box: a long narrow strip makes narrow
    tiles), goes on the open shared page (shelf packing); when it no longer fits, the page is
    given out and a new one opened — except for a part filling more than :data:`ALONE` of the
    window, which gets a page of its own and leaves the shared page open."""
    page: list[Placement] = []
    shelves: list[list[float]] = []              # per row: [depth of its top below the window top, height, x used]
    for index, d in enumerate(drawings):
        for part in _parts(d, index):
            w, h = part.window[2] - part.window[0], part.window[3] - part.window[1]
            spot = _shelf_spot(shelves, w, h)
            if spot is None and w * h > ALONE * WINDOW_MM[0] * WINDOW_MM[1]:
                yield [part]
                continue
            if spot is None:
                yield page
                page, shelves = [], []
                spot = _shelf_spot(shelves, w, h)
            page.append(replace(part, at=spot))
    if page:
        yield page


def _parts(d: Drawing, index: int) -> list[Placement]:
    """The drawing whole (its extents grown by the margin) if that fits the window, else its tiles."""
    x0, y0, x1, y1 = box = _grown(d.page_extents(), MARGIN_MM)
    if x1 - x0 <= WINDOW_MM[0] and y1 - y0 <= WINDOW_MM[1]:
        texts = tuple((t, tx - x0, ty - y0, size) for _, (t, tx, ty, size) in d.page_items()[1])
        return [Placement(d, index, box, (0.0, 0.0), None, texts)]
    tiles = tile_windows(d, box)
    return [Placement(d, index, window, (0.0, 0.0), tile, tuple(texts))
            for (tile, window), texts in zip(tiles, texts_by_tile(d, [w for _, w in tiles]))]


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


def tile_windows(drawing: Drawing, box: Box | None = None) -> list[tuple[Tile, Box]]:
    """Tiles over ``box`` (the drawing's PDF extents grown by the margin): the windows of a grid
    from its upper left corner, the last column and row cut to the box, that hold a cut path, a
    mark or a text (a window holding none is dropped). The first column and row are whole
    windows, so a text as wide as a title block fits whole on some tile."""
    x0, y0, x1, y1 = box or _grown(drawing.page_extents(), MARGIN_MM)
    win_w, win_h = WINDOW_MM
    step_w, step_h = win_w - OVERLAP_MM, win_h - OVERLAP_MM
    cols = max(1, math.ceil((x1 - x0 - OVERLAP_MM) / step_w))
    rows = max(1, math.ceil((y1 - y0 - OVERLAP_MM) / step_h))
    grid = [((r, c), (x0 + c * step_w, max(y0, y1 - win_h - r * step_h), min(x1, x0 + c * step_w + win_w),
                      y1 - r * step_h)) for r in range(rows) for c in range(cols)]
    kept = [t for t, keep in zip(grid, _holding(drawing, [w for _, w in grid])) if keep]
    return [(Tile(r, c, k, len(kept), x0, y1), w) for k, ((r, c), w) in enumerate(kept, start=1)]


def _holding(drawing: Drawing, windows: list[Box]) -> np.ndarray:
    """Per window: does it hold part of a cut path or a mark, or the first place of a text the PDF
    prints (:func:`texts_by_tile`; a window lying wholly inside a piece, blank, is not printed)."""
    cut, _, _ = drawing.paths()
    marks, _ = drawing.page_items()
    lines = [shapely.linearrings(np.asarray(r, dtype=float)[:, :2]) for r in cut if len(r) >= 3]
    lines += [shapely.linestrings(np.asarray(m, dtype=float)[:, :2]) for m in marks if len(m) >= 2]
    holds = np.zeros(len(windows), dtype=bool)
    if lines:
        tree = shapely.STRtree(lines)
        holds[np.unique(tree.query(shapely.box(*np.array(windows).T), predicate="intersects")[0])] = True
    for spots in _text_spots(drawing, windows):
        holds[spots[0][0]] = True
    return holds


def texts_by_tile(drawing: Drawing, windows: list[Box]) -> list[list[Text]]:
    """Per window, the drawing's printed texts at window positions (mm from the window's lower
    left): each on every window that holds its whole box, at its true place; a text no window
    holds whole goes on the one needing the least shift to hold it (ties: the first), shifted
    inside — never on one where the shift would move it onto other lines."""
    placed: list[list[Text]] = [[] for _ in windows]
    for (_, (text, _, _, size)), spots in zip(drawing.page_items()[1], _text_spots(drawing, windows)):
        for k, x, y in spots:
            placed[k].append((text, x, y, size))
    return placed


def _text_spots(drawing: Drawing, windows: list[Box]) -> list[list[tuple[int, float, float]]]:
    """Per printed text, its (window, x, y) places as :func:`texts_by_tile` sets them."""
    wx0, wy0, wx1, wy1 = np.array(windows, dtype=float).reshape(-1, 4).T
    out = []
    for _, (text, x, y, size) in drawing.page_items()[1]:
        w, h = text_box(text, size)
        dx, dy = x - wx0, y - wy0                        # all windows at once (the same float operations)
        px = np.minimum(np.maximum(dx, 0.5), wx1 - wx0 - w - 0.5)
        py = np.minimum(np.maximum(dy, 0.5), wy1 - wy0 - h - 0.5)
        whole = np.flatnonzero((px == dx) & (py == dy)).tolist()
        if not whole:                                    # the least shift into a window it fits in
            room = (wx1 - wx0 >= w + 1.0) & (wy1 - wy0 >= h + 1.0)
            whole = [int(np.argmin(np.hypot(px - dx, py - dy) + np.where(room, 0.0, np.inf)))]
        out.append([(k, float(px[k]), float(py[k])) for k in whole])
    return out


def _grown(box: Box, pad: float) -> Box:
    return box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad
