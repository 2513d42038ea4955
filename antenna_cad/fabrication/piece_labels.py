"""Names inside the pieces of a template: every piece (a CUT outline not inside another, less the
outlines inside it) carries a text wholly inside it, clear of its holes, the marks (the lens-axis
cross, dowel marks, joint lines) and the other texts, never smaller than ``MIN_TEXT_MM``: a piece
cut out of its sheet still says what it is (DESIGN.md pitfalls: label every part)."""

from __future__ import annotations

import numpy as np
import shapely
from shapely.geometry import Polygon

from antenna_cad.fabrication.templates import MIN_TEXT_MM, TEXT_HEIGHT_MM, Drawing, text_box

HEIGHTS = (TEXT_HEIGHT_MM, 4.0, MIN_TEXT_MM)      # tried in turn: the largest that fits
CLEARANCE_MM = 1.0                                 # between a label's box and any other line or text
GRID = 15                                          # candidate spots per axis over the piece's box


def pieces(drawing: Drawing) -> list[Polygon]:
    """The drawing's pieces: each outline at an even depth of nesting among the CUT paths, with the
    outlines directly inside it as holes."""
    cut, _, _ = drawing.paths()
    rings = [Polygon(np.asarray(r, dtype=float)[:, :2]) for r in cut if len(r) >= 3]
    rings = [r for r in rings if r.is_valid and r.area > 0]
    if not rings:
        return []
    tree = shapely.STRtree(rings)
    inside, outer = tree.query([r.representative_point() for r in rings], predicate="within")
    keep = inside != outer
    inside, outer = inside[keep], outer[keep]
    depth = np.bincount(inside, minlength=len(rings))
    out = []
    for k, ring in enumerate(rings):
        if depth[k] % 2:
            continue
        holes = [rings[i].exterior.coords for i, o in zip(inside, outer) if o == k and depth[i] == depth[k] + 1]
        out.append(Polygon(ring.exterior.coords, holes))
    return out


def name_pieces(drawing: Drawing) -> list[Polygon]:
    """Give each piece with no text inside it the drawing's label (:func:`place_labels`); returns
    the pieces no label fits (too small for ``MIN_TEXT_MM`` text). Nothing to do for a drawing
    whose maker named its pieces (``pieces_named``)."""
    if drawing.pieces_named:
        return []
    texts = [shapely.box(x, y, x + w, y + h) for _, (t, x, y, size) in drawing.page_texts()
             for w, h in [text_box(t, size)]]
    bare = []
    for piece in pieces(drawing):
        shapely.prepare(piece)
        if not (texts and shapely.contains_properly(piece, texts).any()):
            bare.append(piece)
    placed = place_labels(drawing, [((drawing.label,), piece, None) for piece in bare])
    return [piece for piece, ok in zip(bare, placed) if not ok]


Label = tuple[tuple[str, ...], Polygon, np.ndarray | tuple[float, float] | None]   # texts, piece, spot(s)


def place_labels(drawing: Drawing, labels: list[Label]) -> list[bool]:
    """Per (texts, piece, spot) of ``labels`` add the first of ``texts`` that fits inside ``piece``
    (clear of its holes) with its box, grown by :data:`CLEARANCE_MM`, crossing no mark or text of
    the drawing (where none fits so, no text: across a mark): at the largest of :data:`HEIGHTS`
    that fits, centred at the first of ``spot`` (a point or (k, 2) points in order of preference)
    where it fits, else at the spot of a grid over the piece nearest its centroid. Per label: was
    one added. The pieces are disjoint, so their labels, each
    inside its own, are too."""
    bar = drawing.bar[0] if drawing.bar else slice(0, 0)
    marks = [shapely.linestrings(np.asarray(m, dtype=float)[:, :2]) for k, m in enumerate(drawing.marks)
             if len(m) >= 2 and not bar.start <= k < bar.stop]
    texts = [shapely.box(x, y, x + w, y + h) for _, (t, x, y, size) in drawing.page_texts()
             for w, h in [text_box(t, size)]]
    trees = (shapely.STRtree(texts + marks), shapely.STRtree(texts))
    return [_place(drawing, trees[0], *label) or _place(drawing, trees[1], *label) for label in labels]


def _place(drawing: Drawing, tree, texts: tuple[str, ...], piece: Polygon, spot) -> bool:
    """:func:`place_labels` for one piece: the spot first, the grid (built only then) after."""
    if spot is not None:
        spots = np.atleast_2d(np.asarray(spot, dtype=float))
        if any(_fit(drawing, tree, text, piece, spots[:, 0], spots[:, 1]) for text in texts):
            return True
    shapely.prepare(piece)
    x0, y0, x1, y1 = piece.bounds
    gx, gy = np.meshgrid(np.linspace(x0, x1, GRID + 2)[1:-1], np.linspace(y0, y1, GRID + 2)[1:-1])
    centre = piece.centroid
    order = np.argsort(np.hypot(gx.ravel() - centre.x, gy.ravel() - centre.y), kind="stable")
    return any(_fit(drawing, tree, text, piece, gx.ravel()[order], gy.ravel()[order]) for text in texts)


def _fit(drawing: Drawing, tree, text: str, piece: Polygon, cx: np.ndarray, cy: np.ndarray) -> bool:
    """Add ``text`` centred at the first of the spots (cx, cy) where it fits, largest height first."""
    for h in HEIGHTS:
        w, c = text_box(text, h)[0], CLEARANCE_MM
        boxes = shapely.box(cx - w / 2 - c, cy - h / 2 - c, cx + w / 2 + c, cy + h / 2 + c)
        free = shapely.contains_properly(piece, boxes)
        free[tree.query(boxes, predicate="intersects")[0]] = False
        if free.any():
            k = int(np.argmax(free))
            drawing.texts.append((text, float(cx[k] - w / 2), float(cy[k] - h / 2), h))
            return True
    return False
