"""End-to-end build of the default recipe, every written file read back by an independent reader."""

import csv
import hashlib
import json
import math
import re
import shutil
from pathlib import Path

import ezdxf
from ezdxf.math import ConstructionArc, bulge_to_arc
import numpy as np
import pytest
import trimesh
from pypdf import PdfReader

from antenna_cad.fabrication.outline import CHORD_TOL_MM
from antenna_cad.pipeline import build
from antenna_cad.spec import load_spec
from antenna_cad.synthesis.collimator import lens_volume_mm3, profile_radius_mm

ROOT = Path(__file__).resolve().parents[1]
RECIPE = ROOT / "recipes" / "xps-collimator-0.5m.yaml"
MM_PT = 72 / 25.4


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("exports")
    spec = load_spec(RECIPE)
    result = build(spec, out)
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    return spec, result, manifest


def test_layout_and_manifest(built):
    spec, result, manifest = built
    d = result.out_dir
    assert d.name == spec.name and manifest["units"] == "mm" and manifest["kind"] == "collimator"
    assert (d / f"{spec.name}.step").exists() and (d / "cutlist.csv").exists()
    assert manifest["figures"]["thickness_mm"] == pytest.approx(311.7, abs=0.5)       # seed-000 §7.4 case 20
    assert [round(s["radius_mm"], 1) for s in manifest["sheets"]] == \
        [97.0, 138.0, 170.1, 197.6, 222.3, 244.9, 250.0]                              # §7.4 case 20
    for entry in manifest["files"]:                                                   # sha256 of every file
        assert hashlib.sha256((d / entry["path"]).read_bytes()).hexdigest() == entry["sha256"]
    listed = {e["path"] for e in manifest["files"]}
    on_disk = {p.relative_to(d).as_posix() for p in d.rglob("*") if p.is_file()} - {"manifest.json"}
    assert listed == on_disk
    assert all(c["status"] != "fail" for c in manifest["checks"])


def test_sheet_containment_and_minimal_excess(built):
    spec, result, manifest = built
    f, n = spec.design.focal_length_mm, 1.047 ** 0.5
    d = manifest["figures"]["thickness_mm"]
    t = spec.fabrication.sheet_thickness_mm
    for s in manifest["sheets"]:
        assert s["z_max_mm"] - s["z_min_mm"] == t                                  # stock thickness
        z = np.linspace(s["z_min_mm"], min(s["z_max_mm"], d), 2001)
        lens_r = profile_radius_mm(z, f, n)
        assert lens_r.max() <= s["radius_mm"] + 1e-9                               # contains the lens
        assert s["radius_mm"] - lens_r.max() < 1e-6                                # no excess
    assert manifest["sheets"][-1]["z_max_mm"] == pytest.approx(d + manifest["figures"]["back_slab_mm"])


def test_step_reimport_labels_and_volumes(built):
    from build123d import import_step
    spec, result, manifest = built
    assembly = import_step(result.out_dir / f"{spec.name}.step")
    labels = {s.label: s for s in _leaves(assembly)}
    expected = {p["label"] for p in manifest["parts"]}
    assert expected <= set(labels), expected - set(labels)
    lens = labels["lens"]
    n, R = 1.047 ** 0.5, 250.0
    analytic = lens_volume_mm3(4000.0, n, manifest["figures"]["thickness_mm"]) + \
        np.pi * R**2 * manifest["figures"]["back_slab_mm"]
    assert lens.volume == pytest.approx(analytic, rel=1e-6)                         # exact revolve
    for part in manifest["parts"]:
        assert labels[part["label"]].volume == pytest.approx(part["volume_mm3"], rel=1e-6)


def _leaves(shape):
    kids = list(getattr(shape, "children", ()) or ())
    if not kids:
        return [shape]
    out = [shape] if shape.label else []
    for k in kids:
        out += _leaves(k)
    return out


def test_stl_watertight_and_volume(built):
    spec, result, manifest = built
    tol = spec.outputs.mesh_tolerance_mm
    for part in manifest["parts"]:
        mesh = trimesh.load(result.out_dir / part["file"], force="mesh")
        assert mesh.is_watertight, part["label"]
        # chord error tol on radii ≥ 10 mm: relative volume deficit ≤ 2·tol/r_min
        assert mesh.volume == pytest.approx(part["volume_mm3"], rel=2 * tol / 10), part["label"]


def test_dxf_audit_layers_and_outline_radius(built):
    spec, result, manifest = built
    kerf = spec.fabrication.kerf_mm
    for s in manifest["sheets"]:
        doc = ezdxf.readfile(result.out_dir / s["file"])
        auditor = doc.audit()
        assert not auditor.has_errors
        assert doc.header["$INSUNITS"] == 4                                            # millimetres
        assert {"CUT", "MARK", "TEXT"} <= {layer.dxf.name for layer in doc.layers}
        cut_pts = np.array([p[:2] for e in doc.modelspace().query("LWPOLYLINE[layer=='CUT']")
                            for p in e.get_points()])
        upper = cut_pts[cut_pts[:, 1] > 0]                                            # lens disc arc only
        radius = np.hypot(upper[:, 0], upper[:, 1]).max()
        assert radius == pytest.approx(s["radius_mm"] + kerf / 2, abs=0.01)
        texts = " ".join(e.dxf.text for e in doc.modelspace().query("TEXT"))
        assert s["label"] in texts and "FEED" in texts and "thickness 50 mm" in texts


def _exact_extremes(path):
    """Vertices plus the exact bounding corners of each bulge arc (ezdxf's paths approximate arcs
    by Béziers, 0.016 mm off on R 250)."""
    out = []
    for (x0, y0, b), (x1, y1, _) in zip(path, path[1:] + path[:1]):
        out.append((x0, y0))
        if b:
            c, a0, a1, r = bulge_to_arc((x0, y0), (x1, y1), b)
            box = ConstructionArc(c, r, math.degrees(a0), math.degrees(a1)).bounding_box
            out += [(box.extmin.x, box.extmin.y), (box.extmax.x, box.extmax.y)]
    return out


def test_svg_is_true_scale(built):
    spec, result, manifest = built
    for s in manifest["sheets"]:
        svg = (result.out_dir / s["file"]).with_suffix(".svg").read_text()
        w, h = (float(v) for v in re.search(r'width="([\d.]+)mm" height="([\d.]+)mm"', svg).groups())
        vx, vy, vw, vh = (float(v) for v in re.search(r'viewBox="([-\d. ]+)"', svg).group(1).split())
        assert (vw, vh) == (w, h)                                                 # 1 user unit = 1 mm
        doc = ezdxf.readfile(result.out_dir / s["file"])
        cut = np.array([p for e in doc.modelspace().query("LWPOLYLINE[layer=='CUT']")
                        for p in _exact_extremes(list(e.get_points("xyb")))])
        svg_pts = np.array([[float(c) for c in pair.split(",")]
                            for pts in re.findall(r'<polygon points="([^"]+)"', svg) for pair in pts.split()])
        # same tool paths as the DXF: the SVG polylines lie within the chord tolerance outside its arcs
        np.testing.assert_allclose(svg_pts.min(axis=0), cut.min(axis=0), atol=CHORD_TOL_MM + 1e-3)
        np.testing.assert_allclose(svg_pts.max(axis=0), cut.max(axis=0), atol=CHORD_TOL_MM + 1e-3)
        # the page (y flipped) holds the cut with at least the 10 mm margin
        assert vx <= cut[:, 0].min() - 10 + 1e-3 and vx + vw >= cut[:, 0].max() + 10 - 1e-3
        assert vy <= -cut[:, 1].max() - 10 + 1e-3 and vy + vh >= -cut[:, 1].min() + 10 - 1e-3


def test_pdf_a4_pages_at_true_scale(built):
    spec, result, manifest = built
    path = result.out_dir / "templates" / f"{spec.name}-templates.pdf"
    reader = PdfReader(path)
    assert len(reader.pages) >= len(manifest["sheets"])
    for page in reader.pages:
        assert float(page.mediabox.width) == pytest.approx(210 * MM_PT, abs=0.01)
        assert float(page.mediabox.height) == pytest.approx(297 * MM_PT, abs=0.01)
        text = page.get_contents().get_data().decode("latin1")
        scale = [float(a) for a, d in re.findall(r"([\d.]+) 0 0 ([\d.]+) [-\d.]+ [-\d.]+ cm", text) if a == d]
        assert scale and all(abs(k - MM_PT) < 1e-8 for k in scale)                   # drawing placed at 1:1
        assert "page" in page.extract_text()
    # an independent renderer (PDFium) draws every page's check bar (black) 100 mm long at 1:1 (longest
    # run of each pixel row); the drawings' own bars are in the DXF/SVG only (the PDF prints its own)
    import pypdfium2
    dpi = 300
    within = 0.25 + 2 * 25.4 / dpi                     # line widths of the end ticks + 2 pixels (0.3 %)
    for page in pypdfium2.PdfDocument(path):
        px = np.asarray(page.render(scale=dpi / 72).to_pil().convert("RGB")).astype(int)
        runs = np.array([_longest_run(row) for row in px.sum(axis=2) < 200]) * 25.4 / dpi
        assert abs(runs.max() - 100.0) <= within


def _longest_run(row: np.ndarray) -> int:
    edges = np.flatnonzero(np.diff(np.concatenate([[0], row.astype(np.int8), [0]])))
    return int((edges[1::2] - edges[::2]).max()) if len(edges) else 0


def test_cutlist_nests_pieces_on_boards(built):
    spec, result, manifest = built
    rows = list(csv.DictReader((result.out_dir / "cutlist.csv").open()))
    pieces = [r for r in rows if r["kind"].startswith("sheet")]
    assert {r["part"] for r in pieces} >= {"sheet-01", "sheet-07"}
    board_w, board_l = spec.fabrication.board.width_mm, spec.fabrication.board.length_mm
    for r in pieces:
        w, h = float(r["width_mm"]), float(r["height_mm"])
        if r["rotated"] == "yes":
            w, h = h, w
        assert float(r["board_x_mm"]) + w <= board_w and float(r["board_y_mm"]) + h <= board_l
    boxes = [r for r in rows if r["kind"] == "box-panel"]
    assert len(boxes) == 5 and all(r["material"] == "plywood" for r in boxes)
    totals = {r["part"]: float(r["mass_kg"]) for r in rows if r["part"].startswith("TOTAL")}
    foam = sum(float(r["mass_kg"]) for r in pieces)
    rounding = 0.0005 * (len(rows) + 1)                # every row is printed to 1 g
    assert totals["TOTAL xps (as cut)"] == pytest.approx(foam, abs=rounding)
    assert totals["TOTAL all"] == pytest.approx(foam + sum(float(r["mass_kg"]) for r in boxes), abs=rounding)
    # independent estimate: finished lens + pedestal ≤ foam as cut ≤ whole stack of full discs
    density = 33.0
    lens = next(p for p in manifest["parts"] if p["label"] == "lens")["volume_mm3"]
    assert lens / 1e9 * density < foam


def test_screws_only_in_the_box(built):
    spec, result, manifest = built
    from antenna_cad.fabrication.box import plan_box
    from antenna_cad.registry import adapter
    kind = adapter("collimator")
    design = kind.synthesize(spec)
    layup, panels = kind.plan(spec, design)
    R, w = layup.lens_radius_mm, layup.pedestal_width_mm
    for panel in panels:
        for h in panel.holes:
            assert abs(h.x_mm) - h.diameter_mm / 2 > w / 2          # beside the foam pedestal
            assert np.hypot(h.x_mm, h.y_mm) > R                      # outside the aperture cylinder
    assert panels == plan_box(layup, wall_mm=12, clearance_mm=0, screw_diameter_mm=4, screw_spacing_mm=150)


def test_rebuild_is_byte_identical_and_atomic(built, tmp_path, monkeypatch):
    spec, result, manifest = built
    again = build(spec, tmp_path)
    second = json.loads((again.out_dir / "manifest.json").read_text())
    assert second["files"] == manifest["files"]
    before = {e["path"]: e["sha256"] for e in second["files"]}

    import antenna_cad.fabrication.templates as templates     # the pipeline imports its writers at use

    def broken(*args, **kwargs):
        raise RuntimeError("interrupted")
    monkeypatch.setattr(templates, "write_tiled_pdf", broken)
    with pytest.raises(RuntimeError):
        build(spec, tmp_path)
    after = {e["path"]: hashlib.sha256((again.out_dir / e["path"]).read_bytes()).hexdigest()
             for e in second["files"]}
    assert after == before                                            # previous build untouched
    assert [p.name for p in tmp_path.iterdir()] == [spec.name]        # no temporary folder left
    shutil.rmtree(tmp_path / spec.name)
