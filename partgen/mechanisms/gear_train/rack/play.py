"""What play costs at the rack (docs/tolerance.md, "What play costs"): the rack's lost motion in mm of
its travel (the pinion held, how far the rack slides freely) and in arc-minutes at the pinion, from
the mesh's backlash and the bores' play; its worst case and 95 % figure over prints and the
transmission-error band (``common/play.py``).

The model (first order; the rack's flanks are straight at the pressure angle α, so a centre distance
changed by Δ changes the backlash along the pitch line by ``2 tan α · Δ``):

* **The mesh**: the circumferential backlash on the pinion's pitch circle, which is the rack's free
  travel: ``j = 2 × backlash_per_gear`` (each thinned at its reference line), less the pinion's and
  the rack's outline deviations over cos α.
* **The pinion's shaft in the base** (radial play c): the pinion's centre anywhere in a disk of
  radius c. Moved along the travel by x it carries the rack's contact with it (x); moved away from
  the rack by y it opens the mesh by ``2 tan α · y``; the rack's range is ``j + 2 max (x + tan α · y)``
  over the disk, ``j + 2c / cos α`` (the centre along (cos α, sin α)). The exact check (the printed
  outlines with the pinion there, ``motion.turn_rack``) agrees.
* **The rack against its rail**: nothing holds it on the pinion but its teeth; it can back off to its
  rail, the rail's running gap g (``running / 2``) away, opening the mesh by ``2 tan α · g``. A print
  moves the rail's face, the pinion's hole (along y) and the rack's back (half its outline's
  deviation) — the tolerance model's terms for the pinion's axis to the rack's pitch line
  (``tolerance.py``) — on this share.
* **A print**: each share with the tolerance model's features and σ; the pinion's play ± half its
  bore's and its shaft's deviation (``running_fits``).
"""

from __future__ import annotations

import math

from ....core.findings import Result
from ....design.tolerance import ModelBuilder
from ..common.play import ARCMIN, Share, lost_motion as cost
from ..common.tolerance import running_fits, tooth

__all__ = ["shares", "lost_motion"]


def shares(kit) -> list[Share]:
    """The rack's lost motion as shares (mm of travel per mm)."""
    s = kit.params
    al = s.system.pressure_angle
    j = 2 * s.system.backlash_per_gear
    plays = running_fits(ModelBuilder(), kit, Result())
    out = [Share("pinion/rack", "pinion/rack", "backlash", j, 1.0,
                 {tooth("pinion"): -1 / math.cos(al), tooth("rack"): -1 / math.cos(al)})]
    p = plays.get("shaft")
    if p is not None:
        out.append(Share("shaft", "the pinion's shaft in the base", "bores", p.nominal, 2 / math.cos(al), p.terms))
    rail = {("frame_bottom rail face y", "position", "frame_bottom"): 1.0,
            ("frame_bottom shaft hole y", "position", "frame_bottom"): -1.0,
            ("rack outline", "outline", "rack"): -0.5}
    out.append(Share("rack on its rail", "the rack against its rail", "bores", s.running / 2, 2 * math.tan(al), rail))
    return out


def lost_motion(spec, kit, te_drive_mm=None, te_coast_mm=None) -> dict:
    """The rack's lost motion (mm of travel: nominal, worst case, 95 % and median of prints at the
    printer's xy accuracy; ``pinion_arcmin``: the same as the pinion's free angle with the rack held)
    and, with the measured transmission errors (mm), the band about nominal."""
    out = cost(shares(kit), spec.printer.xy_accuracy, "mm", te_drive_mm, te_coast_mm)
    per = ARCMIN / spec.pinion.pitch_radius
    out["pinion_arcmin"] = {k: round(out[k] * per, 4) for k in ("total", "backlash", "bores", "worst_case", "p95", "p50")}
    out["radial_play_mm"] = round(spec.running / 2, 6)
    out["model"] = ("first order: j + 2 c_shaft / cos α + 2 tan α · rail gap (mm of rack travel); docs/tolerance.md, "
                    "What play costs")
    return out
