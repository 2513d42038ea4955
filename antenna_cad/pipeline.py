"""The one orchestration: spec → design → plan → fabrication plan → model → files.

:func:`prepare` is everything before CAD (``validate`` runs exactly it, so it rejects what ``build``
would). :func:`build` keeps these promises (DESIGN.md "Outputs", issue 11):

- the output folder is checked (:func:`check_output`) before any synthesis;
- one build at a time per output folder: the folder is locked (``flock``, released by the kernel
  even on SIGKILL) and a second build waits for the first;
- files are written into ``.<name>.tmp-<pid>`` beside the target and swapped into place atomically
  (``renameat2(RENAME_EXCHANGE)`` on Linux), so a build killed at any moment leaves the previous build
  under its own name; leftovers of killed runs (``.<name>.tmp-*``/``.old-*``) are removed by the next.
"""

from __future__ import annotations

import ctypes
import errno
import fcntl
import os
import shutil
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager, suppress
from dataclasses import asdict, dataclass, field
from pathlib import Path

from antenna_cad.limits import counts, limit_checks
from antenna_cad.registry import adapter
from antenna_cad.spec.common import SpecBase, resolve_material
from antenna_cad.synthesis.checks import Check, solving

Progress = Callable[[str, float], None]
STAGES = ("synthesize", "fabricate", "model", "verify", "step", "stl", "templates", "report", "manifest")
IN_PROGRESS: set[Path] = set()      # temporary folders being written (removed on Ctrl-C by the CLI)


class OutputError(ValueError):
    """The output folder cannot take the build (one line: path and reason)."""


@dataclass
class Plan:
    """Everything a build decides before CAD: design, layup plan, box panels, fabrication plan."""
    design: object
    layup: object
    panels: tuple
    fab: object
    checks: list[Check]


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


def prepare(spec: SpecBase) -> Plan:
    """Synthesis, layup plan, resource limits, fabrication plan and its checks — no CAD. Numerical
    failures become DesignError naming the spec block (:func:`solving`), limits raise above hard."""
    kind = adapter(spec.kind)
    with solving(_design_field(spec), "synthesis"):
        design = kind.synthesize(spec)
    checks = list(design.checks)
    with solving("fabrication", "fabrication plan"):
        layup, panels = kind.plan(spec, design)
        checks += limit_checks(counts(design, layup))
        fab = kind.fabricate(spec, design, layup, panels)
        checks += limit_checks({k: v for k, v in counts(design, layup, fab).items() if k in ("pieces", "drawings")})
        checks += list(kind.fabrication_checks(spec, design, layup)) + list(fab.checks)
    return Plan(design, layup, panels, fab, checks)


def _design_field(spec: SpecBase) -> str:
    """The spec block(s) holding a kind's design numbers: ``design``, or the kind's own blocks."""
    if hasattr(spec, "design"):
        return "design"
    return ", ".join(k for k in type(spec).model_fields if k not in SpecBase.model_fields and k != "kind")


def check_output(out_root: Path, name: str) -> None:
    """OutputError unless ``out_root/name`` can be written, checked without writing anything: the root
    a folder (or absent in an existing folder), writable (probed with a file created and removed), and
    ``name`` absent or an earlier build's folder."""
    if out_root.exists() and not out_root.is_dir():
        raise OutputError(f"{out_root}: exists and is not a folder (-o names the folder that gets <name>/)")
    home = out_root if out_root.is_dir() else out_root.parent
    if not home.is_dir():
        raise OutputError(f"{out_root}: its parent folder {home} does not exist")
    try:
        fd, probe = tempfile.mkstemp(prefix=".make-lens-probe-", dir=home)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        raise OutputError(f"{home}: cannot write into the folder ({exc.strerror})") from None
    final = out_root / name
    if final.is_symlink() or final.exists() and not final.is_dir():
        raise OutputError(f"{final}: exists and is not a build folder; move it or choose another -o")
    if final.is_dir() and any(final.iterdir()) and not (final / "manifest.json").is_file():
        raise OutputError(f"{final}: a folder that is not a make-lens build (no manifest.json) — it would be "
                          "replaced; move it or choose another -o")


def build(spec: SpecBase, out_root: Path, progress: Progress | None = None, plan: Plan | None = None) -> BuildResult:
    """Build every artifact of ``spec`` into ``out_root/<name>/`` atomically (``plan``: from
    :func:`prepare`, when the caller has it already). The writers (CAD, DXF, PDF, plots) are imported
    here, not with the module, so ``validate`` stays free of them."""
    from antenna_cad.export.forked import Job
    from antenna_cad.export.gltf import write_view
    from antenna_cad.export.report import write_report
    from antenna_cad.export.step import write_step
    from antenna_cad.export.template_files import template_files, write_templates
    from antenna_cad.fabrication.cutlist import cutlist_csv
    report = progress or (lambda stage, fraction: None)
    seconds: dict[str, float] = {}
    clock = time.perf_counter()

    def stage(name: str) -> None:
        nonlocal clock
        now = time.perf_counter()
        seconds[name] = now - clock
        clock = now
        report(name, (STAGES.index(name) + 1) / len(STAGES))

    check_output(out_root, spec.name)
    kind = adapter(spec.kind)
    p = plan or prepare(spec)
    stage("synthesize")
    stage("fabricate")
    created = not out_root.exists()
    out_root.mkdir(exist_ok=True)
    done = False
    with _locked(out_root, report):
        _remove_leftovers(out_root, spec.name)
        final = out_root / spec.name
        tmp = out_root / f".{spec.name}.tmp-{os.getpid()}"
        IN_PROGRESS.add(tmp)
        jobs: dict[str, Job] = {}
        try:
            tmp.mkdir()
            if spec.outputs.templates and p.fab.drawings:   # templates and STEP: child processes beside the
                # model, verification, STL, cut list and report (templates need only the fabrication plan)
                jobs["templates"] = Job(write_templates, (spec, p.fab, tmp), template_files(spec, p.fab, tmp))
            with solving(_design_field(spec), "solid model"):
                model = kind.model(spec, p.design, p.layup, p.panels)
            checks = p.checks + list(model.checks)
            stage("model")
            if spec.outputs.step:     # the STEP needs only the model: written beside verification, STL, report
                step_file = tmp / f"{spec.name}.step"
                jobs["step"] = Job(write_step, (model, spec.name, step_file), [step_file])
            with solving(_design_field(spec), "as-built verification"):
                verification = kind.verify(spec, p.design, p.layup, p.fab)
            checks += list(verification.checks)
            stage("verify")
            figures = kind.summary(spec, p.design, p.layup)
            stage("step")
            parts = _write_solids(spec, model, tmp, stage)
            stage("templates")
            (tmp / "cutlist.csv").write_text(cutlist_csv(list(p.fab.rows), p.fab.totals_kg), encoding="utf-8")
            for file_name, text in (p.fab.files | verification.files).items():
                (tmp / file_name).parent.mkdir(parents=True, exist_ok=True)
                (tmp / file_name).write_text(text, encoding="utf-8")
            if spec.outputs.step or spec.outputs.report:    # the assembly for viewing: beside the STEP, in the report
                view = write_view(tmp / f"{spec.name}.glb", model)
            if spec.outputs.report:
                write_report(tmp, spec, figures, checks, verification, p.fab, parts, view)
            stage("report")
            values = {}
            for name in list(jobs):                   # the waits: what each child adds to the build
                values[name] = jobs.pop(name).finish()
                seconds[name] += time.perf_counter() - clock
                clock = time.perf_counter()
            templates = values.get("templates", [])
            _write_manifest(spec, tmp, figures, checks, parts, p.layup, p.fab, templates, verification)
            stage("manifest")
            _swap_into_place(tmp, final)
            done = True
        except OSError as exc:
            raise OutputError(f"{out_root}: writing the build failed ({exc.strerror or exc}); "
                              "the previous build is untouched") from None
        finally:
            for job in jobs.values():
                job.finish(wait=False)
            shutil.rmtree(tmp, ignore_errors=True)
            IN_PROGRESS.discard(tmp)
            if created and not done:                    # a failed first build leaves no folder behind
                with suppress(OSError):
                    out_root.rmdir()
    files = sorted(q.relative_to(final).as_posix() for q in final.rglob("*") if q.is_file())
    return BuildResult(spec.name, spec.kind, final, figures, checks, dict(p.fab.totals_kg), dict(p.fab.boards),
                       files, seconds, dict(verification.figures))


@contextmanager
def _locked(out_root: Path, report: Progress) -> Iterator[None]:
    """Hold an exclusive lock on the output folder; wait (reporting it) while another build has it."""
    fd = os.open(out_root, os.O_RDONLY | os.O_DIRECTORY)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            report(f"waiting for another build writing into {out_root}", 0.0)
            fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def _remove_leftovers(out_root: Path, name: str) -> None:
    """Temporary and displaced folders of killed runs of ``name`` (safe: the folder lock is held). A
    displaced old build whose replacement never arrived is put back first."""
    final = out_root / name
    for old in sorted(out_root.glob(f".{name}.old-*")):
        if not final.exists() and old.is_dir():
            old.rename(final)
    for entry in list(out_root.glob(f".{name}.tmp-*")) + list(out_root.glob(f".{name}.old-*")):
        try:
            shutil.rmtree(entry) if entry.is_dir() and not entry.is_symlink() else entry.unlink()
        except OSError as exc:
            raise OutputError(f"{entry}: cannot remove this leftover of an earlier run ({exc.strerror})") from None


def _write_solids(spec, model, out: Path, stage) -> list[dict]:
    from antenna_cad.export.mesh import write_stl
    from antenna_cad.geometry import kernel
    parts = []
    if spec.outputs.stl:
        (out / "stl").mkdir()
    for part in sorted(model.parts, key=lambda p: p.label):
        entry = {"label": part.label, "material": part.material.name, "role": part.role,
                 "volume_mm3": part.volume_mm3, "solids": len(kernel.solids(part.shape)),
                 "valid": part.is_valid()}
        if spec.outputs.stl:
            mesh = write_stl(part.shape, out / "stl" / f"{part.label}.stl", spec.outputs.mesh_tolerance_mm,
                             part.prism)
            entry |= {"file": f"stl/{part.label}.stl", "triangles": len(mesh.faces),
                      "mesher": mesh.metadata["mesher"], "watertight": mesh.metadata["watertight"],
                      "bodies": mesh.metadata["bodies"], "bodies_watertight": mesh.metadata["bodies_watertight"]}
        parts.append(entry)
    stage("stl")
    return parts


def _write_manifest(spec, out: Path, figures, checks, parts, layup, fab, templates, verification) -> None:
    from antenna_cad.export.manifest import write_manifest
    from antenna_cad.export.mesh import ANGULAR_DEFLECTION_RAD
    from antenna_cad.fabrication.outline import CHORD_TOL_MM
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
        "templates": templates,
    }
    sheet_files = {t["label"]: t["dxf"] for t in templates if "dxf" in t}
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
    """``tmp`` becomes ``final``; an earlier ``final`` ends in ``tmp`` (removed by the caller). Atomic
    exchange where the kernel has it; otherwise two renames, the displaced build named ``.old-<pid>``
    so that the next run restores it should this one die in between."""
    if not final.exists():
        tmp.rename(final)
        return
    if _exchange(tmp, final):
        return
    old = final.with_name(f".{final.name}.old-{os.getpid()}")
    final.rename(old)
    tmp.rename(final)
    shutil.rmtree(old, ignore_errors=True)


_RENAME_EXCHANGE, _AT_FDCWD = 2, -100


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths atomically (Linux renameat2); False where unsupported."""
    fn = getattr(ctypes.CDLL(None, use_errno=True), "renameat2", None)
    if fn is None:
        return False
    if fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP):
        return False
    raise OSError(err, os.strerror(err), str(b))
