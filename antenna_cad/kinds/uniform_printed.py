"""``fabrication.method: printed`` for a body of one index n = ``design.refractive_index`` — the
aplanatic mirror-lens body (seed-004) and the single-surface collimator (seed-000): printed from one
filament (``material``) as a uniform cubic lattice whose εr_eff = n² (antenna_cad.printed), inside a
solid skin that gives the refracting (and mirror) faces their smooth surface.

The fill comes from the shipped unit-cell table; the rods alternate layer by layer between the two
nearest widths a slicer places, so the body as printed has their mean εr — the GO and full-wave checks trace it at that εr
(the "fabricated" body) beside the design's n. Loss and density of the lattice: the filament's
scaled by the fill (parallel mixture: ε'' = f·ε''_f, so tanδ = f·εf·tanδf/εeff).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from antenna_cad.kinds.printed_package import (WIDTH_STEP_NOZZLES, PrintedFabPlan, fill_checks, package,
                                              registration_pins)
from antenna_cad.limits import LIMITS
from antenna_cad.materials import Material
from antenna_cad.printed.fill import FillMap, dithered_fill, dithered_widths, eps_of_width, fill_map, rod_width_mm
from antenna_cad.printed.lattice import Printable
from antenna_cad.spec.common import resolve_material
from antenna_cad.spec.printed import PrintedSpec
from antenna_cad.stages import with_cad
from antenna_cad.synthesis.checks import Check

REFERENCE_STEP_CELLS = 1 / 8    # midpoint grid of the analytic ∫fill dV, in cells


@dataclass(frozen=True)
class LatticeBody:
    """The uniform lattice of the printed body: the filament, its fill map (law εr = n²), the rod
    width as printed and what it gives."""
    filament: Material
    fmap: FillMap
    width_mm: float
    fill: float
    eps_target: float
    eps_printed: float

    def material(self, eps_r: float) -> Material:
        """The lattice as a homogeneous dielectric of ``eps_r`` (fill-scaled loss and density)."""
        f, m = self.fill, self.filament
        return Material(f"{m.name}-lattice-{eps_r:.3f}", eps_r, f * m.eps_r * m.tan_delta / eps_r,
                        f * m.density_kg_m3, f"{m.name} printed as a cubic lattice at fill {f:.3f}")


def lattice_body(spec) -> LatticeBody:
    """The fill for εr_eff = n², clipped to the printable range; the rods alternate layer by layer
    between the two nearest widths a slicer places (an eighth of the nozzle apart) so that their mean
    along the axis — the beam's direction — follows it (:func:`antenna_cad.printed.fill.dithered_widths`)."""
    fab = spec.fabrication
    m = resolve_material(spec.material)
    eps = spec.design.refractive_index ** 2
    printable = Printable(fab.lattice, fab.cell_mm, fab.wall_mm, fab.gap_mm)
    fmap = fill_map(lambda r: np.full(np.shape(r), eps), 1.0, fab.lattice, m.eps_r, printable, samples=3)
    w = float(rod_width_mm(fmap, 0.0))
    f, e = dithered_fill(w, *widths_limits(fab), fab.cell_mm, fab.lattice, m.eps_r)
    return LatticeBody(m, fmap, w, float(f), eps, float(e))


def index_material(spec, as_printed: bool = False) -> Material:
    """The body's dielectric: the spec's material, or when printed the lattice at n² (``as_printed``: at
    the εr its rods give)."""
    if not isinstance(spec.fabrication, PrintedSpec):
        return resolve_material(spec.material)
    body = lattice_body(spec)
    return body.material(body.eps_printed if as_printed else body.eps_target)


def widths_limits(fab) -> tuple[float, float, float]:
    """(step, thinnest, widest) rod width the printer places."""
    return fab.nozzle_mm * WIDTH_STEP_NOZZLES, fab.wall_mm, fab.cell_mm - fab.gap_mm


def revolved_envelope(section_mm: np.ndarray):
    """A body of revolution's meridian section (r, z) (r ≥ 0, closed) as the printed body's envelope."""
    from shapely.geometry import Polygon

    from antenna_cad.printed.body import Envelope
    return Envelope("revolved", Polygon(section_mm).buffer(0))


def printed_eps_check(body: LatticeBody, tolerance: float) -> Check:
    """The body as printed against n², within the spec's εr tolerance (tolerances.eps_r_tolerance)."""
    err = body.eps_printed - body.eps_target
    return Check("printed_eps_error", "pass" if abs(err) <= tolerance else "warn", abs(err), tolerance, "εr",
                 f"body as printed: rods of mean width {body.width_mm:.3f} mm (fill {body.fill:.3f}, two printable widths "
                 f"alternated layer by layer) give εr_eff {body.eps_printed:.4f} vs n² = {body.eps_target:.4f} ({err:+.5f})")


def fabricate_printed(spec, section_mm: np.ndarray, volume_mm3: float, radius_mm: float, step: str) -> PrintedFabPlan:
    """The body of revolution of meridian section ``section_mm`` (:func:`revolved_envelope`; ``volume_mm3``,
    largest radius ``radius_mm``) as printed parts (3MF, STL per part), cut list and checks; ``step``: how
    it is printed (the cut list's process step). Without the CAD stages, the checks only (no mesh library
    is loaded)."""
    fab = spec.fabrication
    body = lattice_body(spec)
    too_many = LIMITS["cells"].check(round(volume_mm3 / fab.cell_mm**3))
    checks = (printed_eps_check(body, spec.tolerances.eps_r_tolerance),)
    if not with_cad():
        return PrintedFabPlan((), {}, {}, (), (), {}, {}, 0.0, {}, {}, fill=body.fmap, material=body.filament,
                              check_list=tuple(too_many + fill_checks(spec, fab, body.filament, body.fmap)) + checks)
    from antenna_cad.export.forked import forked_map
    from antenna_cad.printed.body import body_cells, build_lattice_body, reference_volume_mm3
    from antenna_cad.printed.parts import segments
    tol = spec.outputs.mesh_tolerance_mm
    env = revolved_envelope(section_mm)
    idx, centre, inner = body_cells(env, fab.cell_mm, fab.skin_mm, tol)
    ref = reference_volume_mm3(env, lambda u, w: np.full(np.shape(u), body.fill), fab.skin_mm,
                               fab.cell_mm * REFERENCE_STEP_CELLS)
    eps = eps_of_width(fab.lattice, body.filament.eps_r, fab.cell_mm)
    widths, _ = dithered_widths(np.full(len(idx), body.width_mm), idx[:, 2], *widths_limits(fab), eps)
    lens = build_lattice_body(env, idx, centre, inner, widths, fab.cell_mm,
                              skin_mm=fab.skin_mm, bed_mm=(fab.bed.x_mm, fab.bed.y_mm, fab.bed.z_mm), tolerance_mm=tol,
                              segments=segments(radius_mm, tol), reference_volume_mm3=ref, pins=registration_pins(fab),
                              map_parts=forked_map)
    return package(spec, body.filament, body.fmap, lens, too_many, checks, step=step)


def summary_figures(spec) -> dict[str, float]:
    body = lattice_body(spec)
    return {"printed_eps_target": body.eps_target, "printed_eps": body.eps_printed,
            "printed_eps_error": body.eps_printed - body.eps_target, "printed_fill": body.fill,
            "printed_rod_mm": body.width_mm, "printed_n": math.sqrt(body.eps_printed)}
