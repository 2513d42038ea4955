"""The full-wave stage of the as-built check and the phase model the verdicts follow.

:func:`full_wave_study` decides whether Meep runs (``verification.full_wave``: ``on``; ``auto`` when
Meep is installed and the estimate at the measured throughput fits ``budget_s``; ``off``), runs the
ideal lens, the stepped stack as cut and the stack as fabricated with the on-axis feed (in parallel
processes, cached, stopped at ``budget_s``: what did not finish keeps the fast model), and returns the manifest figures ``fullwave_<lens>_on_axis_*``, the report plots and the deck folder. Its
:class:`PhaseModel` gives the phase the stack adds to the ideal lens (variant − ideal on the aperture
plane): from Meep when it ran, else from the fast sub-wavelength model
(:mod:`antenna_cad.fullwave.fastmodel`); the stock choice, the sanding check and the tolerance budget
add it to the GO phase of the ideal lens (GO is exact for the smooth lens, DESIGN.md
"Verification models"). Given the quiet zone's depth, each run also records the field over it
(:class:`FullWave` ``volume``), from which the quiet-zone figures and the sanding verdict are taken.
"""

from __future__ import annotations

import json
import os
import shlex
import time
from dataclasses import dataclass, field

import numpy as np

from antenna_cad.fullwave import solver
from antenna_cad.fullwave.aperture import aperture_stats, difference_stats, phase_deg, window
from antenna_cad.fullwave.budget import Budget, budget_for
from antenna_cad.fullwave.lens import RevolvedLens
from antenna_cad.fullwave.volume import VolumeField
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
    volume: dict[str, VolumeField] = field(default_factory=dict)   # variant → its field over the quiet zone
    volume_model: str = ""                                         # the model (and run) that gave it


def fast_model(lens: RevolvedLens, settings) -> PhaseModel:
    r = np.linspace(0.5 * lens.wavelength_mm, 0.9 * lens.radius_mm, 400)
    return PhaseModel(FAST, r, {v: lens.fast_difference_deg(v, settings.plane_offset_lambda, r) for v in lens.sections})


def on_axis_decks(lens: RevolvedLens, settings, volume_z_mm: tuple[float, float] | None = None) -> list[dict]:
    """The decks of the on-axis feed: the ideal lens, then each stepped section (``volume_z_mm``: each
    also records the field over the quiet zone's depth)."""
    return [lens.deck(v, settings, volume_z_mm=volume_z_mm) for v in ("ideal", *lens.sections)]


@dataclass(frozen=True)
class Decision:
    """Whether a stage runs Meep: the interpreter (None: it does not), why, the estimate, the budget
    it runs within, and the check status of a stage that does not run: skip (its own status, never a
    pass; the message says why and which model the verdicts follow). Runs cut at the budget warn."""
    python: str | None
    why: str
    estimate_s: float
    budget: Budget
    status: str = "pass"


def budget_decision(settings, decks: list[dict], jobs: int) -> Decision:
    """Run when ``on``, or ``auto`` with Meep and the estimate (at the throughput measured on this
    machine, a probe run first when none is known) within what is left of ``budget_s``; either way
    the runs stop at the budget (:func:`run_named`)."""
    within = budget_for(settings)
    if settings.full_wave == "off":
        return Decision(None, "not run: off in the spec (verification.full_wave)", 0.0, within, "skip")
    python = solver.meep_python()
    if python is None:
        if settings.full_wave == "on":
            raise DesignError("verification.full_wave", f"on, but {solver.MISSING}")
        return Decision(None, f"skipped: {solver.MISSING}", 0.0, within, "skip")
    if solver.estimate_s(decks, jobs) > 0.0:
        solver.calibrate(python, within)
    estimate, left = solver.estimate_s(decks, jobs), within.left()
    if settings.full_wave == "auto" and estimate > left:
        spent = f"the {left:.0f} s left of " if left < settings.budget_s else ""
        return Decision(None, f"skipped: estimated {estimate:.0f} s > {spent}budget_s {settings.budget_s:g} s (raise "
                        "it, or lower resolution_px_per_lambda)", estimate, within, "skip")
    return Decision(python, f"ran (estimated {estimate:.0f} s, at most budget_s {settings.budget_s:g} s)",
                    estimate, within)


@dataclass(frozen=True)
class Ran:
    """The runs of one stage: results by name (None: cut by the budget), seconds spent in this build,
    the solver seconds of the results read from the cache."""
    results: dict[str, dict | None]
    seconds: float
    cached_seconds: float
    runs: int
    cached: int
    cut: tuple[str, ...]                  # the names whose run did not finish
    cut_runs: int                         # the runs (identical decks run once)
    budget_s: float

    def figures(self, prefix: str = "fullwave") -> dict[str, float]:
        return {f"{prefix}_seconds": self.seconds, f"{prefix}_cached_solver_seconds": self.cached_seconds,
                f"{prefix}_runs_cut": float(self.cut_runs)}

    def text(self) -> str:
        done = self.runs - self.cut_runs
        saved = f"{self.cached} from the cache, their solver {self.cached_seconds:.0f} s; " if self.cached else ""
        text = f"{done} of {self.runs} runs ({saved}{self.seconds:.0f} s in this build)"
        if self.cut:
            text += f"; cut at budget_s {self.budget_s:g} s: {', '.join(self.cut)} did not finish"
        return text

    @property
    def status(self) -> str:
        return "warn" if self.cut else "pass"


def run_named(names: list[str], decks: list[dict], decision: Decision, jobs: int, what: str = "run") -> Ran:
    """Run the decks (by name) within the decision's budget."""
    t0 = time.monotonic()
    out = solver.run_decks(decks, decision.python, jobs, decision.budget, what)
    spent = time.monotonic() - t0
    unique = {o["key"]: o for o in out if o is not None}
    keys = [solver.deck_key(d) for d in decks]
    cached = [o for o in unique.values() if o["cached"]]
    cut = [(n, k) for n, k, o in zip(names, keys, out) if o is None]
    return Ran(dict(zip(names, out)), spent, float(sum(float(o["seconds"]) for o in cached)), len(set(keys)),
               len(cached), tuple(n for n, _ in cut), len({k for _, k in cut}), decision.budget.seconds)


def full_wave_study(lens: RevolvedLens, settings, go: dict[str, tuple[np.ndarray, np.ndarray]],
                    volume_z_mm: tuple[float, float] | None = None) -> FullWave:
    """The full-wave stage; ``go``: variant → (y, phase deg) of the GO trace at the on-axis feed, drawn
    under the full-wave curves; ``volume_z_mm``: the quiet zone's depth, whose field each run records
    (:class:`FullWave` ``volume``). Variants the budget cut keep the fast model."""
    variants = ["ideal", *lens.sections]
    decks = on_axis_decks(lens, settings, volume_z_mm)
    jobs = max(1, min(len(decks), os.cpu_count() or 1))
    decision = budget_decision(settings, decks, jobs)
    files = deck_files(variants, decks)
    fast = fast_model(lens, settings)
    if decision.python is None:
        return FullWave(fast, checks=(_note(decision.why, FAST, decision, decision.status),), files=files)
    ran = run_named(variants, decks, decision, jobs, "on-axis run")
    results = {v: o for v, o in ran.results.items() if o is not None}
    lam, R = lens.wavelength_mm, lens.radius_mm
    figures = {}
    for v, out in results.items():
        figures |= {f"fullwave_{v}_on_axis_{k}": val
                    for k, val in vars(aperture_stats(out["r_mm"], out["er"], lam, R)).items()}
    if "stepped" in results and "ideal" in results:
        p2p, rms = difference_stats(results["ideal"]["r_mm"], results["stepped"]["er"], results["ideal"]["er"], lam, R)
        figures |= {"fullwave_stepped_minus_ideal_p2p_deg": p2p, "fullwave_stepped_minus_ideal_rms_deg": rms}
    figures |= {"fullwave_resolution_px_per_lambda": settings.resolution_px_per_lambda} | ran.figures()
    model = fast
    if "ideal" in results and len(results) > 1:
        ideal = results["ideal"]
        r = ideal["r_mm"]
        sel = window(r, lam, R)
        meep = f"full-wave (Meep {ideal['meep_version']}, {settings.resolution_px_per_lambda:g} px/λ)"
        added = {v: (phase_deg(r, results[v]["er"] / ideal["er"], lam, R)[sel] if v in results
                     else np.interp(r[sel], fast.r_mm, fast.added_deg[v])) for v in lens.sections}
        kept = [v for v in lens.sections if v not in results]
        name = meep + (f"; the {FAST} for {', '.join(kept)} (cut by the budget)" if kept else "")
        model = PhaseModel(name, r[sel], added)
    elif ran.cut:
        model = PhaseModel(f"{FAST} (the full-wave runs were cut by the budget)", fast.r_mm, fast.added_deg)
    note = _note(f"{decision.why}; {ran.text()}", model.name, decision, ran.status)
    volume = {v: VolumeField.from_run(o) for v, o in results.items() if "volume_er" in o}
    meep = (f"full-wave (Meep {next(iter(results.values()))['meep_version']}, "
            f"{settings.resolution_px_per_lambda:g} px/λ, one run per lens over the zone's depth)") if results else ""
    return FullWave(model, figures, (note,), _plots(lens, results, go, settings) if results else (), files,
                    volume, meep)


def _note(why: str, model: str, decision: Decision, status: str) -> Check:
    """The stage's record: estimated time against budget_s, what ran and which model the verdicts use."""
    return Check("full_wave", status, decision.estimate_s, decision.budget.seconds, "s",
                 f"full-wave stage {why}; stair-step verdicts from the {model}")


def deck_files(variants: list[str], decks: list[dict]) -> dict[str, str]:
    """``fullwave/`` in the output: each variant's deck and the command that reruns it (finer: edit
    ``resolution_px_per_lambda`` in the deck)."""
    files = {f"fullwave/{v}.json": json.dumps(d, indent=1, sort_keys=True) + "\n" for v, d in zip(variants, decks)}
    lines = ["#!/bin/sh", "# Rerun the full-wave decks with Debian's python3-meep; raise resolution_px_per_lambda in",
             "# a deck for a finer run. Results: <variant>.npz (Er, Ephi on the aperture plane, |E| map; Er over",
             "# the quiet zone's depth, volume_z_mm).",
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
