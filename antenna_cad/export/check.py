"""``make-lens check OUT``: a build folder re-read by readers other than the ones that wrote it,
against what manifest.json promises — without trusting the manifest (docs/guide/check.md).

1. The manifest: strict JSON of the shape a build writes (``check_manifest``), else exit 2.
2. The files: every listed path confined to the folder, its bytes and sha256; no unlisted file,
   no symlink or other non-regular entry.
3. What the build always writes, whatever the lists say (``required_files``), and the lists
   against each other: parts ↔ STL files, templates ↔ DXF/SVG/PDF files, the masses against the
   parts' volumes × densities, the cut list against the pieces.
4. The content of each file against its entry: one checker per file type in :data:`CHECKERS`
   (``check_readers``); a new file type plugs in as one more entry. A reader that fails on a
   file (truncated, stray bytes) makes a failed row, never a traceback.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

from antenna_cad.export.check_manifest import (CheckError, Manifest, confined, read_manifest, required_files,
                                               walk_files)
from antenna_cad.export.check_readers import (Finding, dxf_findings, pdf_findings, printed_findings, step_findings,
                                              stl_findings, svg_findings)

__all__ = ["CHECKERS", "CheckError", "Finding", "check_build"]
MASS_RTOL = 0.02        # cut-list masses (as cut, from the plan) vs the model's volumes × densities


@dataclass
class Build:
    """A build folder being checked: its manifest and the listed files that passed their sha256."""
    folder: Path
    m: Manifest
    good: set[str]
    raw: dict               # the manifest as read (entries the model does not type: ``cam[]``)

    def path(self, rel: str | None) -> Path | None:
        """The file ``rel`` if listed, confined and intact (else None: reported by the file checks)."""
        return self.folder / rel if rel in self.good else None


def check_build(folder: Path) -> list[Finding]:
    """All findings for build folder ``folder`` (raises CheckError when it is not one)."""
    m, raw = read_manifest(folder)
    build = Build(folder, m, set(), raw)
    findings = list(_files(build))
    findings += _required(build) + _lists(build)
    for name, checker in CHECKERS.items():
        findings += _guarded(name, checker, build)
    return findings


def _guarded(name: str, checker: Callable[[Build], Iterator[Finding]], build: Build) -> list[Finding]:
    try:
        return list(checker(build))
    except Exception as exc:        # a hostile file breaking a reader is a failed row, not a traceback
        return [Finding(name, f"{name} read", False, f"unreadable: {type(exc).__name__}: {str(exc)[:200]}")]


def _per_file(file: str, check: str, run: Callable[[], Iterator[Finding]]) -> list[Finding]:
    try:
        return list(run())
    except Exception as exc:
        return [Finding(file, check, False, f"unreadable: {type(exc).__name__}: {str(exc)[:200]}")]


def _files(build: Build) -> Iterator[Finding]:
    folder, entries = build.folder, build.m.files
    on_disk, odd = walk_files(folder)
    for name in odd:
        yield Finding(name, "regular files", False, "a symlink or special file (a build holds regular files only)")
    listed = {}
    for e in entries:
        if e.path in listed:
            yield Finding(e.path, "listed", False, "listed twice in manifest.json")
        elif confined(folder, e.path) is None:
            yield Finding(e.path, "confined", False, "path leaves the build folder (absolute, .., or through a "
                          "symlink): not read")
        else:
            listed[e.path] = e
    for name in sorted(on_disk - set(listed) - {"manifest.json"}):
        yield Finding(name, "listed", False, "file not listed in manifest.json")
    bad = 0
    for name, entry in sorted(listed.items()):
        path = folder / name
        if name not in on_disk:
            bad += 1
            yield Finding(name, "sha256", False, "listed in manifest.json but missing")
        elif path.stat().st_size != entry.bytes or _sha256(path) != entry.sha256:
            bad += 1
            yield Finding(name, "sha256", False, "content differs from the manifest")
        else:
            build.good.add(name)
    yield Finding("manifest.json", "sha256", bad == 0, f"strict JSON of a build's shape; {len(listed) - bad} of "
                  f"{len(listed)} listed files with their bytes and sha256")


def _sha256(path: Path) -> str:
    with path.open("rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest()


def _required(build: Build) -> list[Finding]:
    m = build.m
    need = required_files(m)
    missing = {f: why for f, why in need.items() if f not in build.good}
    rows = [Finding(f, "required", False, f"missing or not intact ({why})") for f, why in sorted(missing.items())]
    rows.append(Finding("manifest.json", "required", not missing and bool(m.parts),
                        f"{len(need) - len(missing)} of {len(need)} files a build of this spec always writes"
                        + ("" if m.parts else "; no part listed (a build has at least one)")))
    if m.spec.outputs.templates and any(t.dxf for t in m.templates):
        pdfs = [t.pdf for t in m.templates if t.pdf]
        rows.append(Finding("manifest.json", "template pdf", bool(pdfs), f"{len(pdfs)} template PDF(s) for "
                            f"{sum(1 for t in m.templates if t.dxf)} drawings"))
    return rows


def _lists(build: Build) -> list[Finding]:
    """The manifest's lists against each other and against the files."""
    m, rows = build.m, []
    rows.append(Finding("manifest.json", "spec", (m.spec.name, m.spec.kind) == (m.name, m.kind),
                        f"name {m.name!r} and kind {m.kind!r}; the spec held says {m.spec.name!r}, {m.spec.kind!r}"))
    labels = [p.label for p in m.parts]
    stl = {f.path for f in m.files if f.path.startswith("stl/")}
    claimed = {p.file for p in m.parts if p.file}
    odd_parts = [p.label for p in m.parts if p.file is not None and p.file != f"stl/{p.label}.stl"]
    ok = len(set(labels)) == len(labels) and not odd_parts and stl == claimed
    rows.append(Finding("manifest.json", "parts", ok, f"{len(labels)} parts, {len(claimed)} STL files claimed, "
                        f"{len(stl)} listed" + (f"; files not named for their part: {odd_parts[:3]}" if odd_parts else "")
                        + (f"; STL without a part: {sorted(stl - claimed)[:3]}" if stl - claimed else "")))
    named = {t.dxf for t in m.templates} | {t.svg for t in m.templates} | {t.pdf for t in m.templates}
    tfiles = {f.path for f in m.files if f.path.startswith("templates/")}
    pages = [t for t in m.templates if t.pdf and t.pages is None]
    rows.append(Finding("manifest.json", "templates", tfiles == named - {None} and not pages,
                        f"{len(tfiles)} template files, {len(named - {None})} named by template entries"
                        + (f"; unnamed: {sorted(tfiles - named)[:3]}" if tfiles - named else "")
                        + (f"; named, not listed: {sorted(named - tfiles - {None})[:3]}" if named - tfiles - {None} else "")))
    fabrication = (m.spec.model_extra or {}).get("fabrication")
    taper = isinstance(fabrication, dict) and fabrication.get("edge") == "taper"   # discs cut, then coned
    rows.append(_masses(m, bool(m.sheets) and not taper))
    cutlist = build.path("cutlist.csv")
    if cutlist is not None:
        text = cutlist.read_text(encoding="utf-8", errors="replace")
        missing = [p.get("label") for p in m.pieces if str(p.get("label")) not in text]
        rows.append(Finding("cutlist.csv", "pieces", not missing, f"{len(m.pieces) - len(missing)} of "
                            f"{len(m.pieces)} pieces of the manifest in the cut list"))
    return rows


def _masses(m: Manifest, layup: bool) -> Finding:
    """Σ fabricated parts' volume × density against the cut list's total mass (``mass_kg.all``):
    never above it (machining and sanding only remove stock), and equal within MASS_RTOL for a
    sheet layup with stepped edges (its pieces are cut to the parts' outlines; a taper-cut sheet is cut
    as its disc, then coned by the wire)."""
    from antenna_cad.materials import LIBRARY
    densities = {name: mat.density_kg_m3 for name, mat in LIBRARY.items()} | {m.material.name: m.material.density_kg_m3}
    densities |= _metals(m.spec.model_extra or {})
    made = [p for p in m.parts if p.role == "fabricated"]
    unknown = sorted({p.material for p in made} - set(densities))
    kg = sum(p.volume_mm3 * 1e-9 * densities.get(p.material, 0.0) for p in made)
    total = m.mass_kg.get("all")
    if total is None or total <= 0:
        return Finding("manifest.json", "masses", False, "no positive mass_kg.all")
    ratio = kg / total
    both = layup and not unknown          # parts of materials without a known density: the upper bound only
    ok = ratio <= 1 + MASS_RTOL and (not both or ratio >= 1 - MASS_RTOL)
    rule = f"within {MASS_RTOL:.0%} for a sheet layup" if both else f"at most the stock's + {MASS_RTOL:.0%}"
    return Finding("manifest.json", "masses", ok, f"parts' volumes × densities {kg:.4g} kg, cut list "
                   f"{total:.4g} kg (ratio {ratio:.4f}; {rule})"
                   + (f"; no density for {len(unknown)} materials ({unknown[0]}…)" if unknown else ""))


def _metals(spec: object) -> dict[str, float]:
    """Metal name → density of every block of the spec that has ``metal`` and ``metal_density_kg_m3``."""
    found = {}
    if isinstance(spec, dict):
        metal, density = spec.get("metal"), spec.get("metal_density_kg_m3")
        if isinstance(metal, str) and isinstance(density, (int, float)) and not isinstance(density, bool):
            found[metal] = float(density)
        for value in spec.values():
            found |= _metals(value)
    elif isinstance(spec, list):
        for value in spec:
            found |= _metals(value)
    return found


# ------------------------------------------------------------------ file checkers (one per file type)

def _step(build: Build) -> Iterator[Finding]:
    name = f"{build.m.name}.step"
    path = build.path(name)
    if path is not None:
        yield from _per_file(name, "step", lambda: step_findings(path, name, build.m.parts))


def _stl(build: Build) -> Iterator[Finding]:
    chord = build.m.tolerances.mesh_tolerance_mm
    for part in build.m.parts:
        path = build.path(part.file)
        if path is not None:
            yield from _per_file(part.file, "stl", lambda: stl_findings(path, part.file, part, chord))


def _drawings(build: Build) -> Iterator[Finding]:
    chord = build.m.tolerances.template_chord_tolerance_mm
    for entry in build.m.templates:
        for rel, reader in ((entry.dxf, lambda p, r: dxf_findings(p, r, entry)),
                            (entry.svg, lambda p, r: svg_findings(p, r, entry, chord))):
            path = build.path(rel)
            if path is not None:
                yield from _per_file(rel, rel.rsplit(".", 1)[-1], lambda: reader(path, rel))


def _pdfs(build: Build) -> Iterator[Finding]:
    drawings = tuple(t.label for t in build.m.templates if t.dxf)
    for entry in build.m.templates:
        path = build.path(entry.pdf)
        if path is not None:
            words = drawings if len([t for t in build.m.templates if t.pdf]) == 1 else ()
            yield from _per_file(entry.pdf, "pdf", lambda: pdf_findings(path, entry.pdf, True, entry.pages, words))
    path = build.path("report.pdf")
    if path is not None:
        words = (build.m.name, *(str(p.get("label")) for p in build.m.pieces))     # its cut list
        yield from _per_file("report.pdf", "pdf", lambda: pdf_findings(path, "report.pdf", False, None, words))


def _cam(build: Build) -> Iterator[Finding]:
    """G-code (``cam[]``): each entry's file listed and intact, then parsed back by an independent parser
    and held to the lens profile and the machine's travel (:mod:`antenna_cad.export.check_cam`)."""
    entries = build.raw.get("cam", [])
    if not isinstance(entries, list):
        yield Finding("manifest.json", "cam", False, "cam is not a list")
        return
    intact = [e for e in entries if isinstance(e, dict) and isinstance(e.get("file"), str)
              and build.path(e["file"]) is not None]
    for e in entries:
        if not any(e is i for i in intact):
            name = e.get("file") if isinstance(e, dict) else None
            yield Finding(str(name), "cam listed", False, "a cam[] entry whose file is not listed in files[] or not intact")
    if intact:
        from antenna_cad.export.check_cam import check_cam
        yield from check_cam(build.folder, build.raw | {"cam": intact})


def _printed(build: Build) -> Iterator[Finding]:
    """A printed lens's 3MF against its per-part STLs and the manifest's printed volume."""
    files = [e.path for e in build.m.files if e.path.startswith("printed/")]
    stls = {Path(f).stem: build.path(f) for f in files if f.endswith(".stl") and build.path(f) is not None}
    figures = build.raw.get("figures", {}) | build.raw.get("verification", {}).get("figures", {})
    volume = figures.get("printed_volume_cm3")
    for rel in (f for f in files if f.endswith(".3mf")):
        path = build.path(rel)
        if path is not None:
            yield from _per_file(rel, "3mf", lambda: printed_findings(path, stls, volume, rel))


CHECKERS: dict[str, Callable[[Build], Iterator[Finding]]] = {
    "step": _step, "stl": _stl, "templates": _drawings, "pdf": _pdfs, "cam": _cam, "printed": _printed}
