"""As-built verification of the Luneburg kind: tracers against closed forms, the ideal
lens against the focusing condition, stepping and grade quantization, first-order shortcuts
against re-traces, and the figures in the manifest (seed-002 §2.1, §2.1b, §2.5)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate
from scipy.interpolate import CubicSpline

from antenna_cad.kinds import luneburg_verify as lv
from antenna_cad.raytrace.graded import trace_graded
from antenna_cad.raytrace.luneburg import (added_phase_rms, fan_figures, feed_fan, feed_move_opl, first_order_opl,
                                           focus_shift, launch_angles)
from antenna_cad.raytrace.media import Shells, Staircase, trace_media
from antenna_cad.registry import adapter
from antenna_cad.spec import load_spec, parse_spec
from antenna_cad.synthesis import luneburg as lb

RECIPES = Path(__file__).resolve().parents[1] / "recipes"
KIND = adapter("luneburg")


def _shells_fan(M, law="generalized", b=1.5, R=230.0, q=4.0, n=512):
    radii, eps = lb.layer_split(M, "equal_eps", law, b)
    medium = Shells(radii * R, np.sqrt(eps))
    return feed_fan(lambda o, d: trace_media(medium, o, d), R, b * R, q, "sphere", n_rays=n), medium


# ---------------------------------------------------------------- tracers

def test_media_shells_match_the_closed_form_tracer():
    """Event tracer through concentric shells = the analytic §2.1b sweep/path tracer (1e-9 mm)."""
    R, b = 150.0, 1.5 * 150.0
    radii, eps = lb.layer_split(5, "equal_eps", "generalized", 1.5)
    k = np.linspace(0.01, 0.99, 61) * R
    ref = lb.trace_shells(radii * R, eps, b, impact_mm=k, aperture_z_mm=2 * R)
    th = np.arcsin(k / b)
    tr = trace_media(Shells(radii * R, np.sqrt(eps)), np.tile([-b, 0.0], (len(k), 1)),
                     np.stack([np.cos(th), np.sin(th)], 1))
    t = (2 * R - tr.end[:, 0]) / tr.direction[:, 0]
    ok = ref.valid
    np.testing.assert_allclose((tr.opl + t)[ok], ref.optical_path_mm[ok], atol=1e-9)
    np.testing.assert_allclose((tr.end[:, 1] + t * tr.direction[:, 1])[ok], ref.aperture_x_mm[ok], atol=1e-9)


def test_staircase_slab_and_riser_follow_snell():
    """One sheet of index n between z = 0 and t: the plate shift and path of a tilted ray; a riser
    between two rings refracts by Snell on the plane y = const."""
    n, t = 1.5, 10.0
    slab = Staircase.from_rings([0.0, t], [[(0.0, 1000.0, n)]])
    a = math.radians(30)
    tr = trace_media(slab, [[-5.0, 0.0]], [[math.cos(a), math.sin(a)]])
    inner = math.asin(math.sin(a) / n)
    y_exit = 5 * math.tan(a) + t * math.tan(inner)
    assert tr.exit_zy[0] == pytest.approx([t, y_exit], abs=1e-9)
    assert tr.exit_opl[0] == pytest.approx(5 / math.cos(a) + n * t / math.cos(inner), abs=1e-9)
    rings = Staircase.from_rings([0.0, 100.0], [[(0.0, 20.0, 1.6), (20.0, 40.0, 1.2)]])
    b_ = math.radians(70)                                    # from the disc into the outer ring
    tr = trace_media(rings, [[1.0, 0.0]], [[math.cos(b_), math.sin(b_)]], max_events=4)
    cross = tr.points[1, 0]
    assert cross[1] == pytest.approx(20.0)
    d = tr.points[2, 0] - cross
    out = math.atan2(d[0], d[1])                             # angle to the riser normal (+y)
    assert 1.2 * math.sin(out) == pytest.approx(1.6 * math.sin(math.radians(20)), abs=1e-12)


def test_a_sloped_ring_edge_is_met_on_its_cone_and_refracts_by_snell():
    """A disc of index 1.5 whose edge is the cone y = 20 + 0.5 z (0 ≤ z ≤ 10): a ray along +y at
    z = 4 meets it at y = 22, refracting about the normal (−0.5, 1)/√1.25."""
    disc = Staircase.from_cones([0.0, 10.0], [[((0.0, 0.0), (20.0, 25.0), 1.5)]])
    assert disc.slopes[0, 0] == pytest.approx(0.5)
    tr = trace_media(disc, [[4.0, 0.0]], [[0.0, 1.0]], max_events=3)
    hit = tr.points[1, 0]
    assert hit == pytest.approx([4.0, 22.0], abs=1e-9)
    normal = np.array([-0.5, 1.0]) / math.sqrt(1.25)
    d_out = tr.points[2, 0] - hit
    d_out /= np.linalg.norm(d_out)
    cross = lambda u, v: u[0] * v[1] - u[1] * v[0]                      # noqa: E731  sine of the angle
    assert abs(cross(normal, d_out)) == pytest.approx(1.5 * abs(cross(normal, [0.0, 1.0])), abs=1e-12)
    mirrored = trace_media(disc, [[4.0, 0.0]], [[0.0, -1.0]], max_events=3)     # the other side of the axis
    assert mirrored.points[1, 0] == pytest.approx([4.0, -22.0], abs=1e-9)
    flat = Staircase.from_cones([0.0, 10.0], [[((0.0, 0.0), (20.0, 20.0), 1.5)]])
    rings = Staircase.from_rings([0.0, 10.0], [[(0.0, 20.0, 1.5)]])
    assert flat.slopes is None and rings.slopes is None and np.array_equal(flat.breaks, rings.breaks)


def test_taper_cut_sheets_converge_to_the_sphere():
    """A homogeneous sphere (R 100 mm, n 1.4) cut into sheets whose edges are the cones through it
    at each face: the optical paths of 101 rays from a point 300 mm before it, to a plane behind,
    approach those through the sphere as the sheets thin — the mean error halves with the sheet
    thickness (first order: paraxial rays enter through the polar cap, whose cone's chord is
    √(2Rt) long) — while vertical-edged sheets at their mid-plane radii stay ~2 mm off (GO
    through the risers)."""
    R, n = 100.0, 1.4
    th = np.linspace(0.0, 0.25, 101)
    start, direction = np.tile([-300.0, 0.0], (101, 1)), np.stack([np.cos(th), np.sin(th)], 1)
    far = lambda t: t.opl + (400.0 - t.end[:, 0]) / t.direction[:, 0]     # noqa: E731  to the plane z = 400
    exact = far(trace_media(Shells(np.array([R]), np.array([n])), start, direction))

    def error(sheets: int, cones: bool) -> float:
        z = np.linspace(-R, R, sheets + 1)
        rim = np.sqrt(np.maximum(R * R - z * z, 0.0))
        mid = np.sqrt(R * R - (0.5 * (z[1:] + z[:-1])) ** 2)
        rings = [[((0.0, 0.0), (a, b) if cones else (m, m), n)] for a, b, m in zip(rim[:-1], rim[1:], mid)]
        return float(np.mean(np.abs(far(trace_media(Staircase.from_cones(z, rings), start, direction)) - exact)))
    errors = [error(k, True) for k in (40, 80, 160)]
    assert 1.6 < errors[0] / errors[1] < 2.5 and 1.6 < errors[1] / errors[2] < 2.5 and errors[2] < 0.3
    assert error(160, False) > 5 * errors[2]


def test_straight_paths_through_cones_match_their_index():
    """trace_media's distances to sloped edges agree with ``index``: the optical path of straight
    lines through a two-ring cone stack equals a dense sum of index samples along them."""
    stack = Staircase.from_cones([-20.0, 0.0, 15.0], [[((0.0, 0.0), (10.0, 18.0), 1.5), ((10.0, 18.0), (25.0, 26.0), 1.2)],
                                                     [((0.0, 0.0), (18.0, 12.0), 1.4), ((18.0, 12.0), (26.0, 20.0), 1.1)]])
    rng = np.random.default_rng(3)
    start = np.column_stack([rng.uniform(-30, 25, 40), rng.uniform(-30, 30, 40)])
    angle = rng.uniform(0, 2 * math.pi, 40)
    direction = np.column_stack([np.cos(angle), np.sin(angle)])
    tr = trace_media(stack, start, direction, stop_mm=np.full(40, 60.0), straight=True)
    t = (np.arange(100000) + 0.5) / 100000 * 60.0
    for i in range(40):
        dense = stack.index(start[i] + t[:, None] * direction[i]).mean() * 60.0
        assert tr.opl[i] == pytest.approx(dense, abs=2e-3)


def test_first_order_path_integrates_the_staircase_along_the_rays():
    """∫n ds through a staircase along traced polylines (+ their extension) = a dense sum of index
    samples along the same lines (to the sampling error, 1e-4 mm over ~400 mm)."""
    R = 100.0
    radii, eps = lb.layer_split(4, "equal_eps", "classic", 1.0)
    shells = Shells(radii * R, np.sqrt(eps))
    z = np.linspace(-R, R, 11)
    zm = 0.5 * (z[1:] + z[:-1])[:, None]
    inner = np.sqrt(np.maximum(np.concatenate([[0], radii[:-1]]) ** 2 * R**2 - zm**2, 0))
    outer = np.sqrt(np.maximum((radii * R) ** 2 - zm**2, 0))
    stair = Staircase.from_rings(z, [[(a, b, math.sqrt(e)) for a, b, e in zip(i, o, eps) if b - a > 1e-9]
                                     for i, o in zip(inner, outer)])
    th = np.linspace(-1.2, 1.2, 9)
    ref = trace_media(shells, np.tile([-150.0, 0.0], (9, 1)), np.stack([np.cos(th), np.sin(th)], 1))
    extra = first_order_opl(stair, ref, 20.0)
    pts = np.concatenate([ref.points, (ref.end + 20.0 * ref.direction)[None]])
    for i in range(9):
        dense = 0.0
        for a, b in zip(pts[:-1, i], pts[1:, i]):
            length = np.linalg.norm(b - a)
            if length > 0:
                t = (np.arange(200000) + 0.5) / 200000
                dense += stair.index(a + t[:, None] * (b - a)).mean() * length
        assert extra[i] + ref.opl[i] + 20.0 == pytest.approx(dense, abs=1e-4)
    assert np.any(np.abs(extra) > 0.1)                         # the staircase differs from the shells


def test_ideal_continuous_law_focuses():
    """RK4 trace of the continuous laws (§2.1): plane exit wave (< 1e-4° RMS), exit rays parallel
    to the axis (< 1e-6 rad) and the sine condition ρ = b sin θ (§2.5) to 1e-4 mm, R = 230 mm."""
    R = 230.0
    for law, b, outer in [("classic", 1.0, None), ("generalized", 1.1, None), ("generalized", 1.5, None),
                          ("outer_shell", 1.2, lb.OuterShell(0.95, 1.1))]:
        f = lb.traced_law(law, b, outer, R)
        bm = b * R                       # classic: the feed on the surface, where ε = 1
        th = np.linspace(-1, 1, 41) * math.asin(R / bm) * 0.97
        tr = trace_graded(f.eps_of_r2, R, np.tile([-bm, 0.0], (len(th), 1)), np.stack([np.cos(th), np.sin(th)], 1),
                          core_mm=f.core_mm, shell_eps=f.shell_eps)
        assert tr.ok.all()
        opl = tr.exit_opl + (2 * R - tr.exit_zy[:, 0])
        phase = 360 * (opl - opl.mean()) / 25.0
        assert np.sqrt(np.mean(phase**2)) < 1e-4, law
        assert np.max(np.abs(tr.direction[:, 1])) < 1e-6, law
        np.testing.assert_allclose(tr.exit_zy[:, 1] + (2 * R - tr.exit_zy[:, 0]) * tr.direction[:, 1],
                                   bm * np.sin(th), atol=1e-4)


def test_ideal_fan_figures_match_go_efficiency_and_taper():
    """§2.5 GO: the traced ideal lens gives taper × spillover of ``go_efficiency`` (phase ≈ 1) and
    the aperture power density |A|² ∝ cos^(2q−1) θ, ρ = b sin θ, on the outer/inner tenth (0.1 dB)."""
    R, b, q = 230.0, 1.5, 4.0
    et, es = lb.go_efficiency(b, q)
    f = lb.traced_law("generalized", b, None, R)
    fan = feed_fan(lambda o, d: trace_graded(f.eps_of_r2, R, o, d), R, b * R, q, "sphere", n_rays=512)
    ff = fan_figures(fan, 25.0, R, "sphere", et, es)
    assert ff.efficiency == pytest.approx(et * es, rel=1e-6)
    assert ff.phase_rms_deg < 1e-3 and ff.phase_pp_deg < 5e-3 and ff.lost_fraction < 1e-12
    dens = lambda r: math.cos(math.asin(r / (b * R))) ** (2 * q - 1)                   # noqa: E731
    mean = lambda r0, r1: integrate.quad(lambda r: dens(r) * r, r0, r1)[0] / ((r1**2 - r0**2) / 2)  # noqa: E731
    assert ff.amplitude_taper_db == pytest.approx(10 * math.log10(mean(0.9 * R, R) / mean(0, 0.1 * R)), abs=0.1)
    th, w = launch_angles(b, q, "sphere", 64)
    assert w.sum() == pytest.approx(1.0) and np.all(w > 0) and np.allclose(th, -th[::-1])


# ---------------------------------------------------------------- stepping, grades, first order

@pytest.mark.parametrize("law,b,q", [("classic", 1.0, 1.0), ("generalized", 1.1, 1.25), ("generalized", 1.5, 4.0)])
def test_stepping_error_decreases_with_layer_count(law, b, q):
    rms = [fan_figures(_shells_fan(M, law, b, R=375.0, q=q)[0], 30.0, 375.0, "sphere", 1, 1).phase_rms_deg
           for M in (5, 10, 20, 40, 80)]
    assert all(x > y for x, y in zip(rms, rms[1:])), rms
    assert rms[-1] < 0.15 * rms[0]


def _design(grades=None, fab=None, **design):
    data = {"name": "t", "kind": "luneburg", "frequency_ghz": 12.0, "material": "polystyrene",
            "design": {"diameter_mm": 300, "focal_distance_ratio": 1.5, "law": "generalized",
                       "layers": {"count": 6}} | design | ({"grades": grades} if grades else {}),
            "fabrication": fab or {"method": "shells", "pins_per_shell": 0, "feed_boss": None}}
    spec = parse_spec(data)
    design_ = KIND.synthesize(spec)
    layup, _ = KIND.plan(spec, design_)
    return spec, design_, layup


def test_grade_quantization_is_reflected():
    """Without a grade list the as-built lens is the stepped one; with coarse grades it carries
    the nearest grades (layer table, εr plot) and a different aperture phase."""
    spec, design, layup = _design()
    v = lv.verify_luneburg(spec, design, layup, KIND._fabricate_blanks(spec, design), KIND.layer_materials(spec, design))
    assert v.figures["as_built_axis_phase_rms_deg"] == v.figures["stepped_axis_phase_rms_deg"]
    coarse = [1.0, 1.2, 1.4, 1.6]
    spec, design, layup = _design(grades=coarse)
    materials = KIND.layer_materials(spec, design)
    v = lv.verify_luneburg(spec, design, layup, KIND._fabricate_blanks(spec, design), materials)
    layers = next(t for t in v.tables if t.name == "layers")
    chosen = [row[layers.columns.index("εr chosen")] for row in layers.rows]
    ideal = [row[layers.columns.index("εr ideal")] for row in layers.rows]
    assert chosen == [min(coarse, key=lambda g: abs(g - e)) for e in ideal]
    assert abs(v.figures["as_built_axis_phase_rms_deg"] - v.figures["stepped_axis_phase_rms_deg"]) > 1.0
    grades = next(s for s in next(p for p in v.plots if p.name == "eps-profile").series if s.label == "chosen grades")
    assert set(np.round(grades.y, 6)) <= set(coarse)


def _at(fan, s):
    """A fan's optical path at aperture points ``s`` (interpolated along its smooth mapping)."""
    order = np.argsort(fan.s_mm[fan.ok])
    return CubicSpline(fan.s_mm[fan.ok][order], fan.opl_mm[fan.ok][order])(s)


def test_first_order_shortcuts_match_retraces():
    """Feed moves (Hamilton: ΔL = −δ·t̂) on the ideal lens, a small εr change of a homogeneous
    sphere, and the closed-form focus shift, against re-traced fans compared at the same aperture
    points (to second order in the perturbation)."""
    R, lam, b = 230.0, 25.0, 1.5 * 230.0
    law = lb.traced_law("generalized", 1.5, None, R)
    ideal = lambda o, d: trace_graded(law.eps_of_r2, R, o, d)                            # noqa: E731
    fan = feed_fan(ideal, R, b, 4.0, "sphere", n_rays=256)
    inner = fan.ok & (fan.impact_mm < 0.9 * R)
    for a, l in ((0.05, 0.0), (0.0, 0.05)):
        moved = feed_fan(ideal, R, b, 4.0, "sphere", n_rays=256, axial_mm=a, lateral_mm=l)
        np.testing.assert_allclose(_at(moved, fan.s_mm[inner]) - fan.opl_mm[inner], feed_move_opl(fan, a, l)[inner],
                                   atol=2e-5)
    ball = Shells(np.array([R]), np.array([1.2]))
    bumped = Shells(np.array([R]), np.sqrt(np.array([1.2**2 + 1e-4])))
    trace = lambda m: (lambda o, d: trace_media(m, o, d))                                # noqa: E731
    nominal = feed_fan(trace(ball), R, 3 * R, 4.0, "sphere", n_rays=256)
    inner = nominal.ok & (nominal.impact_mm < 0.5 * R)           # inside the ball lens's caustic
    delta = first_order_opl(bumped, nominal.trace)
    retraced = feed_fan(trace(bumped), R, 3 * R, 4.0, "sphere", n_rays=256)
    np.testing.assert_allclose(delta[inner], _at(retraced, nominal.s_mm[inner]) - nominal.opl_mm[inner], atol=1e-6)
    assert added_phase_rms(nominal, delta, lam, R) > 0
    defocused = feed_fan(ideal, R, b, 4.0, "sphere", n_rays=256, axial_mm=5.0)
    assert focus_shift(defocused, lam, R) == pytest.approx(-5.0, abs=0.05)


def test_sensitivity_scales_with_the_tolerances():
    """First order: doubling every tolerance quadruples the added losses (exactly for the feed;
    n = √(ε + δ) is nearly linear in δ: 1e-4; radius shifts move chords near tangency: 1 %);
    zero tolerances add none."""
    spec, design, layup = _design()
    mats = KIND.layer_materials(spec, design)
    grade = np.array([L.eps_r for L in design.layers])
    built = lv._lenses(spec, design, layup, grade, as_built_only=True)["as_built"]
    nominal = built.fan()

    def losses(scale):
        s = spec.model_copy(update={"tolerances": spec.tolerances.model_copy(update={
            "eps_r_tolerance": 0.01 * scale, "thickness_tolerance_mm": 0.5 * scale,
            "feed_position_tolerance_mm": 2.0 * scale})})
        return lv._sensitivity(s, design, layup, grade, mats, built, nominal)[2]

    one, two, zero = losses(1.0), losses(2.0), losses(0.0)
    for key, rel in (("eps_r", 1e-4), ("thickness", 1e-2), ("feed", 1e-9)):
        assert one[f"sens_{key}_gain_loss_db"] > 0
        assert two[f"sens_{key}_gain_loss_db"] == pytest.approx(4 * one[f"sens_{key}_gain_loss_db"], rel=rel)
        assert zero[f"sens_{key}_gain_loss_db"] == 0


# ---------------------------------------------------------------- the kind's verify stage

def test_layup_verification_traces_the_staircase_when_scanned():
    spec = load_spec(RECIPES / "luneburg-layup-200.yaml")
    design = KIND.synthesize(spec)
    layup, _ = KIND.plan(spec, design)
    v = KIND.verify(spec, design, layup, KIND.fabricate(spec, design, layup, ()))
    f = v.figures
    assert f["ideal_axis_phase_rms_deg"] < lv.IDEAL_RMS_LIMIT_DEG
    assert f["stepped_scan90_phase_rms_deg"] != f["stepped_axis_phase_rms_deg"]       # staircase: not symmetric
    assert f["as_built_scan90_phase_rms_deg"] == f["as_built_axis_phase_rms_deg"]       # turned to spheres
    assert "stepped_go_facets_axis_phase_rms_deg" in f                                  # 10 mm < √(λR) = 39 mm
    checks = {c.name: c for c in v.checks}
    assert checks["ideal_lens_focus"].status == "pass" and "staircase_model" in checks
    assert {t.name for t in v.tables} == {"layers", "grades", "aperture", "sensitivity", "patterns"}
    grades = next(t for t in v.tables if t.name == "grades")
    assert sum(r[grades.columns.index("rings")] for r in grades.rows) == len(layup.rings)
    fan = next(p for p in v.plots if p.name == "ray-fan")
    assert fan.equal_aspect and 25 <= int(np.isnan(fan.series[1].x).sum()) <= 31


def test_verification_figures_reach_the_manifest(tmp_path):
    from antenna_cad.pipeline import build
    result = build(load_spec(RECIPES / "luneburg-cylinder-5.yaml"), tmp_path)
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    figures = manifest["verification"]["figures"]
    for key in ("ideal_axis_phase_rms_deg", "stepped_axis_phase_rms_deg", "as_built_axis_gain_loss_db",
                "as_built_scan90_focus_shift_mm", "sens_eps_r_gain_loss_db", "sens_total_gain_loss_db"):
        assert key in figures and math.isfinite(figures[key])
    assert figures == pytest.approx(result.verified)
    assert {t["name"] for t in manifest["verification"]["tables"]} == {"layers", "grades", "aperture", "sensitivity",
                                                                       "patterns"}
    for key in ("pattern_ideal_axis_directivity_dbi", "pattern_fabricated_scan90_hpbw_deg",
                "pattern_stepped_axis_sll_db", "pattern_fabricated_axis_efficiency"):
        assert math.isfinite(figures[key]), key
