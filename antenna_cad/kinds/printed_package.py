"""The printed parts of a lattice lens as the pipeline's fabrication plan: files (3MF, STL per part,
the fill table), cut-list rows with mass, filament length and print time, the checks of the lattice
(cell size, clipped fill, closed meshes, volume, bed, slicer) and the verification tables. Shared by
every kind printed as a lattice (antenna_cad.printed).
"""

from __future__ import annotations

import math
import mmap
from dataclasses import dataclass, field

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.rings import FabPlanRings
from antenna_cad.materials import Material
from antenna_cad.printed.fill import FillMap
from antenna_cad.printed.homogenization import table_rows
from antenna_cad.spec.printed import C_MM_GHZ, PrintedSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.verification import Table, Verification

VOLUME_TOLERANCE = 0.02     # meshed lattice + skin vs ∫fill dV + skin: cell-centre sampling and facets
WIDTH_STEP_NOZZLES = 1 / 8  # rod widths rounded to an eighth of the nozzle (what a slicer can place)
SLICER_FACTOR = 1.25        # slicer's filament vs our volume: extrusion overlap, perimeter/infill seams


@dataclass(frozen=True)
class PrintedFabPlan(FabPlanRings):
    """The pipeline's fabrication-plan fields, plus the lens as printed."""
    lens: object = None                 # antenna_cad.printed.parts.PrintedLens
    fill: FillMap | None = None
    material: Material | None = None
    check_list: tuple[Check, ...] = ()
    figures: dict = field(default_factory=dict)

    @property
    def checks(self) -> tuple[Check, ...]:
        return self.check_list


def package(spec, m: Material, fmap: FillMap, lens, too_many: list, extra_checks: tuple = (),
            step: str = "print on its flat face") -> PrintedFabPlan:
    """The printed parts as files (3MF of all parts, STL per part, the fill table), cut-list rows with
    mass, filament length and print time, the figures and the checks (cell, fill clip, meshes, bed,
    slicer) of a lattice lens ``lens`` (:class:`antenna_cad.printed.parts.PrintedLens`)."""
    from antenna_cad.export.forked import forked_map
    from antenna_cad.printed.export3mf import mesh_rows_bound, stl_size, three_mf_bytes
    fab: PrintedSpec = spec.fabrication
    settings = {"filament": m.name, "filament_eps_r": f"{m.eps_r:g}", "filament_tan_delta": f"{m.tan_delta:g}",
                "nozzle_mm": f"{fab.nozzle_mm:g}", "layer_height_mm": f"{fab.layer_height_mm:g}",
                "infill_percent": "100 (the lattice is the model: print solid, no extra infill)",
                "perimeters": "1", "supports": "none", "lattice": f"{fab.lattice}, cell {fab.cell_mm:g} mm",
                "orientation": fab.orientation}
    rows, files, closed = [], {}, {}
    area = math.pi * (fab.filament_diameter_mm / 2) ** 2
    order = 0
    for part in lens.parts:
        vol = part.volume_mm3
        mass = vol * 1e-9 * m.density_kg_m3
        hours = vol / fab.flow_mm3_s / 3600
        x, y, z = part.size_mm
        how = step if part.role == "lens" else "print standing on an end (a registration pin, half in each part of a cut)"
        for c in range(part.count):
            order += 1
            rows.append(CutRow(f"{part.label}-{c + 1}" if part.count > 1 else part.label, f"printed-{part.role}",
                               m.name, "", 0.0, 0.0, False, x, y, z, 0.0, mass, order,
                               f"{how}; {vol / 1000:.1f} cm³, filament {vol / area / 1000:.2f} m, "
                               f"~{hours:.1f} h at {fab.flow_mm3_s:g} mm³/s; file printed/{part.label}.stl"))
    shared = [(mmap.mmap(-1, stl_size(len(p.faces))), mmap.mmap(-1, mesh_rows_bound(p.vertices, p.faces)))
              for p in lens.parts]          # the children write here: no copy through a pipe
    encoded = forked_map(_part_files, [(p.vertices, p.faces, f"{spec.name} {p.label}", *shared[n])
                                       for n, p in enumerate(lens.parts)])

    def objects():          # each part's files as its child ends: the 3MF deflates it while the others run
        for n, (part, (ends, closed[part.label])) in enumerate(zip(lens.parts, encoded)):
            (stl, text), shared[n] = shared[n], None        # a part's maps are unmapped once it is written
            files[f"printed/{part.label}.stl"] = stl[:]
            stl.close()
            view = memoryview(text)
            yield {"name": part.label, "vertices": part.vertices, "faces": part.faces,
                   "rows": [view[a:b] for a, b in zip([0] + ends[:-1], ends)],
                   "metadata": {"copies": str(part.count), "role": part.role, "volume_mm3": f"{part.volume_mm3:.1f}"}}
    try:
        files[f"printed/{spec.name}.3mf"] = three_mf_bytes(objects(), {"Title": spec.name, "Designer": "make-lens"} |
                                                           {f"make-lens:{k}": v for k, v in settings.items()})
    finally:
        encoded.close()
    files["printed/fill.csv"] = _fill_csv(fmap)
    total_vol = sum(p.volume_mm3 * p.count for p in lens.parts)
    mass_kg = total_vol * 1e-9 * m.density_kg_m3
    figures = {"printed_cells": float(lens.cells), "printed_triangles": float(sum(len(p.faces) for p in lens.parts)),
               "printed_parts": float(sum(p.count for p in lens.parts)), "printed_volume_cm3": total_vol / 1000,
               "printed_mass_kg": mass_kg, "printed_filament_m": total_vol / area / 1000,
               "printed_time_h": total_vol / fab.flow_mm3_s / 3600,
               "printed_fill_min": fmap.fill_range[0], "printed_fill_max": fmap.fill_range[1],
               "printed_eps_min": fmap.eps_range[0], "printed_eps_max": fmap.eps_range[1],
               "printed_max_eps_error": float(abs(fmap.eps_error).max()),
               "printed_volume_error": lens.body_volume_mm3 / lens.reference_volume_mm3 - 1}
    slice_check, slice_figures = _slicer_check(fab, files[f"printed/{spec.name}.3mf"],
                                               sum(p.volume_mm3 for p in lens.parts), area)
    figures |= slice_figures
    checks = too_many + fill_checks(spec, fab, m, fmap) + _mesh_checks(fab, lens, closed) + \
        list(extra_checks) + [slice_check]
    return PrintedFabPlan((), {}, {}, (), tuple(rows), {m.name: mass_kg, "all": mass_kg}, {}, 0.0, {}, {},
                          files=files, lens=lens, fill=fmap, material=m, check_list=tuple(checks), figures=figures)




def fill_checks(spec, fab, m, fmap: FillMap) -> list[Check]:
    """The lattice's cell size, the fill clipped to the printable range, the table's εr range."""
    limit = C_MM_GHZ / spec.frequency_ghz / (4 * math.sqrt(m.eps_r))
    out = [Check.upper("printed_cell_size", fab.cell_mm, limit, "mm",
                       f"lattice cell ≤ λ/(4·√εr) of {m.name} (homogeneous medium)")]
    err = float(abs(fmap.eps_error).max())
    clipped = fmap.clipped_regions()
    where = "; ".join(f"r {c['r_from_mm']:.1f}–{c['r_to_mm']:.1f} mm {c['side']} (law εr {c['eps_law_min']:.3f}–"
                      f"{c['eps_law_max']:.3f}, printed {c['eps_printed']:.3f})" for c in clipped)
    out.append(Check("printed_fill_clipped", "warn" if clipped else "pass", err, 0.0, "εr",
                     f"fill clipped to the printable range {fmap.fill_range[0]:.3f}–{fmap.fill_range[1]:.3f} "
                     f"(εr {fmap.eps_range[0]:.3f}–{fmap.eps_range[1]:.3f}): {where or 'nowhere'}"))
    tabulated = sorted({r["eps_f"] for r in table_rows() if r["lattice"] == fab.lattice})
    if not tabulated[0] <= m.eps_r <= tabulated[-1]:
        out.append(Check("printed_homogenization_range", "warn", m.eps_r, tabulated[-1], "εr",
                         f"filament εr {m.eps_r:g} outside the unit-cell table ({tabulated[0]:g}–{tabulated[-1]:g}): "
                         "εr_eff(fill) extrapolated by its Wiener-normalized shape"))
    return out


def _part_files(vertices, faces, name: str, stl, text) -> tuple[list[int], bool]:
    """One part's binary STL and its mesh text of the 3MF (UTF-8) written into the buffers ``stl`` and
    ``text``; the end of each piece of text and whether the mesh is closed and oriented: what
    :func:`package` makes of the parts at once, one child process each."""
    from antenna_cad.printed.export3mf import mesh_rows_into, stl_into
    from antenna_cad.printed.parts import closed_and_oriented
    stl_into(stl, vertices, faces, name)
    return mesh_rows_into(text, vertices, faces), closed_and_oriented(faces)


def _mesh_checks(fab, lens, closed: dict[str, bool]) -> list[Check]:
    """The printed parts' meshes: closed and oriented (``closed``: by label), their volume, registration
    pins, the bed."""
    out = []
    bad = [p.label for p in lens.parts if not closed[p.label]]
    out.append(Check("printed_parts_closed", "fail" if bad else "pass", float(len(bad)), 0.0, "parts",
                     f"every part's mesh closed and consistently oriented (each directed edge once, its reverse "
                     f"once); {', '.join(bad) or 'none'} failing"))
    rel = lens.body_volume_mm3 / lens.reference_volume_mm3 - 1
    out.append(Check.upper("printed_volume", abs(rel), VOLUME_TOLERANCE, "",
                           f"meshed lattice + skin {lens.body_volume_mm3 / 1000:.1f} cm³ vs analytic ∫fill dV + skin "
                           f"{lens.reference_volume_mm3 / 1000:.1f} cm³ ({rel:+.2%})"))
    if fab.registration is None and lens.cuts:
        out.append(Check("printed_registration", "warn", float(lens.cuts), 0.0, "cuts",
                         f"{lens.cuts} bed cuts and no registration pins (fabrication.registration: null): align "
                         "and bond the parts on a flat plate (a jig)"))
    if fab.registration is not None and lens.unpinned_cuts:
        out.append(Check("printed_registration", "warn", float(lens.unpinned_cuts), 0.0, "cuts",
                         f"{lens.unpinned_cuts} bed cuts leave no room for a Ø{fab.registration.diameter_mm:g} mm pin "
                         "boss: align those parts by hand (a jig) or use a larger bed"))
    bed = (fab.bed.x_mm, fab.bed.y_mm, fab.bed.z_mm)
    over = [p.label for p in lens.parts if any(s > b + 1e-6 for s, b in zip(p.size_mm, bed))]
    out.append(Check("printed_parts_fit_bed", "fail" if over else "pass", float(len(over)), 0.0, "parts",
                     f"{sum(p.count for p in lens.parts)} parts within the {bed[0]:g}×{bed[1]:g}×{bed[2]:g} mm bed "
                     f"({lens.cuts} bed cuts, {lens.pins} registration pins)"))
    return out


def registration_pins(fab):
    """The spec's registration pins (bosses one min wall thick), or None: align by hand."""
    from antenna_cad.printed.parts import Pins
    r = fab.registration
    return None if r is None else Pins(r.diameter_mm, r.length_mm, r.clearance_mm, fab.wall_mm)


def _slicer_check(fab: PrintedSpec, three_mf: bytes, plate_mm3: float, area_mm2: float) -> tuple[Check, dict]:
    """The 3MF sliced by PrusaSlicer (each part once, one plate), its filament and time beside ours for
    the same plate; skip when not asked for or no slicer is on the PATH."""
    from antenna_cad.printed.slicer import EXECUTABLE, SlicerError, SlicerTimeout, find_slicer, slice_3mf
    ours_h = plate_mm3 / fab.flow_mm3_s / 3600
    if not fab.slicer_check or find_slicer() is None:
        why = "off (fabrication.slicer_check: false)" if not fab.slicer_check else f"{EXECUTABLE} not on the PATH"
        return Check("printed_slicer", "skip", 0.0, SLICER_FACTOR, "×", f"slicer check not run: {why}"), {}
    try:
        s = slice_3mf(three_mf, nozzle_mm=fab.nozzle_mm, layer_height_mm=fab.layer_height_mm,
                      filament_diameter_mm=fab.filament_diameter_mm, timeout_s=fab.slicer_timeout_s)
    except SlicerTimeout as err:
        return Check("printed_slicer", "warn", 0.0, SLICER_FACTOR, "×",
                     f"not judged: {err}; raise fabrication.slicer_timeout_s or slice the 3MF yourself"), {}
    except SlicerError as err:
        return Check("printed_slicer", "fail", 0.0, SLICER_FACTOR, "×", f"the 3MF does not slice: {err}"), {}
    ratio = s.filament_cm3 * 1000 / plate_mm3
    ok = 1 / SLICER_FACTOR <= ratio <= SLICER_FACTOR
    figures = {"printed_slicer_layers": float(s.layers), "printed_slicer_filament_m": s.filament_mm / 1000,
               "printed_slicer_volume_cm3": s.filament_cm3, "printed_slicer_time_h": s.time_s / 3600,
               "printed_plate_filament_m": plate_mm3 / area_mm2 / 1000, "printed_plate_time_h": ours_h}
    return Check("printed_slicer", "pass" if ok else "warn", ratio, SLICER_FACTOR, "×",
                 f"{s.slicer} slices the 3MF (each part once, solid, {s.layers} layers): filament "
                 f"{s.filament_cm3:.1f} cm³ / {s.filament_mm / 1000:.2f} m, {s.time_s / 3600:.2f} h; ours "
                 f"{plate_mm3 / 1000:.1f} cm³ / {plate_mm3 / area_mm2 / 1000:.2f} m, {ours_h:.2f} h at "
                 f"{fab.flow_mm3_s:g} mm³/s (filament ratio {ratio:.3f}, expected within ×{SLICER_FACTOR:g})"), figures


def _fill_csv(fmap: FillMap) -> str:
    lines = ["# fill along the law: r, law εr, chosen fill (clipped), εr_eff of that fill (unit-cell table), error",
             "r_mm,eps_law,fill,eps_printed,eps_error"]
    for r, e, f, p in zip(fmap.r_mm, fmap.eps_law, fmap.fill, fmap.eps_printed):
        lines.append(f"{r:.3f},{e:.5f},{f:.5f},{p:.5f},{p - e:+.5f}")
    return "\n".join(lines) + "\n"


def printed_verification(fab: PrintedFabPlan) -> Verification:
    """The printed lens's figures and its tables (clipped regions, parts) for the manifest and report."""
    clipped = tuple((round(c["r_from_mm"], 2), round(c["r_to_mm"], 2), round(c["eps_law_min"], 4),
                     round(c["eps_law_max"], 4), round(c["eps_printed"], 4), round(c["max_abs_eps_error"], 4),
                     c["side"]) for c in fab.fill.clipped_regions())
    parts = tuple((p.label, p.role, p.count, *(round(s, 2) for s in p.size_mm), len(p.faces),
                   round(p.volume_mm3 / 1000, 2)) for p in fab.lens.parts)
    return Verification(figures=dict(fab.figures), tables=(
        Table("printed-clipped", "Printed lattice: clipped regions",
              ("r from mm", "r to mm", "law εr min", "law εr max", "printed εr", "max |εr error|", "where"), clipped,
              caption="fill outside the printable range (thinnest wall, narrowest gap) is clipped; the lens is "
                      "denser or lighter than its law there"),
        Table("printed-parts", "Printed parts", ("part", "role", "copies", "x mm", "y mm", "z mm", "triangles",
                                                 "volume cm³"), parts,
              caption="one object per part in the 3MF; STL per part in printed/")))
