"""The ``fabrication.cam`` block: the machine that cuts the sheets and how (DESIGN.md ``cam/``).

A built-in profile by name (``hotwire-4axis`` XYUV, ``hotwire-grbl`` XYZA, ``router-3axis``), a
profile file (put inline when the spec is loaded, :mod:`antenna_cad.spec.machine_file`) or an
inline profile; any profile value can be overridden here. Kerf: a table of (feed mm/min, kerf mm)
per foam grade, interpolated at the feed (built-in tables for xps and eps).
"""

from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import AfterValidator, Discriminator, Field, Tag, field_validator, model_validator

from antenna_cad.cam.machines import BUILT_IN
from antenna_cad.spec.common import StrictModel

Axes = Annotated[str, Field(pattern=r"^[A-Z]{3,4}$", description="axis letters: hot wire XYUV/XYZA order "
                            "(tower 1 horizontal, vertical, tower 2 horizontal, vertical); router XYZ")]
KerfTable = tuple[tuple[Annotated[float, Field(ge=1, le=20000)], Annotated[float, Field(ge=0, le=10)]], ...]


class MachineSpec(StrictModel):
    """An inline machine profile (the fields of a built-in one)."""
    name: str = Field("custom", pattern=r"^[a-z0-9_-]+$")
    kind: Literal["hotwire", "router"]
    axes: Axes
    feed_mode: Literal["inverse_time", "per_minute"] = "per_minute"
    span_mm: float = Field(0.0, ge=0, le=10000)
    travel_mm: tuple[Annotated[float, Field(ge=1, le=20000)], Annotated[float, Field(ge=1, le=20000)]]
    rapid_mm_min: float = Field(1000.0, ge=1, le=100000)
    heat_on: str = Field("M3 S{power}", pattern=r"^([A-Z0-9 .\n]|\{power\})*$",
                         description="G-code line(s) switching the wire's heat on; {power}: cam.heat_power")
    heat_off: str = Field("M5", pattern=r"^[A-Z0-9 .\n]*$")
    dwell_s: float = Field(2.0, ge=0, le=600)
    min_span_mm: float = Field(0.0, ge=0, le=10000, description="towers movable down to this span (the plan "
                               "sets them as close as the foam allows); 0: a fixed bow of span_mm")


def _unread_file(v: str) -> str:
    raise ValueError(f"fabrication.cam.machine: the profile file {v} is read when the spec is loaded from its file "
                     "(make-lens SPEC), not from a document")


ProfileFile = Annotated[str, Field(pattern=r"\.ya?ml$", description="a profile file (YAML, the keys of an inline "
                                   "profile), relative to the spec's folder"), AfterValidator(_unread_file)]
MachineRef = Annotated[
    Union[Annotated[Literal[tuple(BUILT_IN)], Tag("builtin")], Annotated[ProfileFile, Tag("profile_file")],
          Annotated[MachineSpec, Tag("inline")]],
    Discriminator(lambda v: ("profile_file" if v.lower().endswith((".yaml", ".yml")) else "builtin") if isinstance(v, str)
                  else "inline"),
    Field(description="a built-in profile name, a profile file (.yaml, relative to the spec's folder), or an "
          "inline profile")]


class RouterSpec(StrictModel):
    """The router's 2.5-D cuts of the flat parts (box panels), one file per board."""
    tool_diameter_mm: float = Field(6.0, ge=0.5, le=50)
    pass_depth_mm: float = Field(6.0, ge=0.1, le=50, description="depth of cut per pass")
    feed_mm_min: float = Field(1500.0, ge=1, le=50000)
    plunge_mm_min: float = Field(300.0, ge=1, le=50000)
    rapid_mm_min: float = Field(5000.0, ge=1, le=100000)
    direction: Literal["climb", "conventional"] = "climb"
    ramp_length_mm: float = Field(30.0, ge=1, le=1000, description="each pass enters on a ramp this long")
    tabs_per_edge: int = Field(1, ge=0, le=10)
    tab_width_mm: float = Field(8.0, ge=1, le=200)
    tab_height_mm: float = Field(3.0, ge=0.1, le=50)


class CamSpec(StrictModel):
    """Toolpaths for the sheets: hot-wire G-code per piece (cones for ``edge: taper``, straight
    XY = UV cuts otherwise) and a drilling file per piece with dowel holes."""
    machine: MachineRef = "hotwire-4axis"
    axes: Axes | None = None
    units: Literal["mm", "inch"] = "mm"
    feed_mm_min: float = Field(300.0, ge=1, le=20000, description="wire speed at the faster foam face")
    feed_mode: Literal["inverse_time", "per_minute"] | None = Field(
        None, description="G93 inverse time (synchronized towers) or G94 units per minute; default: the profile's")
    heat_power: float = Field(100.0, ge=0, le=100000, description="the {power} of the heat-on template")
    dwell_s: float | None = Field(None, ge=0, le=600)
    tower_span_mm: float | None = Field(None, ge=10, le=10000, description="set the towers this far apart for "
                                        "every cut (default: as close as the foam allows, on movable towers)")
    travel_mm: tuple[Annotated[float, Field(ge=1, le=20000)], Annotated[float, Field(ge=1, le=20000)]] | None = None
    foam_grade: str | None = Field(None, pattern=r"^[a-z0-9_-]+$", description="kerf table key; default the material name")
    kerf_table: dict[Annotated[str, Field(pattern=r"^[a-z0-9_-]+$")], KerfTable] = Field(
        default_factory=dict, description="grade → ((feed mm/min, kerf mm), …), over the built-in tables")
    lead_in_mm: float = Field(10.0, ge=0, le=500, description="straight lead from the entry point outward (see lead_in_at)")
    lead_in_at: Literal["top", "foot", "dowel_line", "butt_joint"] = Field(
        "top", description="where the wire enters each piece: its top, its foot (the bottom, under the cradle), "
        "on the radial line through a dowel hole, or at a butt joint of a sheet cut from strips")
    safe_height_mm: float = Field(20.0, ge=1, le=1000, description="wire height above the foam at start/stop")
    order: Literal["flat_first", "vertex_first"] = Field(
        "flat_first", description="cut order of the sheets (flat_first follows the assembly order)")
    drill_feed_mm_min: float = Field(600.0, ge=1, le=20000)
    router: RouterSpec | None = Field(RouterSpec(), description="router files for the box panels (null: none)")

    @field_validator("kerf_table")
    @classmethod
    def _tables(cls, v):
        for grade, table in v.items():
            if len(table) < 1 or len({f for f, _ in table}) != len(table):
                raise ValueError(f"{grade}: needs at least one row and distinct feeds")
        return v

    @model_validator(mode="after")
    def _hotwire(self):
        m = BUILT_IN[self.machine] if isinstance(self.machine, str) else self.machine
        if m.kind != "hotwire":
            raise ValueError(f"machine: {m.name} is a router; the sheets' edges need a hot-wire profile")
        return self
