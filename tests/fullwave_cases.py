"""The collimators of the stored Meep table (tests/data/fullwave_table.csv), built by the project's
own synthesis and layup planner: shared by tests/test_fullwave.py and benchmarks/fullwave_table.py."""

from __future__ import annotations

from antenna_cad.fabrication.section import stepped_section
from antenna_cad.fullwave.lens import RevolvedLens
from antenna_cad.kinds import collimator
from antenna_cad.spec import parse_spec

# (eps_r, diameter_mm, focal_length_mm, sheet_mm, frequency_ghz): εr 1.03–1.3, f/D 2–10 (and the
# seed's f/22.7 lens 1), sheets 10–100 mm
CASES = (
    (1.09, 730.0, 2900.0, 30.0, 9.4),       # the lens of fullwave-notes
    (1.09, 730.0, 2900.0, 60.0, 9.4),
    (1.09, 730.0, 2900.0, 90.0, 9.4),
    (1.047, 500.0, 4000.0, 20.0, 10.0),     # seed-000 §5.10 lens 2
    (1.047, 500.0, 4000.0, 50.0, 10.0),
    (1.047, 500.0, 4000.0, 100.0, 10.0),
    (1.03, 400.0, 4000.0, 100.0, 10.0),
    (1.3, 300.0, 900.0, 10.0, 10.0),
    (1.2, 300.0, 600.0, 20.0, 10.0),
    (1.15, 600.0, 1800.0, 40.0, 10.0),
    (1.047, 1100.0, 25000.0, 50.0, 9.4),    # seed-000 §5.10 lens 1
)


def case_spec(eps_r, diameter_mm, focal_length_mm, sheet_mm, frequency_ghz):
    return parse_spec({"name": "case", "kind": "collimator", "frequency_ghz": frequency_ghz,
                       "material": {"eps_r": eps_r, "tan_delta": 0.0, "density_kg_m3": 30.0},
                       "design": {"diameter_mm": diameter_mm, "focal_length_mm": focal_length_mm},
                       "fabrication": {"method": "sheet_layup", "sheet_thickness_mm": sheet_mm}})


def case_lens(eps_r, diameter_mm, focal_length_mm, sheet_mm, frequency_ghz) -> RevolvedLens:
    spec = case_spec(eps_r, diameter_mm, focal_length_mm, sheet_mm, frequency_ghz)
    design = collimator.synthesize(spec)
    layup, _ = collimator.plan(spec, design)
    lens = collimator._lens(spec, design, layup)
    return RevolvedLens(lens.front_z, lens.back_z, lens.radius_mm, lens.eps_r, frequency_ghz, lens.feed[0],
                        {"stepped": stepped_section(layup, lens.n)})
