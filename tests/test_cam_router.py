"""Router programs of the flat parts of a Luneburg ring layup, one per board as nested on the cut list:
parsed back by an independent parser and held to the parts' outlines ± the tool radius; the check
fails on a move shifted by a tenth of a millimetre; nested rings stay concentric with their hosts."""

import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from antenna_cad.cam.boards import ring_parts
from antenna_cad.export.check_cam import check_cam, parse_moves
from antenna_cad.export.check_router import CAM_TOL_MM
from antenna_cad.pipeline import prepare
from antenna_cad.spec import parse_spec
from antenna_cad.synthesis.checks import DesignError

ROOT = Path(__file__).resolve().parents[1]


def _spec(**cam):
    data = yaml.safe_load((ROOT / "recipes/luneburg-layup-200.yaml").read_text())
    data["fabrication"]["cam"] = cam
    data["outputs"] = {"step": False, "stl": False, "templates": False}
    return parse_spec(data)


@pytest.fixture(scope="module")
def rings(tmp_path_factory):
    spec = _spec()
    plan = prepare(spec)
    folder = tmp_path_factory.mktemp("rings")
    for name, text in plan.fab.files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    return spec, plan, folder, {"spec": json.loads(spec.model_dump_json()), "cam": list(plan.fab.cam.entries)}


def _error(finding) -> float:
    return float(finding.message.split("/2 ")[1].split(" mm")[0])


def test_one_router_file_per_board_every_part_on_it_once(rings):
    spec, plan, folder, manifest = rings
    boards = {pl.board_id for pl in plan.fab.placements.values()}
    assert {e["file"] for e in manifest["cam"] if e["file"].startswith("cam/board-")} == \
        {f"cam/board-{b}.gcode" for b in boards}
    parts = ring_parts(plan.fab, 6.0)
    assert sorted(p.label for ps in parts.values() for p in ps) == sorted(p.label for p in plan.fab.pieces)
    w, length = spec.fabrication.board.width_mm, spec.fabrication.board.length_mm
    for ps in parts.values():
        for i, p in enumerate(ps):
            x0, y0, x1, y1 = p.polygon.bounds
            assert x0 >= 0 and y0 >= 0 and x1 <= w and y1 <= length
            assert all(p.polygon.distance(q.polygon) >= 6.0 for q in ps[i + 1:])   # room for the tool


def test_a_ring_nested_in_a_hole_is_concentric_with_its_host(rings):
    spec, plan, folder, manifest = rings
    assert plan.fab.in_hole
    on_board = {p.label: p.polygon for ps in ring_parts(plan.fab, 6.0).values() for p in ps}
    for guest, host in plan.fab.in_hole.items():
        g, h = on_board[guest].exterior.centroid, on_board[host].exterior.centroid
        assert np.hypot(g.x - h.x, g.y - h.y) < 0.01


def test_every_board_program_rebuilds_its_parts_within_tolerance(rings):
    spec, plan, folder, manifest = rings
    findings = check_cam(folder, manifest)
    assert findings and all(f.ok for f in findings), [f for f in findings if not f.ok][:3]
    assert max(_error(f) for f in findings) <= CAM_TOL_MM
    text = (folder / manifest["cam"][0]["file"]).read_text()
    moves, cutting = parse_moves(text, "XYZ")
    assert min(m[2] for m in moves) == pytest.approx(-spec.fabrication.sheet_thickness_mm - 0.3)
    assert any(line.startswith("G81") for line in text.splitlines())     # registration holes drilled


def test_a_move_shifted_by_a_tenth_of_a_millimetre_fails_the_check(rings):
    spec, plan, folder, manifest = rings
    entry = manifest["cam"][0]
    lines = (folder / entry["file"]).read_text().splitlines()
    cuts = [i for i, line in enumerate(lines) if line.startswith("G1 ")]
    xy = np.array([[float(w[1:]) for w in lines[i].split()[1:3]] for i in cuts])
    steps = np.diff(xy, axis=0)
    k = next(j for j in range(len(cuts) // 2, len(cuts) - 1)   # a move whose path runs along Y: shift it in X
             if abs(steps[j, 1]) > 3 * abs(steps[j, 0]) and abs(steps[j, 1]) > 0.05)
    words = lines[cuts[k + 1]].split()
    words[1] = f"X{float(words[1][1:]) + 0.1:.4f}"
    bad = folder / "bad"
    (bad / "cam").mkdir(parents=True)
    (bad / entry["file"]).write_text("\n".join(lines[:cuts[k + 1]] + [" ".join(words)] + lines[cuts[k + 1] + 1:]) + "\n")
    failed = [f for f in check_cam(bad, manifest | {"cam": [entry]}) if not f.ok]
    assert [f.check for f in failed] == ["cam_router"] and _error(failed[0]) > CAM_TOL_MM


def test_a_tool_wider_than_the_nesting_gap_is_refused_by_field():
    with pytest.raises(DesignError, match=r"fabrication.cam.router.tool_diameter_mm.*Ø12 mm tool"):
        prepare(_spec(router={"tool_diameter_mm": 12}))


def _slot_spec(**router):
    data = yaml.safe_load((ROOT / "recipes/x-slot-array-ellipse.yaml").read_text())
    data["fabrication"]["router"] = {"tool_diameter_mm": 1.0, "pass_depth_mm": 0.5, "feed_mm_min": 600,
                                     "plunge_mm_min": 100, "ramp_length_mm": 5, "tab_width_mm": 2,
                                     "tab_height_mm": 0.4} | router
    data["outputs"] = {"step": False, "stl": False, "templates": False}
    return parse_spec(data)


def test_slot_array_lids_and_plates_are_milled_each_from_its_plate(tmp_path):
    """Every slotted lid and beam-former plate gets a file; every slot and coupling slot is profiled
    inside (one inner contour each), and the check holds each file to its drawing's cut lines."""
    spec = _slot_spec()
    plan = prepare(spec)
    names = {d.label for d in plan.fab.drawings if d.label.startswith(("top-", "plate-"))}
    entries = list(plan.fab.cam.entries)
    assert {e["file"] for e in entries if e["file"].startswith("cam/board-")} == {f"cam/board-{n}.gcode" for n in names}
    for name, text in plan.fab.files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    findings = check_cam(tmp_path, {"spec": json.loads(spec.model_dump_json()), "cam": entries})
    assert len(findings) == len(names) and all(f.ok for f in findings), [f for f in findings if not f.ok][:3]
    lid = next(d for d in plan.fab.drawings if d.label == "top-00")
    text = (tmp_path / "cam/board-top-00.gcode").read_text()
    lines = text.splitlines()
    plunges = [i for i, line in enumerate(lines) if line.startswith("G1 ") and line.endswith("Z0 F100")]
    assert len(plunges) == len(lid.cut)                  # one contour per slot, plus the outline
    tab_z = -spec.fabrication.broad_wall_mm - 0.3 + 0.4 + 0.3
    tabs = [i for i, line in enumerate(lines) if line.startswith("G1 ") and f" Z{tab_z:g} " in line]
    assert tabs and min(tabs) > plunges[-1]              # tabs hold the lid's outline; a slot's waste is cut free


def test_a_slot_narrower_than_the_tool_is_refused_by_part_and_field():
    with pytest.raises(DesignError, match=r"fabrication.router.tool_diameter_mm: part top-\d\d: a hole narrower "
                                          r"than the Ø2 mm tool"):
        prepare(_slot_spec(tool_diameter_mm=2.0))
