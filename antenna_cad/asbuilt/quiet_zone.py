"""The quiet zone of the lenses of revolution (collimator, bifocal), handed to :mod:`antenna_cad.quietzone`.
A feed on the axis: GO through each variant (ideal, stepped as cut, as fabricated), and the fast model:
the ideal lens and a layup's stepped sections each carried from the feed through its foam by the
multi-slice angular spectrum (a taper-cut stack's cones have no sections: GO only there); and, when the
full-wave stage ran, its runs' fields over the zone's volume (:class:`antenna_cad.fullwave.volume.VolumeField`),
which then come first. A feed off the axis (the scan edge, a bifocal lens's foci) on the meridional cut
(:mod:`antenna_cad.quietzone.cut`): GO, and the 2-D angular spectrum of the ideal lens's GO cut with the
stack's thin screen (the full-wave runs off the axis record no volume; the multi-slice model is a body of
revolution's)."""

from __future__ import annotations

import numpy as np

from antenna_cad.fullwave.lens import C_MM_GHZ, RevolvedLens
from antenna_cad.fullwave.verify import FullWave
from antenna_cad.asbuilt.lens import Lens, lens_zone, trace_lens
from antenna_cad.quietzone.cut import cut_fast_fields, cut_y_mm, go_cut
from antenna_cad.quietzone.verdict import FAST_ERROR_DEG, ModelPlanes, quiet_zone_study
from antenna_cad.quietzone.volume import Rays, Zone, fast_fields, radii_mm
from antenna_cad.raytrace.trace2d import Slabs, transmitted_amplitude
from antenna_cad.verification import Verification

GO = "GO (rays carried straight on; no diffraction)"
FAST = "fast model (multi-slice angular spectrum from the feed through the foam; spill-over and edges diffracted)"
FAST_CUT = ("fast model off the axis (2-D angular spectrum of the GO cut; thin screen of the steps diffracted under "
            "the tilted wave); meridional cut, constant across x")
# The off-axis model is the on-axis fast model's earlier construction (GO aperture field, thin screen), whose
# measured error on the axis (tests/data/quiet_zone_table.csv, before the multi-slice model) stands for its own.
FAST_CUT_ERROR_DEG = 51.6


def _rays(lens: Lens, medium, feed, both_halves: bool = False) -> tuple[Rays, float]:
    """The y ≥ 0 exit rays at the antenna plane (``both_halves``: all of them), and GO's cross-polar level
    (dB) over them."""
    tr, keep = trace_lens(lens, medium, feed)
    lam = lens.wavelength_mm
    half = keep if both_halves else keep & (tr.points[-1][:, 1] >= 0)
    perp, par = (transmitted_amplitude(tr, lam, lens.tan_delta, pol)[half] for pol in ("perp", "par"))
    cross = float(np.max(np.abs(par - perp) / np.abs(par + perp)))
    d = tr.directions[-1][half]
    return (Rays(tr.points[-1][half, 1], d[:, 0], d[:, 1], (par + perp) / 2, tr.opl[half], lens.antenna_z_mm),
            20 * np.log10(max(cross, 1e-12)))


def _zone(lens: Lens, z_ref: float, criteria) -> Zone:
    aut = criteria.aut
    aut_d = None if aut is None else (aut.height_mm if aut.circular else float(np.hypot(aut.width_mm, aut.height_mm)))
    return lens_zone(lens, z_ref, criteria.zone, aut_d)


def _revolved(lens: Lens, variants, feed_z_mm: float) -> RevolvedLens:
    """The lens with the stepped sections among ``variants``, its feed on the axis at ``feed_z_mm``."""
    sections = {n: m for n, m in variants if isinstance(m, Slabs)}
    return RevolvedLens(lens.front_z, lens.back_z, lens.radius_mm, lens.eps_r, C_MM_GHZ / lens.wavelength_mm,
                        feed_z_mm, sections)


def _screens(lens: Lens, variants, feed_z_mm: float, z_ref: float) -> dict:
    """variant → the fast model's thin screen of each stepped section (excess foam, n, radius, lead)."""
    rl = _revolved(lens, variants, feed_z_mm)
    return {n: (lambda r, n=n: rl.excess_mm(n, r), lens.n, lens.radius_mm, z_ref - rl.screen_z_mm())
            for n in rl.sections}


def lens_quiet_zone(lens: Lens, variants, feed: tuple[str, float, float], z_ref: float, criteria,
                    full_wave: FullWave | None = None) -> Verification:
    """Quiet-zone figures of every variant at the nominal on-axis ``feed`` (name, z, y) behind the plane
    ``z_ref`` (the back of the stack); ``full_wave``: the full-wave stage, whose fields over the zone's
    volume come first when they cover the zone (the fast model then follows as ``quiet_zone_fast_*``)."""
    lam, R = lens.wavelength_mm, lens.radius_mm
    zone = _zone(lens, z_ref, criteria)
    go, cross = {}, {}
    for name, medium in variants:
        rays, cross[name] = _rays(lens, medium, feed[1:])
        go[name] = [rays.field_at(z_ref + z, lam) for z in zone.planes_mm]
    rho = radii_mm(max(R, zone.diameter_mm / 2), lam)
    rl = _revolved(lens, variants, feed[1])
    fast = fast_fields(rl, z_ref, zone.planes_mm, rho, ["ideal", *rl.sections])
    kept = [n for n, _ in variants if n not in fast]
    name = FAST + (f"; GO for {', '.join(kept)} (taper-cut cones: no stepped section)" if kept else "")
    fast_planes = {n: [(rho, e) for e in fast[n]] if n in fast else go[n] for n, _ in variants}
    models = [ModelPlanes(name, "", fast_planes), ModelPlanes(GO, "go_", go)]
    meep = _full_wave_planes(full_wave, zone, z_ref, [n for n, _ in variants])
    if meep is not None:
        cut = [n for n, _ in variants if n not in meep]
        name = full_wave.volume_model + (f"; the fast model for {', '.join(cut)} (cut by the budget)" if cut else "")
        models = [ModelPlanes(name, "", {n: meep.get(n, fast_planes[n]) for n, _ in variants}),
                  ModelPlanes(models[0].name, "fast_", fast_planes), models[1]]
    explicit = criteria.zone.diameter_mm is not None or criteria.aut is not None
    error = 0.0 if meep is not None else FAST_ERROR_DEG["phase_p2p_deg"]
    return quiet_zone_study(zone, models, feed[0], cross, explicit, error)


def lens_quiet_zone_off_axis(lens: Lens, variants, feed: tuple[str, float, float], z_ref: float, criteria,
                             ideal_exit, nominal: bool) -> Verification:
    """Quiet-zone figures of every variant at a ``feed`` (name, z, y) off the axis, on the meridional cut
    (:mod:`antenna_cad.quietzone.cut`): GO and the fast model; ``ideal_exit``: the ideal lens's GO field at
    this feed on the plane ``z_ref``, (uniform y, E); ``nominal``: the kind's nominal feed (its tables and
    check keep the plain names)."""
    lam, R = lens.wavelength_mm, lens.radius_mm
    zone = _zone(lens, z_ref, criteria)
    y_out = cut_y_mm(max(R, zone.diameter_mm / 2), lam)
    go, cross = {}, {}
    for name, medium in variants:
        rays, cross[name] = _rays(lens, medium, feed[1:], both_halves=True)
        go[name] = [(y_out, go_cut(rays.y_mm, rays.dz, rays.dy, rays.amplitude, rays.path_mm, rays.z_mm, z_ref + z,
                                   lam, y_out)) for z in zone.planes_mm]
    y, e = ideal_exit
    lit = np.abs(e) > 0
    slope = np.polyfit(y[lit], np.unwrap(np.angle(e[lit])), 1)[0]          # k·sin θ of the beam
    fast = cut_fast_fields(y, e, lam, zone.planes_mm, y_out, float(np.clip(slope * lam / (2 * np.pi), -1, 1)),
                           _screens(lens, variants, feed[1], z_ref))
    kept = [n for n, _ in variants if n not in fast]
    name = FAST_CUT + (f"; GO for {', '.join(kept)} (taper-cut cones: no stepped section)" if kept else "")
    fast_planes = {n: [(y_out, f) for f in fast[n]] if n in fast else go[n] for n, _ in variants}
    models = [ModelPlanes(name, "", fast_planes, cut=True),
              ModelPlanes(GO + "; meridional cut, constant across x", "go_", go, cut=True)]
    explicit = criteria.zone.diameter_mm is not None or criteria.aut is not None
    return quiet_zone_study(zone, models, feed[0], cross, explicit, FAST_CUT_ERROR_DEG, nominal)


def _full_wave_planes(full_wave: FullWave | None, zone, z_ref: float, variants: list[str]):
    """variant → [(r, E) per plane] from the full-wave fields over the zone's volume, or None when none
    ran or they do not cover the zone (its planes and its disc)."""
    if full_wave is None or not full_wave.volume:
        return None
    z = z_ref + zone.planes_mm
    fields = {n: v.planes(z) for n, v in full_wave.volume.items()
              if n in variants and v.covers(z, zone.diameter_mm / 2)}
    return fields or None
