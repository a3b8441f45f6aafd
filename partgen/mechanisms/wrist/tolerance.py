"""The wrist pair's tolerance model: each dome tooth of gear 1 in the socket of gear 2 it sweeps over
the workspace, and the cross gear in mesh with its mate, as linear margins of the printed features'
deviations (``design.tolerance``; docs/tolerance.md "Wrist").

**The domes.** The sockets are cut by the dome teeth grown by ``clearance_radial_mm`` and swept over
every bend of the workspace, so wherever a dome runs in its socket its surface stands that clearance
off the socket's wall, in every direction the wall faces: across the dome's path (the two tangent
directions of the pitch surface at the dome) and at the socket's floor (the normal). A print turns
through its workspace when every dome keeps a gap ≥ 0 in every one of them:

    gap = c − δ_dome/2 + δ_sockets/2 − w · (Δdome − Δsocket)

``δ_dome``: gear 1's dome teeth printed larger (their radius grows by half); ``δ_sockets``: gear 2's
sockets printed larger (a cavity, as a hole); ``Δdome``, ``Δsocket``: the dome's centre and its
socket's place moved on their gears (three coordinates each, in the dome's tangent-normal frame,
position features, each dome's coordinates in its own tangent, tangent, normal frame); ``w``: a direction the wall faces. The contact normal turns through every
tangent direction as the dome runs along its socket, so the model takes ``DIRECTIONS`` directions
round the tangent plane (the largest of their projections is within cos(π/DIRECTIONS) of the
relative displacement's length: the model is optimistic by at most that factor in the tangent
plane) and the normal.

**The cross gear and its mate** (when the design has a mate): in the cross gear's plane x = 0 the
pair is a spur mesh (``mate.py``), and its margins are the spur mesh's, at the standard centre
distance (operating pressure angle = α, the cross gear's):

    backlash = j − (δ_cs + δ_mp)/cos α + 2 tan α · Δa
    tip-root cs→mp = a₀ − δ_cs/2 − δ_mp/2 + Δa        (and mp→cs alike)

``j``: the least backlash the check measured (the mate's free turn both ways at a fixed cross-gear
pose, 3-D, on the meshes, at its pitch circle; 0 when the check found the pair overlapping);
``δ_cs``, ``δ_mp``: each gear's outline printed larger, as a diameter (a flank moved out by
e = δ/2 thickens a tooth by 2e/cos α at the pitch circle); ``a₀``: the cross gear's tip to the
mate's root (and the mate's tip to the cross gear's root) on the line of centres, measured on the
meshes (the mate's root and tip radii; the cross gear's tip sphere) and the design (the cross
gear's root); ``Δa``: the centre distance's change, from where each part's teeth sit off the axis
it is held by:

* the mate is held on its shaft by its bore (fixed to it: the drive's output, as the cross gear on
  its D-shaft): its teeth off its bore by the bore centre's two position coordinates in its own
  frame, projected on the line of centres at the mate's turn ψ;
* the cross gear is held at its centre (the pivot it turns about) by its shaft and the flat face
  it seats on: its teeth off that point by its bore's two position coordinates and the printed
  height of its tooth sphere's centre over the face (``height``), projected on the line of centres
  at its turn −ψ z_mp/z_cs about x and its tilt about its ring axis y (the check's tilts).

The bore's projections turn with the parts, so the mesh's margins are taken at ``mate_turns``
(mate turns over its range ±turn_deg · z_cs/z_mp, at most 2π/DIRECTIONS apart: optimistic by at
most cos(π/DIRECTIONS) in those terms) and at the check's tilts. Assumed: the frame the maker
mounts the pair in holds the mate's axis and the cross gear's pivot at the design's distance (not
a printed part of the kit); no bore play is credited (neither gear turns on its bore: each is fixed
to its shaft, so ``seated`` changes nothing); the mate's axial place on its shaft moves the mesh
along the teeth and is not modelled (the backlash only grows off the mid-plane); the spur-mesh
coefficients are first order (an exact 3-D bisection checks the centre distance's: the tests).

Not modelled: the two shafts' distance and their angle (the pair's centre distance is held by
the frame the maker mounts it in, not a printed part of the kit), the press fits on the D-shafts.
The gears do not run in bores, so no play is credited and the worst case is the headline
(``seated`` has no effect).
"""

from __future__ import annotations

import math

import numpy as np

from ...core.findings import Result
from ...design.tolerance import Margin, MarginModel, ModelBuilder

__all__ = ["tolerance_model", "DIRECTIONS", "mate_turns", "MATE_TILTS_DEG", "MATE_UNIT"]

DIRECTIONS = 8  # directions round each dome's tangent plane
INTERFERENCE_MM3 = 0.01  # the check's overlap tolerance (checks.check_wrist's tol)
MATE_TILTS_DEG = (0.0, -35.0, 20.0)  # the cross gear's tilts about its ring axis y (mate.mate_poses')
MATE_UNIT = "cross_gear/cross_mate"


def tolerance_model(kit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of the wrist ``kit`` for a printer accuracy of ± ``accuracy_mm``. Each gap's nominal is
    the design's clearance when the nominal check found the sockets clear over the workspace, and
    0 (every print binds somewhere) when it found an overlap; the mate's (if any) from its check's
    measured backlash and the meshes' tip and root radii."""
    clear = float(result.figures.get("max_overlap_mm3", 0.0)) <= INTERFERENCE_MM3
    c = float(kit.spec.clearance) if clear else 0.0
    b = ModelBuilder()
    dome, socket = ("gear1 domes", "tooth", "gear1"), ("gear2 sockets", "hole", "gear2")
    ws = [np.array([math.cos(2 * math.pi * k / DIRECTIONS), math.sin(2 * math.pi * k / DIRECTIONS), 0.0])
          for k in range(DIRECTIONS)] + [np.array([0.0, 0.0, 1.0])]
    for k, d in enumerate(kit.domes):
        unit = f"dome {k}"
        for n, w in enumerate(ws):
            terms = {dome: -0.5, socket: 0.5}
            for axis, name in enumerate(("u", "v", "n")):
                if w[axis]:
                    terms[(f"gear1 dome {k} {name}", "position", "gear1")] = -float(w[axis])
                    terms[(f"gear2 socket {k} {name}", "position", "gear2")] = float(w[axis])
            what = "floor gap" if n == DIRECTIONS else f"side gap {round(360 * n / DIRECTIONS)}°"
            b.add(Margin(unit, "mesh", what, c, "gear2"), terms)
    if kit.spec.mate is not None and "mate" in result.figures:
        _mate_margins(b, kit, result.figures["mate"])
    return b.model(accuracy_mm, kit.name, "no gear runs in a bore: no play to credit, the worst case is the headline")


def mate_turns(spec) -> np.ndarray:
    """The mate's turns ψ (rad) the mesh's margins are taken at: its range ±turn · z_cs/z_mp (one
    whole turn at most), at most 2π/DIRECTIONS apart."""
    reach = min(math.pi, spec.mate.turn * spec.cross.teeth / spec.mate.teeth)
    if reach >= math.pi:
        return 2 * math.pi * np.arange(DIRECTIONS) / DIRECTIONS
    return np.linspace(-reach, reach, math.ceil(2 * reach / (2 * math.pi / DIRECTIONS)) + 1)


def _radii(kit) -> dict:
    """The meshes' radii the tip-to-root margins need (mm): the mate's root and tip circles (about
    its axis z, away from its bore), the cross gear's tip sphere (about its centre)."""
    by = {p.name: p.solid for p in kit.parts}
    v = np.asarray(by["cross_mate"].to_mesh().vert_properties)[:, :3]
    r = np.hypot(v[:, 0], v[:, 1])
    r = r[r > kit.spec.mate.bore_diameter / 2 + 0.5]
    cs = np.asarray(by["cross_gear"].to_mesh().vert_properties)[:, :3]
    return {"mate_root": float(r.min()), "mate_tip": float(r.max()), "cross_tip": float(np.linalg.norm(cs, axis=1).max())}


def _mate_margins(b: ModelBuilder, kit, figures: dict) -> None:
    """The cross gear/mate mesh's margins (module docstring) at each of ``mate_turns`` and
    ``MATE_TILTS_DEG``."""
    from ...geometry.cross_mate import cross_pose, mate_pose

    spec = kit.spec
    cs, mate = spec.cross, spec.mate
    alpha = cs.system.pressure_angle
    clear = float(figures["max_overlap_mm3"]) <= float(figures["epsilon_mm3"])
    j = float(figures["backlash_min_mm"]) if clear else 0.0
    radii = _radii(kit)
    a = mate.centre_distance(cs)
    tip_root = {"cs→mp": a - radii["cross_tip"] - radii["mate_root"] if clear else 0.0,
                "mp→cs": a - radii["mate_tip"] - cs.root_radius if clear else 0.0}
    teeth = {("cross_gear teeth", "tooth", "cross_gear"): 1.0, ("cross_mate teeth", "tooth", "cross_mate"): 1.0}
    for psi in mate_turns(spec):
        for tilt in MATE_TILTS_DEG:
            Tc = cross_pose(float(psi), cs, mate, math.radians(tilt))
            Tm = mate_pose(float(psi), cs, mate)
            toward = Tm[:3, 3] - Tc[:3, 3]
            toward /= np.linalg.norm(toward)  # the line of centres, cross gear → mate
            n_cs = Tc[:3, :3].T @ toward  # in the cross gear's own frame
            n_mp = Tm[:3, :3].T @ -toward  # in the mate's own frame (towards the cross gear)
            # a bore moved by b leaves the teeth −b off the axis the part is held by; teeth moved
            # towards the other gear shorten the centre distance
            da = {("cross_gear bore x", "position", "cross_gear"): float(n_cs[0]),
                  ("cross_gear bore y", "position", "cross_gear"): float(n_cs[1]),
                  ("cross_gear centre height", "height", "cross_gear"): -float(n_cs[2]),
                  ("cross_mate bore x", "position", "cross_mate"): float(n_mp[0]),
                  ("cross_mate bore y", "position", "cross_mate"): float(n_mp[1])}
            where = f"ψ {math.degrees(psi):.0f}°, tilt {tilt:.0f}°"
            terms = {k: 2 * math.tan(alpha) * v for k, v in da.items()}
            terms.update({k: -v / math.cos(alpha) for k, v in teeth.items()})
            b.add(Margin(MATE_UNIT, "mesh", f"backlash at {where}", j, "cross_gear"), terms)
            for name, a0 in tip_root.items():
                b.add(Margin(MATE_UNIT, "mesh", f"tip-root {name} at {where}", a0, "cross_gear"),
                      {**da, **{k: -0.5 * v for k, v in teeth.items()}})
