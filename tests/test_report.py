"""report.html (+ its workshop copy report.pdf): self-contained, reproducible, and it renders in a real browser (headless Chromium,
Debian's `chromium` + `chromium-driver`, installed by .ci/run) with no console errors and every
figure drawn."""

import base64
import json
import os
import re
import threading
from pathlib import Path

import pypdf
import pytest

from antenna_cad.export.forked import SERIAL_ENV, Job
from antenna_cad.pipeline import build
from antenna_cad.registry import adapter
from antenna_cad.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
RECIPES = ["xps-collimator-0.5m", "ptfe-lens-120mm"]


def _open(browser, page: Path, until: str = "document.getElementById('spec') !== null") -> None:
    """Navigate to ``page`` and wait (≤ 60 s) for the whole document and for ``until`` (JS) to hold:
    a navigation to the URL already shown may hand back control before the new page is parsed."""
    from selenium.webdriver.support.ui import WebDriverWait
    browser.execute_script("window.staleReport = true")
    browser.get(page.as_uri())
    WebDriverWait(browser, 60).until(lambda b: b.execute_script(
        f"return !window.staleReport && document.readyState === 'complete' && ({until})"),
        f"{page.name}: {until}")


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    out = tmp_path_factory.mktemp("reports")
    return {name: build(load_spec(ROOT / "recipes" / f"{name}.yaml"), out) for name in RECIPES}


@pytest.mark.parametrize("name", RECIPES)
def test_report_is_self_contained_and_listed(reports, name):
    result = reports[name]
    page = (result.out_dir / "report.html").read_text(encoding="utf-8")
    assert not re.search(r"""(src|href)=["'](https?:|//|file:)""", page)        # no network, no local links
    assert not re.search(r"<script[^>]*\ssrc=", page)                            # every script inline
    glb = re.search(r'<script type="text/plain" id="v3d-glb">([^<]*)</script>', page).group(1)
    assert base64.b64decode(glb) == (result.out_dir / f"{name}.glb").read_bytes()  # the 3-D view is the .glb
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    assert "report.html" in {f["path"] for f in manifest["files"]}
    for f in manifest["files"]:                                                  # every file is listed
        assert f["path"] in page
    for check in manifest["checks"]:
        assert check["name"] in page


@pytest.mark.parametrize("name", RECIPES)
def test_report_renders_in_chromium_without_errors(reports, browser, name):
    result = reports[name]
    _open(browser, result.out_dir / "report.html")
    assert browser.title.startswith(name)
    errors = [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "ERROR")]
    assert errors == []
    browser.execute_script("document.querySelectorAll('details').forEach(d => d.open = true)")   # as printed
    figures = browser.execute_script("""
        return Array.from(document.querySelectorAll('figure')).map(f => {
            const el = f.querySelector('svg, img, table, canvas');
            const r = el ? el.getBoundingClientRect() : {width: 0, height: 0};
            return {id: f.id, tag: el ? el.tagName.toLowerCase() : null, w: r.width, h: r.height,
                    loaded: el && el.tagName === 'IMG' ? el.complete && el.naturalWidth > 0 : true};
        });""")
    ids = [f["id"] for f in figures]
    assert "views" in ids and "v3d" in ids                                       # assembly pictures, 3-D view
    for f in figures:
        assert f["tag"] and f["w"] > 50 and f["h"] > 20 and f["loaded"], f
    sections = browser.execute_script("return Array.from(document.querySelectorAll('section')).map(s => s.id)")
    assert sections == ["verdicts", "summary", "pictures", "verification", "checks", "cutlist", "files", "spec"]


def test_every_verification_plot_and_table_is_in_the_report(reports):
    result = reports["xps-collimator-0.5m"]
    spec = load_spec(ROOT / "recipes" / "xps-collimator-0.5m.yaml")
    kind = adapter(spec.kind)
    design = kind.synthesize(spec)
    layup, panels = kind.plan(spec, design)
    verification = kind.verify(spec, design, layup, kind.fabricate(spec, design, layup, panels))
    page = (result.out_dir / "report.html").read_text(encoding="utf-8")
    for plot in verification.plots:
        assert f'id="plot-{plot.name}"' in page
    for table in verification.tables:
        assert f'id="table-{table.name}"' in page


@pytest.mark.parametrize("name", RECIPES)
def test_workshop_pdf_has_the_same_content_on_a4(reports, name):
    result = reports[name]
    pdf = pypdf.PdfReader(result.out_dir / "report.pdf")
    for page in pdf.pages:
        assert (float(page.mediabox.width), float(page.mediabox.height)) == pytest.approx((595.4, 841.7), abs=0.5)
    text = "".join(page.extract_text() for page in pdf.pages)
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    for check in manifest["checks"]:
        assert check["name"] in text
    for piece in manifest["pieces"]:
        assert piece["label"] in text


def test_report_is_reproducible(reports, tmp_path):
    again = build(load_spec(ROOT / "recipes" / "ptfe-lens-120mm.yaml"), tmp_path)
    for file in ("report.html", "report.pdf", "ptfe-lens-120mm.glb"):
        assert (again.out_dir / file).read_bytes() == (reports["ptfe-lens-120mm"].out_dir / file).read_bytes()


def test_report_pdf_drawn_beside_equals_serial(reports, tmp_path, monkeypatch):
    """The fixture drew report.pdf in a child process beside report.html (2 cores); one after the
    other in one process gives the same bytes."""
    monkeypatch.setenv(SERIAL_ENV, "1")
    serial = build(load_spec(ROOT / "recipes" / "ptfe-lens-120mm.yaml"), tmp_path)
    for file in ("report.html", "report.pdf"):
        assert (serial.out_dir / file).read_bytes() == (reports["ptfe-lens-120mm"].out_dir / file).read_bytes()


def test_job_runs_in_a_child_and_hands_back_its_error(tmp_path, monkeypatch):
    monkeypatch.delenv(SERIAL_ENV, raising=False)
    marker = tmp_path / "pid"
    Job(lambda: marker.write_text(str(os.getpid())), ()).finish()
    assert int(marker.read_text()) != os.getpid()                    # written by another process

    def fails():
        raise OSError(28, "No space left on device")
    with pytest.raises(OSError, match="No space left"):
        Job(fails, ()).finish()


def test_job_is_in_line_off_the_main_thread(tmp_path, monkeypatch):
    monkeypatch.delenv(SERIAL_ENV, raising=False)
    marker = tmp_path / "pid"
    worker = threading.Thread(target=lambda: Job(lambda: marker.write_text(str(os.getpid())), ()).finish())
    worker.start()
    worker.join()
    assert int(marker.read_text()) == os.getpid()


PIXELS = """
    const c = document.querySelector('#v3d canvas');
    const copy = document.createElement('canvas');
    copy.width = c.width; copy.height = c.height;
    const g = copy.getContext('2d');
    g.drawImage(c, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let ink = 0, hash = 0;
    for (let i = 0; i < d.length; i += 4) {
        if (d[i] < 245 || d[i + 1] < 245 || d[i + 2] < 245) ink++;
        hash = (hash * 31 + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) | 0;
    }
    return [ink, hash, c.width * c.height];"""


def _view(browser, result):
    _open(browser, result.out_dir / "report.html", until="document.getElementById('v3d').dataset.ready === '1'")
    return browser.execute_script(PIXELS)


def test_3d_view_draws_the_assembly_and_groups_toggle(reports, browser):
    """The canvas shows the model (a good share of it not background), unticking a group of parts
    changes the picture, ticking it again brings the same picture back, and a section plane cuts it."""
    result = reports["xps-collimator-0.5m"]
    ink, first, total = _view(browser, result)
    assert 0.03 * total < ink < 0.9 * total
    groups = browser.execute_script(
        "return Array.from(document.querySelectorAll('.v3d-groups input')).map(b => [b.dataset.group, b.checked])")
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    assert {g for g, _ in groups} >= {"sheet", "box"}                  # toggles by group, not by part
    assert len(groups) < len(manifest["parts"])
    box = browser.find_element("css selector", ".v3d-groups input[data-group='sheet']")
    box.click()
    ink_off, hash_off, _ = browser.execute_script(PIXELS)
    assert hash_off != first and ink_off < ink
    box.click()
    assert browser.execute_script(PIXELS)[1] == first
    browser.execute_script("""const a = document.querySelector('.v3d-axis'); a.value = 'x';
                              a.dispatchEvent(new Event('change'));""")
    assert browser.execute_script(PIXELS)[0] < ink                        # half the assembly cut away
    assert "x = " in browser.find_element("css selector", ".v3d-cut-mm").text


def test_glb_has_one_named_node_per_part_coloured_by_material(reports):
    import trimesh
    result = reports["ptfe-lens-120mm"]
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    scene = trimesh.load(result.out_dir / f"{result.name}.glb", force="scene")
    assert sorted(scene.graph.nodes_geometry) == sorted(p["label"] for p in manifest["parts"])
    for part in manifest["parts"]:
        mesh = scene.geometry[part["label"]]
        assert mesh.visual.material.name == part["material"]
        assert mesh.bounds[1].max() < 1.0                               # metres: the parts are < 1 m
    assert "ptfe-lens-120mm.glb" in {f["path"] for f in manifest["files"]}


def test_printed_report_shows_every_collapsed_table(reports, browser):
    result = reports["xps-collimator-0.5m"]
    _open(browser, result.out_dir / "report.html")
    hidden = "return Array.from(document.querySelectorAll('details table')).filter(t => !t.checkVisibility()).length"
    assert browser.execute_script(hidden) > 0                         # on screen: collapsed
    browser.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": "print"})
    try:
        assert browser.execute_script(hidden) == 0                    # in print: all open
    finally:
        browser.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": ""})


def test_pdf_keeps_greek_letters_and_powers_of_ten_readable():
    """The standard PDF fonts have no ε, δ or superscripts: εr stays εr (its outline drawn into the
    line), 2.5 × 10⁻⁵ becomes 2.5e-5, λ is spelled out."""
    from antenna_cad.export.report_pdf import format_table, pdf_text
    assert pdf_text("εr 1.05, tanδ 2.5 × 10⁻⁵, λ/16, 12\u202f345 mm") == "εr 1.05, tanδ 2.5e-5, lambda/16, 12 345 mm"
    lines = format_table(("figure", "value"), [("D/λ", "13.34"), ("Grade εr", "1.9")])
    assert lines[2].index("13.34") == lines[3].index("1.9")           # columns aligned after spelling


def test_pdf_headings_keep_greek_letters():
    """A heading holding εr is drawn as outlines (it reads εr, never "er"); a plain one stays text."""
    from matplotlib.figure import Figure
    from matplotlib.patches import PathPatch

    from antenna_cad.export.report_pdf import _heading
    greek, plain = Figure(), Figure()
    _heading(greek, "Layup: εr per sheet")
    _heading(plain, "Cut list")
    assert [type(a) for a in greek.artists] == [PathPatch] and not greek.texts
    assert len(greek.artists[0].get_path().vertices) > 100                      # every glyph's outline
    assert [t.get_text() for t in plain.texts] == ["Cut list"] and not plain.artists


def test_a_family_of_many_curves_names_only_its_ends():
    """56 planes' curves: one colour ramp, the legend names the first and last and the limits — a
    legend of 56 entries ran past the PDF page."""
    import matplotlib.pyplot as plt

    from antenna_cad.export.plots import MAX_LEGEND, draw_plot
    from antenna_cad.verification import Plot, Series
    curves = tuple(Series(f"z {z} mm", (0.0, 1.0), (0.0, z / 100)) for z in range(100, 1200, 20))
    fig, ax = plt.subplots()
    draw_plot(ax, Plot("family", "many", "r", "phase", curves, hlines=(("+11.25°", 11.25),)))
    names = [t.get_text() for t in ax.get_legend().get_texts()]
    plt.close(fig)
    assert len(curves) > MAX_LEGEND and names == ["z 100 mm", "z 1180 mm", "+11.25°"]
