"""As-built verification of the lenses of revolution, shared by the collimator and bifocal kinds.

Exact 2-D meridional traces (:mod:`antenna_cad.raytrace.trace2d`, vector Snell, seed-000 §4.2) from a
feed to the antenna plane through (a) the ideal lens, (b) the stepped stack as cut (before sanding),
(c) the stack as fabricated (the cut pieces: necks, pedestal feet, dowels; the material's εr). Per feed:
aperture phase peak-to-peak and RMS with the linear tilt removed (seed-000 §4.1, (2.16)), amplitude
taper from Fresnel transmission and dielectric loss (§4.4, no ray-tube factor, as the seed), gain loss
by Ruze, G/G0 = exp(−σ²) with σ the RMS phase error in rad, and the focus shift. Statistics are over
the rays through the lens aperture, launched uniformly in y across it. Also the choice of the stock
thickness (``sheet_thickness_mm: auto``), the tolerance study, and the report's tables and plot data.

Limits of geometrical optics on a stepped stack, both measured and reported:
* the flat sheet faces do not bend rays toward the axis as the smooth face does, so the exact trace
  adds to the stair-step error k0(n−1)Δd (§7.3) a non-collimation term that grows with the ray angle
  and the path to the antenna plane (small for slow lenses, ≈ 3.5° p-p for the seed's f/8 lens);
* rays that meet a riser do so at grazing incidence and are deflected strongly (or totally
  reflected); they fill strips only t·tan γ wide (a few mm: less than a wavelength), where GO gives
  no usable phase. They are traced and drawn but left out of the phase statistics;
  ``riser_fraction`` says how many they are.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fabrication.section import fabricated_section, stepped_section
from antenna_cad.fullwave.verify import FullWave, fast_model, full_wave_study
from antenna_cad.kinds.asbuilt_fullwave import modelled_stats, revolved
from antenna_cad.kinds.taper import Taper
from antenna_cad.raytrace.collimator import ApertureTrace
from antenna_cad.raytrace.trace2d import Interface, Slabs, Trace2D, aim_at_face, trace, trace_slabs, \
    transmitted_amplitude
from antenna_cad.quietzone.tolerance import added_figures, efficiency_loss_db, eps_r_added_deg, residual_deg, \
    thickness_added_deg
from antenna_cad.quietzone.verdict import FAST_ERROR_DEG, UNCERTAIN, judged, undecided
from antenna_cad.quietzone.volume import Zone, radii_mm, stack_ratios, zone_from
from antenna_cad.spec.common import TestZoneSpec, TolerancesSpec, VerificationSpec
from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.collimator import edge_margin_mm, step_phase_error_deg
from antenna_cad.verification import Plot, Series, Table, Verification, detrended

RAYS = 1201                 # rays per trace across the aperture
FAN_RAYS = 31
AIM_MARGIN = 0.999          # rays aimed inside the rim
EDGE_FRACTION = 0.1         # taper: outer vs central tenth of the aperture
TOLERANCE_STEPS = (-1.0, -0.5, 0.0, 0.5, 1.0)     # deviations in units of each tolerance
VOLUME_MARGIN_WAVELENGTHS = 1.0  # the full-wave quiet-zone record reaches this far past the zone
Medium = tuple[Interface, ...] | Slabs


@dataclass(frozen=True)
class Lens:
    """A lens of revolution as the as-built trace sees it, in its kind's frame (z the axis, y
    transverse, mm). ``faces(n)``: the ideal faces with lens index n (front first; the last one is
    the back face the lens really has, e.g. the flat face behind a layup's back slab)."""
    radius_mm: float
    eps_r: float
    tan_delta: float
    wavelength_mm: float
    budget_deg: float
    antenna_z_mm: float
    feed: tuple[float, float]           # nominal feed (z, y)
    faces: Callable[[float], tuple[Interface, ...]]
    zone: TestZoneSpec = TestZoneSpec()         # the quiet zone the stack is judged over
    aut_diameter_mm: float | None = None        # the AUT's (None: the default AUT, :func:`lens_zone`)

    @property
    def n(self) -> float:
        return self.eps_r ** 0.5

    def front_z(self, r) -> np.ndarray:
        return self.faces(self.n)[0].z_of_y(r)

    def back_z(self, r) -> np.ndarray:
        return self.faces(self.n)[-1].z_of_y(r)


@dataclass(frozen=True)
class Stats:
    p2p_deg: float
    rms_deg: float
    taper_db: float
    gain_loss_db: float
    riser_fraction: float       # aperture rays refracted or reflected at a riser (not in the statistics)


def ruze_loss_db(rms_deg: float) -> float:
    """Gain loss of a random-like phase error, −10·log10(exp(−σ²)), σ the RMS in rad (Ruze)."""
    return float(10 * np.log10(np.e) * np.radians(rms_deg) ** 2)


def _aperture(lens: Lens, tr: Trace2D) -> np.ndarray:
    return tr.ok & (np.abs(tr.points[-2][:, 1]) <= lens.radius_mm)


def trace_lens(lens: Lens, medium: Medium, feed, rays: int = RAYS) -> tuple[Trace2D, np.ndarray]:
    """Trace from ``feed`` through ``medium`` (ideal faces or a stepped section) to the antenna plane;
    returns the trace and the rays that cross the lens aperture without meeting a riser."""
    feed = np.asarray(feed, float)
    dirs = aim_at_face(lens.faces(lens.n)[0], feed, AIM_MARGIN * lens.radius_mm, rays)
    origins = np.tile(feed, (rays, 1))
    if isinstance(medium, Slabs):
        tr = trace_slabs(origins, dirs, medium, lens.antenna_z_mm)
    else:
        tr = trace(origins, dirs, medium, 1.0, lens.antenna_z_mm)
    keep = _aperture(lens, tr)
    return tr, keep if tr.riser is None else keep & ~tr.riser


def aperture_stats(lens: Lens, tr: Trace2D, keep: np.ndarray) -> Stats:
    ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
    y = np.abs(ap.y_mm - np.median(ap.y_mm))
    edge, centre = y >= (1 - EDGE_FRACTION) * y.max(), y <= EDGE_FRACTION * y.max()
    taper = min(20 * np.log10(np.mean(a[edge]) / np.mean(a[centre]))
                for a in (transmitted_amplitude(tr, lens.wavelength_mm, lens.tan_delta, pol)[keep]
                          for pol in ("perp", "par")))
    rms = ap.rms_deg()
    return Stats(ap.peak_to_peak_deg(), rms, float(taper), ruze_loss_db(rms),
                 1.0 - keep.sum() / _aperture(lens, tr).sum())


MAX_HALVINGS = 30
MIN_KEPT_RAYS = 3          # a linear fit of the aperture phase needs a few rays


def focus_shift(lens: Lens, medium: Medium, feed) -> tuple[float, Stats]:
    """Axial feed move (+ toward the lens) that minimizes the RMS phase error, and the stats there.
    Gauss–Newton on the first-order change of the optical path, −δz·cos γ (γ the ray's angle at the
    feed, Fermat), two steps; a step that leaves the aperture without rays is halved until it does not."""
    z0, y0 = feed
    shift = 0.0
    tr, keep = trace_lens(lens, medium, feed)
    for _ in range(2):
        ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
        grad = detrended(ap.y_mm, -360.0 / lens.wavelength_mm * tr.directions[0][keep, 0])
        step = -float(np.dot(ap.detrended_phase_deg(), grad) / np.dot(grad, grad))
        for _ in range(MAX_HALVINGS):        # a step past the lens (a feed far off axis) is halved
            moved, kept = trace_lens(lens, medium, (z0 + shift + step, y0))
            if kept.sum() >= MIN_KEPT_RAYS:
                break
            step /= 2
        else:
            break
        shift, tr, keep = shift + step, moved, kept
    return shift, aperture_stats(lens, tr, keep)


# ------------------------------------------------------------------ the quiet zone of the stack

def lens_zone(lens: Lens, z_ref: float, spec: TestZoneSpec | None = None, aut_diameter_mm: float | None = None) -> Zone:
    """The quiet zone behind the plane ``z_ref`` (the back of the stack): ``spec`` (default the lens's)
    with the AUT's diameter, else the default AUT's: the lens less the GO edge margin g of seed-000 §4.6
    (2.1) on each side, at least 2 λ."""
    lam, distance = lens.wavelength_mm, lens.antenna_z_mm - z_ref
    aut = aut_diameter_mm if spec is not None else lens.aut_diameter_mm
    if aut is None:
        aut = max(2 * lens.radius_mm - 2 * edge_margin_mm(lam, distance), 2 * lam)
    return zone_from(spec if spec is not None else lens.zone, aut, distance, lens.radius_mm, lam)


def zone_depth_mm(lens: Lens, z_ref: float) -> tuple[float, float]:
    """The z range (the lens's frame) the full-wave runs record for the quiet zone behind ``z_ref``:
    its depth with ``VOLUME_MARGIN_WAVELENGTHS`` either side (the pattern stage's back plane may
    differ from ``z_ref`` by a fraction of a sheet)."""
    zone, pad = lens_zone(lens, z_ref), VOLUME_MARGIN_WAVELENGTHS * lens.wavelength_mm
    return z_ref + zone.distance_mm - pad, z_ref + zone.distance_mm + zone.depth_mm + pad


@dataclass(frozen=True)
class ZoneStats:
    """The stack's own phase over the quiet zone (its field over the ideal lens's, fast model): worst
    p-p and RMS over the planes, and the plane (mm behind the stack) of the worst p-p."""
    p2p_deg: float
    rms_deg: float
    plane_mm: float


def stack_zone(lens: Lens, layup: LayupPlan, fab=None) -> dict[str, ZoneStats]:
    """:class:`ZoneStats` of each stepped section (stepped; fabricated with ``fab``) by the fast model
    (:func:`antenna_cad.quietzone.volume.stack_ratios`) over :func:`lens_zone`."""
    rl = revolved(lens, layup, fab)
    z_ref = rl.plane_z_mm(0.0)
    zone = lens_zone(lens, z_ref)
    rho = radii_mm(max(lens.radius_mm, zone.diameter_mm / 2), lens.wavelength_mm)
    out = {}
    for name, ratio in stack_ratios(rl, z_ref, zone.planes_mm, rho).items():
        j = judged(zone, [(rho, e) for e in ratio])
        p2p, plane = j.worst("phase_p2p_deg")
        out[name] = ZoneStats(p2p, j.worst("phase_rms_deg")[0], plane)
    return out


def stack_zone_full_wave(lens: Lens, fw: FullWave, z_ref: float, variant: str = "fabricated") -> ZoneStats | None:
    """:class:`ZoneStats` of ``variant`` from the full-wave fields over the zone's volume (its field over
    the ideal lens's on every plane), or None when those runs did not both finish or do not cover the zone."""
    zone = lens_zone(lens, z_ref)
    z = z_ref + zone.planes_mm
    if not all(v in fw.volume and fw.volume[v].covers(z, zone.diameter_mm / 2) for v in ("ideal", variant)):
        return None
    planes = [(r, e / ei) for (r, e), (_, ei) in zip(fw.volume[variant].planes(z), fw.volume["ideal"].planes(z))]
    j = judged(zone, planes)
    p2p, plane = j.worst("phase_p2p_deg")
    return ZoneStats(p2p, j.worst("phase_rms_deg")[0], plane)


# ------------------------------------------------------------------ layers and the stock thickness

def excess_mm(lens: Lens, layup: LayupPlan, r: np.ndarray) -> np.ndarray:
    """(sheets, len(r)) foam of each sheet outside the ideal lens, along z at radius r: what sanding
    removes there (negative: a taper-cut sheet's cone inside the lens)."""
    zf, zb = lens.front_z(r), lens.back_z(r)
    rows = []
    for s in layup.sheets:
        overlap = np.clip(np.minimum(s.z_max_mm, zb) - np.maximum(s.z_min_mm, zf), 0.0, None)
        if s.tapered:       # foam where the cone reaches r, on 64 mid-depth samples of the sheet
            z = s.z_min_mm + s.thickness_mm * (np.arange(64) + 0.5) / 64
            foam = s.thickness_mm * np.mean(s.radius_at_z(z)[:, None] >= r, axis=0)
        else:
            foam = np.where(r <= s.radius_mm, s.thickness_mm, 0.0)
        rows.append(np.where(r <= s.radius_mm, foam - overlap, 0.0))
    return np.array(rows)


def step_estimate_deg(lens: Lens, layup: LayupPlan) -> float:
    """Stair-step error k0(n−1)Δd, seed-000 §7.3, with Δd the spread of the excess foam along the axis."""
    total = excess_mm(lens, layup, np.linspace(0.0, lens.radius_mm, 4001)).sum(axis=0)
    return step_phase_error_deg(lens.n, float(np.ptp(total)), lens.wavelength_mm)


@dataclass(frozen=True)
class Candidate:
    thickness_mm: float
    layup: LayupPlan | None         # None when the stock cannot be laid up (``note`` says why)
    stats: Stats | None
    estimate_deg: float | None      # k0(n−1)Δd
    meets: bool
    note: str = ""
    model: Stats | None = None      # the fast sub-wavelength model on one plane (for comparison)
    zone: ZoneStats | None = None   # the stack's own phase over the quiet zone: what ``meets`` follows


def stock_study(sheets: Callable[[float], LayupPlan], lens_for: Callable[[LayupPlan], Lens],
                stocks: tuple[float, ...], settings: VerificationSpec = VerificationSpec()) -> tuple[Candidate, ...]:
    """Every stock thickness laid up and judged unsanded (stepped stack as cut) at the nominal feed:
    GO trace and the fast sub-wavelength model on one plane (for comparison), and the stack's own
    phase over the quiet zone (:func:`stack_zone`), whose worst p-p decides; a candidate the fast
    model cannot decide (within its measured error of the budget, when that error exceeds a quarter
    of the budget: :func:`antenna_cad.quietzone.verdict.undecided`) is declined, its note saying so."""
    out = []
    for t in stocks:
        try:
            layup = sheets(t)
        except DesignError as exc:
            out.append(Candidate(t, None, None, None, False, str(exc)))
            continue
        lens = lens_for(layup)
        st = aperture_stats(lens, *trace_lens(lens, cut_medium(lens, layup), lens.feed))
        model = modelled_stats(lens, fast_model(revolved(lens, layup), settings), "stepped", lens.feed)
        zone = stack_zone(lens, layup)["stepped"]
        unsure = undecided(zone.p2p_deg, lens.budget_deg, FAST_ERROR_DEG["own_phase_p2p_deg"])
        meets = zone.p2p_deg <= lens.budget_deg and not unsure
        out.append(Candidate(t, layup, st, step_estimate_deg(lens, layup), meets, UNCERTAIN if unsure else "",
                             model=model, zone=zone))
    return tuple(out)


def choose_stock(study: tuple[Candidate, ...]) -> Candidate:
    """The thickest stock that meets the budget unsanded, else the thinnest that can be laid up."""
    feasible = [c for c in study if c.layup is not None]
    if not feasible:
        raise DesignError("fabrication.stock_thicknesses_mm", "no stock thickness can be laid up: "
                          + "; ".join(c.note for c in study))
    meeting = [c for c in feasible if c.meets]
    return max(meeting, key=lambda c: c.thickness_mm) if meeting else min(feasible, key=lambda c: c.thickness_mm)


# ------------------------------------------------------------------ the verification

def _scaled(face: Interface, z0: float, scale: float) -> Interface:
    """``face`` stretched along z about z0 (a machined lens off in thickness)."""
    return Interface(lambda y: z0 + scale * (face.z_of_y(y) - z0), lambda y: scale * face.dz_dy(y),
                     face.n_after, z0 + scale * (face.z_guess - z0))


def _as_built(lens: Lens, section: Slabs | Taper | None, eps_r: float, scale: float) -> Medium:
    """The as-built lens with material εr and its axial size scaled (each sheet, or the lens, thicker)."""
    n = eps_r ** 0.5
    if isinstance(section, Taper):
        return section.faces(n, scale)
    if section is not None:
        z = section.z_edges
        return replace(section, n=n, z_edges=z[0] + scale * (z - z[0]))
    z0 = float(lens.front_z(0.0))
    return tuple(_scaled(f, z0, scale) for f in lens.faces(n))


def _r(x: float) -> float:
    return round(float(x), 3)


def cut_medium(lens: Lens, layup: LayupPlan) -> Medium:
    """The stack as cut for the GO trace: the stepped section, or a taper-cut stack's cones."""
    return Taper(lens, layup).faces(lens.n) if layup.edge == "taper" else stepped_section(layup, lens.n)


def lens_variants(lens: Lens, layup: LayupPlan | None, fab) -> list[tuple[str, Medium]]:
    """(name, medium): the ideal lens, and for a layup the stepped stack as cut and as fabricated. A
    taper-cut stack is its cones in both (dowels only: the feet stay outside the aperture)."""
    n = lens.n
    if layup is None:
        return [("ideal", lens.faces(n))]
    if layup.edge == "taper":
        return [("ideal", lens.faces(n)), ("stepped", cut_medium(lens, layup)), ("fabricated", cut_medium(lens, layup))]
    return [("ideal", lens.faces(n)), ("stepped", stepped_section(layup, n)),
            ("fabricated", fabricated_section(layup, fab, n))]


def verify_lens(lens: Lens, feeds: tuple[tuple[str, float, float], ...], tolerances: TolerancesSpec,
                layup: LayupPlan | None = None, fab=None, study: tuple[Candidate, ...] = (),
                settings: VerificationSpec = VerificationSpec()) -> tuple[Verification, FullWave]:
    """Figures, checks, tables and plots of the as-built lens, and its full-wave stage (whose fields
    over the quiet zone the quiet-zone study takes). ``feeds``: (name, z, y), the first at the nominal
    feed; ``study``: the stock candidates (layups); ``settings``: the full-wave stage whose phase model
    the sanding check and the tolerance budget follow."""
    n = lens.n
    variants = lens_variants(lens, layup, fab)
    section = (Taper(lens, layup) if layup.edge == "taper" else variants[-1][1]) if layup is not None else None
    as_built = variants[-1][1]
    figures: dict[str, float] = {}
    rows, plots, go = [], [], {}
    for name, z, y in feeds:
        series = []
        for variant, medium in variants:
            tr, keep = trace_lens(lens, medium, (z, y))
            st = aperture_stats(lens, tr, keep)
            figures |= {f"{variant}_{name}_{k}": v for k, v in vars(st).items()}
            ap = ApertureTrace.from_trace(tr, lens.wavelength_mm, keep)
            order = np.argsort(ap.y_mm)
            series.append(Series(variant, ap.y_mm[order], ap.detrended_phase_deg()[order]))
            if y == 0.0:
                go[variant] = (ap.y_mm[order], ap.detrended_phase_deg()[order])
            rows.append((name, variant, _r(st.p2p_deg), _r(st.rms_deg), _r(st.taper_db), _r(st.gain_loss_db)))
        shift, refocused = focus_shift(lens, as_built, (z, y))
        figures |= {f"{name}_feed_z_mm": z, f"{name}_feed_y_mm": y, f"{name}_focus_shift_mm": shift,
                    f"{name}_refocused_rms_deg": refocused.rms_deg}
        plots.append(Plot(f"aperture-phase-{name.replace('_', '-')}", f"Aperture phase, feed {name} "
                          f"(z {z:.1f}, y {y:.1f} mm)", "y on the antenna plane (mm)", "phase, tilt removed (deg)",
                          tuple(series), caption="ideal lens, stepped stack as cut, stack as fabricated"))
    tables = [Table("aperture", "Aperture phase and amplitude per feed",
                    ("feed", "lens", "p-p deg", "RMS deg", "taper dB", "gain loss dB"), tuple(rows))]
    rl = revolved(lens, layup, fab)
    fw = full_wave_study(rl, settings, go, zone_depth_mm(lens, rl.plane_z_mm(0.0)))
    figures |= fw.figures
    checks = list(fw.checks)
    nominal = feeds[0][0]
    model = None
    if layup is not None:
        tables.append(_layer_table(lens, layup, fab))
        plots.append(_profile_plot(lens, layup))
        model = modelled_stats(lens, fw.model, "fabricated", feeds[0][1:])
        zone, zone_model = stack_zone_full_wave(lens, fw, rl.plane_z_mm(0.0)), fw.volume_model
        if zone is None:
            zone, zone_model = stack_zone(lens, layup, fab)["fabricated"], "fast model"
        pp = zone.p2p_deg
        figures |= {f"model_fabricated_{nominal}_p2p_deg": model.p2p_deg, f"model_fabricated_{nominal}_rms_deg":
                    model.rms_deg, f"stack_zone_fabricated_{nominal}_p2p_deg": pp,
                    f"stack_zone_fabricated_{nominal}_rms_deg": zone.rms_deg}
        unsure = zone_model == "fast model" and undecided(pp, lens.budget_deg, FAST_ERROR_DEG["own_phase_p2p_deg"])
        checks.append(Check("unsanded_step_phase_error", "warn" if pp > lens.budget_deg or unsure else "pass", pp,
                            lens.budget_deg, "deg", (f"{UNCERTAIN}: " if unsure else "") +
                            f"as fabricated, unsanded ({layup.sheet_thickness_mm:g} mm sheets): the stack's own phase "
                            f"over the quiet zone {pp:.1f}° p-p (worst plane {zone.plane_mm:.0f} mm behind the stack; "
                            f"{zone_model}) vs budget {lens.budget_deg:g}°; on one plane {model.p2p_deg:.1f}° "
                            f"({fw.model.name}), GO alone {figures[f'fabricated_{nominal}_p2p_deg']:.1f}°"
                            + _over_budget(layup, pp > lens.budget_deg)))
    if study:
        tables.append(_candidates_table(study, layup))
    own = (zone.p2p_deg, zone.rms_deg) if layup is not None else None
    own_error = FAST_ERROR_DEG["own_phase_p2p_deg"] if layup is not None and zone_model == "fast model" else 0.0
    added_fab = (lambda y: fw.model.added("fabricated", y)) if "fabricated" in fw.model.added_deg else None
    sens_table, sens_plot, sens_figures, sens_check = _sensitivity(lens, section, tolerances, layup, own, added_fab,
                                                                   model, own_error)
    figures |= sens_figures
    return Verification(figures, tuple(checks + [sens_check]), tuple(tables + [sens_table]),
                        tuple(plots + [_fan_plot(lens, as_built, section), sens_plot]) + fw.plots, fw.files), fw


def _over_budget(layup: LayupPlan, over: bool) -> str:
    if not over:
        return ""
    if layup.edge == "taper":
        return "; taper-cut: thinner sheets bring the cones closer to the profile"
    return "; sanding required: it removes the stack's own error (the ideal lens)"


def _layer_table(lens: Lens, layup: LayupPlan, fab) -> Table:
    excess = excess_mm(lens, layup, np.linspace(0.0, lens.radius_mm, 4001)).max(axis=1)
    pieces = [sum(p.sheet_index == s.index for p in fab.pieces) for s in layup.sheets]
    if layup.edge == "taper":
        gaps = Taper(lens, layup).largest_gap_mm()
        rows = tuple((s.label, _r(s.z_min_mm), _r(s.z_max_mm), *map(_r, s.cone_mm), _r(g), k)
                     for s, g, k in zip(layup.sheets, gaps, pieces))
        return Table("layers", "Sheets (taper-cut)", ("sheet", "z min mm", "z max mm", "cone radius front mm",
                                                      "cone radius back mm", "largest gap to the profile mm",
                                                      "pieces"), rows,
                     caption="each rim is the cone through the lens profile at the sheet's two faces; gap: the "
                     "largest distance from the profile to the cone in the meridional section (no sanding)")
    rows = tuple((s.label, _r(s.z_min_mm), _r(s.z_max_mm), _r(s.radius_mm), _r(e), k)
                 for s, e, k in zip(layup.sheets, excess, pieces))
    return Table("layers", "Sheets", ("sheet", "z min mm", "z max mm", "disc radius mm",
                                      "max excess over the lens mm", "pieces"), rows,
                 caption="excess: the largest foam depth sanding removes in that sheet")


def _candidates_table(study: tuple[Candidate, ...], layup: LayupPlan | None) -> Table:
    rows = tuple((c.thickness_mm, c.layup.count, _r(c.stats.p2p_deg), _r(c.stats.rms_deg), _r(c.model.p2p_deg),
                  _r(c.model.rms_deg), _r(c.zone.p2p_deg), _r(c.zone.rms_deg), _r(c.zone.plane_mm),
                  _r(c.estimate_deg), "yes" if c.meets else (c.note or "no"))
                 if c.layup is not None else (c.thickness_mm, *[None] * 9, f"no: {c.note}")
                 for c in study)
    chosen = f"; chosen: {layup.sheet_thickness_mm:g} mm" if layup is not None else ""
    return Table("stock-candidates", "Stock sheet thickness, unsanded stack at the nominal feed",
                 ("thickness mm", "sheets", "GO p-p deg", "GO RMS deg", "one-plane model p-p deg",
                  "one-plane model RMS deg", "quiet-zone p-p deg", "quiet-zone RMS deg", "worst plane mm",
                  "k0(n-1)Δd deg", "meets budget"), rows,
                 caption=f"GO: exact trace of the stack as cut (blind to sub-wavelength zones); one-plane model: the "
                 "fast sub-wavelength model on the aperture plane (single-plane figures, for comparison); "
                 "quiet-zone: the stack's own phase (its field over the ideal lens's, fast model) worst over the "
                 f"quiet zone's planes and disc, which decides; k0(n−1)Δd the thin screen of seed-000 §7.3{chosen}")


def _sensitivity(lens: Lens, section: Slabs | Taper | None, tol: TolerancesSpec, layup: LayupPlan | None,
                 own: tuple[float, float] | None = None, added_fab: Callable | None = None,
                 model: Stats | None = None, own_error_deg: float = 0.0):
    """The tolerance budget: εr spread, sheet (or lens) thickness and feed position, each at ± its
    tolerance, as what it adds to the smooth lens (εr and thickness to first order along its rays, the
    feed by retracing it: :mod:`antenna_cad.quietzone.tolerance`), root-sum-squared with the stack's own
    figure ``own`` (its quiet-zone p-p and RMS; the smooth lens's own when None); the gain loss from the
    aperture efficiency of the ideal field against the fabricated one (``added_fab``: its added phase at
    y) with every term at its worse end; "uncertain — run full-wave" when ``own_error_deg`` (the error of
    the model that gave ``own``) cannot decide the budget. Kept for comparison: the old figures, GO through
    the steps with the single-plane ``model`` as nominal and Ruze's loss (``tolerance_single_plane_ruze_*``)."""
    t_ref = layup.sheet_thickness_mm if layup is not None else float(lens.back_z(0.0) - lens.front_z(0.0))
    z_front = layup.sheets[0].z_min_mm if layup is not None else float(lens.front_z(0.0))
    z0, y0 = lens.feed
    smooth = lens.faces(lens.n)
    tr, keep = trace_lens(lens, smooth, lens.feed)
    y, lam = tr.points[-1][keep, 1], lens.wavelength_mm
    base_phase = ApertureTrace.from_trace(tr, lam, keep).phase_deg()

    def feed(s, axial):
        moved_tr, moved_keep = trace_lens(lens, smooth, (z0 + s, y0) if axial else (z0, y0 + s))
        moved = ApertureTrace.from_trace(moved_tr, lam, moved_keep)
        order = np.argsort(moved.y_mm)
        return np.interp(y, moved.y_mm[order], moved.phase_deg()[order]) - base_phase

    thick = "sheet thickness" if layup is not None else "lens thickness"
    as_built = _as_built(lens, section, lens.eps_r, 1.0)
    cases = (("εr", tol.eps_r_tolerance, "", lambda s: eps_r_added_deg(tr, keep, lens.n, s, lam),
              lambda s: (_as_built(lens, section, lens.eps_r + s, 1.0), lens.feed)),
             (thick, tol.thickness_tolerance_mm, "mm",
              lambda s: thickness_added_deg(tr, keep, len(smooth), z_front, s / t_ref, lam),
              lambda s: (_as_built(lens, section, lens.eps_r, 1 + s / t_ref), lens.feed)),
             ("feed axial", tol.feed_position_tolerance_mm, "mm", lambda s: feed(s, True),
              lambda s: (as_built, (z0 + s, y0))),
             ("feed transverse", tol.feed_position_tolerance_mm, "mm", lambda s: feed(s, False),
              lambda s: (as_built, (z0, y0 + s))))
    go_base = aperture_stats(lens, *trace_lens(lens, as_built, lens.feed))
    rows, series, added, go_added, worst = [], [], {}, {}, np.zeros(len(y))
    for name, size, unit, at, go_at in cases:
        figs = {k: added_figures(y, at(k * size)) if k else (0.0, 0.0) for k in TOLERANCE_STEPS}
        series.append(Series(f"{name} ±{size:g} {unit}".strip(), np.array(TOLERANCE_STEPS),
                             np.array([figs[k][0] for k in TOLERANCE_STEPS])))
        end = max((-1.0, 1.0), key=lambda k: figs[k][1])
        worst = worst + residual_deg(y, at(end * size))
        added[name] = tuple(max(figs[k][i] for k in (-1.0, 1.0)) for i in (0, 1))
        go = [aperture_stats(lens, *trace_lens(lens, *go_at(k * size))) for k in (-1.0, 1.0)]
        go_added[name] = tuple(max(0.0, max(getattr(s, k) ** 2 for s in go) - getattr(go_base, k) ** 2)
                               for k in ("p2p_deg", "rms_deg"))
        rows += [(name, f"{sign}{size:g} {unit}".strip(), _r(figs[k][0]), _r(figs[k][1]), _r(g.p2p_deg),
                  _r(g.rms_deg)) for sign, k, g in zip("−+", (-1.0, 1.0), go)]
    own = own or added_figures(y, base_phase)
    p2p = float(np.sqrt(own[0] ** 2 + sum(a[0] ** 2 for a in added.values())))
    rms = float(np.sqrt(own[1] ** 2 + sum(a[1] ** 2 for a in added.values())))
    dominant = max(added, key=lambda k: added[k][1])
    r_order = np.argsort(np.abs(y))
    ideal = (transmitted_amplitude(tr, lam, lens.tan_delta, "perp")[keep] * np.exp(1j * np.radians(
        residual_deg(y, base_phase))))[r_order]
    fab = ideal * np.exp(1j * np.radians(added_fab(y)[r_order] if added_fab is not None else 0.0))
    loss = efficiency_loss_db(np.abs(y)[r_order], ideal, fab * np.exp(1j * np.radians(worst[r_order])))
    nominal = model or go_base
    old_p2p = float(np.sqrt(nominal.p2p_deg ** 2 + sum(a[0] for a in go_added.values())))
    old_rms = float(np.sqrt(nominal.rms_deg ** 2 + sum(a[1] for a in go_added.values())))
    figures = {"tolerance_rss_p2p_deg": p2p, "tolerance_rss_rms_deg": rms, "tolerance_rss_gain_loss_db": loss,
               "stack_own_efficiency_loss_db": efficiency_loss_db(np.abs(y)[r_order], ideal, fab),
               "tolerance_dominant_added_rms_deg": added[dominant][1],
               "tolerance_single_plane_ruze_rss_p2p_deg": old_p2p, "tolerance_single_plane_ruze_rss_rms_deg": old_rms,
               "tolerance_single_plane_ruze_gain_loss_db": ruze_loss_db(old_rms)}
    unsure = undecided(p2p, lens.budget_deg, own_error_deg)
    check = Check("tolerance_budget", "warn" if p2p > lens.budget_deg or unsure else "pass", p2p, lens.budget_deg,
                  "deg", (f"{UNCERTAIN}: " if unsure else "") + "as built with every tolerance (the stack's own "
                  f"{own[0]:.1f}° p-p ⊕ each tolerance's change of the smooth lens, RSS): {p2p:.1f}° p-p, "
                  f"{rms:.1f}° RMS vs budget {lens.budget_deg:g}°; dominant: {dominant} (+{added[dominant][1]:.2f}° "
                  f"RMS); gain loss {loss:.3f} dB (aperture efficiency, every tolerance at its worse end); the old "
                  f"GO-through-the-steps figure {old_p2p:.1f}° p-p")
    table = Table("sensitivity", "Phase error each build tolerance adds (nominal feed)",
                  ("tolerance", "deviation", "added p-p deg", "added RMS deg", "old: GO through the steps p-p deg",
                   "old: GO RMS deg"),
                  (("stack's own (quiet zone)", "", _r(own[0]), _r(own[1]), _r(go_base.p2p_deg), _r(go_base.rms_deg)),
                   *rows),
                  caption=f"added: the change of the smooth lens (εr, thickness to first order along its rays; the "
                  f"feed retraced), tilt and piston removed, area-weighted over the disc; dominant: {dominant}; RSS "
                  f"{p2p:.2f}° p-p, {rms:.2f}° RMS. Old (for comparison): GO through the steps, Ruze")
    plot = Plot("sensitivity", "Phase error each build tolerance adds to the smooth lens",
                "deviation (units of the tolerance)", "added p-p phase (deg)", tuple(series),
                hlines=(("budget", lens.budget_deg),))
    return table, plot, figures, check


def _profile_plot(lens: Lens, layup: LayupPlan) -> Plot:
    """Upper half-section: the stepped stack (as cut) filled, the lens after sanding filled over it,
    the sheets outlined; what of the stack shows outside the lens is the sanding allowance."""
    r = np.linspace(0.0, lens.radius_mm, 201)
    lens_z = np.concatenate([lens.front_z(r), lens.back_z(r[::-1])])
    lens_r = np.concatenate([r, r[::-1]])
    z = np.array([[s.z_min_mm, s.z_max_mm] for s in layup.sheets]).ravel()
    rad = np.repeat([s.radius_mm for s in layup.sheets], 2)
    step_z = np.concatenate([[z[0]], z, [z[-1]]])
    step_r = np.concatenate([[0.0], rad, [0.0]])
    boxes = np.array([[(s.z_min_mm, 0.0), (s.z_min_mm, s.radius_mm), (s.z_max_mm, s.radius_mm),
                       (s.z_max_mm, 0.0), (np.nan, np.nan)] for s in layup.sheets]).reshape(-1, 2)
    return Plot("profile", "Section: sheets, lens and sanding allowance", "z (mm)", "r (mm)",
                (Series("stepped stack as cut (sanding allowance)", step_z, step_r, "fill"),
                 Series("lens after sanding", lens_z, lens_r, "fill"),
                 Series("sheets", boxes[:, 0], boxes[:, 1], "line")), equal_aspect=True,
                caption=f"{layup.count} sheets of {layup.sheet_thickness_mm:g} mm; the stack outside the lens "
                        "is sanded off")


def _outline(lens: Lens, section: Slabs | Taper | None) -> np.ndarray:
    """Closed outlines of the as-built section, NaN-separated (z, y) rows."""
    if isinstance(section, Taper):
        return section.outline()
    if section is None:
        y = np.linspace(-lens.radius_mm, lens.radius_mm, 201)
        ring = np.concatenate([np.stack([lens.front_z(y), y], -1), np.stack([lens.back_z(y[::-1]), y[::-1]], -1)])
        return np.concatenate([ring, ring[:1], [[np.nan, np.nan]]])
    y_ext = np.concatenate([[-np.inf], section.y_breaks, [np.inf]])
    out = []
    for k, row in enumerate(section.material):
        z0, z1 = section.z_edges[k], section.z_edges[k + 1]
        edges = np.diff(np.concatenate([[0], row.astype(int), [0]]))
        for lo, hi in zip(y_ext[np.nonzero(edges == 1)[0]], y_ext[np.nonzero(edges == -1)[0]]):
            out += [(z0, lo), (z0, hi), (z1, hi), (z1, lo), (z0, lo), (np.nan, np.nan)]
    return np.array(out)


def _fan_plot(lens: Lens, medium: Medium, section: Slabs | Taper | None) -> Plot:
    """About 30 rays from the nominal feed through the as-built lens to the antenna plane."""
    tr, keep = trace_lens(lens, medium, lens.feed, FAN_RAYS)
    start = max(lens.feed[0], float(lens.front_z(0.0)) - 4 * lens.radius_mm)
    lines = []
    for i in np.nonzero(keep)[0]:
        pts = tr.points[:, i]
        pts = pts[np.concatenate([[True], np.linalg.norm(np.diff(pts, axis=0), axis=-1) > 0])]
        d = tr.directions[0, i]
        pts[0] = pts[0] + (start - pts[0, 0]) / d[0] * d
        lines += [pts, [[np.nan, np.nan]]]
    rays = np.concatenate(lines)
    outline = _outline(lens, section)
    return Plot("ray-fan", "Ray fan through the lens as built", "z (mm)", "y (mm)",
                (Series("lens as built", outline[:, 0], outline[:, 1], "line"),
                 Series("rays", rays[:, 0], rays[:, 1], "line")), equal_aspect=True,
                caption=f"feed at z {lens.feed[0]:.1f}, y {lens.feed[1]:.1f} mm; rays drawn from z {start:.0f} mm")
