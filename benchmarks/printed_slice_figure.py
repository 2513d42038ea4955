"""Slicer preview of a printed lens for the docs: a small printed Luneburg sphere (by default the 120 mm
cubic recipe at another diameter) built with its slicer check, its 3MF sliced by PrusaSlicer, the G-code's
extrusion moves drawn as one layer (the lattice cut by the layer) and a stack of layers.

    PYTHONPATH=. python benchmarks/printed_slice_figure.py [--recipe luneburg-printed-120mm-pla]
        [--diameter 40] [-o docs/images/printed-slice.png]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection  # noqa: E402

from antenna_cad.kinds.luneburg import fabricate, synthesize  # noqa: E402
from antenna_cad.printed.slicer import extrusion_layers, slice_3mf  # noqa: E402
from antenna_cad.spec import load_spec, parse_spec  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--recipe", default="luneburg-printed-120mm-pla", help="a printed Luneburg sphere recipe")
    ap.add_argument("--diameter", type=float, default=40.0)
    ap.add_argument("-o", "--output", default=str(ROOT / "docs" / "images" / "printed-slice.png"))
    args = ap.parse_args(argv)
    data = load_spec(ROOT / "recipes" / f"{args.recipe}.yaml").model_dump(mode="json")
    data["design"]["diameter_mm"] = args.diameter
    data["fabrication"]["slicer_check"] = True
    spec = parse_spec(data)
    fab = fabricate(spec, synthesize(spec), None, ())
    check = next(c for c in fab.checks if c.name == "printed_slicer")
    print(f"{check.status}: {check.message}")
    f = spec.fabrication
    sliced = slice_3mf(fab.files[f"printed/{spec.name}.3mf"], nozzle_mm=f.nozzle_mm,
                       layer_height_mm=f.layer_height_mm, filament_diameter_mm=f.filament_diameter_mm)
    layers = extrusion_layers(sliced.gcode)
    hemi = [z for z in layers if z <= args.diameter / 2 + 1e-6]
    z_show = hemi[len(hemi) // 3]
    fig = plt.figure(figsize=(12, 5.6))
    ax = fig.add_subplot(1, 2, 1)
    seg = layers[z_show]
    ax.add_collection(LineCollection(seg, linewidths=0.6, colors="tab:blue"))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_xlabel("x mm")
    ax.set_ylabel("y mm")
    ax.set_title(f"layer z = {z_show:.1f} mm: {len(seg)} extrusion moves")
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    every = max(1, len(hemi) // 25)
    for z in hemi[::every]:
        s = layers[z]
        pts = [[(a[0], a[1], z), (b[0], b[1], z)] for a, b in s]
        ax3.add_collection3d(Line3DCollection(pts, linewidths=0.3, colors=plt.cm.viridis(z / hemi[-1])))
    xy = seg.reshape(-1, 2)
    lo, hi = xy.min(0) - 5, xy.max(0) + 5
    ax3.set_xlim(lo[0], hi[0])
    ax3.set_ylim(lo[1], hi[1])
    ax3.set_zlim(0, hemi[-1])
    ax3.set_box_aspect((1, 1, hemi[-1] / (hi[0] - lo[0])))
    ax3.view_init(elev=28, azim=-60)
    ax3.set_title(f"every {every}th of {len(hemi)} layers of the hemisphere")
    fig.suptitle(f"{sliced.slicer}: Ø{args.diameter:g} mm printed Luneburg sphere ({f.lattice} lattice), one hemisphere + pin, "
                 f"{sliced.filament_cm3:.2f} cm³ filament, {sliced.time_s / 3600:.2f} h")
    fig.tight_layout()
    Path(args.output).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
