"""Hot-wire programs of a taper-cut Luneburg ring layup (seed-002 §5.1 (b)): per ring its outer
cone, through the shell's outer sphere at the sheet's two faces, and — a ring with a hole — its
inner cone, through the inner sphere, the wire kerf/2 inside the hole. The wire reaches a hole
through a radial slit from the top (a sector joint when the ring is cut in sectors, glued into
its blank first, as a collimator disc wider than a board). Each manifest entry names its sphere
(``sphere_mm``) and side (``edge``: outer or inner), from which ``make-lens check`` rebuilds the cone;
each face is compensated by the kerf at its own speed, as a collimator's cone.
"""

from __future__ import annotations

from antenna_cad.cam.hotwire import cone_ring
from antenna_cad.cam.plan import CamPlan, _hotwire_file, face_kerfs, kerf_of, kerf_table_of, machine_of, with_order


def plan_ring_cam(layup, cam, shells: dict) -> CamPlan:
    """Hot-wire programs of every taper-cut ring of ``layup`` (``shells``: shell index → the
    design's layer, for its sphere radii), sheets in ``cam.order``."""
    m = machine_of(cam)
    sheets = sorted(layup.sheets, key=lambda s: s.index, reverse=cam.order == "flat_first")
    files, entries, cuts = {}, [], []
    for s in sheets:
        z = (s.z_min_mm, s.z_max_mm)
        for r in s.rings:
            kerf = kerf_of(cam, r.material.name)
            sh = shells[r.shell_index]
            edges = [("outer", r.cone_outer_mm, sh.r_outer_mm)]
            if max(r.cone_inner_mm) > 0:
                edges.append(("inner", r.cone_inner_mm, sh.r_inner_mm))
            for side, radii, sphere in edges:
                inward = side == "inner"
                faces = face_kerfs(radii, z[1] - z[0], kerf_table_of(cam, r.material.name), cam.feed_mm_min, inward)
                cut = cone_ring(f"{r.label}-{side}", radii, z, kerf, inward, faces)
                text, entry, xy, uv = _hotwire_file(cut, m, cam, r.material.name)
                entry = entry | {"sphere_mm": sphere, "edge": side}
                files[entry["file"]] = text
                entries.append(entry)
                cuts.append((entry, xy, uv))
    return with_order(files, entries, cuts)
