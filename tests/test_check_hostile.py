"""``make-lens check`` does not trust the manifest: paths out of the folder, emptied lists, deleted
files with their entries, content changed and the manifest re-signed, broken files and manifests —
each a failed row (exit 1) or not a build (exit 2), never a pass and never a traceback."""

import hashlib
import json
import re
import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from antenna_cad.cli import app
from antenna_cad.export.check import check_build

ROOT = Path(__file__).resolve().parents[1]
NAME = "ptfe-lens-120mm"
runner = CliRunner()


@pytest.fixture
def build(recipe_build, tmp_path) -> Path:
    """A fresh copy of the PTFE lens build (made once per session)."""
    return shutil.copytree(recipe_build(ROOT / "recipes" / f"{NAME}.yaml").out_dir, tmp_path / NAME)


def _manifest(folder: Path) -> dict:
    return json.loads((folder / "manifest.json").read_text())


def _resign(folder: Path, manifest: dict | None = None) -> None:
    """Rewrite the manifest with the sizes and sha256 of the files its ``files`` list names (as a
    forger would), keeping any entry whose file is not in the folder."""
    manifest = manifest or _manifest(folder)
    for entry in manifest["files"]:
        path = folder / entry["path"]
        if path.is_file():
            entry["bytes"], entry["sha256"] = path.stat().st_size, hashlib.sha256(path.read_bytes()).hexdigest()
    (folder / "manifest.json").write_text(json.dumps(manifest))


def _failed(folder: Path) -> set[tuple[str, str]]:
    result = runner.invoke(app, ["check", str(folder)])
    assert result.exit_code == 1 and (result.exception is None or isinstance(result.exception, SystemExit)), result.output
    return {(f.file, f.check) for f in check_build(folder) if not f.ok}


def test_intact_build_passes(build):
    result = runner.invoke(app, ["check", str(build)])
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize("path", ["../../../../etc/passwd", "/etc/passwd", "stl/../../outside.txt"])
def test_paths_out_of_the_folder_are_not_read(build, path):
    secret = Path("/etc/passwd").read_bytes()
    (build.parent / "outside.txt").write_bytes(secret)
    manifest = _manifest(build)
    manifest["files"].append({"path": path, "bytes": len(secret), "sha256": hashlib.sha256(secret).hexdigest()})
    (build / "manifest.json").write_text(json.dumps(manifest))
    assert (path, "confined") in _failed(build)


def test_a_symlink_in_the_folder_fails(build):
    (build / "templates" / "link.txt").symlink_to("/etc/passwd")
    assert ("templates/link.txt", "regular files") in _failed(build)


def test_deleted_step_with_its_entry_fails(build):
    (build / f"{NAME}.step").unlink()
    manifest = _manifest(build)
    manifest["files"] = [e for e in manifest["files"] if e["path"] != f"{NAME}.step"]
    _resign(build, manifest)
    assert (f"{NAME}.step", "required") in _failed(build)


def test_everything_deleted_and_lists_emptied_fails(build):
    manifest = _manifest(build)
    for entry in manifest["files"]:
        (build / entry["path"]).unlink()
    manifest |= {"files": [], "parts": [], "templates": [], "pieces": []}
    (build / "manifest.json").write_text(json.dumps(manifest))
    failed = _failed(build)
    assert ("manifest.json", "required") in failed and ("cutlist.csv", "required") in failed


def _scale_numbers(text: str, pattern: str, factor: float) -> str:
    return re.sub(pattern, lambda m: m.group(1) + repr(float(m.group(2)) * factor), text)


@pytest.mark.parametrize("file,change,check", [
    (f"{NAME}.step", lambda t: _scale_numbers(t, r"(CARTESIAN_POINT\('',\()(-?[\d.]+(?:E[-+]?\d+)?)", 1.05),
     "step volumes"),
    ("templates/profile.dxf", lambda t: re.sub(r"(\n 10\n)(-?[\d.]+)", lambda m: f"{m.group(1)}{float(m.group(2)) * 1.05}",
                                               t), "dxf outline"),
    ("templates/profile.svg", lambda t: re.sub(r'points="([^"]*)"', lambda m: 'points="' + " ".join(
        f"{float(x) * 1.05:g},{y}" for x, y in (p.split(",") for p in m.group(1).split())) + '"', t), "svg outline"),
])
def test_content_changed_and_resigned_fails(build, file, change, check):
    path = build / file
    changed = change(path.read_text())
    assert changed != path.read_text()
    path.write_text(changed)
    _resign(build)
    assert (file, check) in _failed(build)


def test_pdfs_changed_and_resigned_fail(build):
    import pypdfium2
    blank = pypdfium2.PdfDocument.new()
    blank.new_page(595.28, 841.89)
    blank.save(build / "report.pdf")
    blank.close()
    shutil.copy(build / "report.pdf", build / "templates" / f"{NAME}-templates.pdf")
    _resign(build)
    failed = _failed(build)
    assert ("report.pdf", "pdf content") in failed
    assert {(f"templates/{NAME}-templates.pdf", c) for c in ("pdf check bar", "pdf content")} <= failed


def test_broken_files_are_failed_rows(build):
    pdf = build / "report.pdf"
    pdf.write_bytes(pdf.read_bytes()[:2000])
    svg = build / "templates" / "profile.svg"
    svg.write_bytes(svg.read_bytes().replace(b"<title>", b"<title>\xff", 1))
    stl = build / "stl" / "lens.stl"
    stl.write_bytes(stl.read_bytes()[:50])
    _resign(build)
    failed = _failed(build)
    assert {("report.pdf", "pdf"), ("templates/profile.svg", "svg"), ("stl/lens.stl", "stl")} <= failed


@pytest.mark.parametrize("text", ["[]", '"a string"', "3", '{"name": "x", "parts": []}', "{}",
                                  '{"name": "x", "kind": "collimator", "files": "nope"}'])
def test_malformed_manifests_are_not_builds(build, text):
    (build / "manifest.json").write_text(text)
    result = runner.invoke(app, ["check", str(build)])
    assert result.exit_code == 2 and isinstance(result.exception, SystemExit), result.output
    (line,) = result.output.strip().splitlines()
    assert line.startswith(f"{build}/manifest.json: ")


def test_manifest_without_a_key_is_not_a_build(build):
    manifest = _manifest(build)
    del manifest["tolerances"]
    (build / "manifest.json").write_text(json.dumps(manifest))
    result = runner.invoke(app, ["check", str(build)])
    assert result.exit_code == 2 and "tolerances" in result.output
