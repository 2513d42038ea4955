"""The beam-former result shared by every former, ray traces through its curves, and the helpers of
the point-by-point (marching) constructions (seed-003 §3.3–§3.7)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import partial
from typing import Callable, Sequence

import numpy as np

from antenna_cad.raytrace.snell import reflect, refract
from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.common import _normal_from_slope, _unit
from antenna_cad.synthesis.slot_array.curves import Curve, _make_curve, intersect_rays_with_curve


@dataclass(frozen=True)
class BeamFormer:
    """A synthesised quasi-optical beam former, scaled to mm (frame: module docstring).

    ``mirrors``/``lenses``: curves (points + tangents). ``foci_mm``: design foci (K, 2) in the
    feed layer. ``beam_dirs``: (K, 2) unit direction in the xy-plane of the wave that focus k
    launches into the guides' layer: its x component is the azimuth direction cosine of the
    radiated beam. ``sigma_mm``: ray-traced RMS path error (2.7) per design focus (N = 50 rays
    over the aperture), ``sigma_norm`` the same divided by ``aperture_mm``. ``guide_curve`` is
    the curve along which the guides start (last mirror; its coupling slot is offset from it
    toward +y). ``eikonal``: callable (x_mm, focus index) -> design path length (mm) from the
    focus to the guide entry point on ``guide_curve``. ``trace``: (source, x of the launch point
    on the first surface) -> (end point on the last mirror, path, ok, vertices), through the
    curves it was built with (:func:`with_surfaces` swaps them for as-built ones). ``focal_locus``: points of the feed arc,
    ``params``: normalised construction figures (l0, δ, …).
    """
    type: str
    mirrors: tuple[Curve, ...]
    lenses: tuple[Curve, ...]
    foci_mm: np.ndarray
    beam_dirs: np.ndarray
    sigma_mm: np.ndarray
    sigma_norm: np.ndarray
    aperture_mm: float
    guide_curve: Curve
    focal_locus_mm: np.ndarray
    focal_locus_centre_mm: np.ndarray
    eikonal: Callable = field(repr=False)
    trace: Callable = field(repr=False)
    params: dict = field(default_factory=dict)


# Ray traces through the (interpolated) curves of a beam former. Each maps a source point and the
# x of the launch point on the first surface to (end point on the last mirror (N, 2), optical
# path (N,), ok (N,), vertices: the hit points in order, the end point last).

def trace_single_mirror(mirror: Curve, src, x_hit_mm):
    """Source → mirror point at x_hit (the mirror edge is the layer transition), §3.5."""
    xh = np.asarray(x_hit_mm, float)
    p = np.stack([xh, mirror.y_at(xh)], axis=-1)
    return p, np.linalg.norm(p - np.asarray(src, float), axis=-1), np.ones(xh.shape, bool), (p,)


def trace_two_mirror(mir1: Curve, mir2: Curve, src, x_hit_mm):
    """Source → mirror 1 at x_hit (reflection) → mirror 2, §3.3."""
    xh = np.asarray(x_hit_mm, float)
    P = np.stack([xh, mir1.y_at(xh)], -1)
    F = np.asarray(src, float)
    e = reflect(_unit(P - F), _normal_from_slope(mir1.slope_at(xh)))
    Q, ok = intersect_rays_with_curve(P, e, mir2)
    return Q, np.linalg.norm(P - F, axis=-1) + np.linalg.norm(Q - P, axis=-1), ok, (P, Q)


def trace_mirror_lens(lens: Curve, mirror: Curve, n: float, src, x_hit_mm):
    """Source → lens surface at x_hit (refraction into index n) → mirror, §3.4."""
    xh = np.asarray(x_hit_mm, float)
    K = np.stack([xh, lens.y_at(xh)], -1)
    F = np.asarray(src, float)
    e, ok1 = refract(_unit(K - F), _normal_from_slope(lens.slope_at(xh)), 1.0, n)
    Q, ok2 = intersect_rays_with_curve(K, _unit(e), mirror)
    return Q, np.linalg.norm(K - F, axis=-1) + n * np.linalg.norm(Q - K, axis=-1), ok1 & ok2, (K, Q)


def with_surfaces(bf: "BeamFormer", mirrors: Sequence[Curve], lenses: Sequence[Curve] = (),
                  lens_index: float | None = None) -> "BeamFormer":
    """The same beam former traced through other surfaces (the as-built curves, a perturbed lens
    index); foci, design eikonal and beam directions stay those of the design."""
    mirrors, lenses = tuple(mirrors), tuple(lenses)
    if bf.type == "single_mirror":
        trace = partial(trace_single_mirror, mirrors[0])
    elif bf.type in ("bifocal_two_mirror", "trifocal_two_mirror"):
        trace = partial(trace_two_mirror, *mirrors)
    else:
        n = bf.params["n"] if lens_index is None else float(lens_index)
        trace = partial(trace_mirror_lens, lenses[0], mirrors[0], n)
    return replace(bf, mirrors=mirrors, lenses=lenses, guide_curve=mirrors[-1], trace=trace)


def _remaining_to_point(P, e, G, L):
    """t with |G − (P + t e)| = L − t (seed-003 §3.3, vector form)."""
    w = G - P
    return (np.sum(w * w, axis=-1) - L**2) / (2.0 * (np.sum(e * w, axis=-1) - L))


def _monotone_prefix(seg):
    """Keep the leading part of a new segment where x still increases (fold = divergence)."""
    x = seg[0]
    dx = np.diff(x)
    typical = np.median(dx[dx > 0]) if np.any(dx > 0) else 0.0
    bad = np.nonzero((dx <= 0) | (dx > 20.0 * typical))[0]      # fold or jump
    if bad.size == 0:
        return seg
    k = int(bad[0]) + 1
    return tuple(a[:k] for a in seg)


def _monotone(seg_x: np.ndarray, what: str, field_name: str) -> None:
    if not np.all(np.diff(seg_x) > 0):
        raise DesignError(field_name, f"{what}: construction folded back (x not increasing); "
                          f"the initial-segment parameters do not give a smooth surface")


def _assemble_symmetric(segs, name, layer, scale):
    """Join the initial (symmetric) segment and the right-hand segments; mirror to the left."""
    x0, y0, s0 = segs[0]
    xr = np.concatenate([s[0] for s in segs[1:]]) if len(segs) > 1 else np.empty(0)
    yr = np.concatenate([s[1] for s in segs[1:]]) if len(segs) > 1 else np.empty(0)
    sr = np.concatenate([s[2] for s in segs[1:]]) if len(segs) > 1 else np.empty(0)
    x = np.concatenate([-xr[::-1], x0, xr])
    y = np.concatenate([yr[::-1], y0, yr])
    s = np.concatenate([-sr[::-1], s0, sr])
    return _make_curve(name, layer, x, y, s, scale)
