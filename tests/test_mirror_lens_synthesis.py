"""Seed-004 aplanatic mirror-lens: series coefficients, exact synthesis, the feed-on-surface ODE,
astigmatism against exact 3-D stationary paths, the target A optimum and σ over the field.

Reference values: seed-004 digest §2.3 (coefficient table), §5.2–§5.3 (profile tables), §3.2–§3.5
(L_X, L_Y, γ*), §7.4 (tolerances stated there and next to each number here). The optimum design is
n = 1.3, f0/d0 = 1.0148 with f0 + d0 = 1 (digest §0 item 7), γ = 0.9371.
"""

import math

import numpy as np
import pytest

from antenna_cad.raytrace.mirror_lens import astigmatism_3d, body_from_profiles, field_scan, trace
from antenna_cad.synthesis.aplanatic import (astigmatism_exact, astigmatism_series, feed_on_surface_profiles,
                                             feed_on_surface_series, optimize_target, series_coefficients,
                                             synthesize_profiles, target_A)
from antenna_cad.synthesis.checks import DesignError

N, F0 = 1.3, 1.0148 / 2.0148
D0, GAMMA = 1 - F0, 0.9371


@pytest.fixture(scope="module")
def optimum():
    return synthesize_profiles(N, F0, D0, GAMMA)


@pytest.fixture(scope="module")
def on_surface():
    return feed_on_surface_profiles(N, 0.496, 0.572)


def test_series_coefficients_with_the_digest_fixes():
    """Digest §2.3 table (tol 1e-6 for f2, F2, k1, D2, W2, RB1; 1e-5 for f4, F4 as §7.4)."""
    c = series_coefficients(N, F0, D0, GAMMA)
    assert c.f2 == pytest.approx(0.520079, abs=1e-6)
    assert c.F2 == pytest.approx(-0.128230, abs=1e-6)
    assert c.f4 == pytest.approx(-0.271081, abs=1e-5)          # printed (unfixed) formula: +0.8110
    assert c.F4 == pytest.approx(-0.001969, abs=1e-5)          # printed: +0.0475
    assert c.k1 == pytest.approx(1.287207, abs=1e-6)
    assert c.k3 == pytest.approx(-5.05213, abs=1e-5)
    assert (c.D2, c.W2) == (pytest.approx(0.453311, abs=1e-6), pytest.approx(2.548526, abs=1e-6))
    assert (c.RB1, c.RB3) == (pytest.approx(1.638876, abs=1e-6), pytest.approx(-3.091016, abs=1e-6))


def test_series_is_the_taylor_expansion_of_the_exact_synthesis(optimum):
    """The marched front face minus f0 + f2 r² + f4 r⁴ is O(r⁶): the fitted r⁴ coefficient is f4."""
    p, c = optimum, series_coefficients(N, F0, D0, GAMMA)
    near = (p.s > 0.01) & (p.s < 0.06)
    r = p.s[near]
    fit = np.polyfit(r**2, (p.f[near] - F0 - c.f2 * r**2) / r**4, 1)
    assert fit[-1] == pytest.approx(c.f4, abs=1e-4)            # digest: fit −0.27111


def test_exact_profiles_match_the_digest_table(optimum):
    """Digest §5.2: f(0.25) 0.53490, Z_B(0.25) 0.99349 (1e-5); rim f(0.5) 0.59503, mirror (0.4947, 0.96614) (1e-4)."""
    p = optimum
    i = int(round(0.25 / (p.s[1] - p.s[0])))
    assert (p.f[i], p.Z_b[i]) == (pytest.approx(0.53490, abs=1e-5), pytest.approx(0.99349, abs=1e-5))
    assert p.f[-1] == pytest.approx(0.59503, abs=1e-4)
    assert (p.R_b[-1], p.Z_b[-1]) == (pytest.approx(0.4947, abs=1e-4), pytest.approx(0.96614, abs=1e-4))
    assert math.degrees(p.alpha[-1]) == pytest.approx(32.246, abs=1e-3)


@pytest.mark.parametrize("which", ["optimum", "on_surface"])
def test_forward_trace_exit_direction_path_and_sine_condition(which, request):
    """An independent 3-D trace through the synthesized faces: exit along −z, eikonal = L0 and
    r_C = γ sin α, all to 1e-9 (units of D; the digest measured 1e-12)."""
    p = request.getfixturevalue(which)
    a = np.arcsin(np.linspace(1e-3, 0.999 * p.s[-1], 300) / p.gamma)
    r = trace(body_from_profiles(p), (0.0, 0.0, 0.0), np.stack([np.sin(a), 0 * a, np.cos(a)], -1))
    assert r.ok.all()
    assert np.max(np.hypot(r.exit_dir[:, 0], r.exit_dir[:, 1])) < 1e-9
    assert np.max(np.abs(r.opl + r.exit_point[:, 2] - p.L0)) < 1e-9
    assert np.max(np.abs(r.exit_point[:, 0] - p.gamma * np.sin(a))) < 1e-9


def test_feed_on_surface_series_and_ode(on_surface):
    """Digest §2.4/§5.3: R2 = 0.143000 (= γ/4), R4 = 0.0146536 (1e-6); at x_C = 0.5: α 60.942°,
    r 0.66095, mirror (0.5778, 0.3210), lens z −0.00363 (1e-4)."""
    R2, R4 = feed_on_surface_series(N, 0.496, 0.572)
    assert (R2, R4) == (pytest.approx(0.143000, abs=1e-6), pytest.approx(0.0146536, abs=1e-6))
    p = on_surface
    assert math.degrees(p.alpha[-1]) == pytest.approx(60.942, abs=1e-3)
    assert p.d[-1] == pytest.approx(0.66095, abs=1e-4)
    assert (p.R_b[-1], p.Z_b[-1]) == (pytest.approx(0.5778, abs=1e-4), pytest.approx(0.3210, abs=1e-4))
    assert p.f[-1] == pytest.approx(-0.00363, abs=1e-4)
    a = p.alpha[(p.alpha > 0.02) & (p.alpha < 0.1)]
    quartic = (p.d[(p.alpha > 0.02) & (p.alpha < 0.1)] - 0.496 - R2 * a**2) / a**4
    assert np.polyfit(a**2, quartic, 1)[-1] == pytest.approx(0.0146560, abs=1e-5)     # digest: ODE fit 0.0146560


@pytest.mark.parametrize("r", [0.15, 0.25, 0.35, 0.45])
def test_astigmatism_formula_against_exact_3d_stationary_paths(optimum, r):
    """General formula of §3.2 on the exact geometry vs 3-D Fermat paths (digest: 5 digits) and the table."""
    lx, ly = astigmatism_exact(optimum, r)
    x3, y3 = astigmatism_3d(body_from_profiles(optimum), r)
    assert (lx[0], ly[0]) == (pytest.approx(x3, abs=1e-5), pytest.approx(y3, abs=1e-5))
    table = {0.15: -0.00382, 0.25: -0.01057, 0.35: -0.02017, 0.45: -0.03064}
    assert lx[0] - ly[0] == pytest.approx(table[r], abs=2e-4)


@pytest.mark.parametrize("r, lx_ref, ly_ref", [(0.15, 0.13016, 0.16532), (0.25, 0.11316, 0.21559),
                                               (0.35, 0.07047, 0.27495), (0.45, 0.01572, 0.31622)])
def test_feed_on_surface_astigmatism_eq20(on_surface, r, lx_ref, ly_ref):
    """Eq. (20) vs the digest table (1e-4) and vs 3-D stationary paths (per unit n, 1e-5)."""
    lx, ly = astigmatism_exact(on_surface, r)
    assert (lx[0], ly[0]) == (pytest.approx(lx_ref, abs=1e-4), pytest.approx(ly_ref, abs=1e-4))
    x3, y3 = astigmatism_3d(body_from_profiles(on_surface), r)
    assert (lx[0], ly[0]) == (pytest.approx(x3, abs=1e-5), pytest.approx(y3, abs=1e-5))


def test_series_astigmatism_19_matches_the_digest():
    lx, ly = astigmatism_series(series_coefficients(N, F0, D0, GAMMA), [0.15, 0.25, 0.35, 0.45])
    assert lx == pytest.approx([0.28764, 0.29159, 0.30370, 0.33089], abs=1e-5)
    assert ly == pytest.approx([0.29080, 0.29699, 0.30393, 0.30985], abs=1e-5)


def test_published_optimum_by_the_series_method():
    """Digest §3.5 item 1: 1-D search of (21) with (19) in [0.88, 0.99]: γ* = 0.93777, A = 0.00842
    (paper 0.9371, 2e-3); the literal d0/f0 reading gives 0.93804."""
    opt = optimize_target(N, F0, D0, 0.93, bounds={"gamma": (0.88, 0.99)})
    assert opt.gamma == pytest.approx(0.93777, abs=2e-5) and opt.A == pytest.approx(0.00842, abs=1e-5)
    assert opt.gamma == pytest.approx(0.9371, abs=2e-3)
    literal = optimize_target(N, D0, F0, 0.93, bounds={"gamma": (0.88, 0.99)})
    assert literal.gamma == pytest.approx(0.93804, abs=2e-5)


def test_exact_target_prefers_a_larger_gamma():
    """Digest §3.5 item 4: A on the exact geometry, 0.0346 at γ = 0.9371, minimum 0.0019 at 0.9965 (3e-3)."""
    assert target_A(N, F0, D0, 0.9371, mode="exact") == pytest.approx(0.0346, abs=2e-4)
    opt = optimize_target(N, F0, D0, 0.95, mode="exact", bounds={"gamma": (0.95, 1.03)})
    assert opt.gamma == pytest.approx(0.9965, abs=3e-3) and opt.A == pytest.approx(0.0019, abs=2e-4)


def test_sigma_grows_with_the_field_and_the_feed_on_surface_is_about_three_times_worse(optimum, on_surface):
    """σ from the 3-D trace: ~0 on axis, rising with the angle; at 20° the f0 = 0 system is about 3×
    the f0 > 0 system of equal thickness (seed-004 §3.6: 'about 3×')."""
    a = field_scan(body_from_profiles(optimum), [0.0, 10.0, 20.0])
    b = field_scan(body_from_profiles(on_surface), [0.0, 10.0, 20.0])
    assert a.sigma[0] < 1e-12 and b.sigma[0] < 1e-12
    assert np.all(np.diff(a.sigma) > 0) and np.all(np.diff(b.sigma) > 0)
    assert np.all(a.sigma <= a.sigma_on_axis_focus + 1e-15)           # the focal curve helps
    assert 2.0 < b.sigma[-1] / a.sigma[-1] < 4.0
    assert a.field_angle_deg[-1] == pytest.approx(20.0, abs=0.5)


@pytest.mark.parametrize("args, field", [
    ((N, F0, D0, 0.45), "design.gamma"),             # γ below the aperture radius
    ((N, F0, D0, F0), "design.gamma"),               # f2 singular
    ((N, 0.0, 0.496, 0.4), "design.gamma"),
])
def test_impossible_designs_name_the_parameter(args, field):
    with pytest.raises(DesignError) as err:
        synthesize_profiles(*args)
    assert err.value.field == field


def test_two_parameter_search_leaves_the_published_point():
    """Digest §3.5 item 2: at n = 1.3 a 2-D (f0, γ) search of (21) finds a lower A at f0 ≈ 0.708,
    γ ≈ 0.959 — the paper's point came from unstated constraints."""
    opt = optimize_target(N, F0, D0, 0.94, free=("f0", "gamma"), bounds={"gamma": (0.88, 1.2), "f0": (0.3, 0.9)})
    assert (opt.f0, opt.gamma) == (pytest.approx(0.708, abs=2e-3), pytest.approx(0.959, abs=2e-3))
    assert opt.A < target_A(N, F0, D0, 0.93777) and opt.f0 + opt.d0 == pytest.approx(1.0)


def test_rays_lost_at_an_earlier_face_are_not_iterated(on_surface):
    """_hit iterates only the ``alive`` rays, with the same bits as iterating all; the others keep
    their start and are not converged (feed on the surface: a fifth of the grid misses the mirror)."""
    from antenna_cad.raytrace.mirror_lens import _hit, launch_grid
    body = body_from_profiles(on_surface)
    w = launch_grid(body)
    p = np.tile([-0.05, 0.0, 0.0], (len(w), 1))
    t0 = (float(body.mirror.z(np.array([0.0]))[0]) - p[:, 2]) / w[:, 2]
    t_all, conv_all = _hit(p, w, body.mirror, t0)
    b = p + t_all[:, None] * w
    alive = conv_all & (np.hypot(b[:, 0], b[:, 1]) <= body.mirror.rho_max)
    assert 0 < np.count_nonzero(~alive) < len(w)
    t, conv = _hit(p, w, body.mirror, t0, alive)
    assert np.array_equal(t[alive], t_all[alive]) and np.array_equal(conv[alive], conv_all[alive])
    assert np.array_equal(t[~alive], t0[~alive]) and not conv[~alive].any()


def test_field_edge_sigma_of_the_paper_design_and_its_ray_set(optimum):
    """The paper's design (n 1.3, f0/d0 1.0148, γ 0.9371) at the field edge: σ 7.45e-4 D at 19.64°
    (tol 1 %) with the rays launched over 1.25× the on-axis cone (the report's convention); over the
    on-axis cone alone (δZ re-optimised) σ is 5.96e-4 D, 20 % lower. The paper states σ < 5.3e-4 D
    within the 40° field: ours is 1.41× that (the paper's ray set, angle definition and focal-curve
    procedure are not given; with the cone-only set the gap is 1.13×)."""
    from scipy.optimize import minimize_scalar

    from antenna_cad.raytrace import mirror_lens as ml
    body = body_from_profiles(optimum)
    scan = field_scan(body, [20.0])
    assert scan.field_angle_deg[0] == pytest.approx(19.64, abs=0.01)
    assert scan.sigma[0] == pytest.approx(7.45e-4, rel=0.01)
    assert scan.sigma[0] / 5.3e-4 == pytest.approx(1.41, abs=0.02)         # the gap to the paper
    cone = ml.launch_grid(body, margin=1.0)
    d = body.gamma * np.sin(np.radians(20.0))
    res = minimize_scalar(lambda z: ml.sigma_at(body, (-d, 0.0, z), cone).sigma, bounds=(-0.05, 0.05),
                          method="bounded", options={"xatol": 1e-7})
    assert res.fun == pytest.approx(5.96e-4, rel=0.01)
    assert res.fun / scan.sigma[0] == pytest.approx(0.80, abs=0.01)
