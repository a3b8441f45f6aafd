"""What every mechanism offers the pipeline, the CLI and export: the ``Kit`` and ``Mechanism``
protocols. A mechanism is one object (see ``partgen.mechanisms.REGISTRY``); the pipeline and the
CLI know nothing of any particular kind."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Protocol, runtime_checkable

import numpy as np

from .findings import Result
from .parts import Part
from .printer import PrinterLimits

__all__ = ["Kit", "ParamsKit", "Mechanism", "Motion", "Trace", "Section", "Step", "TOLERANCE_HOOK", "tolerance_hook"]


@runtime_checkable
class Kit(Protocol):
    """A built kit: its parts and where each one is over the motion parameter."""

    @property
    def name(self) -> str: ...
    @property
    def parts(self) -> tuple[Part, ...]: ...
    @property
    def printer(self) -> PrinterLimits: ...
    @property
    def density(self) -> float: ...  # g/mm³ of the printed material
    @property
    def material(self) -> str: ...

    def poses(self, t: float = 0.0) -> dict[str, np.ndarray]:
        """name -> (4, 4) world-from-local pose of every part at motion parameter ``t``."""
        ...


class ParamsKit:
    """The Kit protocol's name, printer, density and material, read from the kit's ``params``
    (a base for a mechanism's kit dataclass that keeps its parameters as ``params``), and a part
    by its name."""

    def part(self, name: str) -> Part:
        return next(p for p in self.parts if p.name == name)

    @property
    def name(self) -> str:
        return self.params.name

    @property
    def printer(self) -> PrinterLimits:
        return self.params.printer

    @property
    def density(self) -> float:
        return self.params.density

    @property
    def material(self) -> str:
        return self.params.material


@dataclass(frozen=True)
class Motion:
    """The motion parameter of a mechanism: label, unit and the range a check sweeps."""

    label: str
    unit: str
    range: tuple[float, float]


@dataclass(frozen=True)
class Trace:
    """What `trace` found: figures (JSON-able), named files (name -> bytes, written into the plots
    folder) and the text the CLI prints. ``data``: (n, k) rows for ``--csv`` with ``columns``."""

    stats: dict
    files: dict = field(default_factory=dict)
    text: str = ""
    columns: tuple[str, ...] = ()
    data: np.ndarray | None = None


Section = tuple[str, str]  # (title, html) of a report page
Step = tuple[str, tuple[str, ...]]  # an assembly step: (what to do, the names of the kit's parts it uses)


class Mechanism(Protocol):
    """One kind of mechanism, as a vertical slice (schema, resolver, kit, checks, trace, report)."""

    kind: str
    title: str
    schema: type  # the pydantic model of its design YAML
    motion: Motion

    def resolve(self, raw) -> object:
        """The validated YAML (``config.loader.LoadedDesign``) → the mechanism's spec (mm, rad);
        ``ConfigError`` naming the key for anything the user can fix."""
        ...

    def build(self, spec, progress: Callable | None = None) -> Kit:
        """Every part of the kit; ``ConfigError`` (with the key) when a size leaves no part."""
        ...

    def refuse(self, spec, kit: Kit) -> None: ...                    # DesignError: `build` writes no such kit
    def design_summary(self, spec, kit: Kit) -> dict: ...            # the manifest's "design"
    def kit_files(self, spec, kit: Kit) -> dict[str, bytes]: ...     # design.yaml (pinned), printer.yaml
    def plate_margin(self, spec) -> float: ...                       # mm between parts on a plate
    def check(self, spec, kit: Kit, samples: int | None, progress: Callable | None) -> Result: ...
    def trace(self, spec, kit: Kit | None, samples: int | None) -> Trace: ...
    def report_sections(self, spec, kit: Kit, result: Result, trace: Trace, pictures) -> list[Section]: ...
    def bill_text(self, spec, manifest: dict) -> str: ...
    def check_text(self, spec, result: Result) -> str: ...
    # Optional: ``assembly_steps(spec, kit) -> list[Step]``, the steps in the order a maker puts the
    # kit together, each with the parts it uses (the report shows them with their pictures). A
    # mechanism without it gets ``export.assembly.default_steps`` (base first, then kit order).

    # Optional: ``animation_motion(spec, kit) -> Motion``, the input the kit's assembly.glb animates
    # over when it is not ``motion`` (the wrist: its workspace's bend, which the kit decides).

    # Optional (see ``tolerance_hook``): a mechanism that offers `partgen tolerance` defines
    # tolerance_model(spec, kit, result, accuracy_mm) -> design.tolerance.MarginModel: the margins
    # of ``result`` (the nominal check of ``kit``) that decide whether it turns, as linear functions
    # of the printed features' deviations for a printer accuracy of ± accuracy_mm.


TOLERANCE_HOOK = "tolerance_model"


def tolerance_hook(mechanism) -> Callable | None:
    """The mechanism's ``tolerance_model`` (bound), or None when it offers no tolerance study."""
    hook = getattr(mechanism, TOLERANCE_HOOK, None)
    return hook if callable(hook) else None
