"""The design YAML of a balanced Bennett butterfly (``kind: bennett_butterfly``)."""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import Field, model_validator

from ...config.schema import (DesignHeader, Density, Finite, Gap, Length, Material, NonNeg, Ratio, Strict,
                               ToleranceTarget)

__all__ = ["BennettDesign"]


class BennettLinkage(Strict):
    """Bennett 1 (S-B2-D2-B3) and the scales of the four similar Bennetts (van der Wijk 2020)."""

    a_mm: Length = Field(description="S–B2 and D2–B3")
    b_mm: Length = Field(description="B2–D2 and B3–S")
    alpha_deg: Annotated[float, Field(gt=0, lt=180)]
    """Twist α between the joint axes at either end of an a-link (S–B2, D2–B3), 1 to 179."""
    beta_deg: Annotated[float, Field(gt=0, lt=180)] | None = None
    """Twist β of the b-links (B2–D2, B3–S); none: it follows from the Bennett condition sin β = (b / a) sin α;
    given, it must meet that condition."""
    scales: Annotated[list[Ratio], Field(min_length=4, max_length=4)] = [1.0, 0.8, 0.6, 0.7]
    """Scales of the four similar Bennett linkages sharing S; only their ratios to the first count (a_mm and b_mm are
    Bennett 1's)."""
    home_angle_deg: Annotated[float, Field(gt=0, lt=180)] = 77.0
    """Angle at S between links 1 and 4 in the home pose (the kit is assembled and drawn in it, and check measures how
    far it moves freely from it); inside workspace_deg."""
    workspace_deg: Annotated[list[Annotated[float, Field(gt=0, lt=180)]], Field(min_length=2, max_length=2)]
    """[low, high] range of the angle between links 1 and 4 the kit must move through freely (check and the layout
    search cover it)."""

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
    """Each link's layer (link number → layer): its bosses sit layer × (boss_length_mm + axial_gap_mm) along every
    one of its joint axes; links sharing a pin take different layers."""
    shifts_mm: dict[Annotated[str, Field(max_length=40)], Finite] = {}
    """Each joint's stack shift along its axis (joint name → mm); a joint not named is not shifted."""


class BennettParts(Strict):
    bar_diameter_mm: Length
    """Diameter of the round bars joining a link's bosses (at most boss_length_mm)."""
    boss_diameter_mm: Length
    """Outer diameter of a boss, the round hub on each joint axis the pin runs through."""
    boss_length_mm: Length
    """Length of a boss along its joint axis."""
    axial_gap_mm: Length
    """Gap between two bosses stacked on one pin."""
    layout: Literal["auto"] | BennettLayout = "auto"
    """auto: a local search chooses each link's layer and each joint's stack shift (build pins its choice in the
    kit's design.yaml); or a fixed layout as build writes it."""
    layers: Annotated[int, Field(ge=3, le=12)] = 6
    """Layers the automatic layout may put a link on: 1 to layers − 1 (the base is layer 0)."""
    offset_step_mm: Length = 5.0
    """Coarsest step of the stack shifts the automatic layout tries (finer steps follow near the best)."""
    offset_max_mm: Gap = 40.0
    """Largest stack shift the automatic layout tries, either way along a joint's axis."""
    segments: Annotated[int, Field(ge=12, le=256)] = 40
    """Facets round every cylinder (bosses, bars, pins, base, pockets): more is rounder and heavier STLs."""


# ISO 2338 / ISO 8734 parallel (dowel) pins: the standards' length series within the Ø10 mm range
# (ISO 2338: 18–95 mm, ISO 8734: 22–100 mm); shorten the list to what a supplier stocks
DOWEL_LENGTHS_10_MM = [18.0, 20.0, 22.0, 24.0, 26.0, 28.0, 30.0, 32.0, 35.0, 40.0, 45.0, 50.0, 55.0, 60.0, 65.0, 70.0,
                       75.0, 80.0, 85.0, 90.0, 95.0, 100.0]


class Pin(Strict):
    kind: Annotated[str, Field(max_length=200)] = "steel dowel pin (ISO 2338/8734)"
    """What the bill calls the bought pins."""
    diameter_mm: Length
    """Diameter of the steel pins every joint runs on."""
    clearance_diametral_mm: Gap | Literal["printer", "auto"]
    """Diametral running clearance, a bore minus its pin (bore = diameter + clearance); printer: the printer
    profile's measured running fit (fits.running_clearance_diametral_mm); auto: the least (on a 0.01 mm grid,
    diametral) with which a print jams with probability at most tolerance.max_jam_probability on the design's
    printer: the pins in every bore and the four Bennett loops closing on their joints' play (docs/tolerance.md);
    build prints the choice and pins it in the kit's design.yaml."""
    density_g_cm3: Density = 7.85
    """Density of the pins, for their mass in the balance and the bill."""
    stock_lengths_mm: Annotated[list[Length], Field(min_length=1, max_length=200)] = Field(
        default=DOWEL_LENGTHS_10_MM, description="lengths the pins can be bought in (the stock list for Ø10)")


class Slugs(Strict):
    """Stock steel slugs a counterweight pocket holds, stacked end to end in a bore that fits them."""

    kind: Annotated[str, Field(max_length=200)] = "steel dowel pin (ISO 8734)"
    """What the bill calls the slugs."""
    diameter_mm: Length = 20.0
    """Diameter of the slugs (the pocket's bore is this plus the counterweights' clearance)."""
    lengths_mm: Annotated[list[Length], Field(min_length=1, max_length=200)] = [20.0, 25.0, 30.0, 35.0, 40.0, 45.0,
                                                                                 50.0, 60.0]
    """Stock lengths the slugs can be bought in: each pocket holds a whole number of one of them."""
    density_g_cm3: Density = 7.85
    """Density of the slugs, for the balance."""


class Counterweights(Strict):
    """Pockets on three links, each holding a whole number of stock ``slugs`` with ``binder``
    filling the rest of the pocket to the brim."""

    links: Annotated[list[Annotated[int, Field(ge=1, le=12)]], Field(min_length=3, max_length=3)]
    """The three links (numbers 1–12, all different) that carry a counterweight pocket."""
    distance_mm: Annotated[list[Finite], Field(min_length=3, max_length=3)]
    """Each pocket's starting point: a signed distance along its link from the link's reference joint (negative:
    beyond it); the balance then moves the pockets."""
    wall_mm: Length
    """Wall of the cup round and under a pocket."""
    clearance_diametral_mm: Gap = 0.3
    """Diametral clearance of a pocket's bore over its slugs (the binder fills it)."""
    slugs: Slugs = Slugs()
    """The stock steel slugs a pocket holds, stacked end to end."""
    binder: Material = Material(name="epoxy", density_g_cm3=1.15)
    """What fills the rest of each pocket (name and density: its mass counts in the balance)."""


class PrintCfg(Strict):
    wall_mm: Length = 1.2
    """Solid wall (perimeters) thickness of the mass model; set the slicer to match."""
    skin_mm: Length = 1.0
    """Solid top and bottom skin thickness of the mass model; set the slicer to match."""
    infill_percent: Annotated[float, Field(ge=0, le=100)] = 20.0
    """Infill of the parts' interior in the mass model, percent; the balance depends on it, so set the slicer to
    match."""
    overhang_angle_deg: Annotated[float, Field(gt=0, lt=90)] = 45.0
    """Faces steeper than this from the vertical need support (the print orientation minimises that support)."""
    min_bed_contact_mm2: Annotated[float, Field(gt=0, le=1e6)] = 100.0
    """Least flat contact with the bed a part needs in its printing orientation."""


class BennettBase(Strict):
    height_mm: Length = 80.0
    """Height of the base's post, from the S stack down to the foot."""
    foot_diameter_mm: Length = 100.0
    """Diameter of the base's flat round foot (at least boss_diameter_mm)."""
    foot_thickness_mm: Length = 5.0
    """Thickness of the foot."""
    min_tip_angle_deg: Annotated[float, Field(gt=0, lt=90)] = 10.0
    """The kit on its base must stay up tilted this far in every pose (check says what foot diameter it needs)."""


class BennettChecks(Strict):
    balance_tolerance_mm: Length = 0.1
    """Largest distance of the kit's common centre of mass from S, in any pose of the grid, as printed; check fails
    above it."""
    grid: Annotated[list[Annotated[int, Field(ge=2, le=400)]], Field(min_length=2, max_length=2)] = [24, 21]
    """Balance grid: [samples of q1 over a full turn about S, samples of the shape angle over workspace_deg]."""
    infill_error_percent_points: NonNeg = 5.0
    """What-if: check reports how far the centre of mass moves if the infill comes out this many percentage points
    above print.infill_percent."""
    mass_scale: dict[Annotated[int, Field(ge=1, le=12)], Ratio] = Field(
        default={}, description="what-if: a link's mass times this, counterweights not re-sized (seeded faults)")


class BennettDesign(DesignHeader):
    AUTO_PLAY: ClassVar[dict] = {"pin.clearance_diametral_mm": "running"}  # mechanisms.autoplay
    kind: Literal["bennett_butterfly"]
    """The mechanism this file designs: `bennett_butterfly` selects these keys."""
    linkage: BennettLinkage
    """Bennett 1's lengths and twists, the four scales, the home pose and the workspace."""
    parts: BennettParts
    """The links' bars and bosses, and their layout in layers and stack shifts."""
    pin: Pin
    """The bought steel pins the joints run on."""
    counterweights: Counterweights
    """The pockets of stock slugs and binder that balance the kit about S."""
    print: PrintCfg = PrintCfg()
    """How the parts are printed: the mass model and the print orientation rules."""
    base: BennettBase = BennettBase()
    """The base: a post on a flat foot holding the S stack."""
    checks: BennettChecks = BennettChecks()
    """What partgen check holds the kit to."""
    tolerance: ToleranceTarget = ToleranceTarget()
    """The jam probability that auto play (pin.clearance_diametral_mm) is chosen for, and above which check warns."""
