"""The complete slot-array synthesis: spec numbers in, :class:`SlotArrayDesign` out (seed-003)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.slot_array.beamformer import BeamFormer
from antenna_cad.synthesis.slot_array.bifocal_mirror_lens import bifocal_mirror_lens
from antenna_cad.synthesis.slot_array.bifocal_two_mirror import bifocal_two_mirror
from antenna_cad.synthesis.slot_array.common import BEAMFORMERS, C_MM_GHZ, FEED_RMS_WARN, _lower, raise_on_fail
from antenna_cad.synthesis.slot_array.curves import Curve, _make_curve, offset_curve
from antenna_cad.synthesis.slot_array.ellipse import ellipse_mirror
from antenna_cad.synthesis.slot_array.feeds import FeedSet, place_feeds
from antenna_cad.synthesis.slot_array.optimise import FREE, Optimum, optimise
from antenna_cad.synthesis.slot_array.layout import (SlotLayout, build_slot_layout, cell_pattern, check_coupling_clearance,
                                                     check_slot_webs, check_slots_in_wall)
from antenna_cad.synthesis.slot_array.scan import (ScanFigures, guide_gamma_per_mm, guide_wavelength_mm, ideal_gain_dbi,
                                                   period_for_angle_mm, scan_figures)
from antenna_cad.synthesis.slot_array.slot_line import feed_phase_errors, slot_line_t_mm, slot_phase_spread
from antenna_cad.synthesis.slot_array.taper import taper_slot_lengths_mm
from antenna_cad.synthesis.slot_array.trifocal_mirror_lens import optimise_o1, trifocal_mirror_lens
from antenna_cad.synthesis.slot_array.trifocal_two_mirror import optimise_beta_c, trifocal_two_mirror


@dataclass(frozen=True)
class SlotArrayDesign:
    """Complete synthesis result (frame and units: module docstring).

    ``slot_line``: Curve through the first-slot-line points (x, y_Q + t) over the guide array;
    ``coupling_slot_edge``: far edge of the coupling slot, the normal offset of
    ``beamformer.guide_curve`` (slot near edge) by ``coupling_slot_mm`` toward +y;
    ``figures``: scalar key figures (mm, GHz, dBi, rad); ``phase_spread_wavelengths``: peak-to-
    peak slot-phase spread per design focus (ray-traced); per-feed aberration and beam azimuth
    are in ``feeds``. ``termination``: ``matched_load`` (absorber wedge of ``load_length_mm``
    before the end wall) or ``short`` (end wall after the last cell, ``load_length_mm`` = 0).
    """
    scan: ScanFigures
    beamformer: BeamFormer
    slots: SlotLayout
    slot_line: Curve
    coupling_slot_edge: Curve
    feeds: FeedSet
    guide_width_mm: float
    guide_height_mm: float
    wall_mm: float
    fill_eps_r: float
    layer_height_mm: float
    coupling_slot_mm: float
    termination: str
    load_length_mm: float
    phase_spread_wavelengths: np.ndarray
    figures: dict
    checks: tuple[Check, ...]


_CHECK_FIELDS = {
    "slots_inside_wall": "slots.width_mm",
    "slot_web": "slots.period_mm",
    "coupling_slot_clearance": "beamformer.slot_line_offset_mm",
    "te10_cutoff_margin": "waveguide.width_mm",
    "minus1_radiates": "slots.period_mm",
    "guides_inside_aperture": "array.count",
    "lens_thickness": "beamformer",
}


def synthesize_slot_array(
        *, min_ghz: float, max_ghz: float, design_ghz: float,
        guide_width_mm: float, guide_height_mm: float, fill_eps_r: float, wall_mm: float,
        count: int, pitch_mm: float, length_mm: float,
        layout: str, slot_width_mm: float, period_mm: float | None = None,
        design_theta_rad: float = 0.0,
        taper_law: str = "sin", taper_eta: float = 0.9, taper_a0: float | None = None,
        taper_b0: float | None = None, taper_pedestal: float = 0.3,
        lengths_mm=None, l2_mm=None, l2_ratio: float = 0.68, slot_offset_mm: float | None = None,
        pair_shift_mm: float | None = None, transverse_spacings_mm=(1.66, 1.62),
        beamformer_type: str = "single_mirror", beamformer_params: dict | None = None,
        scale_mm: float | None = None, slot_line_offset_mm: float = 10.0,
        layer_height_mm: float = 1.6, coupling_slot_mm: float = 1.1,
        feed_count: int = 1, feed_throat_mm=(7.2, 1.6), feed_aperture_mm=(16.0, 1.6),
        feed_length_mm: float = 30.0, feed_placement: str = "optimal",
        wall_clearance_mm: float = 0.2, min_web_mm: float = 0.3, min_coupling_gap_mm: float = 0.0,
        termination: str = "matched_load", load_length_mm: float | None = None,
        strict: bool = True) -> SlotArrayDesign:
    """Synthesise a frequency-scanning planar multibeam waveguide-slot array (seed-003).

    Steps: period (given, or auto from (3.1) so that the −1st harmonic points at
    ``design_theta_rad`` from broadside at ``design_ghz``: broadside ⇒ p = λg); scan figures and
    mode/harmonic checks over the band (§3.1, §8.3); beam former (§3.3–§3.5) scaled to mm
    (``scale_mm`` = physical size of the normalised D = 1; default pitch·count); curved slot line
    t(x) at the design frequency (§3.5, erratum §7.5, guide index n = γ/k, erratum §7.8); slot
    lengths from the taper (1.1, erratum §7.1) unless ``lengths_mm`` is given; the slot layout;
    manufacturability checks. ``beamformer_params`` (normalised unless _mm):
    single_mirror: minor_semi_axis_mm, focal_separation_mm; bifocal_two_mirror: a0, a2, h1, b0,
    b2, h2, rho1 (rho2 = inf: plane output fronts are required to feed the guides);
    bifocal_mirror_lens: lens_a2, lens_vertex, x0, p1, p2, f0, n; trifocal_two_mirror: f1, f (x, z
    pairs), c, beta_c_deg (None: optimised, §3.8), optional t_b (t at B, normalised; replaces t0);
    trifocal_mirror_lens: f1, f, x_a, gamma_a_rad, n, o1 ((0, z) or None: optimised, §3.8), optional t_b.
    ``optimize`` (all but bifocal_mirror_lens): the given values are the start of the §3.8 search over the
    former's free parameters (:mod:`.optimise`, ``optimize_evaluations`` σ curves); the found values
    are used and reported in ``figures`` (``optimised_*``).
    ``slot_line_offset_mm`` is
    t0, the distance along the guide from the last mirror to the first slot line at x = 0.
    Slots: ``lengths_mm`` (per cell for the longitudinal layouts, s1..s3 for transverse_3),
    ``l2_mm``/``l2_ratio`` (other three slots of the 4-slot cell), ``slot_offset_mm`` (default
    a/4), ``pair_shift_mm`` (default λg/2), ``transverse_spacings_mm`` (d1, d2); see
    :func:`cell_pattern`. Feeds: ``feed_placement`` = optimal | circle (:func:`place_feeds`).
    Manufacturability limits: ``wall_clearance_mm``, ``min_web_mm``, ``min_coupling_gap_mm``.
    Far end (:func:`termination_check`): ``termination`` = matched_load (absorber wedge of
    ``load_length_mm``, default λg at ``min_ghz``) or short.
    With ``strict`` a failed check raises :class:`DesignError` naming the spec field and the
    number; with ``strict=False`` failures are returned in ``checks``.
    """
    bp = dict(beamformer_params or {})
    optimize, evaluations = bool(bp.pop("optimize", False)), int(bp.pop("optimize_evaluations", 40))
    opt = None
    if optimize and beamformer_type not in FREE:
        raise DesignError("beamformer.optimize", f"no §3.8 optimiser for {beamformer_type} (have: {', '.join(FREE)})")
    a, eps = float(guide_width_mm), float(fill_eps_r)
    if count < 1 or pitch_mm <= 0 or length_mm <= 0:
        raise DesignError("array", f"need count >= 1, pitch_mm > 0, length_mm > 0 "
                          f"(got {count}, {pitch_mm}, {length_mm})")
    if pitch_mm < a + 2 * wall_mm - 1e-9:
        raise DesignError("array.pitch_mm", f"pitch {pitch_mm:.4g} mm < guide width + 2 walls "
                          f"{a + 2 * wall_mm:.4g} mm")
    beta_design = np.pi / 2 - design_theta_rad
    if period_mm is None:
        period_mm = period_for_angle_mm(design_ghz, a, eps, beta_design)
    period_mm = float(period_mm)
    layers = [("layer1", layer_height_mm, 1.0)]
    if beamformer_type in ("bifocal_mirror_lens", "trifocal_mirror_lens"):
        layers.append(("lens", layer_height_mm, float(bp.get("n", np.sqrt(2.2)))))
    scan = scan_figures(min_ghz=min_ghz, max_ghz=max_ghz, design_ghz=design_ghz, width_mm=a,
                        height_mm=guide_height_mm, eps_r=eps, period_mm=period_mm,
                        layer_heights_mm=layers)
    nw = scan.n_guide_design
    cb = float(np.cos(scan.beta_design_rad))
    lam = C_MM_GHZ / design_ghz

    span = count * pitch_mm
    guide_x = (np.arange(count) - (count - 1) / 2) * pitch_mm
    checks = list(scan.checks)
    if beamformer_type == "single_mirror":
        D = span if scale_mm is None else float(scale_mm)
        if optimize:
            opt = optimise(beamformer_type, {"minor_semi_axis": bp["minor_semi_axis_mm"] / D,
                                             "focal_separation": bp["focal_separation_mm"] / D}, 0.5, evaluations)
            bp["focal_separation_mm"] = opt.found[0] * D
        bf = ellipse_mirror(bp["minor_semi_axis_mm"], bp["focal_separation_mm"], D / 2)
        aim_point = np.zeros(2)
    elif beamformer_type == "bifocal_two_mirror":
        if np.isfinite(bp.get("rho2", np.inf)):
            raise DesignError("beamformer.rho2", "the guides need plane output fronts: rho2 must "
                              f"be inf (got {bp['rho2']})")
        D = span if scale_mm is None else float(scale_mm)
        keys = ("a0", "a2", "h1", "b0", "b2", "h2", "rho1")
        if optimize:
            opt = optimise(beamformer_type, {k: float(bp[k]) for k in keys}, 0.5, evaluations)
            bp = opt.params(bp)
        bf = bifocal_two_mirror(**{k: float(bp[k]) for k in keys}, half_width=0.5, scale_mm=D)
        aim_point = np.array([0.0, bp["a0"] * D])
    elif beamformer_type == "bifocal_mirror_lens":
        D = span if scale_mm is None else float(scale_mm)
        keys = ("lens_a2", "lens_vertex", "x0", "p1", "p2", "f0", "n")
        bf = bifocal_mirror_lens(**{k: float(bp[k]) for k in keys}, half_width=0.5, scale_mm=D)
        aim_point = np.array([0.0, bp["lens_vertex"] * D])
        checks.append(_lower("lens_thickness", bf.params["min_lens_thickness_mm"], 0.0, "mm",
                             "minimum lens thickness over the aperture"))
    elif beamformer_type == "trifocal_two_mirror":
        D = span if scale_mm is None else float(scale_mm)
        hw = (np.abs(guide_x).max() + a / 2 + wall_mm) / D
        beta_c = (np.radians(bp["beta_c_deg"]) if bp.get("beta_c_deg") is not None else
                  optimise_beta_c(f1=bp["f1"], f_z=bp["f"][1], c=bp["c"], half_width=hw)[0])
        if optimize:
            start = {"f1_x": bp["f1"][0], "f1_z": bp["f1"][1], "f_z": bp["f"][1], "c_x": bp["c"][0], "c_z": bp["c"][1],
                     "beta_c_deg": float(np.degrees(beta_c))}
            opt = optimise(beamformer_type, start, hw, evaluations)
            found = opt.params(start)
            bp |= {"c": (found["c_x"], found["c_z"]), "f1": (found["f1_x"], found["f1_z"]), "f": (0.0, found["f_z"])}
            beta_c = float(np.radians(found["beta_c_deg"]))
        bf = trifocal_two_mirror(f1=bp["f1"], f_z=bp["f"][1], c=bp["c"], beta_c=beta_c, half_width=hw + 0.005,
                                 margin=0.02, scale_mm=D)
        aim_point = np.array([0.0, bf.params["b0"] * D])
    elif beamformer_type == "trifocal_mirror_lens":
        D = span if scale_mm is None else float(scale_mm)
        hw = (np.abs(guide_x).max() + a / 2 + wall_mm) / D
        lens_args = dict(f1=bp["f1"], f_z=bp["f"][1], x_a=bp["x_a"], gamma_a=bp["gamma_a_rad"], n=bp["n"])
        o1_z = bp["o1"][1] if bp.get("o1") is not None else optimise_o1(**lens_args, half_width=hw)[0]
        bf = trifocal_mirror_lens(**lens_args, o1_z=o1_z, half_width=hw + 0.005, margin=0.02, scale_mm=D)
        aim_point = np.zeros(2)                                     # lens vertex
        checks.append(_lower("lens_thickness", bf.params["min_lens_thickness_mm"], 0.0, "mm",
                             "minimum lens thickness over the aperture"))
    else:
        raise DesignError("beamformer.type", f"unknown {beamformer_type!r} (use {BEAMFORMERS})")
    if beamformer_type.startswith("trifocal") and bp.get("t_b") is not None:   # t at B (§3.6/§3.7) → t at x = 0
        xb = float(bf.params["B"][0]) * D
        slot_line_offset_mm = bp["t_b"] * D - float(slot_line_t_mm(bf, np.array([xb]), nw, cb, 0.0)[0])
    half_guides = np.abs(guide_x).max() + a / 2 + wall_mm
    x0c, x1c = bf.guide_curve.x_range_mm
    checks.append(Check.upper("guides_inside_aperture", float(half_guides), float(min(-x0c, x1c)),
                              "mm", "half-width of the guide array vs last-mirror half-width"))
    if strict:
        raise_on_fail(checks, _CHECK_FIELDS)

    # curved slot line at the design frequency
    t = slot_line_t_mm(bf, guide_x, nw, cb, slot_line_offset_mm)
    entry = bf.guide_curve.y_at(guide_x)
    n_cells = int(np.floor(length_mm / period_mm + 1e-9))
    if n_cells < 1:
        raise DesignError("array.length_mm", f"shorter than one period ({period_mm:.4g} mm)")

    # slot lengths
    if lengths_mm is None:
        if layout != "longitudinal_4" and (taper_a0 is None or taper_b0 is None):
            raise DesignError("slots.lengths_mm", f"layout {layout}: give lengths_mm or the cell "
                              "fit taper a0/b0 (the α(L1) fit of seed-003 §3.2 is for the Ka "
                              "4-longitudinal-slot cell only)")
        lengths_mm = taper_slot_lengths_mm(n_cells, period_mm, length_mm, taper_law, taper_eta,
                                           0.0078 if taper_a0 is None else taper_a0,
                                           2.01 if taper_b0 is None else taper_b0, taper_pedestal)
    elif layout != "transverse_3":
        lengths_mm = np.asarray(lengths_mm, float)
        if lengths_mm.ndim == 1 and lengths_mm.size != n_cells:
            raise DesignError("slots.lengths_mm", f"{lengths_mm.size} lengths for {n_cells} cells")
    if pair_shift_mm is None:
        pair_shift_mm = 0.5 * 2 * np.pi / float(guide_gamma_per_mm(design_ghz, a, eps))
    dy, off, lens_, ang = cell_pattern(layout, n_cells=n_cells, period_mm=period_mm,
                                       guide_width_mm=a, lengths_mm=lengths_mm, l2_mm=l2_mm,
                                       l2_ratio=l2_ratio, offset_mm=slot_offset_mm,
                                       pair_shift_mm=pair_shift_mm,
                                       transverse_spacings_mm=transverse_spacings_mm)
    slots = build_slot_layout(layout=layout, guide_x_mm=guide_x, guide_entry_y_mm=entry, t_mm=t,
                              n_cells=n_cells, period_mm=period_mm, width_mm=slot_width_mm,
                              dy=dy, off=off, lengths=lens_, ang=ang)
    mchecks = [check_slots_in_wall(slots, a, wall_clearance_mm),
               check_slot_webs(slots, min_web_mm),
               check_coupling_clearance(slots, bf.guide_curve, coupling_slot_mm,
                                        min_coupling_gap_mm)]
    # phase coherence at the cell reference points, every design focus (ray-traced)
    gx = np.repeat(guide_x, n_cells)
    gyref = (slots.slot_line_y_mm[:, None] + np.arange(n_cells)[None, :] * period_mm).reshape(-1)
    spread = slot_phase_spread(bf, gx, gyref, nw, cb, lam)
    for j, sp in enumerate(spread):
        mchecks.append(Check.upper(f"slot_phase_coherence_focus{j + 1}", float(sp), 1e-3,
                                   "λ", f"slot-phase spread for design focus {j + 1}"))
    for j, sg in enumerate(bf.sigma_norm):
        mchecks.append(Check.upper(f"sigma_design_focus{j + 1}", float(sg), 1e-6, "D",
                                   f"RMS path error σ at design focus {j + 1} (2.7)"))
    checks += mchecks
    if strict:
        raise_on_fail(checks, _CHECK_FIELDS)

    slot_line = _slot_line_curve(bf, span, nw, cb, slot_line_offset_mm)
    coupling_edge = offset_curve(bf.guide_curve, coupling_slot_mm, "coupling_slot_edge")
    objective = lambda p: tuple(v[0] for v in feed_phase_errors(bf, p, guide_x, t, nw, cb, lam))
    feeds = place_feeds(bf, count=feed_count, throat_mm=feed_throat_mm,
                        aperture_mm=feed_aperture_mm, length_mm=feed_length_mm,
                        aim_point_mm=aim_point, objective=objective, placement=feed_placement)
    feed_rms = feeds.phase_rms_wavelengths
    worst = float(np.nanmax(feed_rms)) if np.isfinite(feed_rms).any() else np.inf
    checks.append(Check("feed_phase_rms", "warn" if not worst <= FEED_RMS_WARN else "pass",
                        worst, FEED_RMS_WARN, "λ",
                        f"worst RMS slot-phase aberration over {feed_count} feed(s): {worst:.3g} λ"
                        + ("" if np.isfinite(feed_rms).all() else
                           f"; rays from {int((~np.isfinite(feed_rms)).sum())} feed(s) miss")))
    if termination == "matched_load" and load_length_mm is None:
        load_length_mm = float(guide_wavelength_mm(min_ghz, a, eps))
    load_length_mm = float(load_length_mm) if termination == "matched_load" else 0.0
    checks.append(termination_check(termination, load_length_mm,
                                     float(guide_wavelength_mm(min_ghz, a, eps)), taper_eta))
    figures = {
        "period_mm": period_mm, "n_cells": n_cells, "slot_count": slots.count,
        "broadside_ghz": scan.broadside_ghz, "beta_design_rad": scan.beta_design_rad,
        "n_guide_design": nw, "guide_wavelength_design_mm": scan.guide_wavelength_design_mm,
        "aperture_width_mm": span, "aperture_length_mm": n_cells * period_mm,
        "ideal_gain_dbi": ideal_gain_dbi(span, length_mm, design_ghz),
        "beam_azimuth_rad": float(np.arcsin(abs(bf.beam_dirs[0][0]))),
        "slot_line_sag_mm": float(t.max() - t.min()),
        "load_length_mm": load_length_mm, "load_power_fraction": 1.0 - taper_eta,
    }
    if opt is not None:
        figures |= _optimum_figures(opt)
    if "beta_c_rad" in bf.params:                          # trifocal: the parameters the seed leaves out
        figures |= {"beta_c_deg": float(np.degrees(bf.params["beta_c_rad"])), "mirror2_vertex_z": bf.params["a0"],
                    "march_guide_half_width": bf.params["guide_half_width"]}
    elif bf.type == "trifocal_mirror_lens":
        figures |= {"mirror_vertex_z": bf.params["b0"], "beam_alpha_deg": float(np.degrees(bf.params["alpha_rad"])),
                    "lens_a2": bf.params["a2"], "march_guide_half_width": bf.params["guide_half_width"]}
    return SlotArrayDesign(scan, bf, slots, slot_line, coupling_edge, feeds, a,
                           float(guide_height_mm), float(wall_mm), eps, float(layer_height_mm),
                           float(coupling_slot_mm), termination, load_length_mm, spread, figures,
                           tuple(checks))


def _optimum_figures(opt: Optimum) -> dict[str, float]:
    """The §3.8 search as report figures: σ(80°) before and after, the evaluations, start and found values."""
    out = {"optimised_sigma_fov80_start": opt.sigma_start, "optimised_sigma_fov80_found": opt.sigma_found,
           "optimised_evaluations": float(opt.evaluations)}
    for name, a, b in zip(opt.names, opt.start, opt.found):
        out |= {f"optimised_{name}_start": float(a), f"optimised_{name}": float(b)}
    return out


def termination_check(termination: str, load_length_mm: float, guide_wavelength_max_mm: float,
                      eta: float) -> Check:
    """The far end of a leaky-wave guide takes the 1 − η not radiated (seed-003 §3.2, (1.1)).

    ``matched_load``: an absorber wedge shorter than one guide wavelength at the band minimum
    reflects noticeably (warn). ``short``: the residual power reflects; the backward wave's −1st
    harmonic radiates at β' = π − β, a beam mirrored about broadside about 10·log10(1 − η) dB
    below the main beam (warn).
    """
    if termination == "short":
        return Check("termination", "warn", 1.0 - eta, 0.0, "",
                     f"short-circuit guide ends: the residual {100 * (1 - eta):.0f} % reflects and "
                     f"radiates a beam mirrored about broadside ≈ {10 * np.log10(1 - eta):.1f} dB "
                     "below the main beam (waveguide.termination: matched_load avoids it)")
    if termination != "matched_load":
        raise DesignError("waveguide.termination", f"use matched_load or short (got {termination!r})")
    short = load_length_mm < guide_wavelength_max_mm
    return Check("termination", "warn" if short else "pass", load_length_mm, guide_wavelength_max_mm,
                 "mm", f"matched-load wedge {load_length_mm:.4g} mm "
                 + ("shorter than" if short else "≥") + f" one guide wavelength at the band minimum "
                 f"({guide_wavelength_max_mm:.4g} mm); it takes {100 * (1 - eta):.0f} % of the input")


def _slot_line_curve(bf: BeamFormer, span_mm: float, n_guide: float, cos_beta: float,
                     t0_mm: float, n_points: int = 201) -> Curve:
    """First slot-centre line (x, y_Q(x) + t(x)) over the guide array, with tangents."""
    xs = np.linspace(-span_mm / 2, span_mm / 2, n_points)
    yl = lambda x: bf.guide_curve.y_at(x) + slot_line_t_mm(bf, x, n_guide, cos_beta, t0_mm)
    h = 1e-6 * span_mm
    return _make_curve("slot_line", "guides", xs, yl(xs), (yl(xs + h) - yl(xs - h)) / (2 * h))
