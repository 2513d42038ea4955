"""As-built verification of the lenses of revolution, shared by the collimator and bifocal kinds: per
feed the GO figures of the ideal lens, the stepped stack as cut and the stack as fabricated
(:mod:`antenna_cad.asbuilt.lens`), the full-wave stage, the unsanded-stack check over the quiet zone,
the stock candidates (:mod:`antenna_cad.asbuilt.stock`), the tolerance budget
(:mod:`antenna_cad.asbuilt.tolerance`), and the report's tables and plot data."""

from __future__ import annotations

import numpy as np

from antenna_cad.asbuilt.lens import FAN_RAYS, Lens, Medium, aperture_stats, focus_shift, lens_variants, trace_lens, \
    zone_depth_mm
from antenna_cad.asbuilt.revolved import modelled_stats, revolved
from antenna_cad.asbuilt.stock import Candidate, candidates_table, excess_mm, stack_zone, stack_zone_full_wave
from antenna_cad.asbuilt.taper import Taper
from antenna_cad.asbuilt.tolerance import tolerance_budget
from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fullwave.verify import FullWave, full_wave_study
from antenna_cad.quietzone.verdict import FAST_ERROR_DEG, UNCERTAIN, undecided
from antenna_cad.raytrace.collimator import ApertureTrace
from antenna_cad.raytrace.trace2d import Slabs
from antenna_cad.spec.common import TolerancesSpec, VerificationSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.verification import Plot, Series, Table, Verification, cell


VARIANT_CAPTIONS = {"ideal": "ideal lens", "stepped": "stepped stack as cut", "fabricated": "stack as fabricated"}


def verify_lens(lens: Lens, feeds: tuple[tuple[str, float, float], ...], tolerances: TolerancesSpec,
                layup: LayupPlan | None = None, fab=None, study: tuple[Candidate, ...] = (),
                settings: VerificationSpec = VerificationSpec()) -> tuple[Verification, FullWave]:
    """Figures, checks, tables and plots of the as-built lens, and its full-wave stage (whose fields
    over the quiet zone the quiet-zone study takes). ``feeds``: (name, z, y), the first at the nominal
    feed; ``study``: the stock candidates (layups); ``settings``: the full-wave stage whose phase model
    the sanding check and the tolerance budget follow."""
    n = lens.n
    variants = lens_variants(lens, layup, fab)
    section = (Taper(lens, layup) if layup.edge == "taper" else variants[-1][1]) if layup is not None else None
    as_built = variants[-1][1]
    figures: dict[str, float] = {}
    rows, plots, go = [], [], {}
    for name, z, y in feeds:
        series = []
        for variant, medium in variants:
            tr, keep = trace_lens(lens, medium, (z, y))
            st = aperture_stats(lens, tr, keep)
            figures |= {f"{variant}_{name}_{k}": v for k, v in vars(st).items()}
            ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
            order = np.argsort(ap.y_mm)
            series.append(Series(variant, ap.y_mm[order], ap.detrended_phase_deg()[order]))
            if y == 0.0:
                go[variant] = (ap.y_mm[order], ap.detrended_phase_deg()[order])
            rows.append((name, variant, cell(st.p2p_deg), cell(st.rms_deg), cell(st.taper_db), cell(st.gain_loss_db)))
        shift, refocused = focus_shift(lens, as_built, (z, y))
        figures |= {f"{name}_feed_z_mm": z, f"{name}_feed_y_mm": y, f"{name}_focus_shift_mm": shift,
                    f"{name}_refocused_rms_deg": refocused.rms_deg}
        plots.append(Plot(f"aperture-phase-{name.replace('_', '-')}", f"Aperture phase, feed {name} "
                          f"(z {z:.1f}, y {y:.1f} mm)", "y on the antenna plane (mm)", "phase, tilt removed (deg)",
                          tuple(series), caption=", ".join(VARIANT_CAPTIONS[v] for v, _ in variants)))
    tables = [Table("aperture", "Aperture phase and amplitude per feed",
                    ("feed", "lens", "p-p deg", "RMS deg", "taper dB", "gain loss dB"), tuple(rows))]
    rl = revolved(lens, layup, fab)
    fw = full_wave_study(rl, settings, go, zone_depth_mm(lens, rl.plane_z_mm(0.0)))
    figures |= fw.figures
    checks = list(fw.checks)
    nominal = feeds[0][0]
    model = None
    if layup is not None:
        tables.append(_layer_table(lens, layup, fab))
        plots.append(_profile_plot(lens, layup))
        model = modelled_stats(lens, fw.model, "fabricated", feeds[0][1:])
        zone, zone_model = stack_zone_full_wave(lens, fw, rl.plane_z_mm(0.0)), fw.volume_model
        if zone is None:
            zone, zone_model = stack_zone(lens, layup, fab)["fabricated"], "fast model"
        pp = zone.p2p_deg
        figures |= {f"model_fabricated_{nominal}_p2p_deg": model.p2p_deg, f"model_fabricated_{nominal}_rms_deg":
                    model.rms_deg, f"stack_zone_fabricated_{nominal}_p2p_deg": pp,
                    f"stack_zone_fabricated_{nominal}_rms_deg": zone.rms_deg}
        unsure = zone_model == "fast model" and undecided(pp, lens.budget_deg, FAST_ERROR_DEG["own_phase_p2p_deg"])
        checks.append(Check("unsanded_step_phase_error", "warn" if pp > lens.budget_deg or unsure else "pass", pp,
                            lens.budget_deg, "deg", (f"{UNCERTAIN}: " if unsure else "") +
                            f"as fabricated, unsanded ({layup.sheet_thickness_mm:g} mm sheets): the stack's own phase "
                            f"over the quiet zone {pp:.1f}° p-p (worst plane {zone.plane_mm:.0f} mm behind the stack; "
                            f"{zone_model}) vs budget {lens.budget_deg:g}°; on one plane {model.p2p_deg:.1f}° "
                            f"({fw.model.name}), GO alone {figures[f'fabricated_{nominal}_p2p_deg']:.1f}°"
                            + _over_budget(layup, pp > lens.budget_deg)))
    if study:
        tables.append(candidates_table(study, layup))
    own = (zone.p2p_deg, zone.rms_deg) if layup is not None else None
    own_error = FAST_ERROR_DEG["own_phase_p2p_deg"] if layup is not None and zone_model == "fast model" else 0.0
    added_fab = (lambda y: fw.model.added("fabricated", y)) if "fabricated" in fw.model.added_deg else None
    sens_table, sens_plot, sens_figures, sens_check = tolerance_budget(lens, section, tolerances, layup, own, added_fab,
                                                                   model, own_error)
    figures |= sens_figures
    return Verification(figures, tuple(checks + [sens_check]), tuple(tables + [sens_table]),
                        tuple(plots + [_fan_plot(lens, as_built, section), sens_plot]) + fw.plots, fw.files), fw


def _over_budget(layup: LayupPlan, over: bool) -> str:
    if not over:
        return ""
    if layup.edge == "taper":
        return "; taper-cut: thinner sheets bring the cones closer to the profile"
    return "; sanding required: it removes the stack's own error (the ideal lens)"


def _layer_table(lens: Lens, layup: LayupPlan, fab) -> Table:
    excess = excess_mm(lens, layup, np.linspace(0.0, lens.radius_mm, 4001)).max(axis=1)
    pieces = [sum(p.sheet_index == s.index for p in fab.pieces) for s in layup.sheets]
    if layup.edge == "taper":
        gaps = Taper(lens, layup).largest_gap_mm()
        rows = tuple((s.label, cell(s.z_min_mm), cell(s.z_max_mm), *map(cell, s.cone_mm), cell(g), k)
                     for s, g, k in zip(layup.sheets, gaps, pieces))
        return Table("layers", "Sheets (taper-cut)", ("sheet", "z min mm", "z max mm", "cone radius front mm",
                                                      "cone radius back mm", "largest gap to the profile mm",
                                                      "pieces"), rows,
                     caption="each rim is the cone through the lens profile at the sheet's two faces; gap: the "
                     "largest distance from the profile to the cone in the meridional section (no sanding)")
    rows = tuple((s.label, cell(s.z_min_mm), cell(s.z_max_mm), cell(s.radius_mm), cell(e), k)
                 for s, e, k in zip(layup.sheets, excess, pieces))
    return Table("layers", "Sheets", ("sheet", "z min mm", "z max mm", "disc radius mm",
                                      "max excess over the lens mm", "pieces"), rows,
                 caption="excess: the largest foam depth sanding removes in that sheet")



def _profile_plot(lens: Lens, layup: LayupPlan) -> Plot:
    """Upper half-section: the stepped stack (as cut) filled, the lens after sanding filled over it,
    the sheets outlined; what of the stack shows outside the lens is the sanding allowance."""
    r = np.linspace(0.0, lens.radius_mm, 201)
    lens_z = np.concatenate([lens.front_z(r), lens.back_z(r[::-1])])
    lens_r = np.concatenate([r, r[::-1]])
    z = np.array([[s.z_min_mm, s.z_max_mm] for s in layup.sheets]).ravel()
    rad = np.repeat([s.radius_mm for s in layup.sheets], 2)
    step_z = np.concatenate([[z[0]], z, [z[-1]]])
    step_r = np.concatenate([[0.0], rad, [0.0]])
    boxes = np.array([[(s.z_min_mm, 0.0), (s.z_min_mm, s.radius_mm), (s.z_max_mm, s.radius_mm),
                       (s.z_max_mm, 0.0), (np.nan, np.nan)] for s in layup.sheets]).reshape(-1, 2)
    return Plot("profile", "Section: sheets, lens and sanding allowance", "z (mm)", "r (mm)",
                (Series("stepped stack as cut (sanding allowance)", step_z, step_r, "fill"),
                 Series("lens after sanding", lens_z, lens_r, "fill"),
                 Series("sheets", boxes[:, 0], boxes[:, 1], "line")), equal_aspect=True,
                caption=f"{layup.count} sheets of {layup.sheet_thickness_mm:g} mm; the stack outside the lens "
                        "is sanded off")


def _outline(lens: Lens, section: Slabs | Taper | None) -> np.ndarray:
    """Closed outlines of the as-built section, NaN-separated (z, y) rows."""
    if isinstance(section, Taper):
        return section.outline()
    if section is None:
        y = np.linspace(-lens.radius_mm, lens.radius_mm, 201)
        ring = np.concatenate([np.stack([lens.front_z(y), y], -1), np.stack([lens.back_z(y[::-1]), y[::-1]], -1)])
        return np.concatenate([ring, ring[:1], [[np.nan, np.nan]]])
    y_ext = np.concatenate([[-np.inf], section.y_breaks, [np.inf]])
    out = []
    for k, row in enumerate(section.material):
        z0, z1 = section.z_edges[k], section.z_edges[k + 1]
        edges = np.diff(np.concatenate([[0], row.astype(int), [0]]))
        for lo, hi in zip(y_ext[np.nonzero(edges == 1)[0]], y_ext[np.nonzero(edges == -1)[0]]):
            out += [(z0, lo), (z0, hi), (z1, hi), (z1, lo), (z0, lo), (np.nan, np.nan)]
    return np.array(out)


def _fan_plot(lens: Lens, medium: Medium, section: Slabs | Taper | None) -> Plot:
    """About 30 rays from the nominal feed through the as-built lens to the antenna plane."""
    tr, keep = trace_lens(lens, medium, lens.feed, FAN_RAYS)
    start = max(lens.feed[0], float(lens.front_z(0.0)) - 4 * lens.radius_mm)
    lines = []
    for i in np.nonzero(keep)[0]:
        pts = tr.points[:, i]
        pts = pts[np.concatenate([[True], np.linalg.norm(np.diff(pts, axis=0), axis=-1) > 0])]
        d = tr.directions[0, i]
        pts[0] = pts[0] + (start - pts[0, 0]) / d[0] * d
        lines += [pts, [[np.nan, np.nan]]]
    rays = np.concatenate(lines)
    outline = _outline(lens, section)
    return Plot("ray-fan", "Ray fan through the lens as built", "z (mm)", "y (mm)",
                (Series("lens as built", outline[:, 0], outline[:, 1], "line"),
                 Series("rays", rays[:, 0], rays[:, 1], "line")), equal_aspect=True,
                caption=f"feed at z {lens.feed[0]:.1f}, y {lens.feed[1]:.1f} mm; rays drawn from z {start:.0f} mm")
