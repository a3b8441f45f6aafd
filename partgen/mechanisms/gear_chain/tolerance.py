"""The gear chain's tolerance model: the margins of one nominal check as linear functions of the
printed features' deviations (``design.tolerance``).

Where the chain's features sit (``δ`` = a feature's deviation, ``e = δ/2`` for an outline given as
a diameter):

* **Running fits** (G_j+1 and M_j on B_j's post and pin, G1 on the ground post, the drive axle in
  the base): radial gap ``(hole − pin)/2`` measured by the check, + ``δ_bore/2 − δ_pin/2``.
* **Centre distances.** D_j turns about B_j's proximal hole (both sit on B_j-1's post), M_j on
  B_j's idler pin, G_j+1 on B_j's distal post: each centre distance of a stage is a distance
  between two features of plate B_j, changed by the projection of their position deviations on
  the line of centres (the drive pair: the base's ground post and drive bearing).
* **Where the gears sit** (``seated``, the default; docs/tolerance.md). The floating bodies are
  the drive gear (on its axle in the base), each idler M_j (on B_j's pin) and each link B_j with
  its gear G_j (on B_j-1's post; G1 on the ground post): D_j is pressed onto B_j-1, so B_j's play
  moves M_j's pin away from D_j. A mesh that runs out of backlash pushes its two bodies apart
  along its line of centres; a body gives each of its meshes ``κ`` of its radial play at once
  (``design.tolerance.seat_factor``: 1 for one mesh; for two, the projection of their summed
  separating directions, the least over the crank's turn for a link whose two meshes sit on
  different plates). The play is the printed one (nominal + bore and pin deviations), so the
  credit and the fit's own margin move together. ``seated=False``: every gear centred (no play
  credited, the worst case). The clearances between passing parts are taken with the bodies
  centred.
* **Meshes**: backlash (circumferential, on the operating pitch circle) changes by
  ``2·tan α_w · Δa − (δ_a + δ_b)/cos α_w`` (a flank moved out by e thickens the tooth by
  2e/cos α_w there); each tip-to-root clearance by ``Δa − δ_a/2 − δ_b/2``.
* **Clearances over the motion** (pairs the check found closer than its reach): in the plane, the
  gap changes by the relative displacement of the two parts' axes along the line between them at
  the closest crank angle (joint J_k moves by Σ_i≤k R(α_i)(Δpost_i − Δproximal_i), the link
  lengths and the lateral offsets of each plate's posts) less the two outlines' growth; along z,
  by the stack height under the upper part less the lower part's thickness.
"""

from __future__ import annotations

import math
import numpy as np

from ...core.findings import Result
from ...design.kinematics import link_angles
from ...design.tolerance import Margin, MarginModel, ModelBuilder, Play, seat_credit, seat_factor
from .kit import Kit

__all__ = ["tolerance_model"]


def _pos(part: str, feature: str) -> tuple[tuple[str, str, str], tuple[str, str, str]]:
    """The x and y position features of ``feature`` on ``part`` (in the part's frame)."""
    return ((f"{part} {feature} x", "position", part), (f"{part} {feature} y", "position", part))


def _project(terms: dict, feature: str, part: str, vec, sign: float = 1.0) -> None:
    """Add sign · (vec · Δposition of the feature) to ``terms`` (vec: (2,) in the part's frame)."""
    fx, fy = _pos(part, feature)
    terms[fx] = terms.get(fx, 0.0) + sign * float(vec[0])
    terms[fy] = terms.get(fy, 0.0) + sign * float(vec[1])


def _rot(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


class _Chain:
    """Where each part's axis is, as position features, and how it moves in the world."""

    def __init__(self, kit: Kit):
        self.kit = kit
        mech = kit.mechanism
        self.n = len(mech.chain.links)
        self.idler = {s.j: np.asarray(s.idler, dtype=float) for s in mech.stages}
        self.idler.update({s.j: np.asarray(s.tensioner, dtype=float) for s in mech.belt_stages if s.tensioner is not None})
        self.length = {j: l.length for j, l in enumerate(mech.chain.links, 1)}

    def joint(self, k: int, theta: float) -> list[tuple[str, str, np.ndarray]]:
        """World displacement of joint J_k as [(part, feature, (2, 2) matrix: Δworld = M @ Δlocal)]."""
        out = [("base", "ground post", np.eye(2))]
        a = link_angles(self.kit.mechanism, theta)
        for i in range(1, k + 1):
            R = _rot(a[i])
            out += [(f"B{i}", "distal post", R), (f"B{i}", "proximal hole", -R)]
        return out

    def axis(self, name: str, theta: float) -> list[tuple[str, str, np.ndarray]] | None:
        """World displacement of the axis ``name`` turns about (None: not modelled)."""
        kind, num = name[:1], name[1:]
        a = link_angles(self.kit.mechanism, theta)
        if name in ("G1", "base"):
            return self.joint(0, theta)
        if name in ("drive", "drive_axle", "crank"):
            return [("base", "drive bearing", np.eye(2))]
        if name == "pen_holder":
            return self.joint(self.n, theta)
        if not num.isdigit():
            return None
        j = int(num)
        if kind == "D" or kind == "B":  # D_j on B_j-1's post; a plate by its proximal hole
            return self.joint(j - 1, theta)
        if kind == "G":
            return self.joint(j - 1, theta)
        if kind in "MT":
            R = _rot(a[j])
            return self.joint(j - 1, theta) + [(f"B{j}", "idler pin", R), (f"B{j}", "proximal hole", -R)]
        return None


def _mesh_terms(chain: _Chain, a: str, b: str) -> tuple[dict, float] | None:
    """Δ(centre distance) of a mesh as position terms (in the carrier plate's frame), and the
    distance itself."""
    terms: dict = {}
    if {a, b} == {"G1", "drive"}:
        dc = np.asarray(chain.kit.mechanism.drive_centre, dtype=float)
        u = dc / np.linalg.norm(dc)
        _project(terms, "drive bearing", "base", u)
        _project(terms, "ground post", "base", u, -1.0)
        return terms, float(np.linalg.norm(dc))
    names = {name[0]: name for name in (a, b)}
    j = int((names.get("M") or a)[1:])
    c = chain.idler[j]
    post = np.array([chain.length[j], 0.0])
    if "D" in names:  # D_j (about the proximal hole) and M_j (the idler pin)
        u = c / np.linalg.norm(c)
        _project(terms, "idler pin", f"B{j}", u)
        _project(terms, "proximal hole", f"B{j}", u, -1.0)
        return terms, float(np.linalg.norm(c))
    u = (post - c) / np.linalg.norm(post - c)  # M_j and G_j+1 (the distal post)
    _project(terms, "distal post", f"B{j}", u)
    _project(terms, "idler pin", f"B{j}", u, -1.0)
    return terms, float(np.linalg.norm(post - c))


def _tooth(name: str) -> tuple[str, str, str]:
    return (f"{name} teeth", "tooth", name)


def _where(a: str) -> str:
    if a[:1] in "DMGBT" and a[1:].isdigit():
        j = int(a[1:]) - (1 if a[0] == "G" else 0)
        return f"link {j}" if j >= 1 else "base"
    return "base"


def _pin_of(c) -> tuple[str, str, str, str]:
    """(hole part, hole feature, pin part, pin feature) of a running contact."""
    if c.a == "drive_axle":
        return c.b, "drive bearing", c.a, "shaft"
    if c.a[:1] in "MT":
        return c.a, "bore", c.b, "idler pin"
    return c.a, "bore", c.b, "post" if c.b != "base" else "ground post"


SEAT_ANGLES = 72  # crank angles over a turn at which a link's seat factor is taken (the least)


def _mesh_bodies(chain: _Chain, a: str, b: str, theta: float) -> list[tuple[str, np.ndarray]] | None:
    """The floating bodies a mesh's centre distance depends on, each with the world direction
    (at crank angle ``theta``) in which moving that body in its bore opens the mesh. A body is
    named by the gear that runs in the bore: ``drive``, ``G<j>`` (link B_j) or ``M<j>``/``T<j>``."""
    if {a, b} == {"G1", "drive"}:
        dc = np.asarray(chain.kit.mechanism.drive_centre, dtype=float)
        u = dc / np.linalg.norm(dc)
        return [("drive", u), ("G1", -u)]
    names = {name[0]: name for name in (a, b)}
    m = names.get("M") or names.get("T")
    if m is None:
        return None
    j = int(m[1:])
    R = _rot(link_angles(chain.kit.mechanism, theta)[j])
    c = chain.idler[j]
    if "D" in names:  # M_j on B_j's pin; B_j (on G_j's bore) carries the pin away from D_j
        u = R @ (c / np.linalg.norm(c))
        return [(m, u), (f"G{j}", u)]
    post = np.array([chain.length[j], 0.0])
    v = R @ ((post - c) / np.linalg.norm(post - c))  # from M_j towards G_j+1
    return [(m, -v), (f"G{j + 1}", v)]


def seat_factors(kit: Kit, pairs, angles: int = SEAT_ANGLES) -> dict[str, float]:
    """κ of every floating body whose meshes are ``pairs`` (name pairs): the least over ``angles``
    crank angles of ``seat_factor`` of its meshes' separating directions."""
    chain = _Chain(kit)
    kappa: dict[str, float] = {}
    for theta in np.linspace(0.0, 2 * math.pi, angles, endpoint=False):
        dirs: dict[str, list] = {}
        for a, b in pairs:
            for body, u in _mesh_bodies(chain, a, b, float(theta)) or []:
                dirs.setdefault(body, []).append(u)
        for body, us in dirs.items():
            kappa[body] = min(kappa.get(body, 1.0), seat_factor(us))
    return kappa


def tolerance_model(kit: Kit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) as a ``MarginModel`` for a printer
    accuracy of ± ``accuracy_mm`` (``seated``: gears where their meshes push them in their bores;
    otherwise centred)."""
    b = ModelBuilder()
    chain = _Chain(kit)
    fits = {tuple(r["parts"]): r for r in result.figures.get("fits", {}).get("rows", [])}
    # running fits
    plays: dict[str, Play] = {}
    for c in kit.contacts:
        if c.kind != "running":
            continue
        hole, hf, pin, pf = _pin_of(c)
        nominal = fits.get((c.a, c.b), {}).get("radial_gap_mm", c.radial_gap)
        terms = {(f"{hole} {hf}", "hole", hole): 0.5, (f"{pin} {pf}", "pin", pin): -0.5}
        b.add(Margin(f"{c.a} on {c.b}", "joint", "radial gap", float(nominal), _where(c.a)), terms)
        plays["drive" if c.a == "drive_axle" else c.a] = Play(float(nominal), terms)
    # meshes
    parts = {p.name: p for p in kit.parts}
    rows = result.figures.get("meshes", [])
    kappa = seat_factors(kit, [tuple(r["pair"]) for r in rows]) if seated else {}
    for row in rows:
        a, bb = row["pair"]
        ga, gb = parts[a].gear, parts[bb].gear
        got = _mesh_terms(chain, a, bb)
        if got is None:
            continue
        pos, _ = got
        bodies = _mesh_bodies(chain, a, bb, 0.0) or []
        credit, credit_terms = seat_credit([(kappa.get(body, 0.0), plays[body]) for body, _ in bodies
                                            if body in plays])
        pos = dict(pos)
        for key, c in credit_terms.items():
            pos[key] = pos.get(key, 0.0) + c
        a_op = float(row["centre_distance_mm"])
        rb = (ga.pitch_radius + gb.pitch_radius) * math.cos(ga.system.pressure_angle)
        aw = math.acos(min(1.0, rb / a_op))
        unit, where = f"{a}/{bb}", _where(bb)
        terms = {k: 2 * math.tan(aw) * v for k, v in pos.items()}
        terms[_tooth(a)] = -1.0 / math.cos(aw)
        terms[_tooth(bb)] = -1.0 / math.cos(aw)
        b.add(Margin(unit, "mesh", "backlash", float(row["backlash_mm"]) + 2 * math.tan(aw) * credit, where,
                     2 * math.cos(ga.system.pressure_angle) / math.cos(aw)), terms)
        for key, value in row["tip_clearance_mm"].items():
            terms = dict(pos)
            terms[_tooth(a)] = -0.5
            terms[_tooth(bb)] = -0.5
            b.add(Margin(unit, "mesh", f"tip-root {key.replace('->', '→')}", float(value) + credit, where), terms)
    # Eq 12: D_j and G_j+1 share a layer and turn at different speeds, so their tips pass each
    # other on the line of centres at some crank angle: their tip circles must clear
    for s in kit.mechanism.stages:
        j, D, G = s.j, f"D{s.j}", f"G{s.j + 1}"
        nominal = chain.length[j] - s.D.tip_radius - s.G.tip_radius
        terms = {_tooth(D): -0.5, _tooth(G): -0.5}
        _project(terms, "distal post", f"B{j}", (1.0, 0.0))
        _project(terms, "proximal hole", f"B{j}", (1.0, 0.0), -1.0)
        b.add(Margin(f"{D}–{G}", "clearance", "tip circles", float(nominal), f"link {j}"), terms)
    # clearances over the motion
    poses_at: dict = {}
    for g in result.figures.get("motion", {}).get("gaps", []):
        pa, pb = g["parts"]
        unit = f"{pa}–{pb}"
        if g["axis"] == "z":  # the stack under the upper part, less the lower part's thickness
            b.add(Margin(unit, "clearance", "axial gap", float(g["mm"]), _where(pb)),
                  {(f"{pb} stack height", "height", pb): 1.0, (f"{pa} thickness", "height", pa): -1.0})
            continue
        theta = math.radians(g["theta_deg"])
        if theta not in poses_at:
            poses_at[theta] = kit.poses(theta)
        P = poses_at[theta]
        d = P[pb][:2, 3] - P[pa][:2, 3]
        terms = {}
        for name in (pa, pb):
            kind = _tooth(name) if parts[name].gear is not None else (f"{name} outline", "outline", name)
            terms[kind] = -0.5
        dist = float(np.linalg.norm(d))
        ax_a, ax_b = chain.axis(pa, theta), chain.axis(pb, theta)
        if dist > 1e-9 and ax_a is not None and ax_b is not None:
            u = d / dist
            for sign, ax in ((1.0, ax_b), (-1.0, ax_a)):
                for part, feat, M in ax:
                    _project(terms, feat, part, u @ M, sign)
        b.add(Margin(unit, "clearance", "gap", float(g["mm"]), _where(pb)), terms)
    return b.model(accuracy_mm, kit.name, "gears seated by their meshes in their bores" if seated else "every gear centred on its post (no bore play credited)")
