"""The spatial balanced butterfly as a kit: twelve printed links with bosses on their skew joint axes,
a base, steel pins, and counterweight pockets sized so the common centre of mass stays at S.

Every joint stacks its links' bosses on its axis with an axial gap; where the stack sits along
the axis (and which link is on top) is chosen automatically to keep the links apart over the
workspace (``choose_offsets``). Link–link clearance depends only on the shape angle (q1 turns the
whole linkage rigidly about S's axis, and the base is round about that axis), so the search and
the check sweep the shape angle alone.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from ..design import bennett_butterfly as bbf
from ..design.balanced import LINKS
from ..design.bennett_butterfly import BennettParams
from ..geometry.bennett_link import Bar, Boss, Cup, capsules, link_solid
from ..geometry.capsules import capsule_clearance
from ..geometry.mass import PrintSettings, printed_mass
from ..geometry.parts import Part

__all__ = ["BennettKit", "Layout", "build_bennett", "choose_offsets", "layout", "link_capsules",
           "shape_samples", "sweep_clearance", "solve_counterweights", "home_inputs"]

BASE = 0  # the base (ground) is member 0 of the stack on S's axis


def print_settings(p: BennettParams) -> PrintSettings:
    return PrintSettings(p.print_wall, p.print_skin, p.infill)


def home_inputs(angle: float, q1=0.0):
    """(q1, q4) with the angle between links 1 and 4 (S→B2 and S→B3) equal to ``angle``."""
    q1 = np.asarray(q1, float)
    return q1, q1 - np.asarray(angle, float)


@dataclass(frozen=True)
class Layout:
    """Each link's layer: its bosses sit ``layer × pitch`` mm along every one of its joint axes from
    the joint points (the base is layer 0). Two links that share a joint are on different layers,
    so their bosses stack on the joint's pin with the axial gap between them."""

    layer: dict[int, int]
    shift: dict[str, float] = field(default_factory=dict)  # mm: a joint's whole stack moved along its axis

    def offset(self, joint: str, link: int, pitch: float) -> float:
        return self.shift.get(joint, 0.0) + self.layer[link] * pitch

    def members(self, joint: str) -> tuple[int, ...]:
        links = bbf.JOINTS[joint][0] + ((BASE,) if joint == "S14" else ())
        return tuple(sorted(links, key=lambda i: self.layer[i]))


def default_layout() -> Layout:
    return Layout({BASE: 0, **{i: 1 + (i - 1) % 4 for i in range(1, 13)}})


def _link_features(p: BennettParams, link: int, lay: Layout, body: dict, delta: dict | None = None):
    """Bosses, bars and cups of one link in its body frame; ``delta``: link -> (3,) mm, how far a
    counterweight pocket sits off its nominal point on the link line."""
    pitch = p.boss_length + p.axial_gap
    bore = p.pin_radius + p.pin_clearance / 2
    bosses = [Boss(tuple(pt), tuple(ax), lay.offset(j, link, pitch), p.boss_radius, p.boss_length, bore)
              for j, (pt, ax) in sorted(body.items())]
    # bars: along the link line, in order of the joint points' x (body x runs along the link)
    cs = sorted(((float(b.point[0]), k) for k, b in enumerate(bosses)))
    bars = []
    for (_, k0), (_, k1) in zip(cs, cs[1:]):
        bars += _bar_between(bosses[k0], bosses[k1], p.bar_radius)
    cups = []
    if link in p.cw_links:
        at = cw_nominal(p, link, body, lay) + np.asarray((delta or {}).get(link, np.zeros(3)), float)
        ref_boss = next(b for b in bosses if np.linalg.norm(np.asarray(b.point)) < 1e-9)
        axis = np.asarray(ref_boss.axis)
        base_pt = at - axis * (p.cw_height - (p.cw_height - p.cw_wall) / 2)  # pocket centre at ``at``
        cups.append(Cup(tuple(base_pt), tuple(axis), p.cw_outer_radius, p.cw_height,
                        p.cw_outer_radius - p.cw_wall, p.cw_height - p.cw_wall))
        mid = base_pt + axis * p.cw_height / 2
        e = _exit(ref_boss, mid, p.bar_radius)
        bars += [Bar(tuple(ref_boss.centre), tuple(e), p.bar_radius), Bar(tuple(e), tuple(mid), p.bar_radius)]
    return bosses, bars, cups


def _exit(b: Boss, toward: np.ndarray, r: float) -> np.ndarray:
    """Where a bar from boss b toward a point leaves it: in the boss's mid-plane, r beyond its rim."""
    a = np.asarray(b.axis, float) / np.linalg.norm(b.axis)
    v = toward - b.centre
    v = v - (v @ a) * a
    n = np.linalg.norm(v)
    return b.centre if n < 1e-9 else b.centre + (b.radius + r) * v / n


def _bar_between(b0: Boss, b1: Boss, r: float) -> list[Bar]:
    """Bars joining two bosses of a link: each leaves its boss radially in the boss's mid-plane (so it
    stays between the neighbours stacked on that pin) and the two exits are joined straight."""
    e0, e1 = _exit(b0, b1.centre, r), _exit(b1, b0.centre, r)
    return [Bar(tuple(b0.centre), tuple(e0), r), Bar(tuple(e0), tuple(e1), r), Bar(tuple(e1), tuple(b1.centre), r)]


def cw_nominal(p: BennettParams, link: int, body: dict, lay: Layout) -> np.ndarray:
    """(3,) nominal pocket centre: ``distance`` mm along the link line from its reference joint toward
    the joint its centre-of-mass offset points to (negative: beyond the reference joint), lifted to
    the reference boss's layer."""
    d = p.cw_distance[p.cw_links.index(link)]
    _, ref, toward = LINKS[link]
    t_pt = next(pt for j, (pt, _) in body.items() if bbf.JOINTS[j][2] == toward)
    ref_j = next(j for j, (pt, _) in sorted(body.items()) if np.linalg.norm(pt) < 1e-9)
    pitch = p.boss_length + p.axial_gap
    return d * t_pt / np.linalg.norm(t_pt) + body[ref_j][1] * lay.offset(ref_j, link, pitch)


def _base_features(p: BennettParams, lay: Layout):
    pitch = p.boss_length + p.axial_gap
    bore = p.pin_radius + p.pin_clearance / 2
    off = lay.offset("S14", BASE, pitch)
    boss = Boss((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), off, p.boss_radius, p.boss_length, bore)
    top = off - p.boss_length / 2
    column = Bar((0.0, 0.0, top), (0.0, 0.0, top - p.base_height), p.boss_radius)
    return [boss], [column]


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
        bosses, bars = _base_features(p, lay)
        cups = []
        tags = [("boss", "S14"), ("bar", "S14")]  # the column hangs from the boss
    else:
        bosses, bars, cups = _link_features(p, link, lay, bodies[link], delta)
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
    """Capsule clearances of every pair of parts over fixed shape angles, updated incrementally as
    the layout changes (the frames are computed once)."""

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

    def pair(self, caps, a: int, b: int) -> tuple[float, int] | None:
        ka, kb = caps[a][3], caps[b][3]
        if (ka, kb) in self.pairs:
            return self.pairs[(ka, kb)]
        self.pairs[(ka, kb)] = r = self._pair(caps, a, b)
        return r

    def _pair(self, caps, a: int, b: int) -> tuple[float, int] | None:
        shared = _shared(a, b)
        key = (a, b, tuple(caps[a][2]), tuple(caps[b][2]))
        mask = self.masks.get(key)
        if mask is None:
            mask = np.array([[not _exempt(ta, tb, shared) for tb in caps[b][2]] for ta in caps[a][2]])
            self.masks[key] = mask
        if not mask.any():
            return None
        c = capsule_clearance(caps[a][0], caps[a][1], caps[b][0], caps[b][1])
        c = np.where(mask[None], c, np.inf).min(axis=(1, 2))
        k = int(np.argmin(c))
        return float(c[k]), k

    def profile(self, lay: Layout) -> np.ndarray:
        """(n,) least clearance over all pairs at each sampled angle (mm)."""
        caps = self.capsules(lay)
        out = np.full(self.n, np.inf)
        for a, b in itertools.combinations(range(13), 2):
            key = (a, b, tuple(caps[a][2]), tuple(caps[b][2]))
            if self.pair(caps, a, b) is None:
                continue
            c = capsule_clearance(caps[a][0], caps[a][1], caps[b][0], caps[b][1])
            out = np.minimum(out, np.where(self.masks[key][None], c, np.inf).min(axis=(1, 2)))
        return out

    def all(self, lay: Layout, links: set[int] | None = None, caps=None, old: dict | None = None):
        """Every pair's (clearance, angle index); with ``links`` and ``old``, only pairs touching them recomputed."""
        caps = caps or self.capsules(lay)
        out = dict(old or {})
        for a, b in itertools.combinations(range(13), 2):
            if links is not None and old is not None and a not in links and b not in links:
                continue
            r = self.pair(caps, a, b)
            if r is not None:
                out[(a, b)] = r
        return out


def sweep_clearance(p: BennettParams, lay: Layout, angles: np.ndarray, bodies: dict | None = None
                    ) -> dict[tuple[int, int], tuple[float, int]]:
    """(part a, part b) -> (least capsule clearance mm, index of the shape angle where it occurs),
    0 = the base; features at a joint the two share left out (the stack keeps them apart)."""
    return Sweep(p, angles, bodies or bbf.body_joints(p.bb)).all(lay)


def point_speed(p: BennettParams, lo: float, hi: float, n: int = 361) -> float:
    """The fastest joint point's speed, mm per rad of the shape angle, over [lo, hi] (bosses and bars
    lie within the hull of the joint points plus the offsets, which move with them)."""
    t = np.linspace(lo, hi, n)
    q1, q4 = home_inputs(t)
    pts = bbf.pose(p.bb, q1, q4).points
    reach = p.offset_max + p.boss_length + p.cw_height
    v = max(float((np.linalg.norm(np.diff(x, axis=0), axis=1) / np.diff(t)).max()) for x in pts.values())
    # rotation of a link moves a point `reach` off its joints at up to (joint speed / link length) rad per rad
    omega = max(float(np.abs(np.diff(np.unwrap(np.arctan2(pts["D2"][:, 1] - pts["B2"][:, 1],
                                                             pts["D2"][:, 0] - pts["B2"][:, 0])))).max()
                      / (t[1] - t[0])), 1.0)
    return v + omega * reach


def choose_offsets(p: BennettParams, angles: np.ndarray, bodies: dict, progress=None, layers: int = 6,
                   rounds: int = 6, start: Layout | None = None, delta: dict | None = None) -> tuple[Layout, float]:
    """Local search over each link's layer (1 … ``layers`` − 1; the base is 0) and each joint's stack
    shift (−offset_max … offset_max in offset_step) that removes capsule overlap (and clearance short
    of a bar's radius) over ``angles``, then maximises the least clearance; links sharing a joint stay on different layers; ties go to the
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
                touched = {what}
            else:
                if lay.shift.get(what, 0.0) == val:
                    continue
                trial = Layout(lay.layer, {**lay.shift, what: val})
                touched = set(trial.members(what))
            r = sweep.all(trial, touched, old=res)
            sc = score(r, trial)
            if sc > best:
                best, lay, res, improved = sc, trial, r, True
        if progress:
            progress(f"layout: pass {rnd + 1}, least clearance {best[1]:.2f} mm")
        if not improved:
            break
    return lay, best[1]


@dataclass(frozen=True)
class LinkMass:
    """A link's printed mass (g) and centre (3,) mm in its body frame, solid and as printed (FDM)."""

    solid_mass: float
    solid_centre: np.ndarray
    fdm_mass: float
    fdm_centre: np.ndarray
    shell_volume: float
    interior_volume: float
    interior_centre: np.ndarray


@dataclass(frozen=True)
class BennettKit:
    params: BennettParams
    layout: Layout
    parts: tuple[Part, ...]
    bodies: dict
    masses: dict[int, LinkMass]
    pins: dict[int, list[tuple[float, np.ndarray]]]  # link -> [(mass g, body point)]
    cups: dict[int, Cup]
    fill: dict[str, dict[int, float]]  # model -> link -> fill mass g
    delta: dict[int, np.ndarray]  # link -> (3,) mm: its pocket's offset from the nominal point
    figures: dict = field(default_factory=dict)

    def frames(self, q1, q4) -> dict[int, np.ndarray]:
        return bbf.link_frames(bbf.pose(self.params.bb, q1, q4))

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        """Placement (4, 4) of every part at the home pose (``theta`` turns the linkage about S)."""
        return self.placements(*home_inputs(self.params.home, theta))

    def placements(self, q1: float, q4: float) -> dict[str, np.ndarray]:
        """Placement (4, 4) of every part, pins included, at inputs (q1, q4) rad."""
        fr = self.frames(q1, q4)
        out = {f"link{i:02d}": fr[i][0] for i in range(1, 13)}
        out["base"] = np.eye(4)
        for j in bbf.JOINTS:
            owner = self.layout.members(j)[0]
            lo, hi = pin_span(self.params, self.layout, j)
            pt, ax = (np.zeros(3), np.array([0.0, 0.0, 1.0])) if owner == BASE else self.bodies[owner][j]
            local = _axis_frame(pt + (lo + hi) / 2 * ax, ax)
            out[f"pin_{j}"] = (np.eye(4) if owner == BASE else fr[owner][0]) @ local
        return out


def _axis_frame(origin: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """(4, 4) frame at ``origin`` whose z is ``axis``."""
    z = axis / np.linalg.norm(axis)
    x = np.cross([0.0, 1.0, 0.0] if abs(z[1]) < 0.9 else [1.0, 0.0, 0.0], z)
    x /= np.linalg.norm(x)
    T = np.eye(4)
    T[:3, :3] = np.column_stack([x, np.cross(z, x), z])
    T[:3, 3] = origin
    return T


def pin_span(p: BennettParams, lay: Layout, joint: str) -> tuple[float, float]:
    """(start, end) of the joint's pin along its axis, mm from the joint point."""
    pitch = p.boss_length + p.axial_gap
    offs = [lay.offset(joint, i, pitch) for i in lay.members(joint)]
    return min(offs) - p.boss_length / 2 - 1.0, max(offs) + p.boss_length / 2 + 1.0


def _pin_masses(p: BennettParams, lay: Layout, bodies: dict) -> dict[int, list[tuple[float, np.ndarray]]]:
    """Each pin is pressed into the bottom member of its stack and turns with it: link -> [(g, body point)]."""
    out: dict[int, list] = {i: [] for i in range(0, 13)}
    for j in bbf.JOINTS:
        lo, hi = pin_span(p, lay, j)
        m = p.pin_density * math.pi * p.pin_radius ** 2 * (hi - lo)
        owner = lay.members(j)[0]
        if owner == BASE:
            out[BASE].append((m, np.array([0.0, 0.0, (lo + hi) / 2])))
            continue
        pt, ax = bodies[owner][j]
        out[owner].append((m, pt + (lo + hi) / 2 * ax))
    return out


def solve_counterweights(p: BennettParams, masses: dict[int, tuple[float, np.ndarray]], pins, cups: dict[int, Cup],
                         q1: np.ndarray, q4: np.ndarray, scale: dict[int, float] | None = None) -> tuple[dict[int, float], float]:
    """Fill masses (g) in the cups that bring the common centre of mass to S over the poses, and the
    worst remaining offset (mm). ``masses``: link -> (mass g, body centre (3,))."""
    m, c = _combine(masses, pins, scale)
    P = bbf.pose(p.bb, q1, q4)
    free = [(i, cups[i].pocket_centre) for i in p.cw_links]
    x, worst = bbf.solve_point_masses(P, m, c, free)
    return dict(zip(p.cw_links, map(float, x))), worst


def _combine(masses, pins, scale=None):
    """Link mass and centre with its pins (and an optional mass scale per link, for seeded faults)."""
    m, c = {}, {}
    for i, (mi, ci) in masses.items():
        mi = mi * (scale or {}).get(i, 1.0)
        tot, mom = mi, mi * np.asarray(ci, float)
        for mp, pp in pins.get(i, []):
            tot, mom = tot + mp, mom + mp * pp
        m[i], c[i] = tot, mom / tot
    return m, c


def com_deviation(kit: BennettKit, model: str, q1, q4, fill: dict[int, float] | None = None,
                  infill: float | None = None, scale: dict[int, float] | None = None) -> np.ndarray:
    """(n,) distance (mm) of the common centre of mass from S, links + pins + cup fills, under the
    'solid' or 'fdm' mass model (optionally at another infill fraction)."""
    p = kit.params
    masses = {}
    for i, lm in kit.masses.items():
        if model == "solid":
            masses[i] = (lm.solid_mass, lm.solid_centre)
        else:
            if infill is None:
                masses[i] = (lm.fdm_mass, lm.fdm_centre)
            else:
                # shell and interior keep their centres; only the interior's mass changes
                shell_c = (lm.solid_centre * (lm.shell_volume + lm.interior_volume)
                           - lm.interior_centre * lm.interior_volume) / lm.shell_volume
                ms = p.density * lm.shell_volume
                mi = p.density * infill * lm.interior_volume
                masses[i] = (ms + mi, (ms * shell_c + mi * lm.interior_centre) / (ms + mi))
    m, c = _combine(masses, kit.pins, scale)
    fill = fill if fill is not None else kit.fill[model]
    for i, f in fill.items():
        cp = kit.cups[i].pocket_centre
        m[i], c[i] = m[i] + f, (m[i] * c[i] + f * cp) / (m[i] + f)
    P = bbf.pose(p.bb, q1, q4)
    return np.linalg.norm(bbf.centre_of_mass(P, m, c), axis=1)


def layout(p: BennettParams, progress=None) -> tuple[Layout, dict, np.ndarray, float, float]:
    """The automatic stack layout over the workspace: (layout, bodies, angles, step rad, clearance mm)."""
    bodies = bbf.body_joints(p.bb)
    speed = point_speed(p, *p.workspace)
    # the search samples more coarsely (4× the step); the check sweeps at the full step
    angles, step = shape_samples(p, *p.workspace, speed)
    lay, clear = choose_offsets(p, coarse_samples(angles), bodies, progress, p.layers)
    return lay, bodies, angles, step, clear


def coarse_samples(angles: np.ndarray) -> np.ndarray:
    """Every fourth sample and both ends: what the layout search sweeps (the check sweeps them all)."""
    return angles if len(angles) <= 8 else np.unique(np.concatenate([angles[::4], angles[-1:]]))


def build_bennett(p: BennettParams, progress=None, lay: Layout | None = None) -> BennettKit:
    """Lay out the stacks, build the links and base, weigh them (solid and FDM) and size the counterweights."""
    say = progress or (lambda s: None)
    bodies = bbf.body_joints(p.bb)
    figures = {}
    if lay is None and p.fixed_layout is not None:
        lay = Layout({BASE: 0, **p.fixed_layout[0]}, dict(p.fixed_layout[1]))
        figures["layout_source"] = "fixed"
    if lay is None:
        lay, bodies, angles, step, clear = layout(p, say)
        figures.update({"layout_source": "auto", "search_clearance_mm": clear})
    pins = _pin_masses(p, lay, bodies)
    q1g, q4g = _grid(p)
    P = bbf.pose(p.bb, q1g, q4g)
    solids, masses, cups = {}, {}, {}

    def make(i: int, delta: dict):
        bosses, bars, cw = _link_features(p, i, lay, bodies[i], delta)
        solid = link_solid(bosses, bars, cw, p.segments)
        mm = printed_mass(solid, p.density, print_settings(p))
        solids[i] = solid
        masses[i] = LinkMass(mm.solid_mass, np.asarray(mm.solid_centre), mm.mass, np.asarray(mm.centre),
                             mm.shell_volume, mm.interior_volume, np.asarray(mm.interior_centre))
        if cw:
            cups[i] = cw[0]

    for i in range(1, 13):
        say(f"link {i}")
        make(i, {})
    # counterweights: the fill masses and how far each pocket moves off the link line; the pockets
    # change their links' own mass, so size, rebuild those links, size again (it settles in a few rounds)
    delta = {i: np.zeros(3) for i in p.cw_links}
    history = []
    for rnd in range(4):
        say(f"counterweights, round {rnd + 1}")
        m, c = _combine({i: (lm.fdm_mass, lm.fdm_centre) for i, lm in masses.items()}, pins)
        nominal = [(i, cw_nominal(p, i, bodies[i], lay)) for i in p.cw_links]
        fills, dl, worst = bbf.solve_counterweights(P, m, c, nominal)
        # the fill sits at the pocket centre: its mass and offset are the solution, the cup walls follow
        new = {i: d for (i, _), d in zip(nominal, dl)}
        history.append(max(float(np.linalg.norm(new[i] - delta[i])) for i in p.cw_links))
        delta = new
        for i in p.cw_links:
            make(i, delta)
    if figures.get("layout_source") == "auto":
        # the pockets moved: refine the layout with them where they are, then size the weights again
        speed = point_speed(p, *p.workspace)
        angles, _ = shape_samples(p, *p.workspace, speed)
        lay, clear = choose_offsets(p, coarse_samples(angles), bodies, say, p.layers, rounds=2, start=lay, delta=delta)
        figures["search_clearance_mm"] = clear
        pins = _pin_masses(p, lay, bodies)
        for i in range(1, 13):
            make(i, delta)
        for rnd in range(3):
            say(f"counterweights, refined round {rnd + 1}")
            m, c = _combine({i: (lm.fdm_mass, lm.fdm_centre) for i, lm in masses.items()}, pins)
            nominal = [(i, cw_nominal(p, i, bodies[i], lay)) for i in p.cw_links]
            _, dl, _ = bbf.solve_counterweights(P, m, c, nominal)
            delta = {i: d for (i, _), d in zip(nominal, dl)}
            for i in p.cw_links:
                make(i, delta)
    m, c = _combine({i: (lm.fdm_mass, lm.fdm_centre) for i, lm in masses.items()}, pins)
    at = [(i, cups[i].pocket_centre) for i in p.cw_links]
    fdm, _ = bbf.solve_point_masses(P, m, c, at)
    m, c = _combine({i: (lm.solid_mass, lm.solid_centre) for i, lm in masses.items()}, pins)
    solid_fill, _ = bbf.solve_point_masses(P, m, c, at)
    fill = {"fdm": dict(zip(p.cw_links, map(float, fdm))), "solid": dict(zip(p.cw_links, map(float, solid_fill)))}
    figures.update({"pocket_offsets_mm": {i: [round(float(x), 3) for x in delta[i]] for i in p.cw_links},
                    "pocket_moves_per_round_mm": history})
    parts = [Part(f"link{i:02d}", "bennett_link", solids[i]) for i in range(1, 13)]
    bosses, bars = _base_features(p, lay)
    parts.append(Part("base", "bennett_base", link_solid(bosses, bars, [], p.segments)))
    for j in bbf.JOINTS:
        lo, hi = pin_span(p, lay, j)
        parts.append(Part(f"pin_{j}", "pin", _pin_solid(p, hi - lo), printed=False,
                          info=(("diameter_mm", 2 * p.pin_radius), ("length_mm", round(hi - lo, 3)),
                                ("material", "steel dowel"), ("joint", j))))
    kit = BennettKit(p, lay, tuple(parts), bodies, masses, pins, cups, fill, delta, figures)
    return kit


def _pin_solid(p: BennettParams, length: float):
    import manifold3d as m3d
    return m3d.Manifold.cylinder(length, p.pin_radius, -1.0, p.segments, True)


def _grid(p: BennettParams) -> tuple[np.ndarray, np.ndarray]:
    """The balance grid: q1 over a full turn × the shape angle over the workspace (flattened)."""
    nq, ns = p.grid
    q1 = np.linspace(0, 2 * np.pi, nq, endpoint=False)
    ang = np.linspace(*p.workspace, ns)
    Q1, A = np.meshgrid(q1, ang, indexing="ij")
    return home_inputs(A.ravel(), Q1.ravel())[0], home_inputs(A.ravel(), Q1.ravel())[1]
