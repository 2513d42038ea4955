"""What the verify stage returns (DESIGN.md "The flow": verify ──▶ Verification).

Every design kind's adapter has ``verify(spec, design, layup, fab) -> Verification``: ray traces
of the ideal and the as-built geometry reduced to figures, checks, tables and plot data. The
values here are plain numbers and arrays, so physics code never imports matplotlib; the report
(``export/report.py``) draws them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from antenna_cad.synthesis.checks import Check


@dataclass(frozen=True)
class Series:
    """One curve of a plot. ``style``: ``line``, ``dashed``, ``points``, ``steps`` or ``fill``
    (filled between the curve and y = 0). NaN in x/y breaks a line (ray fans, many segments)."""
    label: str
    x: np.ndarray
    y: np.ndarray
    style: Literal["line", "dashed", "points", "steps", "fill"] = "line"


@dataclass(frozen=True)
class Plot:
    name: str                  # file-safe id, e.g. "aperture-phase"
    title: str
    x_label: str
    y_label: str
    series: tuple[Series, ...]
    caption: str = ""
    equal_aspect: bool = False      # profiles and ray fans: 1 mm in x = 1 mm in y
    hlines: tuple[tuple[str, float], ...] = ()     # labelled horizontal limits (budgets)
    image: tuple[np.ndarray, tuple[float, float, float, float]] | None = None   # (dB[r, z], (r0, r1, z0, z1)) map


@dataclass(frozen=True)
class Table:
    name: str
    title: str
    columns: tuple[str, ...]
    rows: tuple[tuple, ...]
    caption: str = ""


@dataclass(frozen=True)
class Verification:
    """As-built figures and tables (the manifest's ``verification`` block), checks that join the
    build's checks, and plots for the report."""
    figures: dict[str, float] = field(default_factory=dict)
    checks: tuple[Check, ...] = ()
    tables: tuple[Table, ...] = ()
    plots: tuple[Plot, ...] = ()
    files: dict[str, str] = field(default_factory=dict)    # output path → text (the full-wave deck)

    def merged(self, other: "Verification") -> "Verification":
        """This verification with ``other``'s figures, checks, tables, plots and files added."""
        return Verification(self.figures | other.figures, self.checks + other.checks, self.tables + other.tables,
                            self.plots + other.plots, self.files | other.files)


def finite_figures(figures: dict) -> dict[str, float]:
    """``figures`` as plain floats, undefined ones (NaN: e.g. no sidelobe within ±90°) left out."""
    return {k: float(v) for k, v in figures.items() if np.isfinite(v)}


def cell(v: float, nd: int = 3) -> float | None:
    """A figure rounded for a table cell: ``nd`` decimals, None when not finite, never "-0"."""
    return round(float(v), nd) + 0.0 if np.isfinite(v) else None


def detrended(y: np.ndarray, phase_deg: np.ndarray) -> np.ndarray:
    """Aperture phase with the least-squares linear tilt removed (seed-000 §4.1, (2.16))."""
    return phase_deg - np.polyval(np.polyfit(y, phase_deg, 1), y)
