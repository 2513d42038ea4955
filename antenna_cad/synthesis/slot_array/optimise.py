"""§3.8 optimisation of the beam formers: minimum σ (2.7) over the 80° field of view at β = 90°
(seed-003 §3.8, L1184–1186) over each former's free parameters, from the given (thesis) values.

The thesis optimised every former it compares for that criterion (Ch. 3.4) but gives the result only
for the trifocal ones, and even there leaves parameters out (β_C; erratum §7.6). Free parameters and
bounds here (normalised to D):

- ``single_mirror``: the focal separation c in the dF/D range the thesis studies (0.15–0.45, Ch. 3.1);
  the minor semi-axis b stays: σ falls monotonically with b (as ≈ b⁻³·³), so it fixes the size
  against which the formers are compared;
- ``bifocal_two_mirror``: the initial-segment curvatures and half-widths a2, h1, b2, h2 (§3.3);
  a0, b0 (thickness d0 = 0.5) and ρ1 stay, as in the thesis's own optimisation for 50°;
- ``trifocal_two_mirror``: C (x_C, z_C) and β_C (§3.6); the foci stay at the thesis's values (O2 follows
  from the C¹ condition at B, t_B does not change σ at β = 90°). Freeing the foci too (6 parameters,
  300 evaluations) ended, from the thesis's start, where the 15-angle σ was no better than the start.

Search: bounded Nelder–Mead (scipy) from the given values, deterministic, with a budget of
``evaluations`` objective calls (each ≈ 0.05–1.5 s); a parameter set whose construction fails or
whose rays miss before 40° scores 1. The objective is :meth:`FieldCurve.sigma_fov` on a 7-angle
curve; the reported σ before and after are the full 15-angle curves.

:data:`THESIS_START` holds the start of each former's search: the §2.4 ellipse, the R8 bifocal
two-mirror (§3.3, optimised by the thesis for 50°) and, for the trifocal two-mirror, the thesis's foci
with C = (−0.16, 0.25), β_C = 61.647°, the first set found to march over the guides (the thesis's own
C = (−0.08, 0.25) with z_O2 = −1.02 admits no march; β_C is not given). :data:`OPTIMISED` is what :func:`optimise` finds from there with
:data:`EVALUATIONS` (the report's reference formers; a slow test re-runs the search).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.beamformer import BeamFormer
from antenna_cad.synthesis.slot_array.fov import FOV_DEG, field_curve

INFEASIBLE = 1.0        # σ score of a parameter set that cannot be built or traced over the field of view


@dataclass(frozen=True)
class Free:
    """The free parameters of one former: names, bounds and the initial simplex steps."""
    names: tuple[str, ...]
    lower: tuple[float, ...]
    upper: tuple[float, ...]
    steps: tuple[float, ...]


FREE = {
    "single_mirror": Free(("focal_separation",), (0.15,), (0.45,), (0.05,)),
    "bifocal_two_mirror": Free(("a2", "h1", "b2", "h2"), (-0.3, 0.002, -0.3, 0.002), (0.3, 0.15, 0.3, 0.15),
                               (0.02, 0.01, 0.02, 0.01)),
    "trifocal_two_mirror": Free(("c_x", "c_z", "beta_c_deg"), (-0.25, 0.15, 55.0), (-0.05, 0.35, 70.0),
                                (0.005, 0.005, 0.3)),
}


THESIS_START = {
    "single_mirror": ({"minor_semi_axis": 245 / 300, "focal_separation": 75 / 300}, 0.5),
    "bifocal_two_mirror": ({"a0": 0.25, "a2": -0.01, "h1": 0.005, "b0": -0.25, "b2": 0.1, "h2": 0.055, "rho1": 1.2}, 0.5),
    "trifocal_two_mirror": ({"f1_x": -0.25, "f1_z": -0.23, "f_z": -0.25, "c_x": -0.16, "c_z": 0.25, "beta_c_deg": 61.647},
                            0.345),
}
EVALUATIONS = {"single_mirror": 12, "bifocal_two_mirror": 150, "trifocal_two_mirror": 150}
OPTIMISED = {    # σ(80°): 1.03e-3 → 8.03e-4, 9.89e-4 → 2.04e-4, 1.54e-3 → 5.98e-4
    "single_mirror": THESIS_START["single_mirror"][0] | {"focal_separation": 0.45},
    "bifocal_two_mirror": THESIS_START["bifocal_two_mirror"][0] | {
        "a2": 0.04999977382894413, "h1": 0.0036454718140077015, "b2": -0.04139871192051561, "h2": 0.09202692186307208},
    "trifocal_two_mirror": THESIS_START["trifocal_two_mirror"][0] | {
        "c_x": -0.1476825510530287, "c_z": 0.2489904038697887, "beta_c_deg": 62.14497602320981},
}


@dataclass(frozen=True)
class Optimum:
    """Result of :func:`optimise`: the free parameters before and after, σ(80°) before and after
    (units of the aperture width) and the objective calls used."""
    former: str
    names: tuple[str, ...]
    start: tuple[float, ...]
    found: tuple[float, ...]
    sigma_start: float
    sigma_found: float
    evaluations: int

    def params(self, params: dict) -> dict:
        """``params`` with the free parameters replaced by the ones found."""
        return params | dict(zip(self.names, self.found))


def build(former: str, params: dict, half_width: float) -> BeamFormer:
    """The normalised (D = 1) former of ``params`` (the names of :data:`FREE` plus the fixed ones:
    single_mirror: minor_semi_axis, focal_separation; bifocal_two_mirror: a0, a2, h1, b0, b2, h2,
    rho1; trifocal_two_mirror: f1_x, f1_z, f_z, c_x, c_z, beta_c_deg) over |x| ≤ ``half_width``."""
    p = params
    if former == "single_mirror":
        from antenna_cad.synthesis.slot_array.ellipse import ellipse_mirror
        return ellipse_mirror(p["minor_semi_axis"], p["focal_separation"], half_width)
    if former == "bifocal_two_mirror":
        from antenna_cad.synthesis.slot_array.bifocal_two_mirror import bifocal_two_mirror
        keys = ("a0", "a2", "h1", "b0", "b2", "h2", "rho1")
        return bifocal_two_mirror(**{k: float(p[k]) for k in keys}, half_width=half_width)
    if former == "trifocal_two_mirror":
        from antenna_cad.synthesis.slot_array.trifocal_two_mirror import trifocal_two_mirror
        return trifocal_two_mirror(f1=(p["f1_x"], p["f1_z"]), f_z=p["f_z"], c=(p["c_x"], p["c_z"]),
                                   beta_c=np.radians(p["beta_c_deg"]), half_width=half_width + 0.005,
                                   margin=0.02, n_seg=21)
    raise DesignError("beamformer.type", f"no §3.8 optimiser for {former!r} (have: {', '.join(FREE)})")


def sigma_fov(former: str, params: dict, half_width: float, n_angles: int = 15) -> float:
    """σ over the 80° field of view of ``params`` (:data:`INFEASIBLE` when it cannot be built or traced)."""
    try:
        s = field_curve(build(former, params, half_width), half_width, n_angles=n_angles).sigma_fov(FOV_DEG)
    except (DesignError, ValueError, ZeroDivisionError):
        return INFEASIBLE
    return float(s) if np.isfinite(s) else INFEASIBLE


def optimise(former: str, params: dict, half_width: float, evaluations: int = 40,
             field: str = "beamformer") -> Optimum:
    """Minimise σ over the 80° field of view over the free parameters of ``former`` (module
    docstring), from their values in ``params``. Deterministic; at most ``evaluations`` σ curves."""
    free = FREE.get(former)
    if free is None:
        raise DesignError(field + ".optimize", f"no §3.8 optimiser for {former!r} (have: {', '.join(FREE)})")
    lo, hi = np.array(free.lower), np.array(free.upper)
    x0 = np.array([float(params[k]) for k in free.names])
    if np.any(x0 < lo) or np.any(x0 > hi):
        k = int(np.argmax((x0 < lo) | (x0 > hi)))
        raise DesignError(f"{field}.optimize", f"start {free.names[k]} = {x0[k]:.4g} outside the search "
                          f"bounds {lo[k]:g}…{hi[k]:g} (seed-003 §3.8)")
    start = sigma_fov(former, params, half_width)
    if start >= INFEASIBLE:
        raise DesignError(f"{field}.optimize", "the starting parameters give no former covering the 80° "
                          "field of view: give values that build")
    objective = lambda x: sigma_fov(former, params | dict(zip(free.names, x)), half_width, n_angles=7)
    steps = np.array(free.steps)
    simplex = np.vstack([x0, x0 + np.diag(np.where(x0 + steps <= hi, steps, -steps))])
    res = minimize(objective, x0, method="Nelder-Mead", bounds=list(zip(lo, hi)),
                   options={"initial_simplex": simplex, "maxfev": int(evaluations), "xatol": 1e-5, "fatol": 1e-8})
    found = sigma_fov(former, params | dict(zip(free.names, res.x)), half_width)
    if found >= start:                     # the coarse objective misled the search: keep the start
        return Optimum(former, free.names, tuple(x0), tuple(x0), start, start, int(res.nfev))
    return Optimum(former, free.names, tuple(x0), tuple(float(v) for v in res.x), start, found, int(res.nfev))
