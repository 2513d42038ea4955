"""What ``make-lens check`` takes from manifest.json, and how little it trusts it.

The manifest is read as strict JSON and its shape validated (:class:`Manifest`: a mapping with the
keys every build writes, each of its type) — anything else is not a build (``CheckError``, exit 2).
Every path it names is confined to the build folder (:func:`confined`: relative, no ``..``, no
symlink anywhere on the way, inside the folder once resolved), so a manifest cannot make check read
``../../etc/passwd``. What a build always writes is required whatever the lists say
(:func:`required_files`): the cut list, the STEP, one STL per part, a DXF and an SVG per drawing
and the template PDF, the report — from the spec's own ``outputs`` switches held in the manifest.
"""

from __future__ import annotations

import json
import os
from pathlib import Path, PurePosixPath

from pydantic import BaseModel, ConfigDict, Field, ValidationError

SHA256 = r"^[0-9a-f]{64}$"
NAME = r"^[a-z0-9][a-z0-9._-]*$"


class CheckError(Exception):
    """The folder is not a build (no readable manifest, or one of the wrong shape)."""


class _Entry(BaseModel):
    model_config = ConfigDict(extra="allow", strict=True, frozen=True)


class FileEntry(_Entry):
    path: str = Field(min_length=1)
    bytes: int = Field(ge=0)
    sha256: str = Field(pattern=SHA256)


class PartEntry(_Entry):
    label: str = Field(pattern=NAME)
    material: str
    role: str = "fabricated"
    volume_mm3: float = Field(gt=0)
    solids: int = Field(1, ge=1)
    file: str | None = None
    triangles: int | None = Field(None, ge=1)
    watertight: bool | None = None


class TemplateEntry(_Entry):
    label: str = Field(min_length=1)
    dxf: str | None = None
    svg: str | None = None
    cut_bbox_mm: tuple[float, float, float, float] | None = None
    svg_size_mm: tuple[float, float] | None = None
    pdf: str | None = None
    pages: int | None = Field(None, ge=1)


class Outputs(_Entry):
    step: bool
    stl: bool
    templates: bool
    report: bool


class SpecPart(_Entry):
    name: str
    kind: str
    outputs: Outputs


class Tolerances(_Entry):
    mesh_tolerance_mm: float = Field(gt=0)
    template_chord_tolerance_mm: float = Field(ge=0)


class MaterialEntry(_Entry):
    name: str
    density_kg_m3: float = Field(gt=0)


class Manifest(_Entry):
    name: str = Field(pattern=NAME, max_length=100)
    kind: str
    spec: SpecPart
    material: MaterialEntry
    tolerances: Tolerances
    files: list[FileEntry]
    parts: list[PartEntry]
    templates: list[TemplateEntry]
    mass_kg: dict[str, float]
    pieces: list[dict]
    sheets: list[dict] = []


def read_manifest(folder: Path) -> tuple[Manifest, dict]:
    """The validated manifest of ``folder`` and its raw JSON (CheckError naming the first problem)."""
    path = folder / "manifest.json"
    if path.is_symlink() or not path.is_file():
        raise CheckError(f"{folder}: no manifest.json (not a build folder)")

    def refuse(constant):
        raise ValueError(f"bare {constant} is not JSON")
    try:
        text = path.read_bytes().decode("utf-8")
        raw = json.loads(text, parse_constant=refuse)
    except (ValueError, OSError) as exc:
        raise CheckError(f"{path}: not strict JSON: {exc}") from None
    if not isinstance(raw, dict):
        raise CheckError(f"{path}: not a build manifest (a JSON {type(raw).__name__}, not an object)")
    try:
        return Manifest.model_validate_json(text), raw
    except ValidationError as exc:
        first = exc.errors()[0]
        where = ".".join(str(p) for p in first["loc"]) or "<root>"
        more = f" (and {exc.error_count() - 1} more)" if exc.error_count() > 1 else ""
        raise CheckError(f"{path}: {where}: {first['msg']}{more}") from None


def confined(folder: Path, rel: str) -> Path | None:
    """``folder/rel`` when ``rel`` is a plain relative POSIX path whose every component exists below
    ``folder`` without a symlink (so it resolves inside it); None otherwise."""
    parts = PurePosixPath(rel).parts
    if (not parts or rel.startswith("/") or "\\" in rel or "\x00" in rel
            or any(p in ("..", ".", "") for p in parts) or rel != PurePosixPath(*parts).as_posix()):
        return None
    path = folder
    for part in parts:
        path = path / part
        if path.is_symlink():
            return None
    root = os.path.realpath(folder)
    return path if os.path.realpath(path).startswith(root + os.sep) else None


def required_files(m: Manifest) -> dict[str, str]:
    """File → why a build of this manifest's spec always writes it."""
    outputs = m.spec.outputs
    need = {"cutlist.csv": "every build writes its cut list"}
    if outputs.step:
        need[f"{m.name}.step"] = "outputs.step is on"
    if outputs.stl:
        need |= {f"stl/{p.label}.stl": "outputs.stl is on: one STL per part" for p in m.parts}
    if outputs.report:
        need |= {"report.html": "outputs.report is on", "report.pdf": "outputs.report is on"}
    if outputs.templates:
        for t in m.templates:
            if t.dxf is not None or t.svg is not None:
                need |= {f"templates/{t.label}.dxf": "a DXF per drawing", f"templates/{t.label}.svg": "an SVG per drawing"}
    return need


def walk_files(folder: Path) -> tuple[set[str], list[str]]:
    """(regular files below ``folder`` as relative POSIX paths, other entries: symlinks, pipes…);
    symlinked folders are not entered."""
    files, odd = set(), []
    for top, dirs, names in os.walk(folder, followlinks=False):
        for name in dirs + names:
            path = Path(top) / name
            rel = path.relative_to(folder).as_posix()
            if path.is_symlink() or name in names and not path.is_file():
                odd.append(rel)
            elif name in names:
                files.add(rel)
    return files, sorted(odd)
