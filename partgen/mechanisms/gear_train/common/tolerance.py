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

Here: what the three sub-slices' models share (the running fits, the axes, the external meshes, the
clearances); each sub-slice's ``tolerance.py`` puts its own model together from them.
"""

from __future__ import annotations

import math

import numpy as np

from ....core.findings import Result
from ....design.tolerance import Margin, ModelBuilder, Play

__all__ = ["BOUGHT", "feature_xy", "add_term", "project", "axis_features", "project_axis", "short_name", "tooth",
           "running_fits", "external_mesh", "gap_margins"]

BOUGHT = ("nut", "set screw", "threaded rod")


def feature_xy(part: str, feature: str) -> tuple[tuple[str, str, str], tuple[str, str, str]]:
    return ((f"{part} {feature} x", "position", part), (f"{part} {feature} y", "position", part))


def add_term(terms: dict, key, c: float) -> None:
    if c:
        terms[key] = terms.get(key, 0.0) + float(c)


def project(terms: dict, feature: tuple, vec, sign: float = 1.0) -> None:
    """Add sign · (vec · Δ of the (x, y) position ``feature``) to ``terms``."""
    fx, fy = feature
    add_term(terms, fx, sign * float(vec[0]))
    add_term(terms, fy, sign * float(vec[1]))


def axis_features(name: str, both_plates: bool = True) -> list[tuple[tuple, float]]:
    """The position features an axis's displacement at the gears is made of, with their weights:
    the mean of its holes in the bottom and the top plate (the top one carried by the plate's
    register on the bottom), or the bottom plate's hole alone."""
    if not both_plates:
        return [(feature_xy("frame_bottom", f"{name} hole"), 1.0)]
    return [(feature_xy("frame_bottom", f"{name} hole"), 0.5), (feature_xy("frame_top", f"{name} hole"), 0.5),
            (feature_xy("frame_top", "register"), 0.5)]


def project_axis(terms: dict, axis, vec, sign: float = 1.0) -> None:
    for feature, w in axis:
        project(terms, feature, vec, sign * w)


def short_name(part: str) -> str:
    """A part's name as the study's "at" column shows it (the two frame plates: "frame")."""
    return "frame" if part.startswith("frame_") else part


def tooth(part: str) -> tuple[str, str, str]:
    return (f"{part} teeth", "tooth", part)


def running_fits(b: ModelBuilder, kit, result: Result) -> dict[str, Play]:
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
        b.add(Margin(f"{c.a} on {c.b}", "joint", "radial gap", nominal, short_name(hole.name)), terms)
        mover = c.a  # what moves in the bore: a contact names it first (a gear on its pin, a shaft in a plate)
        if mover not in plays or nominal < plays[mover].nominal:
            plays[mover] = Play(nominal, terms)
    return plays


def external_mesh(b: ModelBuilder, unit: str, where: str, row: dict, ga, gb, parts: tuple[str, str], da: dict,
              credit: tuple[float, dict], tag: str = "") -> None:
    """An external mesh's margins (backlash and the two tip-root clearances) from the check's ``row``."""
    a_op = float(row["centre_distance_mm"])
    alpha = ga.system.pressure_angle
    aw = math.acos(min(1.0, (ga.pitch_radius + gb.pitch_radius) * math.cos(alpha) / a_op))
    nominal, cterms = credit
    pos = dict(da)
    for k, v in cterms.items():
        add_term(pos, k, v)
    terms = {k: 2 * math.tan(aw) * v for k, v in pos.items()}
    for p in parts:
        add_term(terms, tooth(p), -1.0 / math.cos(aw))
    b.add(Margin(unit, "mesh", f"backlash{tag}", float(row["backlash_mm"]) + 2 * math.tan(aw) * nominal, short_name(where),
                 2 * math.cos(alpha) / math.cos(aw)), terms)
    for key, value in row["tip_clearance_mm"].items():
        t = dict(pos)
        for p in parts:
            add_term(t, tooth(p), -0.5)
        b.add(Margin(unit, "mesh", f"tip-root {key.replace('->', '→')}{tag}", float(value) + nominal, short_name(where)), t)


def gap_margins(b: ModelBuilder, kit, result: Result, meshing: set, axis_of) -> None:
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
            b.add(Margin(unit, "clearance", "axial gap", float(g["mm"]), short_name(pb)), terms)
            continue
        terms = {}
        for name in (pa, pb):
            if parts[name].printed:
                add_term(terms, tooth(name) if parts[name].role in ("gear", "rack") else (f"{name} outline", "outline", name),
                     -0.5)
        ax_a, ax_b = axis_of(pa), axis_of(pb)
        if ax_a is not None and ax_b is not None:
            ca, cb = ax_a[0], ax_b[0]
            d = np.asarray(cb, float) - np.asarray(ca, float)
            if np.linalg.norm(d) > 1e-9:
                u = d / np.linalg.norm(d)
                project_axis(terms, ax_b[1], u)
                project_axis(terms, ax_a[1], u, -1.0)
        b.add(Margin(unit, "clearance", "gap", float(g["mm"]), short_name(pb)), terms)
