"""The design YAML of a straight bevel gear pair on intersecting shafts (``kind: bevel``). Every
length in mm, every angle in degrees, clearances diametral."""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import Field, model_validator

from ...config.schema import DesignHeader, PlateChecks, Gap, Length, Strict, ToleranceTarget
from ..solid_pair import PairFrame

__all__ = ["BevelDesign"]

Teeth = Annotated[int, Field(ge=6, le=400)]
Fit = Literal["printer"] | Annotated[float, Field(ge=-1, le=5)]
Running = Literal["printer", "auto"] | Annotated[float, Field(ge=-1, le=5)]


class BevelGears(Strict):
    teeth: Annotated[list[Teeth], Field(min_length=2, max_length=2)]
    """Teeth of [driver (input, gear 1, upright on the base), driven (output, gear 2, on the pin)]; equal teeth at a
    90° shaft angle make a mitre pair."""
    module_mm: Length
    """Module at the heel (the teeth's outer, large end): each heel pitch diameter is teeth × module."""
    pressure_angle_deg: Annotated[float, Field(ge=14.5, le=30.0)] = 20.0
    """Pressure angle of the spherical involute teeth (the plane of action's angle to the plane tangent to both pitch
    cones); 20 is standard."""
    face_width_mm: Length
    """Length of the teeth along the pitch cone, from the heel inwards; at most a third of the cone distance."""
    backlash_per_gear_mm: Gap | Literal["auto"] = 0.1
    """Per gear: each tooth is thinned by this arc length at its heel pitch circle; check measures the backlash the
    pair is left with; auto: the least that (with the running clearance) meets tolerance.max_jam_probability on the
    printer."""
    addendum_coeff: Annotated[float, Field(ge=0.5, le=1.5)] = 1.0
    """Tooth height above the pitch cone at the heel, × the module."""
    dedendum_coeff: Annotated[float, Field(ge=0.8, le=2.0)] = 1.25
    """Tooth depth below the pitch cone at the heel, × the module."""
    chord_tolerance_mm: Annotated[float, Field(ge=0.001, le=0.1)] = 0.01
    """Largest chord sagitta (deviation of the faceted heel outline from the exact curve) on flanks, roots and tips;
    smaller is smoother and heavier STLs."""


class BevelShafts(Strict):
    diameter_mm: Annotated[list[Length], Field(min_length=2, max_length=2)] = [8.0, 8.0]
    """Diameters of [gear 1's post (upright on the base), gear 2's pin (pressed into its block)]."""
    running_clearance_diametral_mm: Running = "printer"
    """Diametral running clearance, a gear's bore minus its post or pin; printer: the printer profile's measured
    running fit; auto: the least that (with the backlash) meets tolerance.max_jam_probability on the printer."""
    press_fit_clearance_diametral_mm: Fit = "printer"
    """Diametral clearance of gear 2's pin in its block's hole (hole minus pin; negative: interference); printer:
    the printer profile's measured press fit."""


class BevelFrame(PairFrame):
    """The shared frame (``mechanisms.solid_pair.PairFrame``) with one block, and the hubs."""

    hub_length_mm: Length = 4.0
    """Length of gear 2's hub behind its back face, along its axis (gear 1's hub reaches down to the base)."""
    block_wall_mm: Length = 4.0
    """Material round gear 2's pin in its block, and the hubs' wall round their bores."""
    block_thickness_mm: Length = 12.0
    """Length of gear 2's block along gear 2's axis: how deep the pin is held."""


class BevelChecks(PlateChecks):
    """What `partgen check` holds the pair to."""

    samples: Annotated[int, Field(ge=4, le=1000)] = 12
    """Phases checked over one tooth pitch of gear 1, each an exact 3-D interference and backlash test (--samples
    overrides it)."""


class BevelDesign(DesignHeader):
    AUTO_PLAY: ClassVar[dict] = {"gears.backlash_per_gear_mm": "backlash",
                                 "shafts.running_clearance_diametral_mm": "running"}  # mechanisms.autoplay
    kind: Literal["bevel"]
    """The mechanism this file designs: `bevel` selects these keys."""
    shaft_angle_deg: Annotated[float, Field(ge=30.0, le=150.0)] = 90.0
    """Angle between the two (intersecting) shafts, 30 to 150; 90 for a right-angle (mitre, with equal teeth) pair.
    Above 90 only while both pitch cones stay below 90° (cos Σ > −z_small/z_large: a crown gear at 90°, an internal
    bevel beyond, are not made); gear 2 then leans over gear 1, its block on a leg sloping down behind its back."""
    gears: BevelGears
    """The two straight bevel gears: teeth, module, pressure angle, face width, play."""
    shafts: BevelShafts = BevelShafts()
    """Gear 1's post, gear 2's pin and their fits."""
    frame: BevelFrame = BevelFrame()
    """The base, the hubs and the block holding gear 2's pin."""
    checks: BevelChecks = BevelChecks()
    """What partgen check holds the kit to."""
    tolerance: ToleranceTarget = ToleranceTarget()
    """The jam probability that auto play (gears.backlash_per_gear_mm, shafts.running_clearance_diametral_mm) is
    chosen for."""

    @model_validator(mode="after")
    def _face(self):
        import math

        from ...design.bevel import pitch_angle_limit

        z1, z2 = self.gears.teeth
        s = math.radians(self.shaft_angle_deg)
        limit = math.degrees(pitch_angle_limit((z1, z2)))
        if self.shaft_angle_deg >= limit - 1e-6:
            d1 = math.degrees(math.atan2(math.sin(s), z2 / z1 + math.cos(s)))
            big, d = (1, d1) if z1 > z2 else (2, self.shaft_angle_deg - d1)
            raise ValueError(f"[shaft_angle_deg] {self.shaft_angle_deg:g}° makes gear {big}'s pitch cone {d:.1f}° (90° is a "
                             f"crown gear, more an internal bevel: neither is made): for {z1}/{z2} teeth the shaft "
                             f"angle must stay below {limit:.2f}°")
        d1 = math.atan2(math.sin(s), z2 / z1 + math.cos(s))
        R = self.gears.module_mm * z1 / (2 * math.sin(d1))
        if self.gears.face_width_mm > R / 3 + 1e-9:
            raise ValueError(f"[gears.face_width_mm] {self.gears.face_width_mm:g} mm is more than a third of the cone "
                             f"distance ({R:.2f} mm): at most {R / 3:.2f} mm")
        return self
