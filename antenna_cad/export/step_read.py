"""Second STEP reader: gmsh from PyPI (its own OpenCASCADE 7.x, not our OCP 8).

Used by ``make-lens check`` and the portability tests: the solids an OCCT-7 based tool (FreeCAD,
gmsh, most CAM) sees in our STEP, with the label of each solid's product and its volume.
"""

from __future__ import annotations

import re
from collections import defaultdict
from pathlib import Path


def gmsh_solids(path: Path) -> dict[str, list[float]]:
    """label → volumes (mm³) of the solids gmsh reads under that product name (``sheet-01.2``,
    the 2nd solid of part ``sheet-01``, counts under ``sheet-01``)."""
    import gmsh
    gmsh.initialize(["-noenv"], readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        solids: dict[str, list[float]] = defaultdict(list)
        for dim, tag in gmsh.model.getEntities(3):
            label = re.sub(r"\.\d+$", "", gmsh.model.getEntityName(dim, tag).rsplit("/", 1)[-1])
            solids[label].append(gmsh.model.occ.getMass(dim, tag))
        return dict(solids)
    finally:
        gmsh.finalize()
