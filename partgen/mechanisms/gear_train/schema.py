"""The design YAML of a gear train in a frame (``kind: gear_train``): a table of stages, the tooth
system, the shafts and the frame. Every length in mm, every angle in degrees, clearances diametral."""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import Field, model_validator

from ...config.schema import DesignHeader, Gap, Length, MotionChecks, Ratio, Strict, Teeth, ToleranceTarget

__all__ = ["GearTrainDesign"]

Angle = Annotated[float, Field(ge=-360.0, le=360.0)]
Shift = Annotated[float, Field(ge=-1.0, le=1.5)]


class TrainGears(Strict):
    module_mm: Length
    """Module of every gear (reference pitch diameter / teeth); with helix_system normal, the hob's normal module."""
    pressure_angle_deg: Annotated[float, Field(ge=10.0, le=35.0)] = 20.0
    """Pressure angle of the basic rack (normal or transverse, as helix_system says); 20 is standard."""
    face_width_mm: Length = 8.0
    """Gear thickness along its shaft (each layer of the train)."""
    backlash_per_gear_mm: Gap | Literal["auto"] = 0.1
    """Per gear: each tooth is thinned by this arc length at its reference pitch circle, so a mesh at its
    zero-backlash centre distance has the sum of both as circumferential backlash; auto: the least that (with the
    running clearance) meets tolerance.max_jam_probability on the printer."""
    profile_shift: Literal["auto"] | Shift = "auto"
    """Profile shift coefficient (× module) of stages that give no centre distance; auto: the smallest shift that
    avoids undercut (0 at and above the undercut limit)."""
    shift_range: Annotated[list[Shift], Field(min_length=2, max_length=2)] = [-0.5, 1.0]
    """[lowest, highest] profile shift coefficient a gear may take when a stage's centre_distance_mm is met by
    shifting (the sum is solved, then split)."""
    addendum_coeff: Annotated[float, Field(ge=0.5, le=1.5)] = 1.0
    """Tooth height above the reference circle, × module."""
    dedendum_coeff: Annotated[float, Field(ge=0.8, le=2.0)] = 1.25
    """Tooth depth below the reference circle, × module."""
    chord_tolerance_mm: Annotated[float, Field(ge=0.001, le=0.1)] = 0.01
    """Largest chord sagitta (deviation of the faceted outline from the exact curve) on flanks, fillets and tips;
    smaller is smoother and heavier STLs."""
    min_teeth: Teeth = 12
    """Fewest teeth a gear chosen from a ratio may have."""
    max_teeth: Teeth = 100
    """Most teeth a gear chosen from a ratio may have."""
    helix_angle_deg: Annotated[float, Field(ge=0.0, le=45.0)] = 0.0
    """Helix angle at the reference cylinder; 0: spur gears (meshing gears take opposite hands, a compound part's two
    gears the same)."""
    helix_system: Literal["normal", "transverse"] = "normal"
    """What module_mm and pressure_angle_deg are for helical gears: normal (a hob's: m_t = m_n / cos β) or
    transverse."""
    herringbone: bool = False
    """Make each helical gear two mirrored halves (needs helix_angle_deg); no axial thrust."""

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
    teeth: Annotated[list[Teeth], Field(min_length=2, max_length=2)] | None = None
    """Teeth of [driver, driven]; none: chosen from ratio, or from train.ratio when the stage gives neither."""
    ratio: Ratio | None = None
    """Speed ratio of the stage to meet, z_driven / z_driver: whole teeth with the smallest error, then the smallest
    pair."""
    exact: bool = False
    """The stage's ratio must be met exactly (else the nearest whole teeth)."""
    centre_distance_mm: Length | None = None
    """Centre distance to meet, by profile shifts within gears.shift_range (solved, not looked up); none: the shifted
    pair's own zero-backlash distance."""
    idler: bool = False
    """The previous stage's driven gear drives this stage itself (one layer; the sense of rotation turned back)
    instead of a compound gear on its shaft."""
    angle_deg: Angle = 0.0
    """Direction of the driven shaft from the driver's in the plan: turn stages to fold a train onto the bed."""

    @model_validator(mode="after")
    def _one_way(self):
        if self.teeth is not None and self.ratio is not None:
            raise ValueError("[ratio] give the teeth or a ratio to meet, not both")
        if self.exact and self.ratio is None:
            raise ValueError("[exact] says a ratio must be met exactly: give the ratio")
        return self


class Train(Strict):
    ratio: Ratio | None = None
    """Overall speed ratio input / output, split evenly over the stages that give neither teeth nor a ratio."""
    ratio_exact: bool = False
    """The overall ratio must be met exactly (else the whole teeth nearest it)."""
    stages: Annotated[list[Stage], Field(min_length=1, max_length=8)]
    """The stages, input first: stage k meshes a driver on shaft k with a driven gear on shaft k + 1."""


class Planetary(Strict):
    """A planetary set: the ring fixed in the frame, the sun on the input shaft, the carrier on the output."""

    ratio: Annotated[float, Field(gt=1.0, le=100)] | None = None
    """Speed ratio 1 + z_ring / z_sun to meet (sun input, carrier output, ring fixed): the nearest within 2 % or
    refused with the range that can be reached."""
    exact: bool = False
    """The ratio must be met exactly."""
    teeth: Annotated[list[Teeth], Field(min_length=3, max_length=3)] | None = None
    """Teeth of [sun, planet, ring] instead of a ratio (coaxial: ring = sun + 2 × planet)."""
    planets: Annotated[int, Field(ge=2, le=8)] = 3
    """Number of planets."""
    spacing: Literal["equal", "unequal"] = "equal"
    """equal: planets evenly spaced ((z_sun + z_ring) / planets must be whole); unequal: each where (z_sun + z_ring)
    γ / 2π is whole."""
    pin_diameter_mm: Length | None = None
    """Diameter of the carrier's pins the planets run on; none: shafts.diameter_mm."""
    rim_mm: Length = 5.0
    """Wall of the ring gear beyond its root circle."""

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
    """Teeth of the pinion."""
    travel_mm: Length = 80.0
    """How far the rack moves, end to end, over the checked motion (the rack is long enough to stay in mesh over it)."""
    back_mm: Length = 6.0
    """Depth of the rack's body below its root line."""


class Shafts(Strict):
    diameter_mm: Length = 8.0
    """Diameter of every shaft (and of the carrier's pins unless planetary.pin_diameter_mm)."""
    running_clearance_diametral_mm: Literal["printer", "auto"] | Annotated[float, Field(ge=0, le=5)] = "printer"
    """Diametral running clearance, a bore minus the shaft or pin turning in it; printer: the printer profile's
    measured running fit; auto: the least that (with the backlash) meets tolerance.max_jam_probability on the
    printer."""
    press_fit_clearance_diametral_mm: Literal["printer"] | Annotated[float, Field(ge=-1, le=5)] = "printer"
    """Diametral clearance of a part pressed on a shaft or a pin pressed into a plate (hole minus shaft; negative:
    interference); printer: the printer profile's measured press fit."""
    bores: Annotated[list[Literal["round", "d_flat", "keyway", "hex", "set_screw"]],
                     Field(min_length=1, max_length=9)] | None = None
    """How each shaft's gear part is held, input first: round (the part turns on a fixed pin), d_flat (pressed on a
    D), keyway (over the printed shaft's key), hex (an ISO nut trapped in the hub, screwed onto a bought threaded
    rod) or set_screw (a radial set screw into a captive square nut); none: d_flat at the input and the output,
    round between. A planetary set takes [input (sun), output (carrier)], a rack [pinion], never round."""
    nut: Annotated[str, Field(min_length=1, max_length=10)] | None = None
    """hex bores: the nut and threaded rod size, M3, M4, M5, M6 or M8 (ISO 4032 nut, DIN 976 rod)."""
    set_screw: Annotated[str, Field(min_length=1, max_length=10)] = "M3"
    """set_screw bores: the screw size, M3, M4, M5, M6 or M8 (ISO 4026 set screw, DIN 562 square nut)."""
    extension_mm: Gap = 10.0
    """How far a turning shaft stands above the top plate, for a crank or a coupling."""


class Frame(Strict):
    plate_thickness_mm: Length = 4.0
    """Thickness of the bottom and top plates."""
    margin_mm: Length = 4.0
    """How far the plates reach beyond each tip circle."""
    spacer_diameter_mm: Length = 10.0
    """Diameter of the four spacers between the plates (columns of the bottom plate, pegs pressed into the top
    plate)."""
    axial_gap_mm: Length = 0.5
    """Gap between layers of gears, and between a gear and a plate."""
    hub_diameter_mm: Length | None = None
    """Diameter of the hub a gear part stands on when its lowest gear is above the first layer; none: the bore plus
    three printer walls (at least 2.5 mm) or what its nut or set screw needs; either way at most what clears the
    other shafts' gears by checks.min_clearance_mm."""


class TrainChecks(MotionChecks):
    """What `partgen check` holds a train to (the shared checks' settings; frame.hub_diameter_mm is bounded
    by min_clearance_mm)."""

    samples: Annotated[int, Field(ge=8, le=10_000)] = 360
    """Angles checked over one turn of the slowest shaft, or over the rack's travel (--samples overrides it)."""


class GearTrainDesign(DesignHeader):
    AUTO_PLAY: ClassVar[dict] = {"gears.backlash_per_gear_mm": "backlash",
                                 "shafts.running_clearance_diametral_mm": "running"}  # mechanisms.autoplay
    kind: Literal["gear_train"]
    """The mechanism this file designs: `gear_train` selects these keys."""
    gears: TrainGears
    """The tooth system every gear shares: module, pressure angle, face width, play, shifts, helix."""
    train: Train | None = None
    """A row of stages (one of train, planetary, rack)."""
    planetary: Planetary | None = None
    """A planetary set: ring fixed, sun input, carrier output (one of train, planetary, rack)."""
    rack: Rack | None = None
    """A rack and pinion (one of train, planetary, rack)."""
    shafts: Shafts = Shafts()
    """The shafts, their fits and how each gear part is held on its shaft."""
    frame: Frame = Frame()
    """The frame: two plates on four spacers, and the gaps between layers."""
    checks: TrainChecks = TrainChecks()
    """What partgen check holds the kit to."""
    tolerance: ToleranceTarget = ToleranceTarget()
    """The jam probability that auto play (gears.backlash_per_gear_mm, shafts.running_clearance_diametral_mm) is
    chosen for, and above which check warns."""

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
