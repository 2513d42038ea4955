"""Regenerate the homogenization table ``data/lattice_eps.csv`` from full-wave unit-cell runs.

``python -m antenna_cad.printed.tabulate [--resolution 16] [--jobs 1]``: for each lattice, filament
permittivity and fill, one deck for :mod:`antenna_cad.fullwave.unitcell` (a slab of ``CELLS`` cells at
a/λ = ``A_OVER_LAMBDA``), run by Debian's Meep interpreter; the retrieved n, z, εr, μr are written
with a provenance header (Meep version, resolution, a/λ, cells, date). Both polarizations are run at
three fills per lattice to measure the anisotropy. Takes about 10 CPU-minutes at 16 px per cell.
"""

from __future__ import annotations

import argparse
import datetime as dt
import json
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from antenna_cad.fullwave import unitcell
from antenna_cad.fullwave.solver import _clean_env, meep_python
from antenna_cad.printed.homogenization import TABLE, maxwell_garnett, retrieve, slab_coefficients
from antenna_cad.printed.lattice import LATTICES, fill_fraction, parameter_for

A_OVER_LAMBDA = 0.12     # cell = λ/8.3: inside the λ/(4√εf) limit for εf ≤ 4.3
CELLS = 2                # slab thickness in cells: n k0 d < π, so the phase branch is never in doubt
FILLS = (0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8)
BOTH_POLARIZATIONS = (0.1, 0.4, 0.7)
FILAMENTS = (2.7, 4.0)   # PLA; a ceramic-filled filament
COLUMNS = ("lattice", "eps_f", "fill", "parameter", "polarization", "eps_index", "eps_r", "mu_r", "n", "z_real",
           "maxwell_garnett")


def decks(resolution: int) -> list[dict]:
    out = []
    for lattice in LATTICES:
        for eps_f in FILAMENTS:
            for fill in FILLS:
                for pol in ("x", "y") if fill in BOTH_POLARIZATIONS else ("x",):
                    out.append({"lattice": lattice, "parameter": round(float(parameter_for(lattice, fill)), 6),
                                "eps_r": eps_f, "cells": CELLS, "resolution": resolution,
                                "a_over_lambda": A_OVER_LAMBDA, "polarization": pol})
    return out


def run_deck(python: str, deck: dict) -> dict:
    with tempfile.TemporaryDirectory(prefix="unitcell-") as tmp:
        src, out = Path(tmp) / "deck.json", Path(tmp) / "out.json"
        src.write_text(json.dumps(deck), encoding="utf-8")
        subprocess.run([python, unitcell.__file__, str(src), str(out)], check=True, capture_output=True, cwd=tmp,
                       env=_clean_env())     # Debian's Meep with Debian's numpy: no venv on its path
        return json.loads(out.read_text(encoding="utf-8"))


def row(deck: dict, fields: dict) -> dict:
    k0 = 2 * np.pi * deck["a_over_lambda"]
    fill = float(fill_fraction(deck["lattice"], deck["parameter"]))
    guess = float(np.sqrt(maxwell_garnett(deck["lattice"], fill, deck["eps_r"])))
    r, t = slab_coefficients(fields, k0, deck["cells"], fields["gap"])
    n, z = retrieve(r, t, k0 * deck["cells"], guess)
    return {"lattice": deck["lattice"], "eps_f": deck["eps_r"], "fill": round(fill, 4), "parameter": deck["parameter"],
            "polarization": deck["polarization"], "eps_index": f"{(n * n).real:.5f}", "eps_r": f"{(n / z).real:.5f}",
            "mu_r": f"{(n * z).real:.5f}", "n": f"{n.real:.5f}", "z_real": f"{z.real:.5f}",
            "maxwell_garnett": f"{guess**2:.5f}"}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--resolution", type=int, default=16)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("-o", "--output", type=Path, default=Path(__file__).parent / "data" / TABLE)
    args = ap.parse_args(argv)
    python = meep_python()
    if python is None:
        print("Meep not found, install python3-meep", file=sys.stderr)
        return 2
    version = subprocess.run([python, "-c", "import meep, sys; sys.stderr.write(meep.__version__)"],
                             capture_output=True, text=True).stderr.strip().splitlines()[-1]
    todo = decks(args.resolution)
    with ThreadPoolExecutor(args.jobs) as pool:
        rows = [row(d, f) for d, f in zip(todo, pool.map(lambda d: run_deck(python, d), todo))]
    header = [f"# Effective permittivity of printed lattices: full-wave unit-cell slabs (antenna_cad.fullwave.unitcell),",
              f"# MIT Meep {version}, {args.resolution} px per cell, a/lambda = {A_OVER_LAMBDA}, {CELLS} cells thick,",
              "# normal incidence, zeroth Floquet order; S-parameter retrieval (Smith et al. 2002).",
              "# eps_index = n^2 (what a lens law uses), eps_r = n/z, mu_r = n z; maxwell_garnett: the shape-aware",
              f"# mixing rule of antenna_cad.printed.homogenization. Generated {dt.date.today().isoformat()} by",
              "# python -m antenna_cad.printed.tabulate"]
    lines = header + [",".join(COLUMNS)] + [",".join(str(r[c]) for c in COLUMNS) for r in rows]
    args.output.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
