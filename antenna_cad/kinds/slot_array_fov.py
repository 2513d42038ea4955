"""Report block of the slot array: σ against field angle for this design and the reference formers
(seed-003 §3.8, Fig. 3.15), with the σ(80°) values next to the thesis's.

The reference formers' curves do not depend on the spec (4–8 s of ray tracing): they are
kept in ``ANTENNA_CAD_CACHE`` (default ``$XDG_CACHE_HOME`` or ``~/.cache``, ``/antenna_cad``) under
the SHA-256 of the synthesis sources and the numpy/scipy versions, so any change to the formers or
the σ optimiser computes them afresh; the values are stored exactly (JSON floats round-trip).
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

import numpy as np
import scipy

from antenna_cad.synthesis.slot_array import SlotArrayDesign
from antenna_cad.synthesis.slot_array.fov import FOV_DEG, THESIS_SIGMA_80, FieldCurve, field_curve, reference_curves
from antenna_cad.synthesis.slot_array.optimise import FREE, OPTIMISED
from antenna_cad.verification import Plot, Series, Table

SYNTHESIS = Path(__file__).resolve().parents[1] / "synthesis"


def fov_block(design: SlotArrayDesign) -> tuple[Plot, Table, dict[str, float]]:
    """(plot of σ·10⁴ against beam azimuth, table of σ(80°), figures) — geometrical optics at β = 90°."""
    s = design.slots
    half = float(np.abs(s.guide_x_mm).max() + design.guide_width_mm / 2)
    own = field_curve(design.beamformer, half, f"this design ({design.beamformer.type})")
    curves = [own, *cached_reference_curves()]
    series = tuple(Series(c.name, c.angle_deg, 1e4 * c.sigma, "line" if k else "points")
                   for k, c in enumerate(curves))
    searched = {name: ", ".join(f"{k} {OPTIMISED[name][k]:.4g}" for k in FREE[name].names) for name in OPTIMISED}
    searched[own.name] = ", ".join(f"{k} {design.figures['optimised_' + k]:.4g}" for k in
                                   FREE[design.beamformer.type].names) if "optimised_evaluations" in design.figures else "as given"
    rows = tuple((c.name, f"{c.sigma_fov():.3g}", f"{THESIS_SIGMA_80[c.name]:.2g}" if c.name in THESIS_SIGMA_80 else "—",
                  round(float(c.angle_deg.max()), 1), searched.get(c.name, "as given (no search)")) for c in curves)
    plot = Plot("fov-sigma", "RMS path error σ against field angle (β = 90°)", "beam azimuth φ deg",
                "σ × 10⁴ (units of the aperture width)", series,
                f"σ of (2.7): RMS of the paths to the front about the central ray's, 50 rays; source moved radially "
                f"to minimum σ at every polar angle; {FOV_DEG:g}° field of view = |φ| ≤ {FOV_DEG / 2:g}°; reference "
                "formers optimised for it from the thesis's values (§3.8); a curve ends where rays miss", hlines=())
    table = Table("fov-sigma", f"σ at the {FOV_DEG:g}° field of view (largest σ for |φ| ≤ {FOV_DEG / 2:g}°)",
                  ("former", "σ(80°)", "thesis σ(80°)", "largest φ traced deg", "§3.8 search found (D = 1)"), rows,
                  "thesis values: seed-003 §3.8 (Fig. 3.15), each for a design optimised for 80°; the reference "
                  "formers here are optimised for it too from the thesis's values (the R9 mirror–lens is not); "
                  "NaN: the rays miss before 40°")
    figures = {"fov_traced_half_angle_deg": float(own.angle_deg.max())}
    if np.isfinite(own.sigma_fov()):                      # NaN: rays miss before the edge of the field of view
        figures["sigma_fov80_design"] = own.sigma_fov()
    return plot, table, figures


def cache_dir() -> Path:
    base = os.environ.get("ANTENNA_CAD_CACHE") or Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return Path(base) / "antenna_cad"


def _sources_key() -> str:
    digest = hashlib.sha256(f"{np.__version__} {scipy.__version__}".encode())
    for path in sorted(SYNTHESIS.rglob("*.py")):
        digest.update(path.relative_to(SYNTHESIS).as_posix().encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:32]


def cached_reference_curves() -> tuple[FieldCurve, ...]:
    """:func:`reference_curves`, read from the cache when the synthesis sources are unchanged
    (an unreadable or unwritable cache only costs the computation)."""
    path = cache_dir() / f"fov-reference-{_sources_key()}.json"
    try:
        rows = json.loads(path.read_text(encoding="utf-8"))
        return tuple(FieldCurve(r["name"], np.array(r["angle_deg"], float), np.array(r["sigma"], float),
                                float(r["aperture_mm"])) for r in rows)
    except (OSError, ValueError, KeyError, TypeError):
        pass
    curves = reference_curves()
    rows = [{"name": c.name, "angle_deg": c.angle_deg.tolist(), "sigma": c.sigma.tolist(),
             "aperture_mm": c.aperture_mm} for c in curves]
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        part = path.with_name(f".{path.name}.{os.getpid()}.part")
        part.write_text(json.dumps(rows), encoding="utf-8")
        os.replace(part, path)
    except OSError:
        pass
    return curves
