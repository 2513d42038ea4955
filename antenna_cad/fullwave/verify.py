"""The full-wave stage of the as-built check (issue 10) and the phase model the verdicts follow.

:func:`full_wave_study` decides whether Meep runs (``verification.full_wave``: ``on``; ``auto`` when
Meep is installed and the estimated time fits ``budget_s``; ``off``), runs the ideal lens, the stepped
stack as cut and the stack as fabricated with the on-axis feed (in parallel processes, cached), and
returns the manifest figures ``fullwave_<lens>_on_axis_*``, the report plots and the deck folder. Its
:class:`PhaseModel` gives the phase the stack adds to the ideal lens (variant − ideal on the aperture
plane): from Meep when it ran, else from the fast sub-wavelength model
(:mod:`antenna_cad.fullwave.fastmodel`); the stock choice, the sanding check and the tolerance budget
add it to the GO phase of the ideal lens (GO is exact for the smooth lens, DESIGN.md
"Verification models").
"""

from __future__ import annotations

import json
import os
import shlex
from dataclasses import dataclass, field

import numpy as np

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.aperture import aperture_stats, difference_stats, phase_deg, window
from antenna_cad.fullwave.lens import RevolvedLens
from antenna_cad.synthesis.checks import Check, DesignError, Status
from antenna_cad.verification import Plot, Series

FAST = "fast sub-wavelength model (thin screen + scalar diffraction to the aperture plane)"


@dataclass(frozen=True)
class PhaseModel:
    """Phase (deg) each stepped variant adds to the ideal lens at radius ``r_mm`` on the aperture plane,
    sampled over 0.5 λ ≤ r ≤ 0.9 R (held constant beyond: the axial caustic and the rim's edge
    diffraction are the same for every variant and outside the statistics)."""
    name: str
    r_mm: np.ndarray
    added_deg: dict[str, np.ndarray]

    def added(self, variant: str, y_mm: np.ndarray) -> np.ndarray:
        return np.interp(np.abs(y_mm), self.r_mm, self.added_deg[variant])


@dataclass(frozen=True)
class FullWave:
    model: PhaseModel
    figures: dict[str, float] = field(default_factory=dict)
    checks: tuple[Check, ...] = ()
    plots: tuple[Plot, ...] = ()
    files: dict[str, str] = field(default_factory=dict)


def fast_model(lens: RevolvedLens, settings) -> PhaseModel:
    r = np.linspace(0.5 * lens.wavelength_mm, 0.9 * lens.radius_mm, 400)
    return PhaseModel(FAST, r, {v: lens.fast_difference_deg(v, settings.plane_offset_lambda, r) for v in lens.sections})


def on_axis_decks(lens: RevolvedLens, settings) -> list[dict]:
    """The decks of the on-axis feed: the ideal lens, then each stepped section."""
    return [lens.deck(v, settings) for v in ("ideal", *lens.sections)]


def budget_decision(settings, decks: list[dict], jobs: int) -> tuple[str | None, str, float]:
    """(interpreter, why, estimated s): the interpreter when the full-wave stage runs, else None."""
    if settings.full_wave == "off":
        return None, "off in the spec (verification.full_wave)", 0.0
    python = solver.meep_python()
    if python is None:
        if settings.full_wave == "on":
            raise DesignError("verification.full_wave", f"on, but {solver.MISSING}")
        return None, f"skipped: {solver.MISSING}", 0.0
    estimate = solver.estimate_s(decks, jobs)
    if settings.full_wave == "auto" and estimate > settings.budget_s:
        return None, (f"skipped: estimated {estimate:.0f} s > budget_s {settings.budget_s:g} s "
                      "(raise it, or lower resolution_px_per_lambda)"), estimate
    return python, f"ran (estimated {estimate:.0f} s)", estimate


def full_wave_study(lens: RevolvedLens, settings, go: dict[str, tuple[np.ndarray, np.ndarray]]) -> FullWave:
    """The full-wave stage; ``go``: variant → (y, phase deg) of the GO trace at the on-axis feed, drawn
    under the full-wave curves."""
    variants = ["ideal", *lens.sections]
    decks = on_axis_decks(lens, settings)
    jobs = max(1, min(len(decks), os.cpu_count() or 1))
    python, why, estimate = budget_decision(settings, decks, jobs)
    files = deck_files(variants, decks)
    if python is None:
        return FullWave(fast_model(lens, settings), checks=(_note(why, FAST, estimate, settings),), files=files)
    results = dict(zip(variants, solver.run_decks(decks, python, jobs)))
    unique = {o["key"]: o for o in results.values()}          # the stack as fabricated may equal the stack as cut
    lam, R = lens.wavelength_mm, lens.radius_mm
    ideal = results["ideal"]
    r = ideal["r_mm"]
    figures = {}
    for v, out in results.items():
        figures |= {f"fullwave_{v}_on_axis_{k}": val for k, val in vars(aperture_stats(r, out["er"], lam, R)).items()}
    if "stepped" in results:
        p2p, rms = difference_stats(r, results["stepped"]["er"], ideal["er"], lam, R)
        figures |= {"fullwave_stepped_minus_ideal_p2p_deg": p2p, "fullwave_stepped_minus_ideal_rms_deg": rms}
    figures |= {"fullwave_resolution_px_per_lambda": settings.resolution_px_per_lambda,
                "fullwave_seconds": float(sum(float(o["seconds"]) for o in unique.values()))}
    name = f"full-wave (Meep {results['ideal']['meep_version']}, {settings.resolution_px_per_lambda:g} px/λ)"
    sel = window(r, lam, R)
    added = {v: phase_deg(r, results[v]["er"] / ideal["er"], lam, R)[sel] for v in lens.sections}
    model = PhaseModel(name, r[sel], added)
    cached = sum(bool(o["cached"]) for o in unique.values())
    note = _note(f"{why}; {len(unique)} run{'s' * (len(unique) != 1)} ({cached} from the cache; solver {figures['fullwave_seconds']:.0f} s)",
                 name, estimate, settings)
    return FullWave(model, figures, (note,), _plots(lens, results, go, settings), files)


def stage_status(why: str) -> Status:
    """A full-wave stage's check status from :func:`budget_decision`'s reason: pass when it ran, skip
    when it did not (off, no Meep, over budget) — a stage that did not run is never a pass."""
    return "pass" if why.startswith("ran") else "skip"


def _note(why: str, model: str, estimate: float, settings) -> Check:
    """The stage's record: estimated time against budget_s, what ran and which model the verdicts use."""
    return Check("full_wave", stage_status(why), estimate, settings.budget_s, "s",
                 f"full-wave stage {why}; stair-step verdicts from the {model}")


def deck_files(variants: list[str], decks: list[dict]) -> dict[str, str]:
    """``fullwave/`` in the output: each variant's deck and the command that reruns it (finer: edit
    ``resolution_px_per_lambda`` in the deck)."""
    files = {f"fullwave/{v}.json": json.dumps(d, indent=1, sort_keys=True) + "\n" for v, d in zip(variants, decks)}
    lines = ["#!/bin/sh", "# Rerun the full-wave decks with Debian's python3-meep; raise resolution_px_per_lambda in",
             "# a deck for a finer run. Results: <variant>.npz (Er, Ephi on the aperture plane, |E| map).",
             'cd "$(dirname "$0")"', 'PY="${ANTENNA_CAD_MEEP_PYTHON:-/usr/bin/python3}"']
    lines += [f'"$PY" runner.py {shlex.quote(v + ".json")} {shlex.quote(v + ".npz")}' for v in variants]
    files["fullwave/rerun.sh"] = "\n".join(lines) + "\n"
    files["fullwave/runner.py"] = solver.RUNNER.read_text(encoding="utf-8")
    return files


def _plots(lens: RevolvedLens, results: dict, go: dict, settings) -> tuple[Plot, ...]:
    lam, R = lens.wavelength_mm, lens.radius_mm
    phase, amplitude = [], []
    for v, out in results.items():
        r = out["r_mm"]
        sel = (r <= R)
        phase.append(Series(f"full-wave {v}", r[sel], phase_deg(r, out["er"], lam, R)[sel]))
        amp = np.abs(out["er"][sel])
        ref = np.mean(amp[(r[sel] >= 0.5 * lam) & (r[sel] <= 1.5 * lam)])
        amplitude.append(Series(f"full-wave {v}", r[sel], 20 * np.log10(np.maximum(amp / ref, 1e-6))))
    for v, (y, ph) in go.items():
        keep = y >= 0
        w = window(y[keep], lam, R)
        rr, pp = y[keep], ph[keep] - np.average(ph[keep][w], weights=y[keep][w])
        phase.append(Series(f"GO {v}", rr, pp, "dashed"))
    caption = (f"on-axis feed; plane {settings.plane_offset_lambda:g} λ behind the stack; statistics over "
               f"0.5 λ ≤ r ≤ 0.9 R (the axis of a body of revolution carries a caustic)")
    plots = [Plot("fullwave-aperture-phase", "Full-wave aperture phase over GO", "r (mm)", "phase, mean removed (deg)",
                  tuple(phase), caption=caption),
             Plot("fullwave-aperture-amplitude", "Full-wave aperture amplitude", "r (mm)",
                  "|E| relative to 0.5–1.5 λ (dB)", tuple(amplitude), caption=caption)]
    last = list(results)[-1]
    if "map_abs" in results[last]:
        m = results[last]["map_abs"]
        image = 20 * np.log10(np.maximum(m / m.max(), 1e-3))
        plots.append(Plot("fullwave-field-map", f"|E| in the (r, z) plane, {last} lens", "z (mm)", "r (mm)", (),
                          caption="dB relative to the maximum; feed sheet on the left, aperture plane on the right",
                          image=(image, tuple(float(x) for x in results[last]["map_extent_mm"]))))
    return tuple(plots)
