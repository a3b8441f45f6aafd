"""The shared checks in the order every kit that uses them runs them: the motion sweep, the meshes,
the fits, printability, the bed and the bores — written once.

A mechanism calls ``run_shared`` from its own check with what differs between kits: the view of
the kit the mesh check measures (or none), the pairs of parts whose clearance the mesh check owns
(meshing teeth come within their backlash by design), the sweep's pruning, the parts' printed
extents and whether its bores are tested. Findings go into the mechanism's ``Result`` in that
order; the figures come back for it to file.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..core.findings import Result
from ..core.protocol import CheckedKit
from .bed import bed_findings
from .bores import bore_findings
from .fits import check_fits
from .meshing import check_meshes
from .motion import PartGeometry, prepare, sweep
from .printability import check_printability, printed_extents

__all__ = ["Shared", "run_shared"]


@dataclass(frozen=True)
class Shared:
    """What the shared checks found besides their findings: the figures of each, the geometry the
    sweep used, the clearance findings left to the mesh check and the seconds each step took."""

    motion: dict
    meshes: list
    fits: list
    printing: dict  # printability, the bed's figures and (when tested) "bores"
    geo: dict
    dropped: int
    seconds: dict


def run_shared(res: Result, kit: CheckedKit, thetas: np.ndarray, label: str, progress=None, *,
               geo: dict[str, PartGeometry] | None = None, mesh_view=None, mesh_owned: set | None = None,
               prune: bool = False, extents: dict | None = None, bores: bool = True) -> Shared:
    """Run the shared checks on ``kit`` over the motion values ``thetas`` (``label``: what the
    mechanism calls its input) and add their findings to ``res``.

    ``geo``: the parts' sweep geometry if the mechanism prepared it (``motion.prepare``);
    ``mesh_view``: the kit as the mesh check sees it (``meshing.check_meshes``; None: no mesh check);
    ``mesh_owned``: frozensets of part names whose clearance findings the mesh check owns (dropped
    from the sweep's); ``prune``: the sweep's pruning of slab pairs that cannot come close;
    ``extents``: the parts' printed extents (default ``printability.printed_extents``); ``bores``:
    test that every bore is open (``bores.bore_findings``)."""
    t0 = time.perf_counter()
    geo = prepare(kit) if geo is None else geo
    t1 = time.perf_counter()
    found, motion = sweep(kit, geo, thetas, progress, prune=prune, label=label)
    owned = mesh_owned or set()
    dropped = [f for f in found if f.check == "clearance" and frozenset(f.parts) in owned]
    res.add(*[f for f in found if f not in dropped])
    t2 = time.perf_counter()
    meshes: list = []
    if mesh_view is not None:
        found, meshes = check_meshes(mesh_view, thetas, label)
        res.add(*found)
    t3 = time.perf_counter()
    found, fits = check_fits(kit, geo, thetas)
    res.add(*found)
    found, printing = check_printability(kit, geo, printed_extents(kit) if extents is None else extents)
    res.add(*found)
    found, on_bed = bed_findings(kit.parts, kit.params.printer)
    res.add(*found)
    printing = {**printing, **on_bed}
    if bores:
        found, open_bores = bore_findings(kit.parts)
        res.add(*found)
        printing["bores"] = open_bores
    t4 = time.perf_counter()
    return Shared(motion, meshes, fits, printing, geo, len(dropped),
                  {"prepare": round(t1 - t0, 3), "motion": round(t2 - t1, 3), "meshes": round(t3 - t2, 3),
                   "fits_and_printability": round(t4 - t3, 3)})
