"""The gear train's tolerance model (spur and helical trains, the planetary set, the rack): the margins
of one nominal check as linear functions of the printed features' deviations (``design.tolerance``;
``δ`` a feature's deviation as a diameter, docs/tolerance.md "Gear trains").

* **Running fits** (every ``running`` contact of the kit: a gear on a fixed pin, a shaft turning in
  a plate, a planet on its carrier pin): radial gap measured by the check, + ``δ_hole/2 − δ_pin/2``
  (a bought part — a nut, a screw — does not deviate).
* **Where the axes are.** A shaft stands in the bottom plate's hole and the top plate's: at the
  gears the axis is the mean of the two holes' positions (each hole's x and y, a ``position``
  feature), the top plate carried by its register on the bottom one (x and y: the spacers' press
  fits). A mesh's centre distance changes by the projection of the two axes' displacements on its
  line of centres.
* **Where the gears sit** (``seated``, the chain's and the pair's model: ``design.tolerance``): a
  body is what moves in a running fit — a gear on its fixed pin, a shaft with its gear in its
  plates (the tighter of its two bearings: the axis moves only as far as both let it), a planet on
  its pin, the rack against its rail. A mesh that runs out of backlash pushes its two bodies apart
  along its line of centres; a body gives each mesh ``κ = seat_factor`` of its play (a gear with
  one mesh 1; a compound gear's two meshes in other directions less; a planet between the sun and
  the ring, and the sun among its planets, 0: their meshes push them both ways at once).
  ``seated=False``: every body centred (the worst case).
* **External meshes**: backlash (circumferential, on the operating pitch circle) changes by
  ``2·tan α_w · Δa − (δ_a + δ_b)/cos α_w``; each tip-to-root clearance by ``Δa − δ_a/2 − δ_b/2``.
  **Internal mesh** (planet in the ring): a larger centre distance takes the planet deeper into the
  ring, so the signs of ``Δa`` turn over; the ring's teeth (``frame_bottom teeth``) grow into its
  spaces as a gear's do.
* **The planetary's assembly with printed teeth**: N planets mesh the sun and the ring at once only
  where their pins sit. A pin moved by ``e`` along the planet's path (tangentially) turns the planet
  on the ring and moves its sun-side flank by ``2e``: the sun/planet and planet/ring backlash together
  must take it (``j_sp + j_pr − 2|e| ≥ 0``, two margins; the sun's own turn, which could share out a
  common shift, is not credited: conservative).
* **The rack**: the pinion's axis (its shaft in the base) to the rail's face less the rack's depth
  from its back to its pitch line; the rack pressed back on its rail by a tight mesh takes the
  rail's running gap (its play).
* **Clearances over the motion** (pairs closer than the check's reach that do not mesh): in the plane,
  the gap less the two outlines' growth, plus the axes' displacement along the line between them;
  along z, the upper part's stack height less the lower part's thickness.
"""

from __future__ import annotations

import math

import numpy as np

from ...core.findings import Result
from ...design.involute import inv, reference_tooth_thickness
from ...design.tolerance import Margin, MarginModel, ModelBuilder, Play, seat_credit, seat_factor
from .kit import TrainKit, TrainSpec
from .planetary import PlanetaryKit, PlanetarySpec
from .rack.kit import RackKit
from .rack.tolerance import tolerance_model as _rack_model

__all__ = ["tolerance_model", "internal_backlash", "CARRIER_ANGLES"]

CARRIER_ANGLES = 6  # carrier angles over a turn at which a planet's meshes are taken (the carrier's axis
#                     may be off the sun's in any direction: each angle's projection is a margin)
BOUGHT = ("nut", "set screw", "threaded rod")


def _pos(part: str, feature: str) -> tuple[tuple[str, str, str], tuple[str, str, str]]:
    return ((f"{part} {feature} x", "position", part), (f"{part} {feature} y", "position", part))


def _add(terms: dict, key, c: float) -> None:
    if c:
        terms[key] = terms.get(key, 0.0) + float(c)


def _project(terms: dict, feature: tuple, vec, sign: float = 1.0) -> None:
    """Add sign · (vec · Δ of the (x, y) position ``feature``) to ``terms``."""
    fx, fy = feature
    _add(terms, fx, sign * float(vec[0]))
    _add(terms, fy, sign * float(vec[1]))


def _axis(name: str, both_plates: bool = True) -> list[tuple[tuple, float]]:
    """The position features an axis's displacement at the gears is made of, with their weights:
    the mean of its holes in the bottom and the top plate (the top one carried by the plate's
    register on the bottom), or the bottom plate's hole alone."""
    if not both_plates:
        return [(_pos("frame_bottom", f"{name} hole"), 1.0)]
    return [(_pos("frame_bottom", f"{name} hole"), 0.5), (_pos("frame_top", f"{name} hole"), 0.5),
            (_pos("frame_top", "register"), 0.5)]


def _project_axis(terms: dict, axis, vec, sign: float = 1.0) -> None:
    for feature, w in axis:
        _project(terms, feature, vec, sign * w)


def _short(part: str) -> str:
    """A part's name as the study's "at" column shows it (the two frame plates: "frame")."""
    return "frame" if part.startswith("frame_") else part


def _tooth(part: str) -> tuple[str, str, str]:
    return (f"{part} teeth", "tooth", part)


def _fits(b: ModelBuilder, kit, result: Result) -> dict[str, Play]:
    """Every running fit's margin; the play of each part that runs in a bore (by part name: a shaft
    running in two plates keeps the tighter of the two)."""
    roles = {p.name: p for p in kit.parts}
    measured = {tuple(r["parts"]): r for r in result.figures.get("fits", {}).get("rows", [])}
    plays: dict[str, Play] = {}
    for c in kit.contacts:
        if c.kind != "running":
            continue
        a, bb = roles[c.a], roles[c.b]
        pin, hole = (a, bb) if a.role in ("axle",) + BOUGHT else (bb, a)
        nominal = float(measured.get((c.a, c.b), {}).get("radial_gap_mm", c.radial_gap))
        terms = {}
        if hole.printed:
            terms[(f"{hole.name} hole for {pin.name}", "hole", hole.name)] = 0.5
        if pin.printed:
            terms[(f"{pin.name} diameter", "pin", pin.name)] = -0.5
        b.add(Margin(f"{c.a} on {c.b}", "joint", "radial gap", nominal, _short(hole.name)), terms)
        mover = c.a  # what moves in the bore: a contact names it first (a gear on its pin, a shaft in a plate)
        if mover not in plays or nominal < plays[mover].nominal:
            plays[mover] = Play(nominal, terms)
    return plays


def _external(b: ModelBuilder, unit: str, where: str, row: dict, ga, gb, parts: tuple[str, str], da: dict,
              credit: tuple[float, dict], tag: str = "") -> None:
    """An external mesh's margins (backlash and the two tip-root clearances) from the check's ``row``."""
    a_op = float(row["centre_distance_mm"])
    alpha = ga.system.pressure_angle
    aw = math.acos(min(1.0, (ga.pitch_radius + gb.pitch_radius) * math.cos(alpha) / a_op))
    nominal, cterms = credit
    pos = dict(da)
    for k, v in cterms.items():
        _add(pos, k, v)
    terms = {k: 2 * math.tan(aw) * v for k, v in pos.items()}
    for p in parts:
        _add(terms, _tooth(p), -1.0 / math.cos(aw))
    b.add(Margin(unit, "mesh", f"backlash{tag}", float(row["backlash_mm"]) + 2 * math.tan(aw) * nominal, _short(where),
                 2 * math.cos(alpha) / math.cos(aw)), terms)
    for key, value in row["tip_clearance_mm"].items():
        t = dict(pos)
        for p in parts:
            _add(t, _tooth(p), -0.5)
        b.add(Margin(unit, "mesh", f"tip-root {key.replace('->', '→')}{tag}", float(value) + nominal, _short(where)), t)


def _gaps(b: ModelBuilder, kit, result: Result, meshing: set, axis_of) -> None:
    """The clearances the motion sweep found between parts that do not mesh."""
    parts = {p.name: p for p in kit.parts}
    for g in result.figures.get("motion", {}).get("gaps", []):
        pa, pb = g["parts"]
        if frozenset((pa, pb)) in meshing:
            continue  # the mesh's own margins
        unit = f"{pa}–{pb}"
        if g["axis"] == "z":
            terms = {}
            if parts[pb].printed:
                terms[(f"{pb} stack height", "height", pb)] = 1.0
            if parts[pa].printed:
                terms[(f"{pa} thickness", "height", pa)] = -1.0
            b.add(Margin(unit, "clearance", "axial gap", float(g["mm"]), _short(pb)), terms)
            continue
        terms = {}
        for name in (pa, pb):
            if parts[name].printed:
                _add(terms, _tooth(name) if parts[name].role in ("gear", "rack") else (f"{name} outline", "outline", name),
                     -0.5)
        ax_a, ax_b = axis_of(pa), axis_of(pb)
        if ax_a is not None and ax_b is not None:
            ca, cb = ax_a[0], ax_b[0]
            d = np.asarray(cb, float) - np.asarray(ca, float)
            if np.linalg.norm(d) > 1e-9:
                u = d / np.linalg.norm(d)
                _project_axis(terms, ax_b[1], u)
                _project_axis(terms, ax_a[1], u, -1.0)
        b.add(Margin(unit, "clearance", "gap", float(g["mm"]), _short(pb)), terms)


# --------------------------------------------------------------------------------------------- trains
def _train(kit: TrainKit, result: Result, accuracy_mm: float, seated: bool) -> MarginModel:
    s: TrainSpec = kit.params
    b = ModelBuilder()
    plays = _fits(b, kit, result)

    def body_play(k: int) -> Play | None:
        """The play of shaft k's gear part: its gear on a fixed pin, or its shaft in the plates."""
        return plays.get(f"gears{k}") or plays.get(f"shaft{k}")
    centre = {sh.index: np.asarray(sh.centre, dtype=float) for sh in s.shafts}
    rows = {tuple(r["pair"]): r for r in result.figures.get("meshes", [])}
    dirs: dict[int, list] = {}
    for m in s.meshes:
        i, j = s.gear(m.driver).shaft, s.gear(m.driven).shaft
        u = (centre[j] - centre[i]) / np.linalg.norm(centre[j] - centre[i])
        dirs.setdefault(i, []).append(-u)
        dirs.setdefault(j, []).append(u)
    kappa = {k: seat_factor(v) for k, v in dirs.items()} if seated else {}
    meshing = set()
    for m in s.meshes:
        row = rows.get((m.driver, m.driven))
        if row is None:
            continue
        i, j = s.gear(m.driver).shaft, s.gear(m.driven).shaft
        meshing.add(frozenset((f"gears{i}", f"gears{j}")))
        u = (centre[j] - centre[i]) / np.linalg.norm(centre[j] - centre[i])
        da: dict = {}
        _project_axis(da, _axis(f"shaft{j}"), u)
        _project_axis(da, _axis(f"shaft{i}"), u, -1.0)
        credit = seat_credit([(kappa.get(k, 0.0), body_play(k)) for k in (i, j) if body_play(k) is not None])
        _external(b, f"{m.driver}/{m.driven}", f"gears{j}", row, s.gear(m.driver).spec, s.gear(m.driven).spec,
                  (f"gears{i}", f"gears{j}"), da, credit)

    def axis_of(name: str):
        for prefix in ("gears", "shaft"):
            if name.startswith(prefix) and name[len(prefix):].isdigit():
                k = int(name[len(prefix):])
                return centre[k], _axis(f"shaft{k}")
        return None
    _gaps(b, kit, result, meshing, axis_of)
    return b.model(accuracy_mm, kit.name, "gears and shafts seated by their meshes in their bores" if seated else "every gear and shaft centred in its bores (no play credited)")


# ----------------------------------------------------------------------------------------- planetary
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


def _planetary(kit: PlanetaryKit, result: Result, accuracy_mm: float, seated: bool) -> MarginModel:
    s: PlanetarySpec = kit.params
    b = ModelBuilder()
    plays = _fits(b, kit, result)
    N = len(s.angles)
    a = s.centre_distance
    # the sun pulled outward by each planet, each planet outward by the sun and inward by the ring:
    # their directions cancel (κ = 0); the carrier is not in a mesh
    kappa_planet = seat_factor([(1.0, 0.0), (-1.0, 0.0)]) if seated else 0.0
    kappa_sun = seat_factor([(math.cos(t), math.sin(t)) for t in s.angles]) if seated else 0.0
    sun_axis = [(_pos("frame_bottom", "input hole"), 1.0)]  # the ring is the bottom plate's reference
    carrier_axis = [(_pos("frame_top", "output hole"), 1.0), (_pos("frame_top", "register"), 1.0)]
    rows = {tuple(r["pair"]): r for r in result.figures.get("meshes", [])}
    j_pr, aw_r = internal_backlash(s.planet, s.space, a)
    internal = result.figures.get("internal_mesh", {}).get("tip_root_mm", {})
    alpha = s.system.pressure_angle
    meshing = set()
    for i, t0 in enumerate(s.angles):
        planet = f"planet{i}"
        meshing |= {frozenset(("sun", planet)), frozenset((planet, "frame_bottom"))}
        pin = _pos("carrier", f"pin{i}")
        row = rows.get(("sun", planet))
        p_play = plays.get(planet)
        for k in range(CARRIER_ANGLES):
            c = 2 * math.pi * k / CARRIER_ANGLES
            u_local = np.array([math.cos(t0), math.sin(t0)])  # the planet's radial direction on the carrier
            u = _rot(c) @ u_local  # and in the world at carrier angle c
            tag = f" @{round(math.degrees(c))}°"
            da: dict = {}  # the planet's centre from the ring's (and the sun's) centre, along u
            _project(da, pin, u_local)
            _project_axis(da, carrier_axis, u)
            d_sun = dict(da)
            _project_axis(d_sun, sun_axis, u, -1.0)
            if row is not None:
                plays_sp = [(kappa_planet, p_play)] if p_play is not None else []
                if plays.get("shaft_in") is not None:
                    plays_sp.append((kappa_sun, plays["shaft_in"]))
                _external(b, f"sun/{planet}", planet, row, s.sun, s.planet, ("sun", planet), d_sun,
                          seat_credit(plays_sp), tag)
            # planet in the ring: a larger centre distance takes the planet deeper (signs turn over)
            credit, cterms = seat_credit([(kappa_planet, p_play)] if p_play is not None else [])
            pos = {key: -v for key, v in da.items()}
            for key, v in cterms.items():
                _add(pos, key, v)
            terms = {key: 2 * math.tan(aw_r) * v for key, v in pos.items()}
            _add(terms, _tooth(planet), -1.0 / math.cos(aw_r))
            _add(terms, _tooth("frame_bottom"), -1.0 / math.cos(aw_r))
            unit = f"{planet}/ring"
            b.add(Margin(unit, "mesh", f"backlash{tag}", j_pr + 2 * math.tan(aw_r) * credit, "frame",
                         2 * math.cos(alpha) / math.cos(aw_r)), terms)
            for key, value in internal.items():
                tt = dict(pos)
                _add(tt, _tooth(planet), -0.5)
                _add(tt, _tooth("frame_bottom"), -0.5)
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
                _project(terms, pin, tangent, -2.0 * sign)
                _add(terms, _tooth("sun"), -1.0 / math.cos(aw_s))
                _add(terms, _tooth(planet), -1.0 / math.cos(aw_s) - 1.0 / math.cos(aw_r))
                _add(terms, _tooth("frame_bottom"), -1.0 / math.cos(aw_r))
                b.add(Margin(f"{planet} assembly", "mesh", f"phase {'+' if sign > 0 else '−'}", both, "carrier",
                             2 * math.cos(alpha) / math.cos(aw_s) + 2 * math.cos(alpha) / math.cos(aw_r)), terms)

    def axis_of(name: str):
        if name in ("sun", "shaft_in"):
            return np.zeros(2), sun_axis
        if name in ("carrier", "shaft_out"):
            return np.zeros(2), carrier_axis
        return None
    _gaps(b, kit, result, meshing, axis_of)
    return b.model(accuracy_mm, kit.name, "planets and sun get no play (their meshes push both ways); the carrier and shafts centred" if seated else "every gear and shaft centred in its bores (no play credited)")


# ---------------------------------------------------------------------------------------------- rack


def tolerance_model(kit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) for a printer accuracy of ± ``accuracy_mm``
    (``seated``: bodies where their meshes push them in their bores; otherwise centred)."""
    if isinstance(kit, PlanetaryKit):
        return _planetary(kit, result, accuracy_mm, seated)
    if isinstance(kit, RackKit):
        return _rack_model(kit, result, accuracy_mm, seated)
    return _train(kit, result, accuracy_mm, seated)
