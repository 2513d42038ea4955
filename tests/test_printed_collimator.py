"""The printed single-surface collimator: the lens synthesized at design.refractive_index, its section
in the printer's frame, the uniform lattice inside its skin as closed parts of the analytic volume, the
εr as printed against n², the as-built trace at that εr, and the spec's refusals."""

import math

import numpy as np
import pytest

from antenna_cad.kinds import collimator
from antenna_cad.kinds.printed_package import VOLUME_TOLERANCE
from antenna_cad.kinds.uniform_printed import lattice_body, revolved_envelope
from antenna_cad.printed.body import section_volume_mm3
from antenna_cad.printed.parts import closed_and_oriented, mesh_volume
from antenna_cad.spec import SpecError, load_spec, parse_spec
from antenna_cad.synthesis.collimator import lens_volume_mm3, profile_z_mm

RECIPE = "recipes/xps-collimator-printed-300mm-pla.yaml"
SMALL = {"name": "c", "kind": "collimator", "frequency_ghz": 10, "material": "pla",
         "design": {"diameter_mm": 100, "focal_length_mm": 200, "refractive_index": 1.3},
         "fabrication": {"method": "printed", "cell_mm": 4.5, "bed": {"x_mm": 60, "y_mm": 220, "z_mm": 250}}}


def test_the_lens_is_synthesized_at_n_and_traced_at_the_printed_index():
    spec = load_spec(RECIPE)
    design = collimator.synthesize(spec)
    body = lattice_body(spec)
    assert design.n == pytest.approx(1.3) and body.eps_target == pytest.approx(1.69)
    assert abs(body.eps_printed - body.eps_target) <= spec.tolerances.eps_r_tolerance
    lens = collimator._lens(spec, design, None)
    assert lens.eps_r == pytest.approx(body.eps_printed)
    assert lens.tan_delta == pytest.approx(body.fill * 2.7 * body.filament.tan_delta / body.eps_printed)


def test_the_printed_section_is_the_lens_on_its_flat_face():
    design = collimator.synthesize(load_spec(RECIPE))
    sec = collimator.printed_section(design, 1.2)
    r, z = sec[:-1].T
    assert z[0] == pytest.approx(design.thickness_mm - 1.2) and z[-1] == pytest.approx(-1.2, abs=1e-9)
    assert np.all(np.diff(z) < 0)                                   # each layer inside the one below
    assert np.allclose(design.thickness_mm - 1.2 - z, profile_z_mm(r, design.focal_length_mm, 1.3))
    analytic = lens_volume_mm3(design.focal_length_mm, 1.3, design.thickness_mm)
    assert section_volume_mm3(revolved_envelope(sec)) == pytest.approx(analytic, rel=1e-4)


@pytest.fixture(scope="module")
def small_plan():
    spec = parse_spec(SMALL, "s.yaml")
    design = collimator.synthesize(spec)
    return spec, design, collimator.fabricate(spec, design, None, ())


def test_the_printed_lens_is_closed_parts_of_the_fill_volume(small_plan):
    spec, design, plan = small_plan
    lens = plan.lens
    assert [p.role for p in lens.parts] == ["lens", "lens", "pin"]  # a 60 mm bed across a Ø100 mm lens
    assert lens.cuts == 1 and lens.pins == lens.parts[2].count == 2 and lens.unpinned_cuts == 0
    assert all(closed_and_oriented(p.faces) for p in lens.parts)
    total = sum(mesh_volume(p.vertices, p.faces) for p in lens.parts)
    assert abs(total / lens.reference_volume_mm3 - 1) < VOLUME_TOLERANCE
    body = lattice_body(spec)
    solid = lens_volume_mm3(design.focal_length_mm, 1.3, design.thickness_mm)
    assert body.fill * solid < total < solid                        # a lattice inside a solid skin
    checks = {c.name: c.status for c in plan.checks}
    assert checks["printed_parts_closed"] == checks["printed_volume"] == checks["printed_eps_error"] == "pass"


def test_the_3mf_is_byte_identical_across_builds(small_plan):
    spec, design, plan = small_plan
    again = collimator.fabricate(spec, design, None, ())
    assert again.files["printed/c.3mf"] == plan.files["printed/c.3mf"]
    assert again.files["printed/lens-01.stl"] == plan.files["printed/lens-01.stl"]


@pytest.mark.parametrize("change, expected", [
    ({"design": {"diameter_mm": 100, "focal_length_mm": 200}},
     "design.refractive_index: required with fabrication.method printed"),
    ({"design": SMALL["design"] | {"refractive_index": 1.7}}, "design.refractive_index: n² = 2.89 must be below"),
    ({"design": SMALL["design"] | {"refractive_index": 1.02}}, "design.refractive_index: n² = 1.04 must be ≥ 1.1"),
    ({"fabrication": {"method": "printed", "cell_mm": 5.0}}, "fabrication.cell_mm: must be ≤ λ/(4·√εr)"),
    ({"fabrication": {"method": "printed", "cell_mm": 4.5, "lattice": "gyroid", "min_wall_mm": 0.4, "min_gap_mm": 0.4}},
     "fabrication.lattice: the lens is printed as the cubic lattice"),
    ({"fabrication": {"method": "printed", "cell_mm": 4.5, "orientation": "axis_flat"}},
     "fabrication.orientation: the collimator is printed axis_up"),
    ({"material": "xps"}, "material: a printed lens needs a filament"),
    ({"material": "xps", "fabrication": {"method": "solid"}}, "design.refractive_index: 1.3 ≠ √εr"),
])
def test_illegal_printed_collimators_are_refused_in_one_line(change, expected):
    with pytest.raises(SpecError) as exc:
        parse_spec(SMALL | change, "s.yaml")
    assert len(exc.value.lines) == 1 and expected in exc.value.lines[0], exc.value.lines


def test_the_recipe_reads_back_and_its_cell_is_legal():
    spec = load_spec(RECIPE)
    limit = 299.792458 / spec.frequency_ghz / (4 * math.sqrt(2.7))
    assert spec.fabrication.cell_mm <= limit and spec.design.refractive_index == 1.3
