"""Build promises: output-folder problems are one line and exit 2 before synthesis; leftovers of
killed runs are cleaned (only this spec's, only dead builds'); SIGKILL at any moment leaves the
previous build complete under its own name; Ctrl-C exits 130 at once, or 0 once the new build is in
place; a folder created at the target during a build is never replaced; builds into one folder run
in parallel and only their swaps are serialised."""

import fcntl
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from antenna_cad import pipeline
from antenna_cad.cli import app

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "recipes" / "ptfe-lens-120mm.yaml"       # the quickest full build (STEP, STL, templates, report)
NAME = "ptfe-lens-120mm"
EXE = shutil.which("make-lens") or str(Path(sys.executable).parent / "make-lens")
runner = CliRunner()


def _one_line_exit_2(args, expected):
    result = runner.invoke(app, args)
    lines = [ln for ln in result.output.splitlines() if ln.strip()]
    assert result.exit_code == 2 and len(lines) == 1 and expected in lines[0], result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)


def test_output_problems_are_one_line_before_synthesis(tmp_path, monkeypatch):
    import antenna_cad.pipeline as pipeline

    def no_synthesis(spec):
        raise AssertionError("synthesis ran before the output folder was checked")
    monkeypatch.setattr(pipeline, "prepare", no_synthesis)
    a_file = tmp_path / "file.txt"
    a_file.write_text("x")
    _one_line_exit_2(["build", str(SPEC), "-o", str(a_file)], f"{a_file}: exists and is not a folder")
    _one_line_exit_2(["build", str(SPEC), "-o", str(tmp_path / "no" / "such")], "does not exist")
    _one_line_exit_2(["build", str(SPEC), "-o", "/proc/make-lens-out"], "/proc: cannot write into the folder")
    (tmp_path / NAME).write_text("not a folder")
    _one_line_exit_2(["build", str(SPEC), "-o", str(tmp_path)], f"{tmp_path / NAME}: exists and is not a build folder")
    (tmp_path / NAME).unlink()
    (tmp_path / NAME).mkdir()
    (tmp_path / NAME / "thesis.tex").write_text("precious")
    _one_line_exit_2(["build", str(SPEC), "-o", str(tmp_path)], "not a make-lens build (no manifest.json)")
    assert (tmp_path / NAME / "thesis.tex").read_text() == "precious"


def test_a_file_in_the_output_path_is_named(tmp_path):
    a_file = tmp_path / "file.txt"
    a_file.write_text("x")
    for out in (a_file / "sub", a_file / "sub" / "deeper"):
        _one_line_exit_2(["build", str(SPEC), "-o", str(out)], f"{out}: {a_file} is a file, not a folder")


def test_leftovers_are_only_this_specs_and_only_dead_builds(tmp_path):
    """Spec ``a`` never adopts or removes what belongs to spec ``a.old-1``; a temporary folder whose
    build still runs (it holds the folder's lock) is kept; a dead build's is removed."""
    other = tmp_path / ".a.old-1.tmp-99"          # spec a.old-1 being written (or killed while writing)
    other.mkdir()
    (other / "half.stl").write_text("half")
    dead, live = tmp_path / ".a.tmp-7", tmp_path / ".a.tmp-8"
    dead.mkdir()
    live.mkdir()
    fd = os.open(live, os.O_RDONLY | os.O_DIRECTORY)
    fcntl.flock(fd, fcntl.LOCK_EX)                # its build is running
    try:
        pipeline._remove_leftovers(tmp_path, "a")
        assert sorted(p.name for p in tmp_path.iterdir()) == [".a.old-1.tmp-99", ".a.tmp-8"]
        assert (other / "half.stl").read_text() == "half"
    finally:
        os.close(fd)
    pipeline._remove_leftovers(tmp_path, "a")
    assert sorted(p.name for p in tmp_path.iterdir()) == [".a.old-1.tmp-99"]


def _complete(folder: Path) -> str:
    """sha256 of the manifest of a complete build in ``folder`` (every file listed matches)."""
    manifest = json.loads((folder / "manifest.json").read_text())
    for entry in manifest["files"]:
        assert hashlib.sha256((folder / entry["path"]).read_bytes()).hexdigest() == entry["sha256"], entry["path"]
    return hashlib.sha256((folder / "manifest.json").read_bytes()).hexdigest()


def _run(out: Path) -> subprocess.Popen:
    return subprocess.Popen([EXE, str(SPEC), "-o", str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True)


@pytest.fixture(scope="module")
def first_build(tmp_path_factory):
    out = tmp_path_factory.mktemp("promises")
    start = time.monotonic()
    done = subprocess.run([EXE, str(SPEC), "-o", str(out)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return out, time.monotonic() - start


@pytest.mark.slow
def test_planted_leftovers_are_removed(first_build):
    out, _ = first_build
    (out / f".{NAME}.tmp-1").mkdir()
    (out / f".{NAME}.tmp-1" / "part.stl").write_text("half")
    (out / f".{NAME}.tmp-{os.getpid()}").write_text("a file where a folder goes")
    (out / f".{NAME}.old-2").mkdir()
    done = subprocess.run([EXE, str(SPEC), "-o", str(out)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in out.iterdir()) == [NAME]
    _complete(out / NAME)


@pytest.mark.slow
def test_sigkill_at_any_moment_keeps_a_complete_build(first_build):
    """Kills spread over the whole build (imports, synthesis, CAD, writing, the swap): after each,
    <name>/ is a complete build (the previous one or, after the swap, the new one); the next build
    removes what the killed ones left."""
    out, seconds = first_build
    before = _complete(out / NAME)
    outcomes = []
    for fraction in (0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.9, 0.95, 0.99, 1.02):
        proc = _run(out)
        time.sleep(seconds * fraction)
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=60)
        outcomes.append(_complete(out / NAME) == before)
    print(f"\n{len(outcomes)} SIGKILLs: previous build kept {sum(outcomes)}, new build in place "
          f"{len(outcomes) - sum(outcomes)}, stray entries before the next build: "
          f"{sorted(p.name for p in out.iterdir() if p.name != NAME)}")
    assert any(outcomes)                        # kills before the swap kept the previous build
    done = subprocess.run([EXE, str(SPEC), "-o", str(out)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in out.iterdir()) == [NAME]
    assert _complete(out / NAME) == before      # byte-identical rebuild


@pytest.mark.slow
def test_ctrl_c_exits_130_at_once(first_build):
    out, seconds = first_build
    before = _complete(out / NAME)
    for fraction in (0.1, 0.4, 0.7, 0.9):
        proc = _run(out)
        time.sleep(seconds * fraction)
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=60)
        stopped = time.monotonic() - sent
        if proc.returncode == 0:                # finished before the signal landed
            continue
        # "at once" relative to this machine's pace (a full build took `seconds` under the same load)
        assert proc.returncode == 130 and stopped < max(2.0, 0.2 * seconds), (fraction, proc.returncode, stopped,
                                                                             proc.stderr.read())
        assert "interrupted" in proc.stderr.read()
        assert sorted(p.name for p in out.iterdir()) == [NAME]      # its temporary folder removed
        assert _complete(out / NAME) == before


@pytest.mark.slow
def test_two_builds_into_one_folder_are_serialised(first_build):
    out, _ = first_build
    fd = os.open(out, os.O_RDONLY | os.O_DIRECTORY)
    fcntl.flock(fd, fcntl.LOCK_EX)              # a build in progress (holding the folder)
    proc = _run(out)
    try:
        lines = [""]
        while "waiting" not in lines[-1]:       # said at once, while it waits
            lines.append(proc.stderr.readline())
            assert lines[-1], "".join(lines)
        assert f"waiting: started — for another build writing into {out}" in lines[-1]
        time.sleep(min(60.0, 2 * first_build[1]))
        assert proc.poll() is None              # still waiting for the folder
        assert not any(p.name.startswith(f".{NAME}.tmp-") for p in out.iterdir())
    finally:
        os.close(fd)
    assert proc.wait(timeout=600) == 0
    a, b = _run(out), _run(out)                 # two at once: both succeed, one after the other
    assert a.wait(timeout=900) == 0 and b.wait(timeout=900) == 0
    assert sorted(p.name for p in out.iterdir()) == [NAME]
    _complete(out / NAME)


@pytest.mark.slow
def test_a_folder_created_during_the_build_is_kept_and_so_is_the_build(tmp_path):
    """A folder that appears at OUT/<name> while a build runs (after the first check) is not replaced:
    exit 2 naming it, the folder untouched, the new build complete under its temporary name."""
    proc = _run(tmp_path)
    deadline = time.monotonic() + 600
    while not any(p.name.startswith(f".{NAME}.tmp-") for p in tmp_path.iterdir()):
        assert proc.poll() is None and time.monotonic() < deadline, proc.stderr.read()
        time.sleep(0.05)
    (tmp_path / NAME).mkdir()
    (tmp_path / NAME / "thesis.tex").write_text("precious")
    _, err = proc.communicate(timeout=600)
    assert proc.returncode == 2, err
    last = err.strip().splitlines()[-1]
    assert last.startswith(f"{tmp_path / NAME}: appeared during the build and is not a make-lens build"), err
    assert (tmp_path / NAME / "thesis.tex").read_text() == "precious"
    assert sorted(p.name for p in (tmp_path / NAME).iterdir()) == ["thesis.tex"]
    [kept] = [p for p in tmp_path.iterdir() if p.name.startswith(f".{NAME}.tmp-")]
    assert f"the new build is in {kept}" in last
    _complete(kept)


@pytest.mark.slow
def test_ctrl_c_after_the_swap_says_the_build_is_in_place(tmp_path):
    """SIGINT while the summary is printed (stdout is a one-page pipe nobody reads, so the process
    stops there, after the swap): exit 0 and a line saying the complete build is in place."""
    read_end, write_end = os.pipe()
    fcntl.fcntl(write_end, 1031, 4096)            # F_SETPIPE_SZ: a page; the tables are larger
    proc = subprocess.Popen([EXE, str(SPEC), "-o", str(tmp_path)], stdout=write_end, stderr=subprocess.PIPE,
                            text=True, env=dict(os.environ, PYTHONUNBUFFERED="1"))
    os.close(write_end)
    try:
        lines = [""]
        while "manifest: done" not in lines[-1]:  # the swap is done
            lines.append(proc.stderr.readline())
            assert lines[-1], "".join(lines)
        time.sleep(1.0)                           # it is now blocked writing the tables
        proc.send_signal(signal.SIGINT)
        err = proc.stderr.read()
        assert proc.wait(timeout=60) == 0, err
    finally:
        os.close(read_end)
    assert f"interrupted after the build was complete: {tmp_path / NAME} is in place" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == [NAME]
    _complete(tmp_path / NAME)


@pytest.mark.slow
def test_builds_into_one_folder_run_in_parallel(tmp_path):
    """Three builds into one folder at once — two of one spec, one of another: their temporary folders
    exist side by side (only the swaps are serialised); all succeed; one complete build per spec."""
    other_spec, other = ROOT / "recipes" / "luneburg-classic-5.yaml", "luneburg-classic-5"
    env = dict(os.environ, ANTENNA_CAD_MEEP_PYTHON="/usr/bin/false")
    procs = [subprocess.Popen([EXE, str(spec), "-o", str(tmp_path)], stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True, env=env) for spec in (SPEC, SPEC, other_spec)]
    most = 0
    while any(p.poll() is None for p in procs):
        with_tmp = {p.name for p in tmp_path.iterdir() if ".tmp-" in p.name}
        most = max(most, len(with_tmp))
        time.sleep(0.05)
    errors = [p.stderr.read() for p in procs]
    assert [p.returncode for p in procs] == [0, 0, 0], errors
    assert most >= 2, "the builds never wrote at the same time"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([NAME, other])
    _complete(tmp_path / NAME)
    _complete(tmp_path / other)


@pytest.mark.slow
def test_a_full_disk_keeps_the_previous_build(first_build):
    """Writes that fail (the file-size limit stands in for a full disk: the same errors, no root needed),
    whichever file they hit — the meshing scratch, an STL, the report — end in one line and exit 2;
    the previous build stays byte-identical and nothing is left behind, in the folder or in /dev/shm."""
    import resource
    out, _ = first_build
    before = _complete(out / NAME)
    for limit_kb in (50, 1100):               # the meshing scratch (~1 MB), then report.html (1.1 MB)
        def small_disk():
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit_kb * 1024, limit_kb * 1024))
        proc = subprocess.Popen([EXE, str(SPEC), "-o", str(out), "-q"], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, preexec_fn=small_disk)
        stdout, stderr = proc.communicate(timeout=600)
        assert proc.returncode == 2, (limit_kb, stderr)
        assert stderr.count("\n") == 1 and "writing the build failed" in stderr, stderr
        assert "Traceback" not in stderr and stdout == ""
        assert sorted(p.name for p in out.iterdir()) == [NAME]
        assert _complete(out / NAME) == before
        assert not list(Path("/dev/shm").glob(f"antenna_cad-mesh-{proc.pid}-*"))
