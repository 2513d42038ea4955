"""Rebuild data/lattice_eps.csv with the gyroid rows extrapolated from the shipped 16 px rows and the
32 px runs (benchmarks/gyroid-32px-runs.jsonl), exactly as tabulate.main computes them."""
import csv, json, sys, datetime as dt
from pathlib import Path
from antenna_cad.printed import tabulate as t
from antenna_cad.printed.homogenization import TABLE
path = Path(t.__file__).parent / "data" / TABLE
lines = path.read_text().splitlines()
header = [l for l in lines if l.startswith("#")]
rows = list(csv.DictReader([l for l in lines if not l.startswith("#")]))
fine = {}
for l in open("benchmarks/gyroid-32px-runs.jsonl"):
    r = json.loads(l)
    fine[(float(r["eps_f"]), float(r["parameter"]), r["polarization"])] = (float(r["n"]), float(r["z_real"]))
out = []
for r in rows:
    if r["lattice"] != "gyroid":
        out.append(r); continue
    key = (float(r["eps_f"]), float(r["parameter"]), r["polarization"])
    if key not in fine:
        sys.exit(f"no 32 px run for {key}")
    deck = {"lattice": "gyroid", "parameter": float(r["parameter"]), "eps_r": float(r["eps_f"]),
            "polarization": r["polarization"]}
    nz = t.extrapolated((float(r["n"]), float(r["z_real"])), fine[key])
    new = t.row(deck, nz=nz)
    out.append({k: str(v) for k, v in new.items()})
res = "; ".join(f"{lat} {' and '.join(map(str, px))} px per cell" + (" (Richardson, first order)" if len(px) > 1 else "")
                for lat, px in t.RESOLUTIONS.items())
head = ["# Effective permittivity of printed lattices: full-wave unit-cell slabs (antenna_cad.fullwave.unitcell),",
        f"# MIT Meep 1.25.0, {res},",
        f"# a/lambda = {t.A_OVER_LAMBDA}, {t.CELLS} cells thick, normal incidence, zeroth Floquet order; S-parameter",
        "# retrieval (Smith et al. 2002).",
        "# eps_index = n^2 (what a lens law uses), eps_r = n/z, mu_r = n z; maxwell_garnett: the shape-aware",
        f"# mixing rule of antenna_cad.printed.homogenization. Generated {dt.date.today().isoformat()} by",
        "# python -m antenna_cad.printed.tabulate"]
text = "\n".join(head + [",".join(t.COLUMNS)] + [",".join(str(r[c]) for c in t.COLUMNS) for r in out]) + "\n"
path.write_text(text)
print("written", len(out))
