"""Multilayer Luneburg synthesis against seed-002 (digest ``reference/seed-002.md``).

Reference numbers live in ``tests/data/luneburg_reference.csv`` with their section and an
absolute tolerance (set from the printed precision: half a unit of the last printed digit,
rounded up). Everything else is checked against closed forms or independent computations.
"""

from __future__ import annotations

import csv
import math
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate

from antenna_cad.raytrace.snell import refract
from antenna_cad.synthesis import luneburg as lb
from antenna_cad.synthesis.checks import DesignError

DATA = Path(__file__).parent / "data" / "luneburg_reference.csv"


def _load():
    rows = defaultdict(list)
    with DATA.open(encoding="utf-8") as f:
        for row in csv.DictReader(line for line in f if not line.startswith("#")):
            rows[row["quantity"]].append(
                (row["case"], float(row["x"]), float(row["expected"]), float(row["abs_tol"])))
    return rows


REF = _load()


def _case(case: str):
    """'generalized_b1.1_M5_equal_eps' -> (law, b, M, split)."""
    parts = case.split("_")
    law = parts[0] if parts[0] != "outer" else "outer_shell"
    i = 2 if law == "outer_shell" else 1
    b = float(parts[i][1:])
    M = int(parts[i + 1][1:]) if len(parts) > i + 1 and parts[i + 1].startswith("M") else None
    split = "_".join(parts[i + 2:]) if M is not None else None
    return law, b, M, split


# ------------------------------------------------------------------ continuous laws (§2.1)

@pytest.mark.parametrize("case", sorted({c for c, *_ in REF["eps_profile"]}))
def test_eps_profile_reference_table(case):
    law, b, _, _ = _case(case)
    outer = None
    if law == "outer_shell":
        outer = dict(a_over_r=0.95, eps_r=1.1)
        b = float(case.split("_")[2][1:])
    rows = [r for r in REF["eps_profile"] if r[0] == case]
    r = np.array([x for _, x, _, _ in rows])
    got = lb.eps_profile(r, law, b, outer)
    for (_, x, exp, tol), g in zip(rows, got):
        assert abs(g - exp) <= tol, f"{case} r={x}: expected {exp}, got {g:.6f} (tol {tol})"


def test_eps_centre_reference():
    for case, _, exp, tol in REF["eps_centre"]:
        b = float(case.split("_b")[1])
        got = float(lb.eps_profile(0.0, "generalized", b))
        assert abs(got - exp) <= tol, f"ε(0) b={b}: expected {exp}, got {got:.6f}"


def test_generalized_b1_reduces_to_classic():
    # §2.1 check: the ω integral at b = 1 reproduces √(2−r²); quad tolerance 1e-13 -> 1e-10 bar
    r = np.linspace(0.0, 1.0, 41)
    got = lb.eps_profile(r, "generalized", 1.0)
    assert np.max(np.abs(got - (2.0 - r**2))) < 1e-10


def test_shell_inversion_reduces_to_omega_without_shell():
    # §2.1: with a = 1, n_s = 1 the Abel inversion of the shell law equals ω(ρ, b)
    for b in (1.0, 1.1, 1.5):
        for rho in (0.0, 0.3, 0.77, 0.99):
            assert abs(lb._log_n_shell(rho, b, 1.0, 1.0) - lb._omega(rho, b)) < 1e-12


def test_laws_monotone_and_at_least_one():
    r = np.linspace(0.0, 0.999, 60)
    for law, b, o in [("classic", 1.0, None), ("generalized", 1.3, None),
                      ("outer_shell", 1.2, dict(a_over_r=0.9, eps_r=1.15))]:
        e = lb.eps_profile(r, law, b, o)
        assert np.all(np.diff(e) <= 1e-15) and np.all(e >= 1.0)


@pytest.mark.parametrize("law,b,outer,ks", [
    ("classic", 1.0, None, [0.0, 0.05, 0.3, 0.6, 0.9, 0.99]),
    ("generalized", 1.1, None, [0.02, 0.3, 0.6, 0.9, 0.99]),
    ("generalized", 1.5, None, [0.1, 0.5, 0.95]),
    ("outer_shell", 1.1, dict(a_over_r=0.95, eps_r=1.1), [0.1, 0.5, 0.9, 0.999]),
])
def test_continuous_law_focuses_exactly(law, b, outer, ks):
    """Rays from the focus leave parallel to the axis with equal optical path.

    Sweep by quadrature (r = r_t + (1−r_t)t², quad epsrel 1e-12, n(r) by brentq to 1e-15)
    vs the exact condition Θ = π + asin(k/b) − 2 asin k; measured ≤ 6e-12 rad, bar 1e-9 rad
    (the digest reports ~1e-9 for b = 1.1 and ≤ 4e-5 for the shell law). Equal path: feed →
    exit → plane z = R, bar 1e-9 R. For the shell law k = 0.999 lies beyond ρa = a√εel = 0.9964:
    that ray stays in the homogeneous shell and is not focused by design (§2.1: "the outermost
    0.4 % of the radius"); it is traced but excluded from both bars.
    """
    k = np.array(ks)
    th, L = lb.continuous_sweep(k, law, b, outer)
    req = lb.required_sweep(k, b)
    inside = k < (0.95 * math.sqrt(1.1) if law == "outer_shell" else 1.0)
    assert np.max(np.abs(th - req)[inside]) < 1e-9
    path = np.sqrt(b * b - k * k) - np.sqrt(1 - k * k) + L + (1.0 - np.sqrt(1 - k * k))
    assert np.ptp(path[inside]) < 1e-9


# ------------------------------------------------------------------ splits (§2.2)

@pytest.mark.parametrize("case", sorted({c for c, *_ in REF["layer_eps"]}))
def test_layer_split_reference_tables(case):
    law, b, M, split = _case(case)
    ladder = None
    if split.startswith("ladder"):
        split, ladder = "ladder", dict(eps_outer=1.12, ratio=1.1)
    radii, eps = lb.layer_split(M, split, law, b, ladder=ladder)
    for j_, (_, j, exp, tol) in enumerate(r for r in REF["layer_eps"] if r[0] == case):
        assert abs(eps[int(j) - 1] - exp) <= tol, f"{case} ε{int(j)}: expected {exp}, got {eps[int(j)-1]:.6f}"
    for _, j, exp, tol in (r for r in REF["layer_radius"] if r[0] == case):
        got = radii[int(j) - 1]
        assert abs(got - exp) <= tol, f"{case} r{int(j)}: expected {exp}, got {got:.6f}"


def test_classic_equal_eps_closed_form():
    # §2.2 closed form: r_j = R√(j/M), ε_j = 2 − ((r_{j−1}+r_j)/2R)², to 1e-9 relative (§5.4)
    for M in (5, 10, 23):
        radii, eps = lb.layer_split(M, "equal_eps", "classic", 1.0)
        rj = np.sqrt(np.arange(1, M + 1) / M)
        mid = 0.5 * (np.concatenate([[0.0], rj[:-1]]) + rj)
        assert np.allclose(radii, rj, rtol=1e-9, atol=0)
        assert np.allclose(eps, 2.0 - mid**2, rtol=1e-9, atol=0)


@pytest.mark.parametrize("law,b,outer", [("classic", 1.0, None), ("generalized", 1.2, None),
                                         ("outer_shell", 1.1, dict(a_over_r=0.95, eps_r=1.1))])
@pytest.mark.parametrize("split", ["equal_eps", "equal_n", "equal_thickness"])
def test_layers_cover_lens_and_are_physical(law, b, outer, split):
    for M in (2, 3, 7, 20):
        radii, eps = lb.layer_split(M, split, law, b, outer=outer)
        assert radii.size == M and abs(radii[-1] - 1.0) < 1e-15
        assert radii[0] > 0 and np.all(np.diff(radii) > 0)
        assert np.all(eps >= 1.0) and np.all(np.diff(eps) < 0)
        if outer:
            assert abs(radii[-2] - 0.95) < 1e-12 and abs(eps[-1] - 1.1) < 1e-15


def test_design_layers_contiguous_in_mm():
    d = lb.synthesize_luneburg(diameter_mm=460, frequency_ghz=12.0, focal_distance_ratio=1.5,
                               law="generalized", layer_count=7, split="equal_n",
                               base_eps_r=2.55, base_tan_delta=1e-4)
    L = d.layers
    assert L[0].r_inner_mm == 0.0 and abs(L[-1].r_outer_mm - 230.0) < 1e-12
    assert all(a.r_outer_mm == b.r_inner_mm for a, b in zip(L, L[1:]))
    assert [x.index for x in L] == list(range(1, 8))
    vol = sum(4 / 3 * math.pi * (x.r_outer_mm**3 - x.r_inner_mm**3) for x in L)
    assert abs(vol / (4 / 3 * math.pi * 230.0**3) - 1) < 1e-12       # §5.3-4 shells fill the sphere
    assert abs(d.focal_distance_mm - 345.0) < 1e-12


# ------------------------------------------------------------------ layer count (§2.3)

def test_min_layer_count_reference():
    for _, dl, n, _ in REF["min_layer_count"]:
        assert lb.min_layer_count(dl) == int(n), f"D/λ = {dl}"


def test_auto_count_and_warning_below_rule():
    lam = lb.C_MM_GHZ / 10.0
    kw = dict(frequency_ghz=10.0, focal_distance_ratio=1.1, law="generalized",
              base_eps_r=2.55, base_tan_delta=1e-4)
    d = lb.synthesize_luneburg(diameter_mm=50 * lam, layer_count=None, **kw)
    assert len(d.layers) == d.layer_count_rule == 15
    assert {c.name: c.status for c in d.checks}["layer_count_vs_rule"] == "pass"
    d = lb.synthesize_luneburg(diameter_mm=50 * lam, layer_count=14, **kw)
    c = {c.name: c for c in d.checks}["layer_count_vs_rule"]
    assert c.status == "warn" and c.value == 14 and c.limit == 15
    d = lb.synthesize_luneburg(diameter_mm=3 * lam, layer_count=None, **kw)   # rule gives ≤ 0
    assert len(d.layers) == 1 and d.layer_count_rule <= 0


# ------------------------------------------------------------------ foam model (§2.7)

def test_fill_factor_and_tan_delta_reference():
    for _, e, exp, tol in REF["fill_factor"]:
        assert abs(float(lb.fill_factor(e, 2.55)) - exp) <= tol
    for _, e, exp, tol in REF["tan_delta_ratio"]:
        assert abs(float(lb.effective_tan_delta(e, 2.55, 1.0)) - exp) <= tol


def test_effective_medium_identities():
    # Robinson (4): n_eff = 1 + d(n'−1); tanδ_eff → tanδ for the solid, → 0 for air
    e = np.array([1.0, 1.2, 1.9, 2.55])
    d = lb.fill_factor(e, 2.55)
    assert np.allclose(1 + d * (math.sqrt(2.55) - 1), np.sqrt(e), atol=1e-15)
    t = lb.effective_tan_delta(e, 2.55, 3e-4)
    assert t[0] == 0.0 and abs(t[-1] - 3e-4) < 1e-18 and np.all(np.diff(t) > 0)
    assert np.allclose(lb.foam_density(e, 2.55, 1050.0), d * 1050.0)


def test_layers_carry_effective_loss_and_grades():
    grades = [1.05, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8, 1.9, 2.0]
    d = lb.synthesize_luneburg(diameter_mm=300, frequency_ghz=10.0, law="classic", layer_count=5,
                               base_eps_r=2.55, base_tan_delta=2e-4, base_density_kg_m3=1050,
                               grades=grades)
    want = [1.95, 1.7086, 1.5051, 1.3036, 1.1028]
    for L, w in zip(d.layers, want):
        g = grades[L.grade]
        assert L.eps_r == g and abs(g - w) == min(abs(x - w) for x in grades)
        assert abs(L.eps_r_design - w) < 1e-4
        assert abs(L.tan_delta - float(lb.effective_tan_delta(g, 2.55, 2e-4))) < 1e-18
        assert abs(L.density_kg_m3 - float(lb.fill_factor(g, 2.55)) * 1050) < 1e-9
    rows = d.layer_table()
    assert [r["eps_error"] for r in rows] == [L.eps_r - L.eps_r_design for L in d.layers]
    c = {c.name: c for c in d.checks}["grade_eps_error"]
    # 1.95 sits midway between grades 1.9 and 2.0: error 0.05, the largest of the five; the limit
    # is half the smallest design step (1.3036 → 1.1028), 0.1004
    assert abs(c.value - 0.05) < 1e-4 and abs(c.limit - 0.5 * (1.3036 - 1.1028)) < 1e-4
    assert c.status == "pass"
    coarse = lb.synthesize_luneburg(diameter_mm=300, frequency_ghz=10.0, law="classic", layer_count=5,
                                    base_eps_r=2.55, base_tan_delta=2e-4, grades=[1.0, 1.5, 2.0])
    assert {c.name: c.status for c in coarse.checks}["grade_eps_error"] == "warn"


# ------------------------------------------------------------------ GO efficiency (§2.5)

def test_go_efficiency_reference():
    for case, _, exp, tol in REF["eta_total"]:
        b, q = float(case.split("_")[0][1:]), float(case.split("_")[1][1:])
        et, es = lb.go_efficiency(b, q)
        (et_ref,) = [e for c, _, e, _ in REF["eta_taper"] if c == case]
        (es_ref,) = [e for c, _, e, _ in REF["eta_spill"] if c == case]
        (tp_ref,) = [e for c, _, e, _ in REF["edge_taper_db"] if c == case]
        assert abs(et - et_ref) <= 1e-3 and abs(es - es_ref) <= 1e-3 and abs(et * es - exp) <= tol
        assert abs(lb.feed_q_for_edge_taper(tp_ref, b) - q) < 0.05 * q / abs(tp_ref) * 10
        # closed forms for cos^q: η_s = 1 − c^{2q+1}; η_t from ∫cos^{q+1/2} sin, ∫cos^{2q} sin
        c = math.sqrt(1 - 1 / b**2)
        assert abs(es - (1 - c ** (2 * q + 1))) < 1e-12
        et_cf = ((1 - c ** (q + 1.5)) / (q + 1.5)) ** 2 * b**2 / (0.5 * (1 - c ** (2 * q + 1)) / (2 * q + 1))
        assert abs(et - et_cf) < 1e-12


def test_go_efficiency_optimum_b11():
    """§2.5 gives the b = 1.1 optimum as q ≈ 1.25 (edge ≈ −9.5 dB), η = 0.927.

    NOT reproduced exactly, and the bar is not loosened: the true maximum of η_t·η_s is at
    q = 1.33 (edge −10.1 dB) with η = 0.9281, 1.1e-3 above the printed 0.927. The printed value
    is η at the digest's coarse q = 1.25 (0.9275 → 0.927). So we test η(1.25) against 0.927,
    the located optimum q against 1.25 ± 0.1, and that the maximum is flat (< 1e-3 gain).
    """
    (_, _, eta_ref, tol) = REF["eta_total_optimum"][0]
    (_, _, q_ref, qtol) = REF["q_optimum"][0]
    eta_at_ref = np.prod(lb.go_efficiency(1.1, q_ref))
    assert abs(eta_at_ref - eta_ref) <= tol
    assert abs(20 * q_ref * math.log10(math.sqrt(1 - 1 / 1.21)) - (-9.5)) < 0.05
    q = lb.optimum_feed_q(1.1)
    assert abs(q - q_ref) <= qtol
    assert 0 <= np.prod(lb.go_efficiency(1.1, q)) - eta_at_ref < 1e-3


def test_cylinder_efficiency_line_aperture():
    # 2-D: A(x) ∝ F/√cosθ, x = b sinθ; independent quad of the 1-D integrals
    b, q = 1.2, 3.0
    te = math.asin(1 / b)
    num = integrate.quad(lambda t: math.cos(t) ** (q - 0.5) * b * math.cos(t), 0, te)[0] ** 2
    den = 1.0 * integrate.quad(lambda t: math.cos(t) ** (2 * q - 1) * b * math.cos(t), 0, te)[0]
    es = integrate.quad(lambda t: math.cos(t) ** (2 * q), 0, te)[0] / \
        integrate.quad(lambda t: math.cos(t) ** (2 * q), 0, math.pi / 2)[0]
    et_c, es_c = lb.go_efficiency(b, q, "cylinder")
    assert abs(et_c - num / den) < 1e-10 and abs(es_c - es) < 1e-10


def test_rim_half_angle():
    for case, _, exp, tol in REF["rim_half_angle_deg"]:
        b = float(case[1:])
        tr = lb.trace_shells([1.0], [1.0], b, impact_mm=[1.0 - 1e-15])
        assert abs(math.degrees(tr.launch_angle_rad[0]) - exp) <= tol


# ------------------------------------------------------------------ stepped-lens GO tracer (§2.1b)

def test_five_layer_sweep_errors_reference():
    radii, eps = lb.layer_split(5, "equal_eps", "classic", 1.0)
    rows = REF["sweep_error_deg"]
    tr = lb.trace_shells(radii, eps, 1.0, impact_mm=[x for _, x, _, _ in rows])
    for (_, k, exp, tol), got in zip(rows, np.degrees(tr.sweep_error_rad)):
        assert abs(got - exp) <= tol, f"k={k}: expected {exp}°, got {got:.3f}°"


def test_thin_layer_limit_reference():
    (_, k, exp, tol) = REF["sweep_error_abs_rad"][0]
    radii, eps = lb.layer_split(2000, "equal_thickness", "classic", 1.0)
    tr = lb.trace_shells(radii, eps, 1.0, impact_mm=[k])
    assert abs(abs(tr.sweep_error_rad[0]) - exp) <= tol


def _snell_trace(radii, eps, b, k):
    """Independent sequential tracer: line–circle intersections + vector Snell (raytrace.snell).
    Medium m = 0..M−1 is layer m (innermost first), m = M is air."""
    M = len(radii)
    n = np.append(np.sqrt(eps), 1.0)
    pos = np.array([0.0, -b])
    d = np.array([k / b, math.sqrt(1 - (k / b) ** 2)])
    m, opl = M, 0.0
    for _ in range(2 * M + 2):
        hits = []
        for j, rr in enumerate(radii):
            bq = pos @ d
            disc = bq * bq - (pos @ pos - rr * rr)
            if disc >= 0:
                hits += [(t, j) for t in (-bq - math.sqrt(disc), -bq + math.sqrt(disc)) if t > 1e-9]
        if not hits:
            break
        t, j = min(hits)
        pos = pos + t * d
        opl += n[m] * t
        nxt = j + 1 if pos @ d > 0 else j          # outward: layer above circle j, inward: layer j
        dnew, ok = refract(d[None, :], pos[None, :], n[m], n[nxt])
        assert ok[0], "unexpected total reflection"
        d, m = dnew[0], nxt
        if m == M:
            return pos, d, opl
    raise AssertionError("ray did not leave the lens")


def test_tracer_matches_sequential_snell():
    radii, eps = lb.layer_split(5, "equal_eps", "generalized", 1.2)
    R, b = 100.0, 120.0
    ks = np.array([0.0, 3.0, 25.0, 50.0, 71.0, 88.0, 97.0])
    tr = lb.trace_shells(radii * R, eps, b, impact_mm=ks)
    for i, k in enumerate(ks):
        p, d, opl = _snell_trace(radii * R, eps, b, k)
        assert np.allclose(tr.exit_xz_mm[i], p, atol=1e-9)
        assert np.allclose(tr.exit_dir_xz[i], d, atol=1e-12)
        air = math.sqrt(b * b - k * k) - math.sqrt(R * R - k * k)
        assert abs(air + tr.optical_path_inside_mm[i] - opl) < 1e-9


def test_tracer_single_homogeneous_sphere_tir_and_validation():
    # ε decreasing inward (non-monotone lens) → rays reflect at the inner interface, flagged
    tr = lb.trace_shells([50.0, 100.0], [1.0, 2.0], 150.0, impact_mm=[10.0, 60.0])
    assert not tr.tir[0] and tr.tir[1]
    assert list(tr.turning_layer) == [0, 1]
    tr = lb.trace_shells([50.0, 100.0], [2.0, 1.5], 150.0, impact_mm=[10.0, 90.0, 150.0])
    assert list(tr.turning_layer) == [0, 1, -1] and not tr.valid[2]   # k = R misses the lens
    with pytest.raises(DesignError):
        lb.trace_shells([50.0, 100.0], [0.9, 1.5], 150.0)
    with pytest.raises(DesignError):
        lb.trace_shells([50.0, 100.0], [2.0, 1.5], 90.0)


@pytest.mark.parametrize("law,b", [("classic", 1.0), ("generalized", 1.1), ("generalized", 1.5)])
def test_stepped_error_decreases_with_layer_count(law, b):
    """GO phase error (core, k <= 0.95 R), max sweep error and RMS focus miss fall with M."""
    rms, pp, sweep, miss = [], [], [], []
    for M in (5, 10, 20, 40, 80):
        d = lb.synthesize_luneburg(diameter_mm=300, frequency_ghz=10.0, focal_distance_ratio=b,
                                   law=law, layer_count=M, base_eps_r=2.55, base_tan_delta=1e-4)
        tr = lb.trace_layered_sphere(d.layers, d.focal_distance_mm, n_rays=400)
        core = tr.impact_mm <= 0.95 * 150
        rms.append(d.phase_error_rms_deg)
        pp.append(d.phase_error_pp_deg)
        sweep.append(np.max(np.abs(tr.sweep_error_rad[core])))
        miss.append(d.focus_spread_rms_mm)
    for series in (rms, pp, sweep, miss):
        assert all(a > b_ for a, b_ in zip(series, series[1:])), series
    assert rms[-1] < 0.12 * rms[0]


def test_cylinder_uses_same_section_and_checks_height():
    kw = dict(diameter_mm=300, frequency_ghz=10.0, focal_distance_ratio=1.2, law="generalized",
              layer_count=5, split="ladder", ladder=dict(eps_outer=1.12, ratio=1.1),
              base_eps_r=2.55, base_tan_delta=1e-4)
    s = lb.synthesize_luneburg(**kw)
    c = lb.synthesize_luneburg(shape="cylinder", height_mm=8.0, **kw)
    assert [L.r_outer_mm for L in s.layers] == [L.r_outer_mm for L in c.layers]
    # same rays: p-p phase and max focus miss are weight-free and identical; RMS weights differ
    assert s.phase_error_pp_deg == pytest.approx(c.phase_error_pp_deg, rel=1e-12)
    assert s.focus_spread_mm == c.focus_spread_mm
    assert s.phase_error_rms_deg != c.phase_error_rms_deg
    hmax = lb.C_MM_GHZ / 10.0 / (2 * math.sqrt(1.63979))
    chk = {x.name: x for x in c.checks}["parallel_plate_single_mode"]
    assert chk.status == "pass" and abs(chk.limit - hmax) < 1e-4
    bad = lb.synthesize_luneburg(shape="cylinder", height_mm=20.0, **kw)
    assert {x.name: x.status for x in bad.checks}["parallel_plate_single_mode"] == "fail"
    with pytest.raises(DesignError) as e:
        lb.synthesize_luneburg(shape="cylinder", **kw)
    assert e.value.field == "design.height_mm"


def test_design_figures_consistent():
    d = lb.synthesize_luneburg(diameter_mm=460, frequency_ghz=12.0, focal_distance_ratio=1.5,
                               law="generalized", layer_count=9, base_eps_r=2.55,
                               base_tan_delta=1e-4, edge_taper_db=-10.2108)
    assert abs(d.feed_q - 4.0) < 1e-3 and abs(d.efficiency - 0.860) <= 5e-3
    assert d.efficiency_with_phase <= d.efficiency
    assert d.phase_error_pp_full_deg >= d.phase_error_pp_deg
    assert d.axial_focus_min_mm <= d.focal_distance_mm <= d.axial_focus_max_mm
    # axial GO loss: Σ k0 n tanδ_eff · 2t (Np) → dB; linear in the base tanδ
    d2 = lb.synthesize_luneburg(diameter_mm=460, frequency_ghz=12.0, focal_distance_ratio=1.5,
                                law="generalized", layer_count=9, base_eps_r=2.55,
                                base_tan_delta=2e-4, edge_taper_db=-10.2108)
    assert d2.axial_loss_db == pytest.approx(2 * d.axial_loss_db, rel=1e-12)
    assert 0 < d.axial_loss_db < 0.1


# ------------------------------------------------------------------ impossible physics

@pytest.mark.parametrize("kw,field", [
    (dict(focal_distance_ratio=0.9, law="generalized"), "design.focal_distance_ratio"),
    (dict(focal_distance_ratio=1.1, law="classic"), "design.focal_distance_ratio"),
    (dict(law="outer_shell", focal_distance_ratio=1.1, outer_shell=dict(a_over_r=0.95, eps_r=0.9)),
     "design.outer_shell.eps_r"),
    (dict(law="outer_shell", focal_distance_ratio=1.1, outer_shell=dict(a_over_r=0.99, eps_r=1.1)),
     "design.outer_shell"),
    (dict(split="ladder", ladder=dict(eps_outer=0.95, ratio=1.1)), "design.layers.ladder.eps_outer"),
    (dict(split="ladder", ladder=dict(eps_outer=1.5, ratio=1.1)), "design.layers.ladder"),
    (dict(base_eps_r=1.8), "material.eps_r"),
])
def test_design_errors(kw, field):
    base = dict(diameter_mm=300, frequency_ghz=10.0, layer_count=5, base_eps_r=2.55,
                base_tan_delta=1e-4)
    base.update(kw)
    with pytest.raises(DesignError) as e:
        lb.synthesize_luneburg(**base)
    assert e.value.field == field
    assert any(ch.isdigit() for ch in e.value.message)          # the number that broke


def test_classic_feed_assumption_is_reported():
    kw = dict(diameter_mm=300, frequency_ghz=10.0, law="classic", layer_count=8,
              base_eps_r=2.55, base_tan_delta=1e-4)
    d = lb.synthesize_luneburg(**kw)
    assert d.feed_q == 1.0 and d.edge_taper_db is None
    assert {c.name: c.status for c in d.checks}["feed_model"] == "warn"
    d = lb.synthesize_luneburg(feed_q=2.0, **kw)
    assert "feed_model" not in {c.name for c in d.checks}
    # closed form for b = 1, cos^2 feed: A = cos^1.5 θ, ρ = sinθ ⇒ η_t = (1/3.5)² / (0.5/5), η_s = 1
    assert d.efficiency == pytest.approx((1 / 3.5) ** 2 / (0.5 / 5), rel=1e-12)
