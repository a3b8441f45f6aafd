"""The straight bevel pair's tolerance model: the margins of one nominal check as linear functions of
the printed features' deviations (``design.tolerance``; ``δ`` a feature's deviation as a diameter;
docs/tolerance.md "Straight bevel pair").

Geometry (``design.bevel``'s frame): the pitch cones touch along p = (sin δ_1, 0, −cos δ_1) from the
apex; their common normal there, from gear 1's cone towards gear 2's, is n = (cos δ_1, 0, sin δ_1).
A translation t of gear 2 against gear 1 moves gear 2's pitch cone (and, to first order, each flank
along the contact line, which runs through the apex) off gear 1's by ``s = t·n``, the same all
along the face; like a spur pair's centre distance it opens each flank's normal gap by ``s sin α``,
the circumferential backlash by ``2 s tan α`` (a length, the same at every section of the face).

* **Gear i moved along its own axis** away from the apex by Δ: ``s = Δ sin δ_i`` (t = −Δ u_2 for
  gear 2: −u_2·n = sin(Σ − δ_1) = sin δ_2), so the backlash opens by ``2 Δ tan α sin δ_i``.
* **Gear i moved radially** (square to its axis, in the plane of both axes) by g: ``s = g cos δ_i``.
* **Gear 2's axis** (its pin, in the block's hole) moved by d = (d_x, 0, d_z) in the base: only the
  part of d square to u_2 moves the gear (it sits against its block along u_2), ``s = d·n + (d·u_2)
  sin δ_2``: per mm of the hole's x, ``cos δ_1 − sin Σ sin δ_2`` (0 at Σ = 90°: the hole runs along
  x); of its height above the plate, ``sin δ_1 + cos Σ sin δ_2``. Gear 1's post moved along x:
  ``−cos δ_1`` (y, square to both axes, moves neither cone off the other to first order).
* **Where the backlash is least**: the check's backlash is gear 2's least angular play over the
  face, times its heel pitch radius. The design's thinning is angular (every section a scaled copy),
  but a gap of the same *length* at every section is an angle ``1/k`` larger at the section a fraction
  k of the way out from the apex: an opening counts least at the heel (k = 1), a closing most at the
  toe (k = (R − b)/R). So the mesh has two backlash margins, at the heel (a gain ``2 s tan α``) and
  at the toe (``2 s tan α / k``), both starting from the check's least backlash; the backlash is the
  least of the two (the play is linear in 1/k between them).
* **Teeth**: a gear printed with its axis upright (both do: their back face on the bed) and its
  outline ``δ/2`` fatter moves each flank ``δ/2`` along the flank's normal in the plane square to
  the axis; that normal is at ``α_t'`` from the circumferential direction, ``tan α_t' = tan α cos δ_i``
  (the flank's normal is at α from the circumference in the back-cone plane, the cone normal's
  radial part is cos δ_i), so the tooth thickens by ``δ / cos α_t'`` at every section: the heel
  backlash loses that, the toe's that over k. ``backlash_per_gear`` j thins both gears by j arc at
  the heel and k j at the toe: 2 mm of backlash per mm at either (``per_backlash``).
* **Tip-to-root** (gear i's tip cone to gear k's root cone along n; both cones pass through the
  apex, so the least is at the toe: ``k (h_f,k − h_a,i)``): + s − ``δ_i cos δ_i / 2 − δ_k cos δ_k / 2``.
* **Where the gears sit** (``seated``): a straight bevel's two-flank mesh force is 2 F sin α along n
  (the tangential parts cancel, whichever way gear 1 drives): on each gear a radial part (cos δ_i)
  and a thrust away from the apex (sin δ_i). Each gear has one mesh (κ = 1): it takes up all of its
  bore's radial play, ``s`` += ``g_i cos δ_i``; the thrust slides it back to its axial stop: gear 1
  down its post until its hub rests on the plate (gravity does it too; the check had it the axial
  gap above the plate), gear 2 along its pin until its hub meets the block's near face, ``s`` +=
  ``gap sin δ_i`` each. A hub printed longer, or the block's face nearer the apex (its position along
  u_2, and the base's outline ``δ/2`` fatter), leaves the gear that much nearer the apex.
  ``seated=False``: every gear centred in its bore and where the check had it along its shaft
  (the worst case).
* **Running fits**: gear 1's bore on the post, gear 2's on the pin: the radial gap the check
  measured, + ``δ_bore/2 − δ_post/2`` (``δ_pin/2``).
* **Clearances**: gear 1 to gear 2's pin, gear 2 to the base (the check's least gaps over a turn),
  less both outlines' growth, each body where the check had it (the seated slides close only the
  thrust faces they slide onto; gear 2 slides along its axis, level at Σ = 90°).

Not modelled — **the apex mismatch**: a shift with a part along the pitch line (gear i along its
axis moves its apex along p by Δ cos δ_i; gear 2's pin hole's height likewise) leaves the two gears'
straight teeth aimed at two apexes, and the exact 3-D check shows it costs backlash *whichever way*
(a V, not a slope: on bevel_mitre at a tooth centred, −0.16 mm per mm outwards, −0.25 to −0.39
inwards, more where two teeth share the contact), so no linear term carries it. The n-part above
is exact (tests/mechanisms/bevel/test_tolerance_bevel.py: within 5 % both ways); a pure axial shift of gear 2 opens
0.44 mm per mm against the model's 0.51 (heel) and closes 0.85–0.99 against its 0.75 (toe). The
seat's axial slides (0.35 mm along p each on the mitre pair) cost 0.06–0.14 mm of the 0.67 mm they
are credited. Also: a bore's play tilting its gear (the bores are several mm long), the block's hole
printed askew (the shaft angle off by hundredths of a degree: second order in the backlash), runout,
contact off the pitch line (the flank normal there leans by the roll angle: the linear terms are
the pitch point's).
"""

from __future__ import annotations

import math

from ...core.findings import Result
from ...design.tolerance import Margin, MarginModel, ModelBuilder, Play, seat_credit
from .kit import BevelKit

__all__ = ["tolerance_model", "per_backlash", "separation", "toe_ratio"]

PER_BACKLASH = 2.0  # both gears thinned by j at the heel (k j at a section k): 2j on gear 2's heel circle


def per_backlash(kit: BevelKit) -> float:
    """mm of backlash along gear 2's heel pitch circle per mm of ``backlash_per_gear`` (both gears thinned)."""
    return PER_BACKLASH


def toe_ratio(kit: BevelKit) -> float:
    """k at the toe: (R − b) / R, the toe's scale against the heel."""
    p = kit.spec.pair
    return (p.cone_distance - p.gears[0].face_width) / p.cone_distance


def separation(kit: BevelKit) -> dict[str, float]:
    """mm the pitch cones move apart (along n) per mm of each motion of gear 2 against gear 1:
    ``axial1``/``axial2`` (gear i along its axis, away from the apex), ``radial1``/``radial2`` (gear
    i square to its axis, away from its mate), ``hole_x``/``hole_z`` (gear 2's pin hole in the base),
    ``post_x`` (gear 1's post along x)."""
    p = kit.spec.pair
    d1, d2 = (g.pitch_angle for g in p.gears)
    S = p.shaft_angle
    tidy = lambda c: 0.0 if abs(c) < 1e-12 else c  # noqa: E731  (0 exactly where the geometry says so)
    return {"axial1": math.sin(d1), "axial2": math.sin(d2), "radial1": math.cos(d1), "radial2": math.cos(d2),
            "hole_x": tidy(math.cos(d1) - math.sin(S) * math.sin(d2)), "hole_z": tidy(math.sin(d1) + math.cos(S) * math.sin(d2)),
            "post_x": -math.cos(d1)}


def tolerance_model(kit: BevelKit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) for a printer accuracy of ± ``accuracy_mm``
    (``seated``: each gear pushed by the mesh to the side of its bore and back to its axial stop;
    otherwise centred where the check had it)."""
    s = kit.spec
    pair = s.pair
    f = result.figures
    b = ModelBuilder()
    sep = separation(kit)
    design_gap = float(f["radial_gap_mm"])
    closest = f.get("closest_mm", {})
    bores = {"gear1": ((("gear1 bore", "hole", "gear1"), 0.5), (("base post", "pin", "base"), -0.5)),
             "gear2": ((("gear2 bore", "hole", "gear2"), 0.5), (("pin2 diameter", "pin", "pin2"), -0.5))}
    plays = []
    for i, (gear, on, pair_key) in enumerate((("gear1", "the post", "gear1-base"), ("gear2", "pin2", "gear2-pin2"))):
        terms = dict(bores[gear])
        gap = min(design_gap, float(closest.get(pair_key, design_gap)))  # as measured: the bore's facets
        b.add(Margin(f"{gear} on {on}", "joint", "radial gap", gap, "base" if gear == "gear1" else "pin2"), terms)
        plays.append((sep[f"radial{i + 1}"] if seated else 0.0, Play(gap, terms)))  # κ = 1, along n: cos δ_i
    # s: the pitch cones' separation along n (mm), its terms per mm of each feature
    ds = {("base post x", "position", "base"): sep["post_x"], ("base block hole x", "position", "base"): sep["hole_x"],
          ("base block hole z", "height", "base"): sep["hole_z"]}
    credit, credit_terms = seat_credit(plays)
    if seated:  # each gear slid back to its axial stop by the thrust: the axial gap the check left
        credit += s.gap * (sep["axial1"] + sep["axial2"])
        axial = {("gear1 hub length", "height", "gear1"): -sep["axial1"],
                 ("gear2 hub length", "height", "gear2"): -sep["axial2"],
                 ("base block face", "position", "base"): -sep["axial2"],  # its place along u_2, towards the apex
                 ("base outline", "outline", "base"): -0.5 * sep["axial2"]}
        for key, c in axial.items():
            credit_terms[key] = credit_terms.get(key, 0.0) + c
    for key, c in credit_terms.items():
        ds[key] = ds.get(key, 0.0) + c
    ds = {k: v for k, v in ds.items() if v != 0.0}
    tan_a = math.tan(pair.pressure_angle)
    teeth = {"gear1": ("gear1 teeth", "tooth", "gear1"), "gear2": ("gear2 teeth", "tooth", "gear2")}
    thicken = {g: 1.0 / math.cos(math.atan(tan_a * math.cos(t.pitch_angle))) for g, t in zip(teeth, pair.gears)}
    least = float(f["backlash_mm"]["min"])
    for where, k in (("heel", 1.0), ("toe", toe_ratio(kit))):
        slope = 2 * tan_a / k  # backlash (on gear 2's heel pitch circle, as the check measures it) per mm of s
        terms = {key: slope * c for key, c in ds.items()}
        for g in teeth:
            terms[teeth[g]] = -thicken[g] / k
        b.add(Margin("gear1/gear2", "mesh", f"backlash ({where})", least + slope * credit, "base", PER_BACKLASH), terms)
    gears = {"gear1": s.gear1, "gear2": s.gear2}
    k_toe = toe_ratio(kit)
    for g, h in (("gear1", "gear2"), ("gear2", "gear1")):
        nominal = k_toe * (gears[h].dedendum - gears[g].addendum)
        b.add(Margin("gear1/gear2", "mesh", f"tip-root {g}→{h}", nominal + credit, "base"),
              {**ds, teeth[g]: -0.5 * math.cos(gears[g].pitch_angle), teeth[h]: -0.5 * math.cos(gears[h].pitch_angle)})
    for pa, pb in (("gear1", "pin2"), ("gear2", "base")):  # (gear1–base, gear2–pin2: the running fits above)
        if f"{pa}-{pb}" not in closest:
            continue
        other = ("pin2 diameter", "pin", "pin2") if pb == "pin2" else ("base outline", "outline", "base")
        b.add(Margin(f"{pa}–{pb}", "clearance", "gap", float(closest[f"{pa}-{pb}"]), pb),
              {teeth[pa]: -0.5, other: -0.5})
    return b.model(accuracy_mm, kit.name, "both gears seated by their mesh: sideways in their bores, back to their "
                   "axial stops" if seated else "every gear centred on its shaft where the check had it (no play credited)")
