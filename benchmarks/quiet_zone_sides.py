"""GO, the fast model and full-wave side by side on the quiet-zone figures of a lens of the quiet-zone
table (``tests/fullwave_cases.py``, ``ZONE_CASES``), each figure's worst value over the planes and the
plane (mm behind the stack) where it sits: the build's ``quiet-zone`` table, for the ideal lens and the
stack as cut, with the Meep runs of ``benchmarks/quiet_zone_table.py`` (cached: rerunning costs nothing).
Run from the repository root: ``nice -n 15 python -m benchmarks.quiet_zone_sides 1.12 420 1500 40 12
[--resolution 16]`` (εr, D, F, sheet mm, GHz).
"""

from __future__ import annotations

import argparse
from types import SimpleNamespace

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.volume import VolumeField
from antenna_cad.kinds.patterns import Criteria
from antenna_cad.kinds.quiet_zone import lens_quiet_zone
from antenna_cad.spec.common import VerificationSpec
from antenna_cad.quietzone.verdict import ModelPlanes, stack_own
from tests.fullwave_cases import fast_zone_planes, zone_case

FIGURES = ("phase_p2p_deg", "phase_rms_deg", "amplitude_ripple_db", "amplitude_taper_db", "diameter_mm")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("case", nargs=5, type=float)
    ap.add_argument("--resolution", type=float, default=12.0)
    a = ap.parse_args()
    python = solver.meep_python()
    if python is None:
        raise SystemExit(solver.MISSING)
    case = tuple(a.case)
    lens, layup, rl, z_ref, zone = zone_case(case, False)
    lam = lens.wavelength_mm
    settings = VerificationSpec(resolution_px_per_lambda=a.resolution)
    wide = zone_case(case, True)[4]
    z0 = min(zone.distance_mm, wide.distance_mm) - lam
    z1 = max(zone.distance_mm + zone.depth_mm, wide.distance_mm + wide.depth_mm) + lam
    decks = [rl.deck(v, settings, field_map=False, volume_z_mm=(z_ref + z0, z_ref + z1)) for v in ("ideal", "stepped")]
    runs = solver.run_decks(decks, python, 1)
    fw = SimpleNamespace(volume={v: VolumeField.from_run(o) for v, o in zip(("ideal", "stepped"), runs)},
                         volume_model=f"full-wave (Meep, {a.resolution:g} px/λ)")
    variants = [("ideal", lens.faces(lens.n)), ("stepped", rl.sections["stepped"])]
    v = lens_quiet_zone(lens, variants, ("on_axis", *lens.feed), z_ref, Criteria(), fw)
    worst = {(row[0].split(" ")[0], row[1], row[2]): (row[3], row[4]) for row in v.tables[1].rows
             if "/ ideal" not in row[0]}
    print(f"zone Ø{zone.diameter_mm:.0f} × {zone.depth_mm:.0f} mm at {zone.distance_mm:.0f} mm, {len(zone.planes_mm)} planes")
    for variant in ("ideal", "stepped"):
        for fig in FIGURES:
            cells = []
            for key in ("GO", "fast", "full-wave"):
                value, z = worst[(key, variant, fig)]
                cells.append(f"{value:.1f} @ {z:.0f}")
            print(f"{variant:8s} {fig:22s} GO / fast / full-wave: " + " / ".join(cells))
    fast = stack_own(zone, ModelPlanes("fast model", "", fast_zone_planes(lens, rl, z_ref, zone)), "on_axis")[1]
    for row in [r for r in v.tables[1].rows if "/ ideal" in r[0]] + fast:
        print(f"the stack's own (stepped / ideal), {row[0].split(':')[0]}: {row[2]} {row[3]:.1f} @ {row[4]:.0f}")


if __name__ == "__main__":
    main()
