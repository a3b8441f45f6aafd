"""What play costs in a gear train (docs/tolerance.md, "What play costs"): the lost motion at the
output shaft and the band the output angle can take about its nominal.

* **Each mesh's backlash**: the circumferential backlash on its operating pitch circle
  (``involute.circumferential_backlash`` at the built centre distance), turned into an angle of the
  driven gear (``j / r_w``) and referred to the output through the shafts' speeds
  (``|ω_out / ω_driven|``).
* **The bores' play**: each shaft runs with radial play ``c`` (half the diametral running
  clearance). As the tolerance model credits it, play along a mesh's line of centres opens the mesh:
  its backlash grows by ``2 tan α_w · c`` for each of its two shafts (every body free to take its
  whole play, κ = 1: the most the play can cost).
* **Lost motion** is the sum over meshes, in arc-minutes at the output; the **transmission-error
  band** is the measured drive-flank and coast-flank transmission error (the printed outlines, every
  shaft centred) widened on each side by half the bores' share.
"""

from __future__ import annotations

import math

import numpy as np

from ....design import involute
from ..common.play import ARCMIN, te_band

__all__ = ["lost_motion"]


def lost_motion(spec, te_drive_arcmin: np.ndarray | None = None, te_coast_arcmin: np.ndarray | None = None) -> dict:
    """Lost motion at the output of a spur/helical train ``spec`` (a ``TrainSpec``), in arc-minutes,
    per mesh and in all; with the measured transmission errors (arcmin), the band about nominal."""
    out = spec.shafts[-1]
    c = spec.running / 2
    rows, lash, bores = [], 0.0, 0.0
    for mesh in spec.meshes:
        gd, gn = spec.gear(mesh.driver), spec.gear(mesh.driven)
        a = mesh.centre_distance
        s = gd.spec.system
        z1, z2 = gd.spec.teeth, gn.spec.teeth
        j = involute.circumferential_backlash(z1, z2, s.module, s.pressure_angle, gd.spec.profile_shift,
                                              gn.spec.profile_shift, s.backlash_per_gear, s.backlash_per_gear, a)
        aw = math.acos(min(1.0, (z1 + z2) * s.module / 2 * math.cos(s.pressure_angle) / a))
        rw = a * z2 / (z1 + z2)
        refer = abs(float(out.speed / spec.shafts[gn.shaft].speed))
        m_lash = max(j, 0.0) / rw * refer * ARCMIN
        m_bores = 2 * math.tan(aw) * 2 * c / rw * refer * ARCMIN
        rows.append({"mesh": f"{mesh.driver}/{mesh.driven}", "backlash_mm": round(j, 6),
                     "backlash_arcmin": round(m_lash, 4), "bores_arcmin": round(m_bores, 4)})
        lash += m_lash
        bores += m_bores
    res = {"total": round(lash + bores, 4), "backlash": round(lash, 4), "bores": round(bores, 4),
           "radial_play_mm": round(c, 6), "meshes": rows}
    if te_drive_arcmin is not None and te_coast_arcmin is not None:
        res["transmission_error_band_arcmin"] = te_band(te_drive_arcmin, te_coast_arcmin, bores)
    return res
