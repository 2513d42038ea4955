"""A polyfocal constrained lens scaled to millimetres and realized as channels (seed-001 §1, §2, §6, §8.1).

Each element i is a straight channel from its entry point r1 to its exit point r2 (length d_i) whose
phase index n_i gives it the synthesized electrical length: n_i·d_i = l_i + C. The common constant C
(seed-001 §1.1: l is defined up to a constant) is fixed by the central line's ``phase_index`` n_0.
``parallel_plate`` channels carry TEM waves in a fill of εr_i = n_i²; ``waveguide_array`` channels are
TE10 guides filled with the spec's material (εr), of width a_i = λ / (2·sqrt(εr − n_i²)) (seed-001 §8.1).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.polyfocal import (ConstrainedLens, FiveFocal, SymFocus, Trifocal15, five_focal_3d,
                                             plane_wave_trifocal_2d, two_planes_2d)
from antenna_cad.synthesis.polyfocal_analysis import (SigmaScan, axis_point_circle, design_foci_sigma, fitted_sphere,
                                                      focal_sphere, optimal_axis_point, seed_comparison, sigma_scan)
from antenna_cad.synthesis.polyfocal_oneplane import FinitePair, one_plane_2d
from antenna_cad.synthesis.polyfocal_three_planes import three_planes_3d
from antenna_cad.synthesis.two_storey import TwoStorey

EXACT_LIMIT = 1e-9          # eikonal spread / D at the design foci (closed-form or Newton solutions)
DENSE_POINTS = 201          # half-aperture samples of the 2-D surfaces (the CAD curves)


@dataclass(frozen=True)
class PolyfocalDesign:
    case: str
    unit_mm: float
    wavelength_mm: float
    dense: ConstrainedLens          # normalised, dense (surface curves / grid)
    elements: ConstrainedLens       # normalised, one line per element
    line_type: str
    length_mm: np.ndarray           # d_i, straight channel length
    electrical_mm: np.ndarray       # l_i + C (mm)
    index: np.ndarray               # n_i
    width_mm: np.ndarray            # channel width (in-plane; square side in 3-D)
    fill_eps_r: np.ndarray          # εr of each channel's fill
    height_mm: float
    surfaces: tuple[np.ndarray, np.ndarray] | None     # 3-D: (entry, exit) point grids (n, n, 3), normalised
    scans: tuple[SigmaScan, ...]
    focal: tuple[float, float, str]  # the focal curve/sphere of the scans: (z_c, R, how chosen), normalised
    focal_axis_z: float | None      # bifocal 2-D: the axis point z_F of the focal circle (given or optimised)
    foci_sigma: np.ndarray          # σ/D at each design focus (1.4), dense lines
    comparison: tuple[SigmaScan, ...]
    checks: tuple[Check, ...]
    mirror: TwoStorey | None = None   # §1.5 realised as the two-storey lens–mirror antenna

    @property
    def r1_mm(self) -> np.ndarray:
        return self.elements.r1 * self.unit_mm

    @property
    def r2_mm(self) -> np.ndarray:
        return self.elements.r2 * self.unit_mm

    @property
    def aperture_mm(self) -> float:
        return self.dense.aperture * self.unit_mm


def _element_coords(aperture: float, pitch: float) -> np.ndarray:
    """Half-aperture element ordinates 0, p, 2p … ≤ D/2 (an odd count across, a central line)."""
    return np.arange(0, int(np.floor(aperture / 2 / pitch + 1e-9)) + 1) * pitch


def solve_case(case: str, foci: list[dict], aperture: float, thickness: float, law: str,
               straight_index: float, coords) -> ConstrainedLens:
    """The normalised lens at ``coords`` (2-D: half-aperture ordinates; 3-D: (x1, y1) rows)."""
    rad = np.radians
    if case == "2d/two_planes/foci":
        sym = [SymFocus(f["f"], rad(f["angle_deg"])) for f in foci]
        return two_planes_2d(sym, thickness / 2, aperture, coords, law, straight_index)
    if case == "3d/three_planes/foci":
        f1, f3 = (SymFocus(f["f"], rad(f["angle_deg"])) for f in foci)
        return three_planes_3d(f1, f3, thickness / 2, aperture, coords, rhombus=foci[1]["azimuth_deg"] == 90)
    if case == "2d/one_plane/foci":
        p1, p3 = (FinitePair(f["f"], f["f_image"], rad(f["angle_deg"])) for f in foci)
        return one_plane_2d(p1, p3, aperture, coords).shifted(thickness)
    if case == "2d/one_plane/plane_waves":
        t = Trifocal15(foci[0]["f"], foci[1]["f"], rad(foci[1]["angle_deg"]), thickness)
        errors = []
        for direction in (-1.0, 1.0):
            try:
                return plane_wave_trifocal_2d(t, aperture, coords, direction)
            except DesignError as exc:
                errors.append(exc.message)
        raise DesignError("design.foci", "neither §1.5 solution family covers the aperture: " + "; ".join(errors))
    f1, f3, f5 = foci
    ff = FiveFocal(f1["f"], f3["f"], f5["f"], rad(f1["angle_deg"]), rad(f3["angle_deg"]), rad(f1["azimuth_deg"]),
                   rad(f3["azimuth_deg"]), rad(f5["angle_deg"]))
    return five_focal_3d(ff, aperture, coords).shifted(thickness)


def grid_3d(aperture: float, pitch: float) -> np.ndarray:
    k = _element_coords(aperture, pitch)
    g = np.concatenate([-k[:0:-1], k])
    x, y = np.meshgrid(g, g, indexing="ij")
    inside = x**2 + y**2 <= (aperture / 2) ** 2 * (1 + 1e-12)
    return np.column_stack([x[inside], y[inside]])


SURFACE_GRID = 17          # 3-D B-spline surfaces: points per side of the disc-mapped grid


def _surface_grids(case, foci, aperture, thickness) -> tuple[np.ndarray, np.ndarray]:
    """Entry and exit points on a square (u, v) grid mapped onto the aperture disc
    (x = R u sqrt(1 − v²/2), y = R v sqrt(1 − u²/2): no pole, the rim on the grid edge)."""
    u, v = np.meshgrid(*2 * [np.linspace(-1.0, 1.0, SURFACE_GRID)], indexing="ij")
    half = aperture / 2
    xy = np.column_stack([(half * u * np.sqrt(1 - v**2 / 2)).ravel(), (half * v * np.sqrt(1 - u**2 / 2)).ravel()])
    lens = solve_case(case, foci, aperture, thickness, "", 0.0, xy)
    shape = (SURFACE_GRID, SURFACE_GRID, 3)
    return lens.r1.reshape(shape), lens.r2.reshape(shape)


def synthesize_polyfocal(*, case: str, foci: list[dict], unit_mm: float, aperture: float, thickness: float,
                         law: str, straight_index: float, view_angle_deg: float, line_type: str, pitch_mm: float,
                         phase_index: float, wall_mm: float, height_mm: float, fill_eps_r: float,
                         wavelength_mm: float, focal_axis_z: float | None = None) -> PolyfocalDesign:
    pitch = pitch_mm / unit_mm
    if case.startswith("2d"):
        dense_y = np.linspace(0.0, aperture / 2, DENSE_POINTS)
        el_y = _element_coords(aperture, pitch)
        coords = np.union1d(np.round(dense_y, 12), np.round(el_y, 12))      # one point where they coincide
        dense = solve_case(case, foci, aperture, thickness, law, straight_index, coords)
        surface = dense.r1 if case.endswith("/foci") else dense.r2
        pick = np.isin(np.round(surface[:, 1], 12), np.round(np.concatenate([-el_y, el_y]), 12))
        elements = dense.take(pick)
        dense = dense.take(np.isin(np.round(np.abs(surface[:, 1]), 12), np.round(dense_y, 12)))
        surfaces = None
    else:
        elements = solve_case(case, foci, aperture, thickness, law, straight_index, grid_3d(aperture, pitch))
        dense = solve_case(case, foci, aperture, thickness, law, straight_index, grid_3d(aperture, aperture / 24))
        surfaces = _surface_grids(case, foci, aperture, thickness)
    checks = [Check.upper(f"focus_{i + 1}_eikonal_spread", r / aperture, EXACT_LIMIT, "",
                          f"design focus {i + 1}: eikonal spread over the lines / D (seed-001 (1.1)/(2.1))")
              for i, r in enumerate(dense.residuals())]
    length = np.linalg.norm(elements.r2 - elements.r1, axis=1) * unit_mm
    c = int(np.argmin(np.linalg.norm(elements.r1[:, :2], axis=1)))
    electrical = elements.l * unit_mm + (phase_index * length[c] - elements.l[c] * unit_mm)
    index = electrical / length
    width, eps, rchecks = _realize(line_type, index, fill_eps_r, pitch_mm, wall_mm, height_mm, wavelength_mm)
    half = view_angle_deg / 2
    optimise = case == "2d/two_planes/foci" and len(foci) == 1 and focal_axis_z is None
    if optimise:
        focal_axis_z = optimal_axis_point(dense, half)
    focal = focal_curve(case, dense, half, focal_axis_z)
    if optimise:
        focal = (*focal[:2], focal[2] + " (optimised: least peak σ over the view, seed-001 §1.2)")
    if case.startswith("2d"):
        scans = tuple(sigma_scan(lens, half, 61, label=label, sphere=focal)
                      for lens, label in ((dense, "dense lines"), (elements, "elements")))
    else:
        scans = tuple(sigma_scan(dense, half, 31, azimuth=az, label=f"{plane} plane", sphere=focal)
                      for az, plane in ((0.0, "yz"), (np.pi / 2, "xz")))
    comparison = tuple(seed_comparison()) if case == "2d/two_planes/foci" else ()
    return PolyfocalDesign(case, unit_mm, wavelength_mm, dense, elements, line_type, length, electrical, index,
                           width, eps, height_mm, surfaces, scans, focal, focal_axis_z, design_foci_sigma(dense), comparison,
                           tuple(checks + rchecks))


def focal_curve(case: str, dense: ConstrainedLens, half_view_deg: float,
                focal_axis_z: float | None) -> tuple[float, float, str]:
    """(z_c, R, how) of the focal curve the σ study scans (seed-001 §1.2, §2.2–§2.4; see
    :mod:`~antenna_cad.synthesis.polyfocal_analysis`): bifocal 2-D through the axis point z_F
    (``focal_axis_z``), other 2-D lenses through their foci, 3-D the sphere fitted by minimising σ."""
    if focal_axis_z is not None:
        zc, radius = axis_point_circle(dense, focal_axis_z)
        if focal_axis_z >= zc:
            raise DesignError("design.focal_axis_z", f"z_F {focal_axis_z:.6g} is the near axis point of its circle "
                              f"(centre {zc:.6g}); the sources scan the far arc: give z_F < {zc:.6g}")
        return zc, radius, f"through F1, F2 and the axis point z_F = {focal_axis_z:.6g}"
    if case.startswith("3d"):
        return (*fitted_sphere(dense, half_view_deg), "fitted: minimises the peak σ over the view (yz and xz)")
    zc, radius = focal_sphere(np.array([f.point for f in dense.foci]))
    return zc, radius, "through the design foci"


def _realize(line_type, index, fill_eps_r, pitch_mm, wall_mm, height_mm, lam):
    """Channel widths and fills for the phase indices; checks of realizability (seed-001 §8.3)."""
    room = pitch_mm - wall_mm
    checks = []
    if line_type == "parallel_plate":
        if np.min(index) < 1.0:
            raise DesignError("design.lines.phase_index", f"a TEM channel cannot have phase index "
                              f"{np.min(index):.4g} < 1; raise phase_index or use waveguide_array")
        eps = index**2
        width = np.full_like(index, room)
        checks.append(Check.upper("tem_single_mode", height_mm * 2 * np.sqrt(np.max(eps)) / lam, 1.0, "",
                                  "plate spacing / (λ / 2√εr max): TEM only below 1"))
        return width, eps, checks
    if np.max(index) ** 2 >= fill_eps_r:
        raise DesignError("design.lines.phase_index", f"a TE10 guide filled with εr {fill_eps_r:g} cannot reach "
                          f"phase index {np.max(index):.4g}; lower phase_index or fill with a denser material")
    if np.min(index) <= 0:
        raise DesignError("design.lines.phase_index", "a line would need a phase index ≤ 0; raise phase_index")
    width = lam / (2 * np.sqrt(fill_eps_r - index**2))
    checks.append(Check.upper("guide_fits_pitch", float(np.max(width)), room, "mm",
                              "widest TE10 guide vs pitch − wall"))
    te20, te30 = lam / np.sqrt(fill_eps_r), 1.5 * lam / np.sqrt(fill_eps_r)
    checks.append(Check.upper("guide_below_te30", float(np.max(width)), te30, "mm",
                              "widest guide vs the TE30 cutoff width 3λ/(2√εr) (TE20 above λ/√εr is not "
                              "excited by a symmetric feed)", warn_margin=te30 - te20))
    checks.append(Check.upper("guide_height_single_mode", height_mm * 2 * np.sqrt(fill_eps_r) / lam, 1.0, "",
                              "guide height / TE01 cutoff height λ/(2√εr)"))
    return width, np.full_like(index, fill_eps_r), checks
