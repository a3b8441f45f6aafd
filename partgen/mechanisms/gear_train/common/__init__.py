"""What the gear train's three sub-slices (``stages/``, ``planetary/``, ``rack/``) share, by role:

* ``hubs.py``: how a gear part holds its shaft (``shafts.bores``): each bore's feature and hardware, sized.
* ``kit.py``: those features and the bought hardware as parts (cutters, a hubbed gear, a turning
  shaft, nuts, rods and set screws, their contacts), the manifest's summary of a hub, and the kit's
  ``refuse``, ``kit_files`` and ``plate_margin`` (the same for every sub-slice).
* ``resolve.py``: the shafts' fits from the design or the printer, the checks' settings, the gear
  rules' design findings.
* ``checks.py``: the text ``check`` prints for a turning train (the stages' and the planetary's).
* ``trace.py``: the output against the input of a turning train (the stages' and the planetary's
  trace), its plot, ``trace --csv`` and the text ``trace`` prints.
* ``tolerance.py``: the margins every sub-slice's tolerance model is made of (running fits, external
  meshes, the clearances over the motion).
* ``play.py``: what play costs at the output — a lost motion as shares of backlash and bores' play over
  the tolerance model's features: nominal, worst case, 95 % of prints, the transmission-error band.
* ``report.py``: the bill ``build`` prints (its lines per part), the assembly steps and the report's
  "What play costs".

This package's ``SubSlice`` is what each sub-slice's package gives ``mechanism.py`` (its ``SLICE``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

__all__ = ["KIND", "SubSlice"]

KIND = "gear_train"  # the design file's ``kind:`` (mechanism.GearTrain.kind, the manifest's and the trace's "kind")


@dataclass(frozen=True)
class SubSlice:
    """One arrangement of the gear train (the stages, the planetary set, the rack and pinion) as
    ``mechanism.GearTrain`` dispatches to it: the design key that selects it, its spec's type, and the
    functions behind the protocol's members (``core.protocol.Mechanism``) that differ by arrangement."""

    key: str                 # the design's key that selects it: train, planetary or rack
    spec: type               # the type of the spec its resolve returns
    resolve: Callable        # (loaded) -> spec
    findings: Callable       # (spec) -> [Finding]
    build: Callable          # (spec, progress) -> kit
    design_summary: Callable  # (spec) -> the manifest's "design"
    check: Callable          # (kit, samples, progress) -> Result
    check_text: Callable     # (spec, result, folder, seconds) -> str
    trace: Callable          # (spec, kit, samples, out) -> Trace
    trace_text: Callable     # (spec, trace, folder) -> str
    tolerance_model: Callable  # (kit, result, accuracy_mm, seated) -> MarginModel
    report_sections: Callable  # (spec, kit, result, trace, files) -> [(title, html)]
    subtitle: Callable       # (spec) -> str
    bill_text: Callable      # (spec, man, dest, seconds) -> str
