"""The balanced Bennett butterfly (``kind: bennett_butterfly``) behind the Mechanism protocol: the
adapter whose members call into kit.py (build, refuse, what the kit folder holds), checks.py,
trace.py, report.py (the bill, the report, the assembly steps) and tolerance.py."""

from __future__ import annotations

import math
from pathlib import Path

from ...config.loader import LoadedDesign
from ...core.protocol import Motion, Trace
from . import kit as _kit
from . import report as _report
from . import trace as _trace
from .kit import BennettKit
from .params import BennettParams
from .resolve import resolve_bennett
from .schema import BennettDesign

__all__ = ["BennettButterfly", "MECHANISM"]


class BennettButterfly:
    kind = "bennett_butterfly"
    title = "balanced Bennett butterfly"
    schema = BennettDesign
    motion = Motion("angle between links 1 and 4", "rad", (0.0, math.pi))
    csv_header = "angle_rad,com_from_S_mm,com_from_S_solid_mm\n"
    trace_needs_kit = True
    role_colours = {"bennett_link": "#4c78a8", "bennett_base": "#bbbbbb"}

    def resolve(self, raw: LoadedDesign) -> BennettParams:
        return resolve_bennett(raw)

    def build(self, spec: BennettParams, progress=None) -> BennettKit:
        return _kit.build(spec, progress)

    def refuse(self, spec: BennettParams, kit: BennettKit) -> None:
        _kit.refuse(spec, kit)

    def findings(self, spec: BennettParams):
        return []

    def design_summary(self, spec: BennettParams, kit: BennettKit) -> dict:
        return _kit.design_summary(kit)

    def kit_files(self, spec: BennettParams, kit: BennettKit, raw: LoadedDesign) -> dict[str, bytes]:
        return _kit.kit_files(spec, kit, raw)

    def plate_margin(self, spec: BennettParams) -> float:
        return 5.0

    def check(self, spec: BennettParams, kit: BennettKit, samples: int | None = None, progress=None):
        from .checks import check

        return check(spec, kit, samples, progress)

    def tolerance_model(self, spec, kit, result, accuracy_mm: float, seated: bool = True):
        """What makes a print fail as a ``design.tolerance.MarginModel``: pins in their bores, the Bennett
        loops closing on their joints' play, and the balance as printed (no gear sits in a bore:
        ``seated`` changes nothing)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: BennettParams, kit: BennettKit, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        return _trace.trace(self.kind, spec, kit, samples, out, animate)

    def csv(self, trace: Trace) -> str:
        return _trace.csv(self.csv_header, trace)

    def assembly_steps(self, spec, kit) -> list[tuple[str, tuple[str, ...]]]:
        return _report.assembly_steps(spec, kit)

    def bill_text(self, spec, man: dict, dest, seconds: float) -> str:
        return _report.bill_text(man, dest, seconds)

    def check_text(self, spec, result, folder, seconds: float) -> str:
        from .checks import check_text

        return check_text(spec, result, folder, seconds)

    def trace_text(self, spec, trace: Trace, folder) -> str:
        return _trace.trace_text(spec, trace, folder)

    def report_sections(self, spec, kit, result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        return _report.report_sections(spec, kit, result, trace, files)

    def subtitle(self, spec) -> str:
        return _report.subtitle(spec)


MECHANISM = BennettButterfly()
