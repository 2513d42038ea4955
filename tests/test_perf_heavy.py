"""Speed-ups that must not change results: the σ(FOV) reference-curve cache, the
prism meshes of slotted plates, parallel plates and rings against BRepMesh on their B-reps, the profile validity
test against BRepCheck, the STEP file written by a forked child."""

from __future__ import annotations

import numpy as np
import pytest

from antenna_cad.kinds import slot_array_fov
from antenna_cad.synthesis.slot_array.fov import FieldCurve


def test_fov_reference_cache_round_trips_exactly(tmp_path, monkeypatch):
    monkeypatch.setenv("ANTENNA_CAD_CACHE", str(tmp_path))
    angle = np.array([-41.0, -0.1 / 3, 0.0, 0.1 / 3, 41.0])
    curves = (FieldCurve("a", angle, np.sqrt(np.abs(angle)) * 1e-5 / 7, 1.0),
              FieldCurve("b", angle[1:4], np.array([1 / 3, np.nan, 2 / 3]), 0.69))
    calls = []
    monkeypatch.setattr(slot_array_fov, "reference_curves", lambda: calls.append(1) or curves)
    first = slot_array_fov.cached_reference_curves()
    second = slot_array_fov.cached_reference_curves()
    assert len(calls) == 1 and len(list(tmp_path.rglob("fov-reference-*.json"))) == 1
    for c, a, b in zip(curves, first, second):
        assert b.name == c.name and b.aperture_mm == c.aperture_mm
        np.testing.assert_array_equal(b.angle_deg, c.angle_deg)
        np.testing.assert_array_equal(b.sigma, c.sigma)       # bit-exact, NaN where NaN


def test_fov_reference_cache_follows_the_sources(tmp_path, monkeypatch):
    monkeypatch.setenv("ANTENNA_CAD_CACHE", str(tmp_path / "cache"))
    synthesis = tmp_path / "synthesis"
    synthesis.mkdir()
    (synthesis / "fov.py").write_text("x = 1\n")
    monkeypatch.setattr(slot_array_fov, "SYNTHESIS", synthesis)
    calls = []
    curve = FieldCurve("a", np.zeros(1), np.ones(1), 1.0)
    monkeypatch.setattr(slot_array_fov, "reference_curves", lambda: calls.append(1) or (curve,))
    slot_array_fov.cached_reference_curves()
    (synthesis / "fov.py").write_text("x = 2\n")                # the optimiser changed: computed afresh
    slot_array_fov.cached_reference_curves()
    slot_array_fov.cached_reference_curves()
    assert len(calls) == 2


def test_fov_reference_cache_unwritable_still_computes(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("")
    monkeypatch.setenv("ANTENNA_CAD_CACHE", str(blocker))             # a file: the folder cannot be made
    curve = FieldCurve("a", np.zeros(1), np.ones(1), 1.0)
    monkeypatch.setattr(slot_array_fov, "reference_curves", lambda: (curve,))
    assert slot_array_fov.cached_reference_curves() == (curve,)


TOL = 0.05


def _box(solid) -> np.ndarray:
    from antenna_cad.geometry.kernel import bounding_box
    return np.array(bounding_box([solid]))


def _plate(slots):
    from antenna_cad.geometry.model import SlottedPrism
    from antenna_cad.geometry.slot_array import slot_wire, slotted_plate
    slots = np.asarray(slots, float)
    wires = [slot_wire(*row, 2.0) for row in slots]
    prism = SlottedPrism(np.array([(-3.0, 0.0), (3.0, 0.0), (3.0, 30.0), (-3.0, 30.0)]), slots, 2.0, 2.5)
    return prism, slotted_plate(-3.0, 0.0, 3.0, 30.0, 2.0, 0.5, wires)


SLOTS = [(0.8, 4.0, 4.5, 0.4, 0.0), (-0.8, 10.0, 4.5, 0.4, 0.0), (0.0, 17.0, 4.0, 0.6, 0.7),
         (1.2, 24.0, 3.0, 0.4, -0.3)]


def test_slotted_plate_mesh_matches_its_brep():
    from antenna_cad.export.mesh import mesh_prism, mesh_shape
    from antenna_cad.geometry.kernel import volume
    prism, solid = _plate(SLOTS)
    ours, occt = mesh_prism(prism, TOL), mesh_shape(solid, TOL)
    assert ours.is_watertight and ours.is_winding_consistent and ours.volume > 0
    assert abs(ours.volume - volume(solid)) <= 1e-3 * ours.area * TOL     # vertices on the exact arcs
    assert abs(occt.volume - volume(solid)) <= ours.area * TOL
    np.testing.assert_allclose(ours.bounds, _box(solid), atol=1e-9)
    assert abs(prism.volume_mm3() / volume(solid) - 1) < 1e-9
    again = mesh_prism(prism, TOL)
    assert np.array_equal(again.vertices, ours.vertices) and np.array_equal(again.faces, ours.faces)


@pytest.mark.parametrize("slots", [SLOTS, SLOTS + [(0.8, 6.0, 4.5, 0.4, 0.0)],        # overlaps the first
                                   SLOTS + [(2.9, 12.0, 3.0, 0.4, 0.0)]])             # crosses the edge
def test_profile_validity_agrees_with_brepcheck(slots):
    from antenna_cad.geometry.kernel import is_valid
    from antenna_cad.geometry.model import ModelPart
    from antenna_cad.materials import Material
    prism, solid = _plate(slots)
    part = ModelPart("top", Material("al", 1.0, 0.0, 2700.0, ""), "fabricated", solid, prism)
    assert part.is_valid() == is_valid(solid) == (slots is SLOTS)


@pytest.mark.parametrize("r_in, axis_y", [(0.0, False), (40.0, False), (1400.0, False), (40.0, True)])
def test_ring_mesh_matches_its_brep(r_in, axis_y):
    from antenna_cad.export.mesh import mesh_prism
    from antenna_cad.geometry.kernel import rotate, volume
    from antenna_cad.geometry.luneburg import annulus_solid
    from antenna_cad.geometry.model import RingPrism
    r_out = r_in + 60.0
    solid = annulus_solid(r_in, r_out, -5.0, 5.0)
    solid = rotate(solid, (1, 0, 0), -90) if axis_y else solid
    ring = RingPrism(r_in, r_out, -5.0, 5.0, axis_y)
    mesh = mesh_prism(ring, TOL)
    assert abs(ring.volume_mm3() / volume(solid) - 1) < 1e-9
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert 0 < volume(solid) - mesh.volume <= mesh.area * TOL       # inscribed polygons, within the chord
    box = _box(solid)
    assert np.all(mesh.bounds[0] >= box[0] - 1e-6) and np.all(mesh.bounds[1] <= box[1] + 1e-6)


def test_parallel_plate_prism_matches_its_brep():
    """A bifocal lens's parallel plates (geometry.bifocal.plate_parts): the (y, z) polygon prism
    along x, meshed from its description, equals the OCCT solid (volume, bounding box), closed."""
    from shapely.geometry import Point

    from antenna_cad.export.mesh import mesh_prism
    from antenna_cad.geometry import kernel
    from antenna_cad.geometry.bifocal import plate_parts
    from antenna_cad.materials import Material
    outline = Point(40.0, 5.0).buffer(30.0, quad_segs=200).union(Point(80.0, 0.0).buffer(12.0))   # (z, y)
    parts, checks = plate_parts(outline.convex_hull, [], 3.4, 2.0, Material("al", 1.0, 0.0, 2700.0, ""))
    assert all(c.status == "pass" for c in checks)
    for part, x0 in zip(parts, (-3.7, 1.7)):
        mesh = mesh_prism(part.prism, TOL)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
        assert abs(part.volume_mm3 / kernel.volume(part.shape) - 1) < 1e-9
        assert abs(mesh.volume / kernel.volume(part.shape) - 1) < 1e-9        # straight edges: exact
        np.testing.assert_allclose(mesh.bounds, _box(part.shape), atol=1e-9)
        assert mesh.bounds[0][0] == pytest.approx(x0) and part.is_valid() and kernel.is_valid(part.shape)


def test_solid_swept_along_x_is_meshed_as_its_prism():
    """A spline section extruded along x (as a cylindrical lens): meshed from its cap's boundary,
    divided within the chord tolerance, vertices on the exact edges; anything else is left to BRepMesh."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt

    from antenna_cad.export.mesh import mesh_shape, x_prism
    from antenna_cad.geometry import kernel
    edges = [kernel.spline([(0, -20, 0), (0, 0, 8), (0, 20, 0)], [(0, 1, 0.8), (0, 1, 0), (0, 1, -0.8)]),
             kernel.line((0, 20, 0), (0, 20, -3)),
             kernel.spline([(0, 20, -3), (0, 0, -9), (0, -20, -3)], [(0, -1, -0.6), (0, -1, 0), (0, -1, 0.6)]),
             kernel.line((0, -20, -3), (0, -20, 0))]
    wire = kernel.wire(edges)
    solid = kernel.translate(kernel.extrude(kernel.face(wire), (3.4, 0, 0)), (-1.7, 0, 0))
    prism = x_prism(solid, TOL)
    mesh = mesh_shape(solid, TOL)
    volume = kernel.volume(solid)
    assert mesh.metadata["mesher"] == "prism" and mesh.is_watertight and mesh.is_winding_consistent
    assert 0 < volume - mesh.volume <= mesh.area * TOL          # a convex section: inscribed
    np.testing.assert_allclose(mesh.bounds, _box(solid), atol=TOL)

    def distance(p) -> float:
        return BRepExtrema_DistShapeShape(BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex(), wire).Value()
    ring = np.column_stack([np.zeros(len(prism.outer_mm)), prism.outer_mm])
    mids = (ring + np.roll(ring, -1, axis=0)) / 2
    assert max(distance(p) for p in ring) < 1e-7                    # on the edges
    assert 0.5 * TOL < max(distance(p) for p in mids) <= TOL + 1e-9   # sagitta
    two = kernel.compound([kernel.box((0, 0, 0), (1, 1, 1)), kernel.box((3, 0, 0), (1, 1, 1))])
    assert x_prism(kernel.cylinder(5, 10), TOL) is None and x_prism(two, TOL) is None
    box = x_prism(kernel.box((0, 0, 0), (2, 4, 6)), TOL)
    assert len(box.outer_mm) == 4 and abs(box.volume_mm3() - 48.0) < 1e-12


def _box_model():
    from antenna_cad.geometry.kernel import box, cylinder
    from antenna_cad.geometry.model import Model, ModelPart
    from antenna_cad.materials import Material
    m = Material("foam", 1.1, 0.0, 30.0, "")
    return Model((ModelPart("b", m, "fabricated", box((-5, -10, -15), (10, 20, 30))),
                   ModelPart("c", m, "reference", cylinder(5, 8, (0, 0, -4)))), ())


def test_step_from_the_child_is_byte_identical(tmp_path):
    from antenna_cad.export.forked import Job
    from antenna_cad.export.step import write_step
    model = _box_model()
    write_step(model, "x", tmp_path / "here.step")
    job = Job(write_step, (model, "x", tmp_path / "child.step"), [tmp_path / "child.step"])
    assert (tmp_path / "child.step").exists()           # listed before it is written
    assert job.finish() is None
    assert (tmp_path / "child.step").read_bytes() == (tmp_path / "here.step").read_bytes()


def test_child_values_and_errors_reach_the_parent(tmp_path):
    from antenna_cad.export.forked import Job

    def fails():
        raise ValueError("no STEP today")
    assert Job(lambda a, b: {"sum": a + b}, (2, 3)).finish() == {"sum": 5}
    with pytest.raises(RuntimeError, match="ValueError: no STEP today"):
        Job(fails, ()).finish()
    with pytest.raises(OSError) as err:                  # kept an OSError: the build's one-line OutputError
        Job((tmp_path / "absent" / "f").write_text, ("x",)).finish()
    assert err.value.errno == 2
    Job(__import__("time").sleep, (30,)).finish(wait=False)        # stopped: killed and reaped at once
