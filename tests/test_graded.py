"""Trifocal graded-index lens (seed-001 §3.2): exact layer rays, C¹ layers, the construction's
exactness at the side foci, the split invariance, the seed's comparison, and the recipe build."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from antenna_cad import pipeline
from antenna_cad.registry import adapter
from antenna_cad.spec import SpecError, load_spec, parse_spec
from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.graded import Medium, Ray
from antenna_cad.synthesis.graded_lens import Construction, GradedParams

RECIPE = Path(__file__).resolve().parents[1] / "recipes" / "graded-trifocal-160mm.yaml"
SYMMETRIC = dict(n0=1.6, m=2.0, a2=0.2655, a4=-0.2383, y_a=-0.2, rho=1.0, rho_p=1.0, rho1=1.011, rho1_p=1.011)


def _medium():
    med = Medium(1.6, 2.0)
    for top, m_i in ((0.3, -1.0), (0.45, 3.0), (0.6, -2.0)):
        med.close_top(top)
        med.add_layer(m_i)
    return med


@pytest.mark.parametrize("angle", [20.0, 35.0, 60.0])
def test_layer_rays_match_the_ray_equation(angle):
    """Closed-form sinusoid / sinh / cosh segments vs d²y/dx² = (dn²/dy)/(2a²), dL/dx = n²/a."""
    med = _medium()
    a = 1.6 * np.cos(np.radians(angle))
    ray = Ray(med, 0.0, 0.1, a, 1.0, 2.0)

    def rhs(x, s):
        h = 1e-6
        return [s[1], (med.n2_at(s[0] + h) - med.n2_at(s[0] - h)) / (2 * h) / (2 * a * a), med.n2_at(s[0]) / a]

    _, d0, _ = ray.at(0.0)
    sol = solve_ivp(rhs, [0, 2], [0.1, d0[1] / d0[0], 0.0], rtol=1e-11, atol=1e-12, dense_output=True)
    for x in (0.5, 1.0, 2.0):
        y, _, path = ray.at(x)
        assert y == pytest.approx(sol.sol(x)[0], abs=1e-8)
        assert path == pytest.approx(sol.sol(x)[2], abs=1e-8)
    assert {s.kind for s in ray.segments} >= {"sin"}


def test_layers_are_c1():
    med = _medium()
    for L in med.layers[1:]:
        h = L.lo
        assert med.n2_at(h - 1e-9) == pytest.approx(med.n2_at(h + 1e-9), abs=1e-8)
        slope = [(med.n2_at(h + s * 2e-6) - med.n2_at(h + s * 1e-6)) / (s * 1e-6) for s in (-1, 1)]
        assert slope[0] == pytest.approx(slope[1], abs=1e-4)


@pytest.fixture(scope="module")
def construction():
    c = Construction(GradedParams(**SYMMETRIC, d1=0.5, d2=0.5, points=21))
    try:
        c.run()
    except DesignError as exc:
        assert "folds back" in exc.message           # the construction stops at a fold near the edge
    return c


@pytest.mark.slow
def test_construction_is_exact_for_the_side_foci(construction):
    """Every surface-2 point built by an F1 ray carries the reference eikonal ρ1 + L_AB + ρ1' (1e-9)."""
    c = construction
    for p in c.surf1[1:20]:
        (q,) = c.image(c.F1, c.F1p, c.c1, [p], False)
        ray, s, start = c._launch(c.F1, p, False)
        _, _, path = ray.at(q.p[0])
        total = np.linalg.norm(start - s) + path + np.linalg.norm(q.p - c.F1p)
        assert abs(total - c.c1) < 1e-9
    assert c.surf1[-1].p[1] > 0.45 and c.surf2[-1].p[1] > 0.45


@pytest.mark.slow
def test_thickness_split_only_translates_the_lens(construction):
    other = Construction(GradedParams(**SYMMETRIC, d1=0.62, d2=0.38, points=21))
    try:
        other.run()
    except DesignError:
        pass
    a = np.array([q.p for q in construction.surf2[:60]])
    b = np.array([q.p for q in other.surf2[:60]])
    np.testing.assert_allclose(b[:, 0] + 0.12, a[:, 0], atol=1e-9)
    np.testing.assert_allclose(b[:, 1], a[:, 1], atol=1e-9)


def test_bad_initial_segment_is_a_named_error():
    with pytest.raises(DesignError) as err:
        Construction(GradedParams(**(SYMMETRIC | {"a2": 3.0, "a4": 0.0}), d1=0.5, d2=0.5, points=11)).run()
    assert err.value.field.startswith("design.")


def test_spec_bounds():
    data = load_spec(RECIPE).model_dump(mode="json")
    for field, value in (("n0", 0.9), ("y_a", 0.1), ("m", -1.0), ("unit_mm", float("nan"))):
        with pytest.raises(SpecError, match=field):
            parse_spec(data | {"design": data["design"] | {field: value}})


@pytest.mark.slow
def test_recipe_sigma_and_the_seed_comparison():
    """Seed-001 §3.2: bifocal lens over 80° σ ≈ 4e-3 (factor 2); the trifocal lens 4–20× lower."""
    spec = load_spec(RECIPE)
    design = adapter("graded").synthesize(spec)
    assert all(c.status != "fail" for c in design.checks)
    bifocal = design.comparison_sigma.max()
    assert 4e-3 / 2 <= bifocal <= 4e-3 * 2
    assert 4.0 <= bifocal / design.sigma.max() <= 20.0


@pytest.mark.slow
def test_recipe_builds(tmp_path):
    spec = load_spec(RECIPE)
    res = pipeline.build(spec, tmp_path)
    manifest = json.loads((res.out_dir / "manifest.json").read_text())
    assert "fail" not in {c["status"] for c in manifest["checks"]}
    rows = list(csv.DictReader((res.out_dir / "slabs.csv").open()))
    assert len(rows) == spec.design.slabs.count
    parts = manifest["parts"]
    assert len(parts) == 2 * len(rows) - 1 and all(p["valid"] and p["watertight"] for p in parts)
    eps = {p["label"]: p["material"] for p in parts}
    for row in rows:                       # each slab solid carries its synthesized permittivity
        k = int(row["slab"])
        label = f"slab-{k:02d}" if k == 0 else f"slab-{k:02d}-top"
        assert eps[label].endswith(f"εr {float(row['eps_r']):.4f}")
        assert (res.out_dir / "templates" / f"{label}.dxf").exists()
    assert any(k.startswith("sigma_at_") for k in manifest["figures"])


def test_a_shorter_trace_is_the_same_ray():
    """ray_paths traces a ray only to just past surface 2: a ray traced to a nearer x_max has the
    same segments (the last one cut) and the same state, bit for bit, up to there."""
    med = _medium()
    a = 1.6 * np.cos(np.radians(35.0))
    full, short = Ray(med, 0.0, 0.1, a, 1.0, 2.0), Ray(med, 0.0, 0.1, a, 1.0, 0.7)
    assert short.x_end == pytest.approx(0.7, abs=1e-12) and len(short.segments) < len(full.segments)
    for x in np.linspace(0.0, 0.7, 57):
        assert short.state(float(x)) == full.state(float(x))
