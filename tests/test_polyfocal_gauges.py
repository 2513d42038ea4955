"""Section gauges of the 3-D polyfocal port surfaces: 1:1 templates at x = k·pitch whose working
edge follows the exact synthesized surface, read back against held-out exact points."""

from pathlib import Path

import numpy as np
import pytest
import yaml
from pydantic import ValidationError

from antenna_cad.fabrication.polyfocal_sections import gauge_polygon, gauges_drawing, section_gauges
from antenna_cad.kinds import polyfocal as kp
from antenna_cad.spec.polyfocal import PolyfocalSpec
from antenna_cad.synthesis.polyfocal_design import solve_case

RECIPES = Path(__file__).parent.parent / "recipes"


@pytest.fixture(scope="module")
def w_lens():
    spec = PolyfocalSpec.model_validate(yaml.safe_load((RECIPES / "polyfocal-fivefocal-3d-w.yaml").read_text()))
    return spec, kp.synthesize(spec)


def test_gauges_follow_the_exact_entry_surface(w_lens):
    spec, design = w_lens
    g = spec.design
    gauges, check = section_gauges(design, kp._gauge_grid(spec), 40.0, 20.0)
    assert check.status == "pass" and check.value < 0.02                  # measured 0.013 mm (λ/200 = 0.1 mm)
    entry = [x for x in gauges if x.surface == "entry"]
    assert [x.x_mm for x in entry] == [-80.0, -40.0, 0.0, 40.0, 80.0]
    for gauge in entry:                                                      # exact section by the synthesis
        y = gauge.y_mm[10:-10:20]
        rows = np.column_stack([np.full_like(y, gauge.x_mm), y]) / design.unit_mm
        exact = solve_case(g.case, g.resolved_foci(), g.aperture, g.thickness, "", 0.0, rows).r1[:, 2] * design.unit_mm
        assert np.max(np.abs(gauge.z_mm[10:-10:20] - exact)) < 0.02
        poly = gauge_polygon(gauge)
        assert poly.is_valid and gauge.datum_z_mm == entry[0].datum_z_mm      # one datum plane
        assert gauge.datum_z_mm <= gauge.z_mm.min() - 20.0                   # 20 mm below the surface's extreme
    d = gauges_drawing(gauges, "exit", 40.0, "w")
    assert len(d.cut) == sum(x.surface == "exit" for x in gauges) and d.title


@pytest.mark.slow
def test_gauges_in_the_fabrication_plan(w_lens):
    spec, design = w_lens
    fab = kp.fabricate(spec, design, None, ())
    assert {"gauges-entry", "gauges-exit"} <= {d.label for d in fab.drawings}
    assert [c.name for c in kp.fabrication_checks(spec, design, None)] == ["section_gauge_readback"]


def test_section_pitch_is_for_3d_lenses():
    raw = yaml.safe_load((RECIPES / "polyfocal-fourfocal-2d-60deg.yaml").read_text())
    raw["fabrication"]["section_pitch_mm"] = 20
    with pytest.raises(ValidationError, match="fabrication.section_pitch_mm: section gauges are for 3-D"):
        PolyfocalSpec.model_validate(raw)
