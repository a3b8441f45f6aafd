"""The gear chain (``kind: gear_chain``, with its belt variant) behind the Mechanism protocol: a
Fourier linkage whose links are turned by gear (or belt) stages, drawn by a pen. The adapter: its
members call into checks.py, trace.py, report.py, tolerance.py and exact.py; kit.py (build, refuse,
the manifest's design, the kit files)."""

from __future__ import annotations

import math
from pathlib import Path


from ...config.loader import LoadedDesign
from ...core.findings import Result
from ...core.protocol import Motion, Trace
from . import report as _report
from . import trace as _trace
from . import kit as _kit
from .kit import Kit
from .resolve import ChainSpec, resolve_spec
from .schema import Design

__all__ = ["GearChain", "MECHANISM"]

CSV_HEADER = "theta_rad,x_mm,y_mm\n"
ROLE_COLOURS = {"gear": "#4c78a8", "link": "#f58518", "base": "#8c8c8c", "leg": "#b0b0b0", "axle": "#54a24b",
                "crank": "#e45756", "pen_holder": "#b279a2", "pulley": "#4c78a8", "idler": "#72b7b2"}


class GearChain:
    kind = "gear_chain"
    title = "gear chain"
    schema = Design
    motion = Motion("crank angle", "rad", (0.0, 2 * math.pi))
    csv_header = CSV_HEADER
    trace_needs_kit = False
    role_colours = ROLE_COLOURS

    def resolve(self, raw: LoadedDesign) -> ChainSpec:
        return resolve_spec(raw)


    def build(self, spec: ChainSpec, progress=None) -> Kit:
        return _kit.build(spec, progress)

    def refuse(self, spec: ChainSpec, kit: Kit) -> None:
        _kit.refuse(spec, kit)

    def findings(self, spec: ChainSpec):
        """What the design rules found before any geometry (build prints them)."""
        return list(spec.mechanism.findings)

    def design_summary(self, spec: ChainSpec, kit: Kit) -> dict:
        return _kit.design_summary(spec, kit, self.kind)

    def kit_files(self, spec: ChainSpec, kit: Kit, raw: LoadedDesign) -> dict[str, bytes]:
        return _kit.kit_files(spec, kit, raw)

    def plate_margin(self, spec: ChainSpec) -> float:
        return spec.params.checks.plate_margin

    def check(self, spec: ChainSpec, kit: Kit, samples: int | None = None, progress=None) -> Result:
        from .checks import check_kit

        return check_kit(kit, samples, progress)

    def tolerance_model(self, spec: ChainSpec, kit: Kit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: gears
        sit where their meshes push them in their bores; otherwise centred, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def tolerance_exact(self, spec: ChainSpec, kit: Kit, result: Result, model, seated: bool = True):
        """(task function, shared data) of the exact Monte Carlo: ``fn(shared, seed, index)`` makes
        print ``index`` (its meshes on the printed gear outlines, its fits and clearances by their
        margins) and says whether it jams (``exact``)."""
        from .exact import exact_print, exact_shared

        return exact_print, exact_shared(kit, result, model, seated)

    def trace(self, spec: ChainSpec, kit: Kit | None, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        return _trace.trace(spec, kit, samples, out, animate)

    def csv(self, trace: Trace) -> str:
        return _trace.csv(self.csv_header, trace)

    def bill_text(self, spec: ChainSpec, man: dict, dest, seconds: float) -> str:
        return _report.bill_text(spec, man, dest, seconds)

    def check_text(self, spec: ChainSpec, result: Result, folder, seconds: float) -> str:
        from .checks import check_text

        return check_text(spec, result, folder, seconds)

    def trace_text(self, spec: ChainSpec, trace: Trace, folder) -> str:
        return _trace.trace_text(spec, trace, folder)

    def assembly_steps(self, spec: ChainSpec, kit: Kit) -> list[tuple[str, tuple[str, ...]]]:
        return _report.assembly_steps(spec, kit)

    def report_sections(self, spec: ChainSpec, kit: Kit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        return _report.report_sections(spec, kit, result, trace, files)

    def subtitle(self, spec: ChainSpec) -> str:
        return _report.subtitle(spec)


MECHANISM = GearChain()
