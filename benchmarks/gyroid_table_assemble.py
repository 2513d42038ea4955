"""Rebuild the homogenization table (antenna_cad/printed/data/lattice_eps.csv) from recorded runs, without
Meep: the shipped cubic rows are kept, and each gyroid row is the Richardson extrapolation of its run at
16 px per cell (benchmarks/gyroid-16px-runs.jsonl) and at 32 (benchmarks/gyroid-32px-runs.jsonl), one
JSON line per deck as ``tabulate.row`` writes it. ``python -m antenna_cad.printed.tabulate`` computes the
same table from scratch in about 3 CPU-hours."""
import csv
import json
import sys
from pathlib import Path

from antenna_cad.fullwave.solver import meep_python
from antenna_cad.printed import tabulate
from antenna_cad.printed.homogenization import TABLE

HERE = Path(__file__).parent


def runs(name: str) -> dict:
    """(εf, parameter, polarization) → (n, z) of a run file."""
    out = {}
    for line in (HERE / name).read_text(encoding="utf-8").splitlines():
        run = json.loads(line)
        out[(float(run["eps_f"]), float(run["parameter"]), run["polarization"])] = (float(run["n"]), float(run["z_real"]))
    return out


def main() -> int:
    path = Path(tabulate.__file__).parent / "data" / TABLE
    shipped = csv.DictReader(line for line in path.read_text(encoding="utf-8").splitlines() if not line.startswith("#"))
    coarse, fine = runs("gyroid-16px-runs.jsonl"), runs("gyroid-32px-runs.jsonl")
    if set(coarse) != set(fine):
        sys.exit(f"runs missing at 32 px: {sorted(set(coarse) - set(fine))}")
    rows = [r for r in shipped if r["lattice"] != "gyroid"]
    for key in sorted(coarse):
        deck = {"lattice": "gyroid", "parameter": key[1], "eps_r": key[0], "polarization": key[2]}
        rows.append(tabulate.row(deck, tabulate.extrapolated(coarse[key], fine[key])))
    tabulate.write_table(path, rows, tabulate.meep_version(meep_python()),
                         by="benchmarks/gyroid_table_assemble.py from the runs recorded beside it")
    print(f"{path}: {len(rows)} rows")
    return 0


if __name__ == "__main__":
    sys.exit(main())
