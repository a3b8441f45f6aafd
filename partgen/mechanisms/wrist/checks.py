"""Checks of a wrist gear pair over its 2-DoF workspace: no interference, teeth always engaged,
and the play in bending and in twist; the check as the protocol runs it (with the cross gear's
mate, ``mate.py``, and the printability findings) and its text.

Play: from the pose (θ, ψ), gear 2 is turned — about its own axis (twist: the hand turning on
the forearm) or about the axis through its centre normal to the bending plane (bend, without
rolling) — until it overlaps gear 1 by the tolerance; the two directions add up to the play. Near
the pole the contact lies on gear 2's axis and nothing resists a twist: the play is large there.
"""

from __future__ import annotations

import math
from collections import OrderedDict

import numpy as np

from .kit import WristKit
from .spec import WristSpec
from ...checks.footer import check_footer
from ...design import spherical as sph
from ...geometry import wrist as W
from ...geometry.measure import intersection
from ...core.findings import Finding, Result
from ...core.transforms import turn_about

__all__ = ["check_wrist", "wrist_sampling", "mate_sampling", "check", "check_text"]


PLAY_RESOLUTION_DEG = 0.005  # each direction's free turn is bisected to this (the figures: 0.01°)

# The exact overlaps of a kit's part pairs, remembered in the process (``_overlap``): a wrist's check
# looks at the same poses again — the 16 azimuths of the bend θ = 0 are one pose, and the play's
# bisections at the same bends are the same sequence of poses in every check of the kit (check, then
# report, then the tolerance study). Keyed on the two solids themselves (held here, so an id is never
# reused while its entry lives; a solid is immutable) and the exact bytes of both poses: nothing else
# decides the volume. Bounded: the last _MEMO_PAIRS pairs, _MEMO_POSES poses each (then forgotten).
_MEMO_PAIRS = 4
_MEMO_POSES = 4096
_OVERLAPS: OrderedDict = OrderedDict()  # (id(a), id(b)) -> (a, b, {(Ta bytes, Tb bytes): (volume, centre)})


def _overlap(a, Ta: np.ndarray, b, Tb: np.ndarray) -> tuple[float, np.ndarray | None]:
    """``geometry.measure.intersection(a, Ta, b, Tb)``, remembered (see ``_OVERLAPS``)."""
    key = (id(a), id(b))
    entry = _OVERLAPS.get(key)
    if entry is None or entry[0] is not a or entry[1] is not b:
        entry = _OVERLAPS[key] = (a, b, {})
        while len(_OVERLAPS) > _MEMO_PAIRS:
            _OVERLAPS.popitem(last=False)
    _OVERLAPS.move_to_end(key)
    Ta, Tb = np.asarray(Ta, dtype=float), np.asarray(Tb, dtype=float)
    poses = entry[2]
    pk = (Ta.shape, Ta.tobytes(), Tb.shape, Tb.tobytes())
    if pk not in poses:
        if len(poses) >= _MEMO_POSES:
            poses.clear()
        vol, where = intersection(a, Ta, b, Tb)
        poses[pk] = (vol, None if where is None else tuple(where))
    vol, where = poses[pk]
    return vol, None if where is None else np.array(where)


def _play(g1, g2, T, axis, through, tol, limit=math.radians(20)) -> float:
    total = 0.0
    steps = math.ceil(math.log2(limit / math.radians(PLAY_RESOLUTION_DEG)))
    for sign in (1, -1):
        lo, hi = 0.0, limit
        if _overlap(g1, np.eye(4), g2, turn_about(T, axis, through, sign * hi))[0] <= tol:
            total += hi
            continue
        for _ in range(steps):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if _overlap(g1, np.eye(4), g2, turn_about(T, axis, through, sign * mid))[0] <= tol else (lo, mid)
        total += lo
    return total


def check_wrist(kit: WristKit, grid: tuple[int, int] = (6, 16), random_poses: int = 24, tol: float = 0.01,
                play_thetas: int = 4, progress=None) -> Result:
    spec = kit.spec
    g1, g2 = kit.parts[0].solid, kit.parts[1].solid
    end = sph.valid_end(spec.I)
    th_of = lambda b: 2 * np.arctan(np.tan(np.asarray(b) / 2) / spec.I)  # noqa: E731
    r_of2 = lambda b: sph.pitch_radii(np.clip(th_of(b), 0, end), spec.I, spec.A)[1]  # noqa: E731
    blank2 = W.revolved_cap(r_of2, math.radians(kit.figures["cap_deg"][1]), -spec.base_height, 8.0, spec.tol)
    domes = W.domes_union(kit.domes)
    rng = np.random.default_rng(20260)
    poses = [(t, p) for t in np.linspace(0, kit.theta_max, grid[0]) for p in 2 * np.pi * np.arange(grid[1]) / grid[1]]
    poses += [(float(rng.uniform(0, kit.theta_max)), float(rng.uniform(0, 2 * np.pi))) for _ in range(random_poses)]
    res = Result()
    worst, weakest = (0.0, None), (math.inf, None)
    engaged_at: dict[bytes, float] = {}  # this check's own solids (domes, blank2): remembered here only
    for n, (theta, psi) in enumerate(poses):
        if progress:
            progress(n, len(poses))
        T = kit.pose2(theta, psi)
        vol, where = _overlap(g1, np.eye(4), g2, T)
        if vol > worst[0]:
            worst = (vol, (theta, psi, where))
        if T.tobytes() not in engaged_at:  # the bend θ = 0 is one pose at every azimuth ψ
            engaged_at[T.tobytes()] = intersection(domes, np.eye(4), blank2, T)[0]
        engaged = engaged_at[T.tobytes()]
        if engaged < weakest[0]:
            weakest = (engaged, (theta, psi))
    if progress:
        progress(len(poses), len(poses))
    if worst[0] > tol:
        th, ps, where = worst[1]
        res.add(Finding("interference", "fail", f"gear1 and gear2 overlap by {worst[0]:.3f} mm³ at bend θ = "
                        f"{math.degrees(th):.1f}°, ψ = {math.degrees(ps):.1f}°", ("gear1", "gear2"), th, worst[0], "mm3",
                        tuple(where) if where is not None else None))
    if weakest[0] <= 0:
        th, ps = weakest[1]
        res.add(Finding("engagement", "fail", f"no tooth engaged at θ = {math.degrees(th):.1f}°, ψ = "
                        f"{math.degrees(ps):.1f}°: the wrist would slip", ("gear1", "gear2"), th, 0.0, "mm3"))
    # play along θ at ψ = 0 (the pair is symmetric in ψ up to the tooth layout)
    rows = []
    for theta in np.linspace(0, kit.theta_max, play_thetas):
        T = kit.pose2(float(theta), 0.0)
        c2 = T[:3, 3]
        twist = _play(g1, g2, T, T[:3, 2], c2, tol)  # about gear 2's own axis: the hand's twist
        bend = _play(g1, g2, T, np.array([0.0, 1.0, 0.0]), c2, tol)
        rows.append({"theta_deg": round(math.degrees(theta), 3), "twist_play_deg": round(math.degrees(twist), 2),
                     "bend_play_deg": round(math.degrees(bend), 2)})
    res.figures.update(poses=len(poses), grid=list(grid), random=random_poses,
                       max_overlap_mm3=round(worst[0], 6), min_engaged_mm3=round(weakest[0], 4), play=rows,
                       workspace_bend_deg=round(math.degrees(spec.max_bend), 3),
                       theta_max_deg=kit.figures["theta_max_deg"])
    return res


def wrist_sampling(samples: int | None) -> dict:
    """`check --samples N` on a wrist: about N poses on the (θ, ψ) grid in the default's proportion
    (6 bends × 16 azimuths), N/4 random poses, and the play measured at 4 bends (3 under 96 poses).
    None: the default (96 grid + 24 random poses, play at 4 bends)."""
    if samples is None:
        return {}
    n_theta = max(2, round(math.sqrt(samples * 6 / 16)))
    n_psi = max(4, round(samples / n_theta))
    return {"grid": (n_theta, n_psi), "random_poses": samples // 4, "play_thetas": 4 if samples >= 96 else 3}


def mate_sampling(samples: int | None) -> dict:
    """`check --samples N` on the cross gear's mate: about N/8 mate turns at each of three tilts (3
    to 13), the backlash at 3 turns (1 under 96 samples). None: the default (13 turns, 3)."""
    if samples is None:
        return {}
    return {"psi_samples": max(3, min(13, samples // 8)), "backlash_poses": 3 if samples >= 96 else 1}


def check(spec: WristSpec, kit: WristKit, samples: int | None = None, progress=None) -> Result:
    from ...checks.bed import add_bed_and_bores

    res = check_wrist(kit, progress=progress, **wrist_sampling(samples))
    if spec.mate is not None:
        from .mate import check_mate

        check_mate(kit, res, **mate_sampling(samples))
    add_bed_and_bores(res, kit.parts, kit.printer)
    return res


def check_text(spec: WristSpec, result: Result, folder, seconds: float) -> str:
    f = result.figures
    lines = [f"{spec.name}: {f['poses']} poses over the workspace (bend ≤ {f['workspace_bend_deg']:g}°: a "
             f"{f['grid'][0]} × {f['grid'][1]} (θ, ψ) grid and {f['random']} random poses)",
             f"  largest overlap {f['max_overlap_mm3']:.4f} mm³, least tooth volume engaged "
             f"{f['min_engaged_mm3']:.2f} mm³",
             f"  {'θ on gear 1':>12}{'twist play':>12}{'bend play':>11}"]
    lines += [f"  {r['theta_deg']:>11.1f}°{r['twist_play_deg']:>11.2f}°{r['bend_play_deg']:>10.2f}°" for r in f["play"]]
    if "mate" in f:
        m = f["mate"]
        lines.append(f"  cross gear and its mate: {m['poses']} poses, largest overlap {m['max_overlap_mm3']:.5f} mm³ "
                     f"(ε {m['epsilon_mm3']:g}), backlash {m['backlash_min_mm']:.3f}–{m['backlash_max_mm']:.3f} mm "
                     "at the mate's pitch circle")
    return "\n".join(lines + check_footer(result, seconds, folder))
