"""What the workers run: plain spec dicts in, plain figures out (no CAD object crosses the wire).

A variant's figures come from *stages*; a stage splits into parts (one task each) and reduces the
parts' results into figures. ``figures`` mode runs ``design`` (synthesis, sheets, fabrication plan:
key figures, masses, boards) and ``asbuilt`` (the kind's as-built verification: ray traces of the
ideal, stepped and fabricated lens, tolerance study) as two tasks; ``build`` mode runs ``build``
(:func:`antenna_cad.pipeline.build` into the variant's own folder). A stage with several parts — the
full-wave check, one run per azimuthal order of an off-axis feed — adds one entry to :data:`STAGES`
and its parts spread over the cluster like any other task.

Every result is ``{"figures": {...}, "checks": {name: status}, "folder": str}`` or ``{"error": str}``:
a failing variant is data, not an exception that would stop the sweep.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

Result = dict


@dataclass(frozen=True)
class Stage:
    name: str
    run: Callable[[dict], Result]                                       # one part's payload → result
    parts: Callable[[dict, str], list[dict]] = lambda spec, out: [{"spec": spec, "out": out}]
    reduce: Callable[[list[Result]], Result] = lambda results: results[0]


def _prepare(spec_doc: dict):
    from antenna_cad.registry import adapter, synthesize
    from antenna_cad.spec import parse_spec
    spec = parse_spec(spec_doc)
    kind = adapter(spec.kind)
    design, checks = synthesize(spec)
    layup, panels = kind.plan(spec, design)
    fab = kind.fabricate(spec, design, layup, panels)
    checks += list(kind.fabrication_checks(spec, design, layup)) + list(fab.checks)
    return spec, kind, design, layup, fab, checks


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")


def fabrication_figures(totals_kg: dict[str, float], boards: dict[str, int]) -> dict:
    """Masses (``mass_kg`` for the whole part, ``mass_<material>_kg``) and stock boards
    (``boards`` in all, ``boards_<material>``) as flat figures."""
    figures = {("mass_kg" if k == "all" else f"mass_{_slug(k)}_kg"): float(v) for k, v in totals_kg.items()}
    figures |= {f"boards_{_slug(k)}": int(v) for k, v in boards.items()}
    return figures | {"boards": int(sum(boards.values()))}


def _plain(figures: dict) -> dict:
    """Numbers as Python floats/ints (numpy scalars become floats), anything else as text."""
    out = {}
    for key, value in figures.items():
        if isinstance(value, (bool, int, str)):
            out[key] = value
        else:
            try:
                out[key] = float(value)
            except (TypeError, ValueError):
                out[key] = str(value)
    return out


def _checks(checks) -> dict[str, str]:
    return {c.name: c.status for c in checks}


def run_design(payload: dict) -> Result:
    spec, kind, design, layup, fab, checks = _prepare(payload["spec"])
    figures = dict(kind.summary(spec, design, layup)) | fabrication_figures(fab.totals_kg, fab.boards)
    return {"figures": _plain(figures), "checks": _checks(checks)}


def run_asbuilt(payload: dict) -> Result:
    spec, kind, design, layup, fab, _ = _prepare(payload["spec"])
    verification = kind.verify(spec, design, layup, fab)
    return {"figures": _plain(verification.figures), "checks": _checks(verification.checks)}


def run_build(payload: dict) -> Result:
    from antenna_cad.pipeline import build
    from antenna_cad.spec import parse_spec
    out = Path(payload["out"])
    out.mkdir(parents=True, exist_ok=True)          # builds/<hash>/: the build checks its parent exists
    result = build(parse_spec(payload["spec"]), out)
    figures = dict(result.figures) | dict(result.verified) | fabrication_figures(result.masses_kg, result.boards)
    return {"figures": _plain(figures), "checks": _checks(result.checks), "folder": str(result.out_dir)}


STAGES: dict[str, Stage] = {s.name: s for s in (
    Stage("design", run_design), Stage("asbuilt", run_asbuilt), Stage("build", run_build))}
MODE_STAGES = {"figures": ("design", "asbuilt"), "build": ("build",)}


def run_part(stage: str, payload: dict) -> Result:
    """One task: a stage's part, its failure caught as the row's message."""
    from antenna_cad.spec import SpecError
    from antenna_cad.synthesis.checks import DesignError
    try:
        return STAGES[stage].run(payload)
    except SpecError as exc:
        return {"error": f"{stage}: {'; '.join(exc.lines)}"}
    except DesignError as exc:
        return {"error": f"{stage}: {exc}"}
    except Exception as exc:            # a failing variant is a row with its message, never the end
        return {"error": f"{stage}: {type(exc).__name__}: {exc}"}


def finish(stages: tuple[str, ...], counts: tuple[int, ...], wanted: tuple[str, ...], *results: Result) -> Result:
    """One task per variant: reduce each stage's parts, merge the stages, keep the wanted figures."""
    figures, checks, folder, offset = {}, {}, "", 0
    for stage, count in zip(stages, counts):
        parts = results[offset:offset + count]
        offset += count
        errors = [r["error"] for r in parts if "error" in r]
        if errors:
            return {"error": errors[0]}
        merged = STAGES[stage].reduce(list(parts))
        figures |= merged["figures"]
        checks |= merged["checks"]
        folder = merged.get("folder", folder)
    missing = [w for w in wanted if w not in figures]
    if missing:
        return {"error": f"figures: {', '.join(missing)} not produced by this kind; it gives "
                         f"{', '.join(sorted(k for k, v in figures.items() if not isinstance(v, str)))}"}
    worst = "fail" if "fail" in checks.values() else ("warn" if "warn" in checks.values() else "pass")
    return {"figures": {w: figures[w] for w in wanted}, "checks": worst,
            "check_issues": " ".join(sorted(k for k, v in checks.items() if v in ("fail", "warn"))), "folder": folder}
