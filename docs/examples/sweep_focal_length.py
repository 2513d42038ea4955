"""Sweep the focal length of the bundled Ø0.5 m foam collimator and plot what it does to the lens
thickness and to the aperture phase error of the stack as fabricated (50 mm boards, unsanded).

    python docs/examples/sweep_focal_length.py [OUT_PNG]
"""

import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from antenna_cad import api

base = api.load("xps-collimator-0.5m")                       # a bundled recipe (or a YAML file, or a dict)
quick = {"outputs.step": False, "outputs.stl": False,        # figures only: no solids, templates or report
         "outputs.templates": False, "outputs.report": False,
         "verification.full_wave": "off"}                     # the fast stair-step model instead of Meep
focal_lengths = [2000, 3000, 4000, 6000, 8000]
rows = []
with tempfile.TemporaryDirectory() as out:
    for f in focal_lengths:
        spec = api.with_changes(base, {**quick, "design.focal_length_mm": f})
        result = api.build(spec, out)
        rows.append((f, result.figures["thickness_mm"], result.verified["fabricated_on_axis_p2p_deg"],
                     result.status))
        print(f"F = {f} mm: thickness {rows[-1][1]:.1f} mm, as fabricated {rows[-1][2]:.1f}° p-p, {result.status}")

fig, ax = plt.subplots(figsize=(6.4, 3.6), layout="constrained")
ax.plot([r[0] for r in rows], [r[1] for r in rows], "o-", label="lens thickness (mm)")
ax.set_xlabel("focal length F (mm)")
ax.set_ylabel("thickness (mm)")
twin = ax.twinx()
twin.plot([r[0] for r in rows], [r[2] for r in rows], "s--", color="tab:red", label="phase error as fabricated (° p-p)")
twin.axhline(base.design.phase_error_budget_deg, color="tab:red", lw=0.8, ls=":")
twin.set_ylabel("aperture phase, p-p (°)")
fig.legend(loc="outside upper center", ncols=2, fontsize="small")
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "sweep_focal_length.png", dpi=110)
