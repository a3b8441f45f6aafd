"""What every mechanism offers the pipeline, the CLI and export: the ``Kit`` and ``Mechanism``
protocols. A mechanism is one object (see ``partgen.mechanisms.REGISTRY``); the pipeline and the
CLI know nothing of any particular kind."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Protocol, runtime_checkable

import numpy as np

from .findings import Result
from .parts import Contact, Part
from .printer import PrinterLimits

__all__ = ["Kit", "CheckedKit", "ParamsKit", "SpecKit", "Mechanism", "OptionalHooks", "OPTIONAL_HOOKS", "Motion", "Trace", "Section", "Step",
           "TOLERANCE_HOOK", "tolerance_hook"]


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

    def poses_over(self, ts) -> dict[str, np.ndarray]:
        """name -> (N, 4, 4) poses of every part at the N values ``ts`` of the motion parameter
        (``ParamsKit`` gives it from ``poses``; a kit may compute it at once)."""
        ...


@runtime_checkable
class CheckedKit(Kit, Protocol):
    """A kit the shared checks take (``checks``: the motion sweep, meshing, fits, printability):
    besides ``Kit``, its ``params`` with ``checks`` (``checks.settings.CheckSettings``: what the
    checks hold it to), ``printer`` (``core.printer.PrinterLimits``) and ``face_width`` (mm, its
    gears' face), the ``contacts`` its parts are meant to make (``core.parts.Contact``: fits and
    meshes the checks measure instead of reporting as interference) and a part by its name."""

    @property
    def params(self) -> object: ...
    @property
    def contacts(self) -> tuple[Contact, ...]: ...

    def part(self, name: str) -> Part: ...


class ParamsKit:
    """The Kit protocol's name, printer, density and material, read from the kit's ``params``
    (a base for a mechanism's kit dataclass that keeps its parameters as ``params``), and a part
    by its name."""

    def part(self, name: str) -> Part:
        return next(p for p in self.parts if p.name == name)

    def poses_over(self, ts) -> dict[str, np.ndarray]:
        """name -> (N, 4, 4): ``poses`` at each of the N values ``ts``."""
        each = [self.poses(float(t)) for t in np.atleast_1d(np.asarray(ts, dtype=float))]
        return {name: np.stack([p[name] for p in each]) for name in (each[0] if each else {})}

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


class SpecKit(ParamsKit):
    """``ParamsKit`` for a kit dataclass that keeps its parameters as ``spec``."""

    @property
    def params(self):
        return self.spec


@dataclass(frozen=True)
class Motion:
    """The motion parameter of a mechanism: label, unit and the range a check sweeps."""

    label: str
    unit: str
    range: tuple[float, float]


@dataclass(frozen=True)
class Trace:
    """What `trace` found: figures (JSON-able), the names of the plot files the mechanism wrote into
    the ``out`` folder it was given (none without one), and the text the CLI prints. ``data``: (n, k)
    rows for ``--csv`` with ``columns``. ``animation``: the files it writes only when asked to
    animate (named whether asked or not; the rest of the trace is the same either way)."""

    stats: dict
    files: tuple = ()
    text: str = ""
    columns: tuple[str, ...] = ()
    data: np.ndarray | None = None
    animation: tuple[str, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "files", tuple(self.files))
        object.__setattr__(self, "animation", tuple(self.animation))


Section = tuple[str, str]  # (title, html) of a report page
Step = tuple[str, tuple[str, ...]]  # an assembly step: (what to do, the names of the kit's parts it uses)


class Mechanism(Protocol):
    """One kind of mechanism, as a vertical slice (schema, resolver, kit, checks, trace, report): exactly
    what the pipeline, the studies, the CLI and export call. ``tests/mechanisms/test_mechanisms.py`` holds every
    registered mechanism to these members and their signatures (and to ``OptionalHooks`` for the rest)."""

    kind: str            # the design file's ``kind:``
    title: str           # a human name for the kind
    schema: type         # the pydantic model of its design YAML
    motion: Motion       # the motion parameter: its label (the mechanism's name for its input), unit and range
    role_colours: dict   # part role -> colour (#rrggbb) in pictures, the GLB and the report
    csv_header: str      # the first line `trace --csv` writes (and recognises as its own file)
    trace_needs_kit: bool  # whether `trace` needs the built kit (else it traces the design alone)

    def resolve(self, raw) -> object:
        """The validated YAML (``config.loader.LoadedDesign``) → the mechanism's spec (mm, rad);
        ``ConfigError`` naming the key for anything the user can fix."""
        ...

    def build(self, spec, progress=None) -> Kit:
        """Every part of the kit; ``ConfigError`` (with the key) when a size leaves no part."""
        ...

    def refuse(self, spec, kit) -> None: ...                                # DesignError: `build` writes no such kit
    def findings(self, spec) -> list: ...                                  # design findings (``core.findings.Finding``)
    def design_summary(self, spec, kit) -> dict: ...                        # the manifest's "design"
    def kit_files(self, spec, kit, raw) -> dict: ...                        # name -> bytes: design.yaml (pinned), printer.yaml
    def plate_margin(self, spec) -> float: ...                              # mm between parts on a plate
    def check(self, spec, kit, samples=None, progress=None) -> Result: ...  # every check over the motion
    def trace(self, spec, kit, samples, out, animate=True) -> Trace: ...    # the motion's figures; plots into ``out``
    def csv(self, trace) -> str: ...                                        # `trace --csv`'s file (starts with csv_header)
    def trace_text(self, spec, trace, folder) -> str: ...                   # what `trace` prints
    def bill_text(self, spec, man, dest, seconds) -> str: ...               # what `build` prints (the bill)
    def check_text(self, spec, result, folder, seconds) -> str: ...         # what `check` prints
    def report_sections(self, spec, kit, result, trace, files) -> list: ...  # [(title, html)] of the report
    def subtitle(self, spec) -> str: ...                                    # the report's subtitle


class OptionalHooks(Protocol):
    """Members a mechanism may define (looked up with ``getattr``); a mechanism without one gets the
    shared default the caller names. The signature test holds any it defines to these shapes."""

    def assembly_steps(self, spec, kit) -> list:
        """[(what to do, names of the parts it uses)] in the order a maker puts the kit together
        (default ``export.assembly.default_steps``: base first, then kit order)."""
        ...

    def tolerance_model(self, spec, kit, result, accuracy_mm, seated=True):
        """``design.tolerance.MarginModel``: the margins of ``result`` (the nominal check of ``kit``) as
        linear functions of the printed features' deviations at ± accuracy_mm; ``seated``: gears where
        their meshes push them in their bores (False: centred, the worst case). Without it, `tolerance`
        refuses the kind."""
        ...

    def tolerance_exact(self, spec, kit, result, model, seated=True):
        """(task function, shared data) of `tolerance --exact N`: ``fn(shared, seed, index)`` makes one
        perturbed print of the real geometry and says whether it turns."""
        ...

    def animation_motion(self, spec, kit) -> Motion:
        """The input range ``assembly.glb`` animates over, when it is not ``motion``'s."""
        ...


OPTIONAL_HOOKS = ("assembly_steps", "tolerance_model", "tolerance_exact", "animation_motion")


TOLERANCE_HOOK = "tolerance_model"


def tolerance_hook(mechanism) -> Callable | None:
    """The mechanism's ``tolerance_model`` (bound), or None when it offers no tolerance study."""
    hook = getattr(mechanism, TOLERANCE_HOOK, None)
    return hook if callable(hook) else None
