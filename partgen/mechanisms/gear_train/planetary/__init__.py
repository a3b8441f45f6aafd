"""A planetary set in a frame: the ring gear standing on the bottom plate (fixed), the sun pressed on
the input shaft (D-flat, turning in the bottom plate, reached from below), N planets running on the
pins of a carrier that hangs above them, its output shaft turning in the top plate. A sub-slice of
the gear train (``kind: gear_train`` with ``planetary:``).

Stacking (z up, the bottom plate's top at 0; g axial gap, f face width, t plate thickness): the
gears span [g, g + f]; the sun rests on a thrust ring round the input hole, the planets on a track
(an annulus on the radius of their centres), both [0, g]; the ring stands [0, g + f]; the carrier
plate spans [Z_c, Z_c + t], Z_c = g + f + g, its pins reach down through the planets; the top plate
[Z_t, Z_t + t], Z_t = Z_c + t + g, on spacers outside the ring.

Bores (``shafts.bores: [input, output]``, common/hubs.py): the sun held on its shaft by a D-flat, a
keyway, a nut trap in its bottom face on a bought threaded rod, or a set screw through a hub under it
(then the gears, the ring's teeth, the planets' track and the carrier are raised by the hub's height
b: the gears span [g + b, g + b + f]); the carrier by a D-flat, a keyway, a nut trap in its plate's bottom
face or a set screw through its plate, out to its rim between two pins.

Files by role: ``resolve.py`` (the spec, the design findings), ``kit.py`` (parts, poses, the manifest's
design), ``motion.py`` (the carrier turned by the sun on the printed sections: the check's and the
trace's), ``checks.py`` (check), ``trace.py`` (trace), ``play.py`` (what play costs at the carrier), ``tolerance.py``, ``report.py`` (report sections,
subtitle, the bill's heading). Shared with the other sub-slices (``common/``): the hubs and their
hardware, the fits, the text ``check`` and ``trace`` print for a turning train, the output trace and
``trace --csv``, the assembly steps.
"""

from ..common import SubSlice
from ..common.checks import check_text
from ..common.trace import trace_text
from . import checks, kit, report, resolve, tolerance, trace

__all__ = ["SLICE"]

SLICE = SubSlice(key="planetary", spec=resolve.PlanetarySpec, resolve=resolve.resolve_planetary, findings=resolve.findings,
                 build=kit.build_planetary, design_summary=kit.design_summary, check=checks.check_planetary, check_text=check_text,
                 trace=trace.trace, trace_text=trace_text, tolerance_model=tolerance.tolerance_model,
                 report_sections=report.report_sections, subtitle=report.subtitle, bill_text=report.bill_text)
