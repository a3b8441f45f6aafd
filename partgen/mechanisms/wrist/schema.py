"""The design YAML of a wrist gear pair (``kind: wrist``)."""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import Field, field_validator, model_validator

from ...config.schema import (DesignHeader, Finite, Gap, Length, Strict, ToleranceTarget)

__all__ = ["WristDesign"]


class Tooth(Strict):
    shape: Literal["dome"] = "dome"
    """Tooth form on gear 1: dome (a sphere cap, smooth in every direction and printable without overhang); gear 2's
    sockets are cut by sweeping the domes."""
    radius_mm: Length
    """Radius of the dome's sphere."""
    height_mm: Length
    """How far a dome stands proud of gear 1's pitch surface (under 2 × radius_mm; its foot must be at least the
    printer's thinnest wall across)."""


MAX_SWEEP_POSES = 2048  # each pose unions every dome into the socket cut: more takes hours


class Sweep(Strict):
    theta_steps: Annotated[int, Field(ge=2, le=200)] = 8
    """Poses of gear 1's tilt θ, from 0 to the largest the bend reaches, swept to cut gear 2's sockets."""
    psi_steps: Annotated[int, Field(ge=4, le=720)] = 24
    """Bend directions ψ round the axis swept at each tilt (theta_steps × psi_steps ≤ 2048; the default 8 × 24 cuts
    the sockets within 0.01 mm)."""

    @model_validator(mode="after")
    def _budget(self):
        if self.theta_steps * self.psi_steps > MAX_SWEEP_POSES:
            raise ValueError(f"{self.theta_steps} × {self.psi_steps} = {self.theta_steps * self.psi_steps} poses: at most "
                             f"{MAX_SWEEP_POSES} (the default 8 × 24 cuts sockets within 0.01 mm)")
        return self


class CrossMate(Strict):
    """The cross gear's mate: an ABENICS monopole gear whose axis is parallel to the cross gear's
    ring axis x, on the cross gear's pole axis; its teeth are cut by the cross gear's ring teeth
    about y swept through the mesh (docs/mechanisms/wrist.md)."""

    teeth: Annotated[int, Field(ge=8, le=200)]
    """Teeth of the mate (same module as the cross gear): the mate turns cross_gear.teeth / teeth times per turn of
    the cross gear about the mate's axis."""
    face_width_mm: Length
    """Width of the mate's toothed face along its axis, centred on the cross gear's plane x = 0 (at most the cross
    gear's pitch radius)."""
    bore_diameter_mm: Length
    """Diameter of the mate's round shaft bore (under its root circle by a 1.5 mm wall)."""
    clearance_normal_mm: Gap = 0.05
    """Clearance normal to the flanks: the cross gear's teeth are grown by this before they cut the mate, so the
    mate's flanks stand this far off the cross gear's (its backlash, besides the cross gear's own thinning)."""
    turn_deg: Annotated[float, Field(ge=5, le=80)] = 30.0
    """Largest turn of the cross gear about the mate's axis, each way from its pole facing the mate: the mate's teeth
    are cut to clear every ring tooth that meets it within this turn, and check covers it."""


class CrossGear(Strict):
    """An ABENICS-style cross spherical gear (ring-involute teeth both ways) on a spherical pitch."""

    teeth: Annotated[int, Field(ge=8, le=400)]
    """Teeth of the cross gear (a multiple of 4, so the section through both ring axes is the 2-D profile)."""
    module_mm: Length
    """Module of the cross gear; module × teeth / 2 must equal the sphere's pitch radius (half centre_distance_mm)."""
    pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    """Pressure angle of the cross gear's involute profile; 20 is standard."""
    backlash_per_gear_mm: Gap = 0.05
    """Each tooth thinned by this arc length at the pitch circle (circumferential)."""
    mate: CrossMate | None = None
    """Also build the cross gear's mate (an ABENICS monopole gear) and check the pair; none: the cross gear alone."""

    @field_validator("teeth")
    @classmethod
    def _multiple_of_4(cls, v):
        if v % 4:
            raise ValueError("must be a multiple of 4 so the section through both ring axes is the 2-D profile")
        return v


class Wrist(Strict):
    """A spherical (nominal_ratio 1) or quasi-ellipsoidal wrist gear pair."""

    nominal_ratio: Annotated[float, Field(gt=0.2, lt=5)]
    """Nominal transmission ratio I (gear 2's turning rate over gear 1's at the pole, dφ/dθ): 1 makes both pitch
    surfaces spheres, any other value quasi-ellipsoids."""
    centre_distance_mm: Length
    """Distance from gear 1's centre to gear 2's centre (the sum of the pitch radii at the pole)."""
    longitudinal_pitch_mm: Length
    """Meridian arc between neighbouring rings of teeth on the pitch surface."""
    ring_teeth: Annotated[list[Annotated[int, Field(ge=1, le=200)]], Field(min_length=2, max_length=20)] = [1, 6, 12]
    """Teeth on each ring, from the pole outward (1: a tooth on the pole)."""
    tooth: Tooth
    """Gear 1's teeth."""
    clearance_radial_mm: Finite | Literal["printer", "auto"]
    """Radial clearance: gear 1's domes are grown by this before they cut gear 2's sockets; printer: half the printer
    profile's measured running fit (diametral); auto: the least (on a 0.005 mm grid) with which a print jams with
    probability at most tolerance.max_jam_probability on the design's printer (docs/tolerance.md)."""
    max_bend_deg: Annotated[float, Field(gt=0, lt=180)]
    """Largest bend between the two gears' axes (θ + φ) the workspace reaches and check covers; at least 10."""
    sweep: Sweep = Sweep()
    """How finely the workspace is swept when gear 2's sockets are cut."""
    shaft_diameter_mm: Length
    """Diameter of the D-shaft each gear is pressed onto."""
    press_fit_clearance_diametral_mm: Finite | Literal["printer"] = 0.05
    """Diametral clearance of a gear's D-bore over its shaft (hole minus shaft; negative: interference); printer: the
    printer profile's measured press fit."""
    base_height_mm: Length = 8.0
    """How far each gear's flat bottom face (where the shaft enters) lies below the gear's centre."""
    chord_tolerance_mm: Annotated[float, Field(ge=1e-3, le=0.5)] = 0.02
    """Largest chord sagitta (deviation of the faceted outline from the exact curve) on flanks, fillets and tips;
    smaller is smoother and heavier STLs."""
    cross_gear: CrossGear | None = None
    """Also build an ABENICS-style cross gear on the same sphere (needs nominal_ratio 1); none: not built."""


class WristDesign(DesignHeader):
    AUTO_PLAY: ClassVar[dict] = {"wrist.clearance_radial_mm": "radial"}  # mechanisms.autoplay
    kind: Literal["wrist"]
    """The mechanism this file designs: `wrist` selects these keys."""
    wrist: Wrist
    """The wrist gear pair: pitch surfaces, rings of teeth, clearance, workspace and shafts."""
    tolerance: ToleranceTarget = ToleranceTarget()
    """The jam probability that auto play (wrist.clearance_radial_mm) is chosen for, and above which check warns."""
