"""What play costs at the planetary set's output (docs/tolerance.md, "What play costs"): the lost motion
of the carrier in arc-minutes, the sun (input) held and the ring fixed, from each mesh's backlash and
the bores' radial play; its worst case and 95 % figure over prints and the transmission-error band
(``common/play.py``).

The model (first order in small displacements; ring fixed, sun input, carrier output — the only
arrangement the sub-slice builds; a, the centre distance; r_s + r_r = 2a):

* **A planet's range.** Planet i is free between its two meshes: with the sun held it rolls on the
  sun, so its ring side moves twice its centre, and the carrier turns through
  ``(j_sp + j_pr) / (2a)`` (both meshes' circumferential backlash on their operating pitch circles).
  Turning the printed outlines (``motion.turn_planetary``, the sun held in the world) measures the
  same; ``tests/mechanisms/gear_train/test_planetary_play.py`` holds them together.
* **The planet on its pin** (radial play c_p): moved along the carrier's tangent by t, the planet's
  centre stands where the carrier's pin would be had the carrier turned t/a: the range grows by
  ``2 c_p / a``. Moved radially it opens one mesh by ``2 tan α_w`` per mm and closes the other as
  much (the sum does not change): the tangential direction is the worst, and the exact check (the
  printed outlines with every planet ± c_p along the tangent) agrees.
* **The sun and the carrier on their shafts** float: a displacement d of the sun (or e of the carrier's
  axis) shifts planet i's range by ``(d·t_i)/(2a)`` (``−(e·t_i)/a``) and opens its sun mesh by
  ``−2 tan α_w (d·u_i)``. With weights λ_i ≥ 0 (Σ λ_i = 1) for which ``Σ λ_i (cos γ_i, sin γ_i) = 0``
  — the planets not all on one side of the sun: ``1/N`` for equal spacing — every such shift sums
  to 0, so the carrier's range is at most the λ-mean of the planets' ranges: a floating sun and
  carrier share the load out, they add no lost motion (0 in the table). If no such λ exists (planets
  within a half turn, unequal spacing only) their whole play is added: ``c_s / (a cos α_w)`` and
  ``2 c_e / a``.
* **A print**: the carrier's range is that λ-mean of its planets' ranges ``(j_sp,i + j_pr,i)/(2a) +
  2 c_p,i / a``: each mesh's backlash less its two gears' outline deviations over cos α_w (the ring's
  teeth are frame_bottom's), each pin's play ± half its bore's and its pin's deviation — the tolerance
  model's terms (``common/tolerance.py``, ``running_fits``). The positions of the pins and the two axes
  drop out of the λ-mean (the pins' and the carrier's move the planet's two meshes oppositely, the
  sun's sum to 0 over the planets): they shift the planets' ranges apart, which the floating sun
  takes up as long as its play exceeds the shifts (0.15 mm radial against a few hundredths): when
  it does not, the carrier turns less — the figures are an upper bound.
"""

from __future__ import annotations

import math

import numpy as np

from ....core.findings import Result
from ....design import involute
from ....design.tolerance import ModelBuilder
from ..common.play import ARCMIN, Share, lost_motion as cost
from ..common.tolerance import running_fits, tooth
from .tolerance import internal_backlash

__all__ = ["shares", "lost_motion", "weights"]


def weights(angles) -> np.ndarray | None:
    """λ_i ≥ 0, Σ λ_i = 1 with Σ λ_i e^{iγ_i} = 0 for planets at carrier angles ``angles`` (rad), or
    None when the planets lie within a half turn (no such λ)."""
    u = np.exp(1j * np.asarray(angles, dtype=float))
    n = len(u)
    if abs(u.sum()) < 1e-9:
        return np.full(n, 1.0 / n)
    from scipy.optimize import nnls

    w = 1e3  # Σ λ = 1, weighted well above the two others
    lam, res = nnls(np.vstack([u.real, u.imag, np.full(n, w)]), np.array([0.0, 0.0, w]))
    return lam if res < 1e-9 else None


def shares(kit) -> list[Share]:
    """The carrier's lost motion as shares (arc-minutes per mm), from the kit's planetary spec and
    running fits."""
    s = kit.params
    a, sy = s.centre_distance, s.system
    zs, zp = s.teeth.sun, s.teeth.planet
    j_sp = involute.circumferential_backlash(zs, zp, sy.module, sy.pressure_angle, s.sun.profile_shift,
                                             s.planet.profile_shift, sy.backlash_per_gear, sy.backlash_per_gear, a)
    aw_s = math.acos(min(1.0, (zs + zp) * sy.module / 2 * math.cos(sy.pressure_angle) / a))
    j_pr, aw_r = internal_backlash(s.planet, s.space, a)
    plays = running_fits(ModelBuilder(), kit, Result())  # each running fit's play and its feature terms
    lam = weights(s.angles)
    lam_ = lam if lam is not None else np.full(len(s.angles), 1.0 / len(s.angles))
    out = []
    for i, w in enumerate(lam_):
        planet = f"planet{i}"
        g = float(w) / (2 * a) * ARCMIN
        out.append(Share(f"sun/{planet}", "sun/planet", "backlash", j_sp, g,
                         {tooth("sun"): -1 / math.cos(aw_s), tooth(planet): -1 / math.cos(aw_s)}))
        out.append(Share(f"{planet}/ring", "planet/ring", "backlash", j_pr, g,
                         {tooth(planet): -1 / math.cos(aw_r), tooth("frame_bottom"): -1 / math.cos(aw_r)}))
        p = plays.get(planet)
        if p is not None:
            out.append(Share(f"{planet} on carrier", "a planet on its pin", "bores", p.nominal, 4 * g, p.terms))
    float_gain = {"shaft_in": 1 / (a * math.cos(aw_s)), "shaft_out": 2 / a}  # only without λ
    for body, label in (("shaft_in", "the sun's shaft in frame_bottom"), ("shaft_out", "the carrier's shaft in frame_top")):
        p = plays.get(body)
        if p is not None:
            out.append(Share(body, label, "bores", p.nominal, 0.0 if lam is not None else float_gain[body] * ARCMIN,
                             p.terms))
    return out


def lost_motion(spec, kit, te_drive_arcmin=None, te_coast_arcmin=None) -> dict:
    """The carrier's lost motion (arc-minutes: nominal, worst case, 95 % and median of prints at the
    printer's xy accuracy) and, with the measured transmission errors (arcmin), the band about nominal."""
    out = cost(shares(kit), spec.printer.xy_accuracy, "arcmin", te_drive_arcmin, te_coast_arcmin)
    out["radial_play_mm"] = round(spec.running / 2, 6)
    out["model"] = ("first order: each planet's range (j_sp + j_pr)/(2a) + 2 c_pin/a, the λ-mean over the planets "
                    "(the floating sun and carrier add none); docs/tolerance.md, What play costs")
    return out
