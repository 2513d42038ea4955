"""Where the hot wire enters each piece (``fabrication.cam.lead_in_at``): at the foot, on a dowel's
radial line, at a butt joint; read back from the G-code (gcodeparser) and the rebuilt wire still
held to the cone + kerf/2 by the check."""

import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from antenna_cad.export.check_cam import _faces, check_cam, parse_moves
from antenna_cad.pipeline import prepare
from antenna_cad.spec import parse_spec

ROOT = Path(__file__).resolve().parents[1]


def _build(tmp_path, recipe: str, **fabrication):
    data = yaml.safe_load((ROOT / "recipes" / recipe).read_text())
    data["fabrication"] |= fabrication
    data["outputs"] = {"step": False, "stl": False, "templates": False}
    spec = parse_spec(data)
    plan = prepare(spec)
    for name, text in plan.fab.files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    manifest = {"spec": json.loads(spec.model_dump_json()), "cam": list(plan.fab.cam.entries)}
    findings = check_cam(tmp_path, manifest)
    assert findings and all(f.ok for f in findings), [f for f in findings if not f.ok][:3]
    return plan, manifest


def _entry(folder: Path, manifest: dict, part: str) -> tuple[np.ndarray, np.ndarray]:
    """(the first contour point, the lead point) on the back face, lens frame."""
    e = next(x for x in manifest["cam"] if x["part"] == part)
    moves, cutting = parse_moves((folder / e["file"]).read_text(), e["axes"])
    cut = [p for p, g in zip(moves, cutting) if g]
    _, back = _faces(e, cut[:2])
    return back[1], back[0]


def _angle(p) -> float:
    return float(np.degrees(np.arctan2(p[1], p[0])))


def test_the_wire_enters_at_the_foot_and_on_a_dowel_line(tmp_path):
    plan, manifest = _build(tmp_path / "foot", "xps-collimator-0.5m-taper.yaml", cam={"lead_in_at": "foot"})
    for sheet in plan.layup.sheets:
        point, lead = _entry(tmp_path / "foot", manifest, sheet.label)
        assert _angle(point) == pytest.approx(-90, abs=1e-3)              # a cone is turned: exactly there
        assert lead[1] == pytest.approx(point[1] - 10, abs=1e-3)           # the 10 mm lead runs straight down
    plan, manifest = _build(tmp_path / "dowel", "xps-collimator-0.5m-taper.yaml", cam={"lead_in_at": "dowel_line"})
    for sheet in plan.layup.sheets:
        dowel = max(sheet.lens_dowels, key=lambda h: h.y_mm)
        point, lead = _entry(tmp_path / "dowel", manifest, sheet.label)
        assert _angle(point) == pytest.approx(_angle((dowel.x_mm, dowel.y_mm)), abs=1e-3)
        assert _angle(lead) == pytest.approx(_angle(point), abs=1e-3)    # the lead runs out along it
        assert abs(_angle(point) - 90) > 5                                 # not the default top


def test_the_wire_enters_a_sheet_in_strips_at_its_butt_joint(tmp_path):
    plan, manifest = _build(tmp_path, "xps-collimator-1.1m.yaml", sheet_thickness_mm=100, edge="taper",
                            joining="dowels", cam={"lead_in_at": "butt_joint"})
    strips = [p for p in plan.fab.pieces if p.label[-2:] in ("-a", "-b", "-c")]
    assert strips
    joints = {round(x, 3) for p in strips for q in strips if p is not q and p.sheet_index == q.sheet_index
              for line in [p.polygon.boundary.intersection(q.polygon.boundary)] if line.length > 0
              for x, _ in line.coords}
    for part in [p.label for p in strips] + [e["part"] for e in manifest["cam"] if e["part"].endswith("-blank")]:
        point, _ = _entry(tmp_path, manifest, part)
        kerf = next(e["kerf_mm"] for e in manifest["cam"] if e["part"] == part)
        assert min(abs(point[0] - x) for x in joints) < kerf + 0.05, part   # on the joint (± the kerf offset)
