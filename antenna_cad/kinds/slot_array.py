"""Adapters of the waveguide-slot array (seed-003) between its spec and the pipeline stages.

``material`` = guide filling (and lens) dielectric; metal parts use ``fabrication.metal``.
CAD imports are lazy (model stage only).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from antenna_cad.geometry.slot_layout import PartSizes, clip_curve
from antenna_cad.kinds.slot_array_fov import fov_block
from antenna_cad.kinds.patterns_slots import slot_patterns
from antenna_cad.materials import Material
from antenna_cad.raytrace.slot_array import Cells, cells_from_slot_table, tolerance_effects, trace_beam
from antenna_cad.spec.common import resolve_material
from antenna_cad.spec.slot_array import SlotArraySpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.slot_array import (FEED_RMS_WARN, BeamFormer, SlotArrayDesign, harmonic_direction_cosine,
                                              synthesize_slot_array, traced_rays, with_surfaces)
from antenna_cad.verification import Plot, Series, Table, Verification


PLATE_PARTS = ("top-", "plate-")     # the drawings of the flat metal parts the router mills


def synthesize(spec: SlotArraySpec) -> SlotArrayDesign:
    b, wg, ar, sl, bf, fd = spec.band, spec.waveguide, spec.array, spec.slots, spec.beamformer, spec.feeds
    return synthesize_slot_array(
        min_ghz=b.min_ghz, max_ghz=b.max_ghz, design_ghz=b.design_ghz,
        guide_width_mm=wg.width_mm, guide_height_mm=wg.height_mm, fill_eps_r=spec.fill_eps_r,
        wall_mm=wg.wall_mm, count=ar.count, pitch_mm=ar.pitch_mm, length_mm=ar.length_mm,
        layout=sl.layout, slot_width_mm=sl.width_mm,
        period_mm=None if sl.period_mm == "auto" else sl.period_mm,
        design_theta_rad=math.radians(sl.design_angle_deg or 0.0),
        taper_law=sl.taper.law, taper_eta=sl.taper.eta, taper_a0=sl.taper.a0, taper_b0=sl.taper.b0,
        taper_pedestal=sl.taper.pedestal, lengths_mm=sl.lengths_mm, l2_ratio=sl.l2_ratio,
        slot_offset_mm=sl.offset_mm, beamformer_type=bf.type, beamformer_params=bf.params(),
        scale_mm=bf.scale_mm, slot_line_offset_mm=bf.slot_line_offset_mm,
        layer_height_mm=bf.layer_height_mm, coupling_slot_mm=bf.coupling_slot_mm,
        feed_count=fd.count, feed_throat_mm=fd.throat_mm, feed_aperture_mm=fd.aperture_mm,
        feed_length_mm=fd.length_mm, feed_placement=fd.placement,
        wall_clearance_mm=sl.wall_clearance_mm, min_web_mm=sl.min_web_mm,
        min_coupling_gap_mm=sl.min_coupling_gap_mm, termination=wg.termination,
        load_length_mm=wg.load_length_mm)


def _metal(spec: SlotArraySpec) -> Material:
    f = spec.fabrication
    return Material(f.metal, 1.0, 0.0, f.metal_density_kg_m3, "metal (conductor), from fabrication")


def _sizes(spec: SlotArraySpec) -> PartSizes:
    f, fd = spec.fabrication, spec.feeds
    return PartSizes(f.broad_wall_mm, f.mirror_wall_mm, f.plate_margin_mm, fd.wall_mm, fd.flange_mm,
                     fd.flange_thickness_mm)


def plan(spec: SlotArraySpec, design: SlotArrayDesign):
    """No layup: every part is machined; the model and fabrication read the design directly."""
    return None, ()


def model(spec: SlotArraySpec, design: SlotArrayDesign, layup, panels):
    from antenna_cad.geometry.slot_array import build_model
    return build_model(design, resolve_material(spec.material), _metal(spec),
                       resolve_material(spec.waveguide.load_material), _sizes(spec))


def fabricate(spec: SlotArraySpec, design: SlotArrayDesign, layup, panels):
    from antenna_cad.fabrication.slot_array import fabricate_slot_array
    plan = fabricate_slot_array(design, resolve_material(spec.material), _metal(spec),
                                resolve_material(spec.waveguide.load_material), _sizes(spec), title=spec.name)
    router = spec.fabrication.router
    if router is None:
        return plan
    from antenna_cad.cam.boards import drawing_parts
    from antenna_cad.cam.plan import plan_board_cam
    cam = plan_board_cam(drawing_parts(plan.drawings, PLATE_PARTS, spec.fabrication.broad_wall_mm), router,
                         "fabrication.router")
    return replace(plan, files=plan.files | cam.files, cam=cam)


def summary(spec: SlotArraySpec, design: SlotArrayDesign, layup) -> dict[str, float]:
    figures = {k: (float(v) if not isinstance(v, int) else v) for k, v in design.figures.items()}
    figures |= {"guide_count": spec.array.count, "feed_count": spec.feeds.count,
                "fill_eps_r": design.fill_eps_r}
    return figures


def fabrication_checks(spec: SlotArraySpec, design: SlotArrayDesign, layup) -> list[Check]:
    """Manufacturability checks (slots in wall, webs, coupling clearance) already come with the
    synthesis checks; nothing more is added for machined plates."""
    return []


N_BAND = 17          # frequencies over the band (the thesis's 17 elevation patterns, seed-003 §4)
N_FAN = 9            # rays per feed in the ray-fan plot
HARMONICS = (0, -1, -2)
PHASE_RMS_WARN_DEG = 360.0 * FEED_RMS_WARN
LOSS_WARN_DB = 1.0
SCALES = (0.5, 1.0, 1.5, 2.0)


def as_built(design: SlotArrayDesign) -> BeamFormer:
    """The beam former as modelled: every mirror and lens is the C¹ spline the CAD extrudes
    (lenses within the mirror's span), sampled densely."""
    from antenna_cad.geometry.slot_array import modelled_curve
    bf = design.beamformer
    span = bf.mirrors[0].x_range_mm
    return with_surfaces(bf, [modelled_curve(m) for m in bf.mirrors],
                         [modelled_curve(clip_curve(lens, *span)) for lens in bf.lenses])


def design_cells(design: SlotArrayDesign) -> Cells:
    """Cell reference points of the synthesis (slot line + m·p), the ideal counterpart of the table."""
    s = design.slots
    G = s.guide_x_mm.size
    return Cells(s.guide_x_mm, s.slot_line_y_mm[:, None] + np.arange(s.n_cells)[None, :] * s.period_mm,
                 np.full(G, design.guide_width_mm), np.full(G, design.fill_eps_r))


def verify(spec: SlotArraySpec, design: SlotArrayDesign, layup, fab) -> Verification:
    """As-built verification (seed-003 §3.9, (3.41)): every feed traced through the beam
    former as modelled to the slot centres as written to slots.csv, ideal vs as-built, over the
    band; sensitivity to the spec tolerances (:mod:`antenna_cad.raytrace.slot_array`)."""
    b, tol, bf = spec.band, spec.tolerances, design.beamformer
    built_bf = as_built(design)
    ideal_cells = design_cells(design)
    cells = cells_from_slot_table(fab.files["slots.csv"], design.guide_width_mm, design.fill_eps_r)
    f = np.unique(np.r_[np.linspace(b.min_ghz, b.max_ghz, N_BAND), b.design_ghz])
    i_d = int(np.argmin(np.abs(f - b.design_ghz)))
    feeds = design.feeds.aperture_centres_mm
    ideal = [trace_beam(bf, p, ideal_cells, f) for p in feeds]
    built = [trace_beam(built_bf, p, cells, f) for p in feeds]
    focus = max(float(trace_beam(bf, F, ideal_cells, b.design_ghz).rms_deg[0]) for F in bf.foci_mm)
    centre = len(feeds) // 2
    effects = {s_: tolerance_effects(built_bf, cells, feeds, design.feeds.aim, b.design_ghz,
                                     eps_r_tol=tol.eps_r_tolerance, width_tol_mm=tol.thickness_tolerance_mm,
                                     feed_tol_mm=tol.feed_position_tolerance_mm, scale=s_) for s_ in SCALES}
    at_spec = effects[1.0]
    dominant = max(at_spec, key=lambda e: e.loss_db)
    worst = lambda fits, attr: max(float(getattr(x, attr)[i_d]) for x in fits)
    figures = {
        "design_focus_phase_rms_deg": focus,
        "phase_rms_deg_ideal_worst_feed": worst(ideal, "rms_deg"),
        "phase_rms_deg_as_built_worst_feed": worst(built, "rms_deg"),
        "phase_pp_deg_as_built_worst_feed": worst(built, "pp_deg"),
        "ruze_loss_db_as_built_worst_feed": worst(built, "ruze_loss_db"),
        "centre_feed_elevation_deg": float(np.degrees(built[centre].elevation_rad[i_d])),
        "centre_feed_azimuth_deg": float(np.degrees(built[centre].azimuth_rad[i_d])),
        "centre_feed_band_phase_rms_deg_max": float(np.nanmax(built[centre].rms_deg)),
        "period_written_mm": cells.period_mm,
        "tolerance_loss_db_worst": dominant.loss_db,
    } | {f"tolerance_loss_db_{_slug(e.name)}": e.loss_db for e in at_spec}
    rms = figures["phase_rms_deg_as_built_worst_feed"]
    checks = (
        Check("as_built_phase_rms", "warn" if rms > PHASE_RMS_WARN_DEG else "pass", rms, PHASE_RMS_WARN_DEG, "deg",
              f"worst feed's RMS phase error at the slots as built, design frequency: {rms:.3g} deg "
              f"(λ/16 = {PHASE_RMS_WARN_DEG:g} deg)"),
        Check.upper("slot_table_period", abs(cells.period_mm - design.slots.period_mm), 1e-3, "mm",
                    "cell period read back from slots.csv vs the design period"),
        Check("tolerance_budget", "warn" if dominant.loss_db > LOSS_WARN_DB else "pass", dominant.loss_db,
              LOSS_WARN_DB, "dB", f"dominant tolerance: {dominant.name} ±{dominant.value:g} {dominant.unit}".rstrip()
              + f" costs {dominant.loss_db:.2f} dB toward the nominal beam"),
    )
    fov_plot, fov_table, fov_figures = fov_block(design)
    v = Verification(figures | fov_figures, checks, (_feed_table(design, ideal, built, i_d), _slot_table(design, cells),
                                                     _tolerance_table(at_spec, dominant), fov_table),
                     (_scan_plot(design, cells, f, built[centre], spec), _ray_plot(design, built_bf),
                      _phase_plot(design, ideal, built, i_d), _sensitivity_plot(effects), fov_plot))
    return v.merged(slot_patterns(spec, design, (("ideal", bf, ideal_cells), ("fabricated", built_bf, cells)),
                                  fab.files["slots.csv"], f, i_d))


def _slug(name: str) -> str:
    return "_".join("".join(c if c.isalnum() else " " for c in name.replace("εr", "eps_r")).split()).lower()


def _feed_table(design, ideal, built, i_d) -> Table:
    rows = []
    for k, (p, fi, fb) in enumerate(zip(design.feeds.aperture_centres_mm, ideal, built), start=1):
        rows.append((f"horn-{k}", round(float(p[0]), 3), round(float(p[1]), 3),
                     round(float(np.degrees(fi.azimuth_rad[i_d])), 4), round(float(np.degrees(fb.azimuth_rad[i_d])), 4),
                     round(float(np.degrees(fb.elevation_rad[i_d])), 4),
                     round(float(fi.rms_deg[i_d]), 4), round(float(fb.rms_deg[i_d]), 4),
                     round(float(fb.pp_deg[i_d]), 4), round(float(fb.ruze_loss_db[i_d]), 5)))
    return Table("feeds", "Per feed at the design frequency: beam and phase error at the slots",
                 ("feed", "x mm", "y mm", "azimuth ideal deg", "azimuth as built deg", "elevation as built deg",
                  "phase RMS ideal deg", "phase RMS as built deg", "phase p-p as built deg", "Ruze loss dB"),
                 tuple(rows), "phase detrended across the guides; feed = horn aperture centre")


def _slot_table(design, cells) -> Table:
    s = design.slots
    per_cell = s.count // max(1, s.guide_x_mm.size * s.n_cells)
    rows = (("guides", s.guide_x_mm.size), ("cells per guide", s.n_cells), ("slots per cell", per_cell),
            ("slots", s.count), ("layout", s.layout), ("period design mm", round(s.period_mm, 6)),
            ("period as written mm", round(cells.period_mm, 6)),
            ("broadside GHz", round(design.scan.broadside_ghz, 4)),
            ("termination", design.termination), ("load length mm", round(design.load_length_mm, 3)))
    return Table("slots", "Slot count and period", ("quantity", "value"), rows)


def _tolerance_table(effects, dominant) -> Table:
    rows = tuple((e.name, e.value, e.unit, round(float(np.degrees(e.d_elevation_rad)), 4),
                  round(float(np.degrees(e.d_azimuth_rad)), 4), round(e.rms_deg, 3), round(e.loss_db, 4),
                  "dominant" if e is dominant else "") for e in effects)
    return Table("sensitivity", "Sensitivity to the build tolerances (worst feed and sign, design frequency)",
                 ("tolerance", "±", "unit", "Δ elevation deg", "Δ azimuth deg", "phase RMS deg", "loss dB", ""),
                 rows, "loss = Ruze increase + pointing loss 12(Δ/θ3)² toward the nominal beam")


def _scan_plot(design, cells, f, centre_fit, spec) -> Plot:
    """Scan angle vs frequency per harmonic (3.1): design period (line), period as written
    (dashed), traced centre feed as built (points); the band edges as vertical lines."""
    sc, ff = design.scan, np.linspace(f[0], f[-1], 161)
    series = []
    for m in HARMONICS:
        for p_mm, style, what in ((design.slots.period_mm, "line", "design"), (cells.period_mm, "dashed", "as written")):
            c = harmonic_direction_cosine(ff, design.guide_width_mm, design.fill_eps_r, p_mm, m)
            series.append(Series(f"harmonic {m}, {what}", ff, np.degrees(np.where(np.abs(c) <= 1, np.arcsin(
                np.clip(c, -1, 1)), np.nan)), style))
    series.append(Series("centre feed, traced as built", f, np.degrees(centre_fit.elevation_rad), "points"))
    for edge in (spec.band.min_ghz, spec.band.max_ghz):
        series.append(Series(f"band edge {edge:g} GHz", np.array([edge, edge]), np.array([-90.0, 90.0]), "dashed"))
    return Plot("scan-curves", "Frequency scan: angle from broadside per spatial harmonic", "frequency GHz",
                "angle from broadside deg (+ toward the guides' far end)", tuple(series),
                f"broadside at {sc.broadside_ghz:.4g} GHz; design {sc.design_ghz:g} GHz")


def _ray_plot(design, bf) -> Plot:
    """Beam former as modelled with a ray fan from every feed to the slot line."""
    s = design.slots
    pick = np.unique(np.linspace(0, s.guide_x_mm.size - 1, N_FAN).round().astype(int))
    xg, line = s.guide_x_mm[pick], s.slot_line_y_mm[pick]
    series = [Series(c.name, c.points_mm[:, 0], c.points_mm[:, 1]) for c in (*bf.mirrors, *bf.lenses)]
    series.append(Series("slot line", design.slot_line.points_mm[:, 0], design.slot_line.points_mm[:, 1], "dashed"))
    for k, p in enumerate(design.feeds.aperture_centres_mm, start=1):
        _, vertices = traced_rays(bf, p, xg)
        pts = [np.broadcast_to(p, (xg.size, 2)), *vertices, np.stack([xg, line], -1),
               np.full((xg.size, 2), np.nan)]
        path = np.stack(pts, 1).reshape(-1, 2)
        series.append(Series(f"horn-{k}", path[:, 0], path[:, 1]))
    return Plot("beamformer-rays", "Beam former as modelled, rays from every feed to the slot line", "x mm", "y mm",
                tuple(series), "all layers projected on one plane (seed-003 §2.6)", equal_aspect=True)


def _phase_plot(design, ideal, built, i_d) -> Plot:
    """Detrended phase at the first cell of every guide, design frequency, per feed."""
    x = design.slots.guide_x_mm
    series = []
    for k, (fi, fb) in enumerate(zip(ideal, built), start=1):
        series.append(Series(f"horn-{k} ideal", x, fi.residual_deg[i_d, :, 0]))
        series.append(Series(f"horn-{k} as built", x, fb.residual_deg[i_d, :, 0], "dashed"))
    return Plot("slot-phase", "Phase error at the slots (first cell of each guide), design frequency", "x mm",
                "detrended phase deg", tuple(series))


def _sensitivity_plot(effects) -> Plot:
    scales = np.array(sorted(effects))
    names = [e.name for e in effects[1.0]]
    series = tuple(Series(n, scales, np.array([effects[s_][i].loss_db for s_ in scales]))
                   for i, n in enumerate(names))
    return Plot("sensitivity", "Gain loss toward the nominal beam vs tolerance", "fraction of the spec tolerance",
                "loss dB", series, hlines=(("warning", LOSS_WARN_DB),))
