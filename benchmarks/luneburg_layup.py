"""Build time of large Luneburg sheet layups: 20 layers, 10 mm sheets, D/λ = 25, 50, 100.

Stages without CAD export: synthesis, plan (sheets, rings, sector splits, dowels), fabrication
(pieces, nesting per grade, cut lists), templates (the drawings; ``--write`` also writes their
DXF, SVG and tiled PDF into a temporary folder), verification (ray traces). Prints one row per
size and a sheet-thickness sweep at D/λ = 100 (same rings, more or fewer sheets), with ms per
ring and per piece: linear scaling shows as flat columns.
``--full`` also runs the whole pipeline (STEP, STL; templates only with ``--templates``) for the
D/λ = 100 case.

    PYTHONPATH=. python benchmarks/luneburg_layup.py [--write] [--full [--templates]]
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

from antenna_cad.fabrication.rings import fabricate_rings
from antenna_cad.kinds import luneburg as kind
from antenna_cad.spec import parse_spec


def spec_for(d_over_lambda: float, sheet_mm: float = 10.0, frequency_ghz: float = 10.0, templates: bool = False):
    lam = 299.792458 / frequency_ghz
    return parse_spec({
        "name": "bench", "kind": "luneburg", "frequency_ghz": frequency_ghz, "material": "polystyrene",
        "design": {"diameter_mm": d_over_lambda * lam, "law": "classic", "layers": {"count": 20}},
        "fabrication": {"method": "sheet_layup", "sheet_thickness_mm": sheet_mm, "kerf_mm": 0.5,
                        "board": {"width_mm": 1200, "length_mm": 2400}},
        "outputs": {"templates": templates}})


def run(d_over_lambda: float, sheet_mm: float) -> None:
    spec = spec_for(d_over_lambda, sheet_mm)
    clock = [time.perf_counter()]

    def lap() -> float:
        clock.append(time.perf_counter())
        return clock[-1] - clock[-2]

    design = kind.synthesize(spec)
    t_syn = lap()
    layup, _ = kind.plan(spec, design)
    t_plan = lap()
    fab = kind.fabricate(spec, design, layup, ())
    t_fab = lap()
    drawings = list(fabricate_rings(layup, spec.name, drawings=True).drawings)   # built lazily: all of them here
    t_draw = lap() - t_fab
    pages = write_s = 0.0
    if "--write" in sys.argv:
        from antenna_cad.fabrication.templates import write_dxf, write_svg, write_tiled_pdf
        lap()
        with tempfile.TemporaryDirectory() as out:
            for d in drawings:
                write_dxf(d, Path(out) / f"{d.label}.dxf")
                write_svg(d, Path(out) / f"{d.label}.svg")
            pages = write_tiled_pdf(drawings, Path(out) / "all.pdf", spec.name)
        write_s = lap()
    kind.fabrication_checks(spec, design, layup)
    t_chk = lap()
    kind.verify(spec, design, layup, fab)
    t_ver = lap()
    rings, pieces = len(layup.rings), len(fab.pieces)
    work = t_plan + t_fab
    print(f"{d_over_lambda:5.0f} {sheet_mm:5.0f} {layup.count:6d} {rings:6d} {pieces:7d} {len(drawings):7d} "
          f"{sum(fab.boards.values()):6d} | {t_syn:6.2f} {t_plan:6.2f} {t_fab:6.2f} {t_draw:7.2f} {t_chk:6.2f} "
          f"{t_ver:6.2f} | {1e3 * work / rings:7.3f} {1e3 * work / pieces:7.3f} {1e3 * t_draw / pieces:7.3f}"
          + (f" | {write_s:6.1f} {pages:7.0f} {1e3 * write_s / pieces:7.3f}" if write_s else ""), flush=True)


def full_build(templates: bool) -> None:
    from antenna_cad.pipeline import build
    import antenna_cad.geometry.kernel  # noqa: F401  (import cost kept out of the build time)
    spec = spec_for(100, templates=templates)
    with tempfile.TemporaryDirectory() as out:
        result = build(spec, Path(out))
        files = [p for p in result.out_dir.rglob("*") if p.is_file()]
        size_gb = sum(p.stat().st_size for p in files) / 1e9
    total = sum(result.seconds.values())
    print(f"full build, D/λ 100, 10 mm sheets (templates {'on' if templates else 'off'}), seconds after imports: "
          + ", ".join(f"{k} {v:.1f}" for k, v in result.seconds.items())
          + f"; total {total:.1f}; {len(files)} files, {size_gb:.2f} GB")


if __name__ == "__main__":
    print("  D/λ  t_mm sheets  rings  pieces drawings boards |  synth   plan    fab drawings checks verify"
          " | ms/ring ms/piece draw ms/piece" + (" |  write   pages write ms/piece" if "--write" in sys.argv else ""))
    for dl in (25, 50, 100):
        run(dl, 10.0)
    for t in (20.0, 5.0):
        run(100, t)
    if "--full" in sys.argv:
        full_build(templates="--templates" in sys.argv)
