"""The README's picture of a taper-cut stack as the hot wire cuts it.

    python benchmarks/cam_wire_figure.py [OUT.png]     (default docs/images/cam-wire.png)

Writes the G-code of recipes/xps-collimator-0.5m-taper.yaml, parses it back with gcodeparser
(antenna_cad.export.check_cam), rebuilds each wire position on the two foam faces of every sheet
from the towers' coordinates and the manifest fields, and draws the ruled surfaces against the lens
profile: left in 3-D (every 12th wire position), right in the meridional section with the stepped
stack the same boards would give.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from antenna_cad.export.check_cam import _faces, parse_moves  # noqa: E402
from antenna_cad.pipeline import prepare  # noqa: E402
from antenna_cad.spec import load_spec  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main(out: Path) -> None:
    spec = load_spec(ROOT / "recipes" / "xps-collimator-0.5m-taper.yaml")
    plan = prepare(spec)
    design = plan.design
    fig = plt.figure(figsize=(11, 4.6), dpi=110)
    ax3 = fig.add_subplot(1, 2, 1, projection="3d")
    ax = fig.add_subplot(1, 2, 2)
    for entry in plan.fab.cam.entries:
        if "faces" not in entry or entry["part"].endswith("-foot"):
            continue
        moves, cutting = parse_moves(plan.fab.files[entry["file"]], entry["axes"])
        front, back = _faces(entry, [p for p, g in zip(moves, cutting) if g][1:-2])
        z0, z1 = (f["z_mm"] for f in entry["faces"])
        for k in range(0, len(front), 12):
            ax3.plot([front[k, 0], back[k, 0]], [z0, z1], [front[k, 1], back[k, 1]], color="#1f77b4", lw=0.4)
        top = int(np.argmax(back[:, 1]))
        ax.plot([z0, z1], [front[top, 1], back[top, 1]], color="#1f77b4", lw=2.2,
                label="wire (from the G-code, kerf/2 outside)" if entry["part"] == "sheet-01" else None)
    z = np.linspace(0.0, design.thickness_mm, 400)
    r = np.array([design.radius_at(v) for v in z])
    for a in np.linspace(0, 2 * np.pi, 13)[:-1]:
        ax3.plot(r * np.cos(a), z, r * np.sin(a), color="#d62728", lw=0.8)
    ax.plot(z, r, color="#d62728", lw=1.2, label="lens profile")
    steps_z = np.ravel([[s.z_min_mm, s.z_max_mm] for s in plan.layup.sheets])
    steps_r = np.repeat([s.radius_mm for s in plan.layup.sheets], 2)
    ax.plot(steps_z, steps_r, color="0.5", ls="--", lw=1, label="stepped stack (vertical edges)")
    ax3.set_xlabel("x (mm)")
    ax3.set_ylabel("z (mm)")
    ax3.set_zlabel("y (mm)")
    ax3.set_title("Ruled surfaces cut by the wire (every 12th position)", fontsize=9)
    ax3.view_init(elev=18, azim=-62)
    ax.set_xlabel("z from the vertex (mm)")
    ax.set_ylabel("r (mm)")
    ax.set_title(f"Meridional section: {plan.layup.count} sheets of {plan.layup.sheet_thickness_mm:g} mm", fontsize=9)
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(alpha=0.3)
    fig.suptitle("xps-collimator-0.5m-taper: hot-wire G-code parsed back, against the lens", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, metadata={"Software": None})


if __name__ == "__main__":
    os.environ.setdefault("ANTENNA_CAD_MEEP_PYTHON", "/usr/bin/false")
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "images" / "cam-wire.png")
