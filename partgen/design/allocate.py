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

__all__ = ["Knob", "least_allocation", "play_weight", "hole_slope", "radial_slope", "Unit", "allocate_units", "gear_slopes",
           "joint_slopes"]

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


def radial_slope(model: MarginModel) -> np.ndarray:
    """(K,) mm of margin per mm of *radial* clearance: a radial clearance Δ larger is each cavity it
    sizes printed 2Δ larger, as a diameter — twice ``hole_slope`` where the model has running fits;
    in a model without (the wrist: its sockets are the ``hole`` features of its ``mesh`` margins,
    each dome's gaps opening by half the sockets' growth) every ``hole`` feature is such a cavity."""
    if any(m.group == "joint" for m in model.margins):
        return 2.0 * hole_slope(model)
    cavities = np.array([f.kind == "hole" for f in model.features], dtype=bool)
    return 2.0 * model.coeff[cavities].sum(axis=0) if cavities.any() else np.zeros(len(model.margins))


def play_weight(model: MarginModel, slope: np.ndarray) -> float:
    """mm of play margins (every mesh's backlash, every running fit's radial gap) per mm of a knob."""
    sel = np.array([m.what.startswith(PLAY_WHATS) for m in model.margins], dtype=bool)
    return float(np.asarray(slope)[sel].sum())


def _draws(model: MarginModel, samples: int, seed: int, chunk: int = 0) -> np.ndarray:
    """The margins of ``samples`` prints: chunk ``chunk`` of the stream ``run_chunk`` draws."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(chunk,)))
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


# --- per-unit allocation --------------------------------------------------------------------------

EXCHANGE_TRIES = 4  # raises tried (best first) each time the descent stalls
MAX_ROUNDS = 2000  # moves at most (a bound, never reached on the shipped designs)


@dataclass(frozen=True)
class Unit:
    """One gear's backlash or one running fit's clearance as its own number: ``key`` (the design key
    it belongs to), ``name`` (the gear or the part that runs in the bore), ``start`` (mm the model's
    kit was built with), ``slope`` (K,) mm of margin per mm, ``step`` and the grid ``least`` …
    ``most`` (in steps)."""

    key: str
    name: str
    start: float
    slope: np.ndarray
    step: float
    least: int
    most: int

    def value(self, i: int) -> float:
        return round(i * self.step, 6)


def _natural(name: str) -> tuple:
    """G2 before G10: the letters, then the number."""
    head = name.rstrip("0123456789")
    tail = name[len(head):]
    return (head, int(tail) if tail else -1, name)


def gear_slopes(model: MarginModel) -> dict[str, np.ndarray]:
    """{gear: (K,) mm of margin per mm of *that gear's* backlash}: a mesh ``a/b``'s backlash margin
    moves by half its ``per_backlash`` per mm of either gear's thinning (each gear's thinning Δ opens
    Δ·cos α/cos α_w on the operating circle); in natural name order."""
    out: dict[str, np.ndarray] = {}
    for k, m in enumerate(model.margins):
        if m.group != "mesh" or m.what != "backlash" or not m.per_backlash:
            continue
        for gear in m.unit.split("/"):
            out.setdefault(gear, np.zeros(len(model.margins)))[k] += m.per_backlash / 2
    return {g: out[g] for g in sorted(out, key=_natural)}


def joint_slopes(model: MarginModel) -> dict[str, np.ndarray]:
    """{part: (K,) mm of margin per mm of *its* running fit's diametral clearance}: the coefficients
    of its bore (the ``hole`` feature of its ``joint`` margin ``"<part> on <carrier>"``): the fit's gap
    and every mesh its play is credited to; in natural name order."""
    holes = np.array([f.kind == "hole" for f in model.features], dtype=bool)
    out: dict[str, np.ndarray] = {}
    for k, m in enumerate(model.margins):
        if m.group != "joint" or m.what != "radial gap":
            continue
        rows = np.flatnonzero(holes & (model.coeff[:, k] != 0.0))
        if len(rows) != 1:
            continue
        name = m.unit.split(" on ")[0]
        if name not in out:
            out[name] = model.coeff[rows[0]].copy()
    return {n: out[n] for n in sorted(out, key=_natural)}


PROB_STEP = 1e-12  # the resolution probabilities are compared at (quantised: the same choice on any machine)


class _Analytic:
    """Each margin's exact probability of going below 0 in the linear model (a margin is normal:
    mean the nominal moved by the units' values, σ from its features' spreads), at the current
    values; the kit's is taken as their sum (the union bound: exact for rare jams that do not
    coincide, above it otherwise), so no print's luck steers the allocation."""

    def __init__(self, model: MarginModel, units: list[Unit], idx: list[int]):
        self.units, self.idx = units, list(idx)
        self.S = np.array([u.slope for u in units])  # (U, K)
        self.starts = np.array([u.start for u in units])
        self.sd = np.sqrt(((model.coeff * model.sigma[:, None]) ** 2).sum(axis=0))
        self.nominal = model.nominal
        self.cols = [np.flatnonzero(u.slope != 0.0) for u in units]
        self.moving = np.flatnonzero((self.S != 0.0).any(axis=0) & (self.sd > 0))
        self.p = self._p(self.idx, self.moving)

    def _values(self, idx) -> np.ndarray:
        return np.array([u.value(i) for u, i in zip(self.units, idx)])

    def _p(self, idx, cols) -> np.ndarray:
        mu = self.nominal[cols] + (self._values(idx) - self.starts) @ self.S[:, cols]
        return np.array([0.5 * math.erfc(m / (s * math.sqrt(2.0))) for m, s in zip(mu, self.sd[cols])])

    def total(self, p=None) -> int:
        return quantise(float(np.sum(self.p if p is None else p)), PROB_STEP)

    def trial(self, i: int, d: int) -> int:
        """The kit's probability (quantised) with unit i moved ``d`` steps."""
        idx = list(self.idx)
        idx[i] += d
        p = self.p.copy()
        cols = np.intersect1d(self.cols[i], self.moving)
        where = np.searchsorted(self.moving, cols)
        p[where] = self._p(idx, cols)
        return self.total(p)

    def move(self, i: int, d: int) -> None:
        self.idx[i] += d
        cols = np.intersect1d(self.cols[i], self.moving)
        self.p[np.searchsorted(self.moving, cols)] = self._p(self.idx, cols)


def allocate_units(model: MarginModel, units: list[Unit], start: list[int], samples: int = AUTO_SAMPLES,
                   seed: int = 0, guard: tuple[MarginModel, list[Unit]] | None = None) -> dict:
    """Each unit its own value (on its grid), from ``start`` (grid indices, the uniform choice): the
    least total play Σ weight_i · value_i (weight: the play margins a unit opens per mm,
    ``play_weight``) whose probability of a jam (``_Analytic``: each margin's exact normal tail,
    summed) is no more than at ``start``.

    ``guard``: a second model of the same kit and its units (the same names and grids, in the same
    order; the worst case: no bore play credited) whose probability may not rise above its own at
    ``start`` either — play is moved only where neither the headline nor the worst case gets worse.

    Deterministic greedy: **descent** — lower by one step the unit that saves most play per
    probability it adds (a step that adds none first, the largest saving first), while the
    probability stays within the start's; when none can be lowered, **exchange** — raise by one step
    a unit that lowers the probability (the most per mm of play first; at most ``EXCHANGE_TRIES``
    of them), hold it, and descend again; keep the exchange when the total play fell, else undo it
    and try the next; stop when none helps. Costs and probabilities are compared quantised
    (``core.quantise``: 1e-6 mm, ``PROB_STEP``), ratios exactly (fractions of those integers); ties go
    to the unit with the larger value, then the earlier unit (the ``units`` order: each key's units
    in natural name order). The result counts the jams at the values among the ``samples`` fixed
    prints (seed, chunk 0: ``least_allocation``'s) and gives ``jam`` (N, K): which margins of which
    prints are below 0."""
    from fractions import Fraction

    st = _Analytic(model, units, start)
    budget = st.total()
    gd = _Analytic(guard[0], guard[1], start) if guard is not None else None
    gbudget = gd.total() if gd is not None else 0
    if gd is not None and [(u.key, u.name) for u in guard[1]] != [(u.key, u.name) for u in units]:
        raise ValueError("the guard's units are not the units")

    def within(i: int, d: int) -> bool:
        return gd is None or gd.trial(i, d) <= gbudget

    def step(i: int, d: int) -> None:
        st.move(i, d)
        if gd is not None:
            gd.move(i, d)
    w = [play_weight(model, u.slope) for u in units]
    save = [quantise(wi * u.step) for wi, u in zip(w, units)]  # play one step of each unit opens, in 1e-6 mm

    def cost() -> int:
        return sum(quantise(wi * u.value(i)) for wi, u, i in zip(w, units, st.idx))

    def descend(hold: int | None) -> int:
        moves = 0
        while moves < MAX_ROUNDS:
            best, key = None, None
            now = st.total()
            for i, u in enumerate(units):
                if i == hold or st.idx[i] <= u.least or save[i] <= 0:
                    continue
                p = st.trial(i, -1)
                if p > budget or not within(i, -1):
                    continue
                added = p - now
                k = (0, -save[i], -st.idx[i] * save[i], i) if added <= 0 else \
                    (1, -Fraction(save[i], added), -st.idx[i] * save[i], i)
                if key is None or k < key:
                    best, key = i, k
            if best is None:
                return moves
            step(best, -1)
            moves += 1
        return moves

    descend(None)
    exchanges = 0
    for _ in range(MAX_ROUNDS):
        now, p0 = cost(), st.total()
        gains = []
        for i, u in enumerate(units):
            if st.idx[i] >= u.most or save[i] <= 0:
                continue
            gain = p0 - st.trial(i, +1)
            if gain > 0:
                gains.append((-Fraction(gain, save[i]), i))
        kept = False
        for _, i in sorted(gains)[:EXCHANGE_TRIES]:
            before = list(st.idx)
            step(i, +1)
            descend(i)
            if cost() < now:
                kept = True
                exchanges += 1
                break
            for n in range(len(units)):  # undo: back to the values before the raise
                if st.idx[n] != before[n]:
                    step(n, before[n] - st.idx[n])
        if not kept:
            break
        descend(None)
    S = np.array([u.slope for u in units])
    starts = np.array([u.start for u in units])
    jam = (_draws(model, samples, seed) + (st._values(st.idx) - starts) @ S) < 0.0
    j = int(jam.any(axis=1).sum())
    lo95, hi95 = wilson(j, samples)
    return {"values": [u.value(i) for u, i in zip(units, st.idx)], "index": list(st.idx), "jams": j,
            "probability": j / samples, "ci95": [lo95, hi95], "cost_mm": round(cost() * 1e-6, 6),
            "weights": [round(x, 6) for x in w], "exchanges": exchanges, "jam": jam,
            "analytic": {"start": budget * PROB_STEP, "end": st.total() * PROB_STEP},
            "guard": None if gd is None else {"start": gbudget * PROB_STEP, "end": gd.total() * PROB_STEP}}
