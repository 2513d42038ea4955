"""How a build's results are shown to people — one set of rules for report.html, report.pdf and the
terminal summary: figure names and units read from the keys' unit suffixes (DESIGN.md "Units in
names"), values rounded to the figure's resolution (noise below it shown as 0), check statuses
with ``skip`` as its own, never-green status, and the verdicts a design review opens with.

Plain Python (no HTML): the HTML and the console render what these functions return.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

# unit suffix of a key -> (unit shown, resolution): longest suffix first
UNITS = (
    ("_px_per_lambda", "px/λ", 0.1), ("_mm3", "mm³", 1.0), ("_mm2", "mm²", 0.01), ("_mm", "mm", 0.01),
    ("_deg", "°", 0.01), ("_dbi", "dBi", 0.01), ("_db", "dB", 0.01), ("_kg", "kg", 0.001),
    ("_ghz", "GHz", 0.001), ("_seconds", "s", 0.1), ("_s", "s", 0.1), ("_lambda", "λ", 0.01),
    ("_pct", "%", 0.1), ("_percent", "%", 0.1), ("_rad", "rad", 1e-4), ("_m", "m", 1e-4),
)
SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
SIGNIFICANT = 4
WORDS = {"p2p": "peak-to-peak", "pp": "peak-to-peak", "rss": "RSS", "rms": "RMS", "fullwave": "full-wave", "epsr": "εr", "tir": "TIR", "go": "GO", "aut": "AUT", "sll": "side-lobe level", "hpbw": "half-power beam width",
         "te30": "TE30", "qz": "quiet zone", "dof": "depth of field", "vs": "vs", "tan": "tan", "delta": "δ",
         "lambda": "λ", "num": "number of", "max": "largest", "min": "smallest"}
NAMES = {   # figures whose key alone would read badly
    "thickness_mm": "lens thickness", "diameter_mm": "diameter", "focal_length_mm": "focal length",
    "eps_r": "εr", "tan_delta": "tanδ", "d_over_lambda": "D/λ", "mass_kg": "mass", "fullwave_seconds": "full-wave solver time",
}

STATUS_ORDER = ("fail", "warn", "skip", "pass")          # most urgent first
STATUS_LABEL = {"fail": "fail", "warn": "warning", "skip": "skipped", "pass": "pass",
                "info": ""}                            # info: a verdict that is an instruction (what to buy)
STATUS_COLOUR = {"fail": "red", "warn": "yellow", "skip": "blue", "pass": "green"}   # rich colour names


def split_key(key: str) -> tuple[str, str, float | None]:
    """(stem, unit, resolution) of a figure key or a column heading: ``ideal_on_axis_gain_loss_db`` →
    ("ideal_on_axis_gain_loss", "dB", 0.01), ``"P-p deg"`` → ("P-p", "°", 0.01); no unit: resolution None."""
    low = key.lower()
    if "_over_" in low:                                # a ratio (d_over_lambda): no unit
        return key, "", None
    for suffix, unit, resolution in UNITS:
        for tail in (suffix, " " + suffix[1:]):
            if low.endswith(tail) and len(key) > len(tail):
                return key[:-len(tail)], unit, resolution
    return key, "", None


def figure_name(key: str) -> str:
    """A figure key in words, units off, known abbreviations spelled (``eps_r`` → εr)."""
    stem, unit, _ = split_key(key)
    if key in NAMES or stem in NAMES:
        text = NAMES.get(key) or NAMES[stem]
    else:
        stem = re.sub(r"^n_", "number of_", re.sub(r"(?<![a-z])eps_r(?![a-z])", "epsr", stem))
        text = " ".join(WORDS.get(w, w) for w in stem.split("_"))
    return text[:1].upper() + text[1:] if text[:1].isascii() else text


def format_number(value, resolution: float | None = None) -> str:
    """``value`` to at most :data:`SIGNIFICANT` significant digits and never finer than ``resolution``;
    below half the resolution it is 0 (numerical noise); thousands grouped by a thin space. Without a
    resolution (a ratio, a count) small values keep their significant digits: ``2.5 × 10⁻⁵``."""
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return f"{value:,}".replace(",", "\u202f")
    if not isinstance(value, float):
        return str(value)
    if not math.isfinite(value):
        return "—" if math.isnan(value) else ("∞" if value > 0 else "−∞")
    if value == 0 or resolution is not None and abs(value) < resolution / 2:
        return "0"
    magnitude = math.floor(math.log10(abs(value)))
    if resolution is None:
        if magnitude < -3:
            mantissa = f"{value / 10 ** magnitude:.{SIGNIFICANT - 2}g}".replace("-", "−")
            return f"{mantissa} × 10{str(magnitude).translate(SUPERSCRIPT)}"
        resolution = 10.0 ** (magnitude + 1 - SIGNIFICANT)
    decimals = max(0, min(-math.floor(math.log10(resolution)), SIGNIFICANT - 1 - magnitude))
    if magnitude >= SIGNIFICANT:                     # 123456.7 → 123500
        value = round(value, SIGNIFICANT - 1 - magnitude)
    text = f"{value:,.{decimals}f}"
    return text.replace(",", "\u202f").replace("-", "−")


def figure_value(key: str, value) -> str:
    """``value`` of figure ``key`` rounded to its resolution, with its unit (``"3.2 mm"``, ``"0 dB"``)."""
    _, unit, resolution = split_key(key)
    text = format_number(value, resolution)
    if "." in text and "×" not in text:            # a figure alone: no trailing zeros
        text = text.rstrip("0").rstrip(".")
    if not unit or text in ("—", "yes", "no"):
        return text
    return f"{text}{unit}" if unit == "°" else f"{text} {unit}"


def column_label(key: str) -> str:
    """A table column's heading: its name and, in brackets, its unit (``width_mm`` → "Width (mm)")."""
    unit = split_key(key)[1]
    return f"{figure_name(key)} ({unit})" if unit else figure_name(key)


def cell_text(key: str, value) -> str:
    """A table cell of column ``key``: numbers rounded to the column's resolution, without the unit."""
    return format_number(value, split_key(key)[2])


def figure_rows(figures: dict) -> list[tuple[str, str]]:
    """(name, value with unit) of every figure, in the order given."""
    return [(figure_name(k), figure_value(k, v)) for k, v in figures.items()]


def check_value(check) -> str:
    """A check's measured value against its limit, in its unit: ``"3.1 ° (limit 22.5 °)"``."""
    unit = {"deg": "°", "db": "dB"}.get(check.unit.lower(), check.unit)
    key = {"°": "_deg", "dB": "_db", "mm": "_mm", "s": "_s"}.get(unit, "")
    value = figure_value("v" + key, float(check.value)) if key else format_number(float(check.value))
    limit = figure_value("v" + key, float(check.limit)) if key else format_number(float(check.limit))
    unit_text = "" if key else (f" {unit}" if unit else "")
    return f"{value}{unit_text} (limit {limit}{unit_text})"


def overall(checks) -> str:
    """The build's status: fail if any check fails, else warn if any warns, else pass (skipped stages
    are reported as such, they neither pass nor fail the build)."""
    statuses = {c.status for c in checks}
    return "fail" if "fail" in statuses else ("warn" if "warn" in statuses else "pass")


def by_urgency(checks) -> list:
    """Checks ordered fail, warn, skip, pass (stable within each)."""
    return sorted(checks, key=lambda c: STATUS_ORDER.index(c.status))


@dataclass(frozen=True)
class Verdict:
    """One answer of the design review: a question, its status (a check's, or ``info``) and the sentence
    that answers it."""
    question: str
    status: str
    answer: str


# question -> the checks that answer it (first match by name prefix)
QUESTIONS = (
    ("Sanding", ("unsanded_step_phase_error", "ring_finishing_allowance")),
    ("Test zone (as-built aperture phase)", ("quiet_zone", "test_zone", "as_built_phase_rms",
                                             "aperture_phase_error_rms", "field_edge_phase_error")),
    ("Tolerances", ("tolerance_budget",)),
    ("Full-wave confirmation", ("full_wave", "fullwave_vs_mie")),
)


def verdicts(checks, boards: dict[str, int], totals_kg: dict[str, float]) -> list[Verdict]:
    """The review's opening answers: what to buy, then each question of :data:`QUESTIONS` that a
    check of this build answers, then every other failure or warning."""
    out = []
    if boards:
        buy = "; ".join(f"{n} × {material}" for material, n in sorted(boards.items()))
        mass = sum(totals_kg.values())
        out.append(Verdict("What to buy", "info", f"{buy} (stock boards), {figure_value('mass_kg', mass)} of material"
                           " in the finished parts"))
    used = set()
    for question, prefixes in QUESTIONS:
        hits = [c for c in checks if c.name.startswith(prefixes) and c.name not in used]
        if hits:
            used |= {c.name for c in hits}
            worst = by_urgency(hits)[0]
            out.append(Verdict(question, worst.status, " ".join(c.message.rstrip(".") + "." for c in by_urgency(hits))))
    for c in by_urgency(checks):
        if c.status in ("fail", "warn") and c.name not in used:
            out.append(Verdict(figure_name(c.name), c.status, c.message))
    return out
