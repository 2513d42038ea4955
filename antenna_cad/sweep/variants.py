"""Variant expansion: the product of the sweep's axes applied to the base spec, each variant validated
by the same spec loader as ``make-lens`` (:func:`antenna_cad.spec.parse_spec`) and keyed by the hash of
its resolved spec (every default filled in), so identical variants are computed once."""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
from dataclasses import dataclass

from antenna_cad.spec import SpecError, parse_spec
from antenna_cad.sweep.model import FULL_WAVE, SweepFile


@dataclass(frozen=True)
class Variant:
    index: int                  # 1-based, in the order of the axes' product
    values: dict[str, object]   # axis path → value
    spec: dict | None           # resolved spec (plain JSON types), None when invalid
    key: str                    # sha256 of the resolved spec; "" when invalid
    error: str = ""             # the spec loader's message when invalid


def set_path(doc: dict, path: str, value) -> None:
    """Set ``a.b.c`` in nested mappings, creating missing levels (the spec loader judges the result)."""
    *parents, leaf = path.split(".")
    node = doc
    for i, part in enumerate(parents):
        child = node.get(part)
        if child is None:
            child = node[part] = {}
        if not isinstance(child, dict):
            raise SpecError([f"{'.'.join(parents[:i + 1])}: is {child!r}, not a mapping: cannot set {path}"])
        node = child
    node[leaf] = value


def spec_key(spec: dict) -> str:
    return hashlib.sha256(json.dumps(spec, sort_keys=True, ensure_ascii=True).encode()).hexdigest()


def base_document(file: SweepFile) -> dict:
    """The base spec with full-wave off (unless the sweep file asks for it) and the sweep's ``set``
    applied; every axis must name a field of its resolved
    spec (defaults included), so a mistyped path is an error of the sweep file, not a sweep of errors."""
    doc = copy.deepcopy(file.base)
    if not file.sweep.asks_for_full_wave():
        _set(doc, FULL_WAVE, "off", file.base_source, "base")
    for path, value in file.sweep.set.items():
        _set(doc, path, value, file.source, "set")
    resolved = parse_spec(doc, file.base_source).model_dump(mode="json")
    for path in file.sweep.axes:
        node = resolved
        for part in path.split("."):
            if not isinstance(node, dict) or part not in node:
                raise SpecError([f"{file.source}: axes.{path}: not a field of the base spec"
                                 + (" (set it to a mapping with `set:` first)" if isinstance(node, str) else "")])
            node = node[part]
    return doc


def expand(file: SweepFile) -> list[Variant]:
    """Every variant of the sweep, valid or not (an invalid one carries the loader's message)."""
    sweep, doc = file.sweep, base_document(file)
    groups = sweep.axis_groups()
    columns = [list(zip(*(sweep.axis_values(p) for p in group))) for group in groups]
    variants = []
    for index, combo in enumerate(itertools.product(*columns), start=1):
        values = {p: v for group, row in zip(groups, combo) for p, v in zip(group, row)}
        spec = copy.deepcopy(doc)
        try:
            for path, value in values.items():
                _set(spec, path, copy.deepcopy(value), file.source, "axes")
            resolved = parse_spec(spec, f"variant {index}").model_dump(mode="json")
        except SpecError as exc:
            variants.append(Variant(index, values, None, "", "; ".join(exc.lines)))
            continue
        variants.append(Variant(index, values, resolved, spec_key(resolved)))
    return variants


def _set(doc: dict, path: str, value, source: str, block: str) -> None:
    try:
        set_path(doc, path, value)
    except SpecError as exc:
        raise SpecError([f"{source}: {block}.{exc.lines[0]}"]) from None
