"""Multilayer Luneburg lens synthesis: continuous laws, layer splits, foam grades, GO tracing.

Pure physics (numpy/scipy only). Source: seed-002 (Kuzmin 2004), digest
``reference/seed-002.md``; section numbers below refer to that digest.

Frame (DESIGN.md): lens centre at the origin, +Z is the beam direction. The feed (focus) sits
on the axis at ``z = -b`` where ``b = focal_distance_mm`` is measured from the lens centre
(seed-002 §1: "focus brought outside", ``b >= R``). Lengths are in mm at the interfaces, angles
in radians, frequencies in GHz.

Contents

* continuous laws ε(r) (seed-002 §2.1): classic ``2 - (r/R)^2``; generalised (focus outside,
  Luneburg/Morgan ω integral); homogeneous outer shell (Abel inversion of the core sweep) — in
  :mod:`antenna_cad.synthesis.luneburg_laws`;
* the three splits of §2.2 (equal ε, equal n, equal thickness; layer value at the radial
  midpoint) and the geometric ladder of the experimental cylinder (§2.2, L320);
* the minimum layer count rule (§2.3), the foam effective-medium relations and the effective
  loss tangent (§2.7), nearest-grade selection from a list of available foams;
* an exact, vectorized GO tracer through concentric homogeneous shells (§2.1b) giving exit
  points/directions, optical paths, aperture phase error and focus spread
  (:mod:`antenna_cad.synthesis.luneburg_trace`), and the GO aperture efficiency of a cos^q feed (§2.5).

The names of the two modules are re-exported here, so callers import from this one.

Cylinder (parallel-plate) lens: between two conducting plates the TEM mode (E normal to the
plates) propagates with index √εr for any plate spacing, and the in-plane rays obey the same
invariant ``r·n·sinψ = k`` in concentric rings as meridional rays do in concentric spheres. The
2-D section of the cylinder is therefore exactly the meridional section of the sphere, and the
same tracer and the same layer laws apply; only the aperture is a line (efficiency integrals
are 1-D) and the height must keep higher-order parallel-plate modes cut off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Literal, Sequence

import numpy as np
from scipy import optimize

from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.luneburg_laws import (  # noqa: F401  (re-exported: one module for callers)
    Law, OuterShell, TracedLaw, _Law, _log_n_shell, _omega, _validated_law, continuous_sweep, eps_profile,
    required_sweep, traced_law)
from antenna_cad.synthesis.luneburg_trace import (  # noqa: F401  (re-exported)
    C_MM_GHZ, ApertureFigures, LayeredTrace, Shape, aperture_figures, trace_layered_sphere, trace_shells)

Split = Literal["equal_eps", "equal_n", "equal_thickness", "ladder"]


# --------------------------------------------------------------------------------------------
# Layer count rule (seed-002 §2.3) and foam effective medium (seed-002 §2.7)
# --------------------------------------------------------------------------------------------

def min_layer_count(d_over_lambda: float) -> int:
    """N = int(4.34·log2(D/λ) − 8.75), ``int`` read as truncation (seed-002 §2.3).

    Meaningful for D/λ ≳ 5; returns ≤ 0 for D/λ ≤ 4 (callers clamp)."""
    return int(4.34 * math.log2(d_over_lambda) - 8.75)


def fill_factor(eps_eff, base_eps_r: float) -> np.ndarray:
    """Volume fraction of solid polymer d = (n'_eff − 1)/(n' − 1), Robinson's law (4) (§2.7)."""
    e = np.asarray(eps_eff, dtype=float)
    return (np.sqrt(e) - 1.0) / (math.sqrt(base_eps_r) - 1.0)


def effective_tan_delta(eps_eff, base_eps_r: float, base_tan_delta: float) -> np.ndarray:
    """tanδ_eff = n'/√ε'_eff · (√ε'_eff − 1)/(n' − 1) · tanδ (seed-002 §2.7)."""
    e = np.asarray(eps_eff, dtype=float)
    nb = math.sqrt(base_eps_r)
    return nb / np.sqrt(e) * (np.sqrt(e) - 1.0) / (nb - 1.0) * base_tan_delta


def foam_density(eps_eff, base_eps_r: float, base_density_kg_m3: float) -> np.ndarray:
    """Foam density = d · ρ_solid (air mass neglected; buoyancy cancels it when weighed)."""
    return fill_factor(eps_eff, base_eps_r) * base_density_kg_m3


def nearest_grade(eps_target: float, grades: Sequence[float]) -> tuple[int, float, float]:
    """Nearest available grade: ``(index, eps_grade, eps_grade − eps_target)``."""
    g = np.asarray(grades, dtype=float)
    i = int(np.argmin(np.abs(g - eps_target)))
    return i, float(g[i]), float(g[i] - eps_target)


# --------------------------------------------------------------------------------------------
# GO aperture efficiency (seed-002 §2.5)
# --------------------------------------------------------------------------------------------

@lru_cache(maxsize=8)
def _leggauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    return np.polynomial.legendre.leggauss(n)


def feed_q_for_edge_taper(edge_taper_db: float, b_over_R: float) -> float:
    """Exponent q of a cos^q θ amplitude feed whose level toward the rim, θe = asin(R/b), is
    ``edge_taper_db`` (negative dB). seed-002 §2.5 rule: −10 … −15 dB."""
    ce = math.sqrt(1.0 - 1.0 / b_over_R**2)
    if ce <= 0.0:
        raise DesignError("design.focal_distance_ratio",
                          "b/R = 1: the rim is at 90° from the feed; a cos^q feed has no finite q "
                          "for a given edge taper (use feed_q)")
    return edge_taper_db / (20.0 * math.log10(ce))


def go_efficiency(b_over_R: float, q: float, shape: Shape = "sphere",
                  n_points: int = 400) -> tuple[float, float]:
    """GO taper and spillover efficiencies of a cos^q θ (amplitude, zero behind) feed.

    Sine condition ρ = b·sinθ and power conservation give A(ρ) ∝ F(θ)/√cosθ (§2.5).
    Sphere: η_t = |∫A ρdρ|² / (R²/2 ∫|A|²ρdρ), η_s = ∫_0^θe |F|² sinθ dθ / ∫_0^{π/2} |F|² sinθ dθ.
    Cylinder (line aperture, 2-D): η_t = |∫A dρ|² / (R ∫|A|² dρ), η_s = ∫_0^θe |F|² dθ / ∫_0^{π/2} |F|² dθ.
    Gauss–Legendre in θ; returns ``(eta_taper, eta_spill)``.
    """
    b = float(b_over_R)
    te = math.asin(1.0 / b)
    x, w = _leggauss(n_points)
    th = 0.5 * te * (x + 1.0)
    wt = 0.5 * te * w
    c = np.cos(th)
    F = c**q
    A = F / np.sqrt(c)
    rho = b * np.sin(th)
    drho = b * c * wt  # dρ = b cosθ dθ
    xf = 0.5 * (np.pi / 2) * (x + 1.0)
    wf = 0.5 * (np.pi / 2) * w
    if shape == "sphere":
        eta_t = (np.sum(A * rho * drho) ** 2) / (0.5 * np.sum(A**2 * rho * drho))
        eta_s = np.sum(F**2 * np.sin(th) * wt) / np.sum(np.cos(xf) ** (2 * q) * np.sin(xf) * wf)
    elif shape == "cylinder":
        eta_t = (np.sum(A * drho) ** 2) / (1.0 * np.sum(A**2 * drho))
        eta_s = np.sum(F**2 * wt) / np.sum(np.cos(xf) ** (2 * q) * wf)
    else:
        raise ValueError(f"unknown shape {shape!r}")
    return float(eta_t), float(eta_s)


# --------------------------------------------------------------------------------------------
# Layer splits (seed-002 §2.2)
# --------------------------------------------------------------------------------------------

def _split(L: _Law, count: int, split: str, ladder: dict | None) -> tuple[np.ndarray, np.ndarray]:
    """Outer radii (R = 1) and design εr of each layer, innermost first (seed-002 §2.2)."""
    shell = L.law == "outer_shell"
    if split == "ladder":
        if shell:
            raise DesignError("design.layers.split",
                              "the ladder split spans the whole lens; it cannot be combined with "
                              "law 'outer_shell'")
        if not ladder or "eps_outer" not in ladder or "ratio" not in ladder:
            raise DesignError("design.layers.ladder", "split 'ladder' needs {eps_outer, ratio}")
        e_out, ratio = float(ladder["eps_outer"]), float(ladder["ratio"])
        if not e_out >= 1.0:
            raise DesignError("design.layers.ladder.eps_outer", f"must be >= 1, got {e_out:g}")
        if not ratio > 1.0:
            raise DesignError("design.layers.ladder.ratio",
                              f"εi/εi+1 must be > 1 (permittivity grows inward), got {ratio:g}")
        eps = e_out * ratio ** np.arange(count - 1, -1, -1, dtype=float)
        levels = 0.5 * (eps[:-1] + eps[1:])  # r_i where ε(r) = (εi + εi+1)/2 (L320)
        e0 = L.eps_centre
        if levels.size and levels[0] >= e0:
            raise DesignError("design.layers.ladder",
                              f"boundary level (ε1+ε2)/2 = {levels[0]:.4g} is above the law's "
                              f"centre value ε(0) = {e0:.4g}: no radius has it; lower eps_outer, "
                              "ratio or count")
        radii = np.array([L.r_of_eps(x) for x in levels] + [1.0])
        return radii, eps
    M = count - 1 if shell else count
    a = L.a
    if split == "equal_eps":
        lv = L.eps_centre - (L.eps_centre - L.eps_edge) * np.arange(1, M) / M
        inner = [L.r_of_eps(x) for x in lv]
    elif split == "equal_n":
        n0, na = math.sqrt(L.eps_centre), L.ns
        lv = n0 - (n0 - na) * np.arange(1, M) / M
        inner = [L.r_of_n(x) for x in lv]
    elif split == "equal_thickness":
        inner = list(a * np.arange(1, M) / M)
    else:
        raise DesignError("design.layers.split",
                          f"unknown split {split!r} (equal_eps | equal_n | equal_thickness | ladder)")
    radii = np.array(inner + [a])
    r_in = np.concatenate([[0.0], radii[:-1]])
    eps = np.array([L.eps(0.5 * (r0 + r1)) for r0, r1 in zip(r_in, radii)])  # radial midpoint
    if shell:
        radii = np.append(radii, 1.0)
        eps = np.append(eps, L.ns**2)
    return radii, eps


def layer_split(count: int, split: Split = "equal_eps", law: Law = "classic", b_over_R: float = 1.0,
                outer: OuterShell | dict | None = None, ladder: dict | None = None
                ) -> tuple[np.ndarray, np.ndarray]:
    """Layer outer radii r_i/R and design εi (innermost first) for ``count`` physical layers.

    ``equal_eps``/``equal_n``: the law's range from its centre value to its edge value ε(a⁻) is cut
    in equal steps, r_j = ε⁻¹(ε(0) − jΔ), and each layer takes the law at its radial midpoint;
    ``equal_thickness``: r_j = a·j/M (seed-002 §2.2). With ``outer_shell`` the last layer is the
    homogeneous shell a < r < R and the graded part has count − 1 layers (§2.2 interpretation
    notes). ``ladder``: εi = eps_outer·ratio^(count−i), r_i where ε(r) = (εi + εi+1)/2 (L320).
    """
    L = _validated_law(law, b_over_R, outer)
    minimum = 2 if law == "outer_shell" and split != "ladder" else 1
    if int(count) != count or count < minimum:
        raise DesignError("design.layers.count", f"need an integer >= {minimum}, got {count!r}")
    radii, eps = _split(L, int(count), split, ladder)
    if np.any(np.diff(radii) <= 0.0) or radii[0] <= 0.0:
        raise DesignError("design.layers", f"layer radii not strictly increasing: {np.round(radii, 6)}")
    if np.any(eps < 1.0):
        raise DesignError("design.layers", f"a layer has εr = {eps.min():.4g} < 1")
    return radii, eps


# --------------------------------------------------------------------------------------------
# The design record and the synthesis entry point
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Layer:
    """One homogeneous layer (index 1 = core). ``eps_r`` is the realised value (nearest grade
    when a grade list is given, else the design value); ``tan_delta`` is §2.7's tanδ_eff of it."""

    index: int
    r_inner_mm: float
    r_outer_mm: float
    eps_r: float
    tan_delta: float
    eps_r_design: float
    fill_factor: float
    density_kg_m3: float | None = None
    grade: int | None = None       # index into the grade list, None for an ideal grade

    @property
    def thickness_mm(self) -> float:
        return self.r_outer_mm - self.r_inner_mm


@dataclass(frozen=True)
class LuneburgDesign:
    diameter_mm: float
    frequency_ghz: float
    shape: str                      # "sphere" | "cylinder"
    height_mm: float | None         # cylinder plate spacing
    law: str
    focal_distance_ratio: float     # b/R
    focal_distance_mm: float        # b, from the lens centre; feed at z = −b
    outer_shell: OuterShell | None
    split: str
    layer_count_rule: int           # seed-002 §2.3 (may be ≤ 0 for D/λ ≤ 4)
    layers: tuple[Layer, ...]       # innermost first
    feed_q: float                   # cos^q θ amplitude feed used for the efficiency
    edge_taper_db: float | None     # feed level toward the rim (None for b/R = 1: rim at 90°)
    efficiency_taper: float         # GO, ideal (continuous) lens, seed-002 §2.5
    efficiency_spillover: float
    efficiency: float               # taper × spillover
    efficiency_with_phase: float    # × phase efficiency of the stepped lens' GO aperture phase
    rim_fraction: float             # "core" figures use rays with k <= rim_fraction·R
    phase_error_pp_deg: float       # stepped lens, core, at frequency_ghz, piston removed
    phase_error_rms_deg: float      # core, area weighted
    phase_error_pp_full_deg: float  # whole aperture (rim sliver included)
    phase_error_rms_full_deg: float
    focus_spread_mm: float          # core: max miss of the design focus by reversed parallel rays
    focus_spread_rms_mm: float      # core, area weighted
    focus_spread_full_mm: float     # whole aperture
    axial_focus_min_mm: float       # range of axis crossings of reversed parallel rays (ideal: b)
    axial_focus_max_mm: float
    max_exit_tilt_rad: float
    axial_loss_db: float            # GO dielectric loss along the axial ray (§2.7, §5.3-6)
    checks: tuple[Check, ...] = field(default_factory=tuple)

    @property
    def radius_mm(self) -> float:
        return 0.5 * self.diameter_mm

    @property
    def wavelength_mm(self) -> float:
        return C_MM_GHZ / self.frequency_ghz

    def layer_table(self) -> list[dict]:
        """One row per layer for reports."""
        return [dict(index=L.index, r_inner_mm=L.r_inner_mm, r_outer_mm=L.r_outer_mm,
                     thickness_mm=L.thickness_mm, eps_r_design=L.eps_r_design, eps_r=L.eps_r,
                     eps_error=L.eps_r - L.eps_r_design, tan_delta=L.tan_delta,
                     fill_factor=L.fill_factor, density_kg_m3=L.density_kg_m3, grade=L.grade)
                for L in self.layers]


def optimum_feed_q(b_over_R: float, shape: Shape = "sphere") -> float:
    """q of the cos^q θ feed that maximises the GO η_taper·η_spill (§2.5: a flat maximum).
    Degenerate for b/R = 1 (q = 1/2 gives a uniform aperture with no spillover in GO)."""
    res = optimize.minimize_scalar(lambda q: -np.prod(go_efficiency(b_over_R, q, shape)),
                                   bounds=(0.2, 30.0), method="bounded", options=dict(xatol=1e-4))
    return float(res.x)


def synthesize_luneburg(*, diameter_mm: float, frequency_ghz: float,
                        focal_distance_ratio: float = 1.0, law: Law = "classic",
                        layer_count: int | None = None, split: Split = "equal_eps",
                        ladder: dict | None = None, outer_shell: OuterShell | dict | None = None,
                        base_eps_r: float, base_tan_delta: float,
                        base_density_kg_m3: float | None = None,
                        grades: Sequence[float] | None = None,
                        shape: Shape = "sphere", height_mm: float | None = None,
                        edge_taper_db: float = -10.0, feed_q: float | None = None,
                        n_rays: int = 512, rim_fraction: float = 0.95) -> LuneburgDesign:
    """Synthesize a multilayer Luneburg lens (seed-002).

    ``layer_count=None`` is ``auto``: the §2.3 rule N = int(4.34 log2(D/λ) − 8.75), clamped to
    the minimum the law needs; an explicit count below the rule gives a warning Check.
    Each layer's εr is realised either by the nearest of ``grades`` (its error is reported) or
    by an ideal foam of the base polymer (fill factor, density from §2.7). The stepped lens is
    traced (§2.1b) with the realised εr; the phase error and focus spread are relative to the
    continuous law, which is exact (uniform phase, zero spread). The feed is cos^q θ: ``feed_q``
    or, if None, the q giving ``edge_taper_db`` toward the rim (§2.5 rule −10…−15 dB); for
    b/R = 1 (rim at 90°, rule inapplicable) q = 1 with a warning Check. Figures marked "core"
    use rays with k <= ``rim_fraction``·R (see :class:`ApertureFigures`).
    """
    if not diameter_mm > 0:
        raise DesignError("design.diameter_mm", f"must be > 0, got {diameter_mm:g}")
    if not frequency_ghz > 0:
        raise DesignError("frequency_ghz", f"must be > 0, got {frequency_ghz:g}")
    if shape not in ("sphere", "cylinder"):
        raise DesignError("design.shape", f"unknown shape {shape!r} (sphere | cylinder)")
    if shape == "cylinder" and not (height_mm is not None and height_mm > 0):
        raise DesignError("design.height_mm", f"a cylinder lens needs a plate spacing > 0, got {height_mm!r}")
    if not base_eps_r > 1.0:
        raise DesignError("material.eps_r", f"base polymer εr must be > 1, got {base_eps_r:g}")
    if not base_tan_delta >= 0.0:
        raise DesignError("material.tan_delta", f"must be >= 0, got {base_tan_delta:g}")
    Lw = _validated_law(law, focal_distance_ratio, outer_shell)
    if isinstance(outer_shell, dict):
        outer_shell = OuterShell(**outer_shell)
    R = 0.5 * diameter_mm
    lam = C_MM_GHZ / frequency_ghz
    rule = min_layer_count(diameter_mm / lam)
    minimum = 2 if law == "outer_shell" else 1
    checks: list[Check] = []
    count = max(rule, minimum) if layer_count is None else layer_count
    radii, eps_d = layer_split(count, split, law, focal_distance_ratio, outer_shell, ladder)
    checks.append(Check("layer_count_vs_rule", "warn" if count < rule else "pass", float(count),
                        float(rule), "",
                        f"{count} layers; seed-002 §2.3 minimum for D/λ = {diameter_mm / lam:.3g} "
                        f"is {rule}" + (" — add layers" if count < rule else "")))
    if eps_d.max() > base_eps_r:
        raise DesignError("material.eps_r",
                          f"a layer needs εr = {eps_d.max():.4g} but the solid base polymer has only "
                          f"{base_eps_r:.4g}")
    # realisation: nearest grade or ideal foam (seed-002 §2.7)
    if grades is not None:
        g = np.asarray(grades, dtype=float)
        if g.size == 0 or np.any(g < 1.0) or np.any(g > base_eps_r):
            raise DesignError("material.grades",
                              f"grade εr must lie in [1, {base_eps_r:g}] (solid base), got {list(g)}")
        pick = [nearest_grade(e, g) for e in eps_d]
        idx = [p[0] for p in pick]
        eps_r = np.array([p[1] for p in pick])
        err = np.abs(eps_r - eps_d)
        step = np.min(np.abs(np.diff(eps_d))) if eps_d.size > 1 else np.inf
        lim = 0.5 * step
        dup = sum(1 for i in range(1, len(idx)) if idx[i] == idx[i - 1])
        checks.append(Check("grade_eps_error", "warn" if (err.max() > lim or dup) else "pass",
                            float(err.max()), float(lim), "",
                            f"largest |εr(grade) − εr(design)| = {err.max():.4g} (half the smallest "
                            f"layer step {lim:.4g})" + (f"; {dup} adjacent layers share a grade" if dup else "")))
    else:
        idx = [None] * len(eps_d)
        eps_r = eps_d.copy()
    tand = effective_tan_delta(eps_r, base_eps_r, base_tan_delta)
    ff = fill_factor(eps_r, base_eps_r)
    dens = (foam_density(eps_r, base_eps_r, base_density_kg_m3) if base_density_kg_m3 is not None
            else [None] * len(eps_r))
    r_in = np.concatenate([[0.0], radii[:-1]])
    layers = tuple(Layer(i + 1, float(R * r_in[i]), float(R * radii[i]), float(eps_r[i]),
                         float(tand[i]), float(eps_d[i]), float(ff[i]),
                         None if dens[i] is None else float(dens[i]), idx[i])
                   for i in range(len(radii)))
    b_mm = focal_distance_ratio * R
    # feed and GO efficiency (§2.5)
    if feed_q is not None:
        if not feed_q > 0:
            raise DesignError("feed.q", f"cos^q feed exponent must be > 0, got {feed_q:g}")
        q = float(feed_q)
    elif focal_distance_ratio > 1.0 + 1e-12:
        q = feed_q_for_edge_taper(edge_taper_db, focal_distance_ratio)
    else:
        q = 1.0
        checks.append(Check("feed_model", "warn", q, q, "",
                            "b/R = 1 puts the rim at 90° from the feed, so the −10…−15 dB edge rule "
                            "(seed-002 §2.5) cannot fix the feed; a cos θ feed (q = 1) is assumed — "
                            "give feed_q"))
    ce = math.sqrt(max(1.0 - 1.0 / focal_distance_ratio**2, 0.0))
    taper = 20.0 * q * math.log10(ce) if ce > 0 else None
    if taper is not None:
        ok = -15.0 - 1e-9 <= taper <= -10.0 + 1e-9
        checks.append(Check("feed_edge_taper", "pass" if ok else "warn", taper, -10.0, "dB",
                            f"feed level toward the rim {taper:.3g} dB (seed-002 §2.5 rule: −10 … −15 dB)"))
    eta_t, eta_s = go_efficiency(focal_distance_ratio, q, shape)
    # stepped-lens trace (§2.1b)
    tr = trace_layered_sphere(layers, b_mm, n_rays=n_rays)
    fig = aperture_figures(tr, frequency_ghz, q, shape, rim_fraction)
    checks.append(Check("aperture_phase_error_rms",
                        "warn" if fig.phase_error_rms_deg > 22.5 else "pass",
                        fig.phase_error_rms_deg, 22.5, "deg",
                        f"GO aperture phase error of the stepped lens within {rim_fraction:g}·R "
                        f"{fig.phase_error_rms_deg:.3g}° RMS, {fig.phase_error_pp_deg:.3g}° p-p (λ/16 = 22.5° RMS guide; GO overstates "
                        "few-layer errors, seed-002 §2.1b)"))
    core = tr.impact_mm <= rim_fraction * R
    n_back, n_tir = int(np.sum(core & ~tr.valid)), int(np.sum(core & tr.tir))
    if n_back or n_tir:
        checks.append(Check("ray_trace_anomalies", "warn", float(n_back + n_tir), 0.0, "rays",
                            f"{n_back} core rays leave away from +Z, {n_tir} are totally reflected "
                            "inside the lens (non-monotone layers?)"))
    if shape == "cylinder":
        hmax = lam / (2.0 * math.sqrt(float(eps_r.max())))
        checks.append(Check.upper("parallel_plate_single_mode", float(height_mm), hmax, "mm",
                                  "plate spacing vs TM1 cutoff λ/(2√εmax) in the core"))
    thick = np.array([L.thickness_mm for L in layers])
    loss_db = float(20.0 * math.log10(math.e) * np.sum(np.pi / lam * np.sqrt(eps_r) * tand * 2.0 * thick))
    return LuneburgDesign(
        diameter_mm=float(diameter_mm), frequency_ghz=float(frequency_ghz), shape=shape,
        height_mm=None if height_mm is None else float(height_mm), law=law,
        focal_distance_ratio=float(focal_distance_ratio), focal_distance_mm=float(b_mm),
        outer_shell=outer_shell if law == "outer_shell" else None, split=split,
        layer_count_rule=rule, layers=layers, feed_q=q, edge_taper_db=taper,
        efficiency_taper=eta_t, efficiency_spillover=eta_s, efficiency=eta_t * eta_s,
        efficiency_with_phase=eta_t * eta_s * fig.phase_efficiency,
        rim_fraction=fig.rim_fraction,
        phase_error_pp_deg=fig.phase_error_pp_deg, phase_error_rms_deg=fig.phase_error_rms_deg,
        phase_error_pp_full_deg=fig.phase_error_pp_full_deg,
        phase_error_rms_full_deg=fig.phase_error_rms_full_deg,
        focus_spread_mm=fig.focus_spread_mm, focus_spread_rms_mm=fig.focus_spread_rms_mm,
        focus_spread_full_mm=fig.focus_spread_full_mm,
        axial_focus_min_mm=fig.axial_focus_min_mm, axial_focus_max_mm=fig.axial_focus_max_mm,
        max_exit_tilt_rad=fig.max_exit_tilt_rad, axial_loss_db=loss_db, checks=tuple(checks))
