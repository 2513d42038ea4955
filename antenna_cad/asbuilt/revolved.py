"""Glue between the as-built GO check (:mod:`antenna_cad.asbuilt.lens`) and the full-wave stage
(:mod:`antenna_cad.fullwave`): the lens of revolution handed to Meep, and aperture statistics of
the stack as GO of the ideal lens plus the phase the stack adds (full-wave when it ran, else the fast
sub-wavelength model). GO is exact for the smooth lens; on a staircase of sub-wavelength zones it is not
(only the zone-averaged phase propagates), hence this split."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from antenna_cad.asbuilt.lens import aperture_stats, lens_variants, ruze_loss_db, trace_lens
from antenna_cad.fabrication.section import fabricated_section, stepped_section
from antenna_cad.fullwave.lens import C_MM_GHZ, RevolvedLens
from antenna_cad.fullwave.verify import PhaseModel
from antenna_cad.raytrace.collimator import ApertureTrace


def revolved(lens, layup=None, fab=None, feed_z_mm: float | None = None) -> RevolvedLens:
    """The as-built lens (:class:`antenna_cad.asbuilt.lens.Lens`) as a body of revolution with its feed on the axis."""
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
    tr, keep = trace_lens(lens, lens.faces(lens.n), feed)
    base = aperture_stats(lens, tr, keep)
    ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
    ap = replace(ap, path_mm=ap.path_mm + model.added(variant, ap.y_mm) / 360.0 * lens.wavelength_mm)
    rms = ap.rms_deg()
    return replace(base, p2p_deg=ap.peak_to_peak_deg(), rms_deg=rms, gain_loss_db=ruze_loss_db(rms))


def scan_edge_go(lens, layup, fab, feed) -> dict[str, tuple[np.ndarray, np.ndarray, float, float]]:
    """GO of each variant at the scan-edge ``feed`` (z, y), beside the full-wave scan edge: (y, phase with
    the least-squares tilt removed (deg), beam angle from that tilt (deg), phase efficiency
    |mean e^{iψ}|² over the meridional cut (dB))."""
    out = {}
    for variant, medium in lens_variants(lens, layup, fab):
        tr, keep = trace_lens(lens, medium, feed)
        ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
        order = np.argsort(ap.y_mm)
        slope = np.polyfit(ap.y_mm, ap.phase_deg(), 1)[0]          # deg/mm = k sin θ in degrees
        ph = ap.detrended_phase_deg()
        eff = 20 * np.log10(np.abs(np.mean(np.exp(1j * np.radians(ph)))))
        out[variant] = (ap.y_mm[order], ph[order], float(np.degrees(np.arcsin(slope * lens.wavelength_mm / 360.0))),
                        float(eff))
    return out
