"""The design YAML of a gear chain (``kind: gear_chain``): links or a curve, teeth, gears, plates, joints."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator

from ...config.schema import ToleranceTarget
from ...config.schema import (MAX, Coeff, Finite, Gap, Length, Material, Name, NonNeg, Pos, Ratio, Strict,
                              Teeth, Text)

__all__ = ["Design"]


class Polar(Strict):
    """ρ(θ) = constant + Σ sin[k]·sin kθ + cos[k]·cos kθ (curve units)."""

    constant: Coeff = 0.0
    sin: dict[Annotated[int, Field(ge=1, le=64)], Coeff] = {}
    cos: dict[Annotated[int, Field(ge=1, le=64)], Coeff] = {}


class Cartesian(Strict):
    """x = Σ a_k cos kθ + b_k sin kθ, y = Σ c_k cos kθ + d_k sin kθ; lists indexed by k from 0."""

    a: Annotated[list[Coeff], Field(min_length=1, max_length=65)]
    b: Annotated[list[Coeff], Field(min_length=1, max_length=65)]
    c: Annotated[list[Coeff], Field(min_length=1, max_length=65)]
    d: Annotated[list[Coeff], Field(min_length=1, max_length=65)]

    @model_validator(mode="after")
    def _same_length(self):
        if not (len(self.a) == len(self.b) == len(self.c) == len(self.d)):
            raise ValueError("a, b, c and d must have the same length")
        return self


Point = Annotated[list[Finite], Field(min_length=2, max_length=2)]
FileName = Annotated[str, Field(min_length=1, max_length=500)]


class Curve(Strict):
    """The curve the chain draws: Fourier coefficients (``polar``, ``cartesian``) at
    ``scale_mm_per_unit``, or a drawing (``points``: a CSV file or an inline list of [x, y] mm;
    ``svg``: a path of an SVG file) from which partgen picks the fewest links within
    ``max_deviation_mm``."""

    polar: Polar | None = None
    cartesian: Cartesian | None = None
    points: FileName | Annotated[list[Point], Field(max_length=100_000)] | None = None
    svg: FileName | None = None
    svg_path_id: Annotated[str, Field(min_length=1, max_length=200)] | None = None
    svg_mm_per_unit: Annotated[float, Field(gt=0, le=MAX)] | None = None
    parametrisation: Literal["samples", "arc_length"] | None = None
    close: bool = False
    max_deviation_mm: Annotated[float, Field(ge=0.001, le=MAX)] = 1.0
    max_links: Annotated[int, Field(ge=1, le=64)] = 16
    scale: Ratio | Literal["auto"] = 1.0  # auto: the smallest enlargement that builds (resolve._auto_scale)
    scale_mm_per_unit: Annotated[float, Field(ge=0.01, le=MAX)] | None = None
    drop_links: Annotated[list[Annotated[str, Field(max_length=40)]], Field(max_length=200)] = []

    @property
    def drawn(self) -> bool:
        return self.points is not None or self.svg is not None

    @model_validator(mode="after")
    def _one_form(self):
        given = [k for k in ("polar", "cartesian", "points", "svg") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of 'polar', 'cartesian', 'points' or 'svg'"
                             + (f" (got {', '.join(given)})" if given else ""))
        drawing_keys = ("parametrisation", "svg_path_id", "svg_mm_per_unit")
        if self.drawn:
            if self.scale_mm_per_unit is not None:
                raise ValueError("'scale_mm_per_unit' is for Fourier coefficients; a drawing is in mm "
                                 "(use 'scale' to enlarge or shrink it)")
            if self.drop_links:
                raise ValueError("'drop_links' is for Fourier coefficients; for a drawing partgen picks the links "
                                 "(set 'max_deviation_mm' and 'max_links')")
            if self.points is not None and (self.svg_path_id is not None or self.svg_mm_per_unit is not None):
                raise ValueError("'svg_path_id' and 'svg_mm_per_unit' go with 'svg', not 'points'")
        else:
            if self.scale_mm_per_unit is None:
                raise ValueError("'scale_mm_per_unit' is required with 'polar' or 'cartesian'")
            extra = [k for k in drawing_keys if getattr(self, k) is not None]
            extra += [k for k in ("close",) if self.close] + [k for k in ("scale",) if self.scale != 1.0]
            extra += [k for k in ("max_deviation_mm", "max_links") if k in self.model_fields_set]
            if extra:
                raise ValueError(f"{', '.join(extra)} go with a drawing ('points' or 'svg'), not Fourier coefficients")
        return self


class Target(Strict):
    """The curve a design table is meant to draw (for `partgen trace`), at print scale."""

    polar: Polar | None = None
    cartesian: Cartesian | None = None
    scale_mm_per_unit: Annotated[float, Field(ge=0.01, le=MAX)]

    @model_validator(mode="after")
    def _one_form(self):
        if (self.polar is None) == (self.cartesian is None):
            raise ValueError("give exactly one of 'polar' or 'cartesian'")
        return self


class LinkRow(Strict):
    name: Annotated[str, Field(min_length=1, max_length=40)]
    speed: Annotated[int, Field(ge=-1000, le=1000)]
    length_mm: Length
    initial_angle_deg: Finite

    @model_validator(mode="after")
    def _speed(self):
        if self.speed == 0:
            raise ValueError("speed must be a non-zero integer (0 is the fixed ground offset)")
        return self


class StageTeeth(Strict):
    """Teeth of link j's stage: D_j, idler M_j, G_{j+1}; ``idler_mm`` places the idler by hand (link
    frame: proximal joint at 0, distal at (S, 0)) instead of by circle intersection."""

    D: Teeth
    M: Teeth
    G: Teeth
    idler_mm: Annotated[list[Finite], Field(min_length=2, max_length=2)] | None = None


class Gears(Strict):
    module_mm: Length | Literal["auto"]  # auto: the largest module that builds and prints on the printer
    pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    addendum_coeff: Annotated[float, Field(gt=0, le=2)] = 1.0
    dedendum_coeff: Annotated[float, Field(gt=0, le=2.5)] = 1.25
    cutter_tip_radius_coeff: Annotated[float, Field(ge=0, le=0.6)] = 0.38
    profile_shift: Literal["auto"] | Annotated[float, Field(ge=-1, le=1.5)] = "auto"
    backlash_per_gear_mm: Gap | Literal["auto"] = 0.05  # auto: the least that meets tolerance.max_jam_probability
    face_width_mm: Length
    chord_tolerance_mm: Annotated[float, Field(ge=1e-4, le=0.1)] = 0.001
    hub_wall_mm: Length = 2.5
    tip_gap_mm: Gap = 1.5
    idler_reach_mm: Gap = 1.0


class Drive(Strict):
    teeth: Teeth
    angle_deg: Finite = -90.0


class Plates(Strict):
    thickness_mm: Length
    boss_wall_mm: Length = 4.0


class Joints(Strict):
    axle_diameter_mm: Length
    running_clearance_radial_mm: Finite | None = None
    # ``printer``: the fit the printer profile's maker measured (its fits.*_diametral_mm)
    running_clearance_diametral_mm: Finite | Literal["printer"] | None = None
    press_fit_clearance_radial_mm: Finite | None = None
    press_fit_clearance_diametral_mm: Finite | Literal["printer"] | None = None
    axial_gap_mm: Length = 0.5

    @model_validator(mode="after")
    def _one_each(self):
        for kind in ("running", "press_fit"):
            r, d = getattr(self, f"{kind}_clearance_radial_mm"), getattr(self, f"{kind}_clearance_diametral_mm")
            if (r is None) == (d is None):
                raise ValueError(f"give exactly one of {kind}_clearance_radial_mm or {kind}_clearance_diametral_mm")
        return self

    @property
    def running_diametral(self) -> float:
        r = self.running_clearance_radial_mm
        return 2 * r if r is not None else self.running_clearance_diametral_mm

    @property
    def press_fit_diametral(self) -> float:
        r = self.press_fit_clearance_radial_mm
        return 2 * r if r is not None else self.press_fit_clearance_diametral_mm


class Base(Strict):
    thickness_mm: Length = 6.0
    leg_height_mm: Length = 45.0
    crank_radius_mm: Length = 35.0


class Pen(Strict):
    diameter_mm: Length = 10.0
    holder_height_mm: Length = 20.0


class Belts(Strict):
    """Timing belts instead of idler gears: each D_j drives G_{j+1} through a stock closed belt."""

    profile: Annotated[str, Field(max_length=40)] = "GT2"
    pitch_mm: Length = 2.0
    pitch_line_offset_mm: Gap = 0.254
    groove_depth_mm: Length = 0.75
    groove_radius_mm: Length = 0.555
    back_height_mm: Length = 0.63
    width_mm: Length = 6.0
    stock_teeth: Annotated[list[Annotated[int, Field(ge=20, le=5000)]], Field(min_length=1, max_length=1000)]
    flange_height_mm: Length = 1.5
    flange_thickness_mm: Length = 1.0
    tensioner_radius_mm: Length = 7.0
    tensioner_gap_mm: Gap = 0.5

    @model_validator(mode="after")
    def _pitch_line_in_the_back(self):
        if self.pitch_line_offset_mm >= self.back_height_mm:
            raise ValueError(f"pitch_line_offset_mm ({self.pitch_line_offset_mm:g}) must be less than back_height_mm "
                             f"({self.back_height_mm:g}): the pitch line runs in the belt's tension cords, inside its back")
        return self


class Checks(Strict):
    """What `partgen check` holds a kit to."""

    samples: Annotated[int, Field(ge=4, le=10_000)] = 360
    interference_tolerance_mm3: NonNeg = 0.001
    min_clearance_mm: Gap = 0.3
    min_contact_ratio: Pos = 1.2
    min_tip_width_roads: Pos = 3.0
    plate_margin_mm: Gap = 5.0



class Design(Strict):
    kind: Literal["gear_chain"]
    name: Name
    description: Text = ""
    printer: Annotated[str, Field(min_length=1, max_length=500)]
    curve: Curve | None = None
    links: Annotated[list[LinkRow], Field(max_length=128)] | None = None
    target: Target | None = None
    offset_mm: Annotated[list[Finite], Field(min_length=2, max_length=2)] = [0.0, 0.0]
    teeth: Literal["auto"] | Annotated[list[StageTeeth], Field(max_length=128)]
    gears: Gears
    drive: Drive
    plates: Plates
    joints: Joints
    base: Base = Base()
    pen: Pen = Pen()
    checks: Checks = Checks()
    tolerance: ToleranceTarget = ToleranceTarget()
    belts: Belts | None = None
    material: Material

    @model_validator(mode="after")
    def _one_source(self):
        if self.curve is None and self.links is None:
            raise ValueError("[curve] required key is missing: give 'curve' (derive the links from a curve) or "
                             "'links' (a design table)")
        if self.curve is not None and self.links is not None:
            raise ValueError("[links] give 'curve' (derive the links) or 'links' (a design table), not both")
        if self.belts is not None and self.teeth != "auto":
            raise ValueError("[teeth] a belt design chooses its pulleys: give 'teeth: auto'")
        if self.target is not None and self.curve is not None:
            raise ValueError("[target] 'target' is for design tables ('links'); a 'curve' design is traced against "
                             "its curve")
        return self
