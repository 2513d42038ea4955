"""Physical ranges of spec numbers: no number reaches synthesis unless it is finite
(``StrictModel`` refuses nan/inf) and inside the bounds its field declares.

A field declares both ends — ``Field(ge=MIN_MM, le=5000)`` — and a lower bound with a physical
meaning: ``gt=0`` lets 1e-308 through, which no board, tool or mesher can use. Lists declare
``max_length``. :func:`unbounded_fields` lists what a spec model leaves open; the test suite runs it
on every registered kind, so a new kind adopts the rule by declaring its bounds.
"""

from __future__ import annotations

from pydantic import BaseModel

TINY = 1e-9            # smallest non-zero magnitude of any spec number (StrictModel)
MIN_MM = 0.01          # 10 µm: below any board, machining or printing precision
MIN_GHZ = 0.1          # 100 MHz: below it a foam lens is metres thick per wavelength
MIN_DEG = 0.01         # angles and phase budgets
MIN_RATIO = 1e-4       # normalised (D = 1) construction coefficients and shape ratios
MIN_SHEET_MM = 0.5      # thinnest stock sheet a layup takes
MAX_LIST = 200         # items of a list field (grades, cell lengths, stock thicknesses)


def unbounded_fields(model: type[BaseModel]) -> list[str]:
    """Dotted paths of the numbers of ``model`` without a physical lower and an upper bound, and of
    its lists without a maximum length."""
    schema = model.model_json_schema()
    defs = schema.get("$defs", {})
    found: list[str] = []
    _walk(schema, defs, "", found, set())
    return sorted(set(found))


def _walk(node: dict, defs: dict, path: str, found: list[str], seen: set[str]) -> None:
    if "$ref" in node:
        name = node["$ref"].rsplit("/", 1)[-1]
        if (name, path) not in seen:
            seen.add((name, path))
            _walk(defs[name], defs, path, found, seen)
        return
    for key in ("anyOf", "oneOf", "allOf"):
        for sub in node.get(key, []):
            _walk(sub, defs, path, found, seen)
    kind = node.get("type")
    if kind in ("number", "integer"):
        low = node.get("minimum", node.get("exclusiveMinimum"))
        high = node.get("maximum", node.get("exclusiveMaximum"))
        if low is None or high is None or node.get("exclusiveMinimum") == 0:
            found.append(path or "<root>")
    if kind == "array":
        if "maxItems" not in node:
            found.append(path or "<root>")
        for sub in node.get("prefixItems", []) + ([node["items"]] if isinstance(node.get("items"), dict) else []):
            _walk(sub, defs, f"{path}[]", found, seen)
    for name, sub in node.get("properties", {}).items():
        _walk(sub, defs, f"{path}.{name}" if path else name, found, seen)
