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


# Wide-zone lenses of the quiet-zone table (tests/data/quiet_zone_table.csv): rings 1–5 λ wide, εr to 1.3
ZONE_CASES = (
    (1.3, 300.0, 900.0, 30.0, 10.0),
    (1.2, 300.0, 600.0, 40.0, 10.0),
    (1.15, 400.0, 1200.0, 50.0, 10.0),
    (1.1, 400.0, 1600.0, 60.0, 10.0),
    (1.047, 500.0, 4000.0, 100.0, 10.0),    # seed-000 §5.10 lens 2, 100 mm sheets
    (1.12, 420.0, 1500.0, 25.0, 12.0),      # the lens the independent Meep set-up checked, and auto's candidates
    (1.12, 420.0, 1500.0, 40.0, 12.0),
    (1.12, 420.0, 1500.0, 60.0, 12.0),
)
WIDE_ZONE = 0.8                             # the wide zone: this fraction of the lens diameter, as deep


def zone_case(case, wide: bool):
    """(lens, layup, revolved lens, back of the stack, zone) of a table case: the lens's default quiet
    zone, or (``wide``) Ø and depth 0.8 D at its default distance."""
    import numpy as np
    from antenna_cad.asbuilt.lens import lens_zone
    from antenna_cad.asbuilt.revolved import revolved
    from antenna_cad.spec.common import TestZoneSpec
    spec = case_spec(*case)
    design = collimator.synthesize(spec)
    layup, _ = collimator.plan(spec, design)
    lens = collimator._lens(spec, design, layup)
    rl = revolved(lens, layup)
    z_ref = rl.plane_z_mm(0.0)
    zone = lens_zone(lens, z_ref)
    if wide:
        d = WIDE_ZONE * 2 * lens.radius_mm
        zone = lens_zone(lens, z_ref, TestZoneSpec(diameter_mm=d, depth_mm=d), None)
    assert np.isfinite(z_ref)
    return lens, layup, rl, z_ref, zone


def fast_zone_planes(lens, rl, z_ref: float, zone) -> dict:
    """variant → [(r, E) per plane]: the fast model's ideal lens and stepped stack over ``zone``."""
    from antenna_cad.quietzone.volume import fast_fields, radii_mm
    rho = radii_mm(max(lens.radius_mm, zone.diameter_mm / 2), lens.wavelength_mm)
    fields = fast_fields(rl, z_ref, zone.planes_mm, rho, ["ideal", "stepped"])
    return {v: [(rho, e) for e in planes] for v, planes in fields.items()}


def zone_figures(zone, planes: dict) -> dict:
    """The verdict figures over the zone: the stepped lens's worst per figure, and the stack's own phase
    (stepped over ideal) p-p and RMS."""
    from antenna_cad.quietzone.verdict import FIGURES, judged
    out = {f"stepped_{f}": judged(zone, planes["stepped"]).worst(f)[0] for f in FIGURES}
    own = judged(zone, [(r, e / ei) for (r, e), (_, ei) in zip(planes["stepped"], planes["ideal"])])
    return out | {f"own_{f}": own.worst(f)[0] for f in ("phase_p2p_deg", "phase_rms_deg")}
