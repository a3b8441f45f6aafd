"""The design YAML of a gear chain (``kind: gear_chain``): links or a curve, teeth, gears, plates, joints."""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import AfterValidator, Field, model_validator

from ...config.schema import DesignHeader, MotionChecks, ToleranceTarget
from ...config.schema import (MAX, Coeff, Finite, Gap, Length, Ratio, Strict,
                              Teeth)

__all__ = ["Design"]


def _has_default(m: dict) -> dict:
    if "default" not in m:
        raise ValueError("a mapping of play per gear or joint needs 'default' (the value of every one not named)")
    return m


def _defaults(data, *keys: str):
    """A play mapping without ``default`` named on its key (before the union's alternatives speak)."""
    if isinstance(data, dict):
        for k in keys:
            if isinstance(data.get(k), dict) and "default" not in data[k]:
                raise ValueError(f"[{k}.default] required key is missing: a mapping of play per gear or joint "
                                 "gives the value of every one it does not name")
    return data


# a play per gear or joint: {default: mm, <gear or part name>: mm, …} (what auto's allocation pins)
PerUnit = Annotated[dict[Annotated[str, Field(min_length=1, max_length=40)], Gap],
                    Field(min_length=1, max_length=512), AfterValidator(_has_default)]


class Polar(Strict):
    """ρ(θ) = constant + Σ sin[k]·sin kθ + cos[k]·cos kθ (curve units)."""

    constant: Coeff = 0.0
    """Constant term of ρ(θ), in curve units (× curve.scale_mm_per_unit at print size)."""
    sin: dict[Annotated[int, Field(ge=1, le=64)], Coeff] = {}
    """Coefficients of sin kθ, keyed by k (1–64), curve units."""
    cos: dict[Annotated[int, Field(ge=1, le=64)], Coeff] = {}
    """Coefficients of cos kθ, keyed by k (1–64), curve units."""


class Cartesian(Strict):
    """x = Σ a_k cos kθ + b_k sin kθ, y = Σ c_k cos kθ + d_k sin kθ; lists indexed by k from 0."""

    a: Annotated[list[Coeff], Field(min_length=1, max_length=65)]
    """x's coefficients of cos kθ, k = 0, 1, …, curve units."""
    b: Annotated[list[Coeff], Field(min_length=1, max_length=65)]
    """x's coefficients of sin kθ, k = 0, 1, …, curve units."""
    c: Annotated[list[Coeff], Field(min_length=1, max_length=65)]
    """y's coefficients of cos kθ, k = 0, 1, …, curve units."""
    d: Annotated[list[Coeff], Field(min_length=1, max_length=65)]
    """y's coefficients of sin kθ, k = 0, 1, …, curve units."""

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
    """The curve as a polar Fourier series, ρ(θ)·(cos θ, sin θ)."""
    cartesian: Cartesian | None = None
    """The curve as a Cartesian Fourier series x(θ), y(θ)."""
    points: FileName | Annotated[list[Point], Field(max_length=100_000)] | None = None
    """A drawing: a CSV file (header x_mm,y_mm, in the design's folder) or an inline list of [x, y], in mm at print
    size, in drawing order (at least 16 points)."""
    svg: FileName | None = None
    """A drawing: an SVG file in the design's folder; its first closed path (or svg_path_id's), y up."""
    svg_path_id: Annotated[str, Field(min_length=1, max_length=200)] | None = None
    """The id of the SVG path to draw; none: the first closed path."""
    svg_mm_per_unit: Annotated[float, Field(gt=0, le=MAX)] | None = None
    """Millimetres per SVG user unit; none: from the document's width and height over its viewBox."""
    parametrisation: Literal["samples", "arc_length"] | None = None
    """How the drawing is timed against the crank: samples (point i at crank angle 2πi/n, as given; the default for
    points) or arc_length (a steady pace along the curve; the default for svg)."""
    close: bool = False
    """Join an open drawing's ends with a straight line (else ends farther apart than the largest step are an error)."""
    max_deviation_mm: Annotated[float, Field(ge=0.001, le=MAX)] = 1.0
    """Budget for a drawing: the largest Hausdorff distance from the chain's path to the drawing; partgen keeps the
    fewest links that meet it."""
    max_links: Annotated[int, Field(ge=1, le=64)] = 16
    """Most links the chain drawn from a drawing may have."""
    scale: Ratio | Literal["auto"] = 1.0
    """Enlargement of a drawing before its links are chosen; auto: the smallest enlargement (from a fixed ladder,
    smallest first) with which the kit builds."""
    scale_mm_per_unit: Annotated[float, Field(ge=0.01, le=MAX)] | None = None
    """Print scale of Fourier coefficients: millimetres per curve unit."""
    drop_links: Annotated[list[Annotated[str, Field(max_length=40)]], Field(max_length=200)] = []
    """Fourier links left out, by name (L_k turns at speed k, M_k at −k: [L2, L10, M8])."""

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
    """The target curve as a polar Fourier series."""
    cartesian: Cartesian | None = None
    """The target curve as a Cartesian Fourier series."""
    scale_mm_per_unit: Annotated[float, Field(ge=0.01, le=MAX)]
    """Millimetres per curve unit of the target's coefficients."""

    @model_validator(mode="after")
    def _one_form(self):
        if (self.polar is None) == (self.cartesian is None):
            raise ValueError("give exactly one of 'polar' or 'cartesian'")
        return self


class LinkRow(Strict):
    name: Annotated[str, Field(min_length=1, max_length=40)]
    """The link's name (L_k for speed k, M_k for −k by convention); messages and parts use it."""
    speed: Annotated[int, Field(ge=-1000, le=1000)]
    """The link's angular speed in the world, in turns per crank turn (a non-zero integer; negative: turns
    backwards)."""
    length_mm: Length
    """The link's length, joint to joint."""
    initial_angle_deg: Finite
    """The link's angle in the world at crank angle 0."""

    @model_validator(mode="after")
    def _speed(self):
        if self.speed == 0:
            raise ValueError("speed must be a non-zero integer (0 is the fixed ground offset)")
        return self


class StageTeeth(Strict):
    """Teeth of link j's stage: D_j, idler M_j, G_{j+1}; ``idler_mm`` places the idler by hand (link
    frame: proximal joint at 0, distal at (S, 0)) instead of by circle intersection."""

    D: Teeth
    """Teeth of D_j, fixed to link j − 1's post (the base's ground post for j = 1)."""
    M: Teeth
    """Teeth of the idler M_j, turning on link j's pin."""
    G: Teeth
    """Teeth of G_{j+1}, fixed under link j + 1's plate."""
    idler_mm: Annotated[list[Finite], Field(min_length=2, max_length=2)] | None = None
    """Place idler M_j by hand: its centre [x, y] in link j's frame (proximal joint at 0, distal at (S, 0)); none:
    where its circles of mesh with D_j and G_{j+1} cross. check verifies it."""


class Gears(Strict):
    module_mm: Length | Literal["auto"]
    """Module shared by all gears (reference pitch diameter / teeth); auto: the largest on a 0.05 mm grid from 0.3 to
    5 mm with which the chain builds and meets the printer's gear rules (the kit's design.yaml pins it)."""
    pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    """Pressure angle of the basic rack; 20 is standard."""
    addendum_coeff: Annotated[float, Field(gt=0, le=2)] = 1.0
    """Tooth height above the reference circle, × module."""
    dedendum_coeff: Annotated[float, Field(gt=0, le=2.5)] = 1.25
    """Tooth depth below the reference circle, × module."""
    cutter_tip_radius_coeff: Annotated[float, Field(ge=0, le=0.6)] = 0.38
    """Tip fillet radius of the rack that cuts the teeth, × module (0.38: ISO 53); it shapes the root fillet."""
    profile_shift: Literal["auto"] | Annotated[float, Field(ge=-1, le=1.5)] = "auto"
    """Profile shift coefficient (× module) of every gear; auto: the smallest shift that avoids undercut (0 at and
    above the undercut limit)."""
    backlash_per_gear_mm: Gap | Literal["auto"] | PerUnit = 0.05
    """Per gear: each tooth is thinned by this arc length at its reference pitch circle, so a mesh at its
    zero-backlash centre distance has the sum of both as circumferential backlash; auto: the least that meets
    tolerance.max_jam_probability on the printer (allocated per gear where that saves play); a mapping
    {default: mm, G5: mm, M4: mm, …}: each named gear (drive, G1, D_j, M_j, G_j) its own, the others the default."""
    face_width_mm: Length
    """Gear thickness (a gear layer's height)."""
    chord_tolerance_mm: Annotated[float, Field(ge=1e-4, le=0.1)] = 0.001
    """Largest chord sagitta (deviation of the faceted outline from the exact curve) on flanks, fillets and tips;
    smaller is smoother and heavier STLs."""
    hub_wall_mm: Length = 2.5
    """Least material between a gear's bore and its root circle."""
    tip_gap_mm: Gap = 1.5
    """Least gap between the tip circles of D_j and G_{j+1} on one link (Eq 12 with margin): what teeth: auto chooses
    by, and what build warns about."""
    idler_reach_mm: Gap = 1.0
    """Least margin by which the idler's two centre distances exceed the link's length (Eq 13 with margin; 0: D, M
    and G in one line): what teeth: auto chooses by, and what build warns about."""

    @model_validator(mode="before")
    @classmethod
    def _default_given(cls, data):
        return _defaults(data, "backlash_per_gear_mm")


class Drive(Strict):
    teeth: Teeth
    """Teeth of G1 and of the drive gear meshing with it (the same, so one crank turn is one cycle)."""
    angle_deg: Finite = -90.0
    """Where the drive gear sits round the ground pivot: the direction from G1's centre to its own."""


class Plates(Strict):
    thickness_mm: Length
    """Thickness of every link plate."""
    boss_wall_mm: Length = 4.0
    """Material round holes, posts and pins (the bosses of plates, base and crank)."""


class Joints(Strict):
    axle_diameter_mm: Length
    """Diameter of every post, pin and axle."""
    running_clearance_radial_mm: Finite | None = None
    """Radial running clearance of the revolute joints, bore minus axle on each side (give this or
    running_clearance_diametral_mm)."""
    running_clearance_diametral_mm: Finite | Literal["printer", "auto"] | PerUnit | None = None
    """Diametral running clearance of the revolute joints, bore minus axle; printer: the printer profile's measured
    running fit; auto: the least that (with the backlash) meets tolerance.max_jam_probability on the printer
    (allocated per joint where that saves play); a mapping {default: mm, G5: mm, M4: mm, …}: each named joint (by
    the part that turns in it: G1, drive_axle, M_j, G_j, T_j) its own, the others the default (give this or
    running_clearance_radial_mm)."""
    press_fit_clearance_radial_mm: Finite | None = None
    """Radial clearance of the D-fits (parts pressed on a D-flat), hole minus pin on each side; negative:
    interference (give this or press_fit_clearance_diametral_mm)."""
    press_fit_clearance_diametral_mm: Finite | Literal["printer"] | None = None
    """Diametral clearance of the D-fits, hole minus pin (negative: interference); printer: the printer profile's
    measured press fit (give this or press_fit_clearance_radial_mm)."""
    axial_gap_mm: Length = 0.5
    """Gap between parts that turn against each other along an axle (the thrust rings' height)."""

    @model_validator(mode="before")
    @classmethod
    def _default_given(cls, data):
        return _defaults(data, "running_clearance_diametral_mm")

    @model_validator(mode="after")
    def _one_each(self):
        for kind in ("running", "press_fit"):
            r, d = getattr(self, f"{kind}_clearance_radial_mm"), getattr(self, f"{kind}_clearance_diametral_mm")
            if (r is None) == (d is None):
                raise ValueError(f"give exactly one of {kind}_clearance_radial_mm or {kind}_clearance_diametral_mm")
        return self

    @property
    def running_diametral(self) -> float:
        """The running clearance (diametral) of every joint not named in a mapping."""
        r = self.running_clearance_radial_mm
        d = self.running_clearance_diametral_mm
        return 2 * r if r is not None else (d["default"] if isinstance(d, dict) else d)

    @property
    def press_fit_diametral(self) -> float:
        r = self.press_fit_clearance_radial_mm
        return 2 * r if r is not None else self.press_fit_clearance_diametral_mm


class Base(Strict):
    thickness_mm: Length = 6.0
    """Thickness of the base plate."""
    leg_height_mm: Length = 45.0
    """Height of the four press-fit legs under the base (room for the crank)."""
    crank_radius_mm: Length = 35.0
    """Crank arm: the handle's distance from the drive axle."""


class Pen(Strict):
    diameter_mm: Length = 10.0
    """Diameter of the pen the holder takes (its bore is 0.2 mm larger, diametral)."""
    holder_height_mm: Length = 20.0
    """Height of the pen holder above the last plate (its blind bore plus a 2 mm floor)."""


class Belts(Strict):
    """Timing belts instead of idler gears: each D_j drives G_{j+1} through a stock closed belt."""

    profile: Annotated[str, Field(max_length=40)] = "GT2"
    """The belt profile's name (bill and manifest; the numbers below define it)."""
    pitch_mm: Length = 2.0
    """Belt pitch, tooth to tooth along the pitch line."""
    pitch_line_offset_mm: Gap = 0.254
    """Pulley pitch radius minus its outside radius (the pitch line runs inside the belt's back)."""
    groove_depth_mm: Length = 0.75
    """Depth of a pulley's tooth space below its outside radius."""
    groove_radius_mm: Length = 0.555
    """Radius of the arc forming a pulley's tooth space."""
    back_height_mm: Length = 0.63
    """Height from the belt's pitch line to its back (where a backside tensioner rides)."""
    width_mm: Length = 6.0
    """Belt width."""
    stock_teeth: Annotated[list[Annotated[int, Field(ge=20, le=5000)]], Field(min_length=1, max_length=1000)]
    """Closed belt lengths on offer, in teeth: each stage takes the shortest long enough."""
    flange_height_mm: Length = 1.5
    """How far a pulley's flanges stand out beyond its outside radius."""
    flange_thickness_mm: Length = 1.0
    """Thickness of each pulley flange."""
    tensioner_radius_mm: Length = 7.0
    """Radius of a backside tensioner roller."""
    tensioner_gap_mm: Gap = 0.5
    """Least gap between a tensioner's flanges and a pulley's, and between two pulleys' flanges."""

    @model_validator(mode="after")
    def _pitch_line_in_the_back(self):
        if self.pitch_line_offset_mm >= self.back_height_mm:
            raise ValueError(f"pitch_line_offset_mm ({self.pitch_line_offset_mm:g}) must be less than back_height_mm "
                             f"({self.back_height_mm:g}): the pitch line runs in the belt's tension cords, inside its back")
        return self


class Checks(MotionChecks):
    """What `partgen check` holds a kit to."""

    samples: Annotated[int, Field(ge=4, le=10_000)] = 360
    """Crank angles checked over one cycle (--samples overrides it)."""


class Design(DesignHeader):
    AUTO_PLAY: ClassVar[dict] = {"gears.backlash_per_gear_mm": "backlash",
                                 "joints.running_clearance_diametral_mm": "running"}  # mechanisms.autoplay
    PER_UNIT_PLAY: ClassVar[frozenset] = frozenset(AUTO_PLAY)  # the keys that take {default: mm, <name>: mm}
    kind: Literal["gear_chain"]
    """The mechanism this file designs: `gear_chain` selects these keys."""
    curve: Curve | None = None
    """The curve the chain draws: Fourier coefficients or a drawing (give curve or links)."""
    links: Annotated[list[LinkRow], Field(max_length=128)] | None = None
    """Instead of curve: the design table, link B1 (at the ground pivot) outward."""
    target: Target | None = None
    """With links: the curve the table is meant to draw, which trace measures the kit against."""
    offset_mm: Annotated[list[Finite], Field(min_length=2, max_length=2)] = [0.0, 0.0]
    """With links: the curve's constant term C₀ [x, y] (the ground offset), added to the links' sum."""
    teeth: Literal["auto"] | Annotated[list[StageTeeth], Field(max_length=128)]
    """auto: whole teeth meeting Eq 11 exactly and Eq 12–13 with gears.tip_gap_mm and gears.idler_reach_mm, the
    smallest largest gear first; or per link j = 1 … n − 1 the teeth {D, M, G} of D_j, idler M_j and G_{j+1}."""
    gears: Gears
    """The tooth system every gear shares, and the gears' play, width and hubs."""
    drive: Drive
    """The drive gear and where it sits."""
    plates: Plates
    """The link plates."""
    joints: Joints
    """The axles and the fits of the joints."""
    base: Base = Base()
    """The base, its legs and the crank."""
    pen: Pen = Pen()
    """The pen and its holder on the last link."""
    checks: Checks = Checks()
    """What partgen check holds the kit to."""
    tolerance: ToleranceTarget = ToleranceTarget()
    """The jam probability that auto play (gears.backlash_per_gear_mm, joints.running_clearance_diametral_mm) is
    chosen for."""
    belts: Belts | None = None
    """Timing belts instead of idler gears (needs teeth: auto); none: idler gears."""

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
