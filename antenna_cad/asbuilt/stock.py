"""The stock sheet thickness of a layup (``sheet_thickness_mm: auto``): every candidate laid up and judged
unsanded by the stack's own phase over the quiet zone (the fast model, or full-wave when it ran), beside
GO and the stair-step estimate k0(n−1)Δd of seed-000 §7.3."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from antenna_cad.asbuilt.lens import Lens, Stats, aperture_stats, cut_medium, lens_zone, trace_lens
from antenna_cad.asbuilt.revolved import modelled_stats, revolved
from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fullwave.verify import FullWave, fast_model
from antenna_cad.quietzone.verdict import FAST_ERROR_DEG, UNCERTAIN, judged, undecided
from antenna_cad.quietzone.volume import radii_mm, stack_ratios
from antenna_cad.spec.common import VerificationSpec
from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.collimator import step_phase_error_deg
from antenna_cad.verification import Table, cell


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


def candidates_table(study: tuple[Candidate, ...], layup: LayupPlan | None) -> Table:
    rows = tuple((c.thickness_mm, c.layup.count, cell(c.stats.p2p_deg), cell(c.stats.rms_deg), cell(c.model.p2p_deg),
                  cell(c.model.rms_deg), cell(c.zone.p2p_deg), cell(c.zone.rms_deg), cell(c.zone.plane_mm),
                  cell(c.estimate_deg), "yes" if c.meets else (c.note or "no"))
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
