"""Glue between the as-built GO check (:mod:`antenna_cad.kinds.asbuilt`) and the full-wave stage
(:mod:`antenna_cad.fullwave`, issue 10): the lens of revolution handed to Meep, and aperture statistics of
the stack as GO of the ideal lens plus the phase the stack adds (full-wave when it ran, else the fast
sub-wavelength model). GO is exact for the smooth lens; on a staircase of sub-wavelength zones it is not
(only the zone-averaged phase propagates), hence this split."""

from __future__ import annotations

from dataclasses import replace

from antenna_cad.fabrication.section import fabricated_section, stepped_section
from antenna_cad.fullwave.lens import C_MM_GHZ, RevolvedLens
from antenna_cad.fullwave.verify import PhaseModel
from antenna_cad.raytrace.collimator import ApertureTrace


def revolved(lens, layup=None, fab=None, feed_z_mm: float | None = None) -> RevolvedLens:
    """The as-built lens (kinds.asbuilt.Lens) as a body of revolution with its feed on the axis."""
    sections = {}
    if layup is not None:
        sections["stepped"] = stepped_section(layup, lens.n)
        if fab is not None:
            sections["fabricated"] = fabricated_section(layup, fab, lens.n)
    return RevolvedLens(lens.front_z, lens.back_z, lens.radius_mm, lens.eps_r, C_MM_GHZ / lens.wavelength_mm,
                        lens.feed[0] if feed_z_mm is None else feed_z_mm, sections)


def modelled_stats(lens, model: PhaseModel, variant: str, feed):
    """Stats of ``variant`` at ``feed``: the GO trace of the ideal lens with the model's added phase
    (taper and riser fraction from GO)."""
    from antenna_cad.kinds.asbuilt import aperture_stats, ruze_loss_db, trace_lens
    tr, keep = trace_lens(lens, lens.faces(lens.n), feed)
    base = aperture_stats(lens, tr, keep)
    ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
    ap = replace(ap, path_mm=ap.path_mm + model.added(variant, ap.y_mm) / 360.0 * lens.wavelength_mm)
    rms = ap.rms_deg()
    return replace(base, p2p_deg=ap.peak_to_peak_deg(), rms_deg=rms, gain_loss_db=ruze_loss_db(rms))
