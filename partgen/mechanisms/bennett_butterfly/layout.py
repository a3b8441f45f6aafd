"""The automatic stack layout of the Bennett butterfly kit, and the capsule sweep it is judged by.

Every part is covered by capsules (``geometry.bennett_link.capsules``); over the shape angle (the
only thing link–link clearance depends on: q1 turns the whole linkage rigidly about S's axis and
the base is round about it) the least clearance of every pair is measured, features at a joint the
two share left out (the stack keeps them apart; the check measures those exactly). The search moves
links between layers and joint stacks along their axes until no capsules overlap.

Speed: a trial layout that moves one link recomputes only the pairs that link is in, all of them
in one batch; of those capsule pairs only the ones whose bounding spheres come within ``below`` mm
are measured exactly (a pair of parts farther apart than that everywhere is known only to be at
least that far, which is all the search and the checks need).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from ...design import bennett_butterfly as bbf
from .params import BennettParams
from ...geometry.bennett_link import capsules
from ...core.quantise import RESOLUTION_MM, quantise, quantised
from ...geometry.capsules import segment_distance
from .parts import (BASE, Layout, base_features, default_layout, guess_fill, home_inputs, link_features,
                            stack)

__all__ = ["Sweep", "link_capsules", "part_capsules", "capsule_key", "shape_samples", "coarse_samples", "point_speed",
           "sweep_clearance", "choose_offsets", "search_layout", "part_reach"]


def link_capsules(p: BennettParams, lay: Layout, bodies: dict, pockets: dict | None = None
                  ) -> dict[int, tuple[np.ndarray, np.ndarray, list]]:
    """link (0 = base) -> (capsule ends (k, 2, 3) in the body frame, radii (k,), what each capsule
    is: ("boss", joint), ("bar", joint…), ("cup",), ("foot",) or ("pin", joint))."""
    return {link: part_capsules(p, lay, bodies, link, pockets) for link in range(0, 13)}


def _joints_of(link: int) -> list[str]:
    return ["S14"] if link == BASE else sorted(j for j, (links, _, _) in bbf.JOINTS.items() if link in links)


def capsule_key(lay: Layout, link: int, pockets: dict | None) -> tuple:
    """Everything a part's capsules depend on: its layer, and for each of its joints the shift and
    the members' layers (which decide the pin's span, its owner and the end bosses' lengths), and
    its pocket (offset and fill)."""
    pk = (pockets or {}).get(link)
    return (link, lay.layer[link], tuple((j, lay.shift.get(j, 0.0), tuple(lay.layer[i] for i in lay.members(j)),
                                          lay.members(j)) for j in _joints_of(link)),
            None if pk is None else (tuple(np.round(np.asarray(pk[0], float), 12)), pk[1]))


def part_capsules(p: BennettParams, lay: Layout, bodies: dict, link: int, pockets: dict | None = None):
    """One part's capsules (see ``link_capsules``)."""
    if link == BASE:
        columns, _ = base_features(p, lay)
        ends, radii, owner = capsules([], [], [], columns)
        tags = [("bar", "S14"), ("boss", "S14"), ("foot",)]  # the post below the pin, around it, the foot
    else:
        bosses, bars, cups = link_features(p, link, lay, bodies[link], (pockets or {}).get(link))
        names = sorted(bodies[link])
        tags = [("boss", j) for j in names]
        cs = sorted(((float(b.point[0]), names[k]) for k, b in enumerate(bosses)))
        for (_, a), (_, b) in zip(cs, cs[1:]):
            tags += [("bar", a), ("bar",), ("bar", b)]  # out of boss a, across, into boss b
        if cups:
            ref = next(j for j in names if np.linalg.norm(bodies[link][j][0]) < 1e-9)
            tags += [("bar", ref), ("bar",), ("cup",)]
        ends, radii, owner = capsules(bosses, bars, cups)
    tags = [tags[k] for k in owner]
    pins = [j for j in _joints_of(link) if lay.members(j)[0] == link]
    if pins:
        pe, pr = [], []
        for j in pins:
            lo, hi = stack(p, lay, j).pin
            pt, ax = ((np.zeros(3), np.array([0.0, 0, 1])) if link == BASE else bodies[link][j])
            pe.append([pt + lo * ax, pt + hi * ax])
            pr.append(p.pin_radius)
            tags.append(("pin", j))
        ends, radii = np.concatenate([ends, np.asarray(pe)]), np.concatenate([radii, pr])
    return ends, radii, tags


def own_clearance(p: BennettParams, lay: Layout, bodies: dict, link: int, ends: np.ndarray, radii: np.ndarray,
                  tags: list) -> tuple[float, str]:
    """How far a link's own features keep from the pins through it (mm; negative: a pin runs into
    them): every two pins leave at least the printer's thinnest wall between their bores (the four
    joints at S lie on different axes through one point), and a pin's whole span (it runs through
    every boss of its stack) misses all of the link but its own boss and the bars that leave it. In
    the link's frame the pins stand still, so this holds in every pose. Returns the least margin and
    what it is between."""
    if link == BASE:
        return math.inf, ""
    wall = p.printer.min_wall if p.printer is not None else 1.0
    joints = sorted(bodies[link])
    seg = {}
    for j in joints:
        pt, ax = bodies[link][j]
        lo, hi = stack(p, lay, j).pin
        seg[j] = (pt + lo * ax, pt + hi * ax)
    # every pair of pins, and every pin against every feature that is not its own boss's
    pairs = [(a, b) for x, a in enumerate(joints) for b in joints[x + 1:]]
    other = [(j, k) for j in joints for k, t in enumerate(tags) if t[0] != "pin" and j not in t[1:]]
    s0 = np.array([seg[a] for a, _ in pairs] + [seg[j] for j, _ in other]).reshape(-1, 2, 3)
    s1 = np.concatenate([np.array([seg[b] for _, b in pairs]).reshape(-1, 2, 3),
                         ends[[k for _, k in other]].reshape(-1, 2, 3)])
    need = np.concatenate([np.full(len(pairs), 2 * p.bore_radius + wall), p.bore_radius + radii[[k for _, k in other]]])
    g = segment_distance(s0[:, 0], s0[:, 1], s1[:, 0], s1[:, 1]) - need
    k = int(np.argmin(g))
    what = f"pins {pairs[k][0]} and {pairs[k][1]}" if k < len(pairs) else \
        f"pin {other[k - len(pairs)][0]} and a {tags[other[k - len(pairs)][1]][0]}"
    return float(g[k]), what


def shape_samples(p: BennettParams, lo: float, hi: float, speed: float) -> tuple[np.ndarray, float]:
    """Shape angles from lo to hi (rad) at a step that moves no point more than half the thinnest
    feature (a bar's radius) between samples: step = bar_radius / speed, speed = the fastest point's
    mm per rad of shape angle. Returns the angles and the step."""
    step = p.bar_radius / max(speed, 1e-9)
    n = max(2, int(math.ceil((hi - lo) / step)) + 1)
    return np.linspace(lo, hi, n), (hi - lo) / (n - 1)


def _shared(a: int, b: int) -> set[str]:
    """Joints parts a and b share (the base shares S14 with links 1 and 4)."""
    out = {n for n, (links, _, _) in bbf.JOINTS.items() if a in links and b in links}
    if BASE in (a, b) and (1 in (a, b) or 4 in (a, b)):
        out.add("S14")
    return out


_BIT = {name: 1 << k for k, name in enumerate(sorted(bbf.JOINTS))}
# SHARED[a, b]: the joints parts a and b share, as bits. Features of two parts at a joint they share
# (bosses, the pin, bars as they leave a boss: tagged with that joint) touch by design as capsules;
# the stack's layers keep them apart, and the check measures them exactly.
SHARED = np.array([[sum(_BIT[j] for j in _shared(a, b)) if a != b else 0 for b in range(13)] for a in range(13)],
                  np.int64)


def _bits(tag) -> int:
    return sum(_BIT[j] for j in tag[1:])


@dataclass(frozen=True)
class PartCapsules:
    """A part's capsules over the sweep's angles: world ends (n, k, 2, 3) mm, radii (k,), what each
    is (and its joints as bits), the state they were made from; mid (n, k, 3) and reach (k,): each
    capsule's bounding sphere."""

    ends: np.ndarray
    radii: np.ndarray
    tags: tuple
    bits: np.ndarray
    key: tuple
    mid: np.ndarray
    reach: np.ndarray
    own: float = math.inf  # ``own_clearance``: room between the part's bores and its other features, mm
    centre: np.ndarray | None = None  # (n, 3): the part's bounding sphere over the angles
    radius: float = 0.0


def _least_per_pair(d: np.ndarray, pair: np.ndarray) -> dict[int, int]:
    """pair (a·13 + b) -> the index of its least ``d`` (the first such index where several tie):
    two passes over the arrays, no sort."""
    if not len(d):
        return {}
    least = np.full(169, np.inf)
    np.minimum.at(least, pair, d)
    at = np.flatnonzero(d == least[pair])
    first = np.full(169, len(d))
    np.minimum.at(first, pair[at], at)
    keys = np.flatnonzero(np.bincount(pair, minlength=169))
    return dict(zip(keys.tolist(), first[keys].tolist()))


class Sweep:
    """Capsule clearances of every pair of parts over fixed shape angles. The frames are computed
    once; each part's capsules and each pair's result are remembered by the parts' states, so a
    trial layout that moves one link recomputes only the pairs that link is in (in one batch).
    Clearances under ``below`` mm are exact; a pair that stays farther apart is known only to be at
    least ``below`` (flagged inexact); the least clearance is always exact."""

    def __init__(self, p: BennettParams, angles: np.ndarray, bodies: dict, pockets: dict | None = None,
                 below: float = 12.0):
        self.p, self.bodies, self.pockets, self.below = p, bodies, pockets, below
        q1, q4 = home_inputs(angles)
        self.frames = bbf.link_frames(bbf.pose(p.bb, q1, q4))
        self.n = len(angles)
        self.cache: dict = {}  # capsule_key -> PartCapsules
        self.pairs: dict = {}  # (key a, key b) -> (least clearance, angle index, exact) or None
        self._last = None  # (layout, its capsules): the last asked for

    def capsules(self, lay: Layout) -> dict[int, PartCapsules]:
        """part -> its capsules over the angles; cached per part state."""
        if self._last is not None and self._last[0] is lay:
            return self._last[1]
        out = {}
        for k in range(0, 13):
            key = capsule_key(lay, k, self.pockets)
            hit = self.cache.get(key)
            if hit is None:
                ends, radii, tags = part_capsules(self.p, lay, self.bodies, k, self.pockets)
                if k == BASE:
                    world = np.broadcast_to(ends, (self.n,) + ends.shape)
                else:
                    T = self.frames[k]
                    world = np.einsum("nij,kej->nkei", T[:, :3, :3], ends) + T[:, None, None, :3, 3]
                reach = np.linalg.norm(ends[:, 1] - ends[:, 0], axis=1) / 2 + radii
                own = own_clearance(self.p, lay, self.bodies, k, ends, radii, tags)[0]
                mid = world.mean(axis=2)
                centre = mid.mean(axis=1)
                radius = float((np.linalg.norm(mid - centre[:, None], axis=2) + reach[None]).max())
                hit = PartCapsules(world, radii, tuple(tags), np.array([_bits(t) for t in tags], np.int64), key,
                                   mid, reach, own, centre, radius)
                self.cache[key] = hit
            out[k] = hit
        self._last = (lay, out)
        return out

    def _batch(self, rows: list[int], need: np.ndarray, caps: dict, below: float, chunk: int = 3_000_000):
        """Parts ``rows`` against every part where ``need`` (13, 13) says, all at once: the
        clearances (m,) of the capsule pairs whose bounding spheres come within ``below`` (the others
        are farther), their angle indices, and the part pair of each (a·13 + b); and ``counted``
        (13, 13): the part pairs with any capsule pair not exempt."""
        A = [caps[a] for a in rows]
        # parts whose bounding spheres never come within ``below`` of a row part's need no capsule work
        centre = np.stack([caps[k].centre for k in range(13)])  # (13, n, 3)
        radius = np.array([caps[k].radius for k in range(13)])
        gap = (np.sqrt(((centre[rows][:, None] - centre[None]) ** 2).sum(-1)).min(axis=2)
               - radius[rows][:, None] - radius[None])
        far = np.ones((13, 13), bool)
        far[rows] = gap >= below
        cols = [b for b in range(13) if any(need[a, b] and not far[a, b] for a in rows)]
        need = need & ~far
        B = [caps[b] for b in cols]
        if not B:
            return np.zeros(0), np.zeros(0, int), np.zeros(0, int), np.zeros((13, 13), bool), far
        pid_a = np.concatenate([np.full(len(c.radii), a) for a, c in zip(rows, A)])
        pid_b = np.concatenate([np.full(len(c.radii), b) for b, c in zip(cols, B)])
        bits_a, bits_b = np.concatenate([c.bits for c in A]), np.concatenate([c.bits for c in B])
        mask = need[pid_a[:, None], pid_b[None, :]] & (
            (bits_a[:, None] & bits_b[None, :] & SHARED[pid_a[:, None], pid_b[None, :]]) == 0)
        counted = np.zeros((13, 13), bool)
        starts_a = np.cumsum([0] + [len(c.radii) for c in A])[:-1]
        starts_b = np.cumsum([0] + [len(c.radii) for c in B])[:-1]
        counted[np.ix_(rows, cols)] = np.logical_or.reduceat(np.logical_or.reduceat(mask, starts_a, axis=0), starts_b,
                                                             axis=1)
        mid_a, mid_b = np.concatenate([c.mid for c in A], axis=1), np.concatenate([c.mid for c in B], axis=1)
        reach_a, reach_b = np.concatenate([c.reach for c in A]), np.concatenate([c.reach for c in B])
        near = (reach_a[:, None] + reach_b[None, :] + below) ** 2
        sq_a, sq_b = (mid_a ** 2).sum(-1), (mid_b ** 2).sum(-1)
        step = max(1, chunk // max(1, mask.size))
        hits = []
        for n0 in range(0, self.n, step):  # |mA − mB|² by one batched matrix product per chunk of angles
            sl = slice(n0, n0 + step)
            d2 = sq_a[sl, :, None] + sq_b[sl, None, :] - 2 * np.matmul(mid_a[sl], mid_b[sl].transpose(0, 2, 1))
            ni, ai, bi = np.nonzero((d2 < near[None]) & mask[None])
            hits.append((ni + n0, ai, bi))
        ni, ai, bi = (np.concatenate(x) for x in zip(*hits))
        ends_a, ends_b = np.concatenate([c.ends for c in A], axis=1), np.concatenate([c.ends for c in B], axis=1)
        rad_a, rad_b = np.concatenate([c.radii for c in A]), np.concatenate([c.radii for c in B])
        d = (segment_distance(ends_a[ni, ai, 0], ends_a[ni, ai, 1], ends_b[ni, bi, 0], ends_b[ni, bi, 1])
             - rad_a[ai] - rad_b[bi])
        return d, ni, pid_a[ai] * 13 + pid_b[bi], counted, far

    def _counts(self, a: int, b: int, caps: dict) -> bool:
        """Whether any capsule pair of parts a and b is not exempt (features at a joint they share)."""
        sh = SHARED[a, b]
        return bool(((caps[a].bits[:, None] & caps[b].bits[None, :] & sh) == 0).any())

    def _compute(self, pairs: list[tuple[int, int]], caps: dict, below: float) -> dict[tuple[int, int], tuple | None]:
        """(least clearance, angle index, exact) of each part pair (a < b), None if all exempt."""
        need = np.zeros((13, 13), bool)
        rows, left = [], set(pairs)
        while left:  # rows: parts that cover the pairs (a trial's moved parts)
            count: dict[int, int] = {}
            for a, b in left:
                count[a] = count.get(a, 0) + 1
                count[b] = count.get(b, 0) + 1
            c = max(sorted(count), key=lambda k: count[k])
            rows.append(c)
            for a, b in [x for x in left if c in x]:
                need[c, b if a == c else a] = True
                left.discard((a, b))
        d, ni, pair, counted, far = self._batch(rows, need, caps, below)
        best = _least_per_pair(d, pair)
        out = {}
        for a, b in pairs:
            k = a * 13 + b if need[a, b] else b * 13 + a
            if far[k // 13, k % 13]:  # whether any of their capsules count or not: at least ``below`` apart
                out[(a, b)] = (below, 0, False) if self._counts(a, b, caps) else None
            elif not counted[k // 13, k % 13]:
                out[(a, b)] = None
            elif k in best and d[best[k]] < below:
                out[(a, b)] = (float(d[best[k]]), int(ni[best[k]]), True)
            else:  # every capsule pair at least ``below`` apart
                out[(a, b)] = (below, 0, False)
        return out

    def all(self, lay: Layout) -> dict[tuple[int, int], tuple[float, int]]:
        """Every pair's (least clearance mm, angle index); exact under ``below``, and the least one
        exact whatever it is. Pairs of unchanged parts come from memory."""
        caps = self.capsules(lay)
        todo = [(a, b) for a, b in itertools.combinations(range(13), 2) if (caps[a].key, caps[b].key) not in self.pairs]
        if todo:
            for (a, b), r in self._compute(todo, caps, self.below).items():
                self.pairs[(caps[a].key, caps[b].key)] = r
        out = {}
        for a, b in itertools.combinations(range(13), 2):
            r = self.pairs[(caps[a].key, caps[b].key)]
            if r is not None:
                out[(a, b)] = r
        if out and not min(out.values())[2]:  # everything farther than ``below``: measure them exactly
            loose = [k for k, r in out.items() if not r[2]]
            for (a, b), r in self._compute(loose, caps, math.inf).items():
                self.pairs[(caps[a].key, caps[b].key)] = out[(a, b)] = r
        return {k: (v, i) for k, (v, i, _) in out.items()}

    def profile(self, lay: Layout, below: float | None = None) -> np.ndarray:
        """(n,) least clearance over all pairs at each sampled angle (mm): exact under ``below``
        (default the sweep's), at least ``below`` elsewhere."""
        below = self.below if below is None else below
        caps = self.capsules(lay)
        need = np.triu(np.ones((13, 13), bool), 1)
        d, ni, _, _, _ = self._batch(list(range(13)), need, caps, below)
        out = np.full(self.n, below)
        np.minimum.at(out, ni, d)
        return out


def sweep_clearance(p: BennettParams, lay: Layout, angles: np.ndarray, bodies: dict | None = None
                    ) -> dict[tuple[int, int], tuple[float, int]]:
    """(part a, part b) -> (least capsule clearance mm, index of the shape angle where it occurs),
    0 = the base; features at a joint the two share left out (the stack keeps them apart); exact
    under 12 mm."""
    return Sweep(p, angles, bodies or bbf.body_joints(p.bb)).all(lay)


def point_speed(p: BennettParams, lo: float, hi: float, reach: dict[int, float] | None = None, n: int = 361) -> float:
    """A bound on how fast any point of any part moves, mm per rad of the shape angle, over [lo, hi]:
    for each link the speed of its reference joint plus its angular speed times ``reach`` (link ->
    mm, the farthest point of the part from that joint). Without ``reach``, a generous guess from the
    config (for the search, before the parts exist); the check passes the parts' own."""
    t = np.linspace(lo, hi, n)
    P = bbf.pose(p.bb, *home_inputs(t))
    # angular speed of each of the four link rotations: the angle of R(t)ᵀR(t + dt) over dt
    rel = np.einsum("gnji,gnjk->gnik", P.rot[:, :-1], P.rot[:, 1:])
    cos = np.clip((np.trace(rel, axis1=2, axis2=3) - 1) / 2, -1.0, 1.0)
    omega = (np.arccos(cos) / np.diff(t)).max(axis=1)
    if reach is None:
        span = max(float(np.linalg.norm(pt)) for body in bbf.body_joints(p.bb).values() for pt, _ in body.values())
        cup = guess_fill(p).depth + p.cw_wall
        guess = span + p.offset_max + p.layers * p.pitch + p.boss_radius + abs(max(p.cw_distance, key=abs)) + cup
        reach = {i: guess for i in bbf.GROUP}
    out = 0.0
    for i, g in bbf.GROUP.items():
        x = P.points[bbf.REFERENCE[i]]
        v = float((np.linalg.norm(np.diff(x, axis=0), axis=1) / np.diff(t)).max())
        out = max(out, v + float(omega[g - 1]) * reach[i])
    return out


def part_reach(p: BennettParams, lay: Layout, bodies: dict, pockets: dict | None = None) -> dict[int, float]:
    """link -> the farthest point of its capsules from its reference joint (the body origin), mm."""
    out = {}
    for i in bbf.GROUP:
        ends, radii, _ = part_capsules(p, lay, bodies, i, pockets)
        out[i] = float((np.linalg.norm(ends, axis=2) + radii[:, None]).max())
    return out


def choose_offsets(p: BennettParams, angles: np.ndarray, bodies: dict, progress=None, layers: int = 6,
                   rounds: int = 12, start: Layout | None = None, pockets: dict | None = None,
                   only: set[int] | None = None) -> tuple[Layout, float]:
    """Local search over each link's layer (1 … ``layers`` − 1; the base is 0) and each joint's stack
    shift (−offset_max … offset_max in offset_step) that removes capsule overlap (and clearance short
    of a bar's radius) over ``angles``, then maximises the least clearance; links sharing a joint
    stay on different layers and every stack must take a stock pin; ties go to the smaller offsets.
    ``only``: move just these links and the stacks they are on. Returns the layout and its least
    clearance (mm)."""
    margin = p.bar_radius  # the search sweeps every fourth sample: aim for a bar's radius of room
    sweep = Sweep(p, angles, bodies, pockets, below=2 * margin)

    def ok(l: Layout) -> bool:
        """Links on one pin on different layers, every stack a stock pin."""
        if not all(len({l.layer[i] for i in l.members(j)}) == len(l.members(j)) for j in bbf.JOINTS):
            return False
        need = max((l.layer[l.members(j)[-1]] - l.layer[l.members(j)[0]]) * p.pitch + p.boss_length
                   for j in bbf.JOINTS)
        return need <= max(p.pin_stock) + 1e-9

    def score(res: dict, l: Layout) -> tuple[int, int, int]:
        """(room missing: clearance short of a bar's radius between parts, and within each link
        between its bores and the rest (``own_clearance``); the least clearance; compactness), each
        quantised to ``RESOLUTION_MM`` (core.quantise): candidates within a nanometre are ties, so
        the choice is the same on every machine; a tie keeps the earlier candidate (the moves'
        stated order: links by number, layers up, then stacks in ``bbf.JOINTS``' order, shifts from
        −offset_max up)"""
        c = [v for _, (v, _) in sorted(res.items())]
        own = math.fsum(min(x.own, 0.0) for _, x in sorted(sweep.capsules(l).items()))
        return quantised((math.fsum(min(v - margin, 0.0) for v in c) + own, min(c),
                          -sum(l.layer.values()) - math.fsum(map(abs, l.shift.values()))))

    lay = start or default_layout()
    res = sweep.all(lay)
    best = score(res, lay)
    allowed = set(range(1, 13)) if only is None else set(only)
    full = np.arange(-p.offset_max, p.offset_max + 1e-9, p.offset_step)
    step, fine = p.offset_step, p.offset_step / 8
    passes = 0
    while True:
        # first every shift in offset_step steps over the range; once that settles, shifts near the
        # current ones at half the step, a quarter, an eighth (a pattern search, coarse to fine).
        # After the first pass only the links in a pair short of room (or the least one) and the
        # stacks they are on move: nothing else can raise the score but the compactness tie-break
        improved = False
        movable = set(allowed)
        if passes:
            least = min(quantise(v) for v, _ in res.values())
            short = {x for pair, (v, _) in res.items() if quantise(v) <= max(quantise(margin) - 1, least) for x in pair}
            short |= {k for k, c in sweep.capsules(lay).items() if c.own < 0}
            movable &= short
        joints = [j for j, (links, _, _) in bbf.JOINTS.items() if movable & set(links)]
        moves = [("layer", i, k) for i in sorted(movable) for k in range(1, layers)]
        moves += [("shift", j, None) for j in joints]
        for kind, what, val in moves:
            if kind == "layer":
                if lay.layer[what] == val:
                    continue
                trials = [Layout({**lay.layer, what: val}, lay.shift)]
                if not ok(trials[0]):
                    continue
            else:
                now = lay.shift.get(what, 0.0)
                values = full if step == p.offset_step else now + step * np.array([-3, -2, -1, 1, 2, 3])
                trials = [Layout(lay.layer, {**lay.shift, what: float(v)}) for v in values
                          if abs(v) <= p.offset_max + 1e-9 and v != now]
            for trial in trials:
                r = sweep.all(trial)
                sc = score(r, trial)
                if sc > best:
                    best, lay, res, improved = sc, trial, r, True
        passes += 1
        if progress:
            progress(f"layout: pass {passes} (steps of {step:g} mm), least clearance {best[1] * RESOLUTION_MM:.2f} mm")
        if not improved or passes >= rounds:
            if step <= fine + 1e-9 or passes >= rounds:
                break
            step /= 2
    return lay, min(v for v, _ in res.values())


def search_layout(p: BennettParams, progress=None) -> tuple[Layout, dict, np.ndarray, float, float]:
    """The automatic stack layout over the workspace: (layout, bodies, angles, step rad, clearance mm)."""
    bodies = bbf.body_joints(p.bb)
    # the step as the check would choose it for the starting layout; the search sweeps every fourth
    speed = point_speed(p, *p.workspace, part_reach(p, default_layout(), bodies))
    angles, step = shape_samples(p, *p.workspace, speed)
    lay, clear = choose_offsets(p, coarse_samples(angles), bodies, progress, p.layers)
    return lay, bodies, angles, step, clear


def coarse_samples(angles: np.ndarray) -> np.ndarray:
    """Every fourth sample and both ends: what the layout search sweeps (the check sweeps them all)."""
    return angles if len(angles) <= 8 else np.unique(np.concatenate([angles[::4], angles[-1:]]))
