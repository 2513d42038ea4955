"""Material library: relative permittivity, loss tangent and density.

Dielectric constants and loss tangents are seed-000 Table 1.2 (§3.1 of the digest), X band.
The seed gives **no densities**: the ``density_kg_m3`` values below are typical datasheet values
(XPS boards 30–35 kg/m³, solid polymers and ceramics from common suppliers' sheets, birch plywood
600–700 kg/m³). They are estimates for the mass figures only; override them in a spec with an
inline ``{eps_r, tan_delta, density_kg_m3}`` material taken from your board's datasheet.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Material:
    name: str
    eps_r: float
    tan_delta: float
    density_kg_m3: float
    note: str = ""

    @property
    def n(self) -> float:
        """Refractive index sqrt(εr) (non-magnetic media)."""
        return self.eps_r ** 0.5


_TYPICAL = "density: typical datasheet value (not in the seed)"

_FILAMENT = ("FDM filament, printed solid; εr and tanδ near 10 GHz: typical published values (printed lenses "
             "use the table of antenna_cad.printed for the lattice); " + _TYPICAL)
FILAMENTS: tuple[Material, ...] = (
    Material("pla", 2.7, 1e-2, 1240.0, _FILAMENT),
    Material("petg", 2.6, 7e-3, 1270.0, _FILAMENT),
    Material("abs", 2.5, 5e-3, 1040.0, _FILAMENT),
    Material("hips", 2.45, 3e-3, 1040.0, _FILAMENT),
    Material("abs_ceramic_4.4", 4.4, 4e-3, 1900.0, "ceramic-filled ABS filament (low-loss, εr 4.4 grade); " + _FILAMENT),
)

LIBRARY: dict[str, Material] = {m.name: m for m in (
    Material("xps", 1.047, 2e-4, 33.0, "extruded polystyrene foam board; εr as seed-000 §2–§3; " + _TYPICAL),
    Material("ptfe", 2.08, 3.7e-4, 2200.0, "PTFE (Fluoroplast-4); " + _TYPICAL),
    Material("polyethylene", 2.26, 5e-4, 950.0, "HDPE; " + _TYPICAL),
    Material("polystyrene", 2.55, 7e-4, 1050.0, "solid polystyrene; " + _TYPICAL),
    Material("pmma", 2.61, 8e-3, 1190.0, "plexiglass; " + _TYPICAL),
    Material("ebonite", 2.67, 6e-3, 1150.0, _TYPICAL),
    Material("textolite", 3.67, 6e-2, 1350.0, "phenolic cotton laminate; " + _TYPICAL),
    Material("fused_quartz", 3.8, 1.7e-4, 2200.0, _TYPICAL),
    Material("glass", 4.2, 2.9e-3, 2500.0, "glass C38-1; " + _TYPICAL),
    Material("ceramic", 5.2, 3e-3, 2900.0, _TYPICAL),
    Material("plywood", 2.0, 5e-2, 650.0, "birch plywood for boxes (structural, not a lens material); " + _TYPICAL),
) + FILAMENTS}



def get_material(name: str) -> Material:
    """Library lookup; raises KeyError listing the known names."""
    try:
        return LIBRARY[name]
    except KeyError:
        raise KeyError(f"unknown material {name!r}; known: {', '.join(sorted(LIBRARY))}") from None
