"""The wrist pair's tolerance model: each dome tooth of gear 1 in the socket of gear 2 it sweeps over
the workspace, as linear margins of the printed features' deviations (``design.tolerance``;
docs/tolerance.md "Wrist").

The sockets are cut by the dome teeth grown by ``clearance_radial_mm`` and swept over every bend of
the workspace, so wherever a dome runs in its socket its surface stands that clearance off the
socket's wall, in every direction the wall faces: across the dome's path (the two tangent
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

Not modelled: the two shafts' distance and their angle (the pair's centre distance is held by
the frame the maker mounts it in, not a printed part of the kit), the press fits on the D-shafts,
and the cross gear (a second tooth form shown beside the pair). The gears do not run in bores, so
no play is credited and the worst case is the headline (``seated`` has no effect).
"""

from __future__ import annotations

import math

import numpy as np

from ...core.findings import Result
from ...design.tolerance import Margin, MarginModel, ModelBuilder

__all__ = ["tolerance_model", "DIRECTIONS"]

DIRECTIONS = 8  # directions round each dome's tangent plane
INTERFERENCE_MM3 = 0.01  # the check's overlap tolerance (checks.check_wrist's tol)


def tolerance_model(kit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of the wrist ``kit`` for a printer accuracy of ± ``accuracy_mm``. Each gap's nominal is
    the design's clearance when the nominal check found the sockets clear over the workspace, and
    0 (every print binds somewhere) when it found an overlap."""
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
    return b.model(accuracy_mm, kit.name, "no gear runs in a bore: no play to credit, the worst case is the headline")
