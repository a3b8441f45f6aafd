"""Whether two gear outlines in mesh have a free relative angle (shapely, mm, rad): the exact
Monte Carlos' test of a printed mesh (the mechanisms' ``exact.py``)."""

from __future__ import annotations

import math

from shapely import affinity

__all__ = ["free_angle", "TOL_RAD", "FREE_MM2"]

TOL_RAD = 1e-6
FREE_MM2 = 1e-9


def free_angle(g1, p2, a: float, phi: float, reach: float) -> bool:
    """Whether ``p2`` (an outline about its own centre), turned by ``phi + d`` and moved to ``(a, 0)``,
    clears ``g1`` (prepared, clipped near the mesh) for some ``d`` in ± ``reach``: a golden-section
    search of the overlap area, a function that is zero on the free window and grows either side."""
    def area(d: float) -> float:
        g2 = affinity.translate(affinity.rotate(p2, phi + d, origin=(0, 0), use_radians=True), a)
        return g1.intersection(g2).area if g1.intersects(g2) else 0.0
    lo, hi = -reach, reach
    g = (math.sqrt(5) - 1) / 2
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = area(x1), area(x2)
    while hi - lo > TOL_RAD:
        if f1 <= FREE_MM2 or f2 <= FREE_MM2:
            return True
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - g * (hi - lo)
            f1 = area(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + g * (hi - lo)
            f2 = area(x2)
    return min(f1, f2) <= FREE_MM2
