"""The YAML schema shared by every mechanism: the bounded number types, a printer profile, a material.
Each mechanism's own design schema lives in its folder (``partgen.mechanisms.<kind>.schema``) (pydantic v2, strict, unknown keys forbidden).

Every length key ends in ``_mm``, every angle in ``_deg``; clearances say ``radial`` or
``diametral``. A field's meaning is its docstring (or ``Field(description=...)``): the docs' config
reference is generated from them.
"""

from __future__ import annotations

import typing
from typing import Annotated

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, model_validator

__all__ = ["Strict", "Printer", "Material", "ToleranceTarget", "AUTO_PLAY_START_MM", "nested_models", "DesignHeader"]

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
    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False,
                              use_attribute_docstrings=True)  # a field's docstring is its description


class Fits(Strict):
    """Clearances the maker measured on this printer (diametral: hole minus pin, mm)."""

    running_clearance_diametral_mm: Annotated[float, Field(ge=0, le=5)] = Field(
        description="a pin turns freely in a hole this much larger (revolute joints)")
    press_fit_clearance_diametral_mm: Annotated[float, Field(ge=-1, le=5)] = Field(
        description="a pin pressed into a hole this much larger stays put (negative: interference)")
    gear_backlash_circumferential_mm: Annotated[float, Field(ge=0, le=5)] | None = Field(
        None, description="least total backlash of a printed spur pair that turns smoothly (coupon; informative)")


Bias = Annotated[float, Field(ge=-2, le=2)]


class Biases(Strict):
    """Mean deviations of printed features (printed minus modelled, as a diameter, mm): what
    ``partgen calibrate`` measured. ``compensate``: `build` opens holes and trims outlines by them
    (then leave the slicer's XY compensation at 0)."""

    hole_diametral_mm: Bias = Field(0.0, description="a hole prints this much larger (negative: undersize)")
    pin_diametral_mm: Bias = Field(0.0, description="a pin, post or boss prints this much larger")
    outline_diametral_mm: Bias = Field(0.0, description="any other outline (gear teeth, plates) prints this much larger")
    compensate: bool = Field(True, description="build compensates the geometry by these biases")


class Calibration(Strict):
    """Where a profile's measured values came from (written by ``partgen calibrate``)."""

    coupon: Annotated[int, Field(ge=1, le=1000)]
    """Layout version of the calibration coupon whose results gave these values (partgen coupon's template)."""
    results: Annotated[str, Field(max_length=500)]
    """File name of the filled-in results.yaml the values were computed from."""
    printed_on: Annotated[str, Field(max_length=100)] | None = None
    """Date the coupon was printed, as written in the results file (none: not stated)."""
    calibrated_on: Annotated[str, Field(max_length=100)] | None = None
    """Date partgen calibrate wrote this profile."""
    from_profile: Annotated[str, Field(max_length=200)] | None = None
    """File name of the profile calibrated (its untouched values were copied from it)."""


class Printer(Strict):
    """A printer profile (``partgen/printers/<name>.yaml``); every length in mm, every angle in degrees.
    The rules of `check` derive from these: tooth tips ≥ ``checks.min_tip_width_roads`` × line width,
    walls ≥ min_wall_lines × line width, running holes ≥ min_hole_diameter_mm, holes held to size ≥
    min_hole_to_size_diameter_mm."""

    name: Annotated[str, Field(min_length=1, max_length=200)]
    """The printer's name, as reports, plates and the manifest show it."""
    build_envelope_mm: Annotated[list[Length], Field(min_length=3, max_length=3)]
    """Build volume [x, y, z], as the maker publishes it: build refuses a part larger in every orientation; check
    packs the build plates on x × y and holds part heights to z."""
    nozzle_diameter_mm: Length = Field(0.4, description="the nozzle's bore")
    line_width_mm: Length | None = Field(None, description="width of one extruded line (road)")
    resolution_mm: Length | None = Field(None, description="old name of line_width_mm (read only when that is absent)")
    layer_height_mm: Length = Field(0.2, description="layer height the rules assume")
    xy_accuracy_mm: Annotated[float, Field(ge=0, le=5)] = Field(0.1, description="± error of a printed outline in x and y")
    min_hole_diameter_mm: Length = Field(description="smallest hole that runs reliably on a pin or axle")
    min_hole_to_size_diameter_mm: Length = Field(3.0, description="smallest hole held to size (press-fit D, pen bore)")
    min_wall_lines: Annotated[float, Field(ge=1, le=100)] | None = Field(
        None, description="thinnest wall, in lines: the thinnest wall is min_wall_lines × line_width_mm")
    min_wall_mm: Length | None = Field(None, description="old form of min_wall_lines (a length)")
    min_gear_diameter_mm: Length = Field(15.0, description="smallest reliable gear (reference pitch diameter)")
    min_link_length_mm: Length = Field(20.0, description="smallest link, joint to joint")
    overhang_deg: Annotated[float, Field(ge=0, le=89)] = Field(
        45.0, description="steepest overhang printed without supports, from the vertical")
    plate_edge_mm: Annotated[float, Field(ge=0, le=100)] = Field(
        7.0, description="room left between the parts and the bed's edge on a build plate, for the slicer's "
        "skirt or brim (PrusaSlicer's default skirt lies 6 mm out from the parts and is one line wide)")
    fits: Fits | None = None
    """Clearances measured on this printer: what `printer` means as a design's clearance value (none: a design may
    not say `printer`)."""
    biases: Biases | None = None
    """Mean printed-minus-modelled size errors (partgen calibrate); none: no compensation."""
    measured: bool = Field(False, description="fits, accuracy and biases were measured on this machine (false: "
                           "typical values for its kind)")
    calibration: Calibration | None = None
    """Where the measured values came from (written by partgen calibrate; none: not calibrated)."""

    @model_validator(mode="after")
    def _one_each(self):
        if (self.line_width_mm is None) == (self.resolution_mm is None):
            raise ValueError("give line_width_mm (the width of one extruded line, mm)"
                             + ("; resolution_mm is its old name, give only one" if self.line_width_mm else ""))
        if (self.min_wall_lines is None) == (self.min_wall_mm is None):
            raise ValueError("give min_wall_lines (the thinnest wall, in lines of line_width_mm)"
                             + ("; min_wall_mm is its old form, give only one" if self.min_wall_lines else ""))
        return self

    @property
    def line_width(self) -> float:
        return self.line_width_mm if self.line_width_mm is not None else self.resolution_mm

    @property
    def min_wall(self) -> float:
        """The thinnest wall, mm."""
        return self.min_wall_lines * self.line_width if self.min_wall_lines is not None else self.min_wall_mm


class Material(Strict):
    name: Annotated[str, Field(min_length=1, max_length=200)]
    """The material's name (bill of materials, manifest)."""
    density_g_cm3: Density
    """Density, for the masses in the bill, the manifest and (where a kit balances) the centres of mass."""


AUTO_PLAY_START_MM = 0.05  # backlash_per_gear_mm: auto is built and checked at this value first (docs/tolerance.md)


class DesignHeader(Strict):
    """What every design file starts with, whatever its kind (each kind's design extends it)."""

    kind: str
    """The mechanism this file designs: its kind selects the other keys."""
    name: Name
    """The design's name and its default output folder `out/<name>/`: a plain file name (letters, digits, _ . -; at
    most 100 characters)."""
    description: Text = ""
    """Free text about the design for whoever reads the file (partgen does not use it)."""
    printer: Annotated[str, Field(min_length=1, max_length=500)]
    """The printer the kit is made for and checked against: a shipped profile's name (prusa_mk4) or a .yaml profile
    in the design's folder, relative to it (--printer overrides it)."""
    material: Material
    """The printing material: its name and density, for the masses."""


class PlateChecks(Strict):
    """What every kind's `check` block starts with: how its build plates are packed. Each kind extends
    it (with its own ``samples`` and what else its check holds); one default for every kind."""

    plate_margin_mm: Gap = 5.0
    """Gap left between parts packed on a build plate (the plates check and the 3MF plates), mm."""


class MotionChecks(PlateChecks):
    """What `partgen check` holds a kit of gears and joints to over its motion (the shared checks:
    the sweep, the meshes, the fits, printability, the plates); each kind that uses them extends this
    with its own ``samples``. One set of defaults for every kind."""

    interference_tolerance_mm3: Annotated[float, Field(ge=0, le=100)] = 0.001
    """Overlap volume between two parts at a sampled angle above which check fails them as colliding (smaller is
    numerical noise)."""
    min_clearance_mm: Gap = 0.3
    """Least gap between two parts not meant to touch (meshes and joints have their own checks), in the plane and
    between layers, over the motion; where a kind sizes hubs or bosses by it, it bounds them too."""
    min_contact_ratio: Annotated[float, Field(ge=1.0, le=3.0)] = 1.2
    """Least transverse contact ratio of every mesh (1.2: at least 1.2 tooth pairs in contact on average)."""
    min_tip_width_roads: Annotated[float, Field(ge=0.5, le=10)] = 3.0
    """Least tooth tip width, in extruded lines (× the printer's line_width_mm): 3 by default, 2 for a fine
    nozzle's small teeth, where the design says so."""


class ToleranceTarget(Strict):
    """What ``auto`` play is chosen for: the least play with P(jam) at most this on the design's
    printer (the linear study, gears seated by their meshes)."""

    max_jam_probability: Annotated[float, Field(gt=0, le=1)] = 0.01
    """Largest acceptable probability (0–1) that a print on the design's printer jams: `backlash_per_gear_mm: auto`
    chooses the least play meeting it, and check warns above it."""


def nested_models(model: type[BaseModel]) -> list[type[BaseModel]]:
    """``model`` and every model its fields hold (in lists, mappings, unions), each once, in reading
    order (the config reference's tables, the test that every field is described)."""
    out, todo = [], [model]
    while todo:
        m = todo.pop(0)
        if m in out:
            continue
        out.append(m)
        for f in m.model_fields.values():
            stack = [f.annotation]
            while stack:
                a = stack.pop()
                if isinstance(a, type) and issubclass(a, BaseModel):
                    todo.append(a)
                stack += list(typing.get_args(a))
    return out
