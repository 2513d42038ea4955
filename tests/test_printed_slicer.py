"""Slicer check of printed lenses: the G-code comment parser and extrusion reader on known text, the
check's skip without a slicer, and (PrusaSlicer on the PATH) a small printed sphere's 3MF sliced solid,
its layers and filament against the build's own volume; a slicer past its time limit is stopped."""

import os
import shutil
import time

import pytest

from antenna_cad.kinds.luneburg import fabricate, synthesize
from antenna_cad.kinds.printed_package import SLICER_FACTOR
from antenna_cad.printed.slicer import SlicerError, extrusion_layers, parse_duration, parse_gcode, slice_3mf
from antenna_cad.spec import load_spec, parse_spec

RECIPE = "recipes/luneburg-printed-120mm-pla.yaml"
GCODE = """M83 ; relative E
G1 Z0.2 F720
G1 X10 Y10 F9000
G1 X20 Y10 E0.5
G1 X20 Y20 E0.5 ; extrude
G0 X0 Y0
;LAYER_CHANGE
G1 Z0.4
G1 X5 Y0 E0.2
G1 X5 Y5 E-0.8 ; retract while moving: not an extrusion
; filament used [mm] = 3090.59
; filament used [cm3] = 7.43
; estimated printing time (normal mode) = 1d 1h 44m 55s
"""


def _small_sphere(diameter_mm: float, slicer_check: bool, **fabrication):
    data = load_spec(RECIPE).model_dump(mode="json")
    data["design"]["diameter_mm"] = diameter_mm
    data["fabrication"] |= {"slicer_check": slicer_check} | fabrication
    spec = parse_spec(data)
    return fabricate(spec, synthesize(spec), None, ())


def _check(fab):
    return next(c for c in fab.checks if c.name == "printed_slicer")


def test_gcode_comments_and_durations_are_read():
    got = parse_gcode(GCODE)
    assert got == {"filament_mm": 3090.59, "filament_cm3": 7.43, "time_s": 86400 + 3600 + 44 * 60 + 55, "layers": 1}
    assert parse_duration("44m 5s") == 2645
    with pytest.raises(ValueError):
        parse_duration("soon")
    with pytest.raises(SlicerError, match="filament used"):
        parse_gcode("; nothing here\n")


def test_extrusion_layers_keep_only_extruding_moves():
    layers = extrusion_layers(GCODE)
    assert list(layers) == [0.2, 0.4]
    assert layers[0.2].tolist() == [[[10, 10], [20, 10]], [[20, 10], [20, 20]]]
    assert layers[0.4].tolist() == [[[0, 0], [5, 0]]]
    absolute = "M82\nG1 Z1\nG1 X1 Y0 E1\nG1 X2 Y0 E1\nG1 X3 Y0 E2.5\n"
    assert extrusion_layers(absolute)[1.0].tolist() == [[[0, 0], [1, 0]], [[2, 0], [3, 0]]]


def test_slicer_check_skips_when_off_or_missing(monkeypatch):
    fab = _small_sphere(30.0, False)
    check = _check(fab)
    assert check.status == "skip" and "slicer_check: false" in check.message
    monkeypatch.setenv("PATH", "/nonexistent")
    check = _check(_small_sphere(30.0, True))
    assert check.status == "skip" and "not on the PATH" in check.message
    assert "printed_slicer_time_h" not in fab.figures


def test_a_slicer_past_its_time_limit_is_stopped_and_the_check_warns(monkeypatch, tmp_path):
    slow = tmp_path / "prusa-slicer"
    slow.write_text("#!/bin/sh\nexec sleep 30\n")
    slow.chmod(0o755)
    monkeypatch.setenv("PATH", f"{tmp_path}:{os.environ['PATH']}")
    fab = _small_sphere(30.0, True, slicer_timeout_s=10)
    started = time.monotonic()
    check = _check(fab)
    assert time.monotonic() - started < 25
    assert check.status == "warn" and "did not finish in 10 s" in check.message and "slicer_timeout_s" in check.message
    assert "printed_slicer_time_h" not in fab.figures


needs_slicer = pytest.mark.skipif(shutil.which("prusa-slicer") is None,
                                  reason="prusa-slicer not installed (bash .ci/install-slicer)")


@needs_slicer
@pytest.mark.slow
def test_small_printed_sphere_slices_and_its_filament_matches_ours():
    fab = _small_sphere(40.0, True)
    check = _check(fab)
    assert check.status == "pass", check.message
    assert check.message.startswith("PrusaSlicer-")
    f = fab.figures
    hemisphere_mm = 20.0
    assert abs(f["printed_slicer_layers"] - hemisphere_mm / 0.2) <= 2          # 0.2 mm layers of a 20 mm part
    plate_cm3 = sum(p.volume_mm3 for p in fab.lens.parts) / 1000
    ratio = f["printed_slicer_volume_cm3"] / plate_cm3
    assert 1 / SLICER_FACTOR <= ratio <= SLICER_FACTOR and ratio == pytest.approx(check.value)
    assert f["printed_slicer_time_h"] > f["printed_plate_time_h"]              # travel moves: slower than flow


@needs_slicer
def test_a_broken_3mf_does_not_slice():
    with pytest.raises(SlicerError, match="exit"):
        slice_3mf(b"not a zip", nozzle_mm=0.4, layer_height_mm=0.2, filament_diameter_mm=1.75)
