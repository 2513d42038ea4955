"""``make-lens check`` (export/check.py) and the workshop-output fixes it measures:
each reader on hand-made files that must pass and on broken ones that must fail, then the command
on a real build, intact and tampered."""

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pypdfium2
import pytest
from shapely.geometry import box
from typer.testing import CliRunner

from antenna_cad.cli import app
from antenna_cad.export import check, check_readers as readers
from antenna_cad.export.manifest import write_manifest
from antenna_cad.export.mesh import write_stl
from antenna_cad.export.report_pdf import A4_INCH, COURIER_ADVANCE_EM, MARGIN, text_layout
from antenna_cad.fabrication.outline import Circle, arc_paths, circle_polygon
from antenna_cad.fabrication.page_layout import texts_by_tile, tile_windows
from antenna_cad.fabrication.templates import A4_MM, WINDOW_MM, Drawing, write_dxf, write_tiled_pdf
from antenna_cad.fabrication.vector_pdf import PT_PER_MM, VectorPdf, text_ops
from antenna_cad.geometry import kernel

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()


def test_manifest_is_strict_json_without_infinity(tmp_path):
    write_manifest(tmp_path, {"figures": {"aperture_mm": math.inf, "x": math.nan, "d": 1.5}})
    text = (tmp_path / "manifest.json").read_text()
    data = json.loads(text, parse_constant=lambda c: pytest.fail(f"bare {c}"))
    assert data["figures"] == {"aperture_mm": None, "x": None, "d": 1.5}


def test_stl_claim_is_what_a_reader_sees(tmp_path):
    """Two cubes sharing an edge: each body closed, the file not (an edge of four faces)."""
    pair = kernel.fuse([kernel.box((-5, -5, -5), (10, 10, 10)), kernel.box((5, -5, 5), (10, 10, 10))])
    mesh = write_stl(pair, tmp_path / "pair.stl", 0.01)
    assert mesh.metadata["bodies"] == 2 and mesh.metadata["bodies_watertight"]
    assert mesh.metadata["watertight"] is False
    assert not readers.stl_closed(readers.read_stl(tmp_path / "pair.stl"))
    one = write_stl(kernel.box((-5, -10, -15), (10, 20, 30)), tmp_path / "one.stl", 0.01)
    tri = readers.read_stl(tmp_path / "one.stl")
    assert one.metadata["watertight"] and readers.stl_closed(tri)
    volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6
    assert volume == pytest.approx(6000.0, rel=1e-6)
    flipped = tri[:, ::-1].copy()
    flipped[0] = tri[0]                                       # one face turned the wrong way
    assert not readers.stl_closed(flipped)


def test_arc_paths_true_circles_and_straight_joints(tmp_path):
    """A disc strip with a dowel hole: the rim and the hole become bulge arcs on the exact tool-path
    circles, the joint line stays straight; the DXF parsed here has the exact outline."""
    kerf, R, rh = 0.5, 300.0, 4.0
    poly = circle_polygon(0, 0, R).intersection(box(-400, -400, 100, 400)).difference(circle_polygon(-50, 20, rh, 0.01))
    path = poly.buffer(kerf / 2, quad_segs=64)
    circles = [Circle(0, 0, R + kerf / 2, 0.002, R), Circle(-50, 20, rh - kerf / 2, 0.01, rh)]
    outer, hole = arc_paths(path, circles)
    assert len(hole) == 4 and all(b != 0 for _, _, b in hole)
    assert sum(1 for _, _, b in outer if b) >= 2 and len(outer) < 300
    d = Drawing("strip")
    d.add_polygon(path, [outer, hole])
    write_dxf(d, tmp_path / "strip.dxf")
    bbox, count = readers.dxf_cut_bounds(readers.dxf_entities(tmp_path / "strip.dxf"))
    y = math.sqrt(R**2 - 100**2)        # the nominal corner: the tool rounds it on a kerf/2 radius
    assert count == 2
    assert bbox == pytest.approx((-R - kerf / 2, -R - kerf / 2, 100 + kerf / 2, R + kerf / 2), abs=0.003)
    assert d.cut_bounds() == pytest.approx(bbox, abs=1e-9)
    joint = [(x, yy) for x, yy, _ in outer if abs(x - (100 + kerf / 2)) < 1e-6]
    assert max(abs(v) for _, v in joint) == pytest.approx(y, abs=0.01)


def _drawing() -> Drawing:
    """A Ø420 mm ring (several tiles), a long title, a label across a tile edge, a far note."""
    d = Drawing("sheet-01")
    d.add_polygon(circle_polygon(0, 0, 210).difference(circle_polygon(0, 0, 150)))
    d.texts.append(("a label that crosses the edge of the first tile window", WINDOW_MM[0] - 260, 0.0, 6.0))
    d.texts.append(("+X far away", 400.0, -5.0, 4.0))
    d.add_title(["demo  sheet-01 of 7: xps, thickness 50 mm, z 0-50 mm, " + "a long note " * 12,
                 "second title line"], -210, 222)
    d.add_check_bar(-210, -240)
    return d


def test_tiled_pdf_text_whole_and_drawing_named_on_every_tile(tmp_path):
    pages = write_tiled_pdf([_drawing()], tmp_path / "t.pdf", "demo")
    assert pages >= 4
    findings = {f.check: f for f in readers.pdf_findings(tmp_path / "t.pdf", "t.pdf", templates=True)}
    assert all(f.ok for f in findings.values()), findings
    pdf = pypdfium2.PdfDocument(tmp_path / "t.pdf")
    texts = [pdf[k].get_textpage().get_text_range() for k in range(len(pdf))]
    assert all("sheet-01 tile" in t for t in texts)                          # the page line names it
    assert any("sheet-01 of 7" in t for t in texts) and any("second title line" in t for t in texts)
    whole = "a label that crosses the edge of the first tile window"
    assert any(whole in t.replace("\r\n", " ") for t in texts)
    assert any("+X far away" in t for t in texts)
    for k in range(len(pdf)):
        assert readers.check_bar_mm(pdf[k]) == pytest.approx(100.0, abs=readers.BAR_TOL_MM)


def test_text_beyond_the_outline_gets_its_own_tile_unmoved():
    """A gauge table set below the outline, past every tile that holds geometry, is printed on a
    tile of its own at its true place, not pushed onto the outline."""
    d = Drawing("gauge")
    d.add_polygon(circle_polygon(0, 0, 60))
    d.texts += [(f"row {k}: z 12.5 mm  y 40.0 mm", -50.0, -400.0 - 8 * k, 4.0) for k in range(3)]
    tiles = [w for _, w in tile_windows(d)]
    placed = texts_by_tile(d, tiles)
    rows = [(text, wx + px, wy + py) for (wx, wy, _, _), texts in zip(tiles, placed)
            for text, px, py, _ in texts]
    assert len(tiles) == 2 and len(rows) == 3
    assert all((x, y) == pytest.approx((-50.0, -400.0 - 8 * k)) for k, (_, x, y) in enumerate(rows))
    outline = circle_polygon(0, 0, 60)
    table_tile = next(t for t, texts in zip(tiles, placed) if texts)
    assert not box(*table_tile).intersects(outline)
    # a row starting inside the first window but running out of it: printed only where it fits
    # whole, unmoved (shifting it back into the first window would lay it over the outline)
    d.texts.append(("y mm   z_ill mm   z_sh mm   (a long gauge row)", 125.0, 0.0, 4.0))
    tiles = [w for _, w in tile_windows(d)]
    spots = [(wx + px, wy + py) for (wx, wy, _, _), texts in zip(tiles, texts_by_tile(d, tiles))
             for text, px, py, _ in texts if text.startswith("y mm")]
    assert spots == [pytest.approx((125.0, 0.0))]


def test_pdf_check_fails_on_text_off_the_page_or_across_a_window(tmp_path):
    k = PT_PER_MM
    with VectorPdf(tmp_path / "bad.pdf", A4_MM, "bad") as pdf:
        pdf.add_page(text_ops("runs past the right edge of the page", (A4_MM[0] - 30) * k, 400, 10))
        pdf.add_page(text_ops("straddles the window", (10 + WINDOW_MM[0] - 10) * k, 400, 5))
    findings = {f.check: f for f in readers.pdf_findings(tmp_path / "bad.pdf", "bad.pdf", templates=True)}
    assert not findings["pdf text inside page"].ok and "pages [1]" in findings["pdf text inside page"].message
    assert not findings["pdf text unclipped"].ok and "[1, 2]" in findings["pdf text unclipped"].message
    assert not findings["pdf check bar"].ok                       # no bar printed on these pages


def test_report_text_layout_fits_the_page():
    usable = (1 - 2 * MARGIN) * A4_INCH[0] * 72
    for longest in (40, 140, 170, 400):
        size, width = text_layout(["x" * longest])
        assert width * COURIER_ADVANCE_EM * size <= usable
        assert size == 6.5 or longest > width or size >= 5.0


@pytest.fixture(scope="module")
def ptfe_build(tmp_path_factory):
    from antenna_cad.pipeline import build
    from antenna_cad.spec import load_spec
    return build(load_spec(ROOT / "recipes" / "ptfe-lens-120mm.yaml"), tmp_path_factory.mktemp("b")).out_dir


def test_check_command_on_a_build_and_on_tampered_copies(ptfe_build, tmp_path):
    ok = runner.invoke(app, ["check", str(ptfe_build)])
    assert ok.exit_code == 0, ok.output
    assert "step solids" in ok.output and "pdf check bar" in ok.output
    findings = check.check_build(ptfe_build)
    assert {f.check for f in findings} >= {"sha256", "step solids", "step names", "step volumes", "stl watertight",
                                           "stl volume", "dxf readers", "dxf outline", "svg size", "pdf page size",
                                           "pdf text inside page", "pdf text unclipped", "pdf check bar"}
    bad = shutil.copytree(ptfe_build, tmp_path / "bad")
    with (bad / "templates" / "profile.dxf").open("a") as fh:
        fh.write("999\nextra\n")
    manifest = json.loads((bad / "manifest.json").read_text())
    manifest["parts"][0]["volume_mm3"] *= 1.01           # beyond the STL chord bound (0.3 % here)
    manifest["parts"][0]["watertight"] = False
    (bad / "manifest.json").write_text(json.dumps(manifest))
    result = runner.invoke(app, ["check", str(bad)])
    assert result.exit_code == 1
    failed = {(f.file, f.check) for f in check.check_build(bad) if not f.ok}
    assert failed == {("templates/profile.dxf", "sha256"), ("templates/profile.dxf", "required"), ("manifest.json", "sha256"),
                      ("manifest.json", "required"),
                      ("ptfe-lens-120mm.step", "step volumes"), ("stl/lens.stl", "stl watertight"),
                      ("stl/lens.stl", "stl volume")}
    (bad / "manifest.json").write_text(json.dumps(manifest).replace('"kerf_mm": 0.0', '"kerf_mm": Infinity'))
    result = runner.invoke(app, ["check", str(bad)])
    assert result.exit_code == 2 and "not strict JSON" in result.output
    assert runner.invoke(app, ["check", str(tmp_path)]).exit_code == 2


@pytest.mark.parametrize("angle", [0.0, 0.3, 1.2, -2.0])
def test_slot_round_ends_are_true_half_circles(angle):
    from antenna_cad.fabrication.templates import bulge_bounds
    from antenna_cad.geometry.slot_layout import slot_bulges, slot_outline
    from shapely.geometry import Polygon
    path = slot_bulges(3.0, 4.0, 10.0, 2.0, angle)
    assert [b for _, _, b in path] == [1.0, 0.0, 1.0, 0.0]
    outline = Polygon(slot_outline(3.0, 4.0, 10.0, 2.0, angle))           # circumscribed, ≤ 0.002 mm out
    assert bulge_bounds(path) == pytest.approx(outline.bounds, abs=0.0025)
    u = np.array([math.sin(angle), math.cos(angle)])
    ends = [np.array([3.0, 4.0]) + k * 4.0 * u for k in (1, -1)]
    for (x, y, _), c in zip(path, [ends[0], ends[0], ends[1], ends[1]]):
        assert math.hypot(x - c[0], y - c[1]) == pytest.approx(1.0, abs=1e-12)
