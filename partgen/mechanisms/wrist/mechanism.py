"""The wrist gear pair (``kind: wrist``) behind the Mechanism protocol: two spherical gears with
dome teeth and swept sockets that roll on each other over a bend workspace.

The thin adapter (docs: the house layout): each member is one call into the file of its role —
``resolve.py``, ``kit.py``, ``checks.py`` (with ``mate.py``), ``trace.py``, ``tolerance.py``,
``report.py``."""

from __future__ import annotations

import math
from pathlib import Path

from ...config.loader import LoadedDesign
from ...core.findings import Result
from ...core.protocol import Motion, Trace
from . import kit as _kit
from . import resolve as _resolve
from .kit import WristKit
from .schema import WristDesign
from .spec import WristSpec

__all__ = ["Wrist", "MECHANISM"]


class Wrist:
    kind = "wrist"
    title = "wrist gear pair"
    schema = WristDesign
    motion = Motion("θ on gear 1", "rad", (0.0, math.pi / 2))
    csv_header = "theta_rad,ratio,phi_rad\n"
    trace_needs_kit = False
    role_colours = {"wrist_gear": "#4c78a8"}

    def resolve(self, raw: LoadedDesign) -> WristSpec:
        return _resolve.resolve_wrist(raw)

    def animation_motion(self, spec: WristSpec, kit: WristKit) -> Motion:
        """The assembly's animation bends the pair over its workspace: θ from 0 to ``theta_max``."""
        return _kit.animation_motion(self.motion, spec, kit)

    def build(self, spec: WristSpec, progress=None) -> WristKit:
        return _kit.build(spec, progress)

    def refuse(self, spec: WristSpec, kit: WristKit) -> None:
        return _kit.refuse(spec, kit)

    def findings(self, spec: WristSpec):
        return _resolve.findings(spec)

    def design_summary(self, spec: WristSpec, kit: WristKit) -> dict:
        return _kit.design_summary(self.kind, spec, kit)

    def kit_files(self, spec: WristSpec, kit: WristKit, raw: LoadedDesign) -> dict[str, bytes]:
        return _kit.kit_files(spec, kit, raw)

    def plate_margin(self, spec: WristSpec) -> float:
        return _kit.plate_margin(spec)

    def check(self, spec: WristSpec, kit: WristKit, samples: int | None = None, progress=None) -> Result:
        from .checks import check

        return check(spec, kit, samples, progress)

    def check_text(self, spec: WristSpec, result: Result, folder, seconds: float) -> str:
        from .checks import check_text

        return check_text(spec, result, folder, seconds)

    def tolerance_model(self, spec: WristSpec, kit: WristKit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of each dome tooth in its socket over the workspace, and of the cross gear's mesh
        with its mate, as a ``design.tolerance.MarginModel`` (no bores run: ``seated`` changes nothing)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: WristSpec, kit, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
        """The ratio i(θ) and the mating angle φ(θ) over the valid range, the tooth rows; wrist.png/.svg."""
        from .trace import trace

        return trace(self.kind, spec, kit, samples, out, animate)

    def csv(self, trace: Trace) -> str:
        from .trace import csv

        return csv(self.csv_header, trace)

    def trace_text(self, spec: WristSpec, trace: Trace, folder) -> str:
        from .trace import trace_text

        return trace_text(spec, trace, folder)

    def assembly_steps(self, spec: WristSpec, kit) -> list[tuple[str, tuple[str, ...]]]:
        """Each gear pressed onto its D-shaft from its flat face, then brought into mesh."""
        from .report import assembly_steps

        return assembly_steps(spec, kit)

    def bill_text(self, spec: WristSpec, man: dict, dest, seconds: float) -> str:
        from .report import bill_text

        return bill_text(spec, man, dest, seconds)

    def report_sections(self, spec: WristSpec, kit: WristKit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        from .report import report_sections

        return report_sections(spec, kit, result, trace, files)

    def subtitle(self, spec: WristSpec) -> str:
        from .report import subtitle

        return subtitle(spec)


MECHANISM = Wrist()
