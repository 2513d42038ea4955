"""The tolerance budget of a lens of revolution: each build tolerance as what it adds to the smooth lens,
root-sum-squared with the stack's own quiet-zone figure (:mod:`antenna_cad.quietzone.tolerance`)."""

from __future__ import annotations

from typing import Callable

import numpy as np

from antenna_cad.asbuilt.lens import Lens, Stats, aperture_stats, as_built_medium, ruze_loss_db, trace_lens
from antenna_cad.asbuilt.taper import Taper
from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.quietzone.tolerance import added_figures, efficiency_loss_db, eps_r_added_deg, residual_deg, \
    thickness_added_deg
from antenna_cad.quietzone.verdict import UNCERTAIN, undecided
from antenna_cad.raytrace.collimator import ApertureTrace
from antenna_cad.raytrace.trace2d import Slabs, transmitted_amplitude
from antenna_cad.spec.common import TolerancesSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.verification import Plot, Series, Table, cell

TOLERANCE_STEPS = (-1.0, -0.5, 0.0, 0.5, 1.0)     # deviations in units of each tolerance


def tolerance_budget(lens: Lens, section: Slabs | Taper | None, tol: TolerancesSpec, layup: LayupPlan | None,
                 own: tuple[float, float] | None = None, added_fab: Callable | None = None,
                 model: Stats | None = None, own_error_deg: float = 0.0):
    """The tolerance budget: εr spread, sheet (or lens) thickness and feed position, each at ± its
    tolerance, as what it adds to the smooth lens (εr and thickness to first order along its rays, the
    feed by retracing it: :mod:`antenna_cad.quietzone.tolerance`), root-sum-squared with the stack's own
    figure ``own`` (its quiet-zone p-p and RMS; the smooth lens's own when None); the gain loss from the
    aperture efficiency of the ideal field against the fabricated one (``added_fab``: its added phase at
    y) with every term at its worse end; "uncertain — run full-wave" when ``own_error_deg`` (the error of
    the model that gave ``own``) cannot decide the budget. Kept for comparison: the old figures, GO through
    the steps with the single-plane ``model`` as nominal and Ruze's loss (``tolerance_single_plane_ruze_*``)."""
    t_ref = layup.sheet_thickness_mm if layup is not None else float(lens.back_z(0.0) - lens.front_z(0.0))
    z_front = layup.sheets[0].z_min_mm if layup is not None else float(lens.front_z(0.0))
    z0, y0 = lens.feed
    smooth = lens.faces(lens.n)
    tr, keep = trace_lens(lens, smooth, lens.feed)
    y, lam = tr.points[-1][keep, 1], lens.wavelength_mm
    base_phase = ApertureTrace.from_trace(tr, lam, keep).phase_deg()

    def feed(s, axial):
        moved_tr, moved_keep = trace_lens(lens, smooth, (z0 + s, y0) if axial else (z0, y0 + s))
        moved = ApertureTrace.from_trace(moved_tr, lam, moved_keep)
        order = np.argsort(moved.y_mm)
        return np.interp(y, moved.y_mm[order], moved.phase_deg()[order]) - base_phase

    thick = "sheet thickness" if layup is not None else "lens thickness"
    as_built = as_built_medium(lens, section, lens.eps_r, 1.0)
    cases = (("εr", tol.eps_r_tolerance, "", lambda s: eps_r_added_deg(tr, keep, lens.n, s, lam),
              lambda s: (as_built_medium(lens, section, lens.eps_r + s, 1.0), lens.feed)),
             (thick, tol.thickness_tolerance_mm, "mm",
              lambda s: thickness_added_deg(tr, keep, len(smooth), z_front, s / t_ref, lam),
              lambda s: (as_built_medium(lens, section, lens.eps_r, 1 + s / t_ref), lens.feed)),
             ("feed axial", tol.feed_position_tolerance_mm, "mm", lambda s: feed(s, True),
              lambda s: (as_built, (z0 + s, y0))),
             ("feed transverse", tol.feed_position_tolerance_mm, "mm", lambda s: feed(s, False),
              lambda s: (as_built, (z0, y0 + s))))
    go_base = aperture_stats(lens, *trace_lens(lens, as_built, lens.feed))
    rows, series, added, go_added, worst = [], [], {}, {}, np.zeros(len(y))
    for name, size, unit, at, go_at in cases:
        figs = {k: added_figures(y, at(k * size)) if k else (0.0, 0.0) for k in TOLERANCE_STEPS}
        series.append(Series(f"{name} ±{size:g} {unit}".strip(), np.array(TOLERANCE_STEPS),
                             np.array([figs[k][0] for k in TOLERANCE_STEPS])))
        end = max((-1.0, 1.0), key=lambda k: figs[k][1])
        worst = worst + residual_deg(y, at(end * size))
        added[name] = tuple(max(figs[k][i] for k in (-1.0, 1.0)) for i in (0, 1))
        go = [aperture_stats(lens, *trace_lens(lens, *go_at(k * size))) for k in (-1.0, 1.0)]
        go_added[name] = tuple(max(0.0, max(getattr(s, k) ** 2 for s in go) - getattr(go_base, k) ** 2)
                               for k in ("p2p_deg", "rms_deg"))
        rows += [(name, f"{sign}{size:g} {unit}".strip(), cell(figs[k][0]), cell(figs[k][1]), cell(g.p2p_deg),
                  cell(g.rms_deg)) for sign, k, g in zip("−+", (-1.0, 1.0), go)]
    own = own or added_figures(y, base_phase)
    p2p = float(np.sqrt(own[0] ** 2 + sum(a[0] ** 2 for a in added.values())))
    rms = float(np.sqrt(own[1] ** 2 + sum(a[1] ** 2 for a in added.values())))
    dominant = max(added, key=lambda k: added[k][1])
    r_order = np.argsort(np.abs(y))
    ideal = (transmitted_amplitude(tr, lam, lens.tan_delta, "perp")[keep] * np.exp(1j * np.radians(
        residual_deg(y, base_phase))))[r_order]
    fab = ideal * np.exp(1j * np.radians(added_fab(y)[r_order] if added_fab is not None else 0.0))
    loss = efficiency_loss_db(np.abs(y)[r_order], ideal, fab * np.exp(1j * np.radians(worst[r_order])))
    nominal = model or go_base
    old_p2p = float(np.sqrt(nominal.p2p_deg ** 2 + sum(a[0] for a in go_added.values())))
    old_rms = float(np.sqrt(nominal.rms_deg ** 2 + sum(a[1] for a in go_added.values())))
    figures = {"tolerance_rss_p2p_deg": p2p, "tolerance_rss_rms_deg": rms, "tolerance_rss_gain_loss_db": loss,
               "stack_own_efficiency_loss_db": efficiency_loss_db(np.abs(y)[r_order], ideal, fab),
               "tolerance_dominant_added_rms_deg": added[dominant][1],
               "tolerance_single_plane_ruze_rss_p2p_deg": old_p2p, "tolerance_single_plane_ruze_rss_rms_deg": old_rms,
               "tolerance_single_plane_ruze_gain_loss_db": ruze_loss_db(old_rms)}
    unsure = undecided(p2p, lens.budget_deg, own_error_deg)
    own_name = "stack's own" if layup is not None else "lens as made"      # a machined or printed lens has no stack
    check = Check("tolerance_budget", "warn" if p2p > lens.budget_deg or unsure else "pass", p2p, lens.budget_deg,
                  "deg", (f"{UNCERTAIN}: " if unsure else "") + f"as built with every tolerance (the {own_name} "
                  f"{own[0]:.1f}° p-p ⊕ each tolerance's change of the smooth lens, RSS): {p2p:.1f}° p-p, "
                  f"{rms:.1f}° RMS vs budget {lens.budget_deg:g}°; dominant: {dominant} (+{added[dominant][1]:.2f}° "
                  f"RMS); gain loss {loss:.3f} dB (aperture efficiency, every tolerance at its worse end); the old "
                  f"GO-through-the-steps figure {old_p2p:.1f}° p-p")
    table = Table("sensitivity", "Phase error each build tolerance adds (nominal feed)",
                  ("tolerance", "deviation", "added p-p deg", "added RMS deg", "old: GO through the steps p-p deg",
                   "old: GO RMS deg"),
                  ((f"{own_name} (quiet zone)", "", cell(own[0]), cell(own[1]), cell(go_base.p2p_deg), cell(go_base.rms_deg)),
                   *rows),
                  caption=f"added: the change of the smooth lens (εr, thickness to first order along its rays; the "
                  f"feed retraced), tilt and piston removed, area-weighted over the disc; dominant: {dominant}; RSS "
                  f"{p2p:.2f}° p-p, {rms:.2f}° RMS. Old (for comparison): GO through the steps, Ruze")
    plot = Plot("sensitivity", "Phase error each build tolerance adds to the smooth lens",
                "deviation (units of the tolerance)", "added p-p phase (deg)", tuple(series),
                hlines=(("budget", lens.budget_deg),))
    return table, plot, figures, check
