"""The spatial (Bennett) balanced butterfly linkage — pure math, mm and rad, vectorised over poses.

Bennett 1 (S-B2-D2-B3) is the loop (a, α), (b, β), (a, α), (b, β) of ``design.bennett``. The other
three are *translated, scaled copies* of it (scales s2, s3, s4), exactly as the planar four-bars
are (``design.balanced``): every link of a copy stays parallel to the corresponding link of
Bennett 1, so every joint point is the same fixed real combination of B2, B3 and D2 as in the
planar form, and the balance conditions are the planar ones (``balanced.balance_coefficients``).

What this costs at S: in the planar form links 1, 4, 7 and 10 turn on one pin. Here the four
joints at S are copies of four *different* joints of Bennett 1 (S, B3, D2, B2), so they are four
revolutes whose axes (parallel to those four joint axes) all pass through the point S — a
spherical four-bar, which moves with Bennett 1's own joint angles because it is the rotation part
of the Bennett loop. The parallelogram loops C1-B2-S-B7 and C2-B4-S-B1 have four parallel axes
each (∥ B2's and ∥ D2's): planar parallelograms, so C1 and C2 are ordinary revolutes.

A single pin at S (all four central links on one axis) cannot work: the relative motion of links 2
and 9 then has neither a fixed axis nor a fixed point, so no joint at C1 could follow it
(``tests/mechanisms/bennett_butterfly/test_bennett_butterfly.py`` measures this).

Inputs: q1, the angle of link 1 (S→B2) about S's axis z, and q4, the angle of S→B3 about z (both
lie in the xy plane: they are common normals of the S axis). q1 alone turns the whole linkage
rigidly about z; q1 − q4 alone sets its shape.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.transforms import rot_x, rot_z
from ..errors import DesignError
from .balanced import Butterfly
from .bennett import check_bennett, joint_angles

__all__ = ["BennettButterfly", "JOINTS", "GROUP", "REFERENCE", "Pose", "pose", "link_frames", "body_joints",
           "centre_of_mass", "mass_moment", "solve_point_masses", "solve_counterweights", "solve_offsets", "shape_angle"]

# joint: (links it connects, the Bennett-1 joint its axis is parallel to, the point it sits at)
JOINTS: dict[str, tuple[tuple[int, int], str, str]] = {
    "S14": ((1, 4), "S", "S"), "B2": ((1, 2), "B2", "B2"), "D2": ((2, 3), "D2", "D2"), "B3": ((3, 4), "B3", "B3"),
    "S47": ((4, 7), "B3", "S"), "B8": ((4, 5), "S", "B8"), "D1": ((5, 6), "B2", "D1"), "B1": ((6, 7), "D2", "B1"),
    "S710": ((7, 10), "D2", "S"), "B6": ((7, 8), "B3", "B6"), "D4": ((8, 9), "S", "D4"), "B7": ((9, 10), "B2", "B7"),
    "S101": ((10, 1), "B2", "S"), "B4": ((10, 11), "D2", "B4"), "D3": ((11, 12), "B3", "D3"),
    "B5": ((12, 1), "S", "B5"), "C1": ((2, 9), "B2", "C1"), "C2": ((6, 11), "D2", "C2"),
}
# link -> the link of Bennett 1 it stays parallel to (1: S→B2, 2: B2→D2, 3: D2→B3, 4: B3→S)
GROUP = {1: 1, 5: 1, 9: 1, 2: 2, 6: 2, 10: 2, 3: 3, 7: 3, 11: 3, 4: 4, 8: 4, 12: 4}
# link -> the joint point its body frame sits at (the planar form's reference joints)
REFERENCE = {1: "S", 2: "D2", 3: "B3", 4: "S", 5: "B8", 6: "B1", 7: "S", 8: "B6", 9: "D4", 10: "S", 11: "B4",
             12: "D3"}


@dataclass(frozen=True)
class BennettButterfly:
    """Bennett 1's a (S–B2, D2–B3) and b (B2–D2, B3–S) in mm, twists α, β (rad), and the scales of
    Bennetts 2, 3, 4."""

    a: float
    b: float
    alpha: float
    beta: float
    s2: float
    s3: float
    s4: float

    def __post_init__(self):
        check_bennett(self.a, self.b, self.alpha, self.beta)
        for k in ("s2", "s3", "s4"):
            if not getattr(self, k) > 0:
                raise DesignError(f"the scale {k} must be positive, got {getattr(self, k)}")

    @classmethod
    def from_twist(cls, a: float, b: float, alpha: float, s2: float, s3: float, s4: float,
                   obtuse: bool = False) -> "BennettButterfly":
        """β from the Bennett condition sin β = (b/a)·sin α (the acute root unless ``obtuse``)."""
        x = b / a * math.sin(alpha)
        if not -1 <= x <= 1:
            raise DesignError(f"no Bennett linkage: (b/a)·sin α = {x:.4g} is outside [-1, 1]")
        beta = math.asin(x)
        return cls(a, b, alpha, math.pi - beta if obtuse else beta, s2, s3, s4)

    @property
    def planar(self) -> Butterfly:
        """The same linkage with every twist 0: four-bar 1 is then a parallelogram."""
        return Butterfly(l1a=self.a, l2=self.b, l3=self.a, l4a=self.b, s2=self.s2, s3=self.s3, s4=self.s4)

    @property
    def lengths(self) -> dict[str, float]:
        """The paper's l-names (mm)."""
        return self.planar.lengths


@dataclass(frozen=True)
class Pose:
    """n poses. points: name -> (n, 3) mm; rot: (4, n, 3, 3), the rotation of Bennett 1's links 1–4
    (x along the link, z its proximal joint axis); axis: Bennett-1 joint -> (n, 3) unit direction."""

    q1: np.ndarray
    q4: np.ndarray
    points: dict[str, np.ndarray]
    rot: np.ndarray
    axis: dict[str, np.ndarray]


def shape_angle(q1: np.ndarray, q4: np.ndarray) -> np.ndarray:
    """Bennett 1's DH joint angle θ1 at S (from link 4's x, pointing B3→S, to link 1's x), rad."""
    return np.asarray(q1) - np.asarray(q4) - np.pi


def pose(bb: BennettButterfly, q1, q4) -> Pose:
    """Every joint point and link rotation at inputs q1, q4 (rad, scalars or (n,) arrays); S at 0."""
    q1, q4 = np.broadcast_arrays(np.atleast_1d(np.asarray(q1, float)), np.atleast_1d(np.asarray(q4, float)))
    th = joint_angles(shape_angle(q1, q4), bb.alpha, bb.beta)
    R1 = rot_z(q1)
    R2 = R1 @ rot_x(bb.alpha) @ rot_z(th[:, 1])
    R3 = R2 @ rot_x(bb.beta) @ rot_z(th[:, 2])
    R4 = R3 @ rot_x(bb.alpha) @ rot_z(th[:, 3])
    ex = lambda R: R[..., :, 0]  # noqa: E731
    S = np.zeros((len(q1), 3))
    B2 = bb.a * ex(R1)
    D2 = B2 + bb.b * ex(R2)
    B3 = D2 + bb.a * ex(R3)
    s2, s3, s4 = bb.s2, bb.s3, bb.s4
    B5, B8 = -s4 * B2, -s2 * B3
    D1, B1 = B8 + s2 * B2, B8 + s2 * D2
    D4 = -s3 * D2
    B7, B6 = D4 + s3 * B2, D4 + s3 * B3
    B4, D3 = B5 + s4 * D2, B5 + s4 * B3
    pts = {"S": S, "B1": B1, "B2": B2, "B3": B3, "B4": B4, "B5": B5, "B6": B6, "B7": B7, "B8": B8,
           "D1": D1, "D2": D2, "D3": D3, "D4": D4, "C1": B2 + B7, "C2": B4 + B1}
    axis = {"S": R1[..., :, 2], "B2": R2[..., :, 2], "D2": R3[..., :, 2], "B3": R4[..., :, 2]}
    return Pose(q1, q4, pts, np.stack([R1, R2, R3, R4]), axis)


def link_frames(p: Pose) -> dict[int, np.ndarray]:
    """link -> (n, 4, 4) world-from-body: rotation of its group, origin at its reference joint."""
    out = {}
    n = len(p.q1)
    for link, g in GROUP.items():
        T = np.zeros((n, 4, 4))
        T[:, :3, :3] = p.rot[g - 1]
        T[:, :3, 3] = p.points[REFERENCE[link]]
        T[:, 3, 3] = 1.0
        out[link] = T
    return out


def body_joints(bb: BennettButterfly) -> dict[int, dict[str, tuple[np.ndarray, np.ndarray]]]:
    """link -> {joint: (point (3,), unit axis (3,))} in the link's body frame (constant: links are rigid)."""
    p = pose(bb, 0.0, 1.3)  # any pose: the body coordinates do not depend on it
    frames = link_frames(p)
    out: dict[int, dict[str, tuple[np.ndarray, np.ndarray]]] = {i: {} for i in GROUP}
    for name, (links, ax, at) in JOINTS.items():
        for i in links:
            R, t = frames[i][0, :3, :3], frames[i][0, :3, 3]
            out[i][name] = (R.T @ (p.points[at][0] - t), R.T @ p.axis[ax][0])
    return out


def mass_moment(frames: dict[int, np.ndarray], masses: dict[int, float], body_coms: dict[int, np.ndarray]
                ) -> np.ndarray:
    """(n, 3) Σ mᵢ·(world centre of link i) about S, g·mm, for links with masses (g) and centres (3,)
    in their body frames (``link_frames``)."""
    acc = 0.0
    for i, m in masses.items():
        T = frames[i]
        acc = acc + m * (T[:, :3, :3] @ np.asarray(body_coms[i], float) + T[:, :3, 3])
    return acc


def centre_of_mass(p: Pose, masses: dict[int, float], body_coms: dict[int, np.ndarray]) -> np.ndarray:
    """(n, 3) common centre of mass (mm) of links with masses (g) and centres (3,) in their body frames."""
    return mass_moment(link_frames(p), masses, body_coms) / sum(masses.values())


def solve_point_masses(p: Pose, masses: dict[int, float], body_coms: dict[int, np.ndarray],
                       free: list[tuple[int, np.ndarray]]) -> tuple[np.ndarray, float]:
    """Masses (g) of point masses at body points ``free`` [(link, (3,))] that bring the common centre
    of mass closest to S over the poses (least squares on the mass moment), and the worst remaining
    moment per unit total mass (mm). Raises DesignError if a mass comes out negative."""
    frames = link_frames(p)
    rhs = -mass_moment(frames, masses, body_coms)
    cols = [(frames[i][:, :3, :3] @ np.asarray(pt, float) + frames[i][:, :3, 3]).ravel() for i, pt in free]
    A = np.column_stack(cols)
    x, *_ = np.linalg.lstsq(A, rhs.ravel(), rcond=None)
    resid = (A @ x - rhs.ravel()).reshape(-1, 3)
    total = sum(masses.values()) + float(x.sum())
    if np.any(x < 0):
        bad = [f"link {i}: {v:.3g} g" for (i, _), v in zip(free, x) if v < 0]
        raise DesignError("the balance needs a negative counter-mass (" + ", ".join(bad)
                          + "): put the counterweights on the other side of their joints")
    return x, float(np.linalg.norm(resid, axis=1).max() / total)


def solve_counterweights(p: Pose, masses: dict[int, float], body_coms: dict[int, np.ndarray],
                         at: list[tuple[int, np.ndarray]], mass_weight: float = 100.0
                         ) -> tuple[np.ndarray, np.ndarray, float]:
    """Point masses on links ``at`` [(link, nominal body point (3,))], each free to move off its
    nominal point by δ (3,), that put the common centre of mass at S over the poses.

    The moment is linear in each mass m and in h = m·δ, so this is a linear problem. The balance has
    fewer independent conditions than unknowns; of its exact solutions the minimum-norm one in
    (m/mass_weight, h) is taken, so offsets are kept small. The masses are not fixed by the balance
    (a heavier weight sits closer: ``solve_offsets`` balances weights of given masses), so this
    gives the masses that need the smallest offsets, which the kit rounds to whole stock slugs.
    Returns masses (k,) g, offsets δ (k, 3) mm in the body frames, and the worst remaining moment
    per unit mass (mm)."""
    frames = link_frames(p)
    rhs = -mass_moment(frames, masses, body_coms)
    cols = []
    for i, p0 in at:
        R, t = frames[i][:, :3, :3], frames[i][:, :3, 3]
        cols.append(mass_weight * (R @ np.asarray(p0, float) + t).ravel())
        cols += [R[:, :, k].ravel() for k in range(3)]
    A = np.column_stack(cols)
    y, *_ = np.linalg.lstsq(A, rhs.ravel(), rcond=None)
    resid = (A @ y - rhs.ravel()).reshape(-1, 3)
    y = y.reshape(-1, 4)
    m = mass_weight * y[:, 0]
    if np.any(m <= 0):
        bad = [f"link {i}: {v:.3g} g" for (i, _), v in zip(at, m) if v <= 0]
        raise DesignError("the balance needs a negative counter-mass (" + ", ".join(bad)
                          + "): move the counterweights to the other side of their joints or to other links")
    delta = y[:, 1:] / m[:, None]
    total = sum(masses.values()) + float(m.sum())
    return m, delta, float(np.linalg.norm(resid, axis=1).max() / total)


def solve_offsets(p: Pose, masses: dict[int, float], body_coms: dict[int, np.ndarray],
                  at: list[tuple[int, np.ndarray, float]], moving: dict[int, tuple[float, np.ndarray]] | None = None
                  ) -> tuple[np.ndarray, float]:
    """Counterweights of given masses on links ``at`` [(link, nominal body point (3,), mass g)]: how
    far δ (3,) each must sit off its nominal point for the common centre of mass to stay at S.

    The moment is linear in δ; the balance leaves some of it free (moving pockets together in ways
    whose moments cancel in every pose), and the minimum-norm δ is taken: the smallest offsets.
    ``moving``: link -> (μ g, δ₀ (3,)): the link's own mass moment follows its pocket, Σmc(δ) ≈
    Σmc(δ₀) + μ·(δ − δ₀) (the cup and its bars move with it), solved with the rest (a Newton step
    for the sizing loop). Returns δ (k, 3) mm in the body frames and the worst remaining moment per
    unit mass (mm)."""
    frames = link_frames(p)
    rhs = -mass_moment(frames, masses, body_coms)
    cols = []
    for i, p0, m in at:
        R, t = frames[i][:, :3, :3], frames[i][:, :3, 3]
        rhs = rhs - m * (R @ np.asarray(p0, float) + t)
        mu, d0 = (moving or {}).get(i, (0.0, np.zeros(3)))
        rhs = rhs + mu * (R @ np.asarray(d0, float))
        cols += [(m + mu) * R[:, :, k].ravel() for k in range(3)]
    A = np.column_stack(cols)
    d, *_ = np.linalg.lstsq(A, rhs.ravel(), rcond=None)
    resid = (A @ d - rhs.ravel()).reshape(-1, 3)
    delta = d.reshape(-1, 3)
    total = sum(masses.values()) + sum(m for _, _, m in at)
    return delta, float(np.linalg.norm(resid, axis=1).max() / total)
