"""Template writing cost per drawing and per page (DXF, SVG, tiled PDF) on a Luneburg sheet
layup (20 layers, 10 mm sheets, D/λ = 25: 1131 drawings of sheets and rings), measured on a
sample of drawings; the totals scale linearly with the drawing count.

    PYTHONPATH=. python benchmarks/template_speed.py
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

from antenna_cad.fabrication.rings import fabricate_rings
from antenna_cad.fabrication.templates import write_dxf, write_svg, write_tiled_pdf
from antenna_cad.kinds import luneburg as kind

sys.path.insert(0, str(Path(__file__).parent))
from luneburg_layup import spec_for  # noqa: E402

if __name__ == "__main__":
    spec = spec_for(25)
    design = kind.synthesize(spec)
    layup, _ = kind.plan(spec, design)
    drawings = fabricate_rings(layup, spec.name, drawings=True).drawings
    sample = drawings[:: max(1, len(drawings) // 60)]
    vertices = sum(len(ring) for d in sample for ring in d.cut) / len(sample)
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder)
        t0 = time.perf_counter()
        for d in sample:
            write_dxf(d, out / f"{d.label}.dxf")
        t1 = time.perf_counter()
        for d in sample:
            write_svg(d, out / f"{d.label}.svg")
        t2 = time.perf_counter()
        pages = write_tiled_pdf(sample, out / "templates.pdf", spec.name)
        t3 = time.perf_counter()
        size = (out / "templates.pdf").stat().st_size
    n = len(sample)
    print(f"{len(drawings)} drawings, sample {n} ({vertices:.0f} cut vertices each on average)")
    print(f"DXF {1e3 * (t1 - t0) / n:.1f} ms/drawing, SVG {1e3 * (t2 - t1) / n:.1f} ms/drawing, "
          f"PDF {1e3 * (t3 - t2) / n:.1f} ms/drawing = {1e3 * (t3 - t2) / pages:.2f} ms/page "
          f"({pages} pages, {size / pages / 1e3:.1f} kB/page)")
