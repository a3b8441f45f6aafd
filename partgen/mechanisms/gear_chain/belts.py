"""Timing belts: the belt as assembled is a whole number of teeth long, and enough of its teeth
are in mesh on each pulley."""

from __future__ import annotations

import math

from .kit import Kit, belt_path_of
from ...core.findings import Finding

__all__ = ["check_belts", "MIN_TEETH_IN_MESH"]

MIN_TEETH_IN_MESH = 6  # the usual rule for timing belts


def check_belts(kit: Kit) -> tuple[list[Finding], list[dict]]:
    findings, rows = [], []
    for s in kit.mechanism.belt_stages:
        prof = s.D.profile
        length, path = belt_path_of(s, prof)
        row = {"stage": s.j, "belt_teeth": s.belt_teeth, "path_length_mm": round(length, 5),
               "belt_length_mm": s.belt_teeth * prof.pitch, "tensioner": s.tensioner is not None,
               "link_change_mm": round(s.link_change, 4)}
        names = (f"belt{s.j}", f"D{s.j}", f"G{s.j + 1}")
        if abs(length - s.belt_teeth * prof.pitch) > 0.01:
            findings.append(Finding("belt", "fail", f"belt {s.j}: its path is {length:.3f} mm, the belt "
                                    f"{s.belt_teeth * prof.pitch:g} mm ({s.belt_teeth} teeth): it would be slack or "
                                    "stretched", names, None, length - s.belt_teeth * prof.pitch, "mm"))
        for name, pulley, centre in ((f"D{s.j}", s.D, (0.0, 0.0)), (f"G{s.j + 1}", s.G, (s.length, 0.0))):
            near = [p for p in path if abs(math.hypot(p[0] - centre[0], p[1] - centre[1]) - pulley.pitch_radius) < 1e-6]
            angles = sorted(math.atan2(p[1] - centre[1], p[0] - centre[0]) for p in near)
            gaps = [b - a for a, b in zip(angles, angles[1:])] + [angles[0] + 2 * math.pi - angles[-1]] if angles else [2 * math.pi]
            wrap = 2 * math.pi - max(gaps)
            in_mesh = wrap / (2 * math.pi) * pulley.teeth
            row[f"teeth_in_mesh_{name}"] = round(in_mesh, 2)
            if in_mesh < MIN_TEETH_IN_MESH:
                findings.append(Finding("belt", "fail", f"belt {s.j}: only {in_mesh:.1f} teeth in mesh on {name} "
                                        f"(needs {MIN_TEETH_IN_MESH})", names, None, in_mesh, "teeth"))
        rows.append(row)
    return findings, rows
