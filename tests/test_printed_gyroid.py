"""The printed sheet gyroid: its thinnest sheet and narrowest channel, the level set meshed by manifold3d
(closed, oriented, its local fill the fill asked), the turned-over hemisphere, a small printed sphere."""

import math

import numpy as np
import pytest
from manifold3d import Manifold

from antenna_cad.printed.export3mf import stl_bytes, three_mf_bytes
from antenna_cad.printed.fill import fill_integral_mm3, fill_map
from antenna_cad.printed.gyroid_mesh import gyroid_lattice, level_function
from antenna_cad.printed.lattice import GYROID_WIDTHS, Printable, gyroid, gyroid_edge_mm
from antenna_cad.printed.parts import Pins, build_printed_lens, closed_and_oriented


def _grad(p):
    X, Y, Z = (2 * np.pi * p[:, i] for i in range(3))
    return 2 * np.pi * np.stack([np.cos(X) * np.cos(Y) - np.sin(Z) * np.sin(X),
                                 np.cos(Y) * np.cos(Z) - np.sin(X) * np.sin(Y),
                                 np.cos(Z) * np.cos(X) - np.sin(Y) * np.sin(Z)], -1)


def test_thinnest_sheet_and_narrowest_channel_are_remeasured():
    """Points of g = 0 (Newton), marched along the normal in steps of 1e-3 cells: the thinnest sheet
    |g| ≤ t and the narrowest channel beyond it are the tabulated ones (within 2 steps)."""
    p = np.random.default_rng(7).random((4000, 3))
    for _ in range(15):
        gr = _grad(p)
        p = p - (gyroid(*p.T) / np.einsum("ij,ij->i", gr, gr))[:, None] * gr
    n = _grad(p)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    s = np.arange(1, 701) * 1e-3
    up = np.stack([gyroid(*(p + si * n).T) for si in s], 1)
    down = -np.stack([gyroid(*(p - si * n).T) for si in s], 1)
    for t, wall, gap in GYROID_WIDTHS[2:-1:3]:
        i_up, i_down = np.argmax(up >= t, axis=1), np.argmax(down >= t, axis=1)
        back = (np.arange(len(s))[None] > i_up[:, None]) & (up < t)
        has = back.any(axis=1)
        assert (s[i_up] + s[i_down]).min() == pytest.approx(wall, abs=2e-3)
        assert (s[np.argmax(back, axis=1)] - s[i_up])[has].min() == pytest.approx(gap, abs=2e-3)


def test_printable_gyroid_range_and_the_spec_refusal():
    pr = Printable("gyroid", 6.0, 0.4, 0.8)
    lo, hi = pr.fill_range
    assert pr.wall_mm(lo) == pytest.approx(0.4, abs=0.01) and pr.gap_mm(hi) == pytest.approx(0.8, abs=0.01)
    assert Printable("gyroid", 3.6, 0.8, 0.8).fill_range == (0.0, 0.0)     # 0.22 cells each: no sheet prints


def test_turning_the_lower_half_over_maps_the_gyroid_onto_itself():
    R = 20.0
    fm = fill_map(lambda r: 2 - (r / R) ** 2, R, "gyroid", 2.7, Printable("gyroid", 4.5, 0.6, 0.6))
    f = level_function(fm, "sphere", R)
    pts = np.random.default_rng(2).uniform(-R / 2, R / 2, (500, 3))
    assert max(abs(f(x, y, z) - f(x, -y, -z)) for x, y, z in pts) < 1e-12
    assert max(abs(f(x, y, z) - f(-x, y, -z)) for x, y, z in pts) > 0.1      # not any rotation: the chosen axis


def _fill_map(R, a=4.5):
    return fill_map(lambda r: 2 - (r / R) ** 2, R, "gyroid", 2.7, Printable("gyroid", a, 0.6, 0.6))


def test_meshed_gyroid_is_closed_and_its_local_fill_is_the_fill_asked():
    """A slab of the graded gyroid: manifold3d's status, each directed edge once, and the solid fraction
    of one-cell boxes at three radii against the box's mean of the fill the law asks (within 2 %; the
    level set measures about 1 % light)."""
    R, a = 15.0, 4.5
    fm = _fill_map(R, a)
    m = gyroid_lattice("sphere", R, -a / 2, a / 2, fm, gyroid_edge_mm(a, fm.fill_range))
    assert m.status().name == "NoError" and m.genus() > 10
    assert closed_and_oriented(np.asarray(m.to_mesh().tri_verts, np.int64))
    errors = []
    for r in (2.5, 7.0, 11.5):
        box = Manifold.cube([a, a, a], center=True).translate([r, 0.0, 0.0])
        q = (np.arange(24) + 0.5) / 24 * a - a / 2                 # the box's mean of the fill asked
        x, y, z = np.meshgrid(q + r, q, q, indexing="ij")
        asked = float(np.interp(np.sqrt(x * x + y * y + z * z), fm.r_mm, fm.fill).mean())
        errors.append((m ^ box).volume() / a**3 / asked - 1)
    assert max(map(abs, errors)) < 0.02, errors


def _small_gyroid_sphere():
    R, a, skin = 10.0, 4.5, 0.8
    fm = _fill_map(R, a)
    ref = fill_integral_mm3(fm, R - skin, "sphere") + 4 / 3 * math.pi * (R**3 - (R - skin) ** 3)
    return build_printed_lens("sphere", R, None, fm, skin_mm=skin, wall_mm=0.6, gap_mm=0.6, width_step_mm=0.05,
                              bed_mm=(200.0, 200.0, 200.0), pins=Pins(2.0, 6.0, 0.2, 0.6), tolerance_mm=0.05,
                              reference_volume_mm3=ref)


def test_small_printed_gyroid_sphere_is_closed_holds_its_fill_and_writes_the_same_bytes():
    lens = _small_gyroid_sphere()
    assert abs(lens.body_volume_mm3 / lens.reference_volume_mm3 - 1) < 0.03
    assert all(closed_and_oriented(p.faces) for p in lens.parts)
    assert [(p.label, p.count) for p in lens.parts] == [("lens-01", 2), ("pin", 3)]
    assert lens.parts[0].size_mm == pytest.approx((20.0, 20.0, 10.0), abs=0.05)
    again = _small_gyroid_sphere()
    objects = [[{"name": p.label, "vertices": p.vertices, "faces": p.faces} for p in x.parts] for x in (lens, again)]
    assert three_mf_bytes(objects[0], {}) == three_mf_bytes(objects[1], {})
    assert stl_bytes(lens.parts[0].vertices, lens.parts[0].faces, "a") == \
        stl_bytes(again.parts[0].vertices, again.parts[0].faces, "a")
