"""The least play with P(jam) at most a target, over one or two play knobs (pure numpy: mm).

A *knob* is one number of a design that opens margins when it grows: ``gears.backlash_per_gear_mm``
(each mesh's backlash) or a running clearance (each running fit's radial gap, and — gears seated by
their meshes, ``design.tolerance`` — the meshes their bores' play is credited to). The margin model
(``design.tolerance.MarginModel``) was made from one kit built with each knob at its ``start``; a
knob moves margin k by ``slope[k]`` mm per mm (exact for a clearance: a bore printed Δ larger is the
same margin change as a clearance Δ larger; first order for the backlash, as the model itself).

The search (``least_allocation``):

* **Grid.** Each knob takes whole numbers of its ``step`` from ``least`` to ``most`` steps.
* **Draws.** ``samples`` fixed prints (seed, chunk 0, the stream ``run_chunk`` draws): the same
  prints for every candidate, so a print's jam can only go away as any knob grows, and every
  comparison is of whole jam counts (no float ties).
* **Feasible.** At most ``floor(target · samples)`` jams. When even every knob at its ``most`` jams
  more (margins no knob moves — clearances between passing parts — jam more often than the
  target), the target becomes the jams at the most: the least play that reaches what the most play
  reaches (``reached: False``).
* **One knob**: a bisection finds the least feasible value exactly.
* **Two knobs**: the feasible set is a staircase (monotone in each knob); walking knob 1 down from
  its most while knob 2 steps up finds, for every value of knob 1, the least feasible knob 2 (at
  most n₁ + n₂ jam counts). Among those Pareto points the *cost* is least:
  ``Σ weight_i · value_i``, each knob's weight the mm of *play margins* it opens per mm (the sum of
  its slopes over every mesh's backlash and every running fit's radial gap: the total play the kit
  gains), compared quantised (``core.quantise``); ties go to the smaller first knob, then the
  smaller second (the knobs' stated order).

The result also says where play buys most at the choice: each knob's jams saved by one more step
and, per group (meshes, joints, clearances), the jams left.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.quantise import quantise
from .tolerance import AUTO_SAMPLES, GROUPS, MarginModel, wilson

__all__ = ["Knob", "least_allocation", "play_weight", "hole_slope"]

PLAY_WHATS = ("backlash", "radial gap")  # the margins that are the kit's play (a mesh's, a running fit's)


@dataclass(frozen=True)
class Knob:
    """One ``auto`` number: ``key`` (dotted path in the design), ``label`` (what it sets: "backlash per
    gear", "running clearance, diametral"), ``start`` (mm, what the model's kit was built with),
    ``slope`` (K,) mm of margin per mm, ``step`` mm, and the grid ``least`` … ``most`` (in steps)."""

    key: str
    label: str
    start: float
    slope: np.ndarray
    step: float
    least: int
    most: int

    def value(self, i: int) -> float:
        return round(i * self.step, 6)


def hole_slope(model: MarginModel) -> np.ndarray:
    """(K,) mm of margin per mm of *diametral running clearance*: the sum, over the bores of the
    running fits (the ``hole`` features of the ``joint`` margins), of their coefficients — a
    clearance Δ larger is every such bore printed Δ larger."""
    joint = np.array([m.group == "joint" for m in model.margins], dtype=bool)
    bores = np.array([f.kind == "hole" for f in model.features], dtype=bool)
    if joint.any():
        bores &= (model.coeff[:, joint] != 0.0).any(axis=1)
    else:
        bores[:] = False
    return model.coeff[bores].sum(axis=0) if bores.any() else np.zeros(len(model.margins))


def play_weight(model: MarginModel, slope: np.ndarray) -> float:
    """mm of play margins (every mesh's backlash, every running fit's radial gap) per mm of a knob."""
    sel = np.array([m.what.startswith(PLAY_WHATS) for m in model.margins], dtype=bool)
    return float(np.asarray(slope)[sel].sum())


def _draws(model: MarginModel, samples: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    z = rng.standard_normal((samples, len(model.features)))
    return model.nominal[None, :] + z @ (model.coeff * model.sigma[:, None])


def least_allocation(model: MarginModel, knobs: list[Knob], target: float, samples: int = AUTO_SAMPLES,
                     seed: int = 0) -> dict:
    """The least play (module docstring) as {"values": {key: mm}, "reached", "jams", "probability",
    "ci95", "cost_mm", "weights", "frontier", "buys", "groups", …}."""
    if not 1 <= len(knobs) <= 2:
        raise ValueError("one or two knobs")
    base = _draws(model, samples, seed)
    slopes = np.array([k.slope for k in knobs])  # (n, K)
    moving = (slopes != 0.0).any(axis=0)
    fixed_jam = (base[:, ~moving] < 0.0).any(axis=1)
    bv, sv = base[:, moving], slopes[:, moving]
    starts = np.array([k.start for k in knobs])
    cache: dict = {}

    def jams(idx: tuple) -> int:
        if idx not in cache:
            shift = (np.array([k.value(i) for k, i in zip(knobs, idx)]) - starts) @ sv
            cache[idx] = int((fixed_jam | ((bv + shift[None, :]) < 0.0).any(axis=1)).sum())
        return cache[idx]

    top = tuple(k.most for k in knobs)
    allowed = int(math.floor(target * samples + 1e-9))
    floor = jams(top)
    reached = floor <= allowed
    if not reached:
        allowed = floor

    def least_last(prefix: tuple, lo: int, hi: int) -> int | None:
        """The least index of the last knob (in lo..hi) feasible with ``prefix``; None if none."""
        if jams(prefix + (hi,)) > allowed:
            return None
        while lo < hi:
            mid = (lo + hi) // 2
            if jams(prefix + (mid,)) <= allowed:
                hi = mid
            else:
                lo = mid + 1
        return lo

    weights = [play_weight(model, k.slope) for k in knobs]
    if len(knobs) == 1:
        frontier = [(least_last((), knobs[0].least, knobs[0].most),)]
    else:
        k1, k2 = knobs
        frontier = []
        j = least_last((k1.most,), k2.least, k2.most)
        for i in range(k1.most, k1.least - 1, -1):
            while j <= k2.most and jams((i, j)) > allowed:
                j += 1
            if j > k2.most:
                break
            frontier.append((i, j))
    # the least cost; ties: the smaller first knob, then the second (the knobs' order)
    def cost(idx):
        return sum(w * k.value(i) for w, k, i in zip(weights, knobs, idx))
    best = min(frontier, key=lambda idx: (quantise(cost(idx)), idx))
    j = jams(best)
    lo95, hi95 = wilson(j, samples)
    buys = {}
    for n, k in enumerate(knobs):  # jams one more step of each knob would save: where play buys most
        if best[n] < k.most:
            up = tuple(i + (m == n) for m, i in enumerate(best))
            buys[k.key] = j - jams(up)
    shift = (np.array([k.value(i) for k, i in zip(knobs, best)]) - starts) @ slopes
    jam = (base + shift[None, :]) < 0.0
    groups = {g: int(jam[:, [m.group == g for m in model.margins]].any(axis=1).sum()) for g in GROUPS
              if any(m.group == g for m in model.margins)}
    uidx = model.unit_index
    per_unit = [(int(jam[:, uidx == u].any(axis=1).sum()), u) for u in range(len(model.units))]
    units = [{"unit": model.units[u], "group": model.margins[int(np.flatnonzero(uidx == u)[0])].group, "jams": n}
             for n, u in sorted(per_unit, key=lambda t: (-t[0], t[1])) if n][:5]
    return {"values": {k.key: k.value(i) for k, i in zip(knobs, best)},
            "labels": {k.key: k.label for k in knobs},
            "steps_mm": {k.key: k.step for k in knobs}, "reached": reached, "target": target,
            "samples": samples, "seed": seed, "jams": j, "probability": j / samples, "ci95": [lo95, hi95],
            "cost_mm": round(cost(best), 6), "weights": {k.key: round(w, 6) for k, w in zip(knobs, weights)},
            "frontier": [{k.key: k.value(i) for k, i in zip(knobs, idx)} for idx in frontier],
            "buys": buys, "groups": groups, "units": units}
