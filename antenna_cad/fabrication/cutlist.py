"""Cut list: every piece with its board, position, assembly order, area and mass (CSV)."""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass


@dataclass(frozen=True)
class CutRow:
    part: str              # piece label
    kind: str              # "sheet", "sheet-foot", "sheet-strip", "box-panel"
    material: str
    board: str
    board_x_mm: float
    board_y_mm: float
    rotated: bool
    width_mm: float
    height_mm: float
    thickness_mm: float
    area_m2: float
    mass_kg: float
    assembly_order: int
    note: str


FIELDS = [f for f in CutRow.__dataclass_fields__]


def cutlist_csv(rows: list[CutRow], totals: dict[str, float]) -> str:
    """CSV text with one row per piece, then ``TOTAL`` rows (mass per material and overall)."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(FIELDS)
    for r in rows:
        writer.writerow([_fmt(getattr(r, f)) for f in FIELDS])
    for label, mass in totals.items():
        writer.writerow([f"TOTAL {label}"] + [""] * (FIELDS.index("mass_kg") - 1) + [_fmt(mass), "", ""])
    return buf.getvalue()


def _fmt(value) -> str:
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return f"{value:.3f}" if abs(value) >= 0.01 or value == 0 else f"{value:.6f}"
    return str(value)
