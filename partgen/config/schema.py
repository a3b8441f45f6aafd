"""The YAML schema of a design and a printer profile (pydantic v2, strict, unknown keys forbidden).

Every length key ends in ``_mm``, every angle in ``_deg``; clearances say ``radial`` or
``diametral``. Defaults are documented in README's config reference.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, field_validator, model_validator

__all__ = ["Printer", "Design", "WristDesign", "BennettDesign"]

MAX = 10_000.0  # the largest magnitude any number may have (10 m as a length): larger is a typo, not a design
Pos = Annotated[float, Field(gt=0, le=MAX)]
NonNeg = Annotated[float, Field(ge=0, le=MAX)]
Finite = Annotated[float, Field(ge=-MAX, le=MAX)]
Length = Annotated[float, Field(ge=0.01, le=MAX)]  # mm: a feature finer than 0.01 mm is no print


def _zero_or_at_least(v: float) -> float:
    if 0 < v < 0.001:
        raise ValueError(f"must be 0 or at least 0.001 mm (a gap under a micrometre is no gap), got {v!r}")
    return v


Gap = Annotated[float, Field(ge=0, le=MAX), AfterValidator(_zero_or_at_least)]  # mm


def _zero_or_not_tiny(v: float) -> float:
    if 0 < abs(v) < 1e-9:
        raise ValueError("a term under 1e-9 curve units is nothing at any print scale: write 0 to leave it out")
    return v


Coeff = Annotated[float, Field(ge=-MAX, le=MAX), AfterValidator(_zero_or_not_tiny)]  # a curve term, curve units
Ratio = Annotated[float, Field(ge=0.01, le=100)]
Density = Annotated[float, Field(gt=0, le=30)]  # g/cm³ (osmium is 22.6)
Teeth = Annotated[int, Field(ge=4, le=1000)]
# a design's name is the default output folder: a plain file name, never a path or an option
Name = Annotated[str, Field(pattern=r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$", max_length=100)]
Text = Annotated[str, Field(max_length=10_000)]


class Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False)


class Printer(Strict):
    name: Annotated[str, Field(min_length=1, max_length=200)]
    build_envelope_mm: Annotated[list[Length], Field(min_length=3, max_length=3)]
    resolution_mm: Length
    min_hole_diameter_mm: Length = Field(description="smallest reliable revolute-joint hole")
    min_gear_diameter_mm: Length = Field(description="smallest reliable gear (reference pitch diameter)")
    min_link_length_mm: Length
    min_wall_mm: Length
    min_hole_to_size_diameter_mm: Length = Field(3.0, description="smallest hole held to size (press-fit D, pen bore)")


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


class Curve(Strict):
    polar: Polar | None = None
    cartesian: Cartesian | None = None
    scale_mm_per_unit: Annotated[float, Field(ge=0.01, le=MAX)]
    drop_links: Annotated[list[Annotated[str, Field(max_length=40)]], Field(max_length=200)] = []

    @model_validator(mode="after")
    def _one_form(self):
        if (self.polar is None) == (self.cartesian is None):
            raise ValueError("give exactly one of 'polar' or 'cartesian'")
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
    module_mm: Length
    pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    addendum_coeff: Annotated[float, Field(gt=0, le=2)] = 1.0
    dedendum_coeff: Annotated[float, Field(gt=0, le=2.5)] = 1.25
    cutter_tip_radius_coeff: Annotated[float, Field(ge=0, le=0.6)] = 0.38
    profile_shift: Literal["auto"] | Annotated[float, Field(ge=-1, le=1.5)] = "auto"
    backlash_per_gear_mm: Gap = 0.05
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
    running_clearance_diametral_mm: Finite | None = None
    press_fit_clearance_radial_mm: Finite | None = None
    press_fit_clearance_diametral_mm: Finite | None = None
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


class Material(Strict):
    name: Annotated[str, Field(min_length=1, max_length=200)]
    density_g_cm3: Density


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


class Tooth(Strict):
    shape: Literal["dome"] = "dome"
    radius_mm: Length
    height_mm: Length


MAX_SWEEP_POSES = 2048  # each pose unions every dome into the socket cut: more takes hours


class Sweep(Strict):
    theta_steps: Annotated[int, Field(ge=2, le=200)] = 8
    psi_steps: Annotated[int, Field(ge=4, le=720)] = 24

    @model_validator(mode="after")
    def _budget(self):
        if self.theta_steps * self.psi_steps > MAX_SWEEP_POSES:
            raise ValueError(f"{self.theta_steps} × {self.psi_steps} = {self.theta_steps * self.psi_steps} poses: at most "
                             f"{MAX_SWEEP_POSES} (the default 8 × 24 cuts sockets within 0.01 mm)")
        return self


class CrossGear(Strict):
    """An ABENICS-style cross spherical gear (ring-involute teeth both ways) on a spherical pitch."""

    teeth: Annotated[int, Field(ge=8, le=400)]
    module_mm: Length
    pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    backlash_per_gear_mm: Gap = 0.05

    @field_validator("teeth")
    @classmethod
    def _multiple_of_4(cls, v):
        if v % 4:
            raise ValueError("must be a multiple of 4 so the section through both ring axes is the 2-D profile")
        return v


class Wrist(Strict):
    """A spherical (nominal_ratio 1) or quasi-ellipsoidal wrist gear pair."""

    nominal_ratio: Annotated[float, Field(gt=0.2, lt=5)]
    centre_distance_mm: Length
    longitudinal_pitch_mm: Length
    ring_teeth: Annotated[list[Annotated[int, Field(ge=1, le=200)]], Field(min_length=2, max_length=20)] = [1, 6, 12]
    tooth: Tooth
    clearance_radial_mm: Finite
    max_bend_deg: Annotated[float, Field(gt=0, lt=180)]
    sweep: Sweep = Sweep()
    shaft_diameter_mm: Length
    press_fit_clearance_diametral_mm: Finite = 0.05
    base_height_mm: Length = 8.0
    chord_tolerance_mm: Annotated[float, Field(ge=1e-3, le=0.5)] = 0.02
    cross_gear: CrossGear | None = None


class WristDesign(Strict):
    kind: Literal["wrist"]
    name: Name
    description: Text = ""
    printer: Annotated[str, Field(min_length=1, max_length=500)]
    wrist: Wrist
    material: Material


class BennettLinkage(Strict):
    """Bennett 1 (S-B2-D2-B3) and the scales of the four similar Bennetts (van der Wijk 2020)."""

    a_mm: Length = Field(description="S–B2 and D2–B3")
    b_mm: Length = Field(description="B2–D2 and B3–S")
    alpha_deg: Annotated[float, Field(gt=0, lt=180)]
    beta_deg: Annotated[float, Field(gt=0, lt=180)] | None = None
    scales: Annotated[list[Ratio], Field(min_length=4, max_length=4)] = [1.0, 0.8, 0.6, 0.7]
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
    shifts_mm: dict[Annotated[str, Field(max_length=40)], Finite] = {}


class BennettParts(Strict):
    bar_diameter_mm: Length
    boss_diameter_mm: Length
    boss_length_mm: Length
    axial_gap_mm: Length
    layout: Literal["auto"] | BennettLayout = "auto"
    layers: Annotated[int, Field(ge=3, le=12)] = 6
    offset_step_mm: Length = 5.0
    offset_max_mm: Gap = 40.0
    segments: Annotated[int, Field(ge=12, le=256)] = 40


# ISO 2338 / ISO 8734 parallel (dowel) pins: the standards' length series within the Ø10 mm range
# (ISO 2338: 18–95 mm, ISO 8734: 22–100 mm); shorten the list to what a supplier stocks
DOWEL_LENGTHS_10_MM = [18.0, 20.0, 22.0, 24.0, 26.0, 28.0, 30.0, 32.0, 35.0, 40.0, 45.0, 50.0, 55.0, 60.0, 65.0, 70.0,
                       75.0, 80.0, 85.0, 90.0, 95.0, 100.0]


class Pin(Strict):
    kind: Annotated[str, Field(max_length=200)] = "steel dowel pin (ISO 2338/8734)"
    diameter_mm: Length
    clearance_diametral_mm: Gap
    density_g_cm3: Density = 7.85
    stock_lengths_mm: Annotated[list[Length], Field(min_length=1, max_length=200)] = Field(
        default=DOWEL_LENGTHS_10_MM, description="lengths the pins can be bought in (the stock list for Ø10)")


class Slugs(Strict):
    """Stock steel slugs a counterweight pocket holds, stacked end to end in a bore that fits them."""

    kind: Annotated[str, Field(max_length=200)] = "steel dowel pin (ISO 8734)"
    diameter_mm: Length = 20.0
    lengths_mm: Annotated[list[Length], Field(min_length=1, max_length=200)] = [20.0, 25.0, 30.0, 35.0, 40.0, 45.0,
                                                                                 50.0, 60.0]
    density_g_cm3: Density = 7.85


class Counterweights(Strict):
    """Pockets on three links, each holding a whole number of stock ``slugs`` with ``binder``
    filling the rest of the pocket to the brim."""

    links: Annotated[list[Annotated[int, Field(ge=1, le=12)]], Field(min_length=3, max_length=3)]
    distance_mm: Annotated[list[Finite], Field(min_length=3, max_length=3)]
    wall_mm: Length
    clearance_diametral_mm: Gap = 0.3
    slugs: Slugs = Slugs()
    binder: Material = Material(name="epoxy", density_g_cm3=1.15)


class PrintCfg(Strict):
    wall_mm: Length = 1.2
    skin_mm: Length = 1.0
    infill_percent: Annotated[float, Field(ge=0, le=100)] = 20.0
    overhang_angle_deg: Annotated[float, Field(gt=0, lt=90)] = 45.0
    min_bed_contact_mm2: Annotated[float, Field(gt=0, le=1e6)] = 100.0


class BennettBase(Strict):
    height_mm: Length = 80.0
    foot_diameter_mm: Length = 100.0
    foot_thickness_mm: Length = 5.0
    min_tip_angle_deg: Annotated[float, Field(gt=0, lt=90)] = 10.0


class BennettChecks(Strict):
    balance_tolerance_mm: Length = 0.1
    grid: Annotated[list[Annotated[int, Field(ge=2, le=400)]], Field(min_length=2, max_length=2)] = [24, 21]
    infill_error_percent_points: NonNeg = 5.0
    mass_scale: dict[Annotated[int, Field(ge=1, le=12)], Ratio] = Field(
        default={}, description="what-if: a link's mass times this, counterweights not re-sized (seeded faults)")


class BennettDesign(Strict):
    kind: Literal["bennett_butterfly"]
    name: Name
    description: Text = ""
    printer: Annotated[str, Field(min_length=1, max_length=500)]
    linkage: BennettLinkage
    parts: BennettParts
    pin: Pin
    counterweights: Counterweights
    print: PrintCfg = PrintCfg()
    base: BennettBase = BennettBase()
    checks: BennettChecks = BennettChecks()
    material: Material
