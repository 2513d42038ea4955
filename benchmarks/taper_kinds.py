"""Stepped vs taper-cut layups beyond the collimator, measured (docs/guide/cam.md).

    python benchmarks/taper_kinds.py

For the bifocal (recipes/bifocal-nikulina-9m.yaml, 50 mm), mirror-lens
(recipes/mirror-lens-feed-on-surface.yaml, 30 mm) and Luneburg ring (recipes/luneburg-layup-200.yaml,
10 mm) layups: the largest distance, in the meridional section, from the profile to a sheet's (ring
edge's) vertical edge or cone; the machine time of all cam files (hot wire and drilling; the
vertical-edged stack's straight cuts too, where the kind writes them); and, taper-cut, the largest
G-code reconstruction error (written, parsed back by gcodeparser, checked as ``make-lens check``
does). A wide hot wire (2 m travel) for the steep cones. Prints a Markdown table.
"""

from __future__ import annotations

import os

from taper_study import cam_figures, spec_of

from antenna_cad.fabrication.ring_plan import sphere_radius
from antenna_cad.kinds.bifocal import _lens
from antenna_cad.asbuilt.taper import Taper, cone_gap_mm
from antenna_cad.pipeline import prepare
from antenna_cad.registry import adapter

CAM = {"travel_mm": [2000, 2000], "lead_in_mm": 10}
CASES = ("bifocal-nikulina-9m.yaml", "mirror-lens-feed-on-surface.yaml", "luneburg-layup-200.yaml")


def largest_gap_mm(spec, plan) -> float:
    """Over every sheet (ring edge): the largest distance from the profile to its edge."""
    layup = plan.layup
    if spec.kind == "luneburg":
        shells = {L.index: L for L in plan.design.layers}
        gaps = []
        for s in layup.sheets:
            for r in s.rings:
                sh, z = shells[r.shell_index], (s.z_min_mm, s.z_max_mm)
                edges = [(r.cone_outer_mm or (r.r_outer_mm,) * 2, sh.r_outer_mm)]
                if max(r.cone_inner_mm or (r.r_inner_mm,)) > 0:
                    edges.append((r.cone_inner_mm or (r.r_inner_mm,) * 2, sh.r_inner_mm))
                gaps += [cone_gap_mm(c, z, lambda x, R=R: sphere_radius(R, x)) for c, R in edges]
        return max(gaps)
    if spec.kind == "bifocal":                 # as the layer table: the rim's z sampled too
        return max(Taper(_lens(spec, plan.design, layup), layup).largest_gap_mm())
    r = adapter(spec.kind).cone_radius(spec, plan.design)
    return max(cone_gap_mm(s.cone_mm, (s.z_min_mm, s.z_max_mm), r) for s in layup.sheets)


def main() -> None:
    print("| layup | sheets mm | edge | largest gap mm | cam files | machine time s | G-code error mm |")
    print("|---|---|---|---|---|---|---|")
    for recipe in CASES:
        for edge in ("stepped", "taper"):
            extra = {"cam": CAM} if edge == "taper" or spec_of(recipe).kind != "luneburg" else {}
            spec = spec_of(recipe, edge=edge, **extra)
            plan = prepare(spec)
            cam = getattr(plan.fab, "cam", None)
            seconds, err = cam_figures(spec, plan) if edge == "taper" else (cam.seconds if cam else None, None)
            cells = [recipe.removesuffix(".yaml"), f"{plan.layup.sheet_thickness_mm:g}", edge,
                     f"{largest_gap_mm(spec, plan):.2f}", str(len(cam.entries)) if cam else "—",
                     f"{seconds:.0f}" if seconds else "—", f"{err:.4f}" if err is not None else "—"]
            print("| " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    os.environ.setdefault("ANTENNA_CAD_MEEP_PYTHON", "/usr/bin/false")
    main()
