"""The YAML schema shared by every mechanism: the bounded number types, a printer profile, a material.
Each mechanism's own design schema lives in its folder (``partgen.mechanisms.<kind>.schema``) (pydantic v2, strict, unknown keys forbidden).

Every length key ends in ``_mm``, every angle in ``_deg``; clearances say ``radial`` or
``diametral``. Defaults are documented in README's config reference.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, field_validator, model_validator

__all__ = ["Strict", "Printer", "Material"]

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



class Material(Strict):
    name: Annotated[str, Field(min_length=1, max_length=200)]
    density_g_cm3: Density
