"""The one orchestration: spec → design → plan → model → fabrication plan → files.

``build`` writes into a temporary folder beside the target and renames it into place at the end,
so a failed or interrupted run leaves the previous build untouched (DESIGN.md "Outputs").
"""

from __future__ import annotations

import os
import shutil
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path

from antenna_cad.export.manifest import write_manifest
from antenna_cad.export.report import write_report
from antenna_cad.export.mesh import ANGULAR_DEFLECTION_RAD, write_stl
from antenna_cad.export.step import write_step
from antenna_cad.fabrication.cutlist import cutlist_csv
from antenna_cad.fabrication.outline import CHORD_TOL_MM
from antenna_cad.fabrication.templates import dxf_document, write_dxf, write_svg, write_tiled_pdf
from antenna_cad.registry import adapter, synthesize
from antenna_cad.spec.common import SpecBase, resolve_material
from antenna_cad.synthesis.checks import Check

Progress = Callable[[str, float], None]
STAGES = ("synthesize", "model", "fabricate", "verify", "step", "stl", "templates", "report", "manifest")


@dataclass
class BuildResult:
    name: str
    kind: str
    out_dir: Path
    figures: dict[str, float]
    checks: list[Check]
    masses_kg: dict[str, float]
    boards: dict[str, int]
    files: list[str]
    seconds: dict[str, float] = field(default_factory=dict)
    verified: dict[str, float] = field(default_factory=dict)

    @property
    def status(self) -> str:
        statuses = {c.status for c in self.checks}
        return "fail" if "fail" in statuses else ("warn" if "warn" in statuses else "pass")


def build(spec: SpecBase, out_root: Path, progress: Progress | None = None) -> BuildResult:
    """Build every artifact of ``spec`` into ``out_root/<name>/`` atomically."""
    report = progress or (lambda stage, fraction: None)
    seconds: dict[str, float] = {}
    clock = time.perf_counter()

    def stage(name: str) -> None:
        nonlocal clock
        now = time.perf_counter()
        seconds[name] = now - clock
        clock = now
        report(name, (STAGES.index(name) + 1) / len(STAGES))

    kind = adapter(spec.kind)
    design, checks = synthesize(spec)
    layup, panels = kind.plan(spec, design)
    stage("synthesize")
    model = kind.model(spec, design, layup, panels)
    checks += list(model.checks)
    stage("model")
    fab = kind.fabricate(spec, design, layup, panels)
    checks += list(kind.fabrication_checks(spec, design, layup)) + list(fab.checks)
    stage("fabricate")
    verification = kind.verify(spec, design, layup, fab)
    checks += list(verification.checks)
    stage("verify")

    out_root.mkdir(parents=True, exist_ok=True)
    final = out_root / spec.name
    tmp = out_root / f".{spec.name}.tmp-{os.getpid()}"
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir()
    try:
        parts = _write_solids(spec, model, tmp, stage)
        sheet_files = _write_templates(spec, fab, tmp)
        stage("templates")
        (tmp / "cutlist.csv").write_text(cutlist_csv(list(fab.rows), fab.totals_kg), encoding="utf-8")
        for file_name, text in (fab.files | verification.files).items():
            (tmp / file_name).parent.mkdir(parents=True, exist_ok=True)
            (tmp / file_name).write_text(text, encoding="utf-8")
        figures = kind.summary(spec, design, layup)
        if spec.outputs.report:
            write_report(tmp, spec, figures, checks, verification, model, fab, parts)
        stage("report")
        _write_manifest(spec, tmp, figures, checks, parts, layup, fab, sheet_files, verification)
        stage("manifest")
        _swap_into_place(tmp, final)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    files = sorted(p.relative_to(final).as_posix() for p in final.rglob("*") if p.is_file())
    return BuildResult(spec.name, spec.kind, final, figures, checks, dict(fab.totals_kg), dict(fab.boards),
                       files, seconds, dict(verification.figures))


def _write_solids(spec, model, out: Path, stage) -> list[dict]:
    if spec.outputs.step:
        write_step(model, spec.name, out / f"{spec.name}.step")
    stage("step")
    parts = []
    if spec.outputs.stl:
        (out / "stl").mkdir()
    for part in sorted(model.parts, key=lambda p: p.label):
        entry = {"label": part.label, "material": part.material.name, "role": part.role,
                 "volume_mm3": part.volume_mm3, "valid": bool(part.shape.is_valid)}
        if spec.outputs.stl:
            mesh = write_stl(part.shape, out / "stl" / f"{part.label}.stl", spec.outputs.mesh_tolerance_mm)
            entry |= {"file": f"stl/{part.label}.stl", "triangles": len(mesh.faces),
                      "mesher": mesh.metadata["mesher"],
                      "watertight": bool(mesh.is_watertight)}
        parts.append(entry)
    stage("stl")
    return parts


def _write_templates(spec, fab, out: Path) -> dict[str, str]:
    """DXF + SVG per drawing and one tiled PDF; returns drawing label → DXF path."""
    if not spec.outputs.templates or not fab.drawings:
        return {}
    folder = out / "templates"
    folder.mkdir()
    files = {}
    for drawing in fab.drawings:
        write_dxf(dxf_document(drawing), folder / f"{drawing.label}.dxf")
        write_svg(drawing, folder / f"{drawing.label}.svg")
        files[drawing.label] = f"templates/{drawing.label}.dxf"
    write_tiled_pdf(list(fab.drawings), folder / f"{spec.name}-templates.pdf", spec.name)
    return files


def _write_manifest(spec, out: Path, figures, checks, parts, layup, fab, sheet_files, verification) -> None:
    material = resolve_material(spec.material)
    content = {
        "name": spec.name, "kind": spec.kind, "spec": spec.model_dump(mode="json"),
        "material": asdict(material), "figures": figures,
        "tolerances": {"mesh_tolerance_mm": spec.outputs.mesh_tolerance_mm,
                       "mesh_angular_deflection_rad": ANGULAR_DEFLECTION_RAD,
                       "template_chord_tolerance_mm": CHORD_TOL_MM, "kerf_mm": fab.kerf_mm},
        "checks": [asdict(c) for c in checks], "parts": parts,
        "verification": {"figures": verification.figures,
                         "tables": [{"name": t.name, "columns": list(t.columns), "rows": [list(r) for r in t.rows]}
                                    for t in verification.tables]},
        "mass_kg": fab.totals_kg, "boards": fab.boards,
        "pieces": [{"label": r.part, "board": r.board, "assembly_order": r.assembly_order}
                   for r in fab.rows],
    }
    if layup is not None:
        pieces: dict[int, list[str]] = {}
        for piece in fab.pieces:                      # one pass: linear in pieces, not sheets × pieces
            pieces.setdefault(piece.sheet_index, []).append(piece.label)
        content["sheets"] = [
            {"index": s.index, "label": s.label, "z_min_mm": s.z_min_mm, "z_max_mm": s.z_max_mm,
             "radius_mm": s.radius_mm, "material": material.name, "has_neck": s.has_neck,
             "pieces": pieces.get(s.index, []),
             "joints": [asdict(j) for j in fab.joints.get(s.index, ())], "file": sheet_files.get(s.label)}
            | s.manifest_extra()
            for s in layup.sheets]
    write_manifest(out, content)


def _swap_into_place(tmp: Path, final: Path) -> None:
    old = final.with_name(f".{final.name}.old-{os.getpid()}")
    if final.exists():
        final.rename(old)
    tmp.rename(final)
    shutil.rmtree(old, ignore_errors=True)
