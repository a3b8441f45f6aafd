"""The YAML schema of a design and a printer profile (pydantic v2, strict, unknown keys forbidden).

Every length key ends in ``_mm``, every angle in ``_deg``; clearances say ``radial`` or
``diametral``. Defaults are documented in README's config reference.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

__all__ = ["Printer", "Design", "WristDesign", "BennettDesign"]

Pos = Annotated[float, Field(gt=0)]
NonNeg = Annotated[float, Field(ge=0)]
Teeth = Annotated[int, Field(ge=4, le=1000)]


class Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, frozen=True)


class Printer(Strict):
    name: str
    build_envelope_mm: Annotated[list[Pos], Field(min_length=3, max_length=3)]
    resolution_mm: Pos
    min_hole_diameter_mm: Pos = Field(description="smallest reliable revolute-joint hole")
    min_gear_diameter_mm: Pos = Field(description="smallest reliable gear (reference pitch diameter)")
    min_link_length_mm: Pos
    min_wall_mm: Pos
    min_hole_to_size_diameter_mm: Pos = Field(3.0, description="smallest hole held to size (press-fit D, pen bore)")


class Polar(Strict):
    """ρ(θ) = constant + Σ sin[k]·sin kθ + cos[k]·cos kθ (curve units)."""

    constant: float = 0.0
    sin: dict[Annotated[int, Field(ge=1, le=64)], float] = {}
    cos: dict[Annotated[int, Field(ge=1, le=64)], float] = {}


class Cartesian(Strict):
    """x = Σ a_k cos kθ + b_k sin kθ, y = Σ c_k cos kθ + d_k sin kθ; lists indexed by k from 0."""

    a: list[float]
    b: list[float]
    c: list[float]
    d: list[float]

    @model_validator(mode="after")
    def _same_length(self):
        if not (len(self.a) == len(self.b) == len(self.c) == len(self.d)):
            raise ValueError("a, b, c and d must have the same length")
        return self


class Curve(Strict):
    polar: Polar | None = None
    cartesian: Cartesian | None = None
    scale_mm_per_unit: Pos
    drop_links: list[str] = []

    @model_validator(mode="after")
    def _one_form(self):
        if (self.polar is None) == (self.cartesian is None):
            raise ValueError("give exactly one of 'polar' or 'cartesian'")
        return self


class Target(Strict):
    """The curve a design table is meant to draw (for `partgen trace`), at print scale."""

    polar: Polar | None = None
    cartesian: Cartesian | None = None
    scale_mm_per_unit: Pos

    @model_validator(mode="after")
    def _one_form(self):
        if (self.polar is None) == (self.cartesian is None):
            raise ValueError("give exactly one of 'polar' or 'cartesian'")
        return self


class LinkRow(Strict):
    name: str
    speed: int
    length_mm: Pos
    initial_angle_deg: float

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
    idler_mm: Annotated[list[float], Field(min_length=2, max_length=2)] | None = None


class Gears(Strict):
    module_mm: Pos
    pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    addendum_coeff: Annotated[float, Field(gt=0, le=2)] = 1.0
    dedendum_coeff: Annotated[float, Field(gt=0, le=2.5)] = 1.25
    cutter_tip_radius_coeff: Annotated[float, Field(ge=0, le=0.6)] = 0.38
    profile_shift: Literal["auto"] | Annotated[float, Field(ge=-1, le=1.5)] = "auto"
    backlash_per_gear_mm: NonNeg = 0.05
    face_width_mm: Pos
    chord_tolerance_mm: Annotated[float, Field(ge=1e-4, le=0.1)] = 0.001
    hub_wall_mm: Pos = 3.0
    tip_gap_mm: NonNeg = 1.5
    idler_reach_mm: NonNeg = 1.0


class Drive(Strict):
    teeth: Teeth
    angle_deg: float = -90.0


class Plates(Strict):
    thickness_mm: Pos
    boss_wall_mm: Pos = 4.0


class Joints(Strict):
    axle_diameter_mm: Pos
    running_clearance_radial_mm: float | None = None
    running_clearance_diametral_mm: float | None = None
    press_fit_clearance_radial_mm: float | None = None
    press_fit_clearance_diametral_mm: float | None = None
    axial_gap_mm: Pos = 0.5

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
    thickness_mm: Pos = 6.0
    leg_height_mm: Pos = 45.0
    crank_radius_mm: Pos = 35.0


class Pen(Strict):
    diameter_mm: Pos = 10.0
    holder_height_mm: Pos = 20.0


class Belts(Strict):
    """Timing belts instead of idler gears: each D_j drives G_{j+1} through a stock closed belt."""

    profile: str = "GT2"
    pitch_mm: Pos = 2.0
    pitch_line_offset_mm: NonNeg = 0.254
    groove_depth_mm: Pos = 0.75
    groove_radius_mm: Pos = 0.555
    back_height_mm: Pos = 0.63
    width_mm: Pos = 6.0
    stock_teeth: Annotated[list[Annotated[int, Field(ge=20, le=5000)]], Field(min_length=1)]
    flange_height_mm: Pos = 1.5
    flange_thickness_mm: Pos = 1.0
    tensioner_radius_mm: Pos = 7.0
    tensioner_gap_mm: NonNeg = 0.5


class Checks(Strict):
    """What `partgen check` holds a kit to."""

    samples: Annotated[int, Field(ge=4, le=100000)] = 360
    interference_tolerance_mm3: NonNeg = 0.001
    min_clearance_mm: NonNeg = 0.3
    min_contact_ratio: Pos = 1.2
    min_tip_width_roads: Pos = 3.0
    plate_margin_mm: NonNeg = 5.0


class Material(Strict):
    name: str
    density_g_cm3: Pos


class Design(Strict):
    name: Annotated[str, Field(pattern=r"^[A-Za-z0-9_.-]+$")]
    description: str = ""
    printer: str
    curve: Curve | None = None
    links: list[LinkRow] | None = None
    target: Target | None = None
    offset_mm: Annotated[list[float], Field(min_length=2, max_length=2)] = [0.0, 0.0]
    teeth: Literal["auto"] | list[StageTeeth]
    gears: Gears
    drive: Drive
    plates: Plates
    joints: Joints
    base: Base = Base()
    pen: Pen = Pen()
    checks: Checks = Checks()
    belts: Belts | None = None
    material: Material

    @model_validator(mode="after")
    def _one_source(self):
        if (self.curve is None) == (self.links is None):
            raise ValueError("give exactly one of 'curve' (derive the links) or 'links' (a design table)")
        if self.belts is not None and self.teeth != "auto":
            raise ValueError("a belt design chooses its pulleys: give 'teeth: auto'")
        if self.target is not None and self.curve is not None:
            raise ValueError("'target' is for design tables ('links'); a 'curve' design is traced against its curve")
        return self


class Tooth(Strict):
    shape: Literal["dome"] = "dome"
    radius_mm: Pos
    height_mm: Pos


class Sweep(Strict):
    theta_steps: Annotated[int, Field(ge=2, le=200)] = 8
    psi_steps: Annotated[int, Field(ge=4, le=720)] = 24


class CrossGear(Strict):
    """An ABENICS-style cross spherical gear (ring-involute teeth both ways) on a spherical pitch."""

    teeth: Annotated[int, Field(ge=8, le=400)]
    module_mm: Pos
    pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    backlash_per_gear_mm: NonNeg = 0.05

    @field_validator("teeth")
    @classmethod
    def _multiple_of_4(cls, v):
        if v % 4:
            raise ValueError("must be a multiple of 4 so the section through both ring axes is the 2-D profile")
        return v


class Wrist(Strict):
    """A spherical (nominal_ratio 1) or quasi-ellipsoidal wrist gear pair."""

    nominal_ratio: Annotated[float, Field(gt=0.2, lt=5)]
    centre_distance_mm: Pos
    longitudinal_pitch_mm: Pos
    ring_teeth: Annotated[list[Annotated[int, Field(ge=1, le=200)]], Field(min_length=2)] = [1, 6, 12]
    tooth: Tooth
    clearance_radial_mm: float
    max_bend_deg: Annotated[float, Field(gt=0, lt=180)]
    sweep: Sweep = Sweep()
    shaft_diameter_mm: Pos
    press_fit_clearance_diametral_mm: float = 0.05
    base_height_mm: Pos = 8.0
    chord_tolerance_mm: Annotated[float, Field(ge=1e-3, le=0.5)] = 0.02
    cross_gear: CrossGear | None = None


class WristDesign(Strict):
    kind: Literal["wrist"]
    name: Annotated[str, Field(pattern=r"^[A-Za-z0-9_.-]+$")]
    description: str = ""
    printer: str
    wrist: Wrist
    material: Material


class BennettLinkage(Strict):
    """Bennett 1 (S-B2-D2-B3) and the scales of the four similar Bennetts (van der Wijk 2020)."""

    a_mm: Pos = Field(description="S–B2 and D2–B3")
    b_mm: Pos = Field(description="B2–D2 and B3–S")
    alpha_deg: Annotated[float, Field(gt=0, lt=180)]
    beta_deg: Annotated[float, Field(gt=0, lt=180)] | None = None
    scales: Annotated[list[Pos], Field(min_length=4, max_length=4)] = [1.0, 0.8, 0.6, 0.7]
    home_angle_deg: Annotated[float, Field(gt=0, lt=180)] = 77.0
    workspace_deg: Annotated[list[Annotated[float, Field(gt=0, lt=180)]], Field(min_length=2, max_length=2)]

    @model_validator(mode="after")
    def _ordered(self):
        lo, hi = self.workspace_deg
        if not lo < hi:
            raise ValueError("workspace_deg must be [low, high] with low < high")
        if not lo <= self.home_angle_deg <= hi:
            raise ValueError("home_angle_deg must lie inside workspace_deg")
        return self


class BennettLayout(Strict):
    """A fixed stack layout (what `partgen build` prints after an automatic one)."""

    layers: dict[Annotated[int, Field(ge=1, le=12)], Annotated[int, Field(ge=1, le=20)]]
    shifts_mm: dict[str, float] = {}


class BennettParts(Strict):
    bar_diameter_mm: Pos
    boss_diameter_mm: Pos
    boss_length_mm: Pos
    axial_gap_mm: Pos
    layout: Literal["auto"] | BennettLayout = "auto"
    layers: Annotated[int, Field(ge=3, le=12)] = 6
    offset_step_mm: Pos = 5.0
    offset_max_mm: NonNeg = 40.0
    segments: Annotated[int, Field(ge=12, le=256)] = 40


class Pin(Strict):
    kind: str = "steel dowel pin"
    diameter_mm: Pos
    clearance_diametral_mm: NonNeg
    density_g_cm3: Pos = 7.85


class Counterweights(Strict):
    """Pockets on three links, filled with ``fill`` to the mass the balance conditions ask."""

    links: Annotated[list[Annotated[int, Field(ge=1, le=12)]], Field(min_length=3, max_length=3)]
    distance_mm: Annotated[list[float], Field(min_length=3, max_length=3)]
    outer_diameter_mm: Pos
    height_mm: Pos
    wall_mm: Pos
    fill: Material


class PrintCfg(Strict):
    wall_mm: Pos = 1.2
    skin_mm: Pos = 1.0
    infill_percent: Annotated[float, Field(ge=0, le=100)] = 20.0


class BennettBase(Strict):
    height_mm: Pos = 80.0


class BennettChecks(Strict):
    balance_tolerance_mm: Pos = 0.1
    grid: Annotated[list[Annotated[int, Field(ge=2, le=400)]], Field(min_length=2, max_length=2)] = [24, 21]
    infill_error_percent_points: NonNeg = 5.0
    mass_scale: dict[Annotated[int, Field(ge=1, le=12)], Pos] = Field(
        default={}, description="what-if: a link's mass times this, counterweights not re-sized (seeded faults)")


class BennettDesign(Strict):
    kind: Literal["bennett_butterfly"]
    name: Annotated[str, Field(pattern=r"^[A-Za-z0-9_.-]+$")]
    description: str = ""
    printer: str
    linkage: BennettLinkage
    parts: BennettParts
    pin: Pin
    counterweights: Counterweights
    print: PrintCfg = PrintCfg()
    base: BennettBase = BennettBase()
    checks: BennettChecks = BennettChecks()
    material: Material
