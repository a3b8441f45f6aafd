"""The planetary set's tolerance model (``common/tolerance.py`` for the model's terms, docs/tolerance.md
"Gear trains"): the sun/planet meshes as external meshes, at ``CARRIER_ANGLES`` carrier angles;

* **Internal mesh** (planet in the ring): a larger centre distance takes the planet deeper into the
  ring, so the signs of ``Δa`` turn over; the ring's teeth (``frame_bottom teeth``) grow into its
  spaces as a gear's do.
* **The planetary's assembly with printed teeth**: N planets mesh the sun and the ring at once only
  where their pins sit. A pin moved by ``e`` along the planet's path (tangentially) turns the planet
  on the ring and moves its sun-side flank by ``2e``: the sun/planet and planet/ring backlash together
  must take it (``j_sp + j_pr − 2|e| ≥ 0``, two margins; the sun's own turn, which could share out a
  common shift, is not credited: conservative).
"""

from __future__ import annotations

import math

import numpy as np

from ....core.findings import Result
from ....design.involute import inv, reference_tooth_thickness
from ....design.tolerance import Margin, MarginModel, ModelBuilder, seat_credit, seat_factor
from ..common.tolerance import (add_term, external_mesh, feature_xy, gap_margins, project, project_axis, running_fits,
                                tooth)
from .kit import PlanetaryKit
from .resolve import PlanetarySpec

__all__ = ["tolerance_model", "internal_backlash", "CARRIER_ANGLES"]

CARRIER_ANGLES = 6  # carrier angles over a turn at which a planet's meshes are taken (the carrier's axis
#                     may be off the sun's in any direction: each angle's projection is a margin)


def internal_backlash(planet, space, a: float) -> tuple[float, float]:
    """(circumferential backlash on the operating pitch circles, mm; working pressure angle α_w, rad)
    of ``planet`` (a GearSpec) in the ring whose spaces are the teeth of ``space`` (its space gear)
    at centre distance ``a``: the ring's space width at its operating pitch circle less the planet's
    tooth thickness at its own (the two circles roll on each other; at the zero-backlash distance
    with α_w = α it is the planet's thinning plus the ring's)."""
    z1, z2, m, alpha = planet.teeth, space.teeth, planet.system.module, planet.system.pressure_angle
    aw = math.acos(min(1.0, m * (z2 - z1) / 2 * math.cos(alpha) / a))
    rw1, rw2 = a * z1 / (z2 - z1), a * z2 / (z2 - z1)
    s1 = reference_tooth_thickness(z1, m, alpha, planet.profile_shift, planet.system.backlash_per_gear)
    sE = reference_tooth_thickness(z2, m, alpha, space.profile_shift, space.system.backlash_per_gear)
    space_w = 2 * rw2 * (sE / (m * z2) + inv(alpha) - inv(aw))
    tooth_w = 2 * rw1 * (s1 / (m * z1) + inv(alpha) - inv(aw))
    return space_w - tooth_w, aw


def _rot(a: float) -> np.ndarray:
    c, sn = math.cos(a), math.sin(a)
    return np.array([[c, -sn], [sn, c]])


def tolerance_model(kit: PlanetaryKit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) for a printer accuracy of ± ``accuracy_mm``
    (``seated``: the sun and planets get no play, their meshes push both ways; otherwise centred)."""
    s: PlanetarySpec = kit.params
    b = ModelBuilder()
    plays = running_fits(b, kit, result)
    a = s.centre_distance
    # the sun pulled outward by each planet, each planet outward by the sun and inward by the ring:
    # their directions cancel (κ = 0); the carrier is not in a mesh
    kappa_planet = seat_factor([(1.0, 0.0), (-1.0, 0.0)]) if seated else 0.0
    kappa_sun = seat_factor([(math.cos(t), math.sin(t)) for t in s.angles]) if seated else 0.0
    sun_axis = [(feature_xy("frame_bottom", "input hole"), 1.0)]  # the ring is the bottom plate's reference
    carrier_axis = [(feature_xy("frame_top", "output hole"), 1.0), (feature_xy("frame_top", "register"), 1.0)]
    rows = {tuple(r["pair"]): r for r in result.figures.get("meshes", [])}
    j_pr, aw_r = internal_backlash(s.planet, s.space, a)
    internal = result.figures.get("internal_mesh", {}).get("tip_root_mm", {})
    alpha = s.system.pressure_angle
    meshing = set()
    for i, t0 in enumerate(s.angles):
        planet = f"planet{i}"
        meshing |= {frozenset(("sun", planet)), frozenset((planet, "frame_bottom"))}
        pin = feature_xy("carrier", f"pin{i}")
        row = rows.get(("sun", planet))
        p_play = plays.get(planet)
        for k in range(CARRIER_ANGLES):
            c = 2 * math.pi * k / CARRIER_ANGLES
            u_local = np.array([math.cos(t0), math.sin(t0)])  # the planet's radial direction on the carrier
            u = _rot(c) @ u_local  # and in the world at carrier angle c
            tag = f" @{round(math.degrees(c))}°"
            da: dict = {}  # the planet's centre from the ring's (and the sun's) centre, along u
            project(da, pin, u_local)
            project_axis(da, carrier_axis, u)
            d_sun = dict(da)
            project_axis(d_sun, sun_axis, u, -1.0)
            if row is not None:
                plays_sp = [(kappa_planet, p_play)] if p_play is not None else []
                if plays.get("shaft_in") is not None:
                    plays_sp.append((kappa_sun, plays["shaft_in"]))
                external_mesh(b, f"sun/{planet}", planet, row, s.sun, s.planet, ("sun", planet), d_sun,
                          seat_credit(plays_sp), tag)
            # planet in the ring: a larger centre distance takes the planet deeper (signs turn over)
            credit, cterms = seat_credit([(kappa_planet, p_play)] if p_play is not None else [])
            pos = {key: -v for key, v in da.items()}
            for key, v in cterms.items():
                add_term(pos, key, v)
            terms = {key: 2 * math.tan(aw_r) * v for key, v in pos.items()}
            add_term(terms, tooth(planet), -1.0 / math.cos(aw_r))
            add_term(terms, tooth("frame_bottom"), -1.0 / math.cos(aw_r))
            unit = f"{planet}/ring"
            b.add(Margin(unit, "mesh", f"backlash{tag}", j_pr + 2 * math.tan(aw_r) * credit, "frame",
                         2 * math.cos(alpha) / math.cos(aw_r)), terms)
            for key, value in internal.items():
                tt = dict(pos)
                add_term(tt, tooth(planet), -0.5)
                add_term(tt, tooth("frame_bottom"), -0.5)
                b.add(Margin(unit, "mesh", f"tip-root {key.replace('->', '→')}{tag}", float(value) + credit,
                             "frame"), tt)
        # assembly with printed teeth: the pin's tangential error turns the planet on the ring and
        # moves its sun-side flank by twice it; both meshes' backlash must take it
        if row is not None:
            tangent = np.array([-math.sin(t0), math.cos(t0)])
            aw_s = math.acos(min(1.0, (s.sun.pitch_radius + s.planet.pitch_radius) * math.cos(alpha) / a))
            both = float(row["backlash_mm"]) + j_pr
            for sign in (1.0, -1.0):
                terms = {}
                project(terms, pin, tangent, -2.0 * sign)
                add_term(terms, tooth("sun"), -1.0 / math.cos(aw_s))
                add_term(terms, tooth(planet), -1.0 / math.cos(aw_s) - 1.0 / math.cos(aw_r))
                add_term(terms, tooth("frame_bottom"), -1.0 / math.cos(aw_r))
                b.add(Margin(f"{planet} assembly", "mesh", f"phase {'+' if sign > 0 else '−'}", both, "carrier",
                             2 * math.cos(alpha) / math.cos(aw_s) + 2 * math.cos(alpha) / math.cos(aw_r)), terms)

    def axis_of(name: str):
        if name in ("sun", "shaft_in"):
            return np.zeros(2), sun_axis
        if name in ("carrier", "shaft_out"):
            return np.zeros(2), carrier_axis
        return None
    gap_margins(b, kit, result, meshing, axis_of)
    return b.model(accuracy_mm, kit.name, "planets and sun get no play (their meshes push both ways); the carrier and shafts centred" if seated else "every gear and shaft centred in its bores (no play credited)")
