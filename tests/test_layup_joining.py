"""Joining modes of the sheet layup: dowels add nothing in the aperture; necks make one piece per
sheet and are reported with the foam they add inside the aperture cylinder."""

from pathlib import Path

import pytest

from antenna_cad.fabrication.outline import added_in_aperture_mm2, circle_polygon
from antenna_cad.registry import adapter
from antenna_cad.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
BASE = load_spec(ROOT / "recipes" / "xps-collimator-0.5m.yaml")
KIND = adapter("collimator")


def _plan(joining):
    spec = BASE.model_copy(update={"fabrication": BASE.fabrication.model_copy(update={"joining": joining})})
    design = KIND.synthesize(spec)
    layup, panels = KIND.plan(spec, design)
    return spec, design, layup, panels


def test_dowels_mode_adds_nothing_inside_the_aperture():
    spec, design, layup, panels = _plan("dowels")
    fab = KIND.fabricate(spec, design, layup, panels)
    assert all(added_in_aperture_mm2(layup, s) == pytest.approx(0.0, abs=1e-6) for s in layup.sheets)
    small = [s for s in layup.sheets if s.radius_mm < layup.lens_radius_mm]
    for s in small:                                    # disc and foot are separate pieces, both dowelled
        labels = [p.label for p in fab.pieces if p.sheet_index == s.index]
        assert labels == [s.label, f"{s.label}-foot"]
    names = {c.name for c in KIND.fabrication_checks(spec, design, layup)}
    assert "material_in_aperture" not in names
    # dowel holes lie inside every sheet's disc, clear of its edge
    for s in layup.sheets:
        for h in s.lens_dowels:
            assert (h.x_mm**2 + h.y_mm**2) ** 0.5 + h.diameter_mm / 2 < s.radius_mm - 5


def test_neck_mode_is_one_piece_per_sheet_and_reported():
    spec, design, layup, panels = _plan("neck")
    fab = KIND.fabricate(spec, design, layup, panels)
    for s in layup.sheets:
        assert [p.label for p in fab.pieces if p.sheet_index == s.index] == [s.label]
    check = next(c for c in KIND.fabrication_checks(spec, design, layup) if c.name == "material_in_aperture")
    assert check.status == "warn"
    # independent estimate: each neck is the strip between the disc and the aperture circle
    w, R = layup.neck_width_mm, layup.lens_radius_mm
    expected = sum(w * ((s.radius_mm**2 - w * w / 4) ** 0.5 - (R * R - w * w / 4) ** 0.5) * -1 * s.thickness_mm
                   for s in layup.sheets if s.has_neck)
    assert check.value == pytest.approx(abs(expected), rel=0.02)       # arcs at the strip ends ≈ flat


def test_circumscribed_circle_polygon_tolerance():
    poly = circle_polygon(0.0, 0.0, 250.0, tol=0.002)
    radii = [(x * x + y * y) ** 0.5 for x, y in poly.exterior.coords]
    assert min(radii) > 250.0 and max(radii) - 250.0 <= 0.002
