"""Taper-cut (``edge: taper``) layups beyond the collimator: each sheet's cone passes through the lens's
half-width at its two faces (solved here independently from the face profiles), every hot-wire file
parses back (gcodeparser) and rebuilds the cone + kerf/2 within the check's tolerance, and the check
fails on a wire moved by a tenth of a millimetre."""

import numpy as np
import pytest
from scipy.optimize import brentq

from antenna_cad.export.check_cam import CAM_TOL_MM, check_cam, parse_moves
from antenna_cad.pipeline import prepare
from tests.test_cam import _spec, _surface_errors, _write, moved_wire_failures

FACE_TOL_MM = 1e-6          # cone radius vs the lens half-width at a sheet face
WIDE_HOTWIRE = {"travel_mm": [2000, 2000], "lead_in_mm": 10}     # steep cones swing the towers far


def _taper_build(tmp_path_factory, recipe: str):
    """(spec, plan, folder, manifest) of ``recipe`` taper-cut, its cam files written."""
    spec = _spec(recipe, edge="taper", cam=WIDE_HOTWIRE)
    plan = prepare(spec)
    folder = tmp_path_factory.mktemp(recipe.removesuffix(".yaml"))
    return spec, plan, folder, _write(plan, spec, folder)


def _assert_cones_rebuilt(folder, manifest, cones: int) -> None:
    """Every cam file passes the check, ``cones`` of them rebuilt as cones within the tolerance."""
    findings = check_cam(folder, manifest)
    assert findings and all(f.ok for f in findings), [f for f in findings if not f.ok][:3]
    errors = _surface_errors(findings)
    assert len(errors) == cones and max(errors) <= CAM_TOL_MM


@pytest.fixture(scope="module")
def bifocal(tmp_path_factory):
    """The seed's Ø1 m bifocal lens (X_B = 9 m), 50 mm boards."""
    return _taper_build(tmp_path_factory, "bifocal-nikulina-9m.yaml")


def _bifocal_half_width(design, z: float) -> float:
    """The lens's half-width at depth z from its Hermite faces: the illuminated face before the rim,
    the shadow face behind it, 0 outside the lens."""
    if z <= design.rho1_mm or z >= design.rho2_mm:
        return 0.0
    surface = "illuminated" if z <= design.edge_x_mm else "shadow"
    return brentq(lambda y: float(design.profile(surface, y)) - z, 0.0, design.edge_y_mm, xtol=1e-12)


def test_bifocal_cones_pass_through_the_lens_at_both_faces(bifocal):
    spec, plan, folder, manifest = bifocal
    design, layup = plan.design, plan.layup
    assert layup.edge == "taper" and all(s.tapered for s in layup.sheets)
    worst = max(abs(r - _bifocal_half_width(design, z)) for s in layup.sheets
                for r, z in zip(s.cone_mm, (s.z_min_mm, s.z_max_mm)))
    assert worst < FACE_TOL_MM
    fronts, backs = zip(*(s.cone_mm for s in layup.sheets))
    rim = next(s for s in layup.sheets if s.z_min_mm < design.edge_x_mm < s.z_max_mm)
    assert all(b > f for f, b, s in zip(fronts, backs, layup.sheets) if s.z_max_mm < design.edge_x_mm)
    assert all(b < f for f, b, s in zip(fronts, backs, layup.sheets) if s.z_min_mm > design.edge_x_mm)
    assert max(rim.cone_mm) < design.edge_y_mm          # the chord across the rim
    assert [c for c in plan.checks if c.name == "sheet_cone_fit"][0].status == "pass"


def test_bifocal_gcode_rebuilds_every_cone_and_a_moved_wire_fails(bifocal):
    spec, plan, folder, manifest = bifocal
    _assert_cones_rebuilt(folder, manifest, plan.layup.count)
    assert moved_wire_failures(folder, manifest, _steepest_cone_file(plan, manifest)) == ["cam_surface"]


def test_bifocal_shadow_side_dowels_are_drilled_from_the_front(bifocal):
    spec, plan, folder, manifest = bifocal
    last = plan.layup.sheets[-1]
    assert last.drilled_from_front and not plan.layup.sheets[0].drilled_from_front
    text = (folder / f"cam/{last.label}-drill.gcode").read_text()
    depths = [float(w[1:]) for line in text.splitlines() if line.startswith("G81") for w in line.split() if w[0] == "Z"]
    assert "front (feed-side) face" in text and depths and all(-last.thickness_mm < d < 0 for d in depths)


def test_bifocal_taper_gap_table_follows_the_lens(bifocal):
    """The cones lie far closer to the profile than a full step, except at the rim chord and the
    two vertex caps."""
    from antenna_cad.kinds.bifocal import _lens
    from antenna_cad.asbuilt.taper import Taper
    spec, plan, folder, manifest = bifocal
    gaps = np.array(Taper(_lens(spec, plan.design, plan.layup), plan.layup).largest_gap_mm())
    t = plan.layup.sheet_thickness_mm
    assert np.all(gaps > 0) and np.all(gaps < t / 2)
    inner = [g for g, s in zip(gaps, plan.layup.sheets)
             if 1 < s.index < plan.layup.count and not s.z_min_mm < plan.design.edge_x_mm < s.z_max_mm]
    assert max(inner) < t / 10


def _steepest_cone_file(plan, manifest) -> str:
    """The hot-wire file of the steepest non-vertical cone (a radial move of the wire is nearly
    normal to it), a whole disc or a glued blank."""
    files = {e["part"]: e["file"] for e in manifest["cam"] if "faces" in e}
    cones = [s for s in plan.layup.sheets if abs(s.cone_mm[1] - s.cone_mm[0]) > 1.0]
    s = min(cones, key=lambda s: abs(s.cone_mm[1] - s.cone_mm[0]))
    return files.get(s.label) or files[f"{s.label}-blank"]


@pytest.fixture(scope="module")
def mirror_lens(tmp_path_factory):
    """The seed-004 feed-on-surface mirror-lens (D 346 mm), 30 mm sheets."""
    return _taper_build(tmp_path_factory, "mirror-lens-feed-on-surface.yaml")


def test_mirror_lens_cones_pass_through_the_body_at_both_faces(mirror_lens):
    from shapely.geometry import LineString, Polygon
    spec, plan, folder, manifest = mirror_lens
    body = Polygon(plan.design.section_mm())                 # (r, z) section of the body

    def half_width(z):
        cut = body.intersection(LineString([(0.0, z), (1e4, z)]))
        return 0.0 if cut.is_empty else cut.bounds[2]
    layup = plan.layup
    assert all(s.tapered for s in layup.sheets)
    worst = max(abs(r - half_width(z)) for s in layup.sheets for r, z in zip(s.cone_mm, (s.z_min_mm, s.z_max_mm)))
    assert worst < FACE_TOL_MM
    assert [c for c in plan.checks if c.name == "sheet_cone_fit"][0].status == "pass"


def test_mirror_lens_gcode_rebuilds_every_cone_and_a_moved_wire_fails(mirror_lens):
    spec, plan, folder, manifest = mirror_lens
    _assert_cones_rebuilt(folder, manifest, sum(abs(s.cone_mm[1] - s.cone_mm[0]) > 1e-6 for s in plan.layup.sheets))
    assert moved_wire_failures(folder, manifest, _steepest_cone_file(plan, manifest)) == ["cam_surface"]


@pytest.fixture(scope="module")
def luneburg(tmp_path_factory):
    """The 5-layer Ø200 mm sphere of 10 mm sheets."""
    return _taper_build(tmp_path_factory, "luneburg-layup-200.yaml")


def test_luneburg_ring_cones_pass_through_their_spheres_at_both_faces(luneburg):
    spec, plan, folder, manifest = luneburg
    shells = {L.index: L for L in plan.design.layers}
    worst, discs = 0.0, 0
    for s in plan.layup.sheets:
        for r in s.rings:
            sh = shells[r.shell_index]
            for z, outer, inner in zip((s.z_min_mm, s.z_max_mm), r.cone_outer_mm, r.cone_inner_mm):
                worst = max(worst, abs(outer - np.sqrt(max(sh.r_outer_mm**2 - z * z, 0.0))))
                if max(r.cone_inner_mm) > 0:
                    worst = max(worst, abs(inner - np.sqrt(max(sh.r_inner_mm**2 - z * z, 0.0))))
            discs += max(r.cone_inner_mm) == 0 and sh.r_inner_mm > min(abs(s.z_min_mm), abs(s.z_max_mm))
    assert worst < FACE_TOL_MM
    assert discs > 0 and plan.layup.dropped_caps > 0          # discs over the inner poles, caps inside them
    checks = {c.name: c.status for c in plan.checks}
    assert checks["ring_cone_fit"] == "pass" and checks["taper_dropped_caps"] == "warn"


def test_luneburg_gcode_rebuilds_every_ring_edge_and_a_moved_wire_fails(luneburg):
    spec, plan, folder, manifest = luneburg
    _assert_cones_rebuilt(folder, manifest, sum(1 + (max(r.cone_inner_mm) > 0) for r in plan.layup.rings))
    inner = [e for e in manifest["cam"] if e.get("edge") == "inner"]
    assert inner and all(e["sphere_mm"] > 0 for e in inner)
    # the equator sheet's outermost ring: steep cones, a radial move of the wire nearly normal to them
    assert moved_wire_failures(folder, manifest, "cam/sheet-11-ring-05-inner.gcode") == ["cam_surface"]
    assert moved_wire_failures(folder, manifest, "cam/sheet-11-ring-05-outer.gcode") == ["cam_surface"]


def test_luneburg_taper_needs_contain_blanks():
    """(A ``cam`` block on stepped rings writes router files instead: tests/test_cam_router.py.)"""
    with pytest.raises(ValueError, match="edge: taper needs ring_sizing: contain"):
        _spec("luneburg-layup-200.yaml", edge="taper", ring_sizing="mid_plane")


def test_mirror_lens_and_ring_tables_show_each_cone_and_its_gap(mirror_lens, luneburg):
    """The layer tables: every sheet's (ring's) cones with the largest gap to the profile, which is
    zero on the body's cylinder and far below a sheet elsewhere."""
    from antenna_cad.kinds.luneburg import _ring_cone_table
    from antenna_cad.kinds.mirror_lens import cone_radius
    from antenna_cad.asbuilt.taper import cone_table
    spec, plan, _, _ = mirror_lens
    rows = cone_table(plan.layup, cone_radius(spec, plan.design)).rows
    assert [r[0] for r in rows] == [s.label for s in plan.layup.sheets]
    gaps = [r[-1] for r in rows]
    assert min(gaps) < 1e-6 and 0 < max(gaps) < plan.layup.sheet_thickness_mm / 2
    spec, plan, _, _ = luneburg
    rows = _ring_cone_table(plan.layup, {L.index: L for L in plan.design.layers}).rows
    assert len(rows) == len(plan.layup.rings)
    assert 0 < max(r[-1] for r in rows) < plan.layup.sheet_thickness_mm / 2


def test_bifocal_auto_stock_is_thicker_with_cones(monkeypatch):
    """sheet_thickness_mm: auto picks the thickest board meeting the budget unsanded (fast model, taken
    as exact: its measured error would leave every candidate undecided): taper-cut sheets may be far
    thicker (measured 100 vs 30 mm, docs/guide/cam.md)."""
    from antenna_cad.quietzone.verdict import FAST_ERROR_DEG
    monkeypatch.setitem(FAST_ERROR_DEG, "own_phase_p2p_deg", 0.0)
    chosen = {}
    for edge in ("stepped", "taper"):
        plan = prepare(_spec("bifocal-nikulina-9m.yaml", edge=edge, sheet_thickness_mm="auto"))
        chosen[edge] = plan.layup.sheet_thickness_mm
    assert chosen["taper"] > chosen["stepped"]


def test_graded_slabs_get_straight_wire_cuts_of_their_exact_outlines(tmp_path):
    """A graded lens is planar: each sheet's outline is its slab's section, cut straight (XY = UV).
    Every file parses back and its wire, rebuilt on the foam face, lies kerf/2 outside the piece
    within the check's tolerance; a wire tilted by one tower moved 0.1 mm fails the check."""
    from shapely.geometry import LineString, Polygon
    from antenna_cad.export.check_cam import _faces
    spec = _spec("graded-trifocal-160mm-foam.yaml", cam={})
    plan = prepare(spec)
    manifest = _write(plan, spec, tmp_path)
    findings = check_cam(tmp_path, manifest)
    assert findings and all(f.ok for f in findings), [f for f in findings if not f.ok][:3]
    pieces = {p.label: p for p in plan.fab.pieces}
    hot = [e for e in manifest["cam"] if "faces" in e]
    assert {e["part"] for e in hot} == set(pieces)
    worst = 0.0
    for e in hot:
        moves, cutting = parse_moves((tmp_path / e["file"]).read_text(), e["axes"])
        front, back = _faces(e, [p for p, g in zip(moves, cutting) if g][1:-2])
        assert np.allclose(front, back)
        target = Polygon(pieces[e["part"]].polygon.exterior).buffer(e["kerf_mm"] / 2, quad_segs=64)
        worst = max(worst, LineString(front).hausdorff_distance(target.exterior))
    assert worst <= CAM_TOL_MM
    name = hot[0]["file"]
    lines = (tmp_path / name).read_text().splitlines()
    k = [i for i, line in enumerate(lines) if line.startswith("G1 ")][5]
    words = lines[k].split()
    words[1] = f"X{float(words[1][1:]) + 0.1:.4f}"
    (tmp_path / "bad/cam").mkdir(parents=True)
    (tmp_path / "bad" / name).write_text("\n".join(lines[:k] + [" ".join(words)] + lines[k + 1:]) + "\n")
    entry = next(e for e in manifest["cam"] if e["file"] == name)
    assert [f.check for f in check_cam(tmp_path / "bad", manifest | {"cam": [entry]}) if not f.ok] == ["cam_surface"]


def test_luneburg_as_built_traces_the_ring_cones():
    """The as-built trace of a taper-cut sphere goes through its rings' cones (every ring edge of the
    traced medium, at both sheet faces, is a ring's cone), not through the spheres: the aperture
    path differs from the turned shells' by the cones' chords (0.78 mm RMS at 10 mm sheets: the
    feed at the pole sees the polar caps' long chords), and about half that at 5 mm."""
    from antenna_cad.kinds import luneburg_verify as lv
    rms = []
    for t in (10.0, 5.0):
        spec = _spec("luneburg-layup-200.yaml", edge="taper", sheet_thickness_mm=t)
        plan = prepare(spec)
        design, layup = plan.design, plan.layup
        eps = np.array([L.eps_r_design for L in design.layers])
        medium = lv._staircase(design, layup, eps)
        for k, sheet in enumerate(layup.sheets):
            finite = np.isfinite(medium.breaks[k])
            edges = np.column_stack([medium.breaks[k][finite], medium.breaks[k][finite] + medium.slopes[k][finite] * t])
            outer = np.array([r.cone_outer_mm for r in sheet.rings])
            cones = np.concatenate([outer, [r.cone_inner_mm for r in sheet.rings]])
            assert all(np.abs(edges - c).max(axis=1).min() < 1e-9 for c in outer)
            assert all(np.abs(cones - e).max(axis=1).min() < 1e-9 for e in edges)
        cut = lv._lenses(spec, design, layup, eps, as_built_only=True)["as_built"].fan()
        shells = lv._traced(design, lv._shells(design, eps)).fan()
        ok = cut.ok & shells.ok
        diff, w = cut.opl_mm[ok] - shells.opl_mm[ok], cut.weight[ok]
        rms.append(float(np.sqrt(np.average((diff - np.average(diff, weights=w)) ** 2, weights=w))))
    assert 0.3 < rms[0] < 1.5 and 1.4 < rms[0] / rms[1] < 2.6


def test_luneburg_taper_holes_and_feet_go_to_the_router(luneburg):
    """What the wire cannot cut: every dowel hole of every ring piece is one drilling cycle, in the
    file of the face it opens on (the bottom face's seen from below, x mirrored), to its depth; the
    feet are profiled per board and their router files pass the check against the feet alone."""
    from antenna_cad.export.check_cam import drill_cycles
    from antenna_cad.fabrication.ring_pieces import FootPiece, RingPiece
    spec, plan, folder, manifest = luneburg
    expected, found = {}, {}
    for piece in (p for p in plan.fab.pieces if isinstance(p, RingPiece)):
        for h in piece.holes:
            face, x = ("bottom", -h.x_mm) if h.face == "bottom" else ("top", h.x_mm)
            depth = piece.thickness_mm if h.face == "through" else h.depth_mm
            expected.setdefault((piece.label, face), []).append((x, h.y_mm, -depth))
    for entry in manifest["cam"]:
        if "-drill-" in entry["file"]:
            face = entry["file"].removesuffix(".gcode").rsplit("-", 1)[1]
            found[(entry["part"], face)] = drill_cycles((folder / entry["file"]).read_text())
    assert expected and sorted(found) == sorted(expected)
    for key, holes in expected.items():
        assert len(found[key]) == len(holes)
        assert np.abs(np.array(sorted(found[key])) - np.array(sorted(holes))).max() < 1e-3
    boards = [e for e in manifest["cam"] if e["file"].startswith("cam/board-")]
    feet = {p.label for p in plan.fab.pieces if isinstance(p, FootPiece)}
    assert boards and {name for e in boards for name in e["part"].split(", ")} == feet
