"""The sweep's tidy table (one row per variant: axes, status, figures), written atomically after every
completed row, then as Parquet; and the Pareto front over the objectives."""

from __future__ import annotations

import csv
import io
import json
import math
import os
from pathlib import Path

from antenna_cad.sweep.model import SweepSpec
from antenna_cad.sweep.variants import Variant

META = ("variant", "spec_hash", "status", "error")
CHECKS = ("checks", "check_issues")
RESULTS_CSV, RESULTS_PARQUET, PARETO_CSV, PAGE = "results.csv", "results.parquet", "pareto.csv", "index.html"


def columns(sweep: SweepSpec) -> list[str]:
    extra = ["folder"] if sweep.mode == "build" else []
    return [*META, *sweep.axes, *CHECKS, *sweep.figures, *extra]


def cell(value):
    """Axis values as table cells: numbers and text as they are, lists and mappings as JSON."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    return json.dumps(value, sort_keys=True)


def _head(variant: Variant) -> dict:
    return {"variant": variant.index, "spec_hash": variant.key[:12]} | {p: cell(v) for p, v in variant.values.items()}


def make_row(variant: Variant, result: dict | None, out_dir: Path) -> dict:
    """The row of a variant: ``result`` from its task, None for a variant the spec loader rejected."""
    row = _head(variant)
    if result is None:
        return row | {"status": "invalid", "error": variant.error}
    if "error" in result:
        return row | {"status": "failed", "error": result["error"]}
    folder = Path(result["folder"]).relative_to(out_dir).as_posix() if result["folder"] else None
    return row | {"status": "ok", "error": "", "checks": result["checks"], "check_issues": result["check_issues"],
                  "folder": folder} | result["figures"]


def previous_results(out_dir: Path, cols: list[str], axes: list[str]) -> dict[str, dict]:
    """What an earlier, interrupted run of this sweep left in results.csv, by spec hash: the result
    cells (status, error, checks, figures) of its rows that have one — ok, or failed by the variant
    itself (not by a lost worker) — when the table has this sweep's columns; else nothing."""
    try:
        with open(out_dir / RESULTS_CSV, newline="", encoding="utf-8") as fh:
            reader = csv.DictReader(fh)
            if [c for c in reader.fieldnames or [] if c != "pareto"] != cols:
                return {}
            rows = list(reader)
    except (OSError, UnicodeDecodeError, csv.Error):
        return {}
    found = {}
    for row in rows:
        if row["status"] == "ok" or row["status"] == "failed" and not row["error"].startswith("task:"):
            found[row["spec_hash"]] = {c: _cell_value(c, row[c], row["status"]) for c in cols
                                       if c not in ("variant", "spec_hash", *axes)}
    return found


def kept_row(variant: Variant, result_cells: dict) -> dict:
    """The row of a variant whose result an earlier run computed (:func:`previous_results`)."""
    return _head(variant) | result_cells


def _cell_value(column: str, text: str, status: str):
    """A results.csv cell read back as :func:`make_row` made it (numbers, booleans, empty = None)."""
    if column == "error" or column == "check_issues" and status == "ok":
        return text
    if text == "":
        return None
    if column in META + CHECKS + ("folder",):
        return text
    if text in ("True", "False"):
        return text == "True"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def atomic_write(path: Path, data: bytes) -> None:
    """Write beside the target and rename over it: readers see the old file or the new, never half."""
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    tmp.write_bytes(data)
    os.replace(tmp, path)


def csv_bytes(cols: list[str], rows: list[dict]) -> bytes:
    buf = io.StringIO()
    writer = csv.DictWriter(buf, cols, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({c: ("" if row.get(c) is None else row[c]) for c in cols})
    return buf.getvalue().encode("utf-8")


class RowWriter:
    """Rows by variant index; ``add`` rewrites results.csv (atomically) with every row done so far."""

    def __init__(self, out_dir: Path, cols: list[str]):
        self.out_dir, self.cols, self.rows = out_dir, cols, {}

    def add(self, rows: list[dict]) -> None:
        for row in rows:
            self.rows[row["variant"]] = row
        atomic_write(self.out_dir / RESULTS_CSV, csv_bytes(self.cols, self.sorted()))

    def sorted(self) -> list[dict]:
        return [self.rows[i] for i in sorted(self.rows)]


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def pareto_front(rows: list[dict], objectives: dict[str, str]) -> list[dict]:
    """Rows no other row dominates (as good in every objective, better in one), among the ``ok`` rows
    with every objective a finite number; sorted by the first objective."""
    if not objectives:
        return []
    names = list(objectives)
    sign = [1.0 if objectives[n] == "min" else -1.0 for n in names]
    pool = [r for r in rows if r["status"] == "ok" and all(_number(r.get(n)) for n in names)]
    costs = [[s * r[n] for s, n in zip(sign, names)] for r in pool]

    def dominated(i: int) -> bool:
        return any(all(a <= b for a, b in zip(other, costs[i])) and other != costs[i] for other in costs)
    front = [r for i, r in enumerate(pool) if not dominated(i)]
    return sorted(front, key=lambda r: (sign[0] * r[names[0]], r["variant"]))


def write_tables(out_dir: Path, cols: list[str], rows: list[dict], front: list[dict]) -> None:
    """results.csv with its ``pareto`` column, results.parquet (typed columns) and pareto.csv."""
    on_front = {r["variant"] for r in front}
    rows = [r | {"pareto": r["variant"] in on_front} for r in rows]
    cols = cols + ["pareto"]
    atomic_write(out_dir / RESULTS_CSV, csv_bytes(cols, rows))
    atomic_write(out_dir / PARETO_CSV, csv_bytes(cols, [r | {"pareto": True} for r in front]))
    atomic_write(out_dir / RESULTS_PARQUET, parquet_bytes(cols, rows))


def parquet_bytes(cols: list[str], rows: list[dict]) -> bytes:
    """One typed column per field: bool, int64, float64, or text when the values are mixed."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    fields = []
    for c in cols:
        values = [r.get(c) for r in rows if r.get(c) is not None]
        if values and all(isinstance(v, bool) for v in values):
            kind = pa.bool_()
        elif values and all(isinstance(v, int) and not isinstance(v, bool) for v in values):
            kind = pa.int64()
        elif values and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
            kind = pa.float64()
        else:
            kind = pa.string()
        fields.append(pa.field(c, kind))
    schema = pa.schema(fields)
    data = [{c: (str(r[c]) if schema.field(c).type == pa.string() and r.get(c) is not None else r.get(c))
             for c in cols} for r in rows]
    buf = pa.BufferOutputStream()
    pq.write_table(pa.Table.from_pylist(data, schema=schema), buf)
    return buf.getvalue().to_pybytes()
