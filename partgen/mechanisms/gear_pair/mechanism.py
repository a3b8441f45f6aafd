"""A spur gear pair (``kind: gear_pair``) behind the Mechanism protocol: the adapter whose members
call into resolve.py, kit.py, checks.py (checked over one revolution of the output), trace.py
(transmission error from the printed outlines), report.py, tolerance.py and exact.py."""

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
from .kit import PairKit
from .resolve import PairSpec, resolve_pair
from .schema import GearPairDesign

__all__ = ["GearPair", "MECHANISM"]


class GearPair:
    kind = "gear_pair"
    title = "spur gear pair"
    schema = GearPairDesign
    motion = Motion("output angle", "rad", (0.0, 2 * math.pi))
    csv_header = "input_rad,output_rad,transmission_error_rad,backlash_mm\n"
    trace_needs_kit = True
    role_colours = {"gear": "#4c78a8", "base": "#8c8c8c"}

    def resolve(self, raw: LoadedDesign) -> PairSpec:
        return resolve_pair(raw)

    def build(self, spec: PairSpec, progress=None) -> PairKit:
        return _kit.build(spec, progress)

    def refuse(self, spec: PairSpec, kit: PairKit) -> None:
        _kit.refuse(spec, kit)

    def findings(self, spec: PairSpec):
        return []

    def design_summary(self, spec: PairSpec, kit: PairKit) -> dict:
        return _kit.design_summary(self.kind, spec, kit)

    def kit_files(self, spec: PairSpec, kit: PairKit, raw: LoadedDesign) -> dict[str, bytes]:
        return _kit.kit_files(spec, kit, raw)

    def plate_margin(self, spec: PairSpec) -> float:
        return spec.plate_margin

    def check(self, spec: PairSpec, kit: PairKit, samples: int | None = None, progress=None) -> Result:
        return _checks.check(spec, kit, samples, progress)

    def tolerance_model(self, spec: PairSpec, kit: PairKit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: gears
        sit where their meshes push them in their bores; otherwise centred, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def tolerance_exact(self, spec: PairSpec, kit: PairKit, result: Result, model, seated: bool = True):
        """(task function, shared data) of the exact Monte Carlo: ``fn(shared, seed, index)`` makes
        print ``index`` of the real geometry and says whether it jams (``exact``)."""
        from .exact import exact_print, exact_shared

        return exact_print, exact_shared(kit, result, model, seated)

    def trace(self, spec: PairSpec, kit: PairKit, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
        return _trace.trace(self.kind, spec, kit, samples, out, animate)

    def csv(self, trace: Trace) -> str:
        return _trace.csv(self.csv_header, trace)

    def assembly_steps(self, spec: PairSpec, kit: PairKit) -> list[tuple[str, tuple[str, ...]]]:
        return _report.assembly_steps(spec, kit)

    def bill_text(self, spec: PairSpec, man: dict, dest, seconds: float) -> str:
        return _report.bill_text(spec, man, dest, seconds)

    def check_text(self, spec: PairSpec, result: Result, folder, seconds: float) -> str:
        return _checks.check_text(spec, result, folder, seconds)

    def trace_text(self, spec: PairSpec, trace: Trace, folder) -> str:
        return _trace.trace_text(spec, trace, folder)

    def report_sections(self, spec: PairSpec, kit: PairKit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        return _report.report_sections(spec, kit, result, trace, files)

    def subtitle(self, spec: PairSpec) -> str:
        return _report.subtitle(spec)


MECHANISM = GearPair()
