"""The template files of a build: DXF + SVG per drawing and the tiled PDF — one file, or
for a big sheet layup one PDF per sheet, written by two forked workers over disjoint sheets.

A sheet layup's plan (``SheetDrawings``) groups its drawings by sheet. Above
:data:`PER_SHEET_PDF_DRAWINGS` drawings (the soft limit of ``antenna_cad.limits``: 300) one PDF
would hold 10⁵ pages (a 3 m Luneburg layup: 219,000); a user prints the sheet he is cutting, so
each sheet gets ``templates/pdf/<sheet>.pdf`` with its assembly view and its ring and foot
templates, the pages as in the single file. The sheets are then shared out to :data:`WORKERS`
processes by their estimated page count (largest first, to the least loaded); each file is written
by the same function whichever process writes it, so the bytes are those of a serial run
(``ANTENNA_CAD_SERIAL=1``, ``export.forked``)."""

from __future__ import annotations

from pathlib import Path

PER_SHEET_PDF_DRAWINGS = 300
WORKERS = 2


def per_sheet(fab) -> bool:
    """True when the PDF is one file per sheet (a sheet-grouped plan above the drawing count)."""
    return hasattr(fab.drawings, "groups") and len(fab.drawings) > PER_SHEET_PDF_DRAWINGS


def template_files(spec, fab, out: Path) -> list[Path]:
    """The files :func:`write_templates` writes, named from the drawings' labels (a lazily built
    plan knows them without drawing: ``SheetDrawings.labels``)."""
    folder = out / "templates"
    labels = getattr(fab.drawings, "labels", None) or [d.label for d in fab.drawings]
    pdfs = ([folder / "pdf" / f"{group[0]}.pdf" for group in fab.drawings.groups] if per_sheet(fab)
            else [folder / f"{spec.name}-templates.pdf"])
    return [folder / f"{label}.{ext}" for label in labels for ext in ("dxf", "svg")] + pdfs


def write_templates(spec, fab, out: Path) -> list[dict]:
    """Write the template files; returns their manifest entries (files, the CUT outline's bounding
    box, the SVG's size; each PDF's pages) that ``make-lens check`` measures again."""
    from antenna_cad.export.forked import Job
    folder = out / "templates"
    folder.mkdir(exist_ok=True)
    if not per_sheet(fab):
        entries: list[dict] = []
        pages = _write_pdf(spec, _written(fab.drawings, folder, entries), folder / f"{spec.name}-templates.pdf")
        return entries + [{"label": "all", "pdf": f"templates/{spec.name}-templates.pdf", "pages": pages}]
    (folder / "pdf").mkdir(exist_ok=True)
    shares = _shares(fab.drawings.weights, WORKERS)
    jobs = [Job(_write_sheets, (spec, fab, folder, share)) for share in shares[1:]]
    try:
        done = _write_sheets(spec, fab, folder, shares[0])
        for job in jobs:
            done |= job.finish()
    finally:
        for job in jobs:                    # stopped when this share failed (no-op once finished)
            job.finish(wait=False)
    return [entry for k in sorted(done) for entry in done[k]]


def _write_sheets(spec, fab, folder: Path, sheets: list[int]) -> dict[int, list[dict]]:
    """Per sheet index: its drawings' DXF + SVG and its PDF; their manifest entries."""
    done = {}
    for k in sheets:
        entries: list[dict] = []
        label = fab.drawings.groups[k][0]
        pages = _write_pdf(spec, _written(fab.drawings.sheet(k), folder, entries), folder / "pdf" / f"{label}.pdf")
        done[k] = entries + [{"label": label, "pdf": f"templates/pdf/{label}.pdf", "pages": pages}]
    return done


def _written(drawings, folder: Path, entries: list[dict]):
    """The drawings, each after its pieces are named (``piece_labels``) and its DXF and SVG
    written (its entry appended): one pass, so a lazily built plan draws each sheet once."""
    from antenna_cad.fabrication.piece_labels import name_pieces
    from antenna_cad.fabrication.templates import write_dxf, write_svg
    for drawing in drawings:
        name_pieces(drawing)
        write_dxf(drawing, folder / f"{drawing.label}.dxf")
        svg_mm = write_svg(drawing, folder / f"{drawing.label}.svg")
        entries.append({"label": drawing.label, "dxf": f"templates/{drawing.label}.dxf",
                        "svg": f"templates/{drawing.label}.svg", "cut_bbox_mm": list(drawing.cut_bounds()),
                        "svg_size_mm": list(svg_mm)})
        yield drawing


def _write_pdf(spec, drawings, path: Path) -> int:
    from antenna_cad.fabrication.templates import write_tiled_pdf
    return write_tiled_pdf(drawings, path, spec.name)


def _shares(weights: list[float], workers: int) -> list[list[int]]:
    """Sheet indices split into ``workers`` sorted lists of about equal weight (largest first, each
    to the least loaded share)."""
    shares: list[list[int]] = [[] for _ in range(workers)]
    loads = [0.0] * workers
    for k in sorted(range(len(weights)), key=lambda k: (-weights[k], k)):
        w = loads.index(min(loads))
        shares[w].append(k)
        loads[w] += weights[k]
    return [sorted(s) for s in shares if s] or [[]]
