"""Adapters of the polyfocal constrained lens (seed-001 §1, §2) between its spec and the stages.

``material`` fills the lines; the metal (plates, septa, port surfaces) is named in ``fabrication``.
Verification reads the line table back from the fabrication plan (``lines.csv``) and recomputes the
RMS aberration σ (seed-001 (1.4)) against the field angle for the lines as built.
"""

from __future__ import annotations

import csv
import io
from dataclasses import replace

import numpy as np

from antenna_cad.asbuilt.patterns_arrays import (array_patterns, chief_note, imaged_case, path_mm, ports_case,
                                                 referred)
from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.polyfocal import channel_clearance_check, fabricate_polyfocal
from antenna_cad.fabrication.polyfocal_sections import gauges_drawing, section_gauges
from antenna_cad.kinds import polyfocal_mirror
from antenna_cad.materials import Material
from antenna_cad.spec.common import resolve_material
from antenna_cad.spec.polyfocal import PolyfocalSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.collimator import wavelength_mm
from antenna_cad.synthesis.polyfocal import ConstrainedLens
from antenna_cad.synthesis.polyfocal_analysis import best_direction, image_circle, image_of, sigma_scan, source_on
from antenna_cad.synthesis.polyfocal_design import PolyfocalDesign, grid_3d, solve_case, synthesize_polyfocal
from antenna_cad.verification import Plot, Series, Table, Verification

SUMMARY_ANGLES = 7           # field angles 0 … half view listed in the summary
GAUGE_GRID = 48             # exact points across the aperture for the 3-D section gauges
AS_BUILT_LIMIT = 1e-9        # as-built σ/D may exceed the element σ/D by this (table rounding: 1e-6 mm)


def synthesize(spec: PolyfocalSpec) -> PolyfocalDesign:
    g, ln = spec.design, spec.design.lines
    design = synthesize_polyfocal(
        case=g.case, foci=g.resolved_foci(), unit_mm=g.unit_mm, aperture=g.aperture,
        thickness=g.thickness, law=g.line_law, straight_index=g.straight_index, view_angle_deg=g.view_angle_deg,
        line_type=ln.type, pitch_mm=ln.pitch_mm, phase_index=ln.phase_index, wall_mm=ln.wall_mm,
        height_mm=ln.plate_spacing_mm, fill_eps_r=resolve_material(spec.material).eps_r,
        wavelength_mm=wavelength_mm(spec.frequency_ghz), focal_axis_z=g.focal_axis_z)
    return design if g.lens_mirror is None else polyfocal_mirror.with_mirror(spec, design)


def _metal(spec: PolyfocalSpec) -> Material:
    f = spec.fabrication
    return Material(f.metal, 1.0, 0.0, f.metal_density_kg_m3, "metal (conductor), from fabrication")


def plan(spec: PolyfocalSpec, design: PolyfocalDesign):
    """No layup: plates, septa and channels are machined; the model reads the design directly."""
    return None, ()


def model(spec: PolyfocalSpec, design: PolyfocalDesign, layup, panels):
    from antenna_cad.geometry.polyfocal import build_model
    ln = spec.design.lines
    if design.mirror is not None:
        return polyfocal_mirror.model(design, resolve_material(spec.material), _metal(spec), ln.plate_thickness_mm,
                                      ln.margin_mm)
    return build_model(design, resolve_material(spec.material), _metal(spec), ln.plate_thickness_mm, ln.margin_mm)


def fabricate(spec: PolyfocalSpec, design: PolyfocalDesign, layup, panels):
    ln = spec.design.lines
    if design.mirror is not None:
        return polyfocal_mirror.fabricate(design, _metal(spec), ln.plate_thickness_mm, ln.margin_mm, spec.name)
    fab = fabricate_polyfocal(design, resolve_material(spec.material), _metal(spec), ln.plate_thickness_mm,
                              ln.margin_mm, spec.name)
    if design.case.startswith("2d"):
        return fab
    pitch = _gauge_pitch(spec)
    gauges, _ = _gauges(spec, design)
    drawings = tuple(gauges_drawing(gauges, s, pitch, spec.name) for s in ("entry", "exit"))
    rows = tuple(CutRow(f"gauges-{s}", "section-gauge", "gauge stock", "stock", 0, 0, False, 0, 0, 0, 0, 0, 0,
                        f"{sum(g.surface == s for g in gauges)} gauges, template gauges-{s}") for s in ("entry", "exit"))
    return replace(fab, drawings=fab.drawings + drawings, rows=fab.rows + rows)


def _gauge_pitch(spec: PolyfocalSpec) -> float:
    return spec.fabrication.section_pitch_mm or spec.design.lines.pitch_mm


_LAST_GAUGES: list = []       # [(design, pitch, depth, result)] of the latest section_gauges call


def _gauges(spec: PolyfocalSpec, design: PolyfocalDesign):
    """:func:`section_gauges` of the design, computed once for fabricate and fabrication_checks (the
    same design object, pitch and depth: the same answer; the interpolant's gradients cost ~1 s)."""
    key = (_gauge_pitch(spec), spec.fabrication.gauge_depth_mm)
    if not (_LAST_GAUGES and _LAST_GAUGES[0][0] is design and _LAST_GAUGES[0][1] == key):
        _LAST_GAUGES[:] = [(design, key, section_gauges(design, _gauge_grid(spec), *key))]
    return _LAST_GAUGES[0][2]


def _gauge_grid(spec: PolyfocalSpec) -> ConstrainedLens:
    """The lens solved on a D/GAUGE_GRID grid for the section gauges (its nodes miss the element
    points but at the centre and the rim, so those stay held out for the read-back check)."""
    g = spec.design
    return solve_case(g.case, g.resolved_foci(), g.aperture, g.thickness, "", 0.0,
                      grid_3d(g.aperture, g.aperture / GAUGE_GRID))


def fabrication_checks(spec: PolyfocalSpec, design: PolyfocalDesign, layup) -> list[Check]:
    """2-D: the septa between neighbouring channels are at least the spec's wall thick; 3-D: the
    section gauges read back against exact surface points."""
    if design.mirror is not None:
        return []          # the layout's walls, bends and mapping are checked with the design
    if design.case.startswith("3d"):
        return [_gauges(spec, design)[1]]
    return [channel_clearance_check(design, spec.design.lines.wall_mm)]


def _scan_figures(scan, prefix: str) -> dict[str, float]:
    pick = np.linspace(len(scan.angle_deg) // 2, len(scan.angle_deg) - 1, SUMMARY_ANGLES).round().astype(int)
    return {f"{prefix}_sigma_over_D_at_{scan.angle_deg[i]:.1f}deg": float(scan.sigma[i]) for i in pick}


def summary(spec: PolyfocalSpec, design: PolyfocalDesign, layup) -> dict[str, float]:
    """Key figures: foci count, geometry, line lengths, and σ/D against the field angle."""
    figures = {"foci_count": spec.design.foci_count, "element_count": len(design.length_mm),
               "aperture_mm": design.aperture_mm, "wavelength_mm": design.wavelength_mm}
    if design.mirror is not None:
        figures |= polyfocal_mirror.summary(design)
    else:
        figures |= {
            "line_length_min_mm": float(design.length_mm.min()), "line_length_max_mm": float(design.length_mm.max()),
            "electrical_length_spread_mm": float(np.ptp(design.electrical_mm)),
            "phase_index_min": float(design.index.min()), "phase_index_max": float(design.index.max()),
            "channel_width_min_mm": float(design.width_mm.min()), "channel_width_max_mm": float(design.width_mm.max())}
    figures |= {"design_focus_eikonal_spread_over_D": float(design.dense.residuals().max() / design.dense.aperture),
                "design_foci_sigma_over_D_max": float(design.foci_sigma.max()),
                "focal_centre_z_mm": design.focal[0] * design.unit_mm,
                "focal_radius_mm": design.focal[1] * design.unit_mm}
    if design.focal_axis_z is not None:
        figures["focal_axis_z_mm"] = design.focal_axis_z * design.unit_mm
    for scan in design.scans:
        tag = scan.label.replace(" ", "_")
        figures[f"{tag}_sigma_over_D_max"] = scan.max
        figures |= _scan_figures(scan, tag)
    for scan in design.comparison:
        figures[f"seed_60deg_{scan.label.split(',')[0].split(' ')[0]}_sigma_over_D_max"] = scan.max
    return figures


def lines_from_table(text: str, design: PolyfocalDesign) -> ConstrainedLens:
    """The lens as built from ``lines.csv`` (normalised units; l = electrical length)."""
    rows = list(csv.DictReader(io.StringIO(text)))
    u = design.unit_mm
    col = lambda *names: np.array([[float(r[n]) for n in names] for r in rows]) / u     # noqa: E731
    e = design.elements
    return ConstrainedLens(col("x1_mm", "y1_mm", "z1_mm"), col("x2_mm", "y2_mm", "z2_mm"),
                           col("l_electrical_mm")[:, 0], e.foci, e.aperture, e.dimensions, e.branch)


def aperture_field(design: PolyfocalDesign, lens: ConstrainedLens, angle_deg: float, azimuth_deg: float = 0.0):
    """Plain arrays of the field on the exit ports for a feed on the focal curve at ``angle_deg``:
    (positions_mm N×3, amplitude N, phase_rad N, output direction or image point in mm). Amplitude:
    free-space spreading from the feed to each entry port (1/√r in 2-D, 1/r in 3-D), no feed pattern;
    phase −2π/λ·(|S − r1| + l). For the radiation-pattern module."""
    zc, radius, _ = design.focal
    s = source_on(zc, radius, np.radians(angle_deg), np.radians(azimuth_deg))
    r = np.linalg.norm(lens.r1 - s, axis=1)
    amp = r ** (-0.5 if lens.dimensions == 2 else -1.0)
    phase = -2 * np.pi / design.wavelength_mm * (r + lens.l) * design.unit_mm
    if lens.foci[0].image is None:
        target = best_direction(lens, s)[1]
    else:
        images = image_circle(lens)
        target = (-s if images is None else image_of(images, np.radians(angle_deg), np.radians(azimuth_deg)))
        target = target * design.unit_mm
    return lens.r2 * design.unit_mm, amp / amp.max(), phase, target


def verify(spec: PolyfocalSpec, design: PolyfocalDesign, layup, fab) -> Verification:
    """σ/D (seed-001 (1.4)) against the field angle for the dense synthesis, the elements and the
    lines as built (read back from lines.csv); the seed's two-/three-/four-focal comparison (2-D)."""
    built = lines_from_table(fab.files["lines.csv"], design)
    half = spec.design.view_angle_deg / 2
    azimuths = (0.0,) if design.case.startswith("2d") else (0.0, 90.0)
    count = len(design.scans[0].angle_deg)
    built_scans = [sigma_scan(built, half, count, np.radians(a), f"as built, az {a:g}°", design.focal) for a in azimuths]
    elem_scans = [sigma_scan(design.elements, half, count, np.radians(a), sphere=design.focal) for a in azimuths]
    worst, ref = max(s.max for s in built_scans), max(s.max for s in elem_scans)
    checks = [Check.upper("as_built_sigma", worst - ref, AS_BUILT_LIMIT, "",
                          "σ/D of the lines as built (lines.csv) above the synthesized elements'")]
    lam = design.wavelength_mm
    figures = {"as_built_sigma_over_D_max": worst, "as_built_sigma_max_mm": worst * design.aperture_mm,
               "as_built_sigma_max_deg": worst * design.aperture_mm / lam * 360.0}
    series = tuple(Series(s.label, s.angle_deg, s.sigma) for s in design.scans) + tuple(
        Series(s.label, s.angle_deg, s.sigma, "dashed") for s in built_scans)
    plots = [Plot("sigma", "RMS aberration against the field angle (seed-001 (1.4))", "field angle (deg)",
                  "σ / D", series, caption=_focal_caption(design))]
    if design.comparison:
        plots.append(Plot("seed-comparison", "Seed-001 §1.3: best two-/three-/four-focal lenses, 60° view (±30°)",
                          "field angle (deg)", "σ / D", tuple(Series(s.label, s.angle_deg, s.sigma)
                                                             for s in design.comparison),
                          caption="the seed's designs over their own ±30° whatever this lens's view: f1 = D = 25 λ, "
                                  "2z0 = 10 λ (assumed), focal circles through the design foci (bifocal: and the "
                                  "seed's z_F = −31.1)"))
        tri, four = design.comparison[1].max, design.comparison[2].max
        figures |= {"seed_trifocal_over_fourfocal_sigma_ratio": tri / four}
    pos, amp, phase, _ = aperture_field(design, built, 0.0)
    patterns = _patterns(spec, design, built)
    table = Table("aperture-field", "Aperture field on the exit ports, feed on axis (plain arrays for the "
                  "pattern module)", ("x_mm", "y_mm", "z_mm", "amplitude", "phase_rad"),
                  tuple((*map(float, p), float(a), float(ph)) for p, a, ph in zip(pos, amp, phase)))
    return Verification(figures, tuple(checks), (table,), tuple(plots)).merged(patterns)


def _focal_caption(design: PolyfocalDesign) -> str:
    zc, radius, how = design.focal
    shape = "circle" if design.case.startswith("2d") else "sphere"
    return (f"sources on the focal {shape} {how}: centre z {zc * design.unit_mm:.1f} mm, radius "
            f"{radius * design.unit_mm:.1f} mm (normalised {zc:.4g}, {radius:.4g}); σ at the design foci "
            f"≤ {design.foci_sigma.max():.1e} D")


def _patterns(spec: PolyfocalSpec, design: PolyfocalDesign, built: ConstrainedLens) -> Verification:
    """Patterns of the synthesized elements and the lines as built, feed on axis and at the field
    edge (:mod:`antenna_cad.asbuilt.patterns_arrays`): 2-D a strip of the plate spacing, 3-D the port grid."""
    lam, ln = design.wavelength_mm, spec.design.lines
    cases = []
    for feed, angle in (("on_axis", 0.0), ("field_edge", spec.design.view_angle_deg / 2)):
        for name, lens in (("ideal", design.elements), ("fabricated", built)):
            pos, amp, phase, target = aperture_field(design, lens, angle)
            is_point = lens.foci[0].image is not None
            if lens.dimensions == 2:
                cases.append(imaged_case(name, feed, pos[:, [2, 1]], amp, phase, target[[2, 1]], is_point, lam,
                                         design.aperture_mm / 2, ln.plate_spacing_mm))
            else:
                total, d = referred(pos, path_mm(phase, lam), target, is_point)
                cases.append(ports_case(name, feed, pos, amp, total, d, ln.pitch_mm**2, lam, chief_note(d, is_point)))
    return array_patterns(cases, "exit-port field (1/√r or 1/r spreading from the feed, no feed pattern) referred to "
                                 "the lens's image point or output direction; 2-D: line aperture × plate spacing, "
                                 "3-D: port grid (pitch² each), both principal cuts")
