"""Adapters of the waveguide-slot array (seed-003) between its spec and the pipeline stages.

``material`` = guide filling (and lens) dielectric; metal parts use ``fabrication.metal``.
CAD imports are lazy (model stage only).
"""

from __future__ import annotations

from antenna_cad.verification import Verification
from antenna_cad.materials import Material
from antenna_cad.spec.common import resolve_material
from antenna_cad.spec.slot_array import SlotArraySpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.slot_array import SlotArrayDesign, synthesize_slot_array


def synthesize(spec: SlotArraySpec) -> SlotArrayDesign:
    b, wg, ar, sl, bf, fd = spec.band, spec.waveguide, spec.array, spec.slots, spec.beamformer, spec.feeds
    return synthesize_slot_array(
        min_ghz=b.min_ghz, max_ghz=b.max_ghz, design_ghz=b.design_ghz,
        guide_width_mm=wg.width_mm, guide_height_mm=wg.height_mm, fill_eps_r=spec.fill_eps_r,
        wall_mm=wg.wall_mm, count=ar.count, pitch_mm=ar.pitch_mm, length_mm=ar.length_mm,
        layout=sl.layout, slot_width_mm=sl.width_mm,
        period_mm=None if sl.period_mm == "auto" else sl.period_mm,
        taper_law=sl.taper.law, taper_eta=sl.taper.eta, taper_a0=sl.taper.a0, taper_b0=sl.taper.b0,
        taper_pedestal=sl.taper.pedestal, lengths_mm=sl.lengths_mm, l2_ratio=sl.l2_ratio,
        slot_offset_mm=sl.offset_mm, beamformer_type=bf.type, beamformer_params=bf.params(),
        scale_mm=bf.scale_mm, slot_line_offset_mm=bf.slot_line_offset_mm,
        layer_height_mm=bf.layer_height_mm, coupling_slot_mm=bf.coupling_slot_mm,
        feed_count=fd.count, feed_throat_mm=fd.throat_mm, feed_aperture_mm=fd.aperture_mm,
        feed_length_mm=fd.length_mm, feed_placement=fd.placement,
        wall_clearance_mm=sl.wall_clearance_mm, min_web_mm=sl.min_web_mm)


def _metal(spec: SlotArraySpec) -> Material:
    f = spec.fabrication
    return Material(f.metal, 1.0, 0.0, f.metal_density_kg_m3, "metal (conductor), from fabrication")


def _options(spec: SlotArraySpec) -> dict:
    f = spec.fabrication
    return dict(broad_wall_mm=f.broad_wall_mm, mirror_wall_mm=f.mirror_wall_mm,
                plate_margin_mm=f.plate_margin_mm)


def plan(spec: SlotArraySpec, design: SlotArrayDesign):
    """No layup: every part is machined; the model and fabrication read the design directly."""
    return None, ()


def model(spec: SlotArraySpec, design: SlotArrayDesign, layup, panels):
    from antenna_cad.geometry.slot_array import build_model
    return build_model(design, resolve_material(spec.material), _metal(spec), **_options(spec))


def fabricate(spec: SlotArraySpec, design: SlotArrayDesign, layup, panels):
    from antenna_cad.fabrication.slot_array import fabricate_slot_array
    return fabricate_slot_array(design, resolve_material(spec.material), _metal(spec),
                                title=spec.name, **_options(spec))


def summary(spec: SlotArraySpec, design: SlotArrayDesign, layup) -> dict[str, float]:
    figures = {k: (float(v) if not isinstance(v, int) else v) for k, v in design.figures.items()}
    figures |= {"guide_count": spec.array.count, "feed_count": spec.feeds.count,
                "fill_eps_r": design.fill_eps_r}
    return figures


def fabrication_checks(spec: SlotArraySpec, design: SlotArrayDesign, layup) -> list[Check]:
    """Manufacturability checks (slots in wall, webs, coupling clearance) already come with the
    synthesis checks; nothing more is added for machined plates."""
    return []


def verify(spec, design, layup, fab) -> Verification:
    """As-built verification (issue 6): filled in per kind."""
    return Verification()
