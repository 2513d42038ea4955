"""Fabrication plan of the graded-index lens (seed-001 §3.2): slabs of constant permittivity, each a
1:1 template (its section), the slab table (CSV), the cut list and the masses.

Frame: the synthesis frame in mm — drawing x = lens axis x, drawing y = transverse y, lens centre
between the vertices at the origin of x as synthesized (surface-1 vertex at −d1).
"""

from __future__ import annotations

import io

import numpy as np
from shapely.geometry import Polygon, box

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.graded_design import GradedDesign

SECTION_POINTS = 801


def section_polygon(design: GradedDesign) -> Polygon:
    """Lens section in mm: surface 1 upward, surface 2 downward."""
    u, h = design.unit_mm, design.half_aperture
    y = np.linspace(-h, h, SECTION_POINTS)
    return Polygon(list(zip(design.x1(y) * u, y * u)) + list(zip(design.x2(y[::-1]) * u, y[::-1] * u)))


def slab_pieces(design: GradedDesign) -> list[tuple[str, int, Polygon]]:
    """(label, slab index, section polygon in mm): slab 0 is the central band, the others a top and a
    bottom piece each."""
    sec, u = section_polygon(design), design.unit_mm
    minx, _, maxx, _ = sec.bounds
    out = []
    for k, (lo, hi) in enumerate(zip(design.slab_edges[:-1] * u, design.slab_edges[1:] * u)):
        if k == 0:
            out.append((f"slab-{k:02d}", k, sec.intersection(box(minx - 1, -hi, maxx + 1, hi))))
            continue
        out.append((f"slab-{k:02d}-top", k, sec.intersection(box(minx - 1, lo, maxx + 1, hi))))
        out.append((f"slab-{k:02d}-bottom", k, sec.intersection(box(minx - 1, -hi, maxx + 1, -lo))))
    return out


def slab_material(base: Material, eps: float) -> Material:
    return Material(f"{base.name} εr {eps:.4f}", float(eps), base.tan_delta, base.density_kg_m3,
                    "slab of the synthesized permittivity (loss and density of the base material)")


def slabs_csv(design: GradedDesign) -> str:
    buf = io.StringIO()
    buf.write("slab,y_lo_mm,y_hi_mm,eps_r,n_lo,n_hi\n")
    u = design.unit_mm
    for k, (lo, hi, eps) in enumerate(zip(design.slab_edges[:-1], design.slab_edges[1:], design.slab_eps)):
        n_lo, n_hi = design.n(np.array([lo, hi]))
        buf.write(f"{k},{lo * u:.6f},{hi * u:.6f},{eps:.6f},{n_lo:.6f},{n_hi:.6f}\n")
    return buf.getvalue()


def fabricate_graded(design: GradedDesign, base: Material, height_mm: float, allowance_mm: float,
                     title: str) -> FabPlan:
    rows, drawings, totals = [], [], {}
    for order, (label, k, poly) in enumerate(slab_pieces(design), start=1):
        mat = slab_material(base, design.slab_eps[k])
        minx, miny, maxx, maxy = poly.bounds
        kg = poly.area * height_mm / 1e9 * mat.density_kg_m3
        totals[mat.name] = totals.get(mat.name, 0.0) + kg
        rows.append(CutRow(label, "machined-slab", mat.name, "stock", 0.0, 0.0, False,
                           maxx - minx + 2 * allowance_mm, maxy - miny + 2 * allowance_mm, height_mm,
                           poly.area / 1e6, kg, order, f"εr {design.slab_eps[k]:.4f}; bond in order of y"))
        d = Drawing(label)
        d.add_polygon(poly)
        d.add_title([f"{title}: {label} 1:1, εr {design.slab_eps[k]:.4f}, height {height_mm:g} mm"],
                    minx, maxy + 10.0)
        d.add_check_bar(minx, miny - 20.0)
        drawings.append(d)
    totals["all"] = sum(totals.values())
    return FabPlan((), {}, {}, tuple(drawings), tuple(rows), totals, {}, 0.0, {"slabs.csv": slabs_csv(design)})
