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
    the pieces no label fits (too small for ``MIN_TEXT_MM`` text)."""
    texts = [shapely.box(x, y, x + w, y + h) for _, (t, x, y, size) in drawing.page_items()[1]
             for w, h in [text_box(t, size)]]
    bare = []
    for piece in pieces(drawing):
        shapely.prepare(piece)
        if not (texts and shapely.contains_properly(piece, texts).any()):
            bare.append(piece)
    placed = place_labels(drawing, [((drawing.label,), piece, None) for piece in bare])
    return [piece for piece, ok in zip(bare, placed) if not ok]


Label = tuple[tuple[str, ...], Polygon, tuple[float, float] | None]


def place_labels(drawing: Drawing, labels: list[Label]) -> list[bool]:
    """Per (texts, piece, spot) of ``labels`` add the first of ``texts`` that fits inside ``piece``
    with its box (grown by :data:`CLEARANCE_MM`) crossing no line or text of the drawing (where
    none fits so, no cut path or text: across a mark): at the largest of :data:`HEIGHTS` that
    fits, centred at ``spot`` if it fits there, else at the spot of a grid over the piece nearest
    its centroid. Per label: was one added. The pieces are disjoint, so their labels are too."""
    if not labels:
        return []
    cuts = [shapely.linearrings(np.asarray(r, dtype=float)[:, :2]) for r in drawing.cut if len(r) >= 3]
    cuts += [shapely.box(x, y, x + w, y + h) for _, (t, x, y, size) in drawing.page_items()[1]
             for w, h in [text_box(t, size)]]
    marks = [shapely.linestrings(np.asarray(m, dtype=float)[:, :2]) for m in drawing.page_items()[0] if len(m) >= 2]
    trees = (shapely.STRtree(cuts + marks), shapely.STRtree(cuts))
    return [_place(drawing, trees[0], *label) or _place(drawing, trees[1], *label) for label in labels]


def _place(drawing: Drawing, tree, texts: tuple[str, ...], piece: Polygon, spot) -> bool:
    shapely.prepare(piece)
    x0, y0, x1, y1 = piece.bounds
    gx, gy = np.meshgrid(np.linspace(x0, x1, GRID + 2)[1:-1], np.linspace(y0, y1, GRID + 2)[1:-1])
    centre = piece.centroid
    order = np.argsort(np.hypot(gx.ravel() - centre.x, gy.ravel() - centre.y), kind="stable")
    grid = (gx.ravel()[order], gy.ravel()[order])
    for text in texts:
        for cx, cy in ([(np.array([spot[0]]), np.array([spot[1]]))] if spot else []) + [grid]:
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
