"""The rack and pinion (``kind: gear_train`` with ``rack:``), a sub-slice of the gear train: a rack and
pinion on a base: the pinion pressed on a D-flat shaft turning in the base, the rack sliding along x
on a strip of the base, held against the pinion by a rail behind it. Resolver, kit, check (the mesh
over the whole travel on the printed sections, the rack mesh rules, every pair of parts, fits,
printability) and trace (the rack's travel against the pinion's angle).

Frame: the pinion's centre at the origin, the rack's pitch line at y = −(r_p + x m), its teeth up;
turning by θ (counter-clockwise), the pinion moves the rack by r_p θ along +x. z: the base's top at
0; the pinion and the rack span [g, g + f]; the pinion rests on a thrust ring round its shaft, the
rack on a strip under its body, both [0, g]; the rail stands [0, g + f].

Bores (``shafts.bores: [pinion]``, common/hubs.py): a D-flat, a keyway, a nut trap in the pinion's bottom face
on a bought threaded rod, or a set screw through a hub under it (then the pinion, the rack, its strip
and the rail are raised by the hub's height b).

Files by role: ``resolve.py`` (the spec, the design findings), ``kit.py`` (parts, poses, the manifest's
design), ``motion.py`` (the rack driven by the pinion on their printed sections: the check's and the
trace's), ``checks.py`` (check and its text), ``trace.py`` (trace and its text), ``play.py`` (what play costs at
the rack), ``tolerance.py``,
``report.py`` (report sections, subtitle, the bill's heading). Shared with the other sub-slices
(``common/``): the hubs and their hardware, the fits, ``trace --csv``, the assembly steps.
"""

from ..common import SubSlice
from . import checks, kit, report, resolve, tolerance, trace

__all__ = ["SLICE"]

SLICE = SubSlice(key="rack", spec=resolve.RackSpec, resolve=resolve.resolve_rack, findings=resolve.findings,
                 build=kit.build_rack, design_summary=kit.design_summary, check=checks.check_rack,
                 check_text=checks.check_text, trace=trace.trace, trace_text=trace.trace_text, tolerance_model=tolerance.tolerance_model,
                 report_sections=report.report_sections, subtitle=report.subtitle, bill_text=report.bill_text)
