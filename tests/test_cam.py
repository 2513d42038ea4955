"""Hot-wire toolpaths of taper-cut and stepped layups: every G-code file parsed back by an independent
parser (gcodeparser) and its wire surface held to the lens profile + kerf/2; the checks fail on a
wrong file; refusals name the part; the taper stack verified against the stepped one."""

import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from antenna_cad.cam.machines import kerf_at
from antenna_cad.export.check_cam import CAM_TOL_MM, check_cam, parse_moves
from antenna_cad.export.manifest import _clean
from antenna_cad.pipeline import prepare
from antenna_cad.spec import parse_spec
from antenna_cad.synthesis.checks import DesignError

ROOT = Path(__file__).resolve().parents[1]


def _spec(recipe: str, **fabrication):
    data = yaml.safe_load((ROOT / "recipes" / recipe).read_text())
    data["fabrication"] |= fabrication
    return parse_spec(data)


def _write(plan, spec, folder: Path) -> dict:
    """The cam files of ``plan`` in ``folder`` and the manifest fields the check reads, rounded as
    manifest.json rounds them."""
    for name, text in plan.fab.files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    return _clean({"spec": json.loads(spec.model_dump_json()), "cam": list(plan.fab.cam.entries)})


def _surface_errors(findings) -> list[float]:
    return [float(f.message.split(": ")[1].split(" mm")[0]) for f in findings
            if f.check == "cam_surface" and "cone" in f.message]


@pytest.fixture(scope="module")
def taper(tmp_path_factory):
    spec = _spec("xps-collimator-0.5m-taper.yaml")
    plan = prepare(spec)
    folder = tmp_path_factory.mktemp("taper")
    return spec, plan, folder, _write(plan, spec, folder)


def test_every_taper_file_rebuilds_the_cone_within_tolerance(taper):
    spec, plan, folder, manifest = taper
    findings = check_cam(folder, manifest)
    assert findings and all(f.ok for f in findings), [f for f in findings if not f.ok][:3]
    errors = _surface_errors(findings)
    assert len(errors) == plan.layup.count                  # one cone per sheet, each checked
    assert max(errors) <= CAM_TOL_MM
    hot = [e for e in manifest["cam"] if "faces" in e]
    assert {e["part"] for e in hot} == {p.label for p in plan.fab.pieces}
    for e in hot:
        assert set(e) == {"file", "part", "machine", "axes", "kerf_mm", "feed_mm_min", "seconds",
                          "tower_span_mm", "faces", "center_mm"}
        assert e["faces"][1]["wire_mm"] - e["faces"][0]["wire_mm"] == pytest.approx(
            e["faces"][1]["z_mm"] - e["faces"][0]["z_mm"])


def moved_wire_failures(folder: Path, manifest: dict, name: str) -> list[str]:
    """The failed checks of cam file ``name`` with one contour move a quarter round (the rim's left
    side) moved 0.1 mm along X on both towers: the wire, radially."""
    lines = (folder / name).read_text().splitlines()
    cuts = [i for i, line in enumerate(lines) if line.startswith("G1 ")]
    k = cuts[len(cuts) // 4]
    words = lines[k].split()
    words[1], words[3] = (f"{w[0]}{float(w[1:]) + 0.1:.4f}" for w in (words[1], words[3]))
    bad = folder / "bad"
    (bad / "cam").mkdir(parents=True, exist_ok=True)
    (bad / name).write_text("\n".join(lines[:k] + [" ".join(words)] + lines[k + 1:]) + "\n")
    entry = next(e for e in manifest["cam"] if e["file"] == name)
    return [f.check for f in check_cam(bad, manifest | {"cam": [entry]}) if not f.ok]


def test_a_wire_moved_by_a_tenth_of_a_millimetre_fails_the_check(taper):
    spec, plan, folder, manifest = taper
    assert moved_wire_failures(folder, manifest, "cam/sheet-03.gcode") == ["cam_surface"]


def test_feet_are_straight_cuts_and_dowel_holes_go_to_drilling_files(taper):
    spec, plan, folder, manifest = taper
    foot = next(e for e in manifest["cam"] if e["part"].endswith("-foot"))
    moves, _ = parse_moves((folder / foot["file"]).read_text(), foot["axes"])
    m = np.array(moves)
    assert np.allclose(m[:, :2], m[:, 2:])                                 # XY = UV
    drills = {e["part"] for e in manifest["cam"] if e["file"].endswith("-drill.gcode")}
    assert drills == {p.label for p in plan.fab.pieces}                  # every disc and foot is pinned
    first = (folder / "cam/sheet-01-drill.gcode").read_text()
    depths = [float(w[1:]) for line in first.splitlines() if line.startswith("G81") for w in line.split() if w[0] == "Z"]
    assert depths and all(-50 < d < 0 for d in depths)                    # blind: the vertex cone is in the way


def test_a_disc_in_board_strips_is_cut_to_its_cone_as_a_glued_blank(tmp_path):
    """The Ø1.1 m lens on the built-in 4-axis profile: its towers set as close as the foam allows."""
    spec = _spec("xps-collimator-1.1m.yaml", sheet_thickness_mm=100, edge="taper", joining="dowels", cam={})
    plan = prepare(spec)
    split = {p.sheet_index for p in plan.fab.pieces if p.label.endswith("-a")}
    assert split                                                            # strips on a 600 mm board
    manifest = _write(plan, spec, tmp_path)
    blanks = {e["part"] for e in manifest["cam"] if e["part"].endswith("-blank")}
    assert blanks == {f"sheet-{i:02d}-blank" for i in split}
    findings = check_cam(tmp_path, manifest)
    assert findings and all(f.ok for f in findings), [f for f in findings if not f.ok][:3]
    assert len(_surface_errors(findings)) == plan.layup.count
    assert max(_surface_errors(findings)) <= CAM_TOL_MM
    assert {e["tower_span_mm"] for e in manifest["cam"] if "faces" in e} == {200.0}   # 100 mm foam + 2 × 50


def test_a_piece_longer_than_a_fixed_bow_is_refused_by_name():
    bow = {"kind": "hotwire", "axes": "XYUV", "span_mm": 40, "travel_mm": [1500, 1500]}
    spec = _spec("xps-collimator-0.5m-taper.yaml", cam={"machine": bow})
    with pytest.raises(DesignError, match=r"fabrication.cam: part sheet-\d\d\S*: 50 mm of foam does not fit .*span 40"):
        prepare(spec)


def test_a_piece_beyond_the_travel_is_refused_by_name():
    spec = _spec("xps-collimator-0.5m-taper.yaml", cam={"travel_mm": [400, 400]})
    with pytest.raises(DesignError, match=r"fabrication.cam: part sheet-\d\d.* travel"):
        prepare(spec)


def test_kerf_table_is_interpolated_and_clamped():
    table = ((100.0, 1.6), (300.0, 0.9), (600.0, 0.6))
    assert kerf_at(table, 200.0) == pytest.approx(1.25)
    assert kerf_at(table, 50.0) == 1.6 and kerf_at(table, 900.0) == 0.6


def test_taper_needs_dowels():
    with pytest.raises(ValueError, match="edge: taper needs joining: dowels"):
        _spec("xps-collimator-0.5m-taper.yaml", joining="neck")


def test_taper_stack_beats_the_stepped_stack_unsanded():
    """Fast sub-wavelength model, 100 mm sheets of the Ø0.5 m lens, stepped − ideal: the cones'
    RMS is a quarter of the vertical-edged stack's (measured 2.6° vs 10.8° RMS, docs/guide/cam.md)."""
    from antenna_cad.fullwave.verify import fast_model
    from antenna_cad.asbuilt.revolved import modelled_stats
    from antenna_cad.asbuilt.revolved import revolved
    from antenna_cad.kinds.collimator import _lens
    from antenna_cad.spec.common import VerificationSpec
    rms = {}
    for edge in ("stepped", "taper"):
        spec = _spec("xps-collimator-0.5m.yaml", edge=edge, sheet_thickness_mm=100)
        plan = prepare(spec)
        lens = _lens(spec, plan.design, plan.layup)
        rms[edge] = modelled_stats(lens, fast_model(revolved(lens, plan.layup), VerificationSpec()), "stepped",
                                   lens.feed).rms_deg
    assert rms["taper"] < 0.4 * rms["stepped"]


def test_vertex_cap_gap_is_about_a_quarter_sheet():
    """The chord of the vertex cap lies ≈ t/4 from the profile along the axis (r ∝ √z); every other
    sheet's cone lies far closer."""
    from antenna_cad.kinds.collimator import _lens
    from antenna_cad.asbuilt.taper import Taper
    spec = _spec("xps-collimator-0.5m-taper.yaml", sheet_thickness_mm=100, cam={"tower_span_mm": 200})
    plan = prepare(spec)
    gaps = Taper(_lens(spec, plan.design, plan.layup), plan.layup).largest_gap_mm()
    t = plan.layup.sheet_thickness_mm
    assert 0.1 * t < gaps[0] < 0.25 * t
    assert max(gaps[1:-1]) < gaps[0] / 4


def test_kerf_coupon_cuts_three_squares_and_the_table_reads_them_back():
    from typer.testing import CliRunner

    from antenna_cad.cli import app
    run = CliRunner().invoke(app, ["kerf", "coupon", "--feeds", "100,200,400"])
    assert run.exit_code == 0
    moves, cutting = parse_moves(run.stdout, "XYUV")
    m = np.array(moves)
    assert np.allclose(m[:, :2], m[:, 2:])                                 # straight: XY = UV
    squares = [m[i:i + 8] for i in range(0, len(m), 8)]
    assert len(squares) == 3
    for sq in squares:
        contour = sq[1:7, :2]
        assert np.ptp(contour[:, 0]) == pytest.approx(40) and np.ptp(contour[:, 1]) == pytest.approx(40)
    run = CliRunner().invoke(app, ["kerf", "table", "xps", "100=38.5", "200=39", "400=39.4"])
    assert run.exit_code == 0
    table = yaml.safe_load(run.stdout)["kerf_table"]["xps"]
    assert table == [[100.0, 1.5], [200.0, 1.0], [400.0, pytest.approx(0.6)]]
    spec = _spec("xps-collimator-0.5m-taper.yaml", cam={"kerf_table": {"xps": table}, "feed_mm_min": 200})
    assert {e["kerf_mm"] for e in prepare(spec).fab.cam.entries if "faces" in e} == {1.0}
    assert CliRunner().invoke(app, ["kerf", "table", "xps", "100=41"]).exit_code == 2


def test_box_panels_get_one_router_file_per_board(taper):
    """Each panel's outline pass runs the tool centre one tool radius outside the panel (climb: clockwise
    round it), the last pass leaves tabs, face holes are drilled through, the check passes."""
    spec, plan, folder, manifest = taper
    boards = [e for e in manifest["cam"] if e["file"].startswith("cam/board-")]
    assert {plan.fab.placements[p.label].board_id for p in plan.panels} == \
        {e["file"].removeprefix("cam/board-").removesuffix(".gcode") for e in boards}
    text = (folder / boards[0]["file"]).read_text()
    first = next(p for p in plan.panels if f"({p.label})" in text)
    block = text.split(f"({first.label})")[1].split("\n(")[0]             # the first panel's lines
    m = np.array(parse_moves(block, "XYZ")[0])
    d = spec.fabrication.cam.router.tool_diameter_mm
    w, h = first.face_mm
    assert sorted(np.ptp(m[:, :2], axis=0)) == pytest.approx(sorted((w + d, h + d)), abs=0.01)
    depth = first.thickness_mm + 0.3
    bottom = m[np.isclose(m[:, 2], -depth), :2]
    area = 0.5 * np.sum(bottom[:-1, 0] * bottom[1:, 1] - bottom[1:, 0] * bottom[:-1, 1])
    assert area < 0                                                       # clockwise: climb with M3
    assert m[:, 2].min() == pytest.approx(-depth)
    assert np.any(np.isclose(m[:, 2], -depth + spec.fabrication.cam.router.tab_height_mm + 0.3))   # tabs
    holes = [line for line in block.splitlines() if line.startswith("G81")]
    assert holes and all(f"Z{-depth:g}" in line for line in holes)
    findings = [f for f in check_cam(folder, manifest) if f.file.startswith("cam/board-")]
    assert findings and all(f.ok for f in findings), findings


def test_each_face_of_a_cone_is_compensated_by_the_kerf_at_its_own_speed(taper):
    """Hand computation on sheet-03 with the built-in xps table (100 → 1.6, 300 → 0.9 mm) at 300 mm/min:
    the back (larger) face runs at the feed, the front at feed × its path radius / the back's."""
    from antenna_cad.export.check_cam import _faces
    spec, plan, folder, manifest = taper
    sheet = next(s for s in plan.layup.sheets if s.label == "sheet-03")
    t, r0, r1 = sheet.thickness_mm, sheet.front_radius_mm, sheet.radius_mm
    sec = np.hypot(t, r1 - r0) / t
    k1 = 0.9
    v0 = 300 * (r0 + k1 / 2 * sec) / (r1 + k1 / 2 * sec)
    assert 100 < v0 < 300
    k0 = 1.6 + (v0 - 100) * (0.9 - 1.6) / 200
    entry = next(e for e in manifest["cam"] if e["part"] == "sheet-03")
    assert [f["kerf_mm"] for f in entry["faces"]] == pytest.approx([k0, k1], abs=1e-4)
    moves, cutting = parse_moves((folder / entry["file"]).read_text(), entry["axes"])
    front, back = _faces(entry, [p for p, g in zip(moves, cutting) if g][1:-2])
    assert np.hypot(*front.T) == pytest.approx(r0 + k0 / 2 * sec, abs=2e-3)
    assert np.hypot(*back.T) == pytest.approx(r1 + k1 / 2 * sec, abs=2e-3)


def test_a_rings_hole_is_compensated_inward_by_the_kerf_at_each_faces_speed():
    """Hand computation for a hole's cone (radii 80 → 40 mm over 20 mm, xps table at 300 mm/min): the
    wire runs kerf/2 inside it, so the path radii are r − g, the larger face at the feed."""
    from antenna_cad.cam.hotwire import cone_ring
    from antenna_cad.cam.plan import face_kerfs
    table = ((100.0, 1.6), (300.0, 0.9))
    sec = np.hypot(20.0, 40.0) / 20.0
    g = 0.9 / 2 * sec
    v1 = 300 * (40 - g) / (80 - g)
    k1 = 1.6 + (v1 - 100) * (0.9 - 1.6) / 200
    kerfs = face_kerfs((80.0, 40.0), 20.0, table, 300.0, inward=True)
    assert kerfs == pytest.approx((0.9, k1), abs=1e-12)
    cut = cone_ring("ring-inner", (80.0, 40.0), (0.0, 20.0), 0.9, inward=True, face_kerf_mm=kerfs)
    assert np.hypot(*cut.front.T) == pytest.approx(80 - 0.9 / 2 * sec, abs=1e-9)
    assert np.hypot(*cut.back.T) == pytest.approx(40 - k1 / 2 * sec, abs=1e-9)
