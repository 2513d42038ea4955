"""The report's view of the toolpaths: the cut order with times, and a preview of every hot-wire
cut (both towers' paths, the way in and out, the order and the time)."""

from __future__ import annotations

import numpy as np

from antenna_cad.verification import Plot, Series, Table, Verification


def cam_report(cam) -> Verification:
    """Table and preview plots of a :class:`antenna_cad.cam.plan.CamPlan`."""
    rows = tuple((i, e["file"], e["part"], e["machine"], round(e["seconds"] / 60, 2))
                 for i, e in enumerate(cam.entries, 1))
    table = Table("cut-order", "Cut order and times (cam/cut-order.csv)", ("order", "file", "part", "machine", "minutes"),
                  rows, caption=f"total {cam.seconds / 60:.1f} min of machine time (hot wire at the feed of the "
                  "faster foam face, drilling cycles, dwells; rapid moves to the first point not counted)")
    order = {e["file"]: i for i, e in enumerate(cam.entries, 1)}
    plots = []
    for entry, xy, uv in cam.cuts:
        way = np.r_[xy[:3], [[np.nan, np.nan]], xy[-3:]]            # safe height ↔ lead-in ↔ contour, both ends
        plots.append(Plot(f"cam-{entry['part']}", f"Cut {order[entry['file']]}: {entry['part']} "
                          f"({entry['seconds'] / 60:.1f} min)", "tower X / U (mm)", "tower Y / V (mm)",
                          (Series("first tower (XY)", xy[2:-2, 0], xy[2:-2, 1]),
                           Series("second tower (UV)", uv[2:-2, 0], uv[2:-2, 1], "dashed"),
                           Series("in and out (XY)", way[:, 0], way[:, 1], "points")), equal_aspect=True,
                          caption=f"{entry['file']}: {entry['machine']} {entry['axes']}, towers "
                          f"{entry['tower_span_mm']:g} mm apart, foam faces at {entry['faces'][0]['wire_mm']:g} and "
                          f"{entry['faces'][1]['wire_mm']:g} mm; kerf {entry['kerf_mm']:g} mm"))
    return Verification(figures={"cam_total_seconds": cam.seconds}, tables=(table,), plots=tuple(plots))
