"""Parts of the balanced Bennett butterfly kit in their body frames: each link's bosses (on its
joint axes, at its layer), the bars that join them, its counterweight cup, the base, the pins'
spans. The stack layout (``Layout``) is the design lever: a link's layer sets how far along every
one of its joint axes its bosses sit; a joint's shift moves its whole stack along its axis.

Bought parts are stock: every pin is a stock length (``Stack``: the stack's two end bosses grow
outward until it spans one, the base's bore goes deeper instead), and a counterweight pocket holds
a whole number of stock slugs in a bore exactly as deep as they are (``Fill``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ...design import bennett_butterfly as bbf
from ...design.balanced import LINKS
from .params import BennettParams
from ...errors import DesignError
from ...geometry.bennett_link import Bar, Boss, Column, Cup
from ...geometry.mass import PrintSettings

__all__ = ["BASE", "Layout", "Stack", "Fill", "default_layout", "stack", "guess_fill", "choose_fill", "link_features",
           "base_features", "cup_of", "cw_nominal", "pin_span", "home_inputs", "print_settings"]


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
        """The parts on the joint's pin, bottom to top."""
        return self._members[joint]

    @cached_property
    def _members(self) -> dict[str, tuple[int, ...]]:
        return {j: tuple(sorted(links + ((BASE,) if j == "S14" else ()), key=lambda i: self.layer[i]))
                for j, (links, _, _) in bbf.JOINTS.items()}


def default_layout() -> Layout:
    return Layout({BASE: 0, **{i: 1 + (i - 1) % 4 for i in range(1, 13)}})


@dataclass(frozen=True)
class Stack:
    """One joint's pin and the bosses on it, mm along the joint axis from the joint point: each
    member's boss (start, end), bottom to top; the pin's span, a stock ``length`` that runs through
    every boss from the bottom one's outer face to the top one's."""

    members: tuple[int, ...]
    spans: dict[int, tuple[float, float]]
    pin: tuple[float, float]
    length: float
    extra: float  # mm the stack grew to reach the stock length


def stack(p: BennettParams, lay: Layout, joint: str) -> Stack:
    """The joint's stack with its pin a stock length: the shortest stock pin that spans the bosses
    (their layers' offsets and lengths); the two end bosses grow outward by half the difference
    each, or the base's bore (the base ends the stack at S) goes deeper by all of it."""
    members = lay.members(joint)
    offs = [lay.offset(joint, i, p.pitch) for i in members]
    half = p.boss_length / 2
    lo, hi = offs[0] - half, offs[-1] + half
    need = hi - lo
    length = next((s for s in p.pin_stock if s >= need - 1e-9), None)
    if length is None:
        raise DesignError(f"the stack at {joint} spans {need:.1f} mm, longer than any stock pin (longest "
                          f"{max(p.pin_stock):g} mm): add a longer one or use fewer layers", "pin.stock_lengths_mm")
    extra = length - need
    lo, hi = (lo - extra, hi) if members[0] == BASE else (lo - extra / 2, hi + extra / 2)
    spans = {i: (o - half, o + half) for i, o in zip(members, offs)}
    spans[members[0]] = (lo, spans[members[0]][1])
    spans[members[-1]] = (spans[members[-1]][0], hi)
    return Stack(members, spans, (lo, hi), length, extra)


@dataclass(frozen=True)
class Fill:
    """A counterweight pocket's fill: ``count`` stock slugs (``diameter`` × ``length`` mm, density
    g/mm³) stacked end to end in a bore of ``bore_radius`` exactly ``count × length`` deep, the
    binder filling the rest of it (the radial clearance) to the brim. The pocket is full, so the
    fill's centre is the pocket's."""

    count: int
    diameter: float
    length: float
    density: float
    bore_radius: float
    binder_density: float

    @property
    def depth(self) -> float:
        return self.count * self.length

    @property
    def slug_mass(self) -> float:
        return self.density * math.pi * (self.diameter / 2) ** 2 * self.length

    @property
    def steel_mass(self) -> float:
        return self.count * self.slug_mass

    @property
    def binder_volume(self) -> float:
        return math.pi * self.depth * (self.bore_radius ** 2 - (self.diameter / 2) ** 2)

    @property
    def binder_mass(self) -> float:
        return self.binder_density * self.binder_volume

    @property
    def mass(self) -> float:
        return self.steel_mass + self.binder_mass


def _fill(p: BennettParams, count: int, length: float) -> Fill:
    return Fill(count, p.slug_diameter, length, p.slug_density, (p.slug_diameter + p.cw_clearance) / 2,
                p.binder_density)


def guess_fill(p: BennettParams) -> Fill:
    """The pocket the layout search starts from, before the masses are known: one slug of the
    middle stock length."""
    return _fill(p, 1, p.slug_lengths[len(p.slug_lengths) // 2])


def choose_fill(p: BennettParams, mass: float) -> Fill:
    """The whole number of one stock slug length whose fill (binder included) comes nearest ``mass``
    g (ties: fewer slugs, then the shallower pocket). Any mass balances (the pocket's offset takes up
    the rest); the nearest keeps the offsets smallest."""
    best = None
    for length in p.slug_lengths:
        one = _fill(p, 1, length).mass
        for n in {max(1, math.floor(mass / one)), max(1, math.ceil(mass / one))}:
            f = _fill(p, n, length)
            key = (round(abs(f.mass - mass), 9), n, f.depth)
            if best is None or key < best[0]:
                best = (key, f)
    return best[1]


def cup_of(fill: Fill, centre: np.ndarray, axis: np.ndarray, wall: float) -> Cup:
    """The printed cup around a fill's pocket, the pocket's centre at ``centre`` (3,), its opening
    toward ``axis`` (unit (3,)); ``wall`` around and under it."""
    height = fill.depth + wall
    base_pt = centre - axis * (height - fill.depth / 2)
    return Cup(tuple(base_pt), tuple(axis), fill.bore_radius + wall, height, fill.bore_radius, fill.depth)


def link_features(p: BennettParams, link: int, lay: Layout, body: dict, pocket: tuple | None = None):
    """Bosses, bars and cups of one link in its body frame; ``pocket``: (δ (3,) mm, how far its
    counterweight pocket sits off the nominal point, and its ``Fill``), by default the search's
    first guess at the nominal point."""
    bosses = []
    for j, (pt, ax) in sorted(body.items()):
        lo, hi = stack(p, lay, j).spans[link]
        bosses.append(Boss(tuple(pt), tuple(ax), (lo + hi) / 2, p.boss_radius, hi - lo, p.bore_radius))
    # bars: along the link line, in order of the joint points' x (body x runs along the link)
    cs = sorted(((float(b.point[0]), k) for k, b in enumerate(bosses)))
    bars = []
    for (_, k0), (_, k1) in zip(cs, cs[1:]):
        bars += _bar_between(bosses[k0], bosses[k1], p.bar_radius)
    cups = []
    if link in p.cw_links:
        delta, fill = pocket if pocket is not None else (np.zeros(3), guess_fill(p))
        at = cw_nominal(p, link, body, lay) + np.asarray(delta, float)
        ref_boss = next(b for b in bosses if np.linalg.norm(np.asarray(b.point)) < 1e-9)
        axis = np.asarray(ref_boss.axis, float)
        cup = cup_of(fill, at, axis / np.linalg.norm(axis), p.cw_wall)
        cups.append(cup)
        mid = np.asarray(cup.point) + axis * cup.height / 2
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
    return d * t_pt / np.linalg.norm(t_pt) + body[ref_j][1] * lay.offset(ref_j, link, p.pitch)


def base_features(p: BennettParams, lay: Layout) -> tuple[list[Column], tuple[float, float, float]]:
    """The base in S's frame (z up, as it stands and prints): a round post under the S stack on a
    flat foot, and its bore (radius, bottom, top) from the pin's lower end up through the top face,
    open where the pin goes in. Columns: the post below the pin, the post around it (covered like
    a boss), the foot."""
    lo, top = stack(p, lay, "S14").spans[BASE]
    z_bed = top - p.boss_length - p.base_height
    if lo < z_bed + p.foot_thickness + 1.0:
        raise DesignError(f"the S pin's bore ({top - lo:.1f} mm deep) reaches the foot: make the post taller",
                          "base.height_mm")
    k = math.ceil(math.pi / (2 * math.asin(min(1.0, max(p.foot_thickness / 2, 2.0) / p.foot_radius))))
    columns = [Column(z_bed, lo, p.boss_radius), Column(lo, top, p.boss_radius, 4),
               Column(z_bed, z_bed + p.foot_thickness, p.foot_radius, max(4, k))]
    return columns, (p.bore_radius, lo, top)


def pin_span(p: BennettParams, lay: Layout, joint: str) -> tuple[float, float]:
    """(start, end) of the joint's pin along its axis, mm from the joint point (a stock length)."""
    return stack(p, lay, joint).pin
