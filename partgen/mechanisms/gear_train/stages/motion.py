"""The train turned on its printed outlines: each stage's driven gear turned from its nominal angle
until its flank touches the driver's (the printed gears' sections at mid-face), stage after stage,
so the output's angle against the input's is what the printed teeth give: transmission error,
measured ratio and the backlash at the output."""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import box

from ....checks.contact import free_turn
from ....geometry.measure import section
from .kit import TrainKit

__all__ = ["printed_sections", "turn_train"]


def printed_sections(kit: TrainKit) -> dict[str, object]:
    """gear name -> the printed part's section at the mid-face of that gear's layer (local xy, mm)."""
    s = kit.params
    out = {}
    for g in s.gears:
        part = kit.part(f"gears{g.shaft}")
        out[g.name] = section(part.solid, s.layer_z(g.layer) + s.face_width / 2)
    return out


def _rotate(geom, angle: float, centre) -> object:
    c, sn = math.cos(angle), math.sin(angle)
    R = np.array([[c, -sn], [sn, c]])
    cx, cy = centre
    return shapely.transform(geom, lambda p: (p - (cx, cy)) @ R.T + (cx, cy))


def _place(geom, angle: float, centre) -> object:
    c, sn = math.cos(angle), math.sin(angle)
    R = np.array([[c, -sn], [sn, c]])
    return shapely.transform(geom, lambda p: p @ R.T + centre)


def turn_train(kit: TrainKit, thetas: np.ndarray, sections: dict | None = None, tol: float = 1e-7,
               shifts: dict | None = None) -> dict:
    """Over input angles ``thetas`` (n,) rad: every shaft's angle (rad) with each driven gear turned
    from its nominal angle until it touches its driver, backward against its motion (``drive``: the
    input drives a loaded train forward) and forward (``coast``: the other flanks, as when the input
    turns back). Returns {"drive": (n, shafts), "coast": (n, shafts), "nominal": (n, shafts),
    "overlap_mm2": (n, stages) at the nominal angles}. Bisection to ``tol`` rad. ``shifts``: {shaft index:
    (x, y) mm}, that shaft's body (its gears) moved off its axis by so much — a body at one place in its
    bore's play (the lost-motion model's exact check, ``play.py``); each driven gear's search then starts
    turned by its centre's shift relative to its driver's along the mesh's tangent over its operating
    pitch radius (back in the middle of its backlash)."""
    s = kit.params
    secs = sections or printed_sections(kit)
    n = len(thetas)
    nominal = np.array([[s.angle(sh, float(t)) for sh in s.shafts] for t in thetas])
    out = {"nominal": nominal, "drive": nominal.copy(), "coast": nominal.copy(), "overlap_mm2": np.zeros((n, len(s.meshes)))}
    m = s.system.module
    for key, way in (("drive", -1.0), ("coast", 1.0)):
        A = out[key]
        for mesh in s.meshes:
            gd, gn = s.gear(mesh.driver), s.gear(mesh.driven)
            shd, shn = s.shafts[gd.shaft], s.shafts[gn.shaft]
            cd, cn = np.array(shd.centre), np.array(shn.centre)
            u = (cn - cd) / np.linalg.norm(cn - cd)
            moved = shifts or {}
            dd, dn = (np.asarray(moved.get(sh.index, (0.0, 0.0)), float) for sh in (shd, shn))
            cd, cn = cd + dd, cn + dn
            r_wn = mesh.centre_distance * gn.spec.teeth / (gd.spec.teeth + gn.spec.teeth)
            start = float((dn - dd) @ np.array([-u[1], u[0]])) / r_wn
            pitch_pt = cd + u * mesh.centre_distance * gd.spec.teeth / (gd.spec.teeth + gn.spec.teeth)
            ang = math.atan2(u[1], u[0])
            inner = shapely.affinity.rotate(box(-2.5 * m, -3 * m, 2.5 * m, 3 * m), ang, origin=(0, 0), use_radians=True)
            inner = shapely.affinity.translate(inner, *pitch_pt)
            outer = inner.buffer(3 * m)
            ratio = float(shn.speed / shd.speed)
            sense = way * math.copysign(1.0, float(shn.speed))
            reach = math.pi / gn.spec.teeth
            for i in range(n):
                drv = shapely.intersection(_place(secs[gd.name], A[i, shd.index], cd), inner)
                shapely.prepare(drv)
                phi = shn.phase + ratio * (A[i, shd.index] - shd.phase) + start
                piece = shapely.intersection(_place(secs[gn.name], phi, cn), outer)

                def area(d: float) -> float:
                    q = _rotate(piece, d, cn)
                    return drv.intersection(q).area if drv.intersects(q) else 0.0
                if key == "drive":
                    out["overlap_mm2"][i, mesh.stage] = area(0.0)
                lo = free_turn(lambda d: area(sense * d) > 1e-9, 0.0, reach, tol)
                A[i, shn.index] = phi + sense * lo
                # a compound or idler shaft turns as one: its next stage is driven from this angle
    return out
