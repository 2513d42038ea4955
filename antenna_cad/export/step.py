"""STEP assembly writer: one labelled product per part, millimetres, fixed timestamp."""

from __future__ import annotations

import re
from pathlib import Path

from build123d import Compound, Unit, export_step

from antenna_cad.geometry.model import Model

STEP_TIMESTAMP = "2000-01-01T00:00:00"     # reproducible bytes: same spec → same file


def write_step(model: Model, name: str, path: Path) -> None:
    """Assembly ``name`` with sub-assemblies ``fabricated`` and ``reference``; parts keep labels."""
    groups = []
    for role in ("fabricated", "reference"):
        children = []
        for part in sorted((p for p in model.parts if p.role == role), key=lambda p: p.label):
            children.append(_labelled(part.label, part.shape.solids()))
        if children:
            groups.append(Compound(children=children, label=role))
    if not export_step(Compound(children=groups, label=name), str(path), unit=Unit.MM,
                       timestamp=STEP_TIMESTAMP, write_pcurves=model.step_pcurves):
        raise RuntimeError(f"STEP export failed: {path}")
    path.write_text(snap_near_zero(_renumber_occurrences(path.read_text())))


def _labelled(label: str, solids) -> Compound:
    """A fresh wrapper (labels never leak onto the model's shapes). A part of several solids gets
    one child per solid, ``label.1``, ``label.2``, …: OCCT-7 readers (gmsh) name a solid only when
    its own label holds it, and otherwise guess by bounding box (a sheet took its sanding ring's name)."""
    if len(solids) == 1:
        return Compound(solids, label=label)
    return Compound(children=[Compound([s], label=f"{label}.{i}") for i, s in enumerate(solids, 1)],
                    label=label)


_TINY = re.compile(r"(?<![\w.])-?\d\.\d*E-(?:[1-9]\d\d|[1-9]\d)\b")    # |x| < 1e-9 (exponent ≤ −10)
_NEGATIVE_ZERO = re.compile(r"(?<![\w.])-0\.(?![\dE])")


def snap_near_zero(text: str) -> str:
    """Reals below 1e-9 (mm, or direction components) written as 0. and −0. as 0.: OCCT's
    parallel booleans leave ±3e-30 or exactly 0 on the same point from run to run, which made
    the STEP (and the STLs) of the same spec differ between builds."""
    return _NEGATIVE_ZERO.sub("0.", _TINY.sub("0.", text))


_NAUO = re.compile(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('\d+',(.*?)\);", re.DOTALL)


def _renumber_occurrences(text: str) -> str:
    """OCC numbers assembly occurrences with a process-wide counter, so a second export in the
    same process differs; renumber them 1, 2, … in file order (entity kept on one line)."""
    counter = iter(range(1, 1_000_000))
    return _NAUO.sub(lambda m: "NEXT_ASSEMBLY_USAGE_OCCURRENCE('%d',%s);"
                     % (next(counter), re.sub(r"\s*\n\s*", "", m.group(1))), text)
