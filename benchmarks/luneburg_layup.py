"""Build time of a large Luneburg sheet layup: 20 layers, D/λ = 100, 10 mm sheets.

Plan + fabrication (rings, board splitting, nesting per grade, cut list; templates optional)
without CAD export. Prints time per stage and per sheet×ring, for D/λ = 25, 50, 100 to show the
scaling is linear in sheets × rings. Not a unit test:  python benchmarks/luneburg_layup.py
"""

from __future__ import annotations

import sys
import time

from antenna_cad.kinds import luneburg as kind
from antenna_cad.spec import parse_spec


def spec_for(d_over_lambda: float, frequency_ghz: float = 10.0):
    lam = 299.792458 / frequency_ghz
    return parse_spec({
        "name": "bench", "kind": "luneburg", "frequency_ghz": frequency_ghz, "material": "polystyrene",
        "design": {"diameter_mm": d_over_lambda * lam, "law": "classic", "layers": {"count": 20}},
        "fabrication": {"method": "sheet_layup", "sheet_thickness_mm": 10, "kerf_mm": 0.5,
                        "board": {"width_mm": 1200, "length_mm": 2400}},
        "outputs": {"templates": False}})


def run(d_over_lambda: float, drawings: bool) -> None:
    spec = spec_for(d_over_lambda)
    t0 = time.perf_counter()
    design = kind.synthesize(spec)
    t1 = time.perf_counter()
    layup, _ = kind.plan(spec, design)
    t2 = time.perf_counter()
    from antenna_cad.fabrication.rings import fabricate_rings
    fab = fabricate_rings(layup, spec.name, drawings=drawings)
    t3 = time.perf_counter()
    kind.fabrication_checks(spec, design, layup)
    t4 = time.perf_counter()
    n = len(layup.rings)
    print(f"D/λ {d_over_lambda:5.0f}  D {design.diameter_mm:7.1f} mm  sheets {layup.count:4d}  rings {n:5d}  "
          f"pieces {len(fab.pieces):5d}  in-hole {len(fab.in_hole):5d}  boards {sum(fab.boards.values()):4d}  "
          f"synth {t1 - t0:5.2f} s  plan {t2 - t1:5.3f} s  fabricate {t3 - t2:6.2f} s  checks {t4 - t3:5.2f} s  "
          f"= {1e3 * (t3 - t1) / n:5.2f} ms/ring" + ("  (+templates)" if drawings else ""), flush=True)


if __name__ == "__main__":
    drawings = "--templates" in sys.argv
    for dl in (25, 50, 100):
        run(dl, drawings)
