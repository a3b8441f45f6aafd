"""A throated (enveloping) worm wheel, cut by its worm's envelope (manifold3d; mm, rad).

The generating cut a hob makes: the wheel's blank minus the cutter (the worm, its thread grown by
the wheel's play and its tip by the wheel's bottom clearance) at the sampled phases of the mesh —
the worm turned by φ, the wheel by φ z_1 / z_2 — so every flank of the wheel is the envelope of the
worm's thread in their relative motion (line contact instead of the plain wheel's point).

One tooth is cut, not all: the mesh repeats every tooth of the wheel, so the blank's wedge round
tooth 0 (one tooth pitch and a little more each side) is cut by the cutter at every phase at which
it passes the worm, one boolean at a time, each done at once (the wedge stays small; a union of the
overlapping cutter poses first, which manifold3d makes of a chain of deferred differences, is five
times as slow), and the wheel is that tooth turned to each of its places and joined to the hub
below the roots. The cutter takes only a few orientations (a worm turned by its tooth pitch is
itself), so it is cut to the blank's ring once per orientation and that small piece is what each
pose turns.
"""

from __future__ import annotations

import math
from typing import Iterable

import manifold3d as m3d
import numpy as np

from .bevel import revolved
from .helical import sector_prism
from .outline import circle
from .solid import extrude

__all__ = ["throated_wheel"]

OVERLAP_RAD = 0.02  # each tooth's wedge reaches this far into its neighbours' (they overlap, never just touch)
SLIVER_MM3 = 1e-6  # pieces of a cut smaller than this are the booleans' zero-volume slivers
ROOT_OVERLAP_MM = 0.02  # the hub's top above the generated root: the spaces' roots stand this much higher
SEAM_RAD = 0.002  # each cut tooth is trimmed this far short of the middles of its spaces: its copies never touch


def _now(solid: m3d.Manifold) -> m3d.Manifold:
    """``solid`` with its booleans done now: manifold3d defers them, and a chain of differences left
    to the end is flattened into one difference from the union of all the cut pieces (here ~70
    overlapping ones: five times as slow as cutting them one by one)."""
    solid.num_vert()
    return solid


def throated_wheel(cutter: m3d.Manifold, orientations: Iterable[tuple[np.ndarray, Iterable[float]]], teeth: int,
                   tip_radius: float, centre_distance: float, cutter_tip: float, face: float, bore: float,
                   tol: float) -> m3d.Manifold:
    """The wheel in its local frame (axis z, face from −face/2 to face/2, tooth 0 on +x): a blank of
    ``tip_radius`` cut by ``cutter`` at every pose the mesh puts it in. ``orientations``: (T, angles)
    pairs, T (4, 4) the cutter's pose in the wheel's frame with the wheel at angle 0 and ``angles``
    (rad) the wheel's turns at which the cutter is in that pose relative to the wheel's axis (a worm
    turned by a tooth pitch is itself: the wheel has turned a tooth further) — the cutter is cut to
    the blank's ring once per orientation and that piece turned to each angle; a round bore of
    ``bore`` radius.

    The shafts at 90°: the cutter's tip (``cutter_tip`` round its axis, ``centre_distance`` from the
    wheel's) sweeps the root, the torus ρ = a − √(r_c² − z²). The cut tooth is trimmed to its own
    tooth pitch (the planes through the middles of the spaces) and every copy of it stands on a hub
    whose top is that torus ``ROOT_OVERLAP_MM`` higher; the tooth stops ``SEAM_RAD`` short of those
    planes, so neighbouring teeth never touch (they meet only through the hub: one shell; where the
    faceted cutter left the root a hair above the hub's top, the space's middle keeps a groove that
    shallow)."""
    a, rc = centre_distance, cutter_tip
    if face / 2 >= rc:
        raise ValueError(f"the wheel's face ({face:g} mm) is wider than the worm's tip diameter")
    inner_radius = a - rc - 1.0  # a millimetre below the deepest root
    half = math.pi / teeth + OVERLAP_RAD
    wedge = sector_prism(tip_radius + 1.0, 0.0, half, face / 2 + 1.0)
    ring = extrude(circle(tip_radius, tol), face, -face / 2) - extrude(circle(inner_radius, tol, hole=True), face + 2.0,
                                                                      -face / 2 - 1.0)
    reach = extrude(circle(tip_radius + 0.5, tol), face + 1.0, -face / 2 - 0.5) - extrude(
        circle(inner_radius - 0.5, tol, hole=True), face + 4.0, -face / 2 - 2.0)  # the ring, a little larger
    tooth = ring ^ wedge
    for T, angles in orientations:
        near = cutter.transform(np.asarray(T, dtype=float)[:3, :]) ^ reach
        if near.is_empty():
            continue
        for turn in angles:
            piece = near.rotate((0.0, 0.0, -math.degrees(turn))) ^ wedge
            if not piece.is_empty():
                tooth = _now(tooth - piece)
    tooth = tooth ^ sector_prism(tip_radius + 1.0, 0.0, math.pi / teeth - SEAM_RAD, face / 2 + 1.0)
    kept = [c for c in tooth.decompose() if c.volume() > SLIVER_MM3]
    tooth = m3d.Manifold.batch_boolean(kept, m3d.OpType.Add) if len(kept) > 1 else kept[0]
    z = np.linspace(-face / 2, face / 2, 41)
    top = a - np.sqrt(rc * rc - z * z) + ROOT_OVERLAP_MM
    profile = np.vstack([[[0.0, -face / 2]], np.column_stack([top, z]), [[0.0, face / 2]]])
    hub = revolved(profile, float(top.max()), tol)
    wheel = m3d.Manifold.batch_boolean([hub] + [tooth.rotate((0.0, 0.0, math.degrees(2 * math.pi * k / teeth)))
                                                for k in range(teeth)], m3d.OpType.Add)
    return wheel - extrude(circle(bore, max(tol, 0.005), hole=True), face + 2.0, -face / 2 - 1.0)
