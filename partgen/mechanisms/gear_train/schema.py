"""The design YAML of a gear train in a frame (``kind: gear_train``): a table of stages, the tooth
system, the shafts and the frame. Every length in mm, every angle in degrees, clearances diametral."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator

from ...config.schema import Gap, Length, Material, Name, Ratio, Strict, Teeth, Text

__all__ = ["GearTrainDesign"]

Angle = Annotated[float, Field(ge=-360.0, le=360.0)]
Shift = Annotated[float, Field(ge=-1.0, le=1.5)]


class TrainGears(Strict):
    module_mm: Length
    pressure_angle_deg: Annotated[float, Field(ge=10.0, le=35.0)] = 20.0
    face_width_mm: Length = 8.0
    backlash_per_gear_mm: Gap = 0.1  # circumferential thinning of each gear's tooth at its reference pitch circle
    profile_shift: Literal["auto"] | Shift = "auto"  # for stages whose centre distance is not given
    shift_range: Annotated[list[Shift], Field(min_length=2, max_length=2)] = [-0.5, 1.0]  # a centre distance's shifts
    addendum_coeff: Annotated[float, Field(ge=0.5, le=1.5)] = 1.0
    dedendum_coeff: Annotated[float, Field(ge=0.8, le=2.0)] = 1.25
    chord_tolerance_mm: Annotated[float, Field(ge=0.001, le=0.1)] = 0.01
    min_teeth: Teeth = 12
    max_teeth: Teeth = 100
    helix_angle_deg: Annotated[float, Field(ge=0.0, le=45.0)] = 0.0  # at the reference cylinder; 0: spur
    helix_system: Literal["normal", "transverse"] = "normal"  # what module_mm and pressure_angle_deg are
    herringbone: bool = False  # two mirrored helical halves

    @model_validator(mode="after")
    def _ranges(self):
        if self.herringbone and self.helix_angle_deg == 0:
            raise ValueError("[herringbone] needs a helix angle: give helix_angle_deg")
        if self.shift_range[0] >= self.shift_range[1]:
            raise ValueError(f"[shift_range] must be [lowest, highest], got {self.shift_range}")
        if self.min_teeth > self.max_teeth:
            raise ValueError(f"[min_teeth] {self.min_teeth} is above max_teeth {self.max_teeth}")
        return self


class Stage(Strict):
    teeth: Annotated[list[Teeth], Field(min_length=2, max_length=2)] | None = None  # driver, driven
    ratio: Ratio | None = None  # z_driven / z_driver to meet
    exact: bool = False
    centre_distance_mm: Length | None = None
    idler: bool = False  # the previous stage's driven gear drives this stage itself
    angle_deg: Angle = 0.0  # direction of the driven shaft from the driver's, in the plan

    @model_validator(mode="after")
    def _one_way(self):
        if self.teeth is not None and self.ratio is not None:
            raise ValueError("[ratio] give the teeth or a ratio to meet, not both")
        if self.exact and self.ratio is None:
            raise ValueError("[exact] says a ratio must be met exactly: give the ratio")
        return self


class Train(Strict):
    ratio: Ratio | None = None  # overall speed ratio input / output, split over the stages that give nothing
    ratio_exact: bool = False
    stages: Annotated[list[Stage], Field(min_length=1, max_length=8)]


class Planetary(Strict):
    """A planetary set: the ring fixed in the frame, the sun on the input shaft, the carrier on the output."""

    ratio: Annotated[float, Field(gt=1.0, le=100)] | None = None  # 1 + z_ring / z_sun to meet
    exact: bool = False
    teeth: Annotated[list[Teeth], Field(min_length=3, max_length=3)] | None = None  # sun, planet, ring
    planets: Annotated[int, Field(ge=2, le=8)] = 3
    spacing: Literal["equal", "unequal"] = "equal"  # unequal: where (z_sun + z_ring) γ / 2π is whole
    pin_diameter_mm: Length | None = None  # the carrier's pins the planets run on [shafts.diameter_mm]
    rim_mm: Length = 5.0  # the ring's wall beyond its root circle

    @model_validator(mode="after")
    def _one_way(self):
        if (self.ratio is None) == (self.teeth is None):
            raise ValueError("[ratio] give the ratio to meet or the teeth (sun, planet, ring), one of them")
        if self.exact and self.ratio is None:
            raise ValueError("[exact] says a ratio must be met exactly: give the ratio")
        return self


class Rack(Strict):
    """A rack and pinion: the pinion on a shaft turning in the base, the rack sliding in its guide."""

    pinion_teeth: Teeth
    travel_mm: Length = 80.0  # how far the rack moves, end to end, over the checked motion
    back_mm: Length = 6.0  # the rack's body under its root line


class Shafts(Strict):
    diameter_mm: Length = 8.0
    running_clearance_diametral_mm: Literal["printer"] | Annotated[float, Field(ge=0, le=5)] = "printer"
    press_fit_clearance_diametral_mm: Literal["printer"] | Annotated[float, Field(ge=-1, le=5)] = "printer"
    # per shaft, input first: round (the gear turns on a fixed pin), or the gear fixed to a shaft that
    # turns in the frame: d_flat (pressed on a D), keyway (a keyway over the printed shaft's key), hex
    # (a nut trap: an ISO nut in the hub screws it onto a bought threaded rod) or set_screw (a radial
    # set screw through the hub into a captive square nut); default d_flat at the input and the output,
    # round between. A planetary set: [input (the sun's), output (the carrier's)]; a rack: [the pinion's]
    bores: Annotated[list[Literal["round", "d_flat", "keyway", "hex", "set_screw"]],
                     Field(min_length=1, max_length=9)] | None = None
    nut: Annotated[str, Field(min_length=1, max_length=10)] | None = None  # hex bores: the nut and rod, M3–M8
    set_screw: Annotated[str, Field(min_length=1, max_length=10)] = "M3"  # set_screw bores: the screw, M3–M8
    extension_mm: Gap = 10.0  # how far a turning shaft stands above the top plate


class Frame(Strict):
    plate_thickness_mm: Length = 4.0
    margin_mm: Length = 4.0  # plates beyond each tip circle
    spacer_diameter_mm: Length = 10.0
    axial_gap_mm: Length = 0.5  # between layers, and between a gear and a plate
    hub_diameter_mm: Length | None = None  # None: the largest that clears the other shafts' gears (capped)


class TrainChecks(Strict):
    samples: Annotated[int, Field(ge=8, le=10_000)] = 360  # over one turn of the slowest shaft
    interference_tolerance_mm3: Annotated[float, Field(ge=0, le=100)] = 0.001
    min_clearance_mm: Gap = 0.3
    min_contact_ratio: Annotated[float, Field(ge=1.0, le=3.0)] = 1.2
    min_tip_width_roads: Annotated[float, Field(ge=0.5, le=10)] = 2.0
    plate_margin_mm: Gap = 5.0


class GearTrainDesign(Strict):
    kind: Literal["gear_train"]
    name: Name
    description: Text = ""
    printer: Annotated[str, Field(min_length=1, max_length=500)]
    gears: TrainGears
    train: Train | None = None
    planetary: Planetary | None = None
    rack: Rack | None = None
    shafts: Shafts = Shafts()
    frame: Frame = Frame()
    checks: TrainChecks = TrainChecks()
    material: Material

    @model_validator(mode="after")
    def _train_or_planetary(self):
        if sum(x is not None for x in (self.train, self.planetary, self.rack)) != 1:
            raise ValueError("[train] give one of: a train of stages (train), a planetary set (planetary), a rack and "
                             "pinion (rack)")
        if (self.planetary is not None or self.rack is not None) and self.shafts.bores:
            what, n = (("a planetary set's", 2) if self.planetary is not None else ("a rack's pinion", 1))
            order = "[input (sun), output (carrier)]" if n == 2 else "[pinion]"
            if len(self.shafts.bores) != n:
                raise ValueError(f"[shafts.bores] {what} shafts take {n} bore{'s' * (n > 1)}, {order}; got "
                                 f"{len(self.shafts.bores)}")
            if "round" in self.shafts.bores:
                raise ValueError(f"[shafts.bores] {what} shafts turn with their gear or carrier: d_flat, keyway, hex "
                                 "or set_screw, not round (a fixed pin)")
        if (self.planetary is not None or self.rack is not None) and self.gears.helix_angle_deg:
            raise ValueError("[gears.helix_angle_deg] planetary sets and racks are spur here (helical rings and "
                             "racks are not made)")
        return self
