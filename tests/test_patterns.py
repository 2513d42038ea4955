"""Collimator feed limits, Δl, the aut/test_zone spec and the pattern figures in every kind's
verification."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import yaml

from antenna_cad.raytrace.collimator import axial_defocus_limits
from antenna_cad.spec import parse_spec
from antenna_cad.synthesis.collimator import (diameter_for_path_difference_mm, path_difference_approx_mm,
                                              path_difference_mm)

XPS = 1.047


def test_path_difference_2_14_and_2_15():
    """seed-000 §4.3: the built lenses (§5.10) and the round trip of the Table 2.1 rows."""
    assert path_difference_mm(1100.0, 25000.0) == pytest.approx(6.0493, abs=1e-4)
    assert path_difference_approx_mm(1100.0, 25000.0) == pytest.approx(6.05, abs=1e-9)      # D²/8F, §5.10
    assert path_difference_mm(500.0, 4000.0) == pytest.approx(math.hypot(4000.0, 250.0) - 4000.0, rel=1e-12)
    for dl in (0.25, 5.0, 22.5):
        D = diameter_for_path_difference_mm(dl, 5000.0)
        assert path_difference_mm(D, 5000.0) == pytest.approx(dl, rel=1e-10)
        assert path_difference_approx_mm(D, 5000.0) == pytest.approx(dl, rel=5e-3)


@pytest.mark.parametrize("dl, seed, ours", [(5.0, 0.69, 0.708), (10.0, 0.81, 0.818), (20.0, 0.88, 0.888)])
def test_table_2_1_case_12(dl, seed, ours):
    """seed-000 §7.4 case 12: σ < 1 limit at 22.5°, f = 5 m, XPS, λ0 = 3 cm, 10 cm to the AUT plane:
    the seed's values to the digest's ±0.04, and the digest's own exact trace (§5.6) to ±0.002."""
    f = 5000.0
    near, _ = axial_defocus_limits(f, diameter_for_path_difference_mm(dl, f), XPS, 100.0, 30.0, 22.5)
    assert near == pytest.approx(seed, abs=0.04)
    assert near == pytest.approx(ours, abs=0.002)


@pytest.mark.parametrize("f, dl, near, far", [(5000.0, 5.0, 0.69, 1.80), (5000.0, 10.0, 0.81, 1.31),
                                              (5000.0, 20.0, 0.88, 1.15), (10000.0, 10.0, 0.82, 1.28),
                                              (20000.0, 20.0, 0.90, 1.12)])
def test_table_2_1_is_traced_at_33_mm(f, dl, near, far):
    """Where the 0.02 offset comes from: with λ0 = 33 mm (9.1 GHz; the seed's band is "3 cm") the
    same exact trace gives both columns of Table 2.1 to the table's rounding (±0.012 for σ < 1,
    ±0.02 for σ > 1) — at 30 mm σ > 1 is off by up to 0.12."""
    lo, hi = axial_defocus_limits(f, diameter_for_path_difference_mm(dl, f), XPS, 100.0, 33.0, 22.5)
    assert lo == pytest.approx(near, abs=0.012)
    assert hi == pytest.approx(far, abs=0.02)


BASE = {"name": "t", "kind": "collimator", "frequency_ghz": 10.0, "material": "xps",
        "fabrication": {"method": "solid"}}


def _collimator(**design):
    return parse_spec(BASE | {"design": {"diameter_mm": 500, "focal_length_mm": 4000} | design})


def test_aut_spec_shapes():
    assert _collimator(aut={"diameter_mm": 400}).design.aut.span_mm == 400
    rect = _collimator(aut={"width_mm": 300, "height_mm": 400, "pattern": "sum", "taper": 2})
    assert rect.design.aut.span_mm == pytest.approx(500.0)
    assert rect.design.test_zone.amplitude_db == 1.0 and rect.design.test_zone.phase_deg == 11.25
    for bad in ({"diameter_mm": 400, "width_mm": 300}, {"width_mm": 300}, {"diameter_mm": 400, "taper": 4},
                {"diameter_mm": 400, "pattern": "difference"}):
        with pytest.raises(Exception, match="aut"):
            _collimator(aut=bad)
    with pytest.raises(Exception, match="test_zone"):
        _collimator(test_zone={"amplitude_db": -1})


def test_bifocal_aut_plane_is_antenna_x():
    spec = {"name": "b", "kind": "bifocal", "frequency_ghz": 10.0, "material": "xps", "fabrication": {"method": "solid"},
            "design": {"edge_x_mm": 9000, "edge_y_mm": 500, "beam_tilt_deg": 4, "aut": {"diameter_mm": 800}}}
    assert parse_spec(spec).design.aut.diameter_mm == 800
    spec["design"]["aut"]["distance_mm"] = 100
    with pytest.raises(Exception, match="antenna_x_mm"):
        parse_spec(spec)


def test_collimator_verification_carries_the_pattern_figures():
    """The issue's keys in a machined collimator's verification (no layup: the ideal lens only)."""
    from antenna_cad.kinds import collimator as K
    spec = parse_spec(BASE | {"frequency_ghz": 15.0, "material": "ptfe",
                              "design": {"diameter_mm": 120, "focal_length_mm": 300,
                                         "aut": {"diameter_mm": 80, "pattern": "sum"}}})
    design = K.synthesize(spec)
    v = K.verify(spec, design, None, K.fabricate(spec, design, None, ()))
    for feed in ("on_axis", "edge"):
        for k in ("directivity_dbi", "hpbw_deg", "sll_db", "efficiency"):
            assert math.isfinite(v.figures[f"pattern_ideal_{feed}_{k}"])
    D = 10 * math.log10((math.pi * 120 / design.wavelength_mm) ** 2)
    assert D - 0.3 < v.figures["pattern_ideal_on_axis_directivity_dbi"] < D      # near-uniform GO aperture
    assert 0 < v.figures["test_zone_diameter_mm"] <= 1.25 * 120
    assert v.figures["aut_sum_integral_error"] > 0
    assert "aut_difference_integral_error" not in v.figures                       # pattern: sum
    assert v.figures["axial_feed_limit_sigma_near"] < 1 < v.figures["axial_feed_limit_sigma_far"]
    assert {p.name for p in v.plots} >= {"pattern-on-axis", "pattern-edge", "test-zone-amplitude", "aut-patterns"}


def test_luneburg_fan_aperture_reproduces_the_design_taper():
    """The ideal lens's binned GO power density gives the design's taper efficiency (seed-002 §2.5)."""
    from antenna_cad.kinds import luneburg as K
    from antenna_cad.kinds.luneburg_verify import N_RAYS, _lenses
    from antenna_cad.kinds.patterns_luneburg import fan_aperture
    from antenna_cad.radiation.aperture import pattern_figures
    spec = parse_spec(yaml.safe_load((Path(__file__).parents[1] / "recipes" / "luneburg-classic-5.yaml").read_text()))
    design = K.synthesize(spec)
    ideal = _lenses(spec, design, None, np.array([L.eps_r for L in design.layers]))["ideal"]
    assert N_RAYS >= 256
    pf = pattern_figures(fan_aperture(ideal.fan(0.0), design))
    assert pf.efficiency.taper == pytest.approx(design.efficiency_taper, abs=0.01)
    assert pf.efficiency.phase > 0.999


def test_slot_cells_radiate_the_taper_laws_fraction():
    """Cells driven by the taper law (1.1) radiate the fraction η it was designed for (seed-003 §3.2)."""
    from antenna_cad.kinds.patterns_slots import cell_amplitudes
    from antenna_cad.raytrace.slot_array import Cells
    M, p = 40, 12.0
    cells = Cells(np.arange(4) * 10.0, np.tile(np.arange(M) * p, (4, 1)), np.full(4, 7.0), np.full(4, 1.0))
    for law, eta in (("sin", 0.9), ("uniform", 0.8), ("cos_pedestal", 0.95)):
        spec = SimpleNamespace(slots=SimpleNamespace(layout="longitudinal_pair",
                                                     taper=SimpleNamespace(law=law, eta=eta, pedestal=0.3, a0=None, b0=None)),
                               array=SimpleNamespace(length_mm=M * p))
        amp, radiated = cell_amplitudes(spec, cells, "")
        assert radiated == pytest.approx(eta, abs=0.01)
        if law == "sin":
            assert np.argmax(amp[0]) in range(M // 2 - 3, M // 2 + 3)     # |A|² = sin(πy/L): peak mid-guide
