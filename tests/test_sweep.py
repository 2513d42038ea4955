"""Design sweeps: sweep files, variant expansion, dask execution on a 2-worker LocalCluster and on a
scheduler + worker started here, the table, the Pareto front and the page in Chromium; scheduler
addresses and certificates checked before connecting; the folder's lock; Ctrl-C (workers ended,
rows kept with their page) and resuming an interrupted sweep."""

import contextlib
import csv
import fcntl
import json
import os
import math
import re
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pyarrow.parquet as pq
import pytest
import yaml
from typer.testing import CliRunner

from antenna_cad.cli import app
from antenna_cad.registry import adapter
from antenna_cad.spec import SpecError, parse_spec
from antenna_cad.sweep import run_sweep
from antenna_cad.sweep.model import load_sweep
from antenna_cad.sweep.results import pareto_front
from antenna_cad.sweep.tasks import fabrication_figures, finish
from antenna_cad.sweep.variants import expand

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "recipes" / "xps-collimator-0.5m.yaml"
FIGURES = ["thickness_mm", "sheet_count", "mass_kg", "fabricated_on_axis_p2p_deg", "tolerance_rss_gain_loss_db"]
SMALL = {
    "name": "small", "base": str(BASE), "mode": "figures",
    "axes": {"design.focal_length_mm": [300, 3000, 4000, -5],   # 300: rim ray beyond TIR (DesignError)
             "fabrication.sheet_thickness_mm": [40, 50, 50.0]},  # 50 and 50.0: one resolved spec
    "figures": FIGURES, "objectives": {"mass_kg": "min", "fabricated_on_axis_p2p_deg": "min"}}
REL = 1e-9      # worker processes and this one run the same code; only summation order may differ


def _write(tmp_path, doc, name="sweep.yaml") -> Path:
    path = tmp_path / name
    path.write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
    return path


def _single_run(spec_doc: dict) -> dict:
    """The figures of one variant computed directly, the way `make-lens` builds do (no dask)."""
    spec = parse_spec(spec_doc)
    kind = adapter(spec.kind)
    design = kind.synthesize(spec)
    layup, panels = kind.plan(spec, design)
    fab = kind.fabricate(spec, design, layup, panels)
    figures = kind.summary(spec, design, layup) | fabrication_figures(fab.totals_kg, fab.boards)
    return figures | kind.verify(spec, design, layup, fab).figures


@pytest.fixture(scope="module")
def local(tmp_path_factory):
    """The small sweep through the CLI on a 2-worker local cluster."""
    tmp = tmp_path_factory.mktemp("sweep")
    path = _write(tmp, SMALL)
    done = CliRunner().invoke(app, ["sweep", str(path), "-o", str(tmp / "out"), "--workers", "2"])
    assert done.exit_code == 0, done.output
    return path, tmp / "out" / "small", done.output


def _rows(out: Path, name: str = "results.csv") -> list[dict]:
    with open(out / name, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def test_expansion_ranges_linked_axes_and_dedup(tmp_path):
    doc = {"name": "x", "base": str(BASE),
           "set": {"material": {"name": "foam", "eps_r": 1.047, "tan_delta": 2e-4, "density_kg_m3": 33}},
           "axes": {"design.focal_length_mm": {"from": 3000, "to": 4000, "steps": 3},
                    "material.eps_r": [1.03, 1.07], "material.density_kg_m3": [21, 49],
                    "fabrication.sheet_thickness_mm": [50, 50.0]},
           "linked": [["material.eps_r", "material.density_kg_m3"]], "figures": ["mass_kg"]}
    variants = expand(load_sweep(_write(tmp_path, doc)))
    assert len(variants) == 3 * 2 * 2
    assert [v.values["design.focal_length_mm"] for v in variants[::4]] == [3000, 3500, 4000]
    assert all((v.values["material.eps_r"], v.values["material.density_kg_m3"]) in ((1.03, 21), (1.07, 49))
               for v in variants)
    assert all(v.spec["material"]["eps_r"] == v.values["material.eps_r"] for v in variants)
    assert len({v.key for v in variants}) == 6                  # 50 and 50.0 resolve to one spec


@pytest.mark.parametrize("change,expected", [
    ({"axes": {"design.focal_lenght_mm": [1, 2]}}, "axes.design.focal_lenght_mm: not a field of the base spec"),
    ({"axes": {"material.eps_r": [1.1]}}, "axes.material.eps_r: not a field of the base spec (set it to a mapping"),
    ({"objectives": {"mass_kg": "min"}, "figures": ["thickness_mm"]},
     "objectives.mass_kg: must be one of the figures collected"),
    ({"mode": "draft"}, "mode: Input should be 'figures' or 'build'"),
    ({"axes": {"design.focal_length_mm": {"from": 1, "to": 2, "steps": 1}}},
     "axes.design.focal_length_mm.steps: Input should be greater than or equal to 2"),
    ({"colour": "red"}, "colour: unknown key (not allowed here)"),
    ({"linked": [["design.focal_length_mm", "x"]]}, "linked: 'x' is not an axis"),
])
def test_bad_sweep_file_names_the_field(tmp_path, change, expected):
    path = _write(tmp_path, SMALL | change)
    with pytest.raises(SpecError) as info:
        expand(load_sweep(path))
    assert info.value.lines[0].startswith(str(path)) and expected in info.value.lines[0], info.value.lines
    done = CliRunner().invoke(app, ["sweep", str(path), "-o", str(tmp_path / "out")])
    assert done.exit_code == 2 and expected in done.output and "Traceback" not in done.output
    assert not (tmp_path / "out").exists()                     # nothing written


def test_unreachable_scheduler_is_a_clean_error(tmp_path, monkeypatch):
    monkeypatch.setattr("antenna_cad.sweep.execute.CONNECT_TIMEOUT", "1s")
    path, out = _write(tmp_path, SMALL), tmp_path / "out"
    address = f"tcp://127.0.0.1:{_free_port()}"                  # nobody listens there
    done = CliRunner().invoke(app, ["sweep", str(path), "-o", str(out), "--scheduler", address])
    assert done.exit_code == 2 and f"--scheduler: cannot reach {address}" in done.output, done.output
    assert "Traceback" not in done.output and not out.exists()
    both = CliRunner().invoke(app, ["sweep", str(path), "--scheduler", address, "--workers", "2"])
    assert both.exit_code == 2 and "--workers: only for a local cluster" in both.output


def test_local_cluster_gives_the_figures_of_single_runs(local):
    path, out, _ = local
    variants = {v.index: v for v in expand(load_sweep(path))}
    rows = _rows(out)
    assert [int(r["variant"]) for r in rows] == list(range(1, 13))
    ok = [r for r in rows if r["status"] == "ok"]
    assert len(ok) == 6
    for row in ok:
        single = _single_run(variants[int(row["variant"])].spec)
        for name in FIGURES:
            assert float(row[name]) == pytest.approx(single[name], rel=REL), (row["variant"], name)


def test_invalid_and_failing_variants_are_rows_and_the_rest_complete(local):
    _, out, output = local
    rows = {int(r["variant"]): r for r in _rows(out)}
    for i in (1, 2, 3):                                         # f = 300 mm: valid spec, impossible to build
        assert rows[i]["status"] == "failed"                    # (a thick lens: its first discs are too small)
        assert rows[i]["error"].startswith("design: fabrication.dowel_diameter_mm:")
        assert "do not fit" in rows[i]["error"]
    for i in (10, 11, 12):                                      # f = -5 mm: rejected by the spec loader
        assert rows[i]["status"] == "invalid"
        assert rows[i]["error"] == f"variant {i}: design.focal_length_mm: must be ≥ 1 (got -5)"
    assert "12 variants (6 computed, 6 ok, 3 invalid, 3 failed)" in output.replace("\n", " ")


def test_identical_variants_share_one_result(local):
    _, out, _ = local
    rows = {int(r["variant"]): r for r in _rows(out)}
    for a, b in ((5, 6), (8, 9)):                               # sheet 50 and 50.0
        assert rows[a]["spec_hash"] == rows[b]["spec_hash"]
        assert {k: v for k, v in rows[a].items() if k not in ("variant", "fabrication.sheet_thickness_mm")} == \
               {k: v for k, v in rows[b].items() if k not in ("variant", "fabrication.sheet_thickness_mm")}


def test_parquet_and_pareto_agree_with_the_table(local):
    _, out, _ = local
    table = pq.read_table(out / "results.parquet")
    assert str(table.schema.field("mass_kg").type) == "double" and str(table.schema.field("pareto").type) == "bool"
    data = table.to_pylist()
    rows = _rows(out)
    assert [d["variant"] for d in data] == [int(r["variant"]) for r in rows]
    for d, r in zip(data, rows):
        assert d["status"] == r["status"] and (d["mass_kg"] is None) == (r["mass_kg"] == "")
        if d["mass_kg"] is not None:
            assert d["mass_kg"] == float(r["mass_kg"])
    ok = [d for d in data if d["status"] == "ok"]
    front = {d["variant"] for d in ok if not any(                # brute force: nobody at least as good, and better
        o["mass_kg"] <= d["mass_kg"] and o["fabricated_on_axis_p2p_deg"] <= d["fabricated_on_axis_p2p_deg"]
        and (o["mass_kg"], o["fabricated_on_axis_p2p_deg"]) != (d["mass_kg"], d["fabricated_on_axis_p2p_deg"])
        for o in ok)}
    assert {d["variant"] for d in data if d["pareto"]} == front and front
    assert {int(r["variant"]) for r in _rows(out, "pareto.csv")} == front


def test_pareto_front_directions():
    rows = [{"variant": i, "status": "ok", "a": a, "b": b} for i, (a, b) in
            enumerate([(1, 1), (2, 3), (3, 2), (0, 0.5), (math.nan, 9)], start=1)]
    assert [r["variant"] for r in pareto_front(rows, {"a": "min", "b": "max"})] == [4, 1, 2]
    assert [r["variant"] for r in pareto_front(rows, {"a": "max", "b": "max"})] == [3, 2]
    assert [r["variant"] for r in pareto_front(rows, {"a": "min", "b": "min"})] == [4]


def test_a_figure_the_kind_does_not_give_is_the_rows_error():
    result = finish(("design",), (1,), ("mass_kg", "gain_db"), {"figures": {"mass_kg": 1.0}, "checks": {}})
    assert result == {"error": "figures: gain_db not produced by this kind; it gives mass_kg"}


def test_page_is_self_contained_and_renders_in_chromium(local, browser):
    _, out, _ = local
    page = (out / "index.html").read_text(encoding="utf-8")
    assert "<script" not in page
    assert not re.search(r"""(src|href)=["'](https?:|//|file:)""", page)        # no network, no local links
    browser.get((out / "index.html").as_uri())
    assert browser.title.startswith("small")
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "ERROR")] == []
    plots = browser.execute_script("""return Array.from(document.querySelectorAll('figure.plot')).map(f => {
        const r = f.querySelector('svg').getBoundingClientRect(); return [f.id, r.width, r.height];});""")
    ids = {p[0] for p in plots}
    assert "pareto-mass_kg-fabricated_on_axis_p2p_deg" in ids
    assert {f"plot-{f}-{a}" for f in FIGURES for a in SMALL["axes"]} <= ids
    assert all(w > 200 and h > 100 for _, w, h in plots), plots
    sections = browser.execute_script("return Array.from(document.querySelectorAll('section')).map(s => s.id)")
    assert sections == ["summary", "pareto", "plots", "failures", "results"]
    assert browser.execute_script("return document.querySelectorAll('#results-table tbody tr').length") == 12


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def scheduler(tmp_path_factory):
    """`dask scheduler` + one `dask worker` process on 127.0.0.1 at a free port, torn down at the end."""
    logs_dir = tmp_path_factory.mktemp("dask")
    port, dask = _free_port(), [sys.executable, "-m", "dask"]
    address = f"tcp://127.0.0.1:{port}"
    logs = [open(logs_dir / f"{n}.log", "w") for n in ("scheduler", "worker")]
    procs = [subprocess.Popen(dask + ["scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              stdout=logs[0], stderr=subprocess.STDOUT)]
    try:
        procs.append(subprocess.Popen(dask + ["worker", address, "--no-nanny", "--nthreads", "1",
                                              "--no-dashboard", "--host", "127.0.0.1"],
                                      stdout=logs[1], stderr=subprocess.STDOUT))
        yield address
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:      # a worker still closing gracefully: not under test here
                p.kill()
                p.wait(timeout=30)
        for log in logs:
            log.close()


def test_sweep_on_a_running_scheduler(scheduler, tmp_path):
    doc = SMALL | {"name": "remote", "axes": {"design.focal_length_mm": [3000, 4000],
                                               "fabrication.sheet_thickness_mm": [50]}}
    start = time.perf_counter()
    result = run_sweep(_write(tmp_path, doc), tmp_path / "out", scheduler=scheduler)
    print(f"scheduler {scheduler}: {len(result.rows)} rows in {time.perf_counter() - start:.1f} s; "
          + json.dumps([{k: r[k] for k in ("variant", "status", "mass_kg", "fabricated_on_axis_p2p_deg")}
                        for r in result.rows]))
    assert [r["status"] for r in result.rows] == ["ok", "ok"]
    variants = expand(load_sweep(tmp_path / "sweep.yaml"))
    for row, v in zip(result.rows, variants):
        assert row["mass_kg"] == pytest.approx(_single_run(v.spec)["mass_kg"], rel=REL)
    assert (result.out_dir / "index.html").exists() and (result.out_dir / "results.parquet").exists()


def _wait_for_rows(path: Path, count: int, proc, limit_s: float = 120.0) -> None:
    end = time.monotonic() + limit_s
    while time.monotonic() < end and proc.poll() is None:
        if path.exists() and len(path.read_text(encoding="utf-8").splitlines()) > count:
            return
        time.sleep(0.2)
    raise AssertionError(f"no {count} rows in {path} (exit {proc.poll()})")


@pytest.mark.slow
def test_ctrl_c_keeps_the_rows_done(scheduler, tmp_path):
    """`make-lens sweep --scheduler` interrupted by SIGINT: exit 130, the finished rows on disk."""
    many = SMALL | {"name": "stopped", "axes": {"design.focal_length_mm": {"from": 3000, "to": 8000, "steps": 30}}}
    exe = shutil.which("make-lens") or str(Path(sys.executable).parent / "make-lens")
    cli = subprocess.Popen([exe, "sweep", str(_write(tmp_path, many)), "-o", str(tmp_path / "out"),
                            "--scheduler", scheduler], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    table = tmp_path / "out" / "stopped" / "results.csv"
    _wait_for_rows(table, 2, cli)
    cli.send_signal(signal.SIGINT)
    output, _ = cli.communicate(timeout=60)
    rows = _rows(table.parent)
    print(f"Ctrl-C: exit {cli.returncode}, {len(rows)} of 30 rows kept; {output.strip()}")
    assert cli.returncode == 130 and "Traceback" not in output
    assert f"interrupted: {len(rows)} rows done are in {table}" in output
    assert 2 <= len(rows) < 30 and all(r["status"] == "ok" and float(r["mass_kg"]) > 0 for r in rows)
    assert (table.parent / "index.html").exists() and len(_rows(table.parent, "pareto.csv")) >= 1


@pytest.mark.slow
def test_build_mode_writes_each_variant_in_its_own_folder(scheduler, tmp_path):
    doc = {"name": "builds", "base": str(ROOT / "recipes" / "ptfe-lens-120mm.yaml"), "mode": "build",
           "set": {"outputs.report": False}, "axes": {"design.focal_length_mm": [250, 300]},
           "figures": ["thickness_mm", "ideal_on_axis_p2p_deg"], "objectives": {"thickness_mm": "min"}}
    result = run_sweep(_write(tmp_path, doc), tmp_path / "out", scheduler=scheduler)
    assert [r["status"] for r in result.rows] == ["ok", "ok"], result.rows
    folders = [result.out_dir / r["folder"] for r in result.rows]
    assert len(set(folders)) == 2
    for row, folder, v in zip(result.rows, folders, expand(load_sweep(tmp_path / "sweep.yaml"))):
        assert folder == result.out_dir / "builds" / v.key[:12] / "ptfe-lens-120mm"
        manifest = json.loads((folder / "manifest.json").read_text())
        assert manifest["spec"]["design"]["focal_length_mm"] == v.values["design.focal_length_mm"]
        assert row["thickness_mm"] == pytest.approx(manifest["figures"]["thickness_mm"], rel=1e-9)
        assert (folder / "ptfe-lens-120mm.step").stat().st_size > 0
    assert _rows(result.out_dir)[0]["folder"] == result.rows[0]["folder"]


@pytest.mark.parametrize("name", ["collimator-trade", "luneburg-layers"])
def test_sweep_recipes_expand_to_valid_variants(name):
    path = ROOT / "recipes" / "sweeps" / f"{name}.yaml"
    file = load_sweep(path)
    variants = expand(file)
    assert file.sweep.name == name and len(variants) >= 50 and all(v.key for v in variants), \
        [v.error for v in variants if v.error][:3]
    assert path not in (ROOT / "recipes").glob("*.yaml")      # spec recipe tests do not pick sweeps up


@pytest.mark.parametrize("address,expected", [
    ("http://127.0.0.1:8787", "that is a web address"),
    ("ucx://127.0.0.1:8786", "UCX needs the optional ucx-py transport"),
    ("inproc://x", "inproc:// addresses exist only inside the process"),
    ("tcp://127.0.0.1:abc", "port 'abc' is not a number from 1 to 65535"),
    ("127.0.0.1:8786", "expected tcp://HOST:PORT or tls://HOST:PORT"),
    ("tls://127.0.0.1:8786", "--scheduler tls://: needs certificates: a tls block in the sweep file"),
])
def test_scheduler_address_is_checked_before_connecting(tmp_path, monkeypatch, address, expected):
    def no_connection(*args):
        raise AssertionError("connected")
    monkeypatch.setattr("antenna_cad.sweep.connect", no_connection)
    for name in ("CA_FILE", "CLIENT__CERT", "CLIENT__KEY"):
        monkeypatch.delenv(f"DASK_DISTRIBUTED__COMM__TLS__{name}", raising=False)
    path, out = _write(tmp_path, SMALL), tmp_path / "out"
    done = CliRunner().invoke(app, ["sweep", str(path), "-o", str(out), "--scheduler", address])
    lines = done.output.strip().splitlines()
    assert done.exit_code == 2 and len(lines) == 1 and expected in lines[0], done.output
    assert lines[0].startswith("--scheduler") and not out.exists()


def test_tls_certificates_from_the_sweep_file_or_the_environment(tmp_path, monkeypatch):
    (tmp_path / "ca.pem").write_text("not checked here")
    doc = SMALL | {"tls": {"ca_file": "ca.pem", "cert": "client.pem"}}
    path = _write(tmp_path, doc)
    done = CliRunner().invoke(app, ["sweep", str(path), "--scheduler", "tls://127.0.0.1:8786"])
    assert done.exit_code == 2 and done.output.strip() == (
        f"{tmp_path / 'client.pem'}: cannot read this certificate file from the sweep file's tls block "
        "(No such file or directory)"), done.output
    from antenna_cad.sweep.execute import security
    (tmp_path / "client.pem").write_text("x")
    monkeypatch.setattr("distributed.Security", lambda **kw: kw)
    from antenna_cad.sweep.model import TlsSpec
    assert security(TlsSpec(ca_file="ca.pem", cert="client.pem"), tmp_path) == {
        "require_encryption": True, "tls_ca_file": str(tmp_path / "ca.pem"),
        "tls_client_cert": str(tmp_path / "client.pem")}
    import dask
    with dask.config.set({"distributed.comm.tls.ca-file": str(tmp_path / "ca.pem"),
                          "distributed.comm.tls.client.cert": str(tmp_path / "client.pem")}):
        assert security(None, tmp_path)["tls_client_cert"] == str(tmp_path / "client.pem")


def test_full_wave_is_off_unless_the_sweep_asks_for_it(tmp_path):
    shipped = expand(load_sweep(ROOT / "recipes" / "sweeps" / "luneburg-layers.yaml"))
    assert {v.spec["verification"]["full_wave"] for v in shipped} == {"off"}
    asked = expand(load_sweep(_write(tmp_path, SMALL | {"set": {"verification.full_wave": "auto"}})))
    assert {v.spec["verification"]["full_wave"] for v in asked if v.spec} == {"auto"}
    swept = SMALL | {"axes": {"verification.full_wave": ["off", "on"]}}
    assert [v.spec["verification"]["full_wave"] for v in expand(load_sweep(_write(tmp_path, swept)))] == ["off", "on"]


def test_a_sweep_folder_held_by_another_sweep_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr("antenna_cad.sweep.connect", lambda *args: contextlib.nullcontext())
    folder = tmp_path / "out" / "small"
    folder.mkdir(parents=True)
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    fcntl.flock(fd, fcntl.LOCK_EX)                              # another sweep runs into it
    try:
        done = CliRunner().invoke(app, ["sweep", str(_write(tmp_path, SMALL)), "-o", str(tmp_path / "out")])
    finally:
        os.close(fd)
    assert done.exit_code == 2 and done.output.strip() == (
        f"{folder}: another sweep is writing into this folder; wait for it to end or choose another -o")
    assert list(folder.iterdir()) == []


def test_an_interrupted_sweep_resumes_where_it_stopped(local, tmp_path, monkeypatch):
    """results.csv cut after variant 5 (as an interrupted run leaves it): the next run computes only
    the variants missing, and the table is byte for byte the one of a run never interrupted."""
    path, out, _ = local
    whole = (out / "results.csv").read_bytes()
    again = tmp_path / "small"
    again.mkdir()
    lines = whole.decode().splitlines(keepends=True)
    (again / "results.csv").write_text("".join(lines[:6]), encoding="utf-8")       # header + variants 1–5
    computed = []
    import antenna_cad.sweep as sweep_pkg
    real_run = sweep_pkg.run

    def counting_run(client, todo, *args):
        computed.extend(v.index for v in todo)
        return real_run(client, todo, *args)
    monkeypatch.setattr(sweep_pkg, "run", counting_run)
    result = run_sweep(path, tmp_path, workers=1)
    assert computed == [7, 8, 9]            # 1–3 failed, 4–5 ok, 6 is 5 (sheet 50.0): kept; 10–12 invalid
    assert result.resumed == 6
    assert (again / "results.csv").read_bytes() == whole


def test_ending_a_cluster_never_ends_this_process():
    """A nanny whose worker has already gone has no pid; psutil.Process(None) is this process, so the
    sweep once sent itself SIGTERM while closing after Ctrl-C (exit -15 instead of 130)."""
    from types import SimpleNamespace

    from antenna_cad.sweep.execute import _descendants
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        cluster = SimpleNamespace(workers={"gone": SimpleNamespace(process=None),
                                           "closing": SimpleNamespace(process=SimpleNamespace(pid=None)),
                                           "self": SimpleNamespace(process=SimpleNamespace(pid=os.getpid())),
                                           "alive": SimpleNamespace(process=SimpleNamespace(pid=child.pid))})
        assert [p.pid for p in _descendants(cluster)] == [child.pid]
    finally:
        child.kill()
        child.wait()


@pytest.mark.slow
def test_ctrl_c_on_a_local_sweep_ends_every_worker_and_resumes(tmp_path):
    """Ctrl-C (SIGINT to the process group) on `make-lens sweep --workers 2`: exit 130 saying how many
    rows are done, no traceback from any process, every process
    it started ended, its temporary folder removed, no leaked-semaphore warning, index.html and
    pareto.csv for the rows done, progress lines off a terminal; the same command then finishes the
    sweep, computing only what was missing."""
    many = SMALL | {"name": "stopped", "axes": {"design.focal_length_mm": {"from": 3000, "to": 8000, "steps": 8},
                                                "fabrication.sheet_thickness_mm": [50]}}
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    exe = shutil.which("make-lens") or str(Path(sys.executable).parent / "make-lens")
    command = [exe, "sweep", str(_write(tmp_path, many)), "-o", str(tmp_path / "out"), "--workers", "2"]
    env = dict(os.environ, TMPDIR=str(scratch))
    cli = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
                           start_new_session=True)
    table = tmp_path / "out" / "stopped" / "results.csv"
    _wait_for_rows(table, 1, cli, limit_s=600)
    started = psutil.Process(cli.pid).children(recursive=True)
    os.killpg(cli.pid, signal.SIGINT)                  # as Ctrl-C on a terminal: the whole process group
    output, _ = cli.communicate(timeout=900)           # closing the cluster, then the page of the rows done
    _, alive = psutil.wait_procs(started, timeout=60)  # multiprocessing's resource tracker ends after its parent
    rows = _rows(table.parent)
    print(f"Ctrl-C: exit {cli.returncode}, {len(rows)} of 8 rows kept, {len(started)} processes before, "
          f"{len(alive)} after; {output.strip()}")
    assert cli.returncode == 130 and "Traceback" not in output and "leaked semaphore" not in output
    assert len(started) >= 2 and alive == []
    assert f"interrupted: {len(rows)} rows done are in {table}" in output
    assert re.search(r"sweep.yaml: \d of 8 variants", output)
    assert list(scratch.iterdir()) == []
    assert (table.parent / "index.html").exists() and (table.parent / "pareto.csv").exists()
    done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=1200)
    assert done.returncode == 0, done.stderr
    assert f"({len(rows)} rows kept from the interrupted run)" in done.stdout.replace("\n", " ")
    assert [r["status"] for r in _rows(table.parent)] == ["ok"] * 8


@pytest.mark.slow
def test_sweep_on_a_tls_scheduler(tmp_path):
    """A scheduler and worker that speak TLS only (certificates made here with openssl): the sweep
    connects with the sweep file's tls block and computes its rows."""
    def openssl(*args):
        subprocess.run(["openssl", *args], cwd=tmp_path, check=True, capture_output=True, timeout=120)
    openssl("req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", "ca-key.pem", "-out", "ca.pem", "-days", "2",
            "-subj", "/CN=antenna-cad-test-ca")
    openssl("req", "-newkey", "rsa:2048", "-nodes", "-keyout", "key.pem", "-out", "req.csr", "-subj", "/CN=127.0.0.1")
    openssl("x509", "-req", "-in", "req.csr", "-CA", "ca.pem", "-CAkey", "ca-key.pem", "-CAcreateserial",
            "-out", "cert.pem", "-days", "2")
    tls = ["--tls-ca-file", "ca.pem", "--tls-cert", "cert.pem", "--tls-key", "key.pem"]
    port, dask = _free_port(), [sys.executable, "-m", "dask"]
    address = f"tls://127.0.0.1:{port}"
    procs = [subprocess.Popen(dask + ["scheduler", "--protocol", "tls", "--host", "127.0.0.1", "--port", str(port),
                                      "--no-dashboard", *tls], cwd=tmp_path, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)]
    try:
        procs.append(subprocess.Popen(dask + ["worker", address, "--no-nanny", "--nthreads", "1", "--no-dashboard",
                                              "--host", "127.0.0.1", *tls], cwd=tmp_path,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        doc = SMALL | {"name": "tls", "axes": {"design.focal_length_mm": [3000, 4000],
                                                "fabrication.sheet_thickness_mm": [50]},
                       "tls": {"ca_file": "ca.pem", "cert": "cert.pem", "key": "key.pem"}}
        result = run_sweep(_write(tmp_path, doc), tmp_path / "out", scheduler=address)
        assert [r["status"] for r in result.rows] == ["ok", "ok"]
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=60)
            except subprocess.TimeoutExpired:       # a loaded machine: a worker slow to close
                p.kill()
                p.wait()


def test_a_local_cluster_leaves_nothing_in_the_temporary_folder(tmp_path, monkeypatch):
    """The workers' folder and dask's own lock files live in one scratch folder, removed on exit."""
    import tempfile

    from antenna_cad.sweep.execute import connect
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    with connect(workers=1) as client:
        assert client.submit(abs, -1).result() == 1
    assert list(tmp_path.iterdir()) == []
