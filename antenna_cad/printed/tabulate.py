"""Regenerate the homogenization table ``data/lattice_eps.csv`` from full-wave unit-cell runs.

``python -m antenna_cad.printed.tabulate [--jobs 1]``: for each lattice, filament permittivity and
fill, one deck for :mod:`antenna_cad.fullwave.unitcell` (a slab of ``CELLS`` cells at a/λ =
``A_OVER_LAMBDA``) per resolution of ``RESOLUTIONS``, run by Debian's Meep interpreter; the retrieved n,
z, εr, μr are written with a provenance header (Meep version, resolutions, a/λ, cells, date). Both
polarizations are run at three fills per lattice to measure the anisotropy.

The cubic rods are Meep blocks, whose interfaces Meep smooths (anisotropic subpixel averaging: second
order in the pixel): 16 px per cell is converged (32 px moves n² by 0.003 at fill 0.4). The gyroid is a
``MaterialGrid``, staircased: its error is first order in the pixel (Farjadpour et al., Opt. Lett. 31,
2972, 2006), so it runs at 16 and 32 px per cell and the table holds the Richardson extrapolation
2·v(32) − v(16) of n and z (a run at 24 px lies on that line: the docs give the figures). About 10
CPU-minutes for the cubic rows, 3 CPU-hours for the gyroid's.
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
RESOLUTIONS = {"cubic": (16,), "gyroid": (16, 32)}   # px per cell; two: first-order Richardson extrapolation
FILAMENTS = (2.7, 4.0)   # PLA; a ceramic-filled filament
COLUMNS = ("lattice", "eps_f", "fill", "parameter", "polarization", "eps_index", "eps_r", "mu_r", "n", "z_real",
           "maxwell_garnett")


def decks(resolution: int, lattices=LATTICES) -> list[dict]:
    out = []
    for lattice in lattices:
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


def _fill_and_mixing_rule(deck: dict) -> tuple[float, float]:
    """A deck's fill and its Maxwell Garnett εeff (the retrieval's branch guess and the table's column)."""
    fill = float(fill_fraction(deck["lattice"], deck["parameter"]))
    return fill, float(maxwell_garnett(deck["lattice"], fill, deck["eps_r"]))


def retrieved(deck: dict, fields: dict) -> tuple[complex, complex]:
    """(n, z) of a deck's slab from its fields (the S-parameter retrieval)."""
    k0 = 2 * np.pi * deck["a_over_lambda"]
    r, t = slab_coefficients(fields, k0, deck["cells"], fields["gap"])
    return retrieve(r, t, k0 * deck["cells"], np.sqrt(_fill_and_mixing_rule(deck)[1]))


def extrapolated(coarse: tuple[complex, complex], fine: tuple[complex, complex]) -> tuple[complex, complex]:
    """(n, z) at zero pixel size from runs at a pixel and at half of it, the error first order in the
    pixel (a staircased interface): 2·fine − coarse."""
    return 2 * fine[0] - coarse[0], 2 * fine[1] - coarse[1]


def row(deck: dict, nz: tuple[complex, complex]) -> dict:
    """A table row of a deck from its retrieved (or extrapolated) n and z."""
    n, z = nz
    fill, mixing_rule = _fill_and_mixing_rule(deck)
    return {"lattice": deck["lattice"], "eps_f": deck["eps_r"], "fill": round(fill, 4), "parameter": deck["parameter"],
            "polarization": deck["polarization"], "eps_index": f"{(n * n).real:.5f}", "eps_r": f"{(n / z).real:.5f}",
            "mu_r": f"{(n * z).real:.5f}", "n": f"{n.real:.5f}", "z_real": f"{z.real:.5f}",
            "maxwell_garnett": f"{mixing_rule:.5f}"}


def meep_version(python: str) -> str:
    """The version of the Meep that ``python`` imports."""
    return subprocess.run([python, "-c", "import meep, sys; sys.stderr.write(meep.__version__)"],
                          capture_output=True, text=True).stderr.strip().splitlines()[-1]


def write_table(path: Path, rows: list[dict], version: str, by: str = "python -m antenna_cad.printed.tabulate") -> None:
    """The table at ``path``: the provenance header (Meep ``version``, resolutions, a/λ, cells, date, the
    command ``by`` which it was made), then ``rows``."""
    resolutions = "; ".join(f"{lat} {' and '.join(map(str, px))} px per cell"
                            + (" (Richardson, first order)" if len(px) > 1 else "")
                            for lat, px in RESOLUTIONS.items())
    header = ["# Effective permittivity of printed lattices: full-wave unit-cell slabs (antenna_cad.fullwave.unitcell),",
              f"# MIT Meep {version}, {resolutions},",
              f"# a/lambda = {A_OVER_LAMBDA}, {CELLS} cells thick, normal incidence, zeroth Floquet order; S-parameter",
              "# retrieval (Smith et al. 2002).",
              "# eps_index = n^2 (what a lens law uses), eps_r = n/z, mu_r = n z; maxwell_garnett: the shape-aware",
              f"# mixing rule of antenna_cad.printed.homogenization. Generated {dt.date.today().isoformat()} by",
              f"# {by}"]
    lines = header + [",".join(COLUMNS)] + [",".join(str(r[c]) for c in COLUMNS) for r in rows]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("-o", "--output", type=Path, default=Path(__file__).parent / "data" / TABLE)
    args = ap.parse_args(argv)
    python = meep_python()
    if python is None:
        print("Meep not found, install python3-meep", file=sys.stderr)
        return 2
    version = meep_version(python)
    runs = [d for lattice, px in RESOLUTIONS.items() for res in px for d in decks(res, (lattice,))]
    with ThreadPoolExecutor(args.jobs) as pool:
        nz = [retrieved(d, f) for d, f in zip(runs, pool.map(lambda d: run_deck(python, d), runs))]
    rows = []
    for lattice, px in RESOLUTIONS.items():
        per_px = [[v for d, v in zip(runs, nz) if d["lattice"] == lattice and d["resolution"] == res] for res in px]
        values = per_px[0] if len(px) == 1 else [extrapolated(c, f) for c, f in zip(*per_px)]
        rows += [row(d, v) for d, v in zip(decks(px[0], (lattice,)), values)]
    write_table(args.output, rows, version)
    return 0


if __name__ == "__main__":
    sys.exit(main())
