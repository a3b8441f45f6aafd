"""Parts of the balanced Bennett butterfly kit in their body frames: each link's bosses (on its
joint axes, at its layer), the bars that join them, its counterweight cup, the base, the pins'
spans. The stack layout (``Layout``) is the design lever: a link's layer sets how far along every
one of its joint axes its bosses sit; a joint's shift moves its whole stack along its axis.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..design import bennett_butterfly as bbf
from ..design.balanced import LINKS
from ..design.bennett_butterfly import BennettParams
from ..geometry.bennett_link import Bar, Boss, Cup
from ..geometry.mass import PrintSettings

__all__ = ["BASE", "Layout", "default_layout", "link_features", "base_features", "cw_nominal", "pin_span",
           "home_inputs", "print_settings"]


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


def link_features(p: BennettParams, link: int, lay: Layout, body: dict, delta: dict | None = None):
    """Bosses, bars and cups of one link in its body frame; ``delta``: link -> (3,) mm, how far a
    counterweight pocket sits off its nominal point on the link line."""
    bosses = [Boss(tuple(pt), tuple(ax), lay.offset(j, link, p.pitch), p.boss_radius, p.boss_length, p.bore_radius)
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
    return d * t_pt / np.linalg.norm(t_pt) + body[ref_j][1] * lay.offset(ref_j, link, p.pitch)


def base_features(p: BennettParams, lay: Layout):
    off = lay.offset("S14", BASE, p.pitch)
    boss = Boss((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), off, p.boss_radius, p.boss_length, p.bore_radius)
    top = off - p.boss_length / 2
    # the column is a capsule of the boss's radius: its upper ball must overlap the boss (by h) but
    # stay under the boss's far face, or it seals the pin's bore shut (a void inside the base)
    h = min(p.boss_length, p.boss_radius) / 2
    column = Bar((0.0, 0.0, top - p.boss_radius + h), (0.0, 0.0, top - p.base_height), p.boss_radius)
    return [boss], [column]


def pin_span(p: BennettParams, lay: Layout, joint: str) -> tuple[float, float]:
    """(start, end) of the joint's pin along its axis, mm from the joint point."""
    offs = [lay.offset(joint, i, p.pitch) for i in lay.members(joint)]
    return min(offs) - p.boss_length / 2 - 1.0, max(offs) + p.boss_length / 2 + 1.0
