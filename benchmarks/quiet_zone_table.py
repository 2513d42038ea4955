"""Regenerate ``tests/data/quiet_zone_table.csv``: the quiet-zone verdict figures of the wide-zone
lenses of ``tests/fullwave_cases.py`` (``ZONE_CASES``) from Meep and from the fast model.

Each lens (a single-surface collimator laid up by the project's planner, dipole feed at its focus):
one Meep run of the ideal lens and one of the stack as cut (:mod:`antenna_cad.fullwave`, cylindrical
m = +1, ``resolution_px_per_lambda``), each recording Er over the (r, z) half-plane that covers both
zones (the lens's default quiet zone, and a wide one, Ø and depth 0.8 D); per zone the stepped lens's
worst figure over the planes and the stack's own phase (stepped over ideal), full-wave and fast model.
Run from the repository root, one run at a time: ``nice -n 15 python -m benchmarks.quiet_zone_table``
(needs python3-meep; ≈ 6 min of solver on 2 cores; cached runs cost nothing).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.volume import VolumeField
from antenna_cad.spec.common import VerificationSpec
from tests.fullwave_cases import ZONE_CASES, fast_zone_planes, zone_case, zone_figures

OUT = Path(__file__).resolve().parents[1] / "tests" / "data" / "quiet_zone_table.csv"
SETTINGS = VerificationSpec(resolution_px_per_lambda=12.0)
FIGURES = ("stepped_phase_p2p_deg", "stepped_phase_rms_deg", "stepped_amplitude_ripple_db",
           "stepped_amplitude_taper_db", "stepped_diameter_mm", "own_phase_p2p_deg", "own_phase_rms_deg")
COLUMNS = ("eps_r", "diameter_mm", "focal_length_mm", "sheet_mm", "frequency_ghz", "zone", "resolution_px_per_lambda",
           "ring_width_max_lambda", "zone_diameter_mm", "zone_distance_mm", "zone_depth_mm", "planes",
           *(f"{m}_{f}" for f in FIGURES for m in ("meep", "fast")), "seconds", "method")


def rows(case, python: str) -> list[list]:
    zones = [zone_case(case, wide) for wide in (False, True)]
    lens, layup, rl, z_ref, _ = zones[0]
    lam = lens.wavelength_mm
    z0 = min(z.distance_mm for *_, z in zones) - lam
    z1 = max(z.distance_mm + z.depth_mm for *_, z in zones) + lam
    decks = [rl.deck(v, SETTINGS, field_map=False, volume_z_mm=(z_ref + z0, z_ref + z1)) for v in ("ideal", "stepped")]
    runs = solver.run_decks(decks, python, 1)
    seconds = sum(float(o["seconds"]) for o in runs)          # the solver's own time (also when cached)
    volume = {v: VolumeField.from_run(o) for v, o in zip(("ideal", "stepped"), runs)}
    ring = float(np.max(np.diff([0.0, *sorted({s.radius_mm for s in layup.sheets})]))) / lam
    out = []
    for (name, (*_, zone)) in zip(("default", "wide"), zones):
        meep = zone_figures(zone, {v: f.planes(z_ref + zone.planes_mm) for v, f in volume.items()})
        fast = zone_figures(zone, fast_zone_planes(lens, rl, z_ref, zone))
        out.append([*case, name, SETTINGS.resolution_px_per_lambda, round(ring, 2),
                    round(zone.diameter_mm, 1), round(zone.distance_mm, 1), round(zone.depth_mm, 1), len(zone.planes_mm),
                    *(round(d[f], 3) for f in FIGURES for d in (meep, fast)), round(seconds, 1),
                    "meep 1.25 cylindrical m=+1, Er over the zone's (r, z) half-plane, benchmarks/quiet_zone_table.py"])
    return out


def main() -> None:
    python = solver.meep_python()
    if python is None:
        raise SystemExit(solver.MISSING)
    table = []
    for case in ZONE_CASES:
        table += rows(case, python)
        for r in table[-2:]:
            print(*r[:-1], flush=True)
        with OUT.open("w", newline="", encoding="utf-8") as fh:          # what finished so far is kept
            w = csv.writer(fh, lineterminator="\n")
            w.writerow(COLUMNS)
            w.writerows(table)


if __name__ == "__main__":
    main()
