"""Polyfocal foci given by their positions (normalised or mm) instead of the seed's angle/distance
parameters: the same seed parameters come out, and a position the case cannot take is refused with
its field and rule."""

from pathlib import Path

import numpy as np
import pytest
import yaml
from pydantic import ValidationError

from antenna_cad.spec.polyfocal import PolyfocalSpec

RECIPES = Path(__file__).parent.parent / "recipes"


def _load(name: str) -> dict:
    return yaml.safe_load((RECIPES / name).read_text())


def _with_foci(raw: dict, foci: list[dict]) -> PolyfocalSpec:
    raw = dict(raw, design=dict(raw["design"], foci=foci))
    return PolyfocalSpec.model_validate(raw)


def test_2d_positions_give_the_seed_parameters():
    """Four-focal 60° lens (f1 = 25, α = 11.7°, f3 = 22.925, β = 27.9°, 2z0 = 10): F at
    (f sin a, −z0 − f cos a) from the entry-surface centre; position_mm = position · unit_mm."""
    raw = _load("polyfocal-fourfocal-2d-60deg.yaml")
    ref = PolyfocalSpec.model_validate(raw).design.resolved_foci()
    z0, unit = raw["design"]["thickness"] / 2, raw["design"]["unit_mm"]
    pts = [(f["f"] * np.sin(np.radians(f["angle_deg"])), -z0 - f["f"] * np.cos(np.radians(f["angle_deg"])))
           for f in ref]
    for foci in ([{"position": list(p)} for p in pts], [{"position_mm": [c * unit for c in p]} for p in pts]):
        got = _with_foci(raw, foci).design.resolved_foci()
        for g, r in zip(got, ref):
            assert g["f"] == pytest.approx(r["f"], abs=1e-12) and g["angle_deg"] == pytest.approx(r["angle_deg"], abs=1e-12)
    assert _with_foci(raw, [{"position": list(p)} for p in pts]).design.foci_count == 4


def test_3d_positions_give_the_seed_parameters():
    """Five-focal "W" lens: F_i = f (sin θ sin γ, sin θ cos γ, −cos θ) from O (2.1); F5 in the xz plane."""
    raw = _load("polyfocal-fivefocal-3d-w.yaml")
    ref = PolyfocalSpec.model_validate(raw).design.resolved_foci()
    pts = []
    for f in ref:
        t, g = np.radians(f["angle_deg"]), np.radians(f["azimuth_deg"])
        pts.append([f["f"] * np.sin(t) * np.sin(g), f["f"] * np.sin(t) * np.cos(g), -f["f"] * np.cos(t)])
    pts[2] = [ref[2]["f"] * np.sin(np.radians(ref[2]["angle_deg"])), 0.0, -ref[2]["f"] * np.cos(np.radians(ref[2]["angle_deg"]))]
    got = _with_foci(raw, [{"position": p} for p in pts]).design.resolved_foci()
    for g, r in zip(got, ref):
        for k in ("f", "angle_deg", "azimuth_deg"):
            assert g[k] == pytest.approx(r[k], abs=1e-10)


@pytest.mark.parametrize("recipe, foci, rule", [
    ("polyfocal-fourfocal-2d-60deg.yaml", [{"f": 25, "position": [1, -30]}, {"f": 22.9, "angle_deg": 27.9}],
     "position replaces f"),
    ("polyfocal-fourfocal-2d-60deg.yaml", [{"position": [1, -30], "position_mm": [1, -30]}, {"f": 22.9, "angle_deg": 27.9}],
     "give position or position_mm, not both"),
    ("polyfocal-fourfocal-2d-60deg.yaml", [{"angle_deg": 3}, {"f": 22.9, "angle_deg": 27.9}], "give f"),
    ("polyfocal-fourfocal-2d-60deg.yaml", [{"position": [1, -30, 0]}, {"f": 22.9, "angle_deg": 27.9}],
     r"design.foci\[0\].position: 2-D foci take \(y, z\)"),
    ("polyfocal-fourfocal-2d-60deg.yaml", [{"position": [-5, -30]}, {"f": 22.9, "angle_deg": 27.9}],
     r"design.foci\[0\].position: give the upper focus"),
    ("polyfocal-fourfocal-2d-60deg.yaml", [{"position": [5, -4]}, {"f": 22.9, "angle_deg": 27.9}],
     r"design.foci\[0\].position: the focus must lie in front of the entry surface"),
    ("polyfocal-fourfocal-2d-60deg.yaml", [{"position": [30, -6]}, {"f": 22.9, "angle_deg": 27.9}],
     r"design.foci\[0\].position: angle to the axis .*rule: < 80°"),
    ("polyfocal-fivefocal-3d-w.yaml", [{"f": 1.0, "angle_deg": 11.66, "azimuth_deg": 10},
                                       {"f": 1.118, "angle_deg": 27.8, "azimuth_deg": -5}, {"position_mm": [5, 3, -200]}],
     r"design.foci\[2\].position_mm: the fifth focus lies in the xz plane"),
])
def test_bad_positions_name_field_and_rule(recipe, foci, rule):
    with pytest.raises(ValidationError, match=rule):
        _with_foci(_load(recipe), foci)
