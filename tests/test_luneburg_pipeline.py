"""Luneburg kind end to end: spec → shells / ring layup → files (seed-002 §5.1)."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from antenna_cad.fabrication.rings import fabricate_rings, plan_rings, ring_radii
from antenna_cad.fabrication.outline import circle_polygon
from antenna_cad.geometry import kernel
from antenna_cad.materials import Material
from antenna_cad.registry import ADAPTERS, adapter
from antenna_cad.spec import SPEC_MODELS, SpecError, load_spec, parse_spec

RECIPES = Path(__file__).resolve().parents[1] / "recipes"
LUNEBURG_RECIPES = ["luneburg-classic-5", "luneburg-cube-460", "luneburg-cylinder-5", "luneburg-layup-200"]


def _spec(name):
    return load_spec(RECIPES / f"{name}.yaml")


def _data(**design):
    base = {"name": "t", "kind": "luneburg", "frequency_ghz": 10.0, "material": "polystyrene",
            "design": {"diameter_mm": 200, "layers": {"count": 4}} | design,
            "fabrication": {"method": "shells", "pins_per_shell": 0, "feed_boss": None}}
    return base


def test_registered():
    assert "luneburg" in ADAPTERS and "luneburg" in SPEC_MODELS


@pytest.mark.parametrize("name", LUNEBURG_RECIPES)
def test_recipes_load_and_synthesize(name):
    spec = _spec(name)
    kind = adapter(spec.kind)
    design = kind.synthesize(spec)
    layup, _ = kind.plan(spec, design)
    assert (layup is not None) == (spec.fabrication.method == "sheet_layup")
    figures = kind.summary(spec, design, layup)
    assert "phase_error_rms_deg" in figures and "efficiency_with_phase" in figures
    assert sum(k.startswith("layer ") for k in figures) == len(design.layers)


def test_seed_cases():
    cube = adapter("luneburg").synthesize(_spec("luneburg-cube-460"))
    assert len(cube.layers) == 7 and cube.diameter_mm == 460 and cube.focal_distance_ratio == 1.5
    cyl = adapter("luneburg").synthesize(_spec("luneburg-cylinder-5"))
    assert cyl.shape == "cylinder"
    np.testing.assert_allclose([L.eps_r for L in cyl.layers], [1.63979, 1.49072, 1.35520, 1.23200, 1.12], atol=1e-5)
    np.testing.assert_allclose([L.r_outer_mm / 150 for L in cyl.layers[:-1]], [0.5056, 0.6753, 0.7969, 0.8900], atol=1e-3)


@pytest.mark.parametrize("design, field", [
    ({"law": "classic", "focal_distance_ratio": 1.2}, "design.focal_distance_ratio"),
    ({"shape": "cylinder"}, "design.height_mm"),
    ({"law": "outer_shell"}, "design.outer_shell"),
    ({"focal_distance_ratio": 0.9}, "design.focal_distance_ratio"),
    ({"layers": {"split": "ladder"}}, "design.layers"),
    ({"shape": "cylinder", "height_mm": 10, "fab": {"pedestal_height_mm": 50}}, "fabrication.pedestal_height_mm"),
    ({"fab": {"pedestal_height_mm": 50, "pedestal_width_mm": 250}}, "fabrication.pedestal_width_mm"),
])
def test_spec_errors(design, field):
    data = _data(**{k: v for k, v in design.items() if k != "fab"})
    if "fab" in design:
        data["fabrication"] = {"method": "sheet_layup", "sheet_thickness_mm": 10} | design["fab"]
    with pytest.raises(SpecError) as e:
        parse_spec(data, "x.yaml")
    assert field in str(e.value)


def test_shell_volumes_sum_to_sphere_and_hemispheres_are_closed():
    spec = _spec("luneburg-classic-5")
    kind = adapter("luneburg")
    design = kind.synthesize(spec)
    model = kind.model(spec, design, None, ())
    R = design.radius_mm
    fabricated = [p for p in model.parts if p.label.startswith("shell-")]
    total = sum(p.volume_mm3 for p in fabricated)
    assert total == pytest.approx(4 / 3 * math.pi * R**3, rel=1e-9)
    labels = {p.label for p in model.parts}
    for L in design.layers:
        for side in ("front", "back"):
            part = model.part(f"shell-{L.index:02d}-{side}")
            assert kernel.is_valid(part.shape) and len(kernel.solids(part.shape)) == 1
            assert part.material.eps_r == L.eps_r
        assert f"shell-{L.index:02d}-pin-1" in labels
    assert next(c for c in model.checks if c.name == "shell_volume_sum").status == "pass"
    lo, hi = kernel.bounding_box([model.part("feed-boss").shape])
    assert lo[1] == pytest.approx(-R - 40) and hi[1] <= -R + 1e-6 + (R - math.sqrt(R * R - 400))


def test_hemispheres_without_pins_are_exact():
    from antenna_cad.geometry.luneburg import hemisphere_shell
    for r_in, r_out, sign in [(0.0, 80.0, 1), (50.0, 80.0, -1)]:
        s = hemisphere_shell(r_in, r_out, sign)
        assert kernel.is_valid(s) and kernel.volume(s) == pytest.approx(2 / 3 * math.pi * (r_out**3 - r_in**3), rel=1e-9)


@pytest.mark.parametrize("z_lo, z_hi", [(-100.0, -80.0), (-10.0, 10.0), (35.0, 45.0), (0.0, 20.0), (88.0, 98.0)])
def test_ring_radii_contain_and_minimal(z_lo, z_hi):
    r_in, r_out = np.array([0.0, 30.0, 60.0, 90.0]), np.array([30.0, 60.0, 90.0, 100.0])
    inner, outer = ring_radii(r_in, r_out, z_lo, z_hi, "contain")
    z = np.linspace(z_lo, z_hi, 2001)
    need_out = np.sqrt(np.maximum(r_out[:, None] ** 2 - z**2, 0)).max(axis=1)
    need_in = np.sqrt(np.maximum(r_in[:, None] ** 2 - z**2, 0)).min(axis=1)
    assert np.all(outer >= need_out - 1e-9) and np.all(inner <= need_in + 1e-9)
    np.testing.assert_allclose(outer, need_out, atol=1e-6)      # minimal: no excess
    np.testing.assert_allclose(inner, need_in, atol=1e-6)
    mi, mo = ring_radii(r_in, r_out, z_lo, z_hi, "mid_plane")
    zm = 0.5 * (z_lo + z_hi)
    np.testing.assert_allclose(mo, np.sqrt(np.maximum(r_out**2 - zm**2, 0)))
    assert np.all(mo <= outer + 1e-12) and np.all(mi >= inner - 1e-12)


def _plan(sizing="contain", t=20.0, R=100.0):
    mats = [Material(f"g{k}", 2.0 - 0.2 * k, 1e-4, 100.0 - 10 * k) for k in range(4)]
    return plan_rings([0, 0.3 * R, 0.6 * R, 0.9 * R], [0.3 * R, 0.6 * R, 0.9 * R, R], mats, shape="sphere",
                      height_mm=None, sheet_thickness_mm=t, sizing=sizing, kerf_mm=0.5, board_width_mm=600,
                      board_length_mm=1200, registration_hole_mm=6.0)


def test_layup_plan_covers_sphere_and_nests_per_grade():
    plan = _plan()
    assert plan.count == 10 and plan.sheets[0].z_min_mm == -100 and plan.sheets[-1].z_max_mm == 100
    for s in plan.sheets:
        assert [r.shell_index for r in s.rings] == sorted(r.shell_index for r in s.rings)
    fab = fabricate_rings(plan, "t", drawings=True)
    labels = {d.label for d in fab.drawings}
    assert {s.label for s in plan.sheets} <= labels and {r.label for r in plan.rings} <= labels
    for row in fab.rows:                                      # each ring on a board of its own grade
        if row.kind == "dowel-rod":
            continue
        ring = next(r for r in plan.rings if row.part.startswith(r.label))
        assert row.material == ring.material.name and row.board.startswith(ring.material.name + "-B")
    for guest, host in fab.in_hole.items():                   # discs inside ring holes fit
        gi = next(r for r in plan.rings if r.label == guest)
        hi = next(r for r in plan.rings if r.label == host)
        assert gi.material == hi.material and gi.r_outer_mm + 10 <= hi.r_inner_mm
    assert fab.in_hole and sum(fab.in_hole_saving_m2.values()) > 0
    assert fab.totals_kg["all"] == pytest.approx(sum(v for k, v in fab.totals_kg.items() if k != "all"))


@pytest.mark.parametrize("sizing", ["contain", "mid_plane"])
def test_registration_dowels_inside_their_shell(sizing):
    """Every dowel lies in the rings of both sheets it joins, in blind holes from their joint
    faces; turned (contain) it lies inside its shell along its length (so its own grade leaves
    the layer εr unchanged) except through the lens surface, which trims it — it still crosses
    the joint plane inside the lens. Off the axis; holes never overlap; every sheet joint is
    dowelled (mid-plane rings: but the polar caps', whose rings are smaller)."""
    plan = _plan(sizing, t=10.0)
    shells = {1: (0.0, 30.0), 2: (30.0, 60.0), 3: (60.0, 90.0), 4: (90.0, 100.0)}
    assert plan.dowels and plan.undowelled_joints > 0           # e.g. the thin outer shell at the equator
    rings = {(r.sheet_index, r.shell_index): r for r in plan.rings}
    for dw in plan.dowels:
        r_in, r_out = shells[dw.shell_index]
        z_joint = plan.sheets[dw.sheets[0] - 1].z_max_mm
        assert dw.length_mm == pytest.approx(10.0)                 # min(t/2, 2·Ø) into each sheet
        z_lo, z_hi = z_joint - dw.length_mm / 2, z_joint + dw.length_mm / 2
        rho = math.hypot(dw.x_mm, dw.y_mm)
        assert rho > dw.diameter_mm
        edges = rho + np.array([-1, 1]) * dw.diameter_mm / 2
        if sizing == "contain":
            z = np.linspace(z_lo, z_hi, 101)[:, None]
            rr = np.hypot(edges, z)
            assert np.all(rr >= r_in - 1e-9)
            assert np.all(rr <= r_out + 1e-9) if dw.shell_index < 4 else np.all(np.hypot(edges, z_joint) <= r_out)
        for k, face in zip(dw.sheets, ("top", "bottom")):
            ring = rings[(k, dw.shell_index)]
            assert any((h.x_mm, h.y_mm, h.face, h.depth_mm) == (dw.x_mm, dw.y_mm, face, 5.0) for h in ring.holes)
            assert ring.r_inner_mm <= edges[0] and edges[1] <= ring.r_outer_mm
    for ring in plan.rings:
        pts = np.array([(h.x_mm, h.y_mm) for h in ring.holes]).reshape(-1, 2)
        gaps = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1)) + np.eye(len(pts)) * 1e9
        assert np.all(gaps >= 6.0 + 3.0)
    loose = {(k, k + 1) for k in range(1, plan.count)} - {dw.sheets for dw in plan.dowels}
    assert loose == (set() if sizing == "contain" else {(1, 2), (19, 20)})
    if sizing == "contain":   # equator joint, z −5…5: 90–99.9 mm is too thin for the 4th shell
        assert sorted({d.shell_index for d in plan.dowels if d.sheets == (10, 11)}) == [1, 2, 3]


def test_dowels_clear_sector_joints():
    mats = [Material("g", 1.5, 1e-4, 50.0)]
    plan = plan_rings([0.0], [900.0], mats, shape="sphere", height_mm=None, sheet_thickness_mm=30.0,
                      sizing="contain", kerf_mm=0.5, board_width_mm=600, board_length_mm=1200,
                      registration_hole_mm=8.0)
    split = [r for r in plan.rings if r.sectors > 1 and r.holes]
    assert split
    for r in split:                                          # radial joints keep clear of the holes
        for h in r.holes:
            rho, a = math.hypot(h.x_mm, h.y_mm), math.atan2(h.y_mm, h.x_mm)
            delta = (a - r.joint_angles_rad + math.pi) % (2 * math.pi) - math.pi
            assert np.all(np.abs(delta) * rho >= 4.0 + 3.0 - 1e-6)
    fab = fabricate_rings(plan, "t", drawings=False)
    for p in fab.pieces:                                     # every hole lies wholly in one piece
        for h in p.holes:
            assert p.polygon.contains(circle_polygon(h.x_mm, h.y_mm, h.diameter_mm / 2 + 1.0).exterior)


def test_stand_feet_stay_below_the_aperture_and_are_dowelled():
    from shapely.geometry import Point
    spec = _spec("luneburg-layup-200")
    kind = adapter("luneburg")
    design = kind.synthesize(spec)
    layup, _ = kind.plan(spec, design)
    fab = kind.fabricate(spec, design, layup, ())
    R = design.radius_mm
    feet = [p for p in fab.pieces if p.label.endswith("-foot")]
    outer = kind.layer_materials(spec, design)[-1].name
    assert len(feet) == layup.count
    for p in feet:                                              # outside the aperture disc, below the lens
        assert p.polygon.intersection(Point(0, 0).buffer(R - 0.01, 256)).area < 1e-6
        assert p.polygon.bounds[1] == pytest.approx(-R - 60.0) and p.polygon.bounds[3] <= -0.5 * R
        assert p.polygon.is_valid and p.material.name == outer
        assert fab.placements[p.label].board_id.startswith(outer + "-B")
    joined = {dw.sheets for dw in layup.dowels if dw.shell_index == 0}
    assert joined == {(k, k + 1) for k in range(1, layup.count)}
    assert next(c for c in kind.fabrication_checks(spec, design, layup) if c.name == "stand_outside_aperture").status == "pass"


def test_mid_plane_rings_butt():
    plan = _plan("mid_plane")
    for s in plan.sheets:
        for a, b in zip(s.rings, s.rings[1:]):
            if b.shell_index == a.shell_index + 1 and b.r_inner_mm > 0:
                assert a.r_outer_mm == pytest.approx(b.r_inner_mm)


def _read_back(out: Path, expect_templates: bool):
    import ezdxf
    import trimesh
    from build123d import import_step
    manifest = json.loads((out / "manifest.json").read_text())
    step = import_step(out / f"{manifest['name']}.step")
    assert len(step.solids()) == len(manifest["parts"])
    for part in manifest["parts"]:
        assert part["valid"] and part["watertight"]
        mesh = trimesh.load(out / part["file"])
        mesh.merge_vertices()
        assert mesh.is_watertight
        assert mesh.volume == pytest.approx(part["volume_mm3"], rel=2e-2)
    dxfs = sorted((out / "templates").glob("*.dxf")) if expect_templates else []
    assert bool(dxfs) == expect_templates
    for f in dxfs[:12]:
        doc = ezdxf.readfile(f)
        auditor = doc.audit()
        assert not auditor.has_errors and doc.header["$INSUNITS"] == 4
    rows = list(csv.DictReader((out / "cutlist.csv").open()))
    assert rows and any(r["part"].startswith("TOTAL all") for r in rows)
    return manifest


def test_cylinder_build_reads_back(tmp_path):
    from antenna_cad.pipeline import build
    result = build(_spec("luneburg-cylinder-5"), tmp_path)
    manifest = _read_back(result.out_dir, expect_templates=True)
    assert len(manifest["sheets"]) == 1 and len(manifest["sheets"][0]["rings"]) == 5
    assert len([m for m in manifest["mass_kg"] if m != "all"]) == 5


@pytest.mark.slow
@pytest.mark.parametrize("name", ["luneburg-classic-5", "luneburg-cube-460", "luneburg-layup-200"])
def test_recipe_builds_read_back(tmp_path, name):
    from antenna_cad.pipeline import build
    spec = _spec(name)
    result = build(spec, tmp_path)
    assert result.status != "fail"
    manifest = _read_back(result.out_dir, expect_templates=spec.fabrication.method == "sheet_layup")
    if spec.fabrication.method == "sheet_layup":
        assert {c.name for c in result.checks} >= {"ring_fit", "rings_in_holes"}
        assert sum(len(s["rings"]) for s in manifest["sheets"]) == manifest["figures"]["ring_count"]
    else:
        assert any(p["label"] == "shell-01-front" for p in manifest["parts"])


def test_large_rings_split_into_sectors_that_fit_boards():
    from shapely import affinity
    from antenna_cad.fabrication.outline import fits_board
    from antenna_cad.fabrication.rings import RingPlan, ring_pieces, sector_count
    for r_in in (0.0, 700.0):
        k = sector_count(r_in, 800.0, 600.0, 1200.0, 0.5)
        assert k > 1
        ring = RingPlan("sheet-02-ring-03", 2, 3, r_in, 800.0, Material("g", 1.5, 1e-4, 50.0), k, 0.1)
        whole = RingPlan("w", 2, 3, r_in, 800.0, ring.material)
        parts = ring_pieces(ring, 10.0)
        assert len(parts) == k and len({p.label for p in parts}) == k
        assert sum(p.polygon.area for p in parts) == pytest.approx(ring_pieces(whole, 10.0)[0].polygon.area, rel=1e-6)
        assert sum(p.area_mm2 for p in parts) == pytest.approx(math.pi * (800.0**2 - r_in**2), rel=1e-12)
        for p in parts:
            x0, y0, x1, y1 = affinity.rotate(p.cut_path(0.5), p.nest_rotation_deg, origin=(0, 0)).bounds
            w, h = p.size_mm(0.5)
            assert p.polygon.is_valid and fits_board(w, h, 600.0, 1200.0)
            assert 0 <= w - (x1 - x0) < 0.01 and 0 <= h - (y1 - y0) < 0.01      # analytic size holds the path
            assert p.cut_path(0.5).contains(p.polygon)


@pytest.mark.parametrize("shape, R", [("sphere", 700.0), ("cylinder", 300.0)])
def test_dxf_cut_paths_are_true_arcs_matching_the_polylines(tmp_path, shape, R):
    """Ring pieces go to the DXF as bulge arcs (CNC: exact circles, small files); read back and
    flattened by ezdxf they must match the polylines of the SVG/PDF within their chord tolerance
    (a wrong bulge sign or order would be off by a radius). R = 700 mm on 600 × 1200 boards:
    ring and disc sectors (the Ø700 mm core); the cylinder: through dowel holes."""
    import ezdxf
    import shapely
    from shapely.geometry import LinearRing

    from antenna_cad.fabrication.templates import write_dxf
    mats = [Material(f"g{k}", 2.0 - 0.2 * k, 1e-4, 100.0 - 10 * k) for k in range(2)]
    plan = plan_rings([0, 0.5 * R], [0.5 * R, R], mats, shape=shape,
                      height_mm=40.0 if shape == "cylinder" else None, sheet_thickness_mm=40.0 if shape == "cylinder"
                      else 100.0, sizing="contain", kerf_mm=0.5, board_width_mm=600, board_length_mm=1200,
                      registration_hole_mm=6.0)
    fab = fabricate_rings(plan, "t", drawings=True)
    kinds = set()
    for d in fab.drawings:
        write_dxf(d, tmp_path / "d.dxf")
        cut = ezdxf.readfile(tmp_path / "d.dxf").modelspace().query("LWPOLYLINE[layer=='CUT']")
        assert len(cut) == len(d.cut) and len(d.arcs) == len(d.cut)
        for k, (entity, ring) in enumerate(zip(cut, d.cut)):
            bulges = [p[4] for p in entity.get_points()]
            assert any(bulges)                                                   # true arcs, not facets
            exact = np.array(_exact_points(entity.get_points("xyb")))
            off = max(shapely.distance(shapely.points(exact), LinearRing(ring)).max(),
                      shapely.distance(shapely.points(np.array(ring)), LinearRing(exact)).max())
            assert off < 0.012, (d.label, k)                                     # hole chord tol 0.01
            kinds.add("circle" if len(bulges) == 2 else "sector" if len(bulges) == 4 else "disc sector")
    assert {"circle", "sector"} <= kinds and (shape == "cylinder" or "disc sector" in kinds)


def _exact_points(vertices, step_rad: float = 1e-3) -> list[tuple[float, float]]:
    """A closed bulge path sampled on its true arcs (ezdxf's exact bulge → arc conversion; its
    path flattening uses Bézier approximations 0.05 mm off on a 192 mm radius)."""
    from ezdxf.math import bulge_to_arc
    points = []
    for (x0, y0, b), (x1, y1, _) in zip(vertices, list(vertices[1:]) + [vertices[0]]):
        points.append((x0, y0))
        if b:
            centre, a_start, a_end, r = bulge_to_arc((x0, y0), (x1, y1), b)
            sweep = (a_end - a_start) % (2 * math.pi)
            angles = a_start + np.linspace(0.0, sweep, max(2, int(sweep / step_rad)))[1:-1]
            arc = [(centre.x + r * math.cos(a), centre.y + r * math.sin(a)) for a in angles]
            points += arc if b > 0 else arc[::-1]
    return points
