"""A crossed helical pair (``kind: crossed_helical``) behind the Mechanism protocol: the adapter
whose members call into resolve.py, kit.py, checks.py (checked exactly in 3-D: manifold3d
intersections of the posed solids at phases over a tooth pitch, contact.py), trace.py (transmission
error and the ratio measured from where gear 2's flank touches gear 1's), report.py and
tolerance.py."""

from __future__ import annotations

import math
from pathlib import Path

from ...config.loader import LoadedDesign
from ...core.findings import Result
from ...core.protocol import Motion, Trace
from . import checks as _checks
from . import kit as _kit
from . import report as _report
from . import trace as _trace
from .kit import CrossedKit
from .resolve import CrossedSpec, resolve_crossed
from .schema import CrossedHelicalDesign

__all__ = ["CrossedHelical", "MECHANISM"]


class CrossedHelical:
    kind = "crossed_helical"
    title = "crossed helical pair"
    schema = CrossedHelicalDesign
    motion = Motion("input angle", "rad", (0.0, 2 * math.pi))
    csv_header = "input_rad,output_rad,transmission_error_rad,backlash_mm\n"
    trace_needs_kit = True
    role_colours = {"gear": "#4c78a8", "base": "#8c8c8c", "axle": "#e45756"}

    def resolve(self, raw: LoadedDesign) -> CrossedSpec:
        return resolve_crossed(raw)

    def build(self, spec: CrossedSpec, progress=None) -> CrossedKit:
        return _kit.build(spec, progress)

    def refuse(self, spec: CrossedSpec, kit: CrossedKit) -> None:
        _kit.refuse(spec, kit)

    def findings(self, spec: CrossedSpec):
        return []

    def design_summary(self, spec: CrossedSpec, kit: CrossedKit) -> dict:
        return _kit.design_summary(self.kind, spec, kit)

    def kit_files(self, spec: CrossedSpec, kit: CrossedKit, raw: LoadedDesign) -> dict[str, bytes]:
        return _kit.kit_files(spec, kit, raw)

    def plate_margin(self, spec: CrossedSpec) -> float:
        return spec.plate_margin

    def check(self, spec: CrossedSpec, kit: CrossedKit, samples: int | None = None, progress=None) -> Result:
        return _checks.check(spec, kit, samples, progress)

    def tolerance_model(self, spec: CrossedSpec, kit: CrossedKit, result: Result, accuracy_mm: float,
                        seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: the
        gears sit where their mesh pushes them in their bores; otherwise centred, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: CrossedSpec, kit: CrossedKit, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        return _trace.trace(self.kind, spec, kit, samples, out, animate)

    def csv(self, trace: Trace) -> str:
        return _trace.csv(self.csv_header, trace)

    def assembly_steps(self, spec: CrossedSpec, kit: CrossedKit) -> list[tuple[str, tuple[str, ...]]]:
        return _report.assembly_steps(spec, kit)

    def bill_text(self, spec: CrossedSpec, man: dict, dest, seconds: float) -> str:
        return _report.bill_text(spec, man, dest, seconds)

    def check_text(self, spec: CrossedSpec, result: Result, folder, seconds: float) -> str:
        return _checks.check_text(spec, result, folder, seconds)

    def trace_text(self, spec: CrossedSpec, trace: Trace, folder) -> str:
        return _trace.trace_text(spec, trace, folder)

    def report_sections(self, spec: CrossedSpec, kit: CrossedKit, result: Result, trace: Trace,
                        files: dict) -> list[tuple[str, str]]:
        return _report.report_sections(spec, kit, result, trace, files)

    def subtitle(self, spec: CrossedSpec) -> str:
        return _report.subtitle(spec)


MECHANISM = CrossedHelical()
