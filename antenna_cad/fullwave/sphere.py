"""A graded or layered sphere with its feed on the axis, for the runner, and its exact plane-wave
focusing from the multilayer Mie series (seed-002 §2.4).

Frame of seed-002: sphere centred at the origin, feed on the axis at z = −b, beam toward +z. The feed
touches the sphere (b = R for the classic law), so the collimator's Huygens sheet in front of the lens
does not fit: the feed is meshed as a point source at its phase centre — a transverse electric dipole
(``dipole``) or the crossed electric and magnetic dipoles of a Huygens element (``huygens``, the feed of
seed-002 §2.4.5, pattern (1 + cos θ)/2). The cell is small (the sphere and 1 λ beside it), so the point
feed's grid dispersion over its short path is small; it is measured against Mie in the tests.

Gain by reciprocity (seed-002 §2.4.6, "practical alternative"): a plane wave x̂·e^{ikz} of unit
amplitude focused by the sphere gives E(0, 0, b) at the feed's mirror point; a short dipole there
receives |E_x|² times what it receives in free space, so the lens fed by that dipole has the gain
1.5·|E_x(0, 0, b)|² (referred to the dipole's free-space radiated power; the lens's reaction on the
dipole's impedance is left out). :func:`mie_focal_gain_dbi` evaluates it exactly (``scattnlay``),
the runner's plane-wave deck (:func:`plane_wave_decks`) gives the same from Meep.
"""

from __future__ import annotations

import numpy as np

from antenna_cad.fullwave.deck import BACK_MARGIN_LAMBDA, PML_R_LAMBDA, PML_Z_LAMBDA, R_MARGIN_LAMBDA, make_deck
from antenna_cad.fullwave.mie import mie_field

C_MM_GHZ = 299.792458
FEED_BACK_LAMBDA = 2.0       # air behind the point feed before the axial PML
LAW_SAMPLES = 2049           # the continuous law's ε(r) table for the runner (linear between samples:
                             # < 1e-7 in ε for the classic law; an outer shell's step is smeared over R/2048)
MIE_LAYERS_PER_LAMBDA = 20   # the continuous law as thin Mie shells (≥ MIE_MIN_LAYERS); far below the
MIE_MIN_LAYERS = 60          # quarter-wave thickness at which a periodic stack reflects (0.2 λ shells
                             # at D = 400 λ lost 1.8 dB)
MIE_MAX_D_LAMBDA = 200.0     # the Mie figures up to this D/λ (2000 thin shells, a few seconds)
DIPOLE_DIRECTIVITY = 1.5
PLANE_WAVE_FEED_LAMBDA = 1.0e5   # a feed this far away lights the sphere with a plane wave


def far_directivity_dbi(theta: np.ndarray, power: np.ndarray) -> float:
    """Directivity toward θ = 0 of a runner's ``far_power`` (m = 1, circular polarization: the same in
    every φ plane): 4π·S(0) / (2π ∫ S sin θ dθ)."""
    return float(10 * np.log10(2 * power[0] / np.trapezoid(power * np.sin(theta), theta)))


def law_table(eps_of_r, radius_mm: float) -> dict:
    """The continuous law as the runner's ``graded`` sphere: ε(r) sampled on 0 ≤ r ≤ R."""
    r = np.linspace(0.0, radius_mm, LAW_SAMPLES)
    return {"label": "continuous-law", "center_z_mm": 0.0, "r_mm": np.round(r, 4).tolist(),
            "eps_r": np.round(np.asarray(eps_of_r(r), float), 6).tolist()}


def feed_deck(radius_mm: float, *, parts: list[dict], graded: list[dict], frequency_ghz: float,
              resolution: float, feed_z_mm: float, pattern: str, plane_offset_lambda: float,
              field_map: bool = True, far_field: bool = False) -> dict:
    """The runner's deck of the sphere fed by a point source on the axis at ``feed_z_mm`` (< 0):
    radial extent R + 1 λ and a 4 λ PML as the collimator's, 2 λ of air behind the feed, the aperture
    plane ``plane_offset_lambda`` behind the sphere; ``far_field``: the radiated pattern as well."""
    lam = C_MM_GHZ / frequency_ghz
    plane = radius_mm + plane_offset_lambda * lam
    return {"frequency_ghz": float(frequency_ghz), "resolution_px_per_lambda": float(resolution), "m": 1,
            "parts": parts, "graded": graded, "feed": {"kind": "point", "z_mm": float(feed_z_mm), "pattern": pattern},
            "plane_z_mm": round(plane, 4), "r_max_mm": round(radius_mm + R_MARGIN_LAMBDA * lam, 4),
            "z_min_mm": round(min(-radius_mm, feed_z_mm) - FEED_BACK_LAMBDA * lam, 4),
            "z_max_mm": round(plane + BACK_MARGIN_LAMBDA * lam, 4),
            "pml_r_lambda": PML_R_LAMBDA, "pml_z_lambda": PML_Z_LAMBDA, "field_map": bool(field_map)} | (
            {"far_field": True} if far_field else {})


def plane_wave_decks(parts: list[dict], radius_mm: float, focus_mm: float, *, frequency_ghz: float,
                     resolution: float) -> list[dict]:
    """The sphere lit by a plane wave along +z (the Huygens sheet of a feed 10⁵ λ away) with the plane
    through its focus z = +b, and the same cell empty (the incident field there)."""
    lam = C_MM_GHZ / frequency_ghz
    offset = (focus_mm - radius_mm) / lam
    return [make_deck(p, frequency_ghz=frequency_ghz, resolution=resolution, feed_z_mm=-PLANE_WAVE_FEED_LAMBDA * lam,
                      feed_pattern="dipole", feed_q=1.0, radius_mm=radius_mm, plane_offset_lambda=offset,
                      field_map=False)
            for p in (parts, [dict(q, eps_r=1.0) for q in parts])]


def fine_shells(eps_of_r, radius_mm: float, wavelength_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """The continuous law as thin homogeneous shells (ε at mid-shell) for the Mie series."""
    n = max(MIE_MIN_LAYERS, int(np.ceil(MIE_LAYERS_PER_LAMBDA * radius_mm / wavelength_mm)))
    radii = radius_mm * np.arange(1, n + 1) / n
    return radii, np.asarray(eps_of_r(radii - 0.5 * radius_mm / n), float)


def mie_focal_field(radii_mm, eps, wavelength_mm: float, focus_mm: float, r_mm: np.ndarray) -> np.ndarray:
    """E_x of the plane wave x̂·e^{ikz} focused by the layered sphere, on the plane z = focus at
    radii ``r_mm`` along x (φ = 0, where the runner's Er is E_x)."""
    pts = np.column_stack([r_mm, np.zeros_like(r_mm), np.full(len(r_mm), focus_mm)])
    return mie_field(radii_mm, eps, wavelength_mm, pts)[:, 0]


def focal_gain_dbi(field_ratio: complex) -> float:
    """Gain of the lens fed by a short dipole at the focus from the focal field over the incident one."""
    return float(10 * np.log10(DIPOLE_DIRECTIVITY * abs(field_ratio) ** 2))


def mie_focal_gain_dbi(radii_mm, eps, wavelength_mm: float, focus_mm: float) -> float:
    return focal_gain_dbi(mie_focal_field(radii_mm, eps, wavelength_mm, focus_mm, np.zeros(1))[0])


def aperture_gain_dbi(radius_mm: float, wavelength_mm: float) -> float:
    """(πD/λ)² of the uniformly lit aperture: the bound the focal gain is compared with."""
    return float(20 * np.log10(2 * np.pi * radius_mm / wavelength_mm))
