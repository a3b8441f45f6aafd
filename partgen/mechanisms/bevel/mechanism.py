"""A straight bevel pair (``kind: bevel``) behind the Mechanism protocol: the adapter whose members
call into resolve.py, kit.py, checks.py (checked exactly in 3-D: manifold3d intersections of the
posed solids at phases over a tooth pitch, contact.py), trace.py (transmission error and the ratio
measured from where gear 2's flank touches gear 1's), report.py and tolerance.py."""

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
from .kit import BevelKit
from .resolve import BevelSpec, resolve_bevel
from .schema import BevelDesign

__all__ = ["Bevel", "MECHANISM"]


class Bevel:
    kind = "bevel"
    title = "straight bevel pair"
    schema = BevelDesign
    motion = Motion("input angle", "rad", (0.0, 2 * math.pi))
    csv_header = "input_rad,output_rad,transmission_error_rad,backlash_mm\n"
    trace_needs_kit = True
    role_colours = {"gear": "#4c78a8", "base": "#8c8c8c", "axle": "#e45756"}

    def resolve(self, raw: LoadedDesign) -> BevelSpec:
        return resolve_bevel(raw)

    def build(self, spec: BevelSpec, progress=None) -> BevelKit:
        return _kit.build(spec, progress)

    def refuse(self, spec: BevelSpec, kit: BevelKit) -> None:
        _kit.refuse(spec, kit)

    def findings(self, spec: BevelSpec):
        return []

    def design_summary(self, spec: BevelSpec, kit: BevelKit) -> dict:
        return _kit.design_summary(self.kind, spec, kit)

    def kit_files(self, spec: BevelSpec, kit: BevelKit, raw: LoadedDesign) -> dict[str, bytes]:
        return _kit.kit_files(spec, kit, raw)

    def plate_margin(self, spec: BevelSpec) -> float:
        return spec.plate_margin

    def check(self, spec: BevelSpec, kit: BevelKit, samples: int | None = None, progress=None) -> Result:
        return _checks.check(spec, kit, samples, progress)

    def tolerance_model(self, spec: BevelSpec, kit: BevelKit, result: Result, accuracy_mm: float,
                        seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: each
        gear where its mesh pushes it, sideways in its bore and back to its axial stop; otherwise centred
        where the check had it, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: BevelSpec, kit: BevelKit, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        return _trace.trace(self.kind, spec, kit, samples, out, animate)

    def csv(self, trace: Trace) -> str:
        return _trace.csv(self.csv_header, trace)

    def assembly_steps(self, spec: BevelSpec, kit: BevelKit) -> list[tuple[str, tuple[str, ...]]]:
        return _report.assembly_steps(spec, kit)

    def bill_text(self, spec: BevelSpec, man: dict, dest, seconds: float) -> str:
        return _report.bill_text(spec, man, dest, seconds)

    def check_text(self, spec: BevelSpec, result: Result, folder, seconds: float) -> str:
        return _checks.check_text(spec, result, folder, seconds)

    def trace_text(self, spec: BevelSpec, trace: Trace, folder) -> str:
        return _trace.trace_text(spec, trace, folder)

    def report_sections(self, spec: BevelSpec, kit: BevelKit, result: Result, trace: Trace,
                        files: dict) -> list[tuple[str, str]]:
        return _report.report_sections(spec, kit, result, trace, files)

    def subtitle(self, spec: BevelSpec) -> str:
        return _report.subtitle(spec)


MECHANISM = Bevel()
