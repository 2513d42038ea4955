"""The CAD kernel (geometry/kernel.py, OCP directly): each construction read back against its
closed-form volume, area or extent."""

import math

import numpy as np
import pytest

from antenna_cad.geometry import kernel


def test_box_cut_by_a_batch_of_cylinders():
    plate = kernel.box((0, 0, 0), (40, 20, 5))
    holes = [kernel.cylinder(2.0, 9, (x, 10, -2)) for x in (10, 20, 30)]
    cut = kernel.cut(plate, holes)
    assert kernel.is_valid(cut) and len(kernel.solids(cut)) == 1
    assert kernel.volume(cut) == pytest.approx(40 * 20 * 5 - 3 * math.pi * 4 * 5, rel=1e-12)
    assert kernel.cut(plate, []) is plate


def test_fuse_of_disjoint_solids_keeps_both():
    pair = kernel.fuse([kernel.box((0, 0, 0), (1, 1, 1)), kernel.box((3, 0, 0), (1, 1, 1))])
    assert len(kernel.solids(pair)) == 2 and kernel.volume(pair) == pytest.approx(2.0, rel=1e-12)


def test_revolved_profile_with_an_arc_is_exact():
    r_in, r_out = 30.0, 50.0
    c = math.sqrt(0.5)
    edges = [kernel.line((r_in, 0, 0), (r_out, 0, 0)),
             kernel.arc((r_out, 0, 0), (r_out * c, 0, r_out * c), (0, 0, r_out)), kernel.line((0, 0, r_out), (0, 0, r_in)), kernel.arc((0, 0, r_in), (r_in * c, 0, r_in * c), (r_in, 0, 0))]
    shell = kernel.revolve_z(kernel.face(kernel.wire(edges)))
    assert kernel.is_valid(shell)
    assert kernel.volume(shell) == pytest.approx(2 / 3 * math.pi * (r_out**3 - r_in**3), rel=1e-9)
    lo, hi = kernel.bounding_box([shell])
    np.testing.assert_allclose(lo, [-r_out, -r_out, 0], atol=1e-7)
    np.testing.assert_allclose(hi, [r_out, r_out, r_out], atol=1e-7)


def test_face_with_holes_extruded_and_placed():
    outer = kernel.polygon([(0, 0, 0), (10, 0, 0), (10, 10, 0), (0, 10, 0)])
    hole = kernel.polygon([(2, 2, 0), (4, 2, 0), (4, 4, 0), (2, 4, 0)])        # either orientation: fixed
    prism = kernel.extrude(kernel.face(outer, [hole]), (0, 0, 3))
    assert kernel.volume(prism) == pytest.approx((100 - 4) * 3, rel=1e-12)
    assert kernel.area(kernel.face(outer, [hole])) == pytest.approx(96, rel=1e-12)
    moved = kernel.place(prism, (1, 2, 3), (0, 1, 0), (1, 0, 0))              # local z along +y
    lo, hi = kernel.bounding_box([moved])
    np.testing.assert_allclose([lo, hi], [[1, 2, -7], [11, 5, 3]], atol=1e-9)
    turned = kernel.rotate(kernel.translate(prism, (0, 0, 1)), (1, 0, 0), -90)   # (x, y, z) → (x, z, −y)
    lo, hi = kernel.bounding_box([turned])
    np.testing.assert_allclose([lo, hi], [[0, 1, -10], [10, 4, 0]], atol=1e-9)


def test_sketch_booleans_and_vertices():
    disc_and_tab = kernel.fuse([kernel.disc(0, 0, 10), kernel.rectangle(0, -12, 4, 8)])
    sheet = kernel.cut(disc_and_tab, [kernel.disc(0, 0, 2)])
    solid = kernel.extrude(sheet, (0, 0, 2))
    assert kernel.is_valid(solid)
    below = 4 * 16 - (2 * math.sqrt(96) + 100 * math.asin(0.2))     # rectangle below the circle y = −√(100 − x²)
    assert kernel.volume(solid) == pytest.approx(2 * (math.pi * (100 - 4) + below), rel=1e-9)
    z = kernel.vertices(solid)[:, 2]
    assert set(np.round(z, 9)) == {0.0, 2.0}


def test_spline_interpolates_its_points_and_tangents():
    x = np.linspace(0, 2, 41)
    pts = np.column_stack([x, np.sin(x), np.zeros_like(x)])
    tan = np.column_stack([np.ones_like(x), np.cos(x), np.zeros_like(x)])
    edge = kernel.spline(pts, tan)
    p, d = kernel.edge_points(edge, 101)
    assert np.abs(p[:, 1] - np.sin(p[:, 0])).max() < 1e-6
    np.testing.assert_allclose(p[[0, -1]], pts[[0, -1]], atol=1e-12)
    assert abs(d[0, 1] / d[0, 0] - 1.0) < 1e-9


def test_plate_keeps_thousands_of_holes_linear():
    outer = kernel.polygon([(0, 0, 0), (100, 0, 0), (100, 100, 0), (0, 100, 0)])
    holes = [kernel.wire([kernel.arc((x + 1, y, 0), (x, y - 1, 0), (x - 1, y, 0)),
                          kernel.arc((x - 1, y, 0), (x, y + 1, 0), (x + 1, y, 0))])
             for x in range(5, 100, 10) for y in range(5, 100, 10)]
    plate = kernel.plate(outer, holes, (0, 0, 1))
    assert kernel.volume(plate) == pytest.approx(100 * 100 - 100 * math.pi, rel=1e-9)
