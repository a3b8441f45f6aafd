"""A gear train of stages (``kind: gear_train`` with ``train:``), a sub-slice of the gear train: designed
from a table of stages (teeth, ratios, centre distances, an overall ratio), built as a frame of two
plates with spacers, a shaft per gear axis, a gear part per shaft — two gears on one hub where the
stage is compound; checked over one turn of the slowest shaft, traced on its printed outlines.

Stacking (z up, the bottom plate's top face at z = 0; g = axial gap, f = face width, t = plate
thickness): gear layer j spans [L_j, L_j + f], L_j = g + j(f + g); a stage's two gears share a
layer; a compound shaft's two gears sit in consecutive layers, joined by a web through the gap.
Each gear part rests on a thrust ring (height g, the hub's radius) of the bottom plate; a part whose
lowest gear is above layer 0 stands on a hub down to that ring. The top plate spans [Z_t, Z_t + t],
Z_t = L_last + f + g. Spacers stand on the bottom plate at the corners outside every tip circle and
press into the top plate. A shaft is a fixed pin pressed into both plates (its gear bore round,
running on it) or a shaft turning in both plates (its gear pressed on a D-flat).

Files by role: ``resolve.py`` (the spec: teeth, shifts, shaft centres, z-layers; the design findings),
``kit.py`` (parts, poses, the manifest's design), ``motion.py`` (the train turned on its printed
outlines: the check's backlash at the output, the trace), ``checks.py`` (check), ``trace.py`` (trace),
``play.py`` (what play costs: the lost motion at the output, in the trace and the report),
``tolerance.py``, ``report.py`` (report sections, subtitle, the bill's heading). Shared with the other
sub-slices (``common/``): the hubs and their hardware, the fits, the text ``check`` and ``trace`` print
for a turning train, the output trace and ``trace --csv``, the assembly steps.
"""

from ..common import SubSlice
from ..common.checks import check_text
from ..common.trace import trace_text
from . import checks, kit, report, resolve, tolerance, trace

__all__ = ["SLICE"]

SLICE = SubSlice(key="train", spec=resolve.TrainSpec, resolve=resolve.resolve_train, findings=resolve.findings,
                 build=kit.build_train, design_summary=kit.design_summary, check=checks.check_train, check_text=check_text,
                 trace=trace.trace, trace_text=trace_text, tolerance_model=tolerance.tolerance_model,
                 report_sections=report.report_sections, subtitle=report.subtitle, bill_text=report.bill_text)
