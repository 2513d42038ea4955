"""The recipes shipped with the package (``antenna_cad.recipes``) and starting specs made from them.

A recipe is a complete, commented spec of a design from one of the source methods; ``make-lens
recipes`` lists them and ``make-lens new KIND|RECIPE [NAME]`` copies one under a new name. The
recipes are the repository's ``recipes/`` folder, installed as the package ``antenna_cad.recipes``
(pyproject/setup.py); a source tree run without installing reads that folder directly.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from importlib import resources
from importlib.resources.abc import Traversable
from pathlib import Path

# the recipe `make-lens new KIND` starts from: the plainest complete design of each kind
KIND_RECIPES = {
    "collimator": "xps-collimator-0.5m",
    "bifocal": "bifocal-nikulina-9m",
    "luneburg": "luneburg-classic-5",
    "slot_array": "x-slot-array-ellipse",
    "mirror_lens": "mirror-lens-346mm",
    "polyfocal": "polyfocal-fourfocal-2d-60deg",
    "graded": "graded-trifocal-160mm",
}
NAME_RULE = re.compile(r"^[a-z0-9][a-z0-9._-]*$")     # the spec's `name` field (spec/common.py)
SCHEMA_LINE = "# yaml-language-server:"
SUMMARY_CHARS = 100


class CatalogError(ValueError):
    """An unknown recipe or kind, or a name a spec cannot take (one line)."""


@dataclass(frozen=True)
class Recipe:
    """One bundled recipe: its name (file stem), kind, one-line summary and full YAML text."""
    name: str
    kind: str
    summary: str
    text: str


def recipes_folder() -> Traversable:
    """The bundled recipes: the installed package ``antenna_cad.recipes``, else the source tree's
    ``recipes/`` folder (a clone used without installing it)."""
    try:
        return resources.files("antenna_cad.recipes")
    except ModuleNotFoundError:
        return Path(__file__).resolve().parent.parent / "recipes"


def recipes() -> list[Recipe]:
    """Every bundled spec recipe, sorted by name (sweep files under ``sweeps/`` are not specs)."""
    found = [entry for entry in recipes_folder().iterdir() if entry.name.endswith(".yaml")]
    return [_recipe(entry) for entry in sorted(found, key=lambda e: e.name)]


def recipe(name: str) -> Recipe:
    """The bundled recipe ``name`` (with or without ``.yaml``); CatalogError naming the choices."""
    stem = name.removesuffix(".yaml")
    for entry in recipes():
        if entry.name == stem:
            return entry
    raise CatalogError(f"{name}: no such recipe or kind (recipes: `make-lens recipes`; "
                       f"kinds: {', '.join(KIND_RECIPES)})")


def sweeps() -> list[str]:
    """Names of the bundled sweep files (``recipes/sweeps/*.yaml``)."""
    folder = recipes_folder() / "sweeps"
    return sorted(e.name.removesuffix(".yaml") for e in folder.iterdir() if e.name.endswith(".yaml"))


def starting_spec(source: str, name: str | None = None) -> tuple[str, str]:
    """``(name, YAML text)`` of a new spec from a kind (its plainest recipe) or a recipe: the recipe
    renamed, its editor-schema line replaced by comments on what to change and how to check it."""
    base = recipe(KIND_RECIPES.get(source, source))
    name = name or (f"my-{base.kind.replace('_', '-')}" if source in KIND_RECIPES else base.name)
    if not NAME_RULE.fullmatch(name) or len(name) > 100:
        raise CatalogError(f"{name}: a spec name is lower-case letters, digits, '.', '_' or '-' "
                           "(starting with a letter or digit), at most 100 characters")
    body = [line for line in base.text.splitlines() if not line.startswith(SCHEMA_LINE)]
    renamed = [f"name: {name}" if line.startswith("name:") else line for line in body]
    header = [f"# {name}: a {base.kind} spec started from the bundled recipe {base.name}.",
              "# Change the fields below, then: make-lens validate " + f"{name}.yaml  (writes nothing)",
              f"#                                 make-lens {name}.yaml -o exports",
              "# Every field, unit, range and default: make-lens schema (JSON Schema) or the docs' spec reference.",
              "# The recipe's own notes follow.", "#"]
    return name, "\n".join(header + renamed) + "\n"


def _recipe(entry: Traversable) -> Recipe:
    text = entry.read_text(encoding="utf-8")
    kind = next((line.split(":", 1)[1].split("#")[0].strip() for line in text.splitlines()
                 if line.startswith("kind:")), "?")
    return Recipe(entry.name.removesuffix(".yaml"), kind, _summary(text), text)


def _summary(text: str) -> str:
    """The first sentence of the recipe's header comment, cut to one line."""
    words = []
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        if not line.startswith(SCHEMA_LINE):
            words.append(line.lstrip("# ").strip())
    prose = " ".join(words)
    sentence = re.split(r"\. (?=[A-Z])", prose, maxsplit=1)[0].rstrip(".")
    return sentence if len(sentence) <= SUMMARY_CHARS else sentence[:SUMMARY_CHARS - 1].rstrip() + "…"
