"""Python API for notebooks and scripts: the same steps as ``make-lens``, with results as objects.

    >>> from antenna_cad import api
    >>> spec = api.load("xps-collimator-0.5m")            # a bundled recipe, a YAML file or a dict
    >>> spec = api.with_changes(spec, {"design.focal_length_mm": 3000})
    >>> report = api.validate(spec)                         # synthesis and every rule, no CAD
    >>> result = api.build(spec, "exports")                 # everything into exports/<name>/
    >>> result.figures["thickness_mm"], result.status, result.path("report.html")

Errors are the CLI's: :class:`SpecError` (one line per bad field), :class:`DesignError` (physics
that cannot be built, naming the spec block), :class:`OutputError` (an unusable output folder),
:class:`CatalogError` (``new_spec``: an unknown recipe or kind, a bad name). Nothing is printed; progress comes through the
``progress(stage, fraction)`` callback.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from antenna_cad.catalog import CatalogError, Recipe, recipes, starting_spec
from antenna_cad.catalog import recipe as _recipe
from antenna_cad.pipeline import OutputError, Plan, check_output, prepare, solid_checks
from antenna_cad.pipeline import build as _build
from antenna_cad.spec import SpecError, load_spec, parse_spec
from antenna_cad.spec.common import SpecBase
from antenna_cad.synthesis.checks import Check, DesignError

__all__ = ["Build", "CatalogError", "Check", "DesignError", "OutputError", "Part", "Recipe", "Spec", "SpecError",
           "Validation", "build", "load", "new_spec", "read_build", "recipes", "validate", "with_changes"]

Spec = SpecBase
"""A validated spec: a frozen pydantic model of its kind (``spec.kind``, ``spec.name``, its blocks)."""
Progress = Callable[[str, float], None]
SpecLike = SpecBase | Mapping[str, Any] | str | Path


@dataclass(frozen=True)
class Validation:
    """What ``make-lens validate`` answers: the spec, the checks a build would apply before CAD, and
    the plan (design, layup, fabrication plan) they came from."""
    spec: Spec
    checks: list[Check]
    plan: Plan = field(repr=False)

    @property
    def status(self) -> str:
        """``fail`` if any check fails, else ``warn`` if any warns, else ``pass``."""
        return _worst(self.checks)


@dataclass(frozen=True)
class Part:
    """One part of the STEP assembly as the manifest records it (``stl`` is None without STL output)."""
    label: str
    material: str
    role: str
    volume_mm3: float
    solids: int
    stl: Path | None


@dataclass(frozen=True)
class Build:
    """A finished build in ``out_dir`` (``OUT/<name>/``): key figures, as-built verification figures,
    checks, parts, masses, boards, files and the stage times (s)."""
    name: str
    kind: str
    out_dir: Path
    figures: dict[str, Any]
    verified: dict[str, float]
    checks: list[Check]
    parts: list[Part]
    masses_kg: dict[str, float]
    boards: dict[str, int]
    files: list[str]
    seconds: dict[str, float]

    @property
    def status(self) -> str:
        """``fail`` if any check fails, else ``warn`` if any warns, else ``pass``."""
        return _worst(self.checks)

    def path(self, file: str) -> Path:
        """The path of one output file, e.g. ``path("report.html")``; KeyError if the build has none."""
        if file not in self.files:
            raise KeyError(f"{file}: not among the {len(self.files)} files of {self.out_dir}")
        return self.out_dir / file

    @property
    def manifest(self) -> dict[str, Any]:
        """``manifest.json`` as a dict (resolved spec, figures, checks, parts, sheets, templates, files)."""
        return json.loads((self.out_dir / "manifest.json").read_text(encoding="utf-8"))

    def check(self, name: str) -> Check:
        """The check called ``name`` (KeyError naming the checks there are)."""
        for c in self.checks:
            if c.name == name:
                return c
        raise KeyError(f"{name}: no such check (there are {', '.join(c.name for c in self.checks)})")


def load(source: SpecLike) -> Spec:
    """A validated spec from a YAML file, a bundled recipe's name (when no such file exists), a dict (as
    YAML would give) or a spec (returned as is). Raises SpecError (one line per problem)."""
    if isinstance(source, SpecBase):
        return source
    if isinstance(source, Mapping):
        return parse_spec(_plain(source), "<dict>")
    path = Path(source)
    if not path.exists() and str(source) in {r.name for r in recipes()}:
        return parse_spec(yaml.safe_load(_recipe(str(source)).text), f"recipe {source}")
    return load_spec(path)


def with_changes(spec: SpecLike, changes: Mapping[str, Any]) -> Spec:
    """A copy of ``spec`` with fields set by dotted path (``{"design.focal_length_mm": 3000}``), validated
    again as a whole (a mistyped path is a SpecError naming it)."""
    data = load(spec).model_dump(mode="json", exclude_unset=True)
    for dotted, value in changes.items():
        *parents, leaf = dotted.split(".")
        node = data
        for key in parents:
            node = node.setdefault(key, {})
            if not isinstance(node, dict):
                raise SpecError([f"<changes>: {dotted}: {key} is not a block of fields"])
        node[leaf] = value
    return parse_spec(data, "<changes>")


def validate(spec: SpecLike, out: str | Path | None = None, solids: bool = False) -> Validation:
    """Everything ``build`` can refuse, writing nothing: synthesis, layup plan, resource limits,
    fabrication plan, with ``solids`` the solid model (CAD in memory) and the STL triangles it needs,
    and with ``out`` the output folder (checked first, as ``build`` does); with neither, CAD-free (a
    printed lattice is then planned without its mesh, :mod:`antenna_cad.stages`). Raises SpecError,
    OutputError or DesignError; check failures are in the result."""
    loaded = load(spec)
    if out is not None:
        check_output(Path(out), loaded.name)
    plan = prepare(loaded, cad=solids or out is not None)     # without either: CAD-free (validate --fast)
    return Validation(loaded, list(plan.checks) + (solid_checks(loaded, plan) if solids else []), plan)


def build(spec: SpecLike | Validation, out: str | Path = "exports", progress: Progress | None = None) -> Build:
    """Build every output into ``out/<name>/`` atomically (an earlier build there is replaced) and return
    it; a :class:`Validation` is built without planning again. Raises SpecError, DesignError or
    OutputError (nothing written); a failed check is in the result."""
    checked = spec if isinstance(spec, Validation) else validate(spec, out)
    result = _build(checked.spec, Path(out), progress, checked.plan)
    return _from_manifest(result.out_dir, dict(result.seconds))


def read_build(folder: str | Path) -> Build:
    """An earlier build (``OUT/<name>/``, by ``make-lens`` or :func:`build`) read back from its
    ``manifest.json``; stage times are not recorded there (``seconds`` is empty)."""
    return _from_manifest(Path(folder), {})


def _from_manifest(folder: Path, seconds: dict[str, float]) -> Build:
    manifest = json.loads((folder / "manifest.json").read_text(encoding="utf-8"))
    parts = [Part(p["label"], p["material"], p["role"], p["volume_mm3"], p["solids"],
                  folder / p["file"] if "file" in p else None) for p in manifest["parts"]]
    return Build(manifest["name"], manifest["kind"], folder, manifest["figures"], manifest["verification"]["figures"],
                 [Check(**c) for c in manifest["checks"]], parts, manifest["mass_kg"], manifest["boards"],
                 sorted(f["path"] for f in manifest["files"]) + ["manifest.json"], seconds)


def new_spec(source: str, name: str | None = None) -> tuple[str, str]:
    """``(name, YAML text)`` of a commented starting spec from a kind (``collimator``, …) or a bundled
    recipe, renamed ``name`` (default ``my-<kind>`` or the recipe's name)."""
    return starting_spec(source, name)


def _worst(checks: list[Check]) -> str:
    statuses = {c.status for c in checks}
    return "fail" if "fail" in statuses else ("warn" if "warn" in statuses else "pass")


def _plain(data: Any) -> Any:
    """A dict/list tree of plain values (tuples as lists), as the YAML reader returns it."""
    if isinstance(data, Mapping):
        return {str(k): _plain(v) for k, v in data.items()}
    if isinstance(data, (list, tuple)):
        return [_plain(v) for v in data]
    return data


