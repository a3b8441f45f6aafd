"""The crossed helical pair's tolerance model (the crossed pair and the worm drive): the margins of
one nominal check as linear functions of the printed features' deviations (``design.tolerance``;
``δ`` a feature's deviation as a diameter; docs/tolerance.md "Crossed helical pair and worm").

* **Running fits**: gear 1's bore on the base's post, gear 2's bore on its printed pin: the radial
  gap the check measured (the least gap to the base and to the pin: the bores' facets), + ``δ_bore/2 − δ_post/2`` (``δ_pin/2`` for the pin).
* **The centre distance** (the common perpendicular of the two axes, along x): gear 1's axis is the
  post (its x, a position feature of the base); gear 2's is its pin, pressed through the two
  blocks' holes: the mean of the two holes' x. A hole's height moves gear 2's axis along gear 1's
  (z), which only moves the contact along gear 1's face (not modelled: the faces are wide enough for it).
* **Where the gears sit** (``seated``, the pair's model: ``design.tolerance``): a tight mesh touches
  on both flanks; the two normal forces' tangential and axial parts cancel and their radial parts
  (``sin α_n`` each) add along the common perpendicular, whichever way gear 1 drives: they push the
  gears apart until the mesh runs free or the bores bottom. Each gear has one mesh, so each gives
  it all of its radial play (κ = 1; the pin stays in its press fit). ``seated=False``: both gears
  centred (the worst case).
* **The mesh** (point contact; each gear meshes with the one normal rack both are cut by): the
  centre distance growing by ``Δa`` opens the normal backlash by ``2 Δa sin α_n``, the circumferential
  backlash the check measures along gear 2's pitch circle by ``2 Δa tan α_n / cos β_2``. A gear's
  transverse section printed ``δ/2`` fatter (it prints with its axis upright: its outline is an xy
  outline) thickens its tooth along its transverse pitch circle by ``δ / cos α_t``, its normal
  circular thickness by ``δ cos β / cos α_t``: gear 2's backlash loses ``δ_i cos β_i / (cos α_t,i cos β_2)``.
  ``backlash_per_gear`` thins each gear by ``j`` at its reference circle: the backlash grows by
  ``(cos β_1 + cos β_2) / cos β_2`` per mm of it. Each tip-to-root clearance (gear i's tip cylinder to
  gear k's root cylinder along the common perpendicular) by ``Δa − δ_i/2 − δ_k/2``.
* **Clearances**: gear 1 to gear 2's pin and gear 2 to the base's blocks and plate (the least gaps
  the check measured over a turn), less the two outlines' growth, each body centred (its radial play
  moves it by at most 0.05–0.15 mm against the 0.5 mm axial gaps the frame leaves).

Not modelled: the shafts' angle printed askew (the blocks' holes tilted: it changes the working
helix angles by a few hundredths of a degree and the backlash to second order), the gears' runout,
the worm's lead printed off (its layers stack the thread's pitch in z: a height, held by the
printer's z steps far better than its xy outline).
"""

from __future__ import annotations

import math

from ...core.findings import Result
from ...design.tolerance import Margin, MarginModel, ModelBuilder, Play, seat_credit
from .kit import CrossedKit

__all__ = ["tolerance_model", "per_backlash"]


def per_backlash(kit: CrossedKit) -> float:
    """mm of backlash along gear 2's pitch circle per mm of ``backlash_per_gear`` (both gears thinned)."""
    b1, b2 = kit.spec.pair.helix
    return (math.cos(b1) + math.cos(b2)) / math.cos(b2)


def tolerance_model(kit: CrossedKit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) for a printer accuracy of ± ``accuracy_mm``
    (``seated``: the gears pushed apart in their bores by the mesh; otherwise centred)."""
    s = kit.spec
    pair = s.pair
    f = result.figures
    b = ModelBuilder()
    design_gap = float(f["radial_gap_mm"])
    closest = f.get("closest_mm", {})
    bores = {"gear1": ((("gear1 bore", "hole", "gear1"), 0.5), (("base post", "pin", "base"), -0.5)),
             "gear2": ((("gear2 bore", "hole", "gear2"), 0.5), (("pin2 diameter", "pin", "pin2"), -0.5))}
    plays = []
    for gear, on, pair_key in (("gear1", "the post", "gear1-base"), ("gear2", "pin2", "gear2-pin2")):
        terms = dict(bores[gear])
        gap = min(design_gap, float(closest.get(pair_key, design_gap)))  # as measured: the bore's facets
        b.add(Margin(f"{gear} on {on}", "joint", "radial gap", gap, "base" if gear == "gear1" else "pin2"), terms)
        plays.append((1.0 if seated else 0.0, Play(gap, terms)))
    # the centre distance: gear 2's pin (the mean of its two holes in the blocks) less gear 1's post, along x
    da = {("base block1 hole x", "position", "base"): 0.5, ("base block2 hole x", "position", "base"): 0.5,
          ("base post x", "position", "base"): -1.0}
    credit, credit_terms = seat_credit(plays)
    for key, c in credit_terms.items():
        da[key] = da.get(key, 0.0) + c
    an = pair.normal_pressure_angle
    b1, b2 = pair.helix
    slope = 2 * math.tan(an) / math.cos(b2)  # backlash along gear 2's pitch circle per mm of centre distance
    teeth = {"gear1": ("gear1 teeth", "tooth", "gear1"), "gear2": ("gear2 teeth", "tooth", "gear2")}
    terms = {k: slope * v for k, v in da.items()}
    for i, g in enumerate(("gear1", "gear2")):
        terms[teeth[g]] = -math.cos(pair.helix[i]) / (math.cos(pair.systems[i].pressure_angle) * math.cos(b2))
    b.add(Margin("gear1/gear2", "mesh", "backlash", float(f["backlash_mm"]["min"]) + slope * credit, "base",
                 per_backlash(kit)), terms)
    gears = {"gear1": s.gear1, "gear2": s.gear2}
    for g, h in (("gear1", "gear2"), ("gear2", "gear1")):
        tip, root = gears[g].tip_radius, gears[h].root_radius
        b.add(Margin("gear1/gear2", "mesh", f"tip-root {g}→{h}", s.centre_distance + credit - tip - root, "base"),
              {**da, teeth[g]: -0.5, teeth[h]: -0.5})
    for pa, pb in (("gear1", "pin2"), ("gear2", "base")):  # (gear1–base, gear2–pin2: the running fits above)
        if f"{pa}-{pb}" not in closest:
            continue
        other = ("pin2 diameter", "pin", "pin2") if pb == "pin2" else ("base outline", "outline", "base")
        b.add(Margin(f"{pa}–{pb}", "clearance", "gap", float(closest[f"{pa}-{pb}"]), pb),
              {teeth[pa]: -0.5, other: -0.5})
    return b.model(accuracy_mm, kit.name, "both gears seated by their mesh in their bores" if seated else "every gear centred on its post (no bore play credited)")
