"""The design YAML of a spur gear pair on a base plate (``kind: gear_pair``)."""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import AfterValidator, Field, model_validator

from ...config.schema import DesignHeader, PlateChecks, ToleranceTarget, Gap, Length, Strict, Teeth

__all__ = ["GearPairDesign"]


def _has_default(m: dict) -> dict:
    if "default" not in m:
        raise ValueError("a mapping of play per gear needs 'default' (the value of a gear it does not name)")
    return m


# a play per gear: {default: mm, gear1: mm, gear2: mm} (what auto's allocation pins)
PerGear = Annotated[dict[Annotated[str, Field(min_length=1, max_length=40)], Gap], Field(min_length=1, max_length=3),
                    AfterValidator(_has_default)]


def _defaults(data, key: str):
    """A play mapping without ``default`` named on its key (before the union's alternatives speak)."""
    if isinstance(data, dict) and isinstance(data.get(key), dict) and "default" not in data[key]:
        raise ValueError(f"[{key}.default] required key is missing: a mapping of play per gear gives the value of a "
                         "gear it does not name")
    return data


class PairGears(Strict):
    module_mm: Length
    """Gear module, both gears (reference pitch diameter / teeth)."""
    pressure_angle_deg: Annotated[float, Field(ge=10.0, le=35.0)] = 20.0
    """Pressure angle of the involute tooth system (the basic rack's flank angle); 20 is standard."""
    teeth: Annotated[list[Teeth], Field(min_length=2, max_length=2)]
    """Teeth of [driver (input), driven (output)]; the ratio is driven / driver."""
    face_width_mm: Length = 8.0
    """Gear thickness along the axles."""
    backlash_per_gear_mm: Gap | Literal["auto"] | PerGear = 0.1
    """Per gear: each tooth is thinned by this arc length at its reference pitch circle, so the pair at its
    zero-backlash centre distance has the sum of both as circumferential backlash; auto: the least that meets
    tolerance.max_jam_probability on the printer (allocated per gear where that saves play); a mapping {default: mm,
    gear1: mm, gear2: mm}: each named gear its own."""
    profile_shift: Literal["auto"] | Annotated[float, Field(ge=-1.0, le=1.0)] = "auto"
    """Profile shift coefficient (× module) of both gears; auto: the smallest shift that avoids undercut (0 at and
    above the undercut limit). The posts sit at the shifted pair's zero-backlash centre distance."""
    chord_tolerance_mm: Length = 0.01
    """Largest chord sagitta (deviation of the faceted outline from the exact curve) on flanks, fillets and tips;
    smaller is smoother and heavier STLs."""

    @model_validator(mode="before")
    @classmethod
    def _default_given(cls, data):
        return _defaults(data, "backlash_per_gear_mm")


class Axles(Strict):
    diameter_mm: Length = 8.0
    """Diameter of the two posts standing on the base, each gear turning on one."""
    clearance_diametral_mm: Gap | Literal["printer", "auto"] | PerGear = 0.4
    """Diametral running clearance, a gear's bore minus its post; printer: the printer profile's measured running fit
    (fits.running_clearance_diametral_mm); auto: the least that (with the backlash) meets
    tolerance.max_jam_probability on the printer (allocated per gear where that saves play); a mapping {default: mm,
    gear1: mm, gear2: mm}: each named gear's bore its own."""
    axial_gap_mm: Gap = 0.5
    """Gap between the base plate and a gear's face."""

    @model_validator(mode="before")
    @classmethod
    def _default_given(cls, data):
        return _defaults(data, "clearance_diametral_mm")


class PairBase(Strict):
    thickness_mm: Length = 4.0
    """Thickness of the base plate the posts stand on."""
    margin_mm: Length = 5.0
    """How far the base plate reaches beyond each gear's tip circle."""


class PairChecks(PlateChecks):
    """What `partgen check` holds the pair to."""

    samples: Annotated[int, Field(ge=8, le=10_000)] = 180
    """Input angles checked, evenly over one revolution of the output (check and trace; --samples overrides it)."""


class GearPairDesign(DesignHeader):
    AUTO_PLAY: ClassVar[dict] = {"gears.backlash_per_gear_mm": "backlash",
                                 "axles.clearance_diametral_mm": "running"}  # mechanisms.autoplay
    PER_UNIT_PLAY: ClassVar[frozenset] = frozenset(AUTO_PLAY)  # the keys that take {default: mm, gear1: mm, gear2: mm}
    kind: Literal["gear_pair"]
    """The mechanism this file designs: `gear_pair` selects these keys."""
    gears: PairGears
    """The two spur gears: tooth system, teeth, face width and play."""
    axles: Axles = Axles()
    """The posts the gears turn on and the fit of their bores."""
    base: PairBase = PairBase()
    """The base plate the posts stand on."""
    checks: PairChecks = PairChecks()
    """What partgen check holds the kit to."""
    tolerance: ToleranceTarget = ToleranceTarget()
    """The jam probability that auto play (gears.backlash_per_gear_mm, axles.clearance_diametral_mm) is chosen
    for."""
