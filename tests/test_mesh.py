"""STL meshing (export/mesh.py): absolute chord tolerance, watertight bodies, volume, orientation."""

from __future__ import annotations

import numpy as np
import pytest

from antenna_cad.export.mesh import mesh_shape
from antenna_cad.geometry import kernel
from antenna_cad.geometry.luneburg import annulus_solid, hemisphere_shell

TOL = 0.05


def _chord_sag(mesh, radius_of, r_surface, elements):
    """Largest inward sag from the surface r = r_surface of the centres of mesh elements
    (edges or triangles, as vertex indices) whose corners all lie on it."""
    on = abs(radius_of(mesh.vertices) - r_surface) < 1e-3
    corners_on = on[elements].all(axis=1)
    assert corners_on.sum() > 100
    return (r_surface - radius_of(mesh.vertices[elements[corners_on]].mean(axis=1))).max()


@pytest.mark.parametrize("r_in, r_out", [(40.0, 55.0), (1400.0, 1480.0)])
def test_ring_mesh_holds_the_absolute_chord_tolerance(r_in, r_out):
    mesh = mesh_shape(annulus_solid(r_in, r_out, 0.0, 10.0), TOL)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    r_v = np.hypot(*mesh.vertices[:, :2].T)
    on_surface = np.minimum(abs(r_v - r_in), abs(r_v - r_out))
    assert on_surface.max() < 1e-3                      # vertices on the cylinders (float32 STL)
    radius = lambda p: np.hypot(p[..., 0], p[..., 1])                             # noqa: E731
    assert 0 < _chord_sag(mesh, radius, r_out, mesh.edges_unique) <= TOL + 1e-4
    exact = np.pi * (r_out**2 - r_in**2) * 10.0
    assert mesh.volume == pytest.approx(exact, rel=2 * TOL / r_in)


def test_hemisphere_shell_mesh_is_closed_and_within_tolerance():
    r_in, r_out = 200.0, 230.0
    mesh = mesh_shape(hemisphere_shell(r_in, r_out, 1.0), TOL)
    assert mesh.is_watertight and mesh.volume > 0
    radius = lambda p: np.linalg.norm(p, axis=-1)                                  # noqa: E731
    assert 0 < _chord_sag(mesh, radius, r_out, mesh.edges_unique) <= TOL + 1e-4
    assert 0 < _chord_sag(mesh, radius, r_out, mesh.faces) <= TOL + 1e-4
    exact = 2 / 3 * np.pi * (r_out**3 - r_in**3)
    assert mesh.volume == pytest.approx(exact, rel=2 * TOL / r_in)


def test_bodies_touching_along_an_edge_stay_separate_and_watertight():
    pair = kernel.fuse([kernel.box((-5, -5, -5), (10, 10, 10)), kernel.box((5, -5, 5), (10, 10, 10))])     # two cubes sharing one edge
    assert len(kernel.solids(pair)) == 2
    mesh = mesh_shape(pair, TOL)
    bodies = mesh.split(only_watertight=False)
    assert len(bodies) == 2 and all(b.is_watertight for b in bodies)
    assert mesh.volume == pytest.approx(2000.0, rel=1e-6)
