"""The design YAML of a crossed helical pair on skew shafts (``kind: crossed_helical``). Every
length in mm, every angle in degrees, clearances diametral."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator

from ...config.schema import Gap, Length, Material, Name, Strict, Text

__all__ = ["CrossedHelicalDesign"]

Helix = Annotated[float, Field(ge=3.0, le=85.0)]
Starts = Annotated[int, Field(ge=1, le=1000)]
Fit = Literal["printer"] | Annotated[float, Field(ge=-1, le=5)]


class CrossedGears(Strict):
    # driver (input, gear 1: 1-3 teeth or a transverse pressure angle ≥ 40° make it a ZI worm), driven (output, gear 2)
    teeth: Annotated[list[Starts], Field(min_length=2, max_length=2)]
    normal_module_mm: Length  # the rack both are cut by
    normal_pressure_angle_deg: Annotated[float, Field(ge=10.0, le=35.0)] = 20.0
    helix_angle_deg: Annotated[list[Helix], Field(min_length=2, max_length=2)]  # at the reference cylinders; add up to the shaft angle
    face_width_mm: Annotated[list[Length], Field(min_length=2, max_length=2)]
    backlash_per_gear_mm: Gap = 0.1  # transverse thinning of each gear's tooth at its reference pitch circle
    addendum_coeff: Annotated[float, Field(ge=0.5, le=1.5)] = 1.0  # × the normal module
    dedendum_coeff: Annotated[float, Field(ge=0.8, le=2.0)] = 1.25
    chord_tolerance_mm: Annotated[float, Field(ge=0.001, le=0.1)] = 0.01


class CrossedShafts(Strict):
    diameter_mm: Annotated[list[Length], Field(min_length=2, max_length=2)] = [8.0, 8.0]  # gear 1's post, gear 2's pin
    running_clearance_diametral_mm: Fit = "printer"  # a gear's bore over its post or pin
    press_fit_clearance_diametral_mm: Fit = "printer"  # the pin in its blocks


class CrossedFrame(Strict):
    base_thickness_mm: Length = 5.0
    margin_mm: Length = 4.0  # the base beyond gear 1's tip circle and the blocks
    axial_gap_mm: Length = 0.5  # between a gear and the base or a block
    block_wall_mm: Length = 4.0  # material round gear 2's pin in its blocks
    block_thickness_mm: Length = 8.0  # each block, along gear 2's axis


class CrossedChecks(Strict):
    samples: Annotated[int, Field(ge=4, le=1000)] = 12  # phases over one tooth pitch of gear 1 (exact 3-D tests)
    friction_coefficient: Annotated[float, Field(ge=0.0, le=1.0)] = 0.15  # sliding along the teeth: efficiency, self-locking
    plate_margin_mm: Gap = 5.0


class CrossedHelicalDesign(Strict):
    kind: Literal["crossed_helical"]
    name: Name
    description: Text = ""
    printer: Annotated[str, Field(min_length=1, max_length=500)]
    shaft_angle_deg: Annotated[float, Field(ge=45.0, le=90.0)] = 90.0
    gears: CrossedGears
    shafts: CrossedShafts = CrossedShafts()
    frame: CrossedFrame = CrossedFrame()
    checks: CrossedChecks = CrossedChecks()
    material: Material

    @model_validator(mode="after")
    def _angles(self):
        total = sum(self.gears.helix_angle_deg)
        if abs(total - self.shaft_angle_deg) > 1e-6:
            raise ValueError(f"[gears.helix_angle_deg] the helix angles add up to {total:g}°, not the shaft angle "
                             f"{self.shaft_angle_deg:g}° (Σ = β1 + β2, both one hand)")
        if self.gears.teeth[1] < 4:
            raise ValueError(f"[gears.teeth] gear 2 (the output) needs at least 4 teeth, got {self.gears.teeth[1]}")
        return self
