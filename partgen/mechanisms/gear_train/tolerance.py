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
from .planetary.kit import PlanetaryKit
from .planetary.tolerance import tolerance_model as _planetary_model
from .rack.kit import RackKit
from .rack.tolerance import tolerance_model as _rack_model

__all__ = ["tolerance_model", "internal_backlash", "CARRIER_ANGLES"]

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


# ---------------------------------------------------------------------------------------------- rack


def tolerance_model(kit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) for a printer accuracy of ± ``accuracy_mm``
    (``seated``: bodies where their meshes push them in their bores; otherwise centred)."""
    if isinstance(kit, PlanetaryKit):
        return _planetary_model(kit, result, accuracy_mm, seated)
    if isinstance(kit, RackKit):
        return _rack_model(kit, result, accuracy_mm, seated)
    return _train(kit, result, accuracy_mm, seated)
