"""The rack driven by the pinion on their printed sections (the check's backlash and overlap, the
trace's transmission error)."""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import box

from ....checks.contact import free_turn
from ....geometry.measure import section
from .kit import RackKit

__all__ = ["turn_rack"]


def _sections(kit: RackKit) -> tuple:
    s = kit.params
    z = s.gear_z + s.face_width / 2
    return section(kit.part("pinion").solid, z), section(kit.part("rack").solid, s.face_width / 2)


def _place(geom, angle: float, at) -> object:
    c, sn = math.cos(angle), math.sin(angle)
    R = np.array([[c, -sn], [sn, c]])
    return shapely.transform(geom, lambda p: p @ R.T + np.asarray(at))


def turn_rack(kit: RackKit, thetas: np.ndarray, tol: float = 1e-6, pinion_at: tuple[float, float] = (0.0, 0.0),
              rack_dy: float = 0.0) -> dict:
    """Over pinion angles ``thetas`` (n,) rad, from the printed sections: the rack's x (mm) when the
    pinion drives it (``drive``: the rack found moved back from its nominal place until it touches,
    the pinion turning forward; ``coast``: the other flanks), nominal x, and the overlap (mm²) at
    the nominal place. ``pinion_at``: the pinion's centre moved to (x, y) mm (in its bore's play);
    ``rack_dy``: the rack moved by that along y (towards its rail: negative) — the lost-motion
    model's exact check (``play.py``)."""
    s = kit.params
    pin, rack = _sections(kit)
    m = s.system.module
    window = box(-4 * m, s.pitch_line - 3 * m, 4 * m, s.pitch_line + 3 * m)
    nominal = np.array([s.rack_x(float(t)) for t in thetas])
    out = {"nominal": nominal, "drive": np.empty(len(thetas)), "coast": np.empty(len(thetas)),
           "overlap_mm2": np.zeros(len(thetas))}
    for i, t in enumerate(thetas):
        P = shapely.intersection(_place(pin, -math.pi / 2 + float(t), pinion_at), window)
        shapely.prepare(P)
        piece = shapely.intersection(_place(rack, 0.0, (nominal[i], s.pitch_line + rack_dy)), window.buffer(2 * m))

        def area(d: float) -> float:
            q = shapely.affinity.translate(piece, d)
            return P.intersection(q).area if P.intersects(q) else 0.0
        out["overlap_mm2"][i] = area(0.0)
        for key, sense in (("drive", -1.0), ("coast", 1.0)):
            out[key][i] = nominal[i] + sense * free_turn(lambda d: area(sense * d) > 1e-9, 0.0, math.pi * m / 2, tol)
    return out
