"""The design YAML of a spur gear pair on a base plate (``kind: gear_pair``)."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from ...config.schema import ToleranceTarget, Gap, Length, Material, Name, Strict, Teeth, Text

__all__ = ["GearPairDesign"]


class PairGears(Strict):
    module_mm: Length
    pressure_angle_deg: Annotated[float, Field(ge=10.0, le=35.0)] = 20.0
    teeth: Annotated[list[Teeth], Field(min_length=2, max_length=2)]  # driver (input), driven (output)
    face_width_mm: Length = 8.0
    backlash_per_gear_mm: Gap | Literal["auto"] = 0.1  # auto: the least that meets tolerance.max_jam_probability  # circumferential thinning of each gear's tooth at its pitch circle
    profile_shift: Literal["auto"] | Annotated[float, Field(ge=-1.0, le=1.0)] = "auto"
    chord_tolerance_mm: Length = 0.01


class Axles(Strict):
    diameter_mm: Length = 8.0  # the posts standing on the base, each gear turning on one
    clearance_diametral_mm: Gap | Literal["printer"] = 0.4  # bore over post; printer: the profile's running fit
    axial_gap_mm: Gap = 0.5  # between the base and a gear's face


class PairBase(Strict):
    thickness_mm: Length = 4.0
    margin_mm: Length = 5.0  # beyond each gear's tip circle


class PairChecks(Strict):
    samples: Annotated[int, Field(ge=8, le=10_000)] = 180  # over one revolution of the output
    plate_margin_mm: Gap = 5.0


class GearPairDesign(Strict):
    kind: Literal["gear_pair"]
    name: Name
    description: Text = ""
    printer: Annotated[str, Field(min_length=1, max_length=500)]
    gears: PairGears
    axles: Axles = Axles()
    base: PairBase = PairBase()
    checks: PairChecks = PairChecks()
    tolerance: ToleranceTarget = ToleranceTarget()
    material: Material
