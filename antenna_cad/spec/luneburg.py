"""Spec of the multilayer Luneburg lens (seed-002; digest ``reference/seed-002.md`` §5.2).

``material`` is the solid base polymer of the foams (εr, tanδ, density of the solid); each layer
is a foam of it (Robinson fill factor, §2.7), or the nearest of ``design.grades`` when given.
"""

from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import Field, model_validator

from antenna_cad.spec.bounds import MAX_LIST, MIN_RATIO, MIN_SHEET_MM
from antenna_cad.spec.cam import CamSpec
from antenna_cad.spec.common import BoardSpec, SpecBase, StrictModel, or_auto
from antenna_cad.spec.printed import PrintedSpec


MAX_LAYERS = 100      # shells of a multilayer lens (seed-002 designs use 3–20)


class OuterShellSpec(StrictModel):
    a_over_r: float = Field(ge=MIN_RATIO, lt=1)
    eps_r: float = Field(ge=1.0, le=20.0)


class LadderSpec(StrictModel):
    eps_outer: float = Field(ge=1.0, le=20.0)
    ratio: float = Field(gt=1.0, le=5.0)


class LayersSpec(StrictModel):
    count: or_auto(Annotated[int, Field(ge=1, le=MAX_LAYERS)]) = "auto"
    split: Literal["equal_eps", "equal_n", "equal_thickness", "ladder"] = "equal_eps"
    ladder: LadderSpec | None = None

    @model_validator(mode="after")
    def _ladder(self):
        if self.split == "ladder" and self.ladder is None:
            raise ValueError("design.layers.ladder: split 'ladder' needs {eps_outer, ratio}")
        return self


class FeedBossSpec(StrictModel):
    """Dielectric boss below the equator (−Y) to which the metal feed arm is fixed, outside the
    aperture cylinder; made of the outer layer's foam."""
    diameter_mm: float = Field(40.0, ge=1, le=1000)
    length_mm: float = Field(40.0, ge=1, le=2000)


class LuneburgDesignSpec(StrictModel):
    diameter_mm: float = Field(ge=1, le=20000)
    focal_distance_ratio: float = Field(1.0, ge=1.0, le=10.0, description="b/R, feed distance from the centre")
    law: Literal["classic", "generalized", "outer_shell"] = "classic"
    outer_shell: OuterShellSpec | None = None
    layers: LayersSpec = LayersSpec()
    shape: Literal["sphere", "cylinder"] = "sphere"
    height_mm: float | None = Field(None, ge=0.1, le=1000, description="cylinder: plate spacing")
    grades: list[Annotated[float, Field(ge=1.0, le=20.0)]] | None = Field(
        None, max_length=MAX_LIST, description="available foam grades (εr); each layer takes the nearest")
    edge_taper_db: float = Field(-10.0, lt=0, ge=-40)
    feed_q: float | None = Field(None, ge=MIN_RATIO, le=50)

    @model_validator(mode="after")
    def _rules(self):
        if self.law == "outer_shell" and self.outer_shell is None:
            raise ValueError("design.outer_shell: law 'outer_shell' needs {a_over_r, eps_r}")
        if self.law == "classic" and self.focal_distance_ratio != 1.0:
            raise ValueError(f"design.focal_distance_ratio: law 'classic' focuses on the surface "
                             f"(b/R = 1), got {self.focal_distance_ratio:g}; use law 'generalized'")
        if self.shape == "cylinder" and self.height_mm is None:
            raise ValueError("design.height_mm: a cylinder lens needs its plate spacing")
        return self


class LuneburgShellsSpec(StrictModel):
    """Each shell as front/back hemispheres (moulded or machined), with foam alignment pins."""
    method: Literal["shells"]
    pins_per_shell: int = Field(3, ge=0, le=12)
    pin_diameter_mm: float = Field(8.0, ge=0.5, le=100)
    machining_allowance_mm: float = Field(3.0, ge=0, le=100, description="blank oversize on every side")
    feed_boss: FeedBossSpec | None = FeedBossSpec()


class LuneburgLayupSpec(StrictModel):
    """Sphere sliced into sheets of stock thickness; each sheet a set of concentric rings."""
    method: Literal["sheet_layup"]
    sheet_thickness_mm: float = Field(ge=MIN_SHEET_MM, le=200)
    board: BoardSpec = BoardSpec()
    kerf_mm: float = Field(0.0, ge=0, le=10)
    ring_sizing: Literal["contain", "mid_plane"] = Field(
        "contain", description="contain: every ring holds its shell over the whole slab (sanding/turning "
        "only removes material); mid_plane: ring radii at the sheet mid-plane (stepped, no finishing)")
    registration_hole_mm: float = Field(
        6.0, ge=0, le=50, description="registration dowel holes: across every sheet joint, 3 dowels at 120° per "
        "shell crossed by both sheets, inside that shell and of its grade (cylinder: 3 through pins per ring); "
        "0: none")
    pedestal_height_mm: float | None = Field(
        None, ge=20, le=1000, description="sphere: a stand — under every sheet a foot of the outer grade from "
        "the aperture circle down this far below the lens (a cradle, outside the aperture cylinder, feet "
        "dowelled to each other); none: no stand")
    pedestal_width_mm: float | None = Field(None, ge=1, le=20000, description="stand width; default 60 % of the diameter")
    edge: Literal["stepped", "taper"] = Field(
        "stepped", description="stepped: vertical ring edges (ring_sizing); taper: each ring's outer and inner "
        "edge cut as the cone through its sphere at the sheet's two faces (hot wire, no turning; sphere only)")
    cam: CamSpec | None = Field(None, description="toolpaths (cam/): with edge: taper, hot-wire G-code for each "
                                "ring's cones; with stepped edges, router G-code for the ring pieces and feet, one "
                                "file per board (cam.router)")


class LuneburgSpec(SpecBase):
    kind: Literal["luneburg"]
    design: LuneburgDesignSpec
    fabrication: Annotated[Union[LuneburgShellsSpec, LuneburgLayupSpec, PrintedSpec],
                           Field(discriminator="method")] = \
        LuneburgShellsSpec(method="shells")

    @model_validator(mode="after")
    def _stand(self):
        fab, d = self.fabrication, self.design
        if isinstance(fab, PrintedSpec):
            fab.check_lens(self.material, self.frequency_ghz)
            if d.shape == "cylinder":
                fab.check_height(d.height_mm)
            tall = d.diameter_mm / 2 if d.shape == "sphere" else d.height_mm
            if tall > fab.bed.z_mm:
                raise ValueError(f"fabrication.bed.z_mm: a {'hemisphere' if d.shape == 'sphere' else 'lens'} "
                                 f"{tall:g} mm tall does not fit (horizontal cuts are not made; got {fab.bed.z_mm:g})")
        if isinstance(fab, LuneburgLayupSpec) and fab.edge == "taper":
            if d.shape != "sphere":
                raise ValueError("fabrication.edge: taper is for the sphere (a cylinder's rings are already exact)")
            if fab.ring_sizing != "contain":
                raise ValueError("fabrication.edge: taper needs ring_sizing: contain (the blank each cone is cut from)")
        if isinstance(fab, LuneburgLayupSpec) and fab.pedestal_height_mm is not None:
            if d.shape != "sphere":
                raise ValueError("fabrication.pedestal_height_mm: a stand is for the sphere (the cylinder sits "
                                 "between its plates)")
            if fab.pedestal_width_mm is not None and fab.pedestal_width_mm >= d.diameter_mm:
                raise ValueError(f"fabrication.pedestal_width_mm: must be < design.diameter_mm "
                                 f"({fab.pedestal_width_mm:g} ≥ {d.diameter_mm:g})")
        return self
