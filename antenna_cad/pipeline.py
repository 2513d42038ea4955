"""The one orchestration: spec → design → plan → fabrication plan → model → files.

:func:`prepare` is everything before CAD (``validate`` runs exactly it, so it rejects what ``build``
would). :func:`build` keeps these promises (DESIGN.md "Outputs"):

- the output folder is checked (:func:`check_output`) before any synthesis, and again just before the
  swap: a folder that appeared at the target meanwhile and is not a build is never replaced;
- files are written into ``.<name>.tmp-<pid>`` beside the target and swapped into place atomically
  (``renameat2(RENAME_EXCHANGE)`` on Linux), so a build killed at any moment leaves the previous build
  under its own name; leftovers of killed runs (``.<name>.tmp-<pid>``/``.old-<pid>``) are removed by the next;
- only the clean-up, the re-check and the swap hold the output folder's lock (``flock``, released by
  the kernel even on SIGKILL), so builds of different specs into one folder run in parallel and two
  builds of one spec end in one complete build; a temporary folder is locked by its own build while
  it is written, so no other build takes it for a leftover.
"""

from __future__ import annotations

import ctypes
import errno
import fcntl
import glob
import os
import re
import shutil
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from dataclasses import asdict, dataclass, field
from pathlib import Path

from antenna_cad.fullwave.budget import session as fullwave_session
from antenna_cad.limits import counts, limit_checks, template_pages
from antenna_cad.progress import Progress, reporting
from antenna_cad.registry import adapter
from antenna_cad.spec.common import SpecBase, resolve_material
from antenna_cad.stages import planning
from antenna_cad.synthesis.checks import Check, solving

STAGES = ("synthesize", "fabricate", "model", "verify", "step", "stl", "templates", "report", "manifest")
IN_PROGRESS: set[Path] = set()      # temporary folders being written (removed on Ctrl-C by the CLI)
PLACED: list[Path] = []             # the build folder once swapped into place (complete whatever follows)


class OutputError(ValueError):
    """The output folder cannot take the build (one line: path and reason)."""


@dataclass
class Plan:
    """Everything a build decides before CAD: design, layup plan, box panels, fabrication plan;
    ``cad``: made for the CAD stage (False: by the CAD-free validate, :mod:`antenna_cad.stages`)."""
    design: object
    layup: object
    panels: tuple
    fab: object
    checks: list[Check]
    cad: bool = True


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


def prepare(spec: SpecBase, cad: bool = True) -> Plan:
    """Synthesis, layup plan, resource limits, fabrication plan and its checks — no CAD (``cad``
    False: nor a fabrication plan that is a mesh, :mod:`antenna_cad.stages`). Numerical failures
    become DesignError naming the spec block (:func:`solving`), limits raise above hard."""
    kind = adapter(spec.kind)
    with solving(_design_field(spec), "synthesis"):
        design = kind.synthesize(spec)
    checks = list(design.checks)
    with solving("fabrication", "fabrication plan"):
        layup, panels = kind.plan(spec, design)
        checks += limit_checks(counts(design, layup))
        with planning(cad):
            fab = kind.fabricate(spec, design, layup, panels)
        checks += limit_checks({k: v for k, v in counts(design, layup, fab).items() if k in ("pieces", "drawings")})
        if spec.outputs.templates and len(fab.drawings):
            checks += limit_checks({"pages": template_pages(fab.drawings)})
        checks += list(kind.fabrication_checks(spec, design, layup)) + list(fab.checks)
    return Plan(design, layup, panels, fab, checks, cad)


def solid_checks(spec: SpecBase, plan: Plan) -> list[Check]:
    """What the CAD stage can refuse, for ``validate``: the solid model built (in memory, nothing
    written), its checks and :func:`mesh_checks`."""
    with solving(_design_field(spec), "solid model"):
        model = adapter(spec.kind).model(spec, plan.design, plan.layup, plan.panels)
    return list(model.checks) + mesh_checks(spec, model)


def mesh_checks(spec: SpecBase, model) -> list[Check]:
    """The STL triangles of every part, estimated before any meshing (BRepMesh cannot be stopped
    once started): a part over ``MAX_TRIANGLES`` or a build over the hard limit is refused naming
    ``outputs.mesh_tolerance_mm``; above the soft limit a warning check."""
    if not spec.outputs.stl:
        return []
    from antenna_cad.export.mesh import part_triangles, within_limit
    tolerance = spec.outputs.mesh_tolerance_mm
    total = sum(within_limit(part_triangles(part.shape, tolerance, part.prism), tolerance, f"part {part.label}")
                for part in model.parts)
    return limit_checks({"triangles": total})


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
        blocker = next((p for p in (home, *home.parents) if p.exists() and not p.is_dir()), None)
        if blocker is not None:
            raise OutputError(f"{out_root}: {blocker} is a file, not a folder")
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
    :func:`prepare`, when the caller has it already). ``progress(stage, fraction, detail="")`` is
    called as each stage of :data:`STAGES` starts (``"done"`` at the end), from inside a stage with
    what it is doing (the verification's :func:`antenna_cad.progress.report`), and with stage
    ``"waiting"`` while another build holds the folder. The writers (CAD, DXF, PDF, plots) are
    imported here, not with the module, so ``validate`` stays free of them."""
    from antenna_cad.cam.preview import cam_report
    from antenna_cad.export.forked import Job
    from antenna_cad.export.gltf import write_view
    from antenna_cad.export.report import write_report
    from antenna_cad.export.step import write_step
    from antenna_cad.export.template_files import template_files, write_templates
    from antenna_cad.fabrication.cutlist import cutlist_csv
    report = progress or (lambda stage, fraction, detail="": None)
    seconds: dict[str, float] = {}
    clock = time.perf_counter()

    def stage(name: str) -> None:
        """``name`` is done; the next stage starts."""
        nonlocal clock
        now = time.perf_counter()
        seconds[name] = now - clock
        clock = now
        i = STAGES.index(name) + 1
        report(STAGES[i] if i < len(STAGES) else "done", i / len(STAGES))

    def inside(name: str):
        """Reports from inside stage ``name`` (its share of the build), their stage named in the detail."""
        i = STAGES.index(name)
        return lambda sub, fraction, detail="": report(
            name, (i + min(max(fraction, 0.0), 1.0)) / len(STAGES), f"{sub}: {detail}" if detail else sub)

    PLACED.clear()
    report(STAGES[0], 0.0)
    check_output(out_root, spec.name)
    kind = adapter(spec.kind)
    p = plan if plan is not None and plan.cad else prepare(spec)     # a CAD-free plan lacks its meshes
    stage("synthesize")
    stage("fabricate")
    created = not out_root.exists()
    out_root.mkdir(exist_ok=True)
    final = out_root / spec.name
    tmp = out_root / f".{spec.name}.tmp-{os.getpid()}"
    done = kept = False
    tmp_lock = None
    jobs: dict[str, Job] = {}
    try:
        with _locked(out_root, report, "model"):    # no other build cleans up while ours is created
            _remove_leftovers(out_root, spec.name)
            tmp.mkdir()
            IN_PROGRESS.add(tmp)
            tmp_lock = _lock_folder(tmp)
        if spec.outputs.templates and p.fab.drawings:   # templates and STEP: child processes beside the
            # model, verification, STL, cut list and report (templates need only the fabrication plan)
            jobs["templates"] = Job(write_templates, (spec, p.fab, tmp), template_files(spec, p.fab, tmp))
        with solving(_design_field(spec), "solid model"):
            model = kind.model(spec, p.design, p.layup, p.panels)
        checks = p.checks + list(model.checks) + mesh_checks(spec, model)
        stage("model")
        if spec.outputs.step:     # the STEP needs only the model: written beside verification, STL, report
            step_file = tmp / f"{spec.name}.step"
            jobs["step"] = Job(write_step, (model, spec.name, step_file), [step_file])
        verifying = STAGES.index("verify")          # full-wave heartbeats: fraction of its budget used
        with solving(_design_field(spec), "as-built verification"), reporting(inside("verify")), fullwave_session(
                lambda used, detail: report("verify", (verifying + used) / len(STAGES), detail)):
            verification = kind.verify(spec, p.design, p.layup, p.fab)
        checks += list(verification.checks)
        if getattr(p.fab, "cam", None) is not None:           # the toolpaths' order, times and previews
            verification = verification.merged(cam_report(p.fab.cam))
        stage("verify")
        figures = kind.summary(spec, p.design, p.layup)
        stage("step")
        parts = _write_solids(spec, model, tmp, stage)
        stage("templates")
        (tmp / "cutlist.csv").write_text(cutlist_csv(list(p.fab.rows), p.fab.totals_kg), encoding="utf-8")
        for file_name, text in (p.fab.files | verification.files).items():
            (tmp / file_name).parent.mkdir(parents=True, exist_ok=True)
            if isinstance(text, bytes):                   # printed parts: 3MF and binary STL
                (tmp / file_name).write_bytes(text)
            else:
                (tmp / file_name).write_text(text, encoding="utf-8")
        if spec.outputs.step or spec.outputs.report:    # the assembly for viewing: beside the STEP, in the report
            view = write_view(tmp / f"{spec.name}.glb", model)
        if spec.outputs.report:
            write_report(tmp, spec, figures, checks, verification, p.fab, parts, view)
        stage("report")
        values = {}
        for name in list(jobs):                   # the waits: what each child adds to the build
            report("manifest", (len(STAGES) - 1) / len(STAGES), f"waiting for the {name} writer")
            values[name] = jobs.pop(name).finish()
            seconds[name] += time.perf_counter() - clock
            clock = time.perf_counter()
        templates = values.get("templates", [])
        _write_manifest(spec, tmp, figures, checks, parts, p.layup, p.fab, templates, verification)
        with _locked(out_root, report, "manifest"):
            kept = not _is_replaceable(final)
            if kept:
                raise OutputError(f"{final}: appeared during the build and is not a make-lens build (no "
                                  f"manifest.json), so it was not replaced; the new build is in {tmp} — rename "
                                  "it to keep it (the next build into this folder removes it)")
            _swap_into_place(tmp, final)
            IN_PROGRESS.discard(tmp)
            PLACED.append(final)
        done = True
        stage("manifest")
    except OSError as exc:
        where = f" writing {Path(exc.filename).name}" if exc.filename else ""
        kept_note = "the previous build is untouched" if final.exists() else "nothing was written"
        raise OutputError(f"{out_root}: writing the build failed ({exc.strerror or exc}{where}); {kept_note}") from None
    finally:
        for job in jobs.values():
            job.finish(wait=False)
        if tmp_lock is not None:
            os.close(tmp_lock)
        if not kept:
            shutil.rmtree(tmp, ignore_errors=True)   # this build's leftovers, or the displaced old build
        IN_PROGRESS.discard(tmp)
        if created and not done and not kept:       # a failed first build leaves no folder behind
            with suppress(OSError):
                out_root.rmdir()
    files = sorted(q.relative_to(final).as_posix() for q in final.rglob("*") if q.is_file())
    return BuildResult(spec.name, spec.kind, final, figures, checks, dict(p.fab.totals_kg), dict(p.fab.boards),
                       files, seconds, dict(verification.figures))


def _is_replaceable(final: Path) -> bool:
    """The target may be replaced: absent, an empty folder, or an earlier build (has manifest.json)."""
    if final.is_symlink() or (final.exists() and not final.is_dir()):
        return False
    return not final.exists() or not any(final.iterdir()) or (final / "manifest.json").is_file()


def _lock_folder(folder: Path) -> int:
    """An open descriptor holding ``folder``'s exclusive lock (the caller closes it to release)."""
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    return fd


@contextmanager
def _locked(out_root: Path, report: Progress, stage: str) -> Iterator[None]:
    """Hold an exclusive lock on the output folder; while another build has it, wait, reported at
    once as stage ``waiting`` (then ``stage`` again)."""
    fd = os.open(out_root, os.O_RDONLY | os.O_DIRECTORY)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            report("waiting", STAGES.index(stage) / len(STAGES), f"for another build writing into {out_root}")
            fcntl.flock(fd, fcntl.LOCK_EX)
            report(stage, STAGES.index(stage) / len(STAGES))
        yield
    finally:
        os.close(fd)


def _leftovers(out_root: Path, name: str, kind: str) -> list[Path]:
    """``.<name>.<kind>-<pid>`` entries: exactly this spec's (the spec ``a.old-1`` is not ``a``'s leftover)."""
    pattern = re.compile(rf"\.{re.escape(name)}\.{kind}-\d+")
    return sorted(p for p in out_root.glob(f".{glob.escape(name)}.{kind}-*") if pattern.fullmatch(p.name))


def _remove_leftovers(out_root: Path, name: str) -> None:
    """Temporary and displaced folders of killed runs of ``name`` (the folder lock is held, so every
    ``.old-*`` is a dead run's; a ``.tmp-*`` still locked by its build is left alone). A displaced old
    build whose replacement never arrived is put back first."""
    final = out_root / name
    for old in _leftovers(out_root, name, "old"):
        if not final.exists() and old.is_dir() and not old.is_symlink():
            old.rename(final)
    for entry in _leftovers(out_root, name, "tmp") + _leftovers(out_root, name, "old"):
        try:
            if entry.is_dir() and not entry.is_symlink():
                try:
                    os.close(_lock_folder(entry))
                except BlockingIOError:
                    continue                         # a build writing it now
                shutil.rmtree(entry)
            else:
                entry.unlink()
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
    if getattr(fab, "cam", None) is not None:
        content["cam"] = list(fab.cam.entries)
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
    exchange where the kernel has it (and a rename that never replaces what appeared meanwhile);
    otherwise two renames, the displaced build named ``.old-<pid>`` so that the next run restores it
    should this one die in between."""
    if not final.exists():
        if not _rename2(tmp, final, _RENAME_NOREPLACE):
            tmp.rename(final)
        return
    if _rename2(tmp, final, _RENAME_EXCHANGE):
        return
    old = final.with_name(f".{final.name}.old-{os.getpid()}")
    final.rename(old)
    tmp.rename(final)
    shutil.rmtree(old, ignore_errors=True)


_RENAME_NOREPLACE, _RENAME_EXCHANGE, _AT_FDCWD = 1, 2, -100


def _rename2(a: Path, b: Path, flags: int) -> bool:
    """Linux renameat2 of ``a`` to ``b`` with ``flags``; False where unsupported."""
    fn = getattr(ctypes.CDLL(None, use_errno=True), "renameat2", None)
    if fn is None:
        return False
    if fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), flags) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP):
        return False
    raise OSError(err, os.strerror(err), str(b))
