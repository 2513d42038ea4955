"""Build every recipe (full-wave hidden) and write the docs gallery: docs/gallery.md and one assembly
view and one template picture per recipe in docs/gallery/ (small PNGs, committed).

    python docs/gen_gallery.py [RECIPE ...] [--work DIR]

Named recipes are rebuilt and their sections replaced (or added) in the existing page.

The assembly view is the one embedded in each build's report.html; the template picture is the first
1:1 drawing (DXF) drawn by ezdxf; the key figures are the manifest's. A recipe that fails to build gets
a row saying so. Run from the repository root; the builds go to a temporary folder.
"""

from __future__ import annotations

import argparse
import base64
import io
import os
import re
import sys
import tempfile
from pathlib import Path

DOCS = Path(__file__).resolve().parent
WIDTH_PX = 560
FIGURES_SHOWN = 8


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recipes", nargs="*", help="recipe names (default: all)")
    parser.add_argument("--work", type=Path, help="build folder, whose earlier builds are reused (default: a temporary one)")
    parser.add_argument("--no-build", action="store_true", help="only the builds already in --work (the page marks the rest)")
    args = parser.parse_args()
    os.environ["ANTENNA_CAD_MEEP_PYTHON"] = "/usr/bin/false"      # full-wave hidden: the gallery shows geometry
    from antenna_cad import api
    chosen = [r for r in api.recipes() if not args.recipes or r.name in args.recipes]
    work = args.work or Path(tempfile.mkdtemp(prefix="gallery-"))
    (DOCS / "gallery").mkdir(exist_ok=True)
    entries = []
    for r in chosen:
        print(f"building {r.name} …", file=sys.stderr, flush=True)
        try:
            done = work / r.name / "manifest.json"         # kept from an earlier run into the same --work
            if args.no_build and not done.is_file():
                entries.append((r, None, "not built in the last gallery run"))
                continue
            result = api.read_build(done.parent) if args.work and done.is_file() else api.build(r.name, work)
        except (api.SpecError, api.DesignError, api.OutputError) as exc:
            entries.append((r, None, f"does not build: {exc}"))
            continue
        _save_view(result.out_dir / "report.html", DOCS / "gallery" / f"{r.name}.png")
        drawn = _save_template(result.out_dir, DOCS / "gallery" / f"{r.name}-template.png")
        entries.append((r, result, drawn))
    page = DOCS / "gallery.md"
    if args.recipes and page.is_file():         # only the named recipes rebuilt: the others' sections kept
        page.write_text(_merged(page.read_text(encoding="utf-8"), entries, api.recipes()), encoding="utf-8")
    else:
        page.write_text(_page(entries), encoding="utf-8")


def _save_view(report: Path, target: Path) -> None:
    """The first picture in the report (the assembly views), scaled to the gallery's width."""
    match = re.search(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', report.read_text(encoding="utf-8"))
    if match:
        _write_small(base64.b64decode(match.group(1)), target)


def _save_template(folder: Path, target: Path) -> str | None:
    """The first template drawing (DXF) as a picture; its file name, or None when the build has none."""
    dxfs = sorted((folder / "templates").glob("*.dxf")) if (folder / "templates").is_dir() else []
    if not dxfs:
        return None
    import ezdxf
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from ezdxf.addons.drawing import Frontend, RenderContext
    from ezdxf.addons.drawing.config import BackgroundPolicy, ColorPolicy, Configuration
    from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
    doc = ezdxf.readfile(dxfs[0])
    fig = plt.figure(figsize=(6, 4.5), dpi=100)
    ax = fig.add_axes([0, 0, 1, 1])
    paper = Configuration(background_policy=BackgroundPolicy.WHITE, color_policy=ColorPolicy.BLACK)
    Frontend(RenderContext(doc), MatplotlibBackend(ax), config=paper).draw_layout(doc.modelspace())
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", facecolor="white")
    plt.close(fig)
    _write_small(buffer.getvalue(), target)
    return dxfs[0].name


def _write_small(png: bytes, target: Path) -> None:
    """Scale to WIDTH_PX and store as an adaptive-palette PNG (the gallery is committed)."""
    import matplotlib.image as mpimg
    import numpy as np
    from PIL import Image
    pixels = mpimg.imread(io.BytesIO(png), format="png")
    image = Image.fromarray((np.clip(pixels, 0, 1) * 255).astype("uint8"))
    if image.width > WIDTH_PX:
        image = image.resize((WIDTH_PX, round(image.height * WIDTH_PX / image.width)), Image.LANCZOS)
    image.convert("RGB").quantize(colors=128).save(target, optimize=True)


def _figure(value: object) -> str:
    if isinstance(value, float):
        return "0" if abs(value) < 1e-9 else f"{value:.4g}"
    return str(value)


def _page(entries) -> str:
    lines = ["# Gallery", "",
             "Every bundled recipe, built with full-wave verification hidden: the assembly views from its "
             "`report.html`, its first 1:1 template, and its first key figures from `manifest.json`. "
             "Rebuilt by `python docs/gen_gallery.py` (from the repository root); build one yourself with "
             "`make-lens RECIPE`.", ""]
    for r, result, drawn in entries:
        lines += [f"## {r.name}", "", f"`kind: {r.kind}` — {r.summary}", ""]
        if result is None:
            lines += [f"!!! warning \"{drawn}\"", ""]
            continue
        lines += [f"![{r.name} assembly views](gallery/{r.name}.png){{ width=\"{WIDTH_PX}\" }}"]
        if drawn:
            lines += [f"![{r.name} template {drawn}](gallery/{r.name}-template.png){{ width=\"360\" }}"]
        shown = [(k, v) for k, v in result.figures.items() if isinstance(v, (int, float))][:FIGURES_SHOWN]
        lines += ["", "| figure | value |", "|---|---|"]
        lines += [f"| `{k}` | {_figure(v)} |" for k, v in shown]
        counts = {s: sum(c.status == s for c in result.checks) for s in ("pass", "warn", "fail")}
        lines += ["", f"Checks: {counts['pass']} pass, {counts['warn']} warn, {counts['fail']} fail; "
                      f"{len(result.parts)} parts, {len(result.files)} files.", ""]
    return "\n".join(lines)


def _merged(old_page: str, entries, recipes) -> str:
    """The gallery page with the rebuilt recipes' sections replaced or inserted, in the recipes' order."""
    sections = {}
    for block in re.split(r"^(?=## )", old_page, flags=re.M)[1:]:
        sections[block.split("\n", 1)[0][3:].strip()] = block.rstrip("\n") + "\n"
    for entry in entries:
        sections[entry[0].name] = "## " + _page([entry]).split("\n## ", 1)[1].rstrip("\n") + "\n"
    header = _page([]).rstrip("\n") + "\n"
    return "\n".join([header] + [sections[r.name] for r in recipes if r.name in sections])


if __name__ == "__main__":
    main()
