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
            shape = Compound(part.shape.solids())    # a fresh wrapper, so labels never leak
            shape.label = part.label
            children.append(shape)
        if children:
            groups.append(Compound(children=children, label=role))
    if not export_step(Compound(children=groups, label=name), str(path), unit=Unit.MM,
                       timestamp=STEP_TIMESTAMP, write_pcurves=model.step_pcurves):
        raise RuntimeError(f"STEP export failed: {path}")
    _renumber_occurrences(path)


_NAUO = re.compile(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('\d+',(.*?)\);", re.DOTALL)


def _renumber_occurrences(path: Path) -> None:
    """OCC numbers assembly occurrences with a process-wide counter, so a second export in the
    same process differs; renumber them 1, 2, … in file order (entity kept on one line)."""
    counter = iter(range(1, 1_000_000))
    text = _NAUO.sub(lambda m: "NEXT_ASSEMBLY_USAGE_OCCURRENCE('%d',%s);"
                     % (next(counter), re.sub(r"\s*\n\s*", "", m.group(1))), path.read_text())
    path.write_text(text)
