"""The gear pair's tolerance model: the margins of one nominal check as linear functions of the
printed features' deviations (``design.tolerance``; ``δ`` a feature's deviation as a diameter).

* **Running fits** (each gear's bore on its post): radial gap ``(bore − post)/2``, + ``δ_bore/2 −
  δ_post/2``.
* **Centre distance**: the two posts of the base, each moved by its position deviation; the centre
  distance changes by their difference along the line of centres (x).
* **Where the gears sit** (``seated``, the default; docs/tolerance.md): each gear has one mesh, so
  when the mesh runs out of backlash its two-flank forces push the gears apart along the line of
  centres until the mesh runs free or the bores bottom: the centre distance the mesh can use grows
  by both gears' radial play (κ = 1 each), as printed. ``seated=False``: the gears centred on their
  posts (no play credited: the worst case).
* **Mesh**: the least backlash the check measured over the output's turn (circumferential, on the
  operating pitch circle) changes by ``2·tan α_w · Δa − (δ_1 + δ_2)/cos α_w`` (a flank moved out by
  δ/2 thickens the tooth by δ/cos α_w there); each tip-to-root clearance by ``Δa − δ_1/2 − δ_2/2``.
"""

from __future__ import annotations

import math

from ...core.findings import Result
from ...design.tolerance import Margin, MarginModel, ModelBuilder, Play, seat_credit
from .kit import PairKit

__all__ = ["tolerance_model", "operating_pressure_angle"]


def operating_pressure_angle(kit: PairKit) -> float:
    s = kit.spec
    return math.acos(min(1.0, (s.gear1.pitch_radius + s.gear2.pitch_radius) * math.cos(s.gear1.system.pressure_angle)
                         / s.centre_distance))


def tolerance_model(kit: PairKit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) for a printer accuracy of ± ``accuracy_mm``
    (``seated``: the gears pushed apart in their bores by the mesh; otherwise centred)."""
    s = kit.spec
    b = ModelBuilder()
    gap = float(result.figures["radial_gap_mm"])
    gaps = result.figures.get("radial_gaps_mm", [gap, gap])  # each gear's own (its own clearance)
    plays = []
    for gear, gap in zip(("gear1", "gear2"), gaps):
        terms = {(f"{gear} bore", "hole", gear): 0.5, (f"base {gear} post", "pin", "base"): -0.5}
        b.add(Margin(f"{gear} on its post", "joint", "radial gap", gap, "base"), terms)
        plays.append((1.0 if seated else 0.0, Play(gap, terms)))
    a = s.centre_distance
    aw = operating_pressure_angle(kit)
    alpha = s.gear1.system.pressure_angle
    da = {("base gear2 post x", "position", "base"): 1.0, ("base gear1 post x", "position", "base"): -1.0}
    credit, credit_terms = seat_credit(plays)
    for key, c in credit_terms.items():
        da[key] = da.get(key, 0.0) + c
    teeth = {("gear1 teeth", "tooth", "gear1"): 1.0, ("gear2 teeth", "tooth", "gear2"): 1.0}
    terms = {k: 2 * math.tan(aw) * v for k, v in da.items()}
    terms.update({k: -v / math.cos(aw) for k, v in teeth.items()})
    b.add(Margin("gear1/gear2", "mesh", "backlash", float(result.figures["backlash_mm"]["min"])
                 + 2 * math.tan(aw) * credit, "base", 2 * math.cos(alpha) / math.cos(aw)), terms)
    for g, h in (("gear1", "gear2"), ("gear2", "gear1")):
        tip, root = getattr(s, g).tip_radius, getattr(s, h).root_radius
        b.add(Margin("gear1/gear2", "mesh", f"tip-root {g}→{h}", a + credit - tip - root, "base"),
              {**da, **{k: -0.5 * v for k, v in teeth.items()}})
    return b.model(accuracy_mm, kit.name, "both gears seated by their mesh in their bores" if seated else "every gear centred on its post (no bore play credited)")
