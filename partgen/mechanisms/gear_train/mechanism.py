"""A gear train in a frame (``kind: gear_train``) behind the Mechanism protocol: designed from a table
of stages (teeth, ratios, centre distances, an overall ratio), built, checked over one turn of the
slowest shaft, traced on its printed outlines (output against input: transmission error in
arcminutes, the ratio measured, the backlash at the output) and reported; or a planetary set, or a
rack and pinion.

The thin adapter: each member calls into the sub-slice the design selects — ``stages/`` (a row of
stages, the design's ``train``), ``planetary/`` (``planetary``), ``rack/`` (``rack``), each given as a
``common.SubSlice`` — or into ``common/`` where the three agree."""

from __future__ import annotations

import math
from pathlib import Path

from ...config.loader import LoadedDesign
from ...core.findings import Finding, Result
from ...core.protocol import Motion, Trace
from ...errors import DesignError
from .common import KIND, SubSlice
from .common import kit as common_kit
from .common import report as common_report
from .common import trace as common_trace
from .planetary import SLICE as PLANETARY
from .rack import SLICE as RACK
from .schema import GearTrainDesign
from .stages import SLICE as STAGES

__all__ = ["GearTrain", "MECHANISM"]

_SLICES = (STAGES, PLANETARY, RACK)


def _selected(design: GearTrainDesign) -> SubSlice:
    """The sub-slice the design selects: its rack, its planetary set, or its train of stages."""
    return RACK if design.rack is not None else PLANETARY if design.planetary is not None else STAGES


def _of(spec) -> SubSlice:
    """The sub-slice whose resolver made ``spec``."""
    return next(s for s in _SLICES if isinstance(spec, s.spec))


class GearTrain:
    kind = KIND
    title = "gear train"
    schema = GearTrainDesign
    motion = Motion("input angle", "rad", (0.0, 2 * math.pi))
    csv_header = "input_rad,output_rad,transmission_error_arcmin,backlash_arcmin\n"
    trace_needs_kit = True
    role_colours = {"gear": "#4c78a8", "frame": "#8c8c8c", "axle": "#e45756", "threaded rod": "#b0b0b0",
                    "nut": "#6f6f6f", "set screw": "#3a3a3a"}

    def resolve(self, raw: LoadedDesign):
        return _selected(raw.design).resolve(raw)

    def build(self, spec, progress=None):
        try:
            return _of(spec).build(spec, progress)
        except ValueError as e:
            raise DesignError(str(e), "shafts.diameter_mm") from None

    def refuse(self, spec, kit) -> None:
        common_kit.refuse(spec, kit)

    def findings(self, spec) -> list[Finding]:
        """What `build` warns about (the rules `check` fails on) and notes (undercut gears)."""
        return _of(spec).findings(spec)

    def design_summary(self, spec, kit) -> dict:
        return _of(spec).design_summary(spec)

    def kit_files(self, spec, kit, raw: LoadedDesign) -> dict[str, bytes]:
        return common_kit.kit_files(raw)

    def plate_margin(self, spec) -> float:
        return common_kit.plate_margin(spec)

    def check(self, spec, kit, samples: int | None = None, progress=None) -> Result:
        return _of(spec).check(kit, samples, progress)

    def tolerance_model(self, spec, kit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (every mesh,
        fit and clearance; the planetary's assembly with printed teeth; the rack; ``seated``: bodies where
        their meshes push them in their bores, otherwise centred)."""
        return _of(spec).tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec, kit, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
        """Output angle against input angle over one turn of the output, from the printed outlines (a
        rack's travel against the pinion's angle over its travel)."""
        return _of(spec).trace(spec, kit, samples, out)

    def csv(self, trace: Trace) -> str:
        return common_trace.csv(self.csv_header, trace)

    def bill_text(self, spec, man: dict, dest, seconds: float) -> str:
        return _of(spec).bill_text(spec, man, dest, seconds)

    def check_text(self, spec, result: Result, folder, seconds: float) -> str:
        return _of(spec).check_text(spec, result, folder, seconds)

    def trace_text(self, spec, trace: Trace, folder) -> str:
        return _of(spec).trace_text(spec, trace, folder)

    def assembly_steps(self, spec, kit) -> list[tuple[str, tuple[str, ...]]]:
        """The frame's bottom plate first; then each shaft with the gears and hardware it carries; then the
        planets and their carrier, or the rack on its rail; the top plate last (``common.report``)."""
        return common_report.assembly_steps(spec, kit)

    def report_sections(self, spec, kit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        return _of(spec).report_sections(spec, kit, result, trace, files)

    def subtitle(self, spec) -> str:
        return _of(spec).subtitle(spec)


MECHANISM = GearTrain()
