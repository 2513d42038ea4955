"""Feed horns on the focal locus (seed-003 §8.1 item 8)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.optimize import minimize_scalar

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.beamformer import BeamFormer
from antenna_cad.synthesis.slot_array.common import _unit


@dataclass(frozen=True)
class FeedSet:
    """H-plane sectoral horns in the feed layer (seed-003 §8.1 item 8).

    Feeds are symmetric about x = 0, adjacent aperture centres exactly one H-plane aperture
    apart (chord). ``placement``: ``circle`` puts them on the circle through the design foci
    about ``locus_centre_mm`` (the seed's approximation of the focal curve, §3.3/§3.5);
    ``optimal`` moves each feed radially (polar angle about ``locus_centre_mm`` chained so the
    pitch stays one aperture) to the radius that minimises its RMS slot-phase aberration
    (:func:`feed_phase_errors`). ``aim`` (K, 2): unit vectors from each aperture centre to
    ``aim_point_mm`` (vertex of the first mirror/lens). The horn body extends from the aperture
    back along −aim by ``length_mm``; throat and aperture are (H-plane, E-plane) mm.
    ``phase_rms_wavelengths`` / ``azimuth_rad``: per feed, residual RMS aberration and beam
    azimuth at the design frequency (NaN where rays miss). ``locus_mm``: the focal locus used
    (circle points, or the optimal-radius locus sampled over the feeds' angular range).
    """
    aperture_centres_mm: np.ndarray
    aim: np.ndarray
    polar_angle_rad: np.ndarray
    radius_mm: np.ndarray
    phase_rms_wavelengths: np.ndarray
    azimuth_rad: np.ndarray
    locus_mm: np.ndarray
    locus_centre_mm: np.ndarray
    aim_point_mm: np.ndarray
    throat_mm: tuple[float, float]
    aperture_mm: tuple[float, float]
    length_mm: float
    placement: str


def place_feeds(bf: BeamFormer, *, count: int, throat_mm, aperture_mm, length_mm: float,
                aim_point_mm, objective: Callable | None = None, placement: str = "circle",
                radius_bounds: tuple[float, float] = (0.6, 1.4), n_locus: int = 9) -> FeedSet:
    """Place ``count`` feeds; ``objective(point_mm) -> (rms_λ, sin φ)`` scores a feed position."""
    if count < 1:
        raise DesignError("feeds.count", f"must be >= 1 (got {count})")
    if placement not in ("circle", "optimal"):
        raise DesignError("feeds.placement", f"use circle or optimal (got {placement!r})")
    c = np.asarray(bf.focal_locus_centre_mm, float)
    F = bf.foci_mm[0]
    R0 = float(np.linalg.norm(F - c))
    up = 1.0 if F[1] > c[1] else -1.0           # side of the foci relative to the centre
    ap = float(aperture_mm[0])
    if ap >= 2 * R0 * radius_bounds[0]:
        raise DesignError("feeds.aperture_mm", f"horn aperture {ap:.4g} mm too large for the "
                          f"focal circle (radius {R0:.4g} mm)")
    pos_of = lambda R, phi: c + np.array([R * np.sin(phi), up * R * np.cos(phi)])

    def score(p):
        if objective is None:
            return np.nan, np.nan
        try:
            r, z = objective(p)
            return float(r), float(np.arcsin(np.clip(z, -1, 1)))
        except DesignError:
            return np.nan, np.nan

    def best_radius(phi_of_R):
        if placement == "circle" or objective is None:
            return R0
        f = lambda R: np.nan_to_num(score(pos_of(R, phi_of_R(R)))[0], nan=1e3)
        res = minimize_scalar(f, bounds=(radius_bounds[0] * R0, radius_bounds[1] * R0),
                              method="bounded", options={"xatol": 1e-5 * R0})
        return float(res.x)

    right = []                                    # (R, phi) of feeds with phi >= 0
    if count % 2:
        right.append((best_radius(lambda R: 0.0), 0.0))
    else:
        phi1 = lambda R: float(np.arcsin(ap / (2 * R)))
        R = best_radius(phi1)
        right.append((R, phi1(R)))
    while 2 * len(right) - (count % 2) < count:
        Rp, php = right[-1]
        def phi_next(R, Rp=Rp, php=php):
            cosd = (R * R + Rp * Rp - ap * ap) / (2 * R * Rp)
            return php + float(np.arccos(np.clip(cosd, -1.0, 1.0)))
        R = best_radius(phi_next)
        right.append((R, phi_next(R)))
    Rs = np.array([r for r, _ in right])
    ph = np.array([p for _, p in right])
    if count % 2:
        Rs = np.concatenate([Rs[:0:-1], Rs])
        ph = np.concatenate([-ph[:0:-1], ph])
    else:
        Rs = np.concatenate([Rs[::-1], Rs])
        ph = np.concatenate([-ph[::-1], ph])
    pos = np.array([pos_of(R, p) for R, p in zip(Rs, ph)])
    aim = _unit(np.asarray(aim_point_mm, float) - pos)
    sc = np.array([score(p) for p in pos]).reshape(-1, 2)
    lim = max(float(np.abs(ph).max()), float(abs(np.arctan2(F[0] - c[0], up * (F[1] - c[1])))))
    lim = max(lim, np.radians(5.0))
    if placement == "optimal" and objective is not None:
        phis = np.linspace(-lim, lim, n_locus)
        half = [best_radius(lambda R, q=q: q) for q in phis[phis >= 0]]
        rl = np.concatenate([half[::-1][:-1] if phis.size % 2 else half[::-1], half])
        locus = np.array([pos_of(R, q) for R, q in zip(rl, phis)])
    else:
        phis = np.linspace(-lim, lim, 121)
        locus = np.array([pos_of(R0, q) for q in phis])
    return FeedSet(pos, aim, ph, Rs, sc[:, 0], sc[:, 1], locus, c,
                   np.asarray(aim_point_mm, float), (float(throat_mm[0]), float(throat_mm[1])),
                   (float(aperture_mm[0]), float(aperture_mm[1])), float(length_mm), placement)
