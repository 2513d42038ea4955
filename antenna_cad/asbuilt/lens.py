"""The lens of revolution as the as-built check sees it, and its exact meridional GO trace.

Exact 2-D meridional traces (:mod:`antenna_cad.raytrace.trace2d`, vector Snell, seed-000 §4.2) from a
feed to the antenna plane through (a) the ideal lens, (b) the stepped stack as cut (before sanding),
(c) the stack as fabricated (the cut pieces: necks, pedestal feet, dowels; the material's εr). Per feed:
aperture phase peak-to-peak and RMS with the linear tilt removed (seed-000 §4.1, (2.16)), amplitude
taper from Fresnel transmission and dielectric loss (§4.4, no ray-tube factor, as the seed), gain loss
by Ruze, G/G0 = exp(−σ²) with σ the RMS phase error in rad, and the focus shift. Statistics are over
the rays through the lens aperture, launched uniformly in y across it.

Limits of geometrical optics on a stepped stack, both measured and reported:
* the flat sheet faces do not bend rays toward the axis as the smooth face does, so the exact trace
  adds to the stair-step error k0(n−1)Δd (§7.3) a non-collimation term that grows with the ray angle
  and the path to the antenna plane (small for slow lenses, ≈ 3.5° p-p for the seed's f/8 lens);
* rays that meet a riser do so at grazing incidence and are deflected strongly (or totally
  reflected); they fill strips only t·tan γ wide (a few mm: less than a wavelength), where GO gives
  no usable phase. They are traced and drawn but left out of the phase statistics;
  ``riser_fraction`` says how many they are.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from antenna_cad.asbuilt.taper import Taper
from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fabrication.section import fabricated_section, stepped_section
from antenna_cad.quietzone.volume import Zone, zone_from
from antenna_cad.raytrace.collimator import ApertureTrace
from antenna_cad.raytrace.trace2d import Interface, Slabs, Trace2D, aim_at_face, trace, trace_slabs, \
    transmitted_amplitude
from antenna_cad.spec.common import TestZoneSpec
from antenna_cad.synthesis.collimator import edge_margin_mm
from antenna_cad.verification import detrended

RAYS = 1201                 # rays per trace across the aperture
FAN_RAYS = 31
AIM_MARGIN = 0.999          # rays aimed inside the rim
EDGE_FRACTION = 0.1         # taper: outer vs central tenth of the aperture
VOLUME_MARGIN_WAVELENGTHS = 1.0  # the full-wave quiet-zone record reaches this far past the zone
Medium = tuple[Interface, ...] | Slabs


@dataclass(frozen=True)
class Lens:
    """A lens of revolution as the as-built trace sees it, in its kind's frame (z the axis, y
    transverse, mm). ``faces(n)``: the ideal faces with lens index n (front first; the last one is
    the back face the lens really has, e.g. the flat face behind a layup's back slab)."""
    radius_mm: float
    eps_r: float
    tan_delta: float
    wavelength_mm: float
    budget_deg: float
    antenna_z_mm: float
    feed: tuple[float, float]           # nominal feed (z, y)
    faces: Callable[[float], tuple[Interface, ...]]
    zone: TestZoneSpec = TestZoneSpec()         # the quiet zone the stack is judged over
    aut_diameter_mm: float | None = None        # the AUT's (None: the default AUT, :func:`lens_zone`)

    @property
    def n(self) -> float:
        return self.eps_r ** 0.5

    def front_z(self, r) -> np.ndarray:
        return self.faces(self.n)[0].z_of_y(r)

    def back_z(self, r) -> np.ndarray:
        return self.faces(self.n)[-1].z_of_y(r)


@dataclass(frozen=True)
class Stats:
    p2p_deg: float
    rms_deg: float
    taper_db: float
    gain_loss_db: float
    riser_fraction: float       # aperture rays refracted or reflected at a riser (not in the statistics)


def ruze_loss_db(rms_deg: float) -> float:
    """Gain loss of a random-like phase error, −10·log10(exp(−σ²)), σ the RMS in rad (Ruze)."""
    return float(10 * np.log10(np.e) * np.radians(rms_deg) ** 2)


def _aperture(lens: Lens, tr: Trace2D) -> np.ndarray:
    return tr.ok & (np.abs(tr.points[-2][:, 1]) <= lens.radius_mm)


def trace_lens(lens: Lens, medium: Medium, feed, rays: int = RAYS) -> tuple[Trace2D, np.ndarray]:
    """Trace from ``feed`` through ``medium`` (ideal faces or a stepped section) to the antenna plane;
    returns the trace and the rays that cross the lens aperture without meeting a riser."""
    feed = np.asarray(feed, float)
    dirs = aim_at_face(lens.faces(lens.n)[0], feed, AIM_MARGIN * lens.radius_mm, rays)
    origins = np.tile(feed, (rays, 1))
    if isinstance(medium, Slabs):
        tr = trace_slabs(origins, dirs, medium, lens.antenna_z_mm)
    else:
        tr = trace(origins, dirs, medium, 1.0, lens.antenna_z_mm)
    keep = _aperture(lens, tr)
    return tr, keep if tr.riser is None else keep & ~tr.riser


def aperture_stats(lens: Lens, tr: Trace2D, keep: np.ndarray) -> Stats:
    ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
    y = np.abs(ap.y_mm - np.median(ap.y_mm))
    edge, centre = y >= (1 - EDGE_FRACTION) * y.max(), y <= EDGE_FRACTION * y.max()
    taper = min(20 * np.log10(np.mean(a[edge]) / np.mean(a[centre]))
                for a in (transmitted_amplitude(tr, lens.wavelength_mm, lens.tan_delta, pol)[keep]
                          for pol in ("perp", "par")))
    rms = ap.rms_deg()
    return Stats(ap.peak_to_peak_deg(), rms, float(taper), ruze_loss_db(rms),
                 1.0 - keep.sum() / _aperture(lens, tr).sum())


MAX_HALVINGS = 30
MIN_KEPT_RAYS = 3          # a linear fit of the aperture phase needs a few rays


def focus_shift(lens: Lens, medium: Medium, feed) -> tuple[float, Stats]:
    """Axial feed move (+ toward the lens) that minimizes the RMS phase error, and the stats there.
    Gauss–Newton on the first-order change of the optical path, −δz·cos γ (γ the ray's angle at the
    feed, Fermat), two steps; a step that leaves the aperture without rays is halved until it does not."""
    z0, y0 = feed
    shift = 0.0
    tr, keep = trace_lens(lens, medium, feed)
    for _ in range(2):
        ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
        grad = detrended(ap.y_mm, -360.0 / lens.wavelength_mm * tr.directions[0][keep, 0])
        step = -float(np.dot(ap.detrended_phase_deg(), grad) / np.dot(grad, grad))
        for _ in range(MAX_HALVINGS):        # a step past the lens (a feed far off axis) is halved
            moved, kept = trace_lens(lens, medium, (z0 + shift + step, y0))
            if kept.sum() >= MIN_KEPT_RAYS:
                break
            step /= 2
        else:
            break
        shift, tr, keep = shift + step, moved, kept
    return shift, aperture_stats(lens, tr, keep)


# ------------------------------------------------------------------ the quiet zone behind the lens

def lens_zone(lens: Lens, z_ref: float, spec: TestZoneSpec | None = None, aut_diameter_mm: float | None = None) -> Zone:
    """The quiet zone behind the plane ``z_ref`` (the back of the stack): ``spec`` (default the lens's)
    with the AUT's diameter, else the default AUT's: the lens less the GO edge margin g of seed-000 §4.6
    (2.1) on each side, at least 2 λ."""
    lam, distance = lens.wavelength_mm, lens.antenna_z_mm - z_ref
    aut = aut_diameter_mm if spec is not None else lens.aut_diameter_mm
    if aut is None:
        aut = max(2 * lens.radius_mm - 2 * edge_margin_mm(lam, distance), 2 * lam)
    return zone_from(spec if spec is not None else lens.zone, aut, distance, lens.radius_mm, lam)


def zone_depth_mm(lens: Lens, z_ref: float) -> tuple[float, float]:
    """The z range (the lens's frame) the full-wave runs record for the quiet zone behind ``z_ref``:
    its depth with ``VOLUME_MARGIN_WAVELENGTHS`` either side (the pattern stage's back plane may
    differ from ``z_ref`` by a fraction of a sheet)."""
    zone, pad = lens_zone(lens, z_ref), VOLUME_MARGIN_WAVELENGTHS * lens.wavelength_mm
    return z_ref + zone.distance_mm - pad, z_ref + zone.distance_mm + zone.depth_mm + pad


# ------------------------------------------------------------------ the lens as built

def _scaled(face: Interface, z0: float, scale: float) -> Interface:
    """``face`` stretched along z about z0 (a machined lens off in thickness)."""
    return Interface(lambda y: z0 + scale * (face.z_of_y(y) - z0), lambda y: scale * face.dz_dy(y),
                     face.n_after, z0 + scale * (face.z_guess - z0))


def as_built_medium(lens: Lens, section: Slabs | Taper | None, eps_r: float, scale: float) -> Medium:
    """The as-built lens with material εr and its axial size scaled (each sheet, or the lens, thicker)."""
    n = eps_r ** 0.5
    if isinstance(section, Taper):
        return section.faces(n, scale)
    if section is not None:
        z = section.z_edges
        return replace(section, n=n, z_edges=z[0] + scale * (z - z[0]))
    z0 = float(lens.front_z(0.0))
    return tuple(_scaled(f, z0, scale) for f in lens.faces(n))



def cut_medium(lens: Lens, layup: LayupPlan) -> Medium:
    """The stack as cut for the GO trace: the stepped section, or a taper-cut stack's cones."""
    return Taper(lens, layup).faces(lens.n) if layup.edge == "taper" else stepped_section(layup, lens.n)


def lens_variants(lens: Lens, layup: LayupPlan | None, fab) -> list[tuple[str, Medium]]:
    """(name, medium): the ideal lens, and for a layup the stepped stack as cut and as fabricated. A
    taper-cut stack is its cones in both (dowels only: the feet stay outside the aperture)."""
    n = lens.n
    if layup is None:
        return [("ideal", lens.faces(n))]
    if layup.edge == "taper":
        return [("ideal", lens.faces(n)), ("stepped", cut_medium(lens, layup)), ("fabricated", cut_medium(lens, layup))]
    return [("ideal", lens.faces(n)), ("stepped", stepped_section(layup, n)),
            ("fabricated", fabricated_section(layup, fab, n))]
