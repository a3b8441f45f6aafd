"""The balanced Bennett butterfly's tolerance model: what makes a print of it fail, as linear margins of
the printed features' deviations (``design.tolerance``; docs/tolerance.md "Bennett linkage").

* **Pins in their bores** (a ``joint`` per member of every stack): each printed boss turns on a steel
  dowel with radial gap ``(bore − pin)/2`` + ``δ_bore/2`` (a ground dowel's own tolerance, a few
  µm, is left out).
* **The loops close** (``joint``, one unit per Bennett loop). A Bennett linkage moves only because its
  opposite links match: printed, each link's bores stand where its position deviations put them, and
  the loop's closure error — the sum round the loop of each link's bore-to-bore displacement, in the
  world, ``e = Σ_k R_k (Δp_k,out − Δp_k,in)`` — must be taken up by the play of the loop's four
  joints (each: both members' radial play about its pin). The margins are ``Σ play − w·e`` over
  ``SPHERE`` directions ``w`` at the workspace's two ends and its home angle (the largest projection
  is within ``COVER`` of |e|). Joint axes printed askew (twist errors) and the coupling joints C1, C2
  (which close further loops through two Bennetts) are not modelled.
* **Balance as printed** (``balance``): the common centre of mass of the links, pins and fills must
  stay within ``checks.balance_tolerance_mm`` of S. Its scatter comes from each link's infill
  fraction (``process``, σ = the design's ``checks.infill_error_percent_points`` / 3: part to part,
  independent), each link's walls (its outline grown by δ/2 in the print's plane adds ``density · A_side · δ/2``
  at the link's centre, ``A_side`` the faces' area times the horizontal part of their normals as
  the link prints: ``side_area``), each pocket's place on its link (three position coordinates: the fill moves with
  it) and its bore (a wider bore holds more binder in place of printed material). The margins are
  ``tol − w·d(g)`` over ``SPHERE`` directions at ``BALANCE_POSES`` poses of the check's grid (the
  worst nominal ones and a spread), ``d(g) = d₀(g) + Σ J(g)·δ`` to first order (a mass δm at X moves
  the centre by δm (X − centre)/M). The slugs are ground dowels (their mass scatter, ~0.1 %, is left
  out); the binder is taken to centre them in their pockets.

No gear sits in a bore: ``seated`` changes nothing (the worst case is the headline).
"""

from __future__ import annotations

import math

import numpy as np

from ...core.findings import Result
from ...design import bennett_butterfly as bbf
from ...design.tolerance import Margin, MarginModel, ModelBuilder
from . import kit as A

__all__ = ["tolerance_model", "LOOPS", "SPHERE", "BALANCE_POSES", "directions"]

LOOPS = ((1, 2, 3, 4), (4, 5, 6, 7), (7, 8, 9, 10), (10, 11, 12, 1))  # the four Bennett loops, link by link
SPHERE = 32  # directions over the sphere a 3-D error is projected on
BALANCE_POSES = 12  # poses of the balance grid the balance margins are taken at


def directions(n: int = SPHERE) -> np.ndarray:
    """(n, 3) unit vectors spread evenly over the sphere (a Fibonacci lattice)."""
    k = np.arange(n) + 0.5
    z = 1 - 2 * k / n
    r = np.sqrt(1 - z * z)
    phi = math.pi * (3 - math.sqrt(5)) * k
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def cover(n: int = SPHERE, probes: int = 20000) -> float:
    """The least, over unit vectors, of their largest projection on ``directions(n)``: how far
    below |e| the margins' max_w w·e can fall (measured on a dense lattice)."""
    return float((directions(probes) @ directions(n).T).max(axis=1).min())


def side_area(solid, body_from_print) -> float:
    """mm²: the part's surface area as the printer's xy error sees it — each face's area times the
    horizontal part of its normal in the part's print orientation (an outline grown by δ/2 in the
    plane adds that times δ/2 of material; a flat top or bottom adds none)."""
    from ...geometry.solid import mesh_arrays

    v, f = mesh_arrays(solid)
    cross = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    area2 = np.linalg.norm(cross, axis=1)
    up = np.asarray(body_from_print, float)[:3, 2]  # the print's z in the body frame
    cos = np.abs(cross @ up) / np.where(area2 > 0, area2, 1.0)
    return float((0.5 * area2 * np.sqrt(np.clip(1 - cos * cos, 0.0, 1.0))).sum())


def _name(i: int) -> str:
    return "base" if i == A.BASE else f"link{i:02d}"


def _joint_of(a: int, b: int) -> str:
    return next(j for j, (pair, _, _) in bbf.JOINTS.items() if set(pair) == {a, b})


def tolerance_model(kit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of the Bennett ``kit`` (``result``: its nominal check) for a printer accuracy of
    ± ``accuracy_mm``."""
    p = kit.params
    b = ModelBuilder()
    gap = p.bore_radius - p.pin_radius
    for j in bbf.JOINTS:
        for i in kit.layout.members(j):
            bore = (f"{_name(i)} bore {j}", "hole", _name(i))
            b.add(Margin(f"{_name(i)} on pin {j}", "joint", "radial gap", gap, _name(i)), {bore: 0.5})
    W = directions()
    # the loops close
    angles = sorted({float(p.workspace[0]), float(p.home), float(p.workspace[1])})
    q1, q4 = A.home_inputs(np.array(angles))
    frames = kit.frames(q1, q4)
    for n, loop in enumerate(LOOPS, 1):
        joints = [_joint_of(loop[k - 1], loop[k]) for k in range(len(loop))]  # joint k: into link k
        # each joint's play between the loop's two links there: both their bores' radial play
        total = 2 * len(joints) * gap
        base_terms: dict = {}
        for k, j in enumerate(joints):
            for i in (loop[k - 1], loop[k]):
                base_terms[(f"{_name(i)} bore {j}", "hole", _name(i))] = 0.5
        for g, ang in enumerate(angles):
            e_terms: list[tuple[tuple, np.ndarray]] = []  # (feature, world vector of e per unit of it)
            for k, link in enumerate(loop):
                R = frames[link][g][:3, :3]
                j_in, j_out = joints[k], joints[(k + 1) % len(loop)]
                for j, sign in ((j_out, 1.0), (j_in, -1.0)):
                    for axis, c in enumerate("xyz"):
                        e_terms.append(((f"{_name(link)} bore {j} {c}", "position", _name(link)), sign * R[:, axis]))
            for w in W:
                terms = dict(base_terms)
                for key, vec in e_terms:
                    terms[key] = terms.get(key, 0.0) - float(w @ vec)
                b.add(Margin(f"Bennett {n} loop", "joint", f"closure at {math.degrees(ang):.0f}°", total, "S"), terms)
    # balance as printed
    _balance(b, kit, W)
    return b.model(accuracy_mm, kit.name, "no gear runs in a bore: no play to credit, the worst case is the headline")


def _balance(b: ModelBuilder, kit, W: np.ndarray) -> None:
    p = kit.params
    q1, q4 = A.grid(p)
    P = bbf.pose(p.bb, q1, q4)
    frames = bbf.link_frames(P)
    masses = {i: (lm.fdm_mass, lm.fdm_centre) for i, lm in kit.masses.items()}
    m, c = A._combine(masses, kit.pins)
    for i, pts in A.fill_points(kit).items():
        for f, cp in pts:
            m[i], c[i] = m[i] + f, (m[i] * c[i] + f * np.asarray(cp, float)) / (m[i] + f)
    com = bbf.centre_of_mass(P, m, c)  # (n, 3): S at the origin
    M = sum(m.values())
    dist = np.linalg.norm(com, axis=1)
    worst = list(np.argsort(-dist, kind="stable")[: BALANCE_POSES // 3])
    spread = [int(x) for x in np.linspace(0, len(dist) - 1, BALANCE_POSES - len(worst)).round()]
    poses = list(dict.fromkeys([int(x) for x in worst] + spread))
    sigma_infill = p.infill_error / 3
    for g in poses:
        jac: dict = {}  # feature -> (3,) world shift of the centre per unit of it

        def at(i: int, point) -> np.ndarray:
            T = frames[i][g]
            return T[:3, :3] @ np.asarray(point, float) + T[:3, 3]

        for i, lm in kit.masses.items():
            name = _name(i)
            dm = p.density * lm.interior_volume  # g per unit of infill fraction
            jac[(f"{name} infill", "process", name, sigma_infill)] = dm * (at(i, lm.interior_centre) - com[g]) / M
            area = side_area(kit.solids[i], kit.printing[name].body_from_print)
            jac[(f"{name} outline", "outline", name)] = p.density * area / 2 * (at(i, lm.solid_centre) - com[g]) / M
        for i, f in kit.fills.items():
            name, cup = _name(i), kit.cups[i]
            R = frames[i][g][:3, :3]
            for axis, ch in enumerate("xyz"):
                jac[(f"{name} pocket {ch}", "position", name)] = f.mass * R[:, axis] / M
            dm = (f.binder_density - p.density) * math.pi * f.bore_radius * f.depth  # g per mm of bore diameter
            jac[(f"{name} pocket bore", "hole", name)] = dm * (at(i, cup.pocket_centre) - com[g]) / M
        for w in W:
            terms = {key: -float(w @ v) for key, v in jac.items()}
            b.add(Margin("balance", "balance", f"centre of mass off S, pose {g}", float(p.tolerance - w @ com[g]), "S"),
                  terms)
