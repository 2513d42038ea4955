"""Template files of a big sheet layup: one PDF per sheet, written by two forked
workers over disjoint sheets, byte for byte what one process writes, and checked by ``check``."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest

from antenna_cad.export import template_files
from antenna_cad.export.forked import SERIAL_ENV
from tests.ring_cases import two_grade_sphere

RECIPES = Path(__file__).resolve().parents[1] / "recipes"


def _fab():
    return two_grade_sphere(400.0)


def _bytes(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_shares_balance_the_sheets():
    shares = template_files._shares([9.0, 1.0, 5.0, 4.0, 1.0], 2)
    assert sorted(k for s in shares for k in s) == [0, 1, 2, 3, 4]
    assert shares == [[0, 1], [2, 3, 4]]                           # 10 against 10
    assert template_files._shares([3.0], 2) == [[0]]


def test_per_sheet_pdfs_from_two_workers_match_one_process(tmp_path, monkeypatch):
    from antenna_cad.export.check_readers import pdf_findings
    plan, fab = _fab()
    spec = SimpleNamespace(name="t")
    monkeypatch.setattr(template_files, "PER_SHEET_PDF_DRAWINGS", 0)
    assert template_files.per_sheet(fab) and len(plan.sheets) >= 4
    written = {}
    for serial in ("1", "0"):
        monkeypatch.setenv(SERIAL_ENV, serial)
        out = tmp_path / serial
        out.mkdir()
        entries = template_files.write_templates(spec, fab, out)
        written[serial] = (entries, _bytes(out))
        assert sorted(p.relative_to(out).as_posix() for p in template_files.template_files(spec, fab, out)) \
            == sorted(written[serial][1])
    assert written["0"] == written["1"]
    entries, files = written["0"]
    pdfs = [e for e in entries if "pdf" in e]
    assert [e["pdf"] for e in pdfs] == [f"templates/pdf/{s.label}.pdf" for s in plan.sheets]
    assert all(e["pages"] >= 1 for e in pdfs) and f"templates/{plan.rings[0].label}.dxf" in files
    findings = list(pdf_findings(tmp_path / "0" / pdfs[0]["pdf"], pdfs[0]["pdf"], templates=True))           # what `make-lens check` runs
    assert {f.check for f in findings} >= {"pdf check bar", "pdf text inside page"} and all(f.ok for f in findings)
    monkeypatch.setattr(template_files, "PER_SHEET_PDF_DRAWINGS", 10**6)     # small builds: the one PDF
    (tmp_path / "single").mkdir()
    single = template_files.write_templates(spec, fab, tmp_path / "single")
    assert [e["pdf"] for e in single if "pdf" in e] == ["templates/t-templates.pdf"]
    assert single[-1]["pages"] <= sum(e["pages"] for e in pdfs)     # the same parts; one file shares more pages


@pytest.mark.slow
def test_layup_build_with_per_sheet_pdfs_passes_check(tmp_path, monkeypatch):
    from antenna_cad.export.check import check_build
    from antenna_cad.pipeline import build
    from antenna_cad.spec import load_spec
    monkeypatch.setattr(template_files, "PER_SHEET_PDF_DRAWINGS", 0)
    result = build(load_spec(RECIPES / "luneburg-cylinder-5.yaml"), tmp_path)
    assert any(f.startswith("templates/pdf/") for f in result.files)
    findings = check_build(result.out_dir)
    pdf = [f for f in findings if f.file.startswith("templates/pdf/")]
    assert {f.check for f in pdf} >= {"pdf check bar", "pdf text inside page"}
    assert all(f.ok for f in findings), [f for f in findings if not f.ok]
