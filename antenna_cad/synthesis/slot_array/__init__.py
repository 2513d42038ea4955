"""Frequency-scanning planar multibeam waveguide-slot arrays with curved slot lines (seed 003).

Pure physics (numpy/scipy only). Source: Le Doan Trinh, PhD thesis, MIPT 2020 (the README's
references), cited below as "seed-003 §N".

Frame and units (one frame for everything this package returns)
----------------------------------------------------------------
* All layers are projected onto one plane. **x** runs across the guides, **y** along the guides,
  in the direction the wave travels in the radiating guides (away from the last mirror / coupling
  slot); **z** is the outward normal of the radiating (slotted) face, i.e. broadside = +Z, as in
  seed-003 §2.6 row "3.1". Layers are stacked in z; which layer a curve belongs to is named.
* The origin is the seed's own origin for each beam former: the mirror vertex O for the elliptic
  mirror (§3.5) and the mirror–lens system (§3.4); the centre O between the two mirrors for the
  two-mirror system (§3.3).
* Lengths are millimetres at every interface (``_mm``), frequencies GHz (``_ghz``), angles
  radians. Normalised constructions (D = 1) are scaled by ``scale_mm``.
* β is the angle of the −1st-harmonic ray from the guide axis (+y); broadside is β = π/2 and
  θ = π/2 − β is the elevation angle from broadside (seed-003 §3.1).

The guide wave model is the unloaded TE10 mode, γ = sqrt(ε k² − (π/a)²) (seed-003 §3.1). The
thesis's loaded (slotted) γ came from HFSS and is not available; the broadside frequency of a
slotted guide is ≈ 1 % lower (10.7 vs 10.80 GHz, §3.1).

Modules (one per concern): :mod:`.scan` (§3.1 scan law), :mod:`.taper` (§3.2), :mod:`.curves`,
:mod:`.beamformer` (the shared result and ray traces) and one module per former
(:mod:`.ellipse`, :mod:`.bifocal_two_mirror`, :mod:`.bifocal_mirror_lens`, :mod:`.trifocal_two_mirror`
and :mod:`.trifocal_mirror_lens` on the march of :mod:`.trifocal`), :mod:`.slot_line`, :mod:`.fov` (σ against field angle), :mod:`.optimise` (§3.8),
:mod:`.layout`, :mod:`.feeds`, :mod:`.design`. The names below are re-exported so that
``from antenna_cad.synthesis.slot_array import ...`` keeps working.
"""

from antenna_cad.raytrace.snell import reflect, refract
from antenna_cad.synthesis.slot_array.beamformer import (BeamFormer, trace_mirror_lens, trace_single_mirror,
                                                         trace_two_mirror, with_surfaces)
from antenna_cad.synthesis.slot_array.bifocal_mirror_lens import bifocal_mirror_lens
from antenna_cad.synthesis.slot_array.bifocal_two_mirror import bifocal_two_mirror
from antenna_cad.synthesis.slot_array.common import (BEAMFORMERS, C_MM_GHZ, FEED_RMS_WARN, LAYOUTS, N_SIGMA_RAYS,
                                                     TAPER_LAWS, _normal_from_slope, _slope_from_normal, _unit,
                                                     raise_on_fail)
from antenna_cad.synthesis.slot_array.curves import Curve, intersect_rays_with_curve, offset_curve
from antenna_cad.synthesis.slot_array.design import SlotArrayDesign, synthesize_slot_array, termination_check
from antenna_cad.synthesis.slot_array.ellipse import ellipse_mirror
from antenna_cad.synthesis.slot_array.feeds import FeedSet, place_feeds
from antenna_cad.synthesis.slot_array.layout import (SlotLayout, build_slot_layout, cell_pattern,
                                                     check_coupling_clearance, check_slot_webs, check_slots_in_wall,
                                                     slot_webs_mm)
from antenna_cad.synthesis.slot_array.scan import (ScanFigures, broadside_frequency_ghz, guide_gamma_per_mm,
                                                   guide_wavelength_mm, harmonic_direction_cosine, ideal_gain_dbi,
                                                   period_for_angle_mm, scan_figures, wavenumber_per_mm)
from antenna_cad.synthesis.slot_array.slot_line import (feed_phase_errors, slot_line_t_mm, slot_phase_spread,
                                                        traced_eikonal_mm, traced_rays)
from antenna_cad.synthesis.slot_array.fov import FieldCurve, field_curve, sigma_at
from antenna_cad.synthesis.slot_array.taper import (slot_length_from_alpha_mm, taper_alpha_np_per_m,
                                                    taper_slot_lengths_mm)
from antenna_cad.synthesis.slot_array.trifocal_mirror_lens import optimise_o1, trifocal_mirror_lens
from antenna_cad.synthesis.slot_array.trifocal_two_mirror import optimise_beta_c, trifocal_two_mirror

__all__ = ['reflect', 'refract', 'BeamFormer', 'trace_mirror_lens', 'trace_single_mirror', 'trace_two_mirror',
           'with_surfaces', 'bifocal_mirror_lens', 'bifocal_two_mirror', 'BEAMFORMERS', 'C_MM_GHZ',
           'FEED_RMS_WARN', 'LAYOUTS', 'N_SIGMA_RAYS', 'TAPER_LAWS', '_normal_from_slope',
           '_slope_from_normal', '_unit', 'raise_on_fail', 'Curve', 'intersect_rays_with_curve',
           'offset_curve', 'SlotArrayDesign', 'synthesize_slot_array', 'termination_check', 'ellipse_mirror',
           'FeedSet', 'place_feeds', 'SlotLayout', 'build_slot_layout', 'cell_pattern',
           'check_coupling_clearance', 'check_slot_webs', 'check_slots_in_wall', 'slot_webs_mm',
           'ScanFigures', 'broadside_frequency_ghz', 'guide_gamma_per_mm', 'guide_wavelength_mm',
           'harmonic_direction_cosine', 'ideal_gain_dbi', 'period_for_angle_mm', 'scan_figures',
           'wavenumber_per_mm', 'feed_phase_errors', 'slot_line_t_mm', 'slot_phase_spread',
           'traced_eikonal_mm', 'traced_rays', 'FieldCurve', 'field_curve', 'sigma_at',
           'slot_length_from_alpha_mm', 'taper_alpha_np_per_m', 'taper_slot_lengths_mm', 'optimise_beta_c',
           'trifocal_two_mirror', 'optimise_o1', 'trifocal_mirror_lens']
