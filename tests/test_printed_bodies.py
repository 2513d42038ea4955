"""Printed lattice bodies of any section (the graded lens between plates, the mirror-lens body): the
inner lattice joined to the trimmed boundary and skin, bed cuts on cell faces, the dithered widths
whose mean follows the law, the kinds' spec and their refusals."""

import math

import numpy as np
import pytest
from shapely.geometry import Polygon

from antenna_cad.printed.body import (Envelope, bed_planes, body_cells, body_pins, build_lattice_body, lattice_origin,
                                     reference_volume_mm3)
from antenna_cad.printed.export3mf import three_mf_bytes
from antenna_cad.printed.fill import dithered_fill, dithered_widths
from antenna_cad.printed.homogenization import homogenized
from antenna_cad.printed.lattice import fill_fraction
from antenna_cad.printed.parts import Pins, closed_and_oriented, mesh_volume
from antenna_cad.spec import SpecError, load_spec, parse_spec

A, SKIN = 3.0, 1.2


def _revolved():
    return Envelope("revolved", Polygon([(0, 0), (30, 0), (24, 30), (0, 33)]))


def _extruded():
    return Envelope("extruded", Polygon([(-30, -30), (30, -27), (21, 30), (-30, 30)]), 6.0)


def _width(centre, env):
    return np.full(len(centre), 1.5) if env.kind == "revolved" else np.round(1.0 + 0.02 * np.abs(centre[:, 1]), 1)


def _fill(env):
    if env.kind == "revolved":
        return lambda u, w: np.full(np.shape(u), fill_fraction("cubic", 0.5))
    return lambda u, w: fill_fraction("cubic", np.round(1.0 + 0.02 * np.abs(w), 1) / A)


def _build(env, bed=200.0, pins=None):
    idx, centre, inner = body_cells(env, A, SKIN, 0.02)
    ref = reference_volume_mm3(env, _fill(env), SKIN, 0.1)
    return build_lattice_body(env, idx, centre, inner, _width(centre, env), A, skin_mm=SKIN, bed_mm=(bed, bed, 300.0),
                              tolerance_mm=0.02, segments=96, reference_volume_mm3=ref, pins=pins), inner


def _winding(vertices, faces, points):
    """Generalized winding number of a closed mesh at ``points`` (n, 3): 1 inside, 0 outside (Van
    Oosterom and Strackee's solid angle of each triangle)."""
    a, b, c = (vertices[faces[:, k]][None] - points[:, None] for k in range(3))
    la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
    dot = lambda x, y: np.einsum("pfi,pfi->pf", x, y)
    num = dot(a, np.cross(b, c))
    den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb
    return np.arctan2(num, den).sum(axis=1) / (2 * np.pi)


@pytest.mark.parametrize("make", [_revolved, _extruded])
def test_inner_lattice_and_trimmed_skin_weld_into_closed_parts_of_the_fill_volume(make):
    lens, inner = _build(make())
    assert inner.sum() > 0 and (~inner).sum() > 0                  # both paths used, so the seam is
    assert all(closed_and_oriented(p.faces) for p in lens.parts)
    assert abs(lens.body_volume_mm3 / lens.reference_volume_mm3 - 1) < 0.015
    part = lens.parts[0]
    assert not closed_and_oriented(part.faces[1:])


def test_bed_cuts_lie_on_cell_faces_and_every_part_is_closed():
    lens, _ = _build(_extruded(), bed=40.0)
    assert lens.cuts == 2 and len(lens.parts) == 4
    assert all(closed_and_oriented(p.faces) for p in lens.parts)
    assert all(s <= 40.0 + 2 * A for p in lens.parts for s in p.size_mm[:2])
    whole, _ = _build(_extruded())
    assert sum(p.volume_mm3 for p in lens.parts) == pytest.approx(whole.body_volume_mm3, rel=1e-6)


@pytest.mark.parametrize("make", [_revolved, _extruded])
def test_bed_cuts_of_a_body_are_registered_by_pins_in_blind_holes_of_solid_bosses(make):
    env, pins = make(), Pins(4.0, 12.0, 0.2, 0.8)
    if env.kind == "extruded":
        env = Envelope("extruded", env.section, 18.0)       # tall enough for a Ø5.8 mm boss 1 mm off the plates
    lens, _ = _build(env, bed=40.0, pins=pins)
    plain, _ = _build(env, bed=40.0)
    lens_parts = [p for p in lens.parts if p.role == "lens"]
    assert lens.cuts == 2 and lens.unpinned_cuts == 0 and lens.pins == 4 and len(lens_parts) == 4
    assert lens.parts[-1].role == "pin" and lens.parts[-1].count == 4
    assert all(closed_and_oriented(p.faces) for p in lens.parts)
    o = lattice_origin(env, A)
    u0, w0, u1, w1 = env.full.bounds
    ext = ((-u1, u1), (-u1, u1)) if env.kind == "revolved" else ((u0, u1), (w0, w1))
    planes = {k: bed_planes(ext[k], 40.0, A, o[k]) for k in (0, 1)}
    *_, sites, _ = body_pins(env, planes, pins, SKIN, 0.02)
    assert len(sites) == 4
    probes, inside = [], []
    for axis, c, u, z in sites:
        e = np.eye(3)[axis]
        at = np.array([c, u, z]) if axis == 0 else np.array([u, c, z])
        side = np.eye(3)[1 - axis] * (pins.hole_radius + pins.wall_mm / 2)
        for s in (-1, 1):
            probes += [at + s * e * pins.depth / 2, at + s * e * (pins.depth + pins.wall_mm / 2),
                       at + s * e * pins.depth / 2 + side]
            inside += [0, 1, 1]                          # the hole, the boss's end, the boss's wall
    probes = np.array(probes)
    total = sum(_winding(p.vertices + np.array(p.offset_mm), p.faces, probes) for p in lens_parts)
    assert np.allclose(total, inside, atol=1e-6)        # each probe in exactly one part, or in none
    added = lens.body_volume_mm3 - plain.body_volume_mm3  # bosses' solid less the lattice they replace, less holes
    boss = np.pi * pins.boss_radius**2 * 2 * (pins.depth + pins.wall_mm)
    hole = np.pi * pins.hole_radius**2 * 2 * pins.depth
    assert -4 * hole < added < 4 * (boss - hole)


def test_inner_cells_lie_inside_the_skin_and_boundary_cells_reach_the_trim():
    env = _revolved()
    idx, centre, inner = body_cells(env, A, SKIN, 0.02)
    hole = env.polygon(-SKIN, 0.02)
    r = np.hypot(np.abs(centre[inner, 0]) + A / 2, np.abs(centre[inner, 1]) + A / 2)
    corners = [(rr, z) for rr, zc in zip(r, centre[inner, 2]) for z in (zc - A / 2, zc + A / 2)]
    assert all(hole.contains(Polygon([(0, z), (rr, z), (rr, z + 1e-3), (0, z + 1e-3)])) for rr, z in corners)


def test_the_part_files_are_byte_identical_across_builds():
    one, _ = _build(_revolved(), bed=40.0)
    two, _ = _build(_revolved(), bed=40.0)
    objs = lambda lens: [{"name": p.label, "vertices": p.vertices, "faces": p.faces} for p in lens.parts]
    assert three_mf_bytes(objs(one), {"Title": "t"}) == three_mf_bytes(objs(two), {"Title": "t"})


def test_dithered_widths_are_printable_steps_whose_mean_is_the_asked_width():
    w, t = dithered_widths(np.full(40, 1.337), np.arange(40), 0.05, 0.8, 2.7)
    assert set(np.round(w, 9)) == {1.3, 1.35} and t[0] == pytest.approx(0.74)
    assert w.mean() == pytest.approx(1.337, abs=0.05 / 40)
    f, e = dithered_fill(1.337, 0.05, 0.8, 2.7, 3.5, "cubic", 2.7)
    h = homogenized("cubic", 2.7)
    assert float(e) == pytest.approx(float(h.eps_at(fill_fraction("cubic", 1.337 / 3.5))), abs=2e-3)
    low, _ = dithered_widths(np.array([0.1]), [0], 0.05, 0.8, 2.7)
    assert low[0] == pytest.approx(0.8)                             # never below the thinnest wall


def test_the_printed_mirror_lens_body_is_at_n_squared_and_the_graded_rows_follow_the_law():
    from antenna_cad.kinds import graded, graded_printed, uniform_printed
    ml = load_spec("recipes/mirror-lens-346mm-printed.yaml")
    body = uniform_printed.lattice_body(ml)
    assert body.eps_target == pytest.approx(1.69)
    assert abs(body.eps_printed - body.eps_target) < 1e-3
    spec = load_spec("recipes/graded-trifocal-160mm-printed.yaml")
    design = graded.synthesize(spec)
    edges, eps = graded_printed.printed_steps(spec, design)
    centres = np.arange(len(eps)) * spec.fabrication.cell_mm
    inside = centres <= design.half_aperture * design.unit_mm
    assert np.abs(eps[inside] - graded_printed.law(design)(centres[inside])).max() < 1e-4
    assert eps[0] == pytest.approx(spec.design.n0**2, abs=0.02)


ML = {"name": "m", "kind": "mirror_lens", "frequency_ghz": 13, "material": "pla",
      "design": {"diameter_mm": 346, "refractive_index": 1.3, "f0_mm": 174, "d0_mm": 172, "gamma": 0.9371},
      "fabrication": {"method": "printed", "cell_mm": 3.5}}
GR = load_spec("recipes/graded-trifocal-160mm-printed.yaml").model_dump(mode="json", exclude_none=True)


@pytest.mark.parametrize("data, expected", [
    ({**ML, "design": {k: v for k, v in ML["design"].items() if k != "refractive_index"}},
     "design.refractive_index: required with fabrication.method printed"),
    ({**ML, "design": ML["design"] | {"refractive_index": 1.7}}, "design.refractive_index: n² = 2.89 must be below"),
    ({**ML, "fabrication": {"method": "printed", "cell_mm": 3.5, "lattice": "gyroid", "min_wall_mm": 0.4, "min_gap_mm": 0.4}},
     "fabrication.lattice: the body is printed as the cubic lattice"),
    ({**ML, "fabrication": {"method": "printed", "cell_mm": 4.0}}, "fabrication.cell_mm: must be ≤ λ/(4·√εr)"),
    ({**ML, "fabrication": {"method": "printed", "cell_mm": 3.5, "orientation": "axis_flat"}},
     "fabrication.orientation: the mirror-lens body is printed axis_up"),
    ({**GR, "fabrication": GR["fabrication"] | {"cell_mm": 0.9}},
     "fabrication.cell_mm: the height between the plates must be a whole number of cells"),
    ({**GR, "material": "polystyrene"}, "material: a printed lens needs a filament"),
])
def test_illegal_printed_bodies_are_refused_in_one_line(data, expected):
    with pytest.raises(SpecError) as exc:
        parse_spec(data, "s.yaml")
    assert len(exc.value.lines) == 1 and expected in exc.value.lines[0], exc.value.lines


def test_a_printed_recipe_reads_back():
    assert parse_spec(ML, "s.yaml").design.refractive_index == 1.3
    assert math.isclose(parse_spec(GR, "s.yaml").fabrication.cell_mm * 4, 3.4)


def test_the_mirror_lens_is_synthesized_at_n_and_traced_at_the_printed_index():
    from antenna_cad.kinds import mirror_lens
    from antenna_cad.kinds.uniform_printed import lattice_body
    from antenna_cad.stages import planning
    spec = load_spec("recipes/mirror-lens-346mm-printed.yaml")
    design = mirror_lens.synthesize(spec)
    assert design.profiles.n == pytest.approx(1.3)
    body = lattice_body(spec)
    assert mirror_lens.body_material(spec, as_printed=True).eps_r == pytest.approx(body.eps_printed)
    assert mirror_lens.body_material(spec).density_kg_m3 == pytest.approx(body.fill * 1240.0)
    with planning(False):
        plan = mirror_lens.fabricate(spec, design, None, ())
    names = {c.name: c for c in plan.checks}
    assert names["printed_eps_error"].status == "pass" and names["printed_fill_clipped"].status == "pass"
    assert plan.lens is None                                        # CAD-free: limits and fill, no mesh
    off = parse_spec(spec.model_dump(mode="json", exclude_none=True) | {"design": ML["design"] | {
        "refractive_index": 1.55}}, "s.yaml")
    assert lattice_body(off).eps_printed == pytest.approx(1.55**2, abs=1e-3)


def test_weld_keeps_the_first_of_each_vertex_in_key_order_and_the_3mf_text_is_the_model_in_order():
    import io
    import zipfile

    from antenna_cad.printed.export3mf import model_xml
    from antenna_cad.printed.lattice_mesh import cross_rows, lattice_triangles, weld
    p, q = np.random.default_rng(3).normal(size=(2, 1000, 3)) * 1e3
    assert np.array_equal(cross_rows(p, q), np.cross(p, q))             # bit for bit: the meshes' bytes rely on it
    idx = np.stack(np.meshgrid(*[np.arange(3)] * 3, indexing="ij"), -1).reshape(-1, 3)
    tris = lattice_triangles(idx, np.where(idx[:, 2] % 2, 1.2, 1.5), A)
    v, f = weld(tris)
    assert np.array_equal(v[f], tris) and len(v) == len(np.unique(tris.reshape(-1, 3), axis=0))
    assert np.all(np.diff(v[:, 0]) >= 0)                                 # x is the key's leading coordinate
    objs = [{"name": "a", "vertices": v, "faces": f}, {"name": "b", "vertices": v[::-1] + 1, "faces": f[:, ::-1]}]
    with zipfile.ZipFile(io.BytesIO(three_mf_bytes(objs, {"Title": "t"}))) as z:
        assert z.read("3D/3dmodel.model").decode() == "".join(model_xml(objs, {"Title": "t"}))
    with pytest.raises(TypeError):                                       # the text thread's error, in the caller
        three_mf_bytes([{"name": "c", "vertices": v, "faces": np.zeros((2, 2), int)}], {})
