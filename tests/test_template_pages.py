"""Templates that waste no paper and hide no cut: small drawings nested on shared pages without
overlap, large ones tiled so the tiles reassemble 1:1, every drawing a margin inside its window,
every piece named inside its outline, no text under 2.5 mm, no near-duplicate vertices."""

from __future__ import annotations

import re
import zlib
from pathlib import Path

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString, box
from shapely.ops import polylabel, unary_union

from antenna_cad.export import check_readers
from antenna_cad.fabrication.outline import circle_polygon
from antenna_cad.fabrication.page_layout import MARGIN_MM, layout
from antenna_cad.fabrication.piece_labels import CLEARANCE_MM, name_pieces, pieces
from antenna_cad.fabrication.templates import (MIN_TEXT_MM, MIN_VERTEX_STEP_MM, OVERLAP_MM, WINDOW_MM, Drawing,
                                               bulge_bounds, text_box, thinned, thinned_bulges, write_dxf,
                                               write_svg, write_tiled_pdf)
from antenna_cad.fabrication.vector_pdf import PT_PER_MM

RECIPES = Path(__file__).resolve().parents[1] / "recipes"
PLACED = re.compile(r"q ([\d.-]+) ([\d.-]+) ([\d.-]+) ([\d.-]+) re W n ([\d.]+) 0 0 ([\d.]+) ([\d.-]+) ([\d.-]+) cm "
                    r"/X(\d+) Do Q")


def _strip(k: int) -> Drawing:
    d = Drawing(f"strip-{k}")
    d.add_polygon(box(0.0, 0.0, 160.0 - 7 * k, 10.0 + k))
    d.add_title([f"demo strip-{k}: a strip of foam, grade {k}, with a title long enough to wrap in two rows"],
                0.0, 22.0 + k)
    d.add_check_bar(0.0, -20.0)
    return d


def _ring() -> Drawing:
    d = Drawing("ring")
    d.add_polygon(circle_polygon(0, 0, 260).difference(circle_polygon(0, 0, 200)))
    d.add_cross(0.0, 0.0, 10.0)
    d.add_title(["demo ring: Ø520 mm, several tiles"], -260, 272)
    d.add_check_bar(-260, -280)
    return d


def _page_boxes(placements) -> list[tuple[float, float, float, float]]:
    return [(p.at[0], p.at[1], p.at[0] + p.window[2] - p.window[0], p.at[1] + p.window[3] - p.window[1])
            for p in placements]


def test_small_drawings_share_pages_without_overlap_each_a_margin_inside():
    strips = [_strip(k) for k in range(12)]
    pages = list(layout(strips[:5] + [_ring()] + strips[5:]))
    nested = [p for page in pages for p in page if p.tile is None]
    assert sorted(p.drawing.label for p in nested) == sorted(d.label for d in strips)    # each once, whole
    assert len({id(page) for page in pages for p in page if p.tile is None}) <= 4           # 12 strips, ≤ 4 pages
    for page in pages:
        boxes = _page_boxes(page)
        for x0, y0, x1, y1 in boxes:                                   # inside the page window
            assert -1e-9 <= x0 and -1e-9 <= y0 and x1 <= WINDOW_MM[0] + 1e-9 and y1 <= WINDOW_MM[1] + 1e-9
        for i in range(len(boxes)):                                    # and apart
            for j in range(i):
                assert box(*boxes[i]).intersection(box(*boxes[j])).area < 1e-9
    for p in nested:                                                   # the content a margin inside its window
        x0, y0, x1, y1 = p.drawing.page_extents()
        wx0, wy0, wx1, wy1 = p.window
        assert min(x0 - wx0, y0 - wy0, wx1 - x1, wy1 - y1) >= MARGIN_MM - 1e-9
        for text, x, y, h in p.texts:                                  # every text whole in it
            assert 0 <= x and x + text_box(text, h)[0] <= wx1 - wx0 and 0 <= y and y + h <= wy1 - wy0


def test_tiles_reassemble_one_to_one_and_hide_no_cut():
    d = _ring()
    tiles = [p for page in layout([d]) for p in page]
    assert len(tiles) > 1 and all(p.tile is not None for p in tiles)
    windows = [box(*p.window) for p in tiles]
    assert all(w.bounds[2] - w.bounds[0] <= WINDOW_MM[0] + 1e-9 and w.bounds[3] - w.bounds[1] <= WINDOW_MM[1] + 1e-9
               for w in windows)
    union = unary_union(windows)
    cut = shapely.MultiLineString([np.vstack([r, r[:1]]) for r in d.paths()[0]])
    assert union.covers(cut)                                           # every cut on some tile
    assert cut.distance(union.boundary) >= MARGIN_MM - 1e-6            # ... a margin inside the tiles' outline
    by_cell = {(p.tile.row, p.tile.col): p.window for p in tiles}
    pairs = 0
    for (r, c), w in by_cell.items():                                  # neighbours share exactly the overlap strip
        if (r, c + 1) in by_cell:
            assert w[2] - by_cell[r, c + 1][0] == pytest.approx(OVERLAP_MM)
            pairs += 1
        if (r + 1, c) in by_cell:
            assert w[1] - by_cell[r + 1, c][3] == pytest.approx(-OVERLAP_MM) or \
                by_cell[r + 1, c][3] - w[1] == pytest.approx(OVERLAP_MM)
            pairs += 1
    assert pairs >= 2


def _page_streams(path: Path) -> list[str]:
    data = path.read_bytes()
    streams = {int(m.group(1)): zlib.decompress(m.group(2)).decode("latin-1") for m in
               re.finditer(rb"(\d+) 0 obj\n<<[^>]*?/Length \d+ /Filter /FlateDecode >>\nstream\n(.*?)\nendstream",
                           data, re.S)}
    contents = [int(n) for n in re.findall(rb"/Contents (\d+) 0 R", data)]
    return [streams[n] for n in contents]


def test_pdf_places_every_part_at_one_to_one_inside_the_window(tmp_path):
    import pypdfium2
    drawings = [_strip(k) for k in range(7)] + [_ring()]
    pages = write_tiled_pdf(drawings, tmp_path / "t.pdf", "demo")
    planned = list(layout([_strip(k) for k in range(7)] + [_ring()]))
    one_each = len(drawings) - 1 + sum(1 for page in planned for p in page if p.tile)      # a page a part
    assert pages == len(planned) < one_each
    k = PT_PER_MM
    left, bottom = 10.0 * k, 28.0 * k
    for content, page in zip(_page_streams(tmp_path / "t.pdf"), planned):
        found = PLACED.findall(content)
        assert len(found) == len(page)
        for (cx, cy, cw, ch, sx, sy, tx, ty, _), p in zip(found, page):
            assert float(sx) == float(sy) == pytest.approx(k, abs=1e-9)          # exactly 72/25.4 pt per mm
            wx0, wy0, wx1, wy1 = p.window
            assert float(cw) / k == pytest.approx(wx1 - wx0, abs=2e-3) and float(ch) / k == pytest.approx(wy1 - wy0, abs=2e-3)
            # the window's lower left corner lands on the clip's: drawing mm → page pt at scale k
            assert float(tx) + wx0 * k == pytest.approx(float(cx), abs=2e-3)
            assert float(ty) + wy0 * k == pytest.approx(float(cy), abs=2e-3)
            assert left - 1e-3 <= float(cx) and float(cx) + float(cw) <= left + WINDOW_MM[0] * k + 2e-3
            assert bottom - 1e-3 <= float(cy) and float(cy) + float(ch) <= bottom + WINDOW_MM[1] * k + 2e-3
        sizes = [float(s) for s in re.findall(r"/F1 ([\d.]+) Tf", content)]
        assert min(sizes) * 0.72 / k >= MIN_TEXT_MM - 1e-3                      # no text under 2.5 mm caps
    findings = {f.check: f for f in check_readers.pdf_findings(tmp_path / "t.pdf", "t.pdf", templates=True)}
    assert all(f.ok for f in findings.values()), findings
    pdf = pypdfium2.PdfDocument(tmp_path / "t.pdf")
    assert check_readers.check_bar_mm(pdf[0]) == pytest.approx(100.0, abs=check_readers.BAR_TOL_MM)


def test_near_duplicate_vertices_dropped_alike_in_dxf_and_svg(tmp_path):
    import ezdxf
    ring = np.array([[0, 0], [50, 0], [50.003, 0.0], [50, 30], [0, 30], [0.002, 0.001]], dtype=float)
    fine = np.column_stack([np.linspace(0, 1, 51), np.zeros(51)])      # 20 µm steps: real geometry, kept
    assert thinned(fine, False) is fine
    kept = thinned(ring, True)
    assert len(kept) == 4 and np.hypot(*np.diff(np.vstack([kept, kept[:1]]), axis=0).T).min() >= MIN_VERTEX_STEP_MM
    arc = [(0.0, 0.0, 0.0), (40.0, 0.0, 0.0), (40.004, 0.0, 0.4142135), (40.004, 40.0, 0.0), (0.0, 40.0, 0.0)]
    thin = thinned_bulges(arc)
    assert len(thin) == 4 and bulge_bounds(thin) == pytest.approx(bulge_bounds(arc), abs=0.01)
    d = Drawing("t")
    d.cut.append(ring)
    d.cut.append([(x, y) for x, y, _ in arc])
    d.arcs[1] = arc
    d.marks.append([(0.0, -5.0), (0.004, -5.0), (30.0, -5.0)])
    write_dxf(d, tmp_path / "t.dxf")
    write_svg(d, tmp_path / "t.svg")
    steps = []
    for e in ezdxf.readfile(tmp_path / "t.dxf").modelspace().query("LWPOLYLINE"):
        pts = np.array([p[:2] for p in e.get_points("xy")])
        pts = np.vstack([pts, pts[:1]]) if e.closed else pts
        steps.append(np.hypot(*np.diff(pts, axis=0).T).min())
    for tag, text in re.findall(r'<(polygon|polyline) points="([^"]*)"', (tmp_path / "t.svg").read_text()):
        pts = np.array([[float(v) for v in p.split(",")] for p in text.split()])
        pts = np.vstack([pts, pts[:1]]) if tag == "polygon" else pts
        steps.append(np.hypot(*np.diff(pts, axis=0).T).min())
    assert len(steps) == 6 and min(steps) >= MIN_VERTEX_STEP_MM


def test_every_piece_named_inside_its_outline_off_the_marks():
    d = Drawing("sheet-03")
    d.add_polygon(circle_polygon(0, 0, 120).difference(circle_polygon(40, 0, 8)))
    d.add_polygon(box(150, -20, 154, 20))                              # 4 mm wide: no 2.5 mm label fits
    d.add_cross(0.0, 0.0, 20.0)
    assert [len(p.interiors) for p in pieces(d)] == [1, 0]
    unfit = name_pieces(d)
    assert len(unfit) == 1 and unfit[0].bounds == pytest.approx((150, -20, 154, 20))
    (text, x, y, h), = d.texts
    label = box(x, y, x + text_box(text, h)[0], y + h)
    assert text == "sheet-03" and h >= MIN_TEXT_MM
    assert pieces(d)[0].contains(label)                                # inside, clear of the hole
    assert not label.intersects(LineString([(-20, 0), (20, 0)])) and not label.intersects(LineString([(0, -20), (0, 20)]))
    name_pieces(d)
    assert len(d.texts) == 1                                           # named once


THIN_WALLS = {"x-slot-array-ellipse.yaml": 1, "graded-trifocal-160mm-foam.yaml": 0}     # 3 mm mirror walls


@pytest.mark.parametrize("recipe", sorted(THIN_WALLS))
def test_recipe_templates_nest_name_and_read_at_2_5_mm(recipe, tmp_path):
    from types import SimpleNamespace

    from antenna_cad.export.template_files import write_templates
    from antenna_cad.pipeline import prepare
    from antenna_cad.spec import load_spec
    spec = load_spec(RECIPES / recipe)
    fab = prepare(spec).fab
    entries = write_templates(SimpleNamespace(name=spec.name), fab, tmp_path)
    drawings = list(fab.drawings)
    pages = entries[-1]["pages"]
    tiles = sum(len(page) for page in layout(drawings))
    assert pages < tiles                                               # parts share pages
    thin = 0
    for d in drawings:
        assert min(h for *_, h in d.texts) >= MIN_TEXT_MM
        unfit = name_pieces(d)                                         # nothing left to add ...
        for piece in unfit:                                            # ... but to a piece too thin for a name
            assert piece.boundary.distance(polylabel(piece, 0.05)) < MIN_TEXT_MM / 2 + CLEARANCE_MM
        thin += len(unfit)
        texts = [box(x, y, x + text_box(t, h)[0], y + h) for t, x, y, h in d.texts]
        for piece in pieces(d):
            assert any(piece.contains(t) for t in texts) or piece in unfit, (d.label, piece.bounds)
    assert thin == THIN_WALLS[recipe]
    findings = {f.check: f for f in check_readers.pdf_findings(tmp_path / entries[-1]["pdf"], entries[-1]["pdf"],
                                                               templates=True)}
    assert all(f.ok for f in findings.values()), findings


def test_layup_assembly_views_name_each_ring_in_its_own_band_and_no_texts_overlap():
    """The sheet assembly views of a Luneburg layup (``contain`` rings overlap their neighbours until
    turned): each ring's name lies in the band of radii that is its alone, no two texts overlap, and the
    title block lists every ring's grade."""
    from antenna_cad.fabrication.rings import fabricate_rings
    from antenna_cad.kinds import luneburg as kind
    from antenna_cad.spec import load_spec
    spec = load_spec(RECIPES / "luneburg-layup-200.yaml")
    layup, _ = kind.plan(spec, kind.synthesize(spec))
    drawings = fabricate_rings(layup, spec.name, drawings=True).drawings
    views = [drawings[i] for i, label in enumerate(drawings.labels) if label.count("-") == 1]
    assert len(views) == layup.count
    for sheet, d in zip(layup.sheets, views):
        boxes = [(t, box(x, y, x + text_box(t, h)[0], y + h)) for t, x, y, h in d.texts]
        tree = shapely.STRtree([b for _, b in boxes])
        pairs = tree.query([b for _, b in boxes], predicate="intersects")
        overlapping = [(boxes[i][0], boxes[j][0]) for i, j in zip(*pairs) if i < j]
        assert not overlapping, (d.label, overlapping)
        title = " ".join(t for t, *_ in d.texts)
        for ring in sheet.rings:
            name = ring.label[-7:]
            assert f"{name} {ring.material.name}" in title
            lo = max([ring.r_inner_mm] + [r.r_outer_mm for r in sheet.rings if r.shell_index < ring.shell_index])
            hi = min([ring.r_outer_mm] + [r.r_inner_mm for r in sheet.rings
                                          if r.shell_index > ring.shell_index and r.r_inner_mm > lo])
            label = next(b for t, b in boxes if t in (name, name[-2:]))
            corners = np.hypot(*np.array(label.exterior.coords).T)
            assert corners.max() <= hi + 1e-6 and (lo == 0 or shapely.distance(label, shapely.Point(0, 0)) >= lo - 1e-6)
