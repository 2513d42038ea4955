"""Foam sheet layup of the graded lens: each slab cut from sheets of its grade,
stacked along the extrusion; the sheet solids read back against the slabs."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from antenna_cad import pipeline
from antenna_cad.export.check import check_build
from antenna_cad.fabrication.graded import slab_pieces
from antenna_cad.fabrication.graded_layup import fabricate_graded_layup, plan_graded_layup
from antenna_cad.materials import LIBRARY
from antenna_cad.spec import SpecError, load_spec, parse_spec

RECIPE = Path(__file__).resolve().parents[1] / "recipes" / "graded-trifocal-160mm-foam.yaml"
BASE = LIBRARY["polystyrene"]


def _design(count: int = 3, unit_mm: float = 100.0):
    """A stand-in lens section (normalised, D = 1): biconvex faces x1 = −0.3 + 0.4 y², x2 = −x1, εr
    falling with |y| — the layup only reads the section, the slab edges and their εr."""
    edges = np.linspace(0.0, 0.45, count + 1)
    return SimpleNamespace(unit_mm=unit_mm, half_aperture=0.45, slab_edges=edges,
                           slab_eps=np.linspace(2.5, 1.8, count), x1=lambda y: -0.3 + 0.4 * np.asarray(y) ** 2,
                           x2=lambda y: 0.3 - 0.4 * np.asarray(y) ** 2, n=lambda y: 1.6 - 0.5 * np.asarray(y))


def test_sheets_stack_the_height_and_carry_their_slab_grade():
    design = _design()
    layup = plan_graded_layup(design, BASE, 3.4, 1.5, 0.0, 600.0, 1200.0)
    pieces = slab_pieces(design)
    assert layup.layers == 3 and layup.count == 3 * len(pieces)
    assert layup.top_layer_mm == pytest.approx(0.4)
    for label, k, poly in pieces:
        mine = [s for s in layup.sheets if s.piece == label]
        z = sorted((s.z_min_mm, s.z_max_mm) for s in mine)
        assert z[0][0] == pytest.approx(-1.7) and z[-1][1] == pytest.approx(1.7)
        assert all(a[1] == b[0] for a, b in zip(z, z[1:]))                      # no gap, no overlap
        assert {s.material.eps_r for s in mine} == {design.slab_eps[k]}
        assert all(s.outline.equals(poly) for s in mine)
    assert [s.index for s in layup.sheets] == list(range(1, layup.count + 1))


def test_exact_multiple_gives_whole_sheets():
    layup = plan_graded_layup(_design(), BASE, 3.4, 1.7, 0.0, 600.0, 1200.0)
    assert layup.layers == 2 and all(s.thickness_mm == pytest.approx(1.7) for s in layup.sheets)


def test_cut_list_templates_and_boards_per_grade():
    design = _design()
    layup = plan_graded_layup(design, BASE, 3.4, 1.5, 0.2, 600.0, 1200.0)
    fab = fabricate_graded_layup(design, layup, "t")
    assert len(fab.rows) == layup.count and len(fab.drawings) == layup.count
    grades = {s.label: s.material.name for s in layup.sheets}
    assert all(r.material == grades[r.part] and r.board.startswith(r.material) for r in fab.rows)
    assert all(("plane to 0.400 mm" in r.note) == r.part.endswith("-sheet-3") for r in fab.rows)
    assert set(fab.boards) == set(grades.values()) and all(n == 1 for n in fab.boards.values())
    mass = sum(poly.area for _, _, poly in slab_pieces(design)) * 3.4 / 1e9 * BASE.density_kg_m3
    assert fab.totals_kg["all"] == pytest.approx(mass, rel=1e-9)
    d = fab.drawings[0]                                  # CUT path: the outline offset by half the kerf
    x0, y0, x1, y1 = d.cut_bounds()
    px0, py0, px1, py1 = layup.sheets[0].outline.bounds
    assert x1 - x0 == pytest.approx(px1 - px0 + 0.2, abs=1e-6) and y1 - y0 == pytest.approx(py1 - py0 + 0.2, abs=1e-6)


def test_small_board_splits_sheets_into_strips():
    design = _design(unit_mm=1000.0)                    # 900 mm tall section on 600 × 1200 boards
    layup = plan_graded_layup(design, BASE, 20.0, 10.0, 0.0, 300.0, 400.0)
    fab = fabricate_graded_layup(design, layup, "t")
    assert any(r.kind == "sheet-strip" for r in fab.rows) and any(fab.joints.values())


def test_sheet_solids_read_back_against_the_slabs():
    from antenna_cad.geometry.graded import build_model
    design = _design()
    layup = plan_graded_layup(design, BASE, 3.4, 1.5, 0.0, 600.0, 1200.0)
    model = build_model(design, BASE, 3.4, layup)
    assert [p.label for p in model.parts] == [s.label for s in layup.sheets]
    assert all(p.material.eps_r == s.eps_r for p, s in zip(model.parts, layup.sheets))
    checks = {c.name: c for c in model.checks}
    assert checks["sheet_slab_volume"].status == "pass" and checks["sheet_slab_volume"].value < 1e-9
    assert checks["sheet_outline"].status == "pass" and checks["sheet_outline"].value < 1e-9
    broken = plan_graded_layup(design, BASE, 3.0, 1.5, 0.0, 600.0, 1200.0)     # sheets 0.4 mm short
    bad = {c.name: c for c in build_model(design, BASE, 3.4, broken).checks}
    assert bad["sheet_slab_volume"].status == "fail"


def test_spec_bounds_and_default_method():
    data = load_spec(RECIPE).model_dump(mode="json")
    for field, value in (("sheet_thickness_mm", 0.1), ("sheet_thickness_mm", 0.0), ("kerf_mm", -1.0),
                         ("kerf_mm", 11.0)):
        with pytest.raises(SpecError, match=field):
            parse_spec(data | {"fabrication": data["fabrication"] | {field: value}})
    with pytest.raises(SpecError, match="sheet_thickness_mm"):
        parse_spec(data | {"fabrication": {"method": "sheet_layup"}})
    solid = parse_spec(data | {"fabrication": {"method": "solid"}})
    assert solid.fabrication.method == "solid"


@pytest.mark.slow
def test_foam_recipe_builds_and_checks(tmp_path):
    res = pipeline.build(load_spec(RECIPE), tmp_path)
    manifest = json.loads((res.out_dir / "manifest.json").read_text())
    assert "fail" not in {c["status"] for c in manifest["checks"]}
    assert manifest["figures"]["sheet_count"] == 30 == len(manifest["sheets"])
    assert all(s["material"].endswith(f"εr {s['eps_r']:.4f}") and s["file"] for s in manifest["sheets"])
    findings = check_build(res.out_dir)
    assert findings and all(f.ok for f in findings)
