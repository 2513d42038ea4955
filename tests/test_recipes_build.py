"""Every collimator recipe builds end to end (the Ø1.1 m one is slow: 6 sheets split into strips)."""

import json
from pathlib import Path

import pytest

from antenna_cad.pipeline import build
from antenna_cad.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_large_lens_splits_sheets_into_board_strips(tmp_path):
    spec = load_spec(ROOT / "recipes" / "xps-collimator-1.1m.yaml")
    result = build(spec, tmp_path)
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    assert manifest["figures"]["thickness_mm"] == pytest.approx(257.7, abs=0.5)    # seed-000 §7.4 case 19
    widest = max(manifest["sheets"], key=lambda s: s["radius_mm"])
    assert widest["radius_mm"] == pytest.approx(550.0)
    assert len(widest["pieces"]) >= 2 and widest["joints"]                          # Ø1.1 m ≠ 600 mm board
    joints = [tuple(j["at_mm"] for j in s["joints"]) for s in manifest["sheets"] if s["joints"]]
    assert all(a != b for a, b in zip(joints, joints[1:]))                           # staggered
    assert {c["name"]: c["status"] for c in manifest["checks"]}["edge_margin"] == "warn"
    rows = (result.out_dir / "cutlist.csv").read_text()
    assert "sheet-strip" in rows
