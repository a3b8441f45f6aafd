"""The cross gear and its mate (an ABENICS monopole gear) checked and traced.

Check (3-D, exact): the two meshes' intersection volume (manifold3d) at sampled poses of the
workspace — the mate turned through more than a tooth pitch each way with the cross gear turning
−ψ z_mp / z_cs about the mate's axis, the cross gear tilted about its ring axis y (its free
motion), and at both ends of its turn (``turn_deg``) — must stay under ``INTERFERENCE_MM3``. The
backlash: at a fixed cross-gear pose the mate is turned about its own axis each way until the
meshes first overlap (bisection on the intersection volume), the two free turns added.

Trace (2-D, the mid-plane): the mate's section by the cross gear's plane x = 0 (its exact 2-D
generating cut, ``geometry.cross_mate.mate_section``) drives the cross gear's profile there; at each
mate turn ψ the cross gear's turn at first contact (bisection on the overlap area) gives its angle
φ(ψ). Ratio: the mate's turn over the cross gear's across whole pitches (z_cs / z_mp by design);
transmission error: φ(ψ) minus the nominal −ψ z_mp / z_cs, its mean removed (the constant part is
backlash).
"""

from __future__ import annotations

import math

import numpy as np

from ...core.findings import Finding, Result

__all__ = ["check_mate", "trace_mate", "INTERFERENCE_MM3", "TOUCH_MM3"]

INTERFERENCE_MM3 = 0.01  # the largest overlap the check lets pass (tessellation: the meshes' facets)
TOUCH_MM3 = 1e-5  # an overlap above this is a contact when the backlash is bisected
BACKLASH_RESOLUTION_DEG = 0.005
BACKLASH_LIMIT_DEG = 4.0  # the bisection's bracket: a free turn beyond it is reported as this


def _parts(kit):
    by = {p.name: p for p in kit.parts}
    return by["cross_gear"].solid, by["cross_mate"].solid


def _overlap(cs_solid, mp_solid, T_cs, T_mp) -> tuple[float, object]:
    from .checks import _overlap as remembered  # the exact volume, remembered in the process

    return remembered(cs_solid, T_cs, mp_solid, T_mp)


def mate_poses(spec, psi_samples: int = 13, tilts_deg=(0.0, -35.0, 20.0)) -> list[tuple[float, float, float]]:
    """(ψ, tilt, extra) poses: the mate through a pitch and a half each way at each tilt about the
    cross gear's ring axis, and a pitch each way at both ends of the cross gear's turn."""
    cs, mate = spec.cross, spec.mate
    p = 2 * math.pi / mate.teeth
    out = [(float(psi), math.radians(t), 0.0) for t in tilts_deg for psi in np.linspace(-1.5 * p, 1.5 * p, psi_samples)]
    end = mate.turn * cs.teeth / mate.teeth
    for sign in (1, -1):
        out += [(float(sign * end + d), 0.0, 0.0) for d in np.linspace(-p, p, 5)]
    return out


def _free_turn(cs_solid, mp_solid, T_cs, psi, spec, sign: int, limit: float) -> float:
    """How far the mate turns about its axis from ψ (direction ``sign``) before it overlaps."""
    from ...geometry.cross_mate import mate_pose

    def touches(d):
        return _overlap(cs_solid, mp_solid, T_cs, mate_pose(psi + sign * d, spec.cross, spec.mate))[0] > TOUCH_MM3

    if not touches(limit):
        return limit
    lo, hi = 0.0, limit
    if touches(0.0):
        return 0.0
    while hi - lo > math.radians(BACKLASH_RESOLUTION_DEG):
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if touches(mid) else (mid, hi)
    return lo


def check_mate(kit, res: Result, psi_samples: int = 13, backlash_poses: int = 3) -> None:
    """Adds the pair's findings to ``res`` and its figures under ``res.figures["mate"]``."""
    from ...geometry.cross_mate import cross_pose, mate_pose

    spec = kit.spec
    cs, mate = spec.cross, spec.mate
    cs_solid, mp_solid = _parts(kit)
    poses = mate_poses(spec, psi_samples)
    worst = (0.0, None, None)
    for psi, tilt, extra in poses:
        vol, where = _overlap(cs_solid, mp_solid, cross_pose(psi, cs, mate, tilt, extra), mate_pose(psi, cs, mate))
        if vol > worst[0]:
            worst = (vol, (psi, tilt), where)
    if worst[0] > INTERFERENCE_MM3:
        psi, tilt = worst[1]
        res.add(Finding("interference", "fail", f"cross_gear and cross_mate overlap by {worst[0]:.4f} mm³ at the mate's "
                        f"turn ψ = {math.degrees(psi):.2f}°, the cross gear tilted {math.degrees(tilt):.0f}° about its "
                        "ring axis", ("cross_gear", "cross_mate"), psi, worst[0], "mm3",
                        tuple(worst[2]) if worst[2] is not None else None, key="wrist.cross_gear.mate"))
    p = 2 * math.pi / mate.teeth
    rows = []
    for psi in np.linspace(0.0, p / 2, backlash_poses) if backlash_poses > 1 else [0.0]:
        for tilt in (0.0, math.radians(-35.0)):
            T_cs = cross_pose(float(psi), cs, mate, tilt)
            free = [_free_turn(cs_solid, mp_solid, T_cs, float(psi), spec, s, min(p / 2, math.radians(BACKLASH_LIMIT_DEG)))
                    for s in (1, -1)]
            turn = sum(free)
            rows.append({"psi_deg": round(math.degrees(psi), 3), "tilt_deg": round(math.degrees(tilt), 1),
                         "backlash_deg": round(math.degrees(turn), 4),
                         "backlash_mm": round(turn * mate.pitch_radius(cs), 4)})
            if turn <= 0:
                res.add(Finding("mesh", "fail", f"the mate is jammed at ψ = {math.degrees(psi):.2f}°: no free turn",
                                ("cross_gear", "cross_mate"), float(psi), 0.0, "deg", key="wrist.cross_gear.mate"))
    res.figures["mate"] = {"poses": len(poses), "max_overlap_mm3": round(worst[0], 6),
                           "epsilon_mm3": INTERFERENCE_MM3, "backlash": rows,
                           "backlash_min_mm": min(r["backlash_mm"] for r in rows),
                           "backlash_max_mm": max(r["backlash_mm"] for r in rows)}


def trace_mate(spec, pitches: int = 2, per_pitch: int = 12) -> dict:
    """The pair in its mid-plane: ratio over ``pitches`` whole mate pitches and the transmission
    error at ``per_pitch`` turns a pitch (see the module's docstring). Returns the stats and the
    (ψ, φ, error) rows."""
    import shapely
    from shapely import affinity
    from shapely.geometry import Polygon

    from ...geometry.cross_gear import GROW
    from ...geometry.cross_mate import cross_pose, mate_pose, mate_section
    from ...geometry.gear import gear_outline

    cs, mate = spec.cross, spec.mate
    sec = mate_section(cs, mate)
    prof = Polygon(gear_outline(cs).points).buffer(GROW, join_style="mitre")
    A, ra = mate.centre_distance(cs), mate.tip_radius(cs)
    window = shapely.Point(0, A).buffer(ra + 1.0, 64)
    rho = mate.teeth / cs.teeth
    p = 2 * math.pi / mate.teeth
    pc = 2 * math.pi / cs.teeth
    shapely.prepare(sec)

    def cs_in_mp(psi, delta):
        """The cross gear's profile (turned δ more about x) in the mate's frame at its turn ψ."""
        T = np.linalg.inv(mate_pose(psi, cs, mate)) @ cross_pose(psi, cs, mate, 0.0, delta)
        # only the teeth near the mate: clip in the cross gear's frame first (cheap)
        near = shapely.intersection(prof, affinity.rotate(window, -math.degrees(-psi * rho + delta), origin=(0, 0)))
        pts = [np.asarray(g.exterior.coords) for g in getattr(near, "geoms", [near]) if not g.is_empty]
        out = []
        for q in pts:
            P = np.column_stack([np.zeros(len(q)), q[:, 0], q[:, 1]]) @ T[:3, :3].T + T[:3, 3]
            out.append(Polygon(P[:, :2]))
        return out

    def touches(psi, delta):
        return any(shapely.intersection(sec, q).area > 1e-9 for q in cs_in_mp(psi, delta))

    def contact(psi, sign):
        lo, hi = 0.0, pc / 2
        if touches(psi, 0.0):
            return 0.0
        for _ in range(40):  # to ~1e-13 rad
            mid = (lo + hi) / 2
            lo, hi = (lo, mid) if touches(psi, sign * mid) else (mid, hi)
        return sign * lo

    psis = np.linspace(0.0, pitches * p, pitches * per_pitch + 1)
    lead = np.array([contact(float(s), -1) for s in psis])  # the cross gear held back: the mate drives on one flank
    trail = np.array([contact(float(s), +1) for s in psis])
    phi = -psis * rho + lead
    ratio = float((psis[-1] - psis[0]) / -(phi[-1] - phi[0]))
    te = lead - lead.mean()
    stats = {"ratio": ratio, "ratio_design": cs.teeth / mate.teeth, "ratio_error": abs(ratio - cs.teeth / mate.teeth),
             "te_pp_urad": round(float(np.ptp(te)) * 1e6, 3),
             "te_pp_um": round(float(np.ptp(te)) * cs.pitch_radius * 1000, 3),
             "backlash_mid_deg": round(float(np.degrees((trail - lead).mean())), 4),
             "backlash_mid_mm": round(float((trail - lead).mean()) * cs.pitch_radius, 4),
             "pitches": pitches, "samples": int(len(psis))}
    return {"stats": stats, "rows": np.column_stack([psis, phi, te])}
