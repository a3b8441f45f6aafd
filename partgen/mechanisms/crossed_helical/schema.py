"""The design YAML of a crossed helical pair on skew shafts (``kind: crossed_helical``). Every
length in mm, every angle in degrees, clearances diametral."""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import Field, model_validator

from ...config.schema import DesignHeader, PlateChecks, Gap, Length, Strict, ToleranceTarget
from ..solid_pair import PairFrame

__all__ = ["CrossedHelicalDesign"]

Helix = Annotated[float, Field(ge=3.0, le=85.0)]
Starts = Annotated[int, Field(ge=1, le=1000)]
Fit = Literal["printer"] | Annotated[float, Field(ge=-1, le=5)]
Running = Literal["printer", "auto"] | Annotated[float, Field(ge=-1, le=5)]


class CrossedGears(Strict):
    teeth: Annotated[list[Starts], Field(min_length=2, max_length=2)]
    """Teeth (starts) of [driver (input, gear 1), driven (output, gear 2)]; gear 1 with 1–3 teeth or a transverse
    pressure angle of 40° or more is a ZI worm; gear 2 needs at least 4."""
    normal_module_mm: Length
    """Normal module of the rack both gears are cut by (each gear's transverse module is this / cos of its helix
    angle)."""
    normal_pressure_angle_deg: Annotated[float, Field(ge=10.0, le=35.0)] = 20.0
    """Normal pressure angle of that rack; 20 is standard."""
    helix_angle_deg: Annotated[list[Helix], Field(min_length=2, max_length=2)]
    """Helix angle of [gear 1, gear 2] at their reference cylinders, both one hand; they must add up to
    shaft_angle_deg."""
    face_width_mm: Annotated[list[Length], Field(min_length=2, max_length=2)]
    """Face width of [gear 1, gear 2], along each gear's own axis."""
    backlash_per_gear_mm: Gap = 0.1
    """Per gear: each tooth is thinned by this transverse arc length at its reference pitch circle; check measures
    the backlash the pair is left with."""
    addendum_coeff: Annotated[float, Field(ge=0.5, le=1.5)] = 1.0
    """Tooth height above the reference circle, × the normal module."""
    dedendum_coeff: Annotated[float, Field(ge=0.8, le=2.0)] = 1.25
    """Tooth depth below the reference circle, × the normal module."""
    chord_tolerance_mm: Annotated[float, Field(ge=0.001, le=0.1)] = 0.01
    """Largest chord sagitta (deviation of the faceted outline from the exact curve) on flanks, fillets and tips;
    smaller is smoother and heavier STLs."""
    throated: bool = False
    """Only for a worm (gear 1 with 1-3 starts): gear 2, the wheel, cut by the worm's envelope (a throated,
    enveloping wheel: the worm's thread, grown by the wheel's backlash, posed at the sampled phases of the mesh and
    subtracted from the blank) instead of a plain helical wheel: line contact across its face instead of a point."""


class CrossedShafts(Strict):
    diameter_mm: Annotated[list[Length], Field(min_length=2, max_length=2)] = [8.0, 8.0]
    """Diameters of [gear 1's post (upright on the base), gear 2's pin (held in the two blocks)]."""
    running_clearance_diametral_mm: Running = "printer"
    """Diametral running clearance, a gear's bore minus its post or pin; printer: the printer profile's measured
    running fit; auto: the least that meets tolerance.max_jam_probability on the printer."""
    press_fit_clearance_diametral_mm: Fit = "printer"
    """Diametral clearance of gear 2's pin in its blocks' holes (hole minus pin; negative: interference); printer:
    the printer profile's measured press fit."""


class CrossedFrame(PairFrame):
    """The shared frame (``mechanisms.solid_pair.PairFrame``): gear 2's pin held by two blocks."""


class CrossedChecks(PlateChecks):
    """What `partgen check` holds the pair to."""

    samples: Annotated[int, Field(ge=4, le=1000)] = 12
    """Phases checked over one tooth pitch of gear 1, each an exact 3-D interference and backlash test (--samples
    overrides it)."""
    friction_coefficient: Annotated[float, Field(ge=0.0, le=1.0)] = 0.15
    """Assumed sliding friction coefficient along the teeth, from which check states the efficiency both ways and
    whether the pair self-locks."""


class CrossedHelicalDesign(DesignHeader):
    AUTO_PLAY: ClassVar[dict] = {"shafts.running_clearance_diametral_mm": "running"}  # mechanisms.autoplay
    kind: Literal["crossed_helical"]
    """The mechanism this file designs: `crossed_helical` selects these keys."""
    shaft_angle_deg: Annotated[float, Field(ge=45.0, le=90.0)] = 90.0
    """Angle between the two (skew) shafts; 90 for a worm drive or a right-angle pair."""
    gears: CrossedGears
    """The two helical gears (or worm and wheel): teeth, rack, helix angles, face widths, play."""
    shafts: CrossedShafts = CrossedShafts()
    """Gear 1's post, gear 2's pin and their fits."""
    frame: CrossedFrame = CrossedFrame()
    """The base and the two blocks holding gear 2's pin."""
    checks: CrossedChecks = CrossedChecks()
    """What partgen check holds the kit to."""
    tolerance: ToleranceTarget = ToleranceTarget()
    """The jam probability that auto play (shafts.running_clearance_diametral_mm) is chosen for."""

    @model_validator(mode="after")
    def _angles(self):
        total = sum(self.gears.helix_angle_deg)
        if abs(total - self.shaft_angle_deg) > 1e-6:
            raise ValueError(f"[gears.helix_angle_deg] the helix angles add up to {total:g}°, not the shaft angle "
                             f"{self.shaft_angle_deg:g}° (Σ = β1 + β2, both one hand)")
        if self.gears.teeth[1] < 4:
            raise ValueError(f"[gears.teeth] gear 2 (the output) needs at least 4 teeth, got {self.gears.teeth[1]}")
        return self
