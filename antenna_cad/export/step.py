"""STEP assembly writer: one labelled product per part, millimetres, fixed timestamp."""

from __future__ import annotations

from pathlib import Path

from build123d import Color, Compound, Unit, export_step

from antenna_cad.geometry.model import Model

STEP_TIMESTAMP = "2000-01-01T00:00:00"     # reproducible bytes: same spec → same file
_COLORS = {"fabricated": (0.75, 0.85, 0.95), "reference": (0.95, 0.75, 0.55)}


def write_step(model: Model, name: str, path: Path) -> None:
    """Assembly ``name`` with sub-assemblies ``fabricated`` and ``reference``; parts keep labels."""
    groups = []
    for role in ("fabricated", "reference"):
        children = []
        for part in sorted((p for p in model.parts if p.role == role), key=lambda p: p.label):
            shape = Compound(part.shape.solids())    # a fresh wrapper, so labels never leak
            shape.label = part.label
            shape.color = Color(*_COLORS[role])
            children.append(shape)
        if children:
            groups.append(Compound(children=children, label=role))
    if not export_step(Compound(children=groups, label=name), str(path), unit=Unit.MM,
                       timestamp=STEP_TIMESTAMP, write_pcurves=model.step_pcurves):
        raise RuntimeError(f"STEP export failed: {path}")
