"""Parts the design means to touch: each fit is checked for its clearance, not skipped.

Running and press fits: no overlap at a few angles, and the radial gap measured in the section
through the middle of the fit compared with the design's. Thrust faces: touching, not overlapping.

The overlap is measured as the motion sweep does: parts are stacks of z-prisms that turn about z,
so the overlap of two parts is the sum over their slabs sharing z of section ∩ section × shared
height, exact for prisms. Only a fit that overlaps by that measure (or a pose that tilts a part)
is measured in 3-D with manifold3d, which gives the volume and where it is."""

from __future__ import annotations

import math

import numpy as np
import shapely

from ..core.protocol import CheckedKit as Kit  # what the shared checks read of a kit
from ..geometry.measure import intersection, place2d
from ..core.findings import Finding
from .motion import PartGeometry

__all__ = ["check_fits"]


def _slab_at(g: PartGeometry, z_local: float):
    return next((s for s in g.slabs if s.z0 - 1e-9 <= z_local <= s.z1 + 1e-9), None)


def _planar(T: np.ndarray) -> bool:
    return abs(T[2, 2] - 1.0) < 1e-12


def _prism_overlap(ga: PartGeometry, Ta: np.ndarray, gb: PartGeometry, Tb: np.ndarray) -> float:
    """Overlap volume (mm³) of two slab stacks at planar poses: Σ area(section ∩ section) × shared height."""
    za, zb = Ta[2, 3], Tb[2, 3]
    vol = 0.0
    for sa in ga.slabs:
        ca = Ta[:2, :2] @ sa.centre + Ta[:2, 3]
        for sb in gb.slabs:
            h = min(sa.z1 + za, sb.z1 + zb) - max(sa.z0 + za, sb.z0 + zb)
            if h <= 1e-9:
                continue
            cb = Tb[:2, :2] @ sb.centre + Tb[:2, 3]
            if math.dist(ca, cb) >= sa.radius + sb.radius:
                continue
            common = shapely.intersection(place2d(sa.shape, Ta), place2d(sb.shape, Tb))
            vol += common.area * h
    return vol


FIT_KINDS = ("running", "press", "thrust")  # the contacts (core.parts.Contact) that are fits


def check_fits(kit: Kit, geo: dict[str, PartGeometry], thetas: np.ndarray, angles: int = 4) -> tuple[list[Finding], list[dict]]:
    tol = kit.params.checks.interference_tolerance
    picks = thetas[:: max(1, len(thetas) // angles)][:angles]
    poses = [kit.poses(float(t)) for t in picks]
    findings, rows = [], []
    for c in kit.contacts:
        if c.kind not in FIT_KINDS:  # meshes and drives are other checks' (meshing, the mechanism's own)
            continue
        ga, gb = geo[c.a], geo[c.b]
        worst = (0.0, 0, None)
        for n, pz in enumerate(poses if c.kind == "running" else poses[:1]):
            Ta, Tb = pz[c.a], pz[c.b]
            if _planar(Ta) and _planar(Tb) and _prism_overlap(ga, Ta, gb, Tb) <= tol:
                continue  # exact for prisms: no overlap worth measuring in 3-D
            vol, centre = intersection(ga.solid, Ta, gb.solid, Tb)
            if vol > worst[0]:
                worst = (vol, n, centre)
        row = {"parts": [c.a, c.b], "kind": c.kind, "overlap_mm3": round(worst[0], 6)}
        if c.window is not None:
            z = sum(c.window) / 2
            Ta, Tb = poses[0][c.a], poses[0][c.b]
            sa, sb = _slab_at(ga, z - Ta[2, 3]), _slab_at(gb, z - Tb[2, 3])
            if sa is not None and sb is not None:
                A, B = place2d(sa.shape, Ta), place2d(sb.shape, Tb)
                gap = shapely.distance(A, B) if not shapely.intersects(A, B) or shapely.intersection(A, B).area < 1e-9 \
                    else -shapely.intersection(A, B).area / max(B.length, 1e-9)  # overlap as a mean depth
                row.update(radial_gap_mm=round(gap, 5), design_radial_gap_mm=round(c.radial_gap, 5))
                if worst[0] <= tol and gap < c.radial_gap - 0.02:
                    findings.append(Finding("fit", "warn", f"{c.a} on {c.b} ({c.kind} fit): radial gap {gap:.3f} mm, "
                                            f"design {c.radial_gap:.3f} mm", (c.a, c.b), None, gap, "mm"))
        rows.append(row)
        if worst[0] > tol:
            why = {"running": "a joint that must turn is jammed", "press": "the press fit interferes",
                   "thrust": "the parts overlap where they should only rest on each other"}[c.kind]
            findings.append(Finding("fit", "fail", f"{c.a} on {c.b} ({c.kind} fit): overlap {worst[0]:.3f} mm³ — {why}"
                                    + (f" (design radial clearance {c.radial_gap:+.3f} mm)" if c.window else ""),
                                    (c.a, c.b), float(picks[worst[1]]), worst[0], "mm3",
                                    tuple(worst[2]) if worst[2] is not None else None))
    return findings, rows
