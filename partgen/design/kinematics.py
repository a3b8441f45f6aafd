"""Motion of a gear-coupled chain over the crank angle θ (pure math, mm and rad).

Bodies: the base (index 0) and links B_1..B_n. Link j points at ``α_j(θ) = speed_j·θ + δ_j``.
Every gear turns with what it is fixed to plus, for an idler or the drive gear, what its mesh
makes it turn; ``clocking`` is the constant angle of a gear's tooth 0 relative to that, chosen
so every meshing pair interleaves (tooth of one centred in a space of the other on the line of
centres) at θ = 0 — the involute action keeps them interleaved from there on.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .mechanism import ChainDesign

__all__ = ["GearPose", "GearTrack", "gear_tracks", "link_angles_over", "joint_positions_over", "link_angles", "joint_positions", "gear_poses", "mesh_pairs", "clockings", "mesh_phase_error"]

TAU = 2 * math.pi


@dataclass(frozen=True)
class GearPose:
    """A gear's centre (x, y) mm and the world angle of its tooth 0, rad, at one crank angle."""

    name: str
    carrier: int
    centre: tuple[float, float]
    angle: float


@dataclass(frozen=True)
class GearTrack:
    """A gear's centres (N, 2) mm and the world angles of its tooth 0 (N,) rad at N crank angles."""

    name: str
    carrier: int
    centre: np.ndarray
    angle: np.ndarray


def link_angles_over(mech: ChainDesign, thetas) -> np.ndarray:
    """(N, n + 1) rad: ``link_angles`` at each of N crank angles."""
    t = np.atleast_1d(np.asarray(thetas, dtype=float))[:, None]
    speed = np.array([l.speed for l in mech.chain.links], dtype=float)
    phase = np.array([l.phase for l in mech.chain.links], dtype=float)
    return np.concatenate([np.zeros((len(t), 1)), speed * t + phase], axis=1)


def joint_positions_over(mech: ChainDesign, thetas, angles: np.ndarray | None = None) -> np.ndarray:
    """(N, n + 1, 2) mm: ``joint_positions`` at each of N crank angles (``angles``: their
    ``link_angles_over``, if already known)."""
    a = (link_angles_over(mech, thetas) if angles is None else angles)[:, 1:]
    lengths = np.array([l.length for l in mech.chain.links], dtype=float)
    p = np.concatenate([np.zeros((len(a), 1), dtype=complex), np.cumsum(lengths * np.exp(1j * a), axis=1)], axis=1)
    return np.stack([p.real, p.imag], axis=-1)


def link_angles(mech: ChainDesign, theta: float) -> np.ndarray:
    """(n + 1,) rad: α_0 = 0 for the base, then α_j for each link."""
    return link_angles_over(mech, [theta])[0]


def joint_positions(mech: ChainDesign, theta: float) -> np.ndarray:
    """(n + 1, 2) mm: J_0 = the ground pivot at the origin, J_j = distal joint of link j (J_n = pen)."""
    return joint_positions_over(mech, [theta])[0]


def _turned(angle: np.ndarray, v) -> np.ndarray:
    """A link-frame vector (2,) mm in the world at the link angles ``angle`` (N,) rad: (N, 2)."""
    c, s = np.cos(angle), np.sin(angle)
    rc, rs = np.round(c) + 0.0, np.round(s) + 0.0  # exact at quarter turns, as core.transforms
    c = np.where(np.abs(c - rc) < 1e-12, rc, c)
    s = np.where(np.abs(s - rs) < 1e-12, rs, s)
    vx, vy = float(v[0]), float(v[1])
    return np.stack([c * vx - s * vy, s * vx + c * vy], axis=-1)


def _raw_tracks(mech: ChainDesign, thetas) -> list[GearTrack]:
    """Gear tracks without clocking (every gear's tooth 0 on its carrier's +x at θ = 0)."""
    a = link_angles_over(mech, thetas)
    J = joint_positions_over(mech, thetas, a)
    n = len(a)
    out = [
        GearTrack("G1", 1, np.zeros((n, 2)), a[:, 1]),
        GearTrack("drive", 0, np.broadcast_to(np.asarray(mech.drive_centre, dtype=float), (n, 2)),
                  -(mech.G1.teeth / mech.drive.teeth) * a[:, 1]),
    ]
    for s in mech.stages:
        j = s.j
        rel_d = a[:, j - 1] - a[:, j]  # D_j relative to the carrier B_j
        out += [
            GearTrack(f"D{j}", j - 1, J[:, j - 1], a[:, j - 1]),
            GearTrack(f"M{j}", j, J[:, j - 1] + _turned(a[:, j], s.idler), a[:, j] - (s.D.teeth / s.M.teeth) * rel_d),
            GearTrack(f"G{j + 1}", j + 1, J[:, j], a[:, j + 1]),
        ]
    for s in mech.belt_stages:  # pulleys turn with what they are fixed to; the belt's tensioner with its link
        j = s.j
        out += [GearTrack(f"D{j}", j - 1, J[:, j - 1], a[:, j - 1]), GearTrack(f"G{j + 1}", j + 1, J[:, j], a[:, j + 1])]
        if s.tensioner is not None:
            out.append(GearTrack(f"T{j}", j, J[:, j - 1] + _turned(a[:, j], s.tensioner), a[:, j]))
    return out


def gear_tracks(mech: ChainDesign, thetas, clock: dict[str, float] | None = None) -> dict[str, GearTrack]:
    """Every gear's track over the crank angles ``thetas`` (N,), clocked (``clock`` defaults to
    ``clockings(mech)``)."""
    clock = clockings(mech) if clock is None else clock
    return {t.name: GearTrack(t.name, t.carrier, t.centre, t.angle + clock.get(t.name, 0.0))
            for t in _raw_tracks(mech, thetas)}


def _raw_poses(mech: ChainDesign, theta: float) -> list[GearPose]:
    """Gear poses without clocking (every gear's tooth 0 on its carrier's +x at θ = 0)."""
    return [GearPose(t.name, t.carrier, (float(t.centre[0, 0]), float(t.centre[0, 1])), float(t.angle[0]))
            for t in _raw_tracks(mech, [theta])]


def mesh_pairs(mech: ChainDesign) -> list[tuple[str, str]]:
    """Meshing pairs (driver, driven) in the order their clockings are decided."""
    pairs = [("G1", "drive")]
    for s in mech.stages:
        pairs += [(f"D{s.j}", f"M{s.j}"), (f"M{s.j}", f"G{s.j + 1}")]
    return pairs


def _phase(pose_a: GearPose, za: int, pose_b: GearPose, zb: int) -> float:
    """u_A + u_B - 1/2 (mod 1, in [-1/2, 1/2)): 0 when the pair interleaves exactly."""
    beta = math.atan2(pose_b.centre[1] - pose_a.centre[1], pose_b.centre[0] - pose_a.centre[0])
    ua = (beta - pose_a.angle) * za / TAU
    ub = (beta + math.pi - pose_b.angle) * zb / TAU
    return (ua + ub - 0.5 + 0.5) % 1.0 - 0.5


def clockings(mech: ChainDesign) -> dict[str, float]:
    """Tooth-0 clocking of every gear (rad): D_j and G1 are the references (0); each driven gear
    is turned so it interleaves with its driver at θ = 0."""
    teeth = dict(mech.gears)
    poses = {p.name: p for p in _raw_poses(mech, 0.0)}
    clock = {name: 0.0 for name in teeth}  # pulleys need none: a belt takes any tooth phase
    for a, b in mesh_pairs(mech):
        pa = GearPose(a, poses[a].carrier, poses[a].centre, poses[a].angle + clock[a])
        err = _phase(pa, teeth[a].teeth, poses[b], teeth[b].teeth)
        clock[b] = (err * TAU / teeth[b].teeth) % (TAU / teeth[b].teeth)
    return clock


def gear_poses(mech: ChainDesign, theta: float, clock: dict[str, float] | None = None) -> dict[str, GearPose]:
    """Every gear's pose at crank angle θ, clocked (``clock`` defaults to ``clockings(mech)``)."""
    clock = clockings(mech) if clock is None else clock
    return {p.name: GearPose(p.name, p.carrier, p.centre, p.angle + clock.get(p.name, 0.0)) for p in _raw_poses(mech, theta)}


def mesh_phase_error(mech: ChainDesign, theta: float, clock: dict[str, float] | None = None) -> dict[tuple[str, str], float]:
    """For each meshing pair, how far from interleaved it is at θ, in fractions of a pitch."""
    teeth = dict(mech.gears)
    poses = gear_poses(mech, theta, clock)
    return {(a, b): _phase(poses[a], teeth[a].teeth, poses[b], teeth[b].teeth) for a, b in mesh_pairs(mech)}
