"""The balanced Bennett butterfly as a kit: twelve printed links, a base, steel pins, and
counterweight pockets sized so the common centre of mass stays at S in every pose.

``build_bennett`` lays the stacks out (``bennett_layout``), builds and weighs every part (solid and
as printed, ``geometry.mass``), then sizes the counterweights: the fill masses and how far each
pocket sits off its nominal point (``design.bennett_butterfly.solve_counterweights``); the pockets
change their own links' mass, so it sizes, rebuilds those links and sizes again until they settle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..design import bennett_butterfly as bbf
from ..design.bennett_butterfly import BennettParams
from ..geometry.bennett_link import Cup, link_solid, pin_solid
from ..geometry.mass import printed_mass
from ..geometry.parts import Part
from .bennett_layout import (Sweep, choose_offsets, coarse_samples, link_capsules, part_reach, point_speed,
                             search_layout, shape_samples, sweep_clearance)
from .bennett_parts import (BASE, Layout, base_features, cw_nominal, default_layout, home_inputs, link_features,
                            pin_span, print_settings)

__all__ = ["BennettKit", "LinkMass", "build_bennett", "com_deviation", "grid",
           # the layout and the parts, for the checks and the tests
           "BASE", "Layout", "Sweep", "choose_offsets", "coarse_samples", "default_layout", "home_inputs",
           "link_capsules", "link_features", "part_reach", "point_speed", "shape_samples", "sweep_clearance"]


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


def _pin_masses(p: BennettParams, lay: Layout, bodies: dict) -> dict[int, list[tuple[float, np.ndarray]]]:
    """Each pin's mass, counted with the bottom member of its stack: its centre lies on the joint axis,
    which every member shares, so this is exact however the pin turns. link -> [(g, body point)]."""
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


def build_bennett(p: BennettParams, progress=None, lay: Layout | None = None) -> BennettKit:
    """Lay out the stacks (``lay``, the config's fixed layout, or a search), build the links and the
    base, weigh them (solid and FDM) and size the counterweights.

    A searched layout is searched with the pockets at their nominal points, the kit sized, the layout
    refined with the pockets where the sizing put them, and the kit built again from that layout —
    by the very path a fixed layout takes, so the kit folder's design.yaml rebuilds it byte for byte."""
    say = progress or (lambda s: None)
    if lay is None and p.fixed_layout is not None:
        lay = Layout({BASE: 0, **p.fixed_layout[0]}, dict(p.fixed_layout[1]))
    if lay is not None:
        return _build(p, lay, say, {"layout_source": "given"})
    lay, bodies, angles, _, _ = search_layout(p, say)
    first = _build(p, lay, say, {})
    lay, clear = choose_offsets(p, coarse_samples(angles), bodies, say, p.layers, rounds=2, start=lay,
                                delta=first.delta)
    return _build(p, lay, say, {"layout_source": "auto", "search_clearance_mm": clear})


def _build(p: BennettParams, lay: Layout, say, figures: dict) -> BennettKit:
    bodies = bbf.body_joints(p.bb)
    q1g, q4g = grid(p)
    P = bbf.pose(p.bb, q1g, q4g)
    solids, masses, cups = {}, {}, {}

    def make(i: int, delta: dict):
        bosses, bars, cw = link_features(p, i, lay, bodies[i], delta)
        solid = link_solid(bosses, bars, cw, p.segments)
        mm = printed_mass(solid, p.density, print_settings(p))
        solids[i] = solid
        masses[i] = LinkMass(mm.solid_mass, np.asarray(mm.solid_centre), mm.mass, np.asarray(mm.centre),
                             mm.shell_volume, mm.interior_volume, np.asarray(mm.interior_centre))
        if cw:
            cups[i] = cw[0]

    def size(delta: dict, rounds: int, settled: float = 1e-3) -> tuple[dict, list[float]]:
        """Solve for the fills and the pockets' offsets, rebuild the cup links, repeat until no
        pocket moves more than ``settled`` mm (or ``rounds`` rounds)."""
        moves = []
        for rnd in range(rounds):
            say(f"counterweights, round {rnd + 1}")
            m, c = _combine({i: (lm.fdm_mass, lm.fdm_centre) for i, lm in masses.items()}, pins)
            nominal = [(i, cw_nominal(p, i, bodies[i], lay)) for i in p.cw_links]
            _, dl, _ = bbf.solve_counterweights(P, m, c, nominal)
            new = {i: d for (i, _), d in zip(nominal, dl)}
            moves.append(max(float(np.linalg.norm(new[i] - delta[i])) for i in p.cw_links))
            delta = new
            for i in p.cw_links:
                make(i, delta)
            if moves[-1] < settled:
                break
        return delta, moves

    pins = _pin_masses(p, lay, bodies)
    for i in range(1, 13):
        say(f"link {i}")
        make(i, {})
    delta, history = size({i: np.zeros(3) for i in p.cw_links}, 12)
    m, c = _combine({i: (lm.fdm_mass, lm.fdm_centre) for i, lm in masses.items()}, pins)
    at = [(i, cups[i].pocket_centre) for i in p.cw_links]
    fdm, _ = bbf.solve_point_masses(P, m, c, at)
    m, c = _combine({i: (lm.solid_mass, lm.solid_centre) for i, lm in masses.items()}, pins)
    solid_fill, _ = bbf.solve_point_masses(P, m, c, at)
    fill = {"fdm": dict(zip(p.cw_links, map(float, fdm))), "solid": dict(zip(p.cw_links, map(float, solid_fill)))}
    figures.update({"pocket_offsets_mm": {i: [round(float(x), 3) for x in delta[i]] for i in p.cw_links},
                    "pocket_moves_per_round_mm": history})
    parts = [Part(f"link{i:02d}", "bennett_link", solids[i]) for i in range(1, 13)]
    bosses, bars = base_features(p, lay)
    parts.append(Part("base", "bennett_base", link_solid(bosses, bars, [], p.segments)))
    for j in bbf.JOINTS:
        lo, hi = pin_span(p, lay, j)
        parts.append(Part(f"pin_{j}", "pin", pin_solid(hi - lo, p.pin_radius, p.segments), printed=False,
                          info=(("diameter_mm", 2 * p.pin_radius), ("length_mm", round(hi - lo, 3)),
                                ("material", p.pin_kind), ("joint", j))))
    kit = BennettKit(p, lay, tuple(parts), bodies, masses, pins, cups, fill, delta, figures)
    return kit


def grid(p: BennettParams) -> tuple[np.ndarray, np.ndarray]:
    """The balance grid: q1 over a full turn × the shape angle over the workspace (flattened)."""
    nq, ns = p.grid
    q1 = np.linspace(0, 2 * np.pi, nq, endpoint=False)
    ang = np.linspace(*p.workspace, ns)
    Q1, A = np.meshgrid(q1, ang, indexing="ij")
    return home_inputs(A.ravel(), Q1.ravel())[0], home_inputs(A.ravel(), Q1.ravel())[1]
