"""Hot-wire programs of layups whose pieces all have vertical edges: a graded lens's foam slabs
(seed-001 §3.2). The lens is planar — its section extruded between the plates, the sheets stacked
along the extrusion — so each sheet's outline is exact and a straight cut (XY = UV) is the whole
piece: there is no cone to cut (``edge: taper`` has nothing to add)."""

from __future__ import annotations

from antenna_cad.cam.hotwire import straight_cut
from antenna_cad.cam.plan import CamPlan, _hotwire_file, kerf_of, machine_of, with_order


def plan_straight_cam(sheets, pieces, cam) -> CamPlan:
    """One straight hot-wire program per piece; ``sheets`` carry the z faces and the foam grade
    (``material``) of the pieces' ``sheet_index``, in ``cam.order``."""
    m = machine_of(cam)
    sheet_of = {s.index: s for s in sheets}
    files, entries, cuts = {}, [], []
    for p in sorted(pieces, key=lambda p: (p.sheet_index, p.label), reverse=cam.order == "flat_first"):
        s = sheet_of[p.sheet_index]
        text, entry, xy, uv = _hotwire_file(straight_cut(p, s, kerf_of(cam, s.material.name)), m, cam, s.material.name)
        files[entry["file"]] = text
        entries.append(entry)
        cuts.append((entry, xy, uv))
    return with_order(files, entries, cuts)
