"""The design YAML of a balanced Bennett butterfly (``kind: bennett_butterfly``)."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator

from ...config.schema import (Density, Finite, Gap, Length, Material, Name, NonNeg, Ratio, Strict, Text)

__all__ = ["BennettDesign"]


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
    clearance_diametral_mm: Gap | Literal["printer"]  # printer: the running fit the printer profile measured
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
