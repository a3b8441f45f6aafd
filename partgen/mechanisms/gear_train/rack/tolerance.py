"""The rack and pinion's tolerance model (``common/tolerance.py`` for the model's terms, docs/tolerance.md
"Gear trains"):

* **The rack**: the pinion's axis (its shaft in the base) to the rail's face less the rack's depth
  from its back to its pitch line; the rack pressed back on its rail by a tight mesh takes the
  rail's running gap (its play).
"""

from __future__ import annotations

import math

from ....core.findings import Result
from ....design.tolerance import Margin, MarginModel, ModelBuilder
from ..common.tolerance import add_term, gap_margins, running_fits, tooth
from .kit import RackKit
from .resolve import RackSpec

__all__ = ["tolerance_model"]


def tolerance_model(kit: RackKit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) for a printer accuracy of ± ``accuracy_mm``
    (``seated``: the pinion's shaft and the rack where their mesh pushes them; otherwise centred)."""
    s: RackSpec = kit.params
    b = ModelBuilder()
    plays = running_fits(b, kit, result)
    row = result.figures.get("rack_mesh", {})
    alpha = s.system.pressure_angle
    # the pinion's axis to the rack's pitch line (along y, the line of centres): the base's shaft hole
    # to its rail face, less the rack's depth back to pitch line (its back face moves out by half its
    # outline's deviation); the rack pressed back onto its rail takes the rail's gap
    rail_gap = s.running / 2
    da = {("frame_bottom rail face y", "position", "frame_bottom"): 1.0,
          ("frame_bottom shaft hole y", "position", "frame_bottom"): -1.0,
          ("rack outline", "outline", "rack"): -0.5}
    credit = 0.0
    if seated:
        credit += rail_gap
        if plays.get("shaft") is not None:
            credit += plays["shaft"].nominal
            for k, v in plays["shaft"].terms.items():
                add_term(da, k, v)
    # the rack's flanks are straight at α: Δa moves the backlash by 2 tan α · Δa, the teeth by 1/cos α
    terms = {k: 2 * math.tan(alpha) * v for k, v in da.items()}
    add_term(terms, tooth("pinion"), -1.0 / math.cos(alpha))
    add_term(terms, tooth("rack"), -1.0 / math.cos(alpha))
    lash = row.get("backlash_mm", {})
    b.add(Margin("pinion/rack", "mesh", "backlash", float(lash.get("min", 0.0)) + 2 * math.tan(alpha) * credit,
                 "frame", 2.0), terms)
    for key, value in row.get("tip_root_mm", {}).items():
        t = dict(da)
        add_term(t, tooth("pinion"), -0.5)
        add_term(t, tooth("rack"), -0.5)
        b.add(Margin("pinion/rack", "mesh", f"tip-root {key.replace('->', '→')}", float(value) + credit,
                     "frame"), t)
    gap_margins(b, kit, result, {frozenset(("pinion", "rack"))}, lambda name: None)
    return b.model(accuracy_mm, kit.name, "the pinion's shaft and the rack seated by their mesh" if seated else "the pinion's shaft and the rack centred (no play credited)")
