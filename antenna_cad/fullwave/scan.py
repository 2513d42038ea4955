"""The scan-edge feed's full-wave stage: the ideal lens and the lens as built, lit by the feed
displaced to the edge of the scan range, as a sum over azimuthal orders (:mod:`.offaxis`; one Meep run
per order, in parallel processes, cached per deck).

:func:`plan_scan_edge` makes the decks and decides before anything runs: ``on`` runs it; ``auto`` runs it
only when the estimate of every run still to do (the on-axis ones and all orders of the scan edge) fits
``budget_s``, otherwise its check says why (estimated seconds vs budget). The runs share the build's
budget with the on-axis ones and stop at it; a cut scan edge reports no figures and says so. :func:`scan_edge_study` rebuilds
the co-polar aperture field on the plane behind the lens, removes the beam's tilt and reports
``fullwave_<lens>_scan_edge_{p2p_deg,rms_deg,beam_deg,phase_efficiency_db}`` beside GO's for the
same feed, a table and the scan-plane and orthogonal cuts of the phase over GO's.
"""

from __future__ import annotations

import json
import os
import shlex
from dataclasses import dataclass, replace

import numpy as np

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.lens import RevolvedLens
from antenna_cad.fullwave.offaxis import OrderChoice, aperture_copolar, order_decks, order_fields, tilt_removed, \
    tilted_stats
from antenna_cad.fullwave.verify import Decision, budget_decision, on_axis_decks, run_named
from antenna_cad.synthesis.checks import Check
from antenna_cad.verification import Plot, Series, Table, Verification

GRID_PER_LAMBDA = 8          # aperture samples per λ for the statistics (uniform: equal area weights)
CUT_POINTS = 401


@dataclass(frozen=True)
class ScanEdgePlan:
    lens: RevolvedLens
    feed_y_mm: float
    variants: tuple[str, ...]                 # ideal and the lens as built
    decks: dict[str, list[dict]]              # variant → one deck per order run
    choices: dict[str, OrderChoice]
    decision: Decision                        # its interpreter when it runs, why, the budget
    plane_offset_lambda: float

    @property
    def python(self) -> str | None:
        return self.decision.python


def plan_scan_edge(lens: RevolvedLens, settings, feed_y_mm: float,
                   volume_z_mm: tuple[float, float] | None = None) -> ScanEdgePlan:
    """Decks of the scan-edge feed (at transverse displacement ``feed_y_mm``) for the ideal lens and the
    lens as built (its last section: as fabricated, else as cut), and whether they run, within the
    budget left by the on-axis runs (which record the quiet zone's depth ``volume_z_mm``)."""
    variants = ("ideal", *list(lens.sections)[-1:])
    decks, choices = {}, {}
    if settings.full_wave != "off" and solver.meep_python() is not None:
        for v in variants:
            decks[v], choices[v] = order_decks(lens.deck(v, settings, field_map=False), feed_y_mm)
    every = on_axis_decks(lens, settings, volume_z_mm) + [d for v in variants for d in decks.get(v, [])]
    jobs = os.cpu_count() or 1
    decision = budget_decision(settings, every, jobs)
    if decision.python is not None:
        decision = replace(decision, why=decision.why.replace("ran (", "ran (on-axis and scan-edge runs "))
    return ScanEdgePlan(lens, feed_y_mm, variants, decks, choices, decision, settings.plane_offset_lambda)


def _check(plan: ScanEdgePlan, detail: str = "", status: str | None = None) -> Check:
    d = plan.decision
    text = f"full-wave scan-edge feed (y {plan.feed_y_mm:.1f} mm) {d.why}"
    if plan.choices:
        orders = max(len(c.orders) for c in plan.choices.values())
        text += (f": {orders} azimuthal orders, {sum(len(d) for d in plan.decks.values())} Meep runs over "
                 f"{len(plan.variants)} lenses{detail}")
    return Check("full_wave_scan_edge", status or d.status, d.estimate_s, d.budget.seconds, "s", text)


def scan_edge_study(plan: ScanEdgePlan, go: dict[str, tuple[np.ndarray, np.ndarray, float, float]]) -> Verification:
    """Run the plan (when it runs) and report. ``go``: variant → (y, phase deg with the tilt removed,
    beam deg, phase efficiency dB) of the GO trace at the same feed."""
    if plan.python is None:
        return Verification(checks=(_check(plan),))
    lens = plan.lens
    flat = [d for v in plan.variants for d in plan.decks[v]]
    names = [f"{v} m={d['m']}" for v in plan.variants for d in plan.decks[v]]
    ran = run_named(names, flat, plan.decision, max(1, min(len(flat), os.cpu_count() or 1)), "scan-edge run")
    if ran.cut:                                   # the aperture field needs every order
        return Verification(ran.figures("fullwave_scan_edge"),
                            (_check(plan, f"; {ran.text()}; no scan-edge figures (they need every order)",
                                    ran.status),))
    results = list(ran.results.values())
    dz = plan.decks["ideal"][0]["plane_z_mm"] - lens.feed_z_mm
    guess = -plan.feed_y_mm / np.hypot(plan.feed_y_mm, dz)
    figures, rows, series, start = {}, [], [], 0
    for v in plan.variants:
        chunk = results[start:start + len(plan.decks[v])]
        start += len(chunk)
        f, t, s = _variant_report(v, chunk[0]["r_mm"], order_fields(plan.choices[v], chunk), lens, guess, go.get(v))
        figures, rows, series = figures | f, rows + t, series + s
    worst = max(plan.choices.values(), key=lambda c: c.sheet_error)
    figures |= ran.figures("fullwave_scan_edge")
    figures |= {"fullwave_scan_edge_feed_y_mm": plan.feed_y_mm, "fullwave_scan_edge_orders": float(len(worst.orders)),
                "fullwave_scan_edge_runs": float(ran.runs), "fullwave_scan_edge_sheet_error": worst.sheet_error,
                "fullwave_scan_edge_sheet_power_fraction": worst.power_fraction}
    detail = (f" |m| ≤ {max(worst.orders)} rebuild the sheet's co-polar field to {worst.sheet_error:.1e} "
              f"({100 * worst.power_fraction:.4f} % of its power)"
              + (f", order −m from m by mirror symmetry (residual {worst.symmetry_residual:.0e})"
                 if worst.mirror else "")
              + f"; {ran.text()}")
    check = _check(plan, ";" + detail)
    caption = (f"feed displaced {plan.feed_y_mm:.1f} mm along y (E along x: H-plane scan); co-polar phase on the "
               f"plane {plan.plane_offset_lambda:g} λ behind the lens (GO: on the antenna plane), best-fit tilt "
               "(the beam squint) removed; statistics "
               "over 0.5 λ ≤ ρ ≤ 0.9 R of the 2-D aperture")
    table = Table("fullwave-scan-edge", "Scan-edge feed: full-wave against GO",
                  ("lens", "model", "p-p deg", "RMS deg", "beam deg", "phase efficiency dB"), tuple(rows), caption)
    plot = Plot("fullwave-scan-edge-phase", "Scan-edge aperture phase: full-wave over GO", "position on the cut (mm)",
                "phase, tilt removed (deg)", tuple(series), caption=caption)
    return Verification(figures, (check,), (table,), (plot,), deck_files(plan))


def _variant_report(v: str, r: np.ndarray, fields: dict, lens: RevolvedLens, guess: float, go) -> tuple:
    """(figures, table rows, plot series) of one lens at the scan edge: the 2-D aperture statistics, the
    scan-plane and orthogonal cuts with the same tilt removed, and GO's meridional cut beside them."""
    lam, R = lens.wavelength_mm, lens.radius_mm
    g = np.arange(-0.9 * R, 0.9 * R + lam / GRID_PER_LAMBDA / 2, lam / GRID_PER_LAMBDA)
    x, y = (a.ravel() for a in np.meshgrid(g, g))
    disc = (np.hypot(x, y) >= 0.5 * lam) & (np.hypot(x, y) <= 0.9 * R)
    x, y = x[disc], y[disc]
    st = tilted_stats(aperture_copolar(r, fields, x, y), x, y, lam, guess)
    figures = {f"fullwave_{v}_scan_edge_{k}": val for k, val in vars(st).items() if k != "k_xy"}
    rows = [(v, "full-wave (2-D aperture)", *(round(float(a), 3) for a in (st.p2p_deg, st.rms_deg, st.beam_deg,
                                                                          st.phase_efficiency_db)))]
    cut = np.linspace(-R, R, CUT_POINTS)
    scan, orthogonal = (tilt_removed(aperture_copolar(r, fields, cx, cy), cx, cy, st.k_xy)
                        for cx, cy in ((0 * cut, cut), (cut, 0 * cut)))
    series = [Series(f"full-wave {v}, scan plane", cut, scan), Series(f"full-wave {v}, orthogonal cut", cut,
                                                                      orthogonal, "points")]
    ph = scan[(np.abs(cut) >= 0.5 * lam) & (np.abs(cut) <= 0.9 * R)]     # as GO's meridional cut
    rows.append((v, "full-wave (scan-plane cut)", round(float(np.ptp(ph)), 3), round(float(np.std(ph)), 3), "", ""))
    if go is not None:
        gy, gph, beam, eff = go
        figures |= {f"go_{v}_scan_edge_beam_deg": beam, f"go_{v}_scan_edge_phase_efficiency_db": eff}
        rows.append((v, "GO (meridional cut)", round(float(np.ptp(gph)), 3), round(float(np.std(gph)), 3),
                     round(beam, 3), round(eff, 3)))
        series.append(Series(f"GO {v}", gy, gph - np.mean(gph), "dashed"))
    return figures, rows, series


def deck_files(plan: ScanEdgePlan) -> dict[str, str]:
    """When it ran: ``fullwave/scan-edge/<lens>-m<m>.json``, one deck per order run, and ``rerun-scan-edge.sh`` (the
    orders −m are the mirror images of m: see :mod:`antenna_cad.fullwave.offaxis`)."""
    files, lines = {}, ["#!/bin/sh", "# Rerun the scan-edge feed's azimuthal orders (one deck per order m >= 0)",
                        "# with Debian's python3-meep; results <lens>-m<m>.npz (Er, Ephi of that order on the",
                        "# aperture plane).",
                        'cd "$(dirname "$0")/scan-edge"', 'PY="${ANTENNA_CAD_MEEP_PYTHON:-/usr/bin/python3}"']
    for v, decks in plan.decks.items():
        for d in decks:
            name = f"{v}-m{d['m']}"
            files[f"fullwave/scan-edge/{name}.json"] = json.dumps(d, sort_keys=True) + "\n"
            lines.append(f'"$PY" ../runner.py {shlex.quote(name + ".json")} {shlex.quote(name + ".npz")}')
    if files:
        files["fullwave/rerun-scan-edge.sh"] = "\n".join(lines) + "\n"
    return files
