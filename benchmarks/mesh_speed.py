"""Meshing time per part: OCCT's Watson vs Delabella triangulators at the same absolute chord
tolerance (export/mesh.py), on Luneburg layup rings and moulded hemisphere shells (the rest of the
mesh: OCCT's STL writer + trimesh read-back and merge).

Prints ms per part, triangles and the largest chord sag of outer-surface edges (must stay within
the tolerance for both).

    PYTHONPATH=. python benchmarks/mesh_speed.py
"""

from __future__ import annotations

import time

import numpy as np
from antenna_cad.export.mesh import mesh_shape
from antenna_cad.geometry.luneburg import annulus_solid, hemisphere_shell

TOL = 0.05
CASES = {
    "ring r 50": (lambda: annulus_solid(50, 130, 0, 10), 130, 2),
    "ring r 300": (lambda: annulus_solid(300, 380, 0, 10), 380, 2),
    "ring r 1400": (lambda: annulus_solid(1400, 1480, 0, 10), 1480, 2),
    "hemisphere r 230": (lambda: hemisphere_shell(200, 230, 1.0), 230, 3),
}


def outer_sag(mesh, r_out: float, dims: int) -> float:
    radius = np.linalg.norm(mesh.vertices[:, :dims], axis=1)
    edges = mesh.edges_unique[(abs(radius - r_out) < 1e-3)[mesh.edges_unique].all(axis=1)]
    return float((r_out - np.linalg.norm(mesh.vertices[edges].mean(axis=1)[:, :dims], axis=1)).max())


if __name__ == "__main__":
    print(f"{'part':18s} {'algorithm':10s} {'ms':>8s} {'triangles':>10s} {'sag mm':>8s}")
    for name, (make, r_out, dims) in CASES.items():
        for label in ("watson", "delabella"):
            shapes = [make() for _ in range(5)]
            t = time.perf_counter()
            meshes = [mesh_shape(s, TOL, (label,)) for s in shapes]
            ms = 1e3 * (time.perf_counter() - t) / len(shapes)
            sag = outer_sag(meshes[0], r_out, dims)
            print(f"{name:18s} {label:10s} {ms:8.1f} {len(meshes[0].faces):10d} {sag:8.4f}")
