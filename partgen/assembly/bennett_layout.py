"""The automatic stack layout of the Bennett butterfly kit, and the capsule sweep it is judged by.

Every part is covered by capsules (``geometry.bennett_link.capsules``); over the shape angle (the
only thing link–link clearance depends on: q1 turns the whole linkage rigidly about S's axis and
the base is round about it) the least clearance of every pair is measured, features at a joint the
two share left out (the stack keeps them apart; the check measures those exactly). The search moves
links between layers and joint stacks along their axes until no capsules overlap.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from ..design import bennett_butterfly as bbf
from ..design.bennett_butterfly import BennettParams
from ..geometry.bennett_link import capsules
from ..geometry.capsules import capsule_clearance
from .bennett_parts import BASE, Layout, base_features, default_layout, home_inputs, link_features, pin_span

__all__ = ["Sweep", "link_capsules", "part_capsules", "capsule_key", "shape_samples", "coarse_samples", "point_speed",
           "sweep_clearance", "choose_offsets", "search_layout", "part_reach"]


def link_capsules(p: BennettParams, lay: Layout, bodies: dict, delta: dict | None = None
                  ) -> dict[int, tuple[np.ndarray, np.ndarray, list]]:
    """link (0 = base) -> (capsule ends (k, 2, 3) in the body frame, radii (k,), what each capsule
    is: ("boss", joint), ("bar", joint…), ("cup",) or ("pin", joint))."""
    return {link: part_capsules(p, lay, bodies, link, delta) for link in range(0, 13)}


def _joints_of(link: int) -> list[str]:
    return ["S14"] if link == BASE else sorted(j for j, (links, _, _) in bbf.JOINTS.items() if link in links)


def capsule_key(lay: Layout, link: int, delta: dict | None) -> tuple:
    """Everything a part's capsules depend on: its layer, and for each of its joints the shift and
    the members' layers (which decide the pin's span and owner), and its pocket's offset."""
    d = (delta or {}).get(link)
    return (link, lay.layer[link], tuple((j, lay.shift.get(j, 0.0), tuple(lay.layer[i] for i in lay.members(j)),
                                          lay.members(j)) for j in _joints_of(link)),
            None if d is None else tuple(np.round(np.asarray(d, float), 12)))


def part_capsules(p: BennettParams, lay: Layout, bodies: dict, link: int, delta: dict | None = None):
    """One part's capsules (see ``link_capsules``)."""
    if link == BASE:
        bosses, bars = base_features(p, lay)
        cups = []
        tags = [("boss", "S14"), ("bar", "S14")]  # the column hangs from the boss
    else:
        bosses, bars, cups = link_features(p, link, lay, bodies[link], delta)
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
            lo, hi = pin_span(p, lay, j)
            pt, ax = ((np.zeros(3), np.array([0.0, 0, 1])) if link == BASE else bodies[link][j])
            pe.append([pt + lo * ax, pt + hi * ax])
            pr.append(p.pin_radius)
            tags.append(("pin", j))
        ends, radii = np.concatenate([ends, np.asarray(pe)]), np.concatenate([radii, pr])
    return ends, radii, tags


def shape_samples(p: BennettParams, lo: float, hi: float, speed: float) -> tuple[np.ndarray, float]:
    """Shape angles from lo to hi (rad) at a step that moves no point more than half the thinnest
    feature (a bar's radius) between samples: step = bar_radius / speed, speed = the fastest point's
    mm per rad of shape angle. Returns the angles and the step."""
    step = p.bar_radius / max(speed, 1e-9)
    n = max(2, int(math.ceil((hi - lo) / step)) + 1)
    return np.linspace(lo, hi, n), (hi - lo) / (n - 1)


def _world(frames, caps, link, n):
    ends = caps[link][0]
    if link == BASE:
        return np.broadcast_to(ends, (n,) + ends.shape)
    T = frames[link]
    return np.einsum("nij,kej->nkei", T[:, :3, :3], ends) + T[:, None, None, :3, 3]


def _exempt(tag_a, tag_b, shared: set[str]) -> bool:
    """Features of two links at a joint they share (bosses, the pin, bars leaving it) touch by design
    as capsules; the stack's layers keep them apart, and the exact check measures them."""
    return bool(set(tag_a[1:]) & set(tag_b[1:]) & shared)


def _shared(a: int, b: int) -> set[str]:
    out = {n for n, (links, _, _) in bbf.JOINTS.items() if a in links and b in links}
    if BASE in (a, b) and (1 in (a, b) or 4 in (a, b)):
        out.add("S14")
    return out


class Sweep:
    """Capsule clearances of every pair of parts over fixed shape angles. The frames are computed
    once; each part's capsules and each pair's result are remembered by the parts' states, so a
    trial layout that moves one link recomputes only the pairs that link is in."""

    def __init__(self, p: BennettParams, angles: np.ndarray, bodies: dict, delta: dict | None = None):
        self.p, self.bodies, self.delta = p, bodies, delta
        q1, q4 = home_inputs(angles)
        self.frames = bbf.link_frames(bbf.pose(p.bb, q1, q4))
        self.n = len(angles)
        self.masks: dict = {}
        self.cache: dict = {}  # capsule_key -> world capsules
        self.pairs: dict = {}  # (key a, key b) -> least clearance and where

    def capsules(self, lay: Layout) -> dict[int, tuple[np.ndarray, np.ndarray, list]]:
        """part -> (world capsule ends (n, k, 2, 3), radii (k,), tags, key); cached per part state."""
        out = {}
        for k in range(0, 13):
            key = capsule_key(lay, k, self.delta)
            hit = self.cache.get(key)
            if hit is None:
                ends, radii, tags = part_capsules(self.p, lay, self.bodies, k, self.delta)
                hit = (_world(self.frames, {k: (ends,)}, k, self.n), radii, tags, key)
                self.cache[key] = hit
            out[k] = hit
        return out

    def per_angle(self, caps, a: int, b: int) -> np.ndarray | None:
        """(n,) least clearance of parts a and b at each angle (mm); None if every feature pair is exempt."""
        key = (a, b, tuple(caps[a][2]), tuple(caps[b][2]))
        mask = self.masks.get(key)
        if mask is None:
            shared = _shared(a, b)
            mask = np.array([[not _exempt(ta, tb, shared) for tb in caps[b][2]] for ta in caps[a][2]])
            self.masks[key] = mask
        if not mask.any():
            return None
        c = capsule_clearance(caps[a][0], caps[a][1], caps[b][0], caps[b][1])
        return np.where(mask[None], c, np.inf).min(axis=(1, 2))

    def pair(self, caps, a: int, b: int) -> tuple[float, int] | None:
        """(least clearance mm, angle index) of parts a and b, remembered per pair of part states."""
        key = (caps[a][3], caps[b][3])
        if key in self.pairs:
            return self.pairs[key]
        c = self.per_angle(caps, a, b)
        self.pairs[key] = r = None if c is None else (float(c.min()), int(np.argmin(c)))
        return r

    def profile(self, lay: Layout) -> np.ndarray:
        """(n,) least clearance over all pairs at each sampled angle (mm)."""
        caps = self.capsules(lay)
        out = np.full(self.n, np.inf)
        for a, b in itertools.combinations(range(13), 2):
            c = self.per_angle(caps, a, b)
            if c is not None:
                out = np.minimum(out, c)
        return out

    def all(self, lay: Layout) -> dict[tuple[int, int], tuple[float, int]]:
        """Every pair's (least clearance mm, angle index); pairs of unchanged parts come from memory."""
        caps = self.capsules(lay)
        out = {}
        for a, b in itertools.combinations(range(13), 2):
            r = self.pair(caps, a, b)
            if r is not None:
                out[(a, b)] = r
        return out


def sweep_clearance(p: BennettParams, lay: Layout, angles: np.ndarray, bodies: dict | None = None
                    ) -> dict[tuple[int, int], tuple[float, int]]:
    """(part a, part b) -> (least capsule clearance mm, index of the shape angle where it occurs),
    0 = the base; features at a joint the two share left out (the stack keeps them apart)."""
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
        guess = span + p.offset_max + p.layers * p.pitch + p.boss_radius + abs(max(p.cw_distance, key=abs)) + p.cw_height
        reach = {i: guess for i in bbf.GROUP}
    out = 0.0
    for i, g in bbf.GROUP.items():
        x = P.points[bbf.REFERENCE[i]]
        v = float((np.linalg.norm(np.diff(x, axis=0), axis=1) / np.diff(t)).max())
        out = max(out, v + float(omega[g - 1]) * reach[i])
    return out


def part_reach(p: BennettParams, lay: Layout, bodies: dict, delta: dict | None = None) -> dict[int, float]:
    """link -> the farthest point of its capsules from its reference joint (the body origin), mm."""
    out = {}
    for i in bbf.GROUP:
        ends, radii, _ = part_capsules(p, lay, bodies, i, delta)
        out[i] = float((np.linalg.norm(ends, axis=2) + radii[:, None]).max())
    return out


def choose_offsets(p: BennettParams, angles: np.ndarray, bodies: dict, progress=None, layers: int = 6,
                   rounds: int = 6, start: Layout | None = None, delta: dict | None = None) -> tuple[Layout, float]:
    """Local search over each link's layer (1 … ``layers`` − 1; the base is 0) and each joint's stack
    shift (−offset_max … offset_max in offset_step) that removes capsule overlap (and clearance short
    of a bar's radius) over ``angles``, then maximises the least clearance; links sharing a joint
    stay on different layers; ties go to the
    smaller offsets. Returns the layout and its least clearance (mm)."""
    sweep = Sweep(p, angles, bodies, delta)

    def ok(l: Layout) -> bool:
        return all(len({l.layer[i] for i in l.members(j)}) == len(l.members(j)) for j in bbf.JOINTS)

    margin = p.bar_radius  # the search sweeps every fourth sample: aim for a bar's radius of room

    def score(res: dict, l: Layout) -> tuple[float, float, float]:
        c = [v for v, _ in res.values()]
        return sum(min(v - margin, 0.0) for v in c), min(c), -sum(l.layer.values()) - sum(map(abs, l.shift.values()))

    lay = start or default_layout()
    res = sweep.all(lay)
    best = score(res, lay)
    shifts = np.arange(-p.offset_max, p.offset_max + 1e-9, p.offset_step)
    for rnd in range(rounds):
        improved = False
        moves = [("layer", i, k) for i in range(1, 13) for k in range(1, layers)]
        moves += [("shift", j, float(c)) for j in bbf.JOINTS for c in shifts]
        for kind, what, val in moves:
            if kind == "layer":
                if lay.layer[what] == val:
                    continue
                trial = Layout({**lay.layer, what: val}, lay.shift)
                if not ok(trial):
                    continue
            else:
                if lay.shift.get(what, 0.0) == val:
                    continue
                trial = Layout(lay.layer, {**lay.shift, what: val})
            r = sweep.all(trial)
            sc = score(r, trial)
            if sc > best:
                best, lay, res, improved = sc, trial, r, True
        if progress:
            progress(f"layout: pass {rnd + 1}, least clearance {best[1]:.2f} mm")
        if not improved:
            break
    return lay, best[1]


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
