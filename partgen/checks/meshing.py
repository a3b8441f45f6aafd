"""Every meshing pair of gears: centre distance, backlash, contact ratio, tip and involute
interference, and tooth overlap over the motion with the kit's tooth phases.

Gears are prisms over their face width, so the overlap of two gear bodies is the overlap of
their outlines (the rack-generated ones the parts are extruded from) times the face width.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import Point, Polygon, box

from .contact import free_turn
from ..core.protocol import CheckedKit as Kit  # what the shared checks read of a kit
from ..design import involute, rules
from ..design.gearing import centre_distance
from ..design.rules import gear_rules
from ..geometry.gear import gear_outline
from ..geometry.measure import place2d
from ..core.findings import Finding
from ..core.transforms import turn_about

__all__ = ["check_meshes"]


class _Pair:
    def __init__(self, kit: Kit, a: str, b: str, outlines: dict):
        self.a, self.b = a, b
        self.ga, self.gb = kit.part(a).gear, kit.part(b).gear
        self.oa, self.ob = outlines[self.ga], outlines[self.gb]
        self.face = kit.params.face_width

    def window(self, Ta: np.ndarray, Tb: np.ndarray):
        """The region near the line of centres where the two outlines can meet (world, mm)."""
        ca, cb = Ta[:2, 3], Tb[:2, 3]
        d = np.linalg.norm(cb - ca)
        u = (cb - ca) / d
        pitch_pt = ca + u * d * self.ga.teeth / (self.ga.teeth + self.gb.teeth)
        h = 2.5 * self.ga.module
        window = shapely.affinity.rotate(box(-h, -2.2 * h, h, 2.2 * h), math.atan2(u[1], u[0]), origin=(0, 0),
                                         use_radians=True)
        return shapely.affinity.translate(window, *pitch_pt)

    def overlap(self, Ta: np.ndarray, Tb: np.ndarray, near=None) -> tuple[float, Point]:
        """Overlap area (mm²) of the two outlines at these poses, only near the line of centres.
        ``near``: (window, gear a's outline clipped to it) when a and both centres stay put."""
        window, A = near or self.near(Ta, Tb)
        B = shapely.intersection(place2d(self.ob, Tb), window)
        common = shapely.intersection(A, B)
        return common.area, common.centroid

    def near(self, Ta: np.ndarray, Tb: np.ndarray):
        window = self.window(Ta, Tb)
        return window, shapely.intersection(place2d(self.oa, Ta), window)


PLAY_RESOLUTION = 1e-7  # mm of arc at gear b's tip: the bisection's last step


def _play(pair: _Pair, Ta, Tb, direction: int) -> float:
    """How far gear b turns (rad, ``direction`` ±1) about its centre before it touches a."""
    pitch = 2 * math.pi / pair.gb.teeth
    lo, hi = 0.0, pitch / 2
    cb = Tb[:2, 3]
    near = pair.near(Ta, Tb)  # b turns about its own centre: the window and a's clipped outline hold
    if pair.overlap(Ta, Tb, near)[0] > 1e-9:
        return 0.0
    reach = pair.gb.tip_radius
    return free_turn(lambda d: pair.overlap(Ta, turn_about(Tb, (0.0, 0.0, 1.0), (cb[0], cb[1], 0.0), direction * d),
                                            near)[0] > 1e-9, lo, hi, PLAY_RESOLUTION / reach)


def check_meshes(kit: Kit, thetas: np.ndarray, label: str = "motion parameter") -> tuple[list[Finding], list[dict]]:
    """Findings and one row of figures per meshing pair (``label``: what the mechanism calls the
    motion parameter ``thetas`` samples, e.g. the angle of its input)."""
    settings = kit.params.checks
    mesh_rules = gear_rules(kit.params)
    outlines = {}
    for p in kit.parts:
        if p.gear is not None and p.gear not in outlines:
            outlines[p.gear] = Polygon(gear_outline(p.gear).points)
    findings, rows = [], []
    P = kit.poses_over(np.asarray(thetas, dtype=float))  # name -> (N, 4, 4)
    for c in kit.contacts:
        if c.kind != "mesh":
            continue
        pair = _Pair(kit, c.a, c.b, outlines)
        ga, gb = pair.ga, pair.gb
        s = ga.system
        P0a, P0b = P[c.a][0], P[c.b][0]
        a_op = float(np.linalg.norm(P0b[:2, 3] - P0a[:2, 3]))
        a_design = centre_distance(ga, gb)
        names = (c.a, c.b)
        backlash = involute.circumferential_backlash(ga.teeth, gb.teeth, s.module, s.pressure_angle, ga.profile_shift,
                                                     gb.profile_shift, s.backlash_per_gear, gb.system.backlash_per_gear, a_op)
        # the play measured on the outlines: turn b both ways from its assembled phase until it touches
        r_wb = a_op * gb.teeth / (ga.teeth + gb.teeth)
        measured = (_play(pair, P0a, P0b, 1) + _play(pair, P0a, P0b, -1)) * r_wb
        eps = rules.contact_ratio(ga, gb, a_op) if backlash > -a_op else 0.0
        tip = {f"{x}->{y}": rules.tip_root_clearance(gx, gy, a_op) for x, y, gx, gy in
               ((c.a, c.b, ga, gb), (c.b, c.a, gb, ga))}
        # tooth overlap over the motion, one evaluation per distinct mesh phase
        seen, worst = set(), (0.0, None, None)
        pa_pitch, pb_pitch = 2 * math.pi / ga.teeth, 2 * math.pi / gb.teeth
        for n in range(len(thetas)):
            Ta, Tb = P[c.a][n], P[c.b][n]
            rel = np.linalg.inv(Ta) @ Tb
            line = math.atan2(rel[1, 3], rel[0, 3])
            key = (round((line % pa_pitch) / pa_pitch * 512) % 512,
                   round(((math.atan2(rel[1, 0], rel[0, 0]) - line) % pb_pitch) / pb_pitch * 512) % 512)
            if key in seen:
                continue
            seen.add(key)
            area, where = pair.overlap(Ta, Tb)
            if area * pair.face > worst[0]:
                worst = (area * pair.face, n, (where.x, where.y, Ta[2, 3] + pair.face / 2))
        row = {"pair": list(names), "teeth": [ga.teeth, gb.teeth], "centre_distance_mm": round(a_op, 5),
               "design_centre_distance_mm": round(a_design, 5), "backlash_mm": round(backlash, 5),
               "measured_backlash_mm": round(measured, 5), "contact_ratio": round(eps, 4),
               "tip_clearance_mm": {k: round(v, 4) for k, v in tip.items()}, "phases_tested": len(seen),
               "worst_overlap_mm3": round(worst[0], 6)}
        rows.append(row)
        label = f"{c.a}/{c.b} ({ga.teeth}/{gb.teeth})"
        # the rules `teeth: auto` chooses by (design.rules), at the centre distance as assembled
        broken = rules.mesh_breaches(ga, gb, a_op, mesh_rules, names)
        if worst[0] > settings.interference_tolerance:
            n = worst[1]
            # teeth that overlap where the pair breaks a rule (a tip in its mate's fillet) overlap
            # because of it: the finding carries that rule
            cause = next((b.rule for b in broken if b.rule in ("involute", "tip-root", "backlash")), "")
            findings.append(Finding("mesh", "fail", f"{label}: teeth overlap by {worst[0]:.3f} mm³ at {label} "
                                    f"{math.degrees(thetas[n]):.1f}° (centre distance {a_op:.3f} mm, design "
                                    f"{a_design:.3f} mm)" + (f", from the {cause} rule broken below" if cause else ""),
                                    names, float(thetas[n]), worst[0], "mm3", worst[2], rule=cause))
        for b in broken:
            findings.append(Finding("mesh", "fail", f"{label}: {b.message}", names, None, b.value,
                                    "" if b.rule == "contact-ratio" else "mm", rule=b.rule))
        if not any(b.rule == "backlash" for b in broken) and abs(a_op - a_design) > 0.01:
            findings.append(Finding("mesh", "fail", f"{label}: centre distance {a_op:.3f} mm, design {a_design:.3f} mm",
                                    names, None, a_op - a_design, "mm"))
    return findings, rows
