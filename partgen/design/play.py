"""What play costs: the pen's error band of a gear (or belt) chain from its backlash and joint play
(pure math, mm and rad; docs/tolerance.md, "What play costs").

The model is linear in small displacements about the nominal (centred) kit:

* **A link's free angle.** Link j's gear G_j is driven by a stage (the drive pair for j = 1; for
  j ≥ 2 the stage of link j-1: D_j-1 → M_j-1 → G_j, referred to G_j through the teeth). With its
  driver held, G_j (and so B_j) can turn through ``±h_j``: half of each mesh's circumferential
  backlash on its operating pitch circle over the operating pitch radius of the gear it turns,
  referred to G_j, plus, for each running fit whose bore carries a gear of the stage, its radial
  play ``c`` along the line of action of each mesh it moves, over G_j's base radius (a gear centre
  moved by ``t`` changes a line of action's length by ``t·n`` ≤ c): the drive gear and B_j's bore
  move one line each, an idler two. A belt stage's own play (belt teeth in their grooves, stretch)
  is not modelled: its free angle is 0.
* **Propagation.** Link angles follow the stages' recurrence ``α_j+1 = α_j + ρ_j (α_j-1 − α_j)``
  (``ρ_j = T_D,j / T_G,j+1``, α_0 = 0 the base), so a free angle ε_j of link j turns every link
  after it: ``Δα = T ε`` with T lower triangular.
* **The pen.** ``P = offset + Σ_k L_k e^{iα_k}``: ``∂P/∂α_k = i L_k e^{iα_k}``; and each link's
  proximal bore (on the post of the link before) translates it and every link after it by up to its
  radial play ``c_j`` in any direction.

At a crank angle the pen can be anywhere in the zonotope ``Σ_j [−h_j, h_j] g_j + Σ_j disk(c_j)``
(``g_j = Σ_k T_kj ∂P/∂α_k``). Its support function in a direction u is ``Σ h_j |u·g_j| + Σ c_j``;
the worst case is its largest value over u (the farthest the pen can be from the nominal path).

The 95 % band is a Monte Carlo over the tolerance study's features (each gear's outline, each mesh's
centre distance, each bore and pin: normal, σ = A/3): a print has its own backlash and play (the
tolerance model's linear terms, a play that comes out negative is 0), and sits in it at a random
place held through the turn (each free angle uniform in its range, each translation uniform in its
disk). A print's band is the farthest its pen gets from the nominal path over the turn; ``p95_max``
is the 95th percentile over the prints.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import involute
from .mechanism import ChainDesign
from .trace import built_chain

__all__ = ["ChainPlay", "chain_play", "pen_band", "PenBand"]

DIRECTIONS = 360  # directions u at which the support function is taken (exact to 1 − cos 0.5° = 4e-5)


@dataclass(frozen=True)
class ChainPlay:
    """The play of a chain's links: per link j, its free-angle half range ``h`` (rad) with the
    backlash and play it comes from, and the radial play ``c`` of its proximal bore (mm)."""

    h: np.ndarray  # (n,) rad
    c: np.ndarray  # (n,) mm
    rho: np.ndarray  # (n - 1,) stage ratios T_D/T_G
    # linear sensitivities for the Monte Carlo: h_j = h0_j + Σ dh_j/dx x over (mesh backlash, body play)
    mesh_backlash: tuple[tuple[int, float, float, float], ...]  # (link j, backlash mm, rad per mm, cos α_w)
    bore_play: tuple[tuple[int, str, float], ...]  # (link j, body, rad per mm) per (body, line of action) it moves
    body_play: dict  # body ("drive", "B<j>", "M<j>") -> radial play, mm


def _mesh(g1, g2, a: float) -> tuple[float, float, float]:
    """Circumferential backlash on the operating pitch circle (mm), the driven gear's operating
    pitch radius (mm) and cos α_w of a pair at centre distance a."""
    s = g1.system
    j = involute.circumferential_backlash(g1.teeth, g2.teeth, s.module, s.pressure_angle, g1.profile_shift,
                                          g2.profile_shift, s.backlash_per_gear, g2.system.backlash_per_gear, a)
    rb = (g1.teeth + g2.teeth) * s.module / 2 * math.cos(s.pressure_angle)
    return j, a * g2.teeth / (g1.teeth + g2.teeth), rb / a


def _base_radius(g) -> float:
    return g.pitch_radius * math.cos(g.system.pressure_angle)


def chain_play(mech: ChainDesign, radial_play_mm: float) -> ChainPlay:
    """The nominal play of every link of ``mech`` when every running fit has ``radial_play_mm``."""
    n = len(mech.chain.links)
    c = np.full(n, float(radial_play_mm))
    meshes: list[tuple[int, float, float, float]] = []
    bores: list[tuple[int, str, float]] = []
    body = {"drive": float(radial_play_mm), **{f"B{j}": float(radial_play_mm) for j in range(1, n + 1)},
            **{f"M{s.j}": float(radial_play_mm) for s in mech.stages}}
    dd = float(np.hypot(*mech.drive_centre))
    j0, rw, cw = _mesh(mech.drive, mech.G1, dd)
    meshes.append((1, j0, 0.5 / rw, cw))
    rb = _base_radius(mech.G1)
    bores += [(1, "drive", 1 / rb), (1, "B1", 1 / rb)]  # the drive gear's bore and B1's
    for s in mech.stages:  # stage j drives link j + 1
        k = s.j + 1
        jdm, rwm, cdm = _mesh(s.D, s.M, s.a_DM)
        jmg, rwg, cmg = _mesh(s.M, s.G, s.a_MG)
        meshes += [(k, jdm, 0.5 / rwm * s.M.teeth / s.G.teeth, cdm), (k, jmg, 0.5 / rwg, cmg)]
        rb = _base_radius(s.G)
        # B_j's bore carries M_j's pin from D_j (one line), the idler's bore moves two, B_k's bore one
        bores += [(k, f"B{s.j}", 1 / rb), (k, f"M{s.j}", 1 / rb), (k, f"M{s.j}", 1 / rb), (k, f"B{k}", 1 / rb)]
    h = np.zeros(n)
    for j, jb, per, _ in meshes:
        h[j - 1] += max(jb, 0.0) * per
    for j, b, per in bores:
        h[j - 1] += body[b] * per
    rho = np.array([float(td) / float(tg) for td, tg in mech.couplings])
    return ChainPlay(h, c, rho, tuple(meshes), tuple(bores), body)


def _transfer(rho: np.ndarray, n: int) -> np.ndarray:
    """(n, n) T with Δα = T ε (α_0 = 0; α_1 = ε_1; α_k+1 = α_k + ρ_k (α_k-1 − α_k) + ε_k+1)."""
    T = np.zeros((n, n))
    for j in range(n):
        a_prev, a_cur = 0.0, 0.0  # Δα_0 (the base) and the link before
        for k in range(n):
            if k == 0:
                val = 0.0
            else:
                val = a_cur + rho[k - 1] * (a_prev - a_cur)
            if k == j:
                val += 1.0
            T[k, j] = val
            a_prev, a_cur = a_cur, val
    return T


@dataclass(frozen=True)
class PenBand:
    """The pen's error band over the crank angles ``theta``: the worst case at each angle (mm), its
    part across the nominal path (mm, the band drawn beside it), and the Monte Carlo's figures."""

    theta: np.ndarray
    worst: np.ndarray
    worst_normal: np.ndarray
    p95_normal: np.ndarray
    p95_max: float
    p50_max: float
    prints: int
    play: ChainPlay
    p95_path_max: float = 0.0  # the same, across the path only (what the drawing shows)
    p50_path_max: float = 0.0

    def to_dict(self) -> dict:
        r = lambda x: round(float(x), 6)  # noqa: E731
        k = int(np.argmax(self.worst))
        return {"worst_case_max": r(self.worst.max()), "worst_case_mean": r(self.worst.mean()),
                "worst_case_theta_rad": r(self.theta[k]), "p95_max": r(self.p95_max), "p50_max": r(self.p50_max),
                "path_worst_case_max": r(self.worst_normal.max()), "path_p95_max": r(self.p95_path_max),
                "path_p50_max": r(self.p50_path_max),
                "prints": self.prints,
                "link_free_angle_arcmin": [r(math.degrees(h) * 60) for h in self.play.h],
                "joint_radial_play_mm": [r(c) for c in self.play.c],
                "model": "linear: backlash and running-fit play taken up at the pen (docs/tolerance.md, What play costs); "
                         "worst_case/p95/p50: from the nominal pen point at the same crank angle (a lag along the path "
                         "included); path_*: across the nominal path (what the drawing shows)"}


def _gains(mech: ChainDesign, theta: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """(n, m) complex: the pen's displacement per radian of each link's free angle at each θ."""
    chain = built_chain(mech)
    n = len(chain.links)
    dP = np.array([1j * l.vector(theta) for l in chain.links])  # (n, m) ∂P/∂α_k
    return _transfer(rho, n).T @ dP


def _support(g: np.ndarray, h: np.ndarray, c: float, u: np.ndarray) -> np.ndarray:
    """Support function Σ_j h_j |u·g_j| + c: g (n, m) complex, h (n,), u (d,) complex unit → (d, m)."""
    dots = np.abs((np.conj(u)[:, None, None] * g[None]).real)  # (d, n, m)
    return np.einsum("dnm,n->dm", dots, h) + c


def pen_band(mech: ChainDesign, radial_play_mm: float, theta: np.ndarray, accuracy_mm: float = 0.0,
             prints: int = 2000, seed: int = 0, mc_angles: int = 720) -> PenBand:
    """The pen's error band of ``mech`` over ``theta`` (rad) for running fits of ``radial_play_mm``
    radial play and a printer of ± ``accuracy_mm`` (3σ; 0: every print nominal)."""
    theta = np.asarray(theta, dtype=float)
    play = chain_play(mech, radial_play_mm)
    g = _gains(mech, theta, play.rho)
    u = np.exp(1j * np.linspace(0, np.pi, DIRECTIONS // 2, endpoint=False))  # |u·g| is even in u
    worst = np.zeros(len(theta))
    for s in range(0, len(theta), 512):
        worst[s:s + 512] = _support(g[:, s:s + 512], play.h, float(play.c.sum()), u).max(axis=0)
    pen = np.array([l.vector(theta) for l in built_chain(mech).links]).sum(axis=0)
    tangent = np.gradient(pen)
    normal = 1j * tangent / np.maximum(np.abs(tangent), 1e-12)
    worst_normal = np.abs((np.conj(normal) * g).real).T @ play.h + play.c.sum()

    # Monte Carlo: each print's play, then its place in it
    rng = np.random.default_rng(seed)
    sig = accuracy_mm / 3.0
    n = len(play.h)
    h = np.tile(play.h, (prints, 1))
    for j, jb, per, cw in play.mesh_backlash:  # teeth (two gears) and the centre distance
        dj = (-(rng.normal(0, sig, prints) + rng.normal(0, sig, prints)) / cw
              + 2 * math.tan(math.acos(min(cw, 1.0))) * rng.normal(0, sig, prints))
        h[:, j - 1] += (np.maximum(jb + dj, 0.0) - max(jb, 0.0)) * per
    bodies = sorted(play.body_play)
    drawn = {b: np.maximum(play.body_play[b] + (rng.normal(0, sig, prints) - rng.normal(0, sig, prints)) / 2, 0.0)
             for b in bodies}  # radial play + δ_bore/2 − δ_pin/2
    for j, b, per in play.bore_play:
        h[:, j - 1] += (drawn[b] - play.body_play[b]) * per
    h = np.maximum(h, 0.0)
    cprint = np.column_stack([drawn[f"B{j}"] for j in range(1, n + 1)])
    eps = rng.uniform(-1, 1, (prints, n)) * h
    r = np.sqrt(rng.uniform(0, 1, (prints, n))) * cprint
    t = (r * np.exp(2j * np.pi * rng.uniform(0, 1, (prints, n)))).sum(axis=1)
    idx = np.linspace(0, len(theta), min(mc_angles, len(theta)), endpoint=False).astype(int)
    dP = eps @ g[:, idx] + t[:, None]  # (prints, m)
    band = np.abs(dP).max(axis=1)
    across = np.abs((np.conj(normal[idx]) * dP).real)  # (prints, m): each print's distance across the path
    p95_normal = np.interp(theta, theta[idx], np.percentile(across, 95, axis=0), period=2 * np.pi)
    path = across.max(axis=1)
    return PenBand(theta, worst, worst_normal, p95_normal, float(np.percentile(band, 95)),
                   float(np.percentile(band, 50)), prints, play, float(np.percentile(path, 95)),
                   float(np.percentile(path, 50)))
