"""The template writers' fast paths: the DXF written into ezdxf's empty document, bulk
number formatting, linear title wrapping, and one Luneburg template per ring."""

from __future__ import annotations

import re

import numpy as np
import pytest
from shapely.geometry import box

from antenna_cad.fabrication.templates import MIN_TEXT_MM, Drawing, dxf_text, text_box, write_dxf
from antenna_cad.fabrication.vector_pdf import _helvetica, num, nums, wrap_text
from tests.ring_cases import two_grade_sphere


def _drawing() -> Drawing:
    d = Drawing("t")
    d.cut.append(np.array([[0.0, 0.0], [150.5, 0.0], [150.5, 80.25], [0.0, 80.0]]))
    d.cut.append([(10, 10), (20, 10), (20, 20)])
    d.arcs[1] = [(10.0, 10.0, 0.5), (20.0, 10.0, 0.0), (20.0, 20.0, -0.25)]
    d.marks.append([(0.0, -5.0), (100.0, -5.0)])
    d.texts.append(("sheet-01-ring-02 εr 1.2 Ø6 ↑", 5.0, 40.0, 3.0))
    return d


def test_dxf_reads_back_with_ezdxf_entity_for_entity(tmp_path):
    import ezdxf
    d = _drawing()
    write_dxf(d, tmp_path / "t.dxf")
    doc = ezdxf.readfile(tmp_path / "t.dxf")
    assert not doc.audit().has_errors and doc.header["$INSUNITS"] == 4
    msp = list(doc.modelspace())
    assert [(e.dxftype(), e.dxf.layer) for e in msp] == [("LWPOLYLINE", "CUT")] * 2 + [("LWPOLYLINE", "MARK"),
                                                                                       ("TEXT", "TEXT")]
    assert [tuple(p) for p in msp[0].get_points("xyb")] == [(0, 0, 0), (150.5, 0, 0), (150.5, 80.25, 0), (0, 80, 0)]
    assert [tuple(p) for p in msp[1].get_points("xyb")] == d.arcs[1]               # true arcs, not the polyline
    assert msp[0].closed and msp[1].closed and not msp[2].closed
    assert msp[3].dxf.text == d.texts[0][0] and tuple(msp[3].dxf.insert)[:2] == (5.0, 40.0)
    handles = [int(e.dxf.handle, 16) for e in doc.entitydb.values()]
    assert len(set(handles)) == len(handles) and int(doc.header["$HANDSEED"], 16) > max(handles)
    assert dxf_text(d) == dxf_text(_drawing())                                     # reproducible


def test_bulk_numbers_match_num():
    rng = np.random.default_rng(3)
    digits = rng.integers(0, 4, size=(4000, 2))                       # up to 3 decimals: exactly as num
    pts = np.round(rng.normal(size=(4000, 2)) * 500 * 10.0**digits) / 10.0**digits
    pts[:4] = [[0.0, -0.0], [-0.0004, 1e-9], [-12.5, 3.0], [7.1, -0.05]]
    got = nums(pts, ",", " ").split()
    assert got == [f"{num(x)},{num(y)}" for x, y in pts.tolist()]
    assert got[:4] == ["0,0", "0,0", "-12.5,3", "7.1,-0.05"]
    fine = rng.normal(size=(4000, 2)) * 500                           # any value: within half a micrometre
    for g, (x, y) in zip(nums(fine, ",", " ").split(), fine.tolist()):
        gx, gy = map(float, g.split(","))
        assert abs(gx - x) <= 0.0005 + 1e-9 and abs(gy - y) <= 0.0005 + 1e-9
        assert not re.search(r"\.\d*0(,|$)|^-0(,|$)|,-0$", g)          # no trailing zeros, no -0


def test_title_wrapping_fills_lines_greedily():
    widths = _helvetica()
    words = "sheet-03-ring-07 grade xps-200 εr 1.234 board thickness 10 mm; dowel holes 3 × Ø6 " * 8
    lines = wrap_text(words.strip(), 120.0, 8.0)
    width = lambda s: sum(widths.get(c, 1000.0) for c in s.replace("ε", "e").replace("×", "x")) * 8.0 / 1000
    assert " ".join(lines) == words.strip()
    for a, b in zip(lines, lines[1:]):
        assert width(a) <= 120.0 < width(f"{a} {b.split(' ')[0]}")
    assert wrap_text("x" * 400, 30.0, 8.0) and all(width(s) <= 30.0 for s in wrap_text("x" * 400, 30.0, 8.0))


def test_luneburg_templates_one_per_ring_hold_every_sector():
    plan, fab = two_grade_sphere(700.0)
    drawings = {d.label: d for d in fab.drawings}
    assert set(drawings) == {s.label for s in plan.sheets} | {r.label for r in plan.rings}
    sectored = [r for r in plan.rings if r.sectors > 1]
    assert sectored
    for ring in sectored:
        d = drawings[ring.label]
        assert len(d.cut) == ring.sectors and len(d.arcs) == ring.sectors              # one outline a sector
        pieces = [p for p in fab.pieces if getattr(p, "ring", None) is ring]
        assert len(pieces) == ring.sectors
        for p in pieces:                                   # its name (or letter) inside its own outline
            outline = p.cut_path(plan.kerf_mm)
            assert any(t in (p.label, p.label.rsplit("-", 1)[1]) and h >= MIN_TEXT_MM
                       and outline.contains(box(x, y, x + text_box(t, h)[0], y + h)) for t, x, y, h in d.texts)
        holes = sum(1 for t, *_ in d.texts if t in ("T", "B"))
        assert holes == sum(h.face != "through" for h in ring.holes)
    for row in fab.rows:                                                  # every cut-list line has its template
        if row.kind.endswith("sector"):
            assert f"(template {row.part.rsplit('-', 1)[0]})" in row.note
        if row.kind != "dowel-rod":
            assert any(row.part == label or row.part.startswith(label + "-") for label in drawings)


def test_luneburg_drawings_built_a_sheet_at_a_time_are_the_same_drawings():
    plan, fab = two_grade_sphere(500.0, pedestal_height_mm=60.0, pedestal_width_mm=300.0)
    drawings = fab.drawings
    listed = list(drawings)
    assert len(drawings) == len(listed) == len(drawings.labels) == len(plan.sheets) * 2 + len(plan.rings)
    assert [d.label for d in listed] == list(drawings.labels)          # labels known before drawing
    for k in (len(listed) - 1, 0, len(listed) // 2, -1):               # random access: same drawing, same lines
        again, first = drawings[k], listed[k]
        assert again.label == first.label and again.texts == first.texts and again.title == first.title
        assert all(np.array_equal(np.asarray(a), np.asarray(b)) for a, b in zip(again.cut, first.cut))
    assert [d.label for d in drawings[1::3]] == [d.label for d in listed[1::3]]
    with pytest.raises(IndexError):
        drawings[len(listed)]


@pytest.mark.parametrize("n", [3, 40])
def test_polylines_short_and_long_format_alike(n):
    pts = np.column_stack([np.linspace(-3, 3, n), np.linspace(0.1234, 9.87651, n)])
    assert nums(pts, " ", " l\n") == "".join(f"{num(x)} {num(y)} l\n" for x, y in pts.tolist())
