"""Regenerate ``tests/data/fullwave_table.csv``: Meep's stepped − ideal phase on axis for the
collimators of ``tests/fullwave_cases.py``.

How each row is computed: a single-surface collimator (seed-000 §1.2) with a dipole feed at its focus,
laid up from ``sheet_mm`` sheets by the project's layup planner (every disc = the lens radius at its far
face, the back slab kept); the ideal lens and the stack as cut run by :mod:`antenna_cad.fullwave`
(MIT Meep, cylindrical, m = +1, Huygens-sheet feed 1.5 λ before the lens, radial PML 4 λ) at
``resolution_px_per_lambda``; phase statistics over 0.5 λ ≤ r ≤ 0.9 R, RMS area-weighted, on the plane
2 λ behind the stack. The thin screen k0(n−1)Δd is listed beside it.
Run from the repository root: ``python -m benchmarks.fullwave_table [jobs]`` (needs python3-meep).
"""

from __future__ import annotations

import csv
import sys
import time
from pathlib import Path

import numpy as np

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.aperture import aperture_stats, difference_stats, phase_stats
from antenna_cad.fullwave.fastmodel import thin_screen_deg
from antenna_cad.spec.common import VerificationSpec
from tests.fullwave_cases import CASES, case_lens

OUT = Path(__file__).resolve().parents[1] / "tests" / "data" / "fullwave_table.csv"
SETTINGS = VerificationSpec(resolution_px_per_lambda=16.0)
COLUMNS = ("eps_r", "diameter_mm", "focal_length_mm", "sheet_mm", "frequency_ghz", "resolution_px_per_lambda",
           "thin_screen_p2p_deg", "thin_screen_rms_deg", "meep_ideal_p2p_deg", "meep_ideal_rms_deg",
           "meep_stepped_p2p_deg", "meep_stepped_rms_deg", "meep_diff_p2p_deg", "meep_diff_rms_deg",
           "cells", "seconds", "method")


def row(case, python: str, jobs: int) -> list:
    lens = case_lens(*case)
    lam, R = lens.wavelength_mm, lens.radius_mm
    decks = [lens.deck(v, SETTINGS, field_map=False) for v in ("ideal", "stepped")]
    t0 = time.perf_counter()
    ideal, stepped = solver.run_decks(decks, python, jobs)
    wall = time.perf_counter() - t0
    r = ideal["r_mm"]
    thin = phase_stats(r, thin_screen_deg(lens.excess_mm("stepped", r), lens.n, lam), lam, R)
    si, ss = (aperture_stats(o["r_mm"], o["er"], lam, R) for o in (ideal, stepped))
    diff = difference_stats(r, stepped["er"], ideal["er"], lam, R)
    return [*case, SETTINGS.resolution_px_per_lambda, *np.round(thin, 3), round(si.p2p_deg, 3), round(si.rms_deg, 3),
            round(ss.p2p_deg, 3), round(ss.rms_deg, 3), *np.round(diff, 3), int(ideal["cells"]), round(wall, 1),
            "meep 1.25 cylindrical m=+1, dipole Huygens sheet, benchmarks/fullwave_table.py"]


def main(jobs: int = 2) -> None:
    python = solver.meep_python()
    if python is None:
        raise SystemExit(solver.MISSING)
    rows = []
    for case in CASES:
        rows.append(row(case, python, jobs))
        print(*rows[-1][:-1], flush=True)
    with OUT.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(COLUMNS)
        w.writerows(rows)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2)
