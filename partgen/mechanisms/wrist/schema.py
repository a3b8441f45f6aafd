"""The design YAML of a wrist gear pair (``kind: wrist``)."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, field_validator, model_validator

from ...config.schema import (Finite, Gap, Length, Material, Name, Strict, Text)

__all__ = ["WristDesign"]


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
    # ``printer``: half the running fit (diametral) the printer profile's maker measured
    clearance_radial_mm: Finite | Literal["printer"]
    max_bend_deg: Annotated[float, Field(gt=0, lt=180)]
    sweep: Sweep = Sweep()
    shaft_diameter_mm: Length
    press_fit_clearance_diametral_mm: Finite | Literal["printer"] = 0.05  # printer: the profile's press fit
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
