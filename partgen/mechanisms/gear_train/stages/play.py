"""What play costs in a gear train of stages (spur, helical, herringbone; docs/tolerance.md, "What play
costs"): the lost motion at the output shaft in arc-minutes (the input held, how far the output turns
freely), from each mesh's backlash and each body's radial play in its bore; its worst case and 95 %
figure over prints and the transmission-error band (``common/play.py``).

The model (first order in small displacements, in the transverse plane; every body — a gear on its
fixed pin, a shaft with its gears in the plates — turns about an axis parallel to its bore's and its
centre may sit anywhere in a disk of radius c, its radial play; the teeth are involutes, so a flank's
contacts lie on its line of action, tangent to both base circles at the operating pressure angle α_w):

* **One mesh, the bodies at their axes.** The driven gear (operating pitch radius r_w, base radius
  r_b = r_w cos α_w) turns freely through its circumferential backlash ``j`` over ``r_w``; referred to
  the output through the shafts' speeds (``|ω_out / ω_driven|``).
* **The bodies moved.** Moving a gear by e moves each of its flanks along that flank's normal by e · n
  — a flank's normal lies along its line of action, at α_w to the mesh's tangent t, leaning (sin α_w)
  along the line of centres u. With u from the driver to the driven gear and e the driven gear's
  displacement less the driver's, the driven gear's forward limit (the flank its forward turn closes)
  opens by ``e · ν_f``, ``ν_f = sin α_w u + σ cos α_w t`` (σ the sign of its speed, t = ẑ × u), its
  backward limit by ``e · ν_b``, ``ν_b = sin α_w u − σ cos α_w t``; each mm along a flank's normal is
  ``1/r_b`` of the driven gear's turn. (Along the line of centres alone, both open by sin α_w each:
  the backlash's ``2 tan α_w`` per mm times r_b/r_w; across it, one flank opens as the other closes:
  the range moves, no wider, but a body free in its bore can be at one side for the forward limit and
  at the other for the backward limit.)
* **The range.** With the input held, the output's forward limit is ``Σ_m G_m (g_f,m + e_m · ν_f,m)``
  (``G_m = |ω_out / ω_driven| / r_b``: the meshes in series add), the backward one likewise with ν_b;
  each is linear in the bodies' displacements d_k, ``Σ_k d_k · w_k``, and is largest with each body at
  ``c_k w_k / |w_k|``. The bores' share is therefore ``Σ_k c_k (|w_f,k| + |w_b,k|)``, ``w_k`` the sum over
  body k's meshes of ``± G_m ν_m`` (+ where it is driven, − where it drives). A body in one mesh (the
  input, the output, a single gear): ``2 c / r_b = 2 c / (r_w cos α_w)`` of the driven gear's
  turn — ``1/sin α_w`` (≈ 3×) the play along the line of centres alone; a compound gear or an idler in
  two meshes: the vector sum, between the difference and the sum of its two meshes' parts. The
  exact check (``tests/mechanisms/gear_train/test_stages_play.py``): the printed outlines turned until
  they touch with every body where the model puts it (``motion.turn_train(shifts=)``), and at other
  places in the bores (never further).
* **A print**: each mesh's backlash less its two gears' outline deviations over cos α_w, plus
  ``2 tan α_w`` times its axes' displacement along the line of centres (each axis the mean of its holes
  in the two plates, the top one carried by its register, ``common/tolerance.py``); each body's play ±
  half its bore's and its pin's (or shaft's) deviation (``running_fits``: a shaft in two plates keeps
  the tighter bore).

Not modelled: a body tilting in its bore (its axis no longer parallel: a compound gear's two gears
could then sit apart, up to the sum of their meshes' parts; a gear resting on its plate over its face
and the frame's axial gap keep it small); a single-helical gear's axial float (turning its section by
``f tan β / r``; a herringbone's two halves cancel it); the teeth's bending.
"""

from __future__ import annotations

import math

import numpy as np

from ....core.findings import Result
from ....design import involute
from ....design.tolerance import ModelBuilder, Play
from ..common.play import ARCMIN, Share, lost_motion as cost
from ..common.tolerance import axis_features, project_axis, running_fits, tooth

__all__ = ["mesh_terms", "body_reach", "worst_shifts", "shares", "lost_motion"]


def mesh_terms(spec) -> list[dict]:
    """Per mesh (the train's order): its shafts ``i`` (driver) and ``j`` (driven), the unit line of
    centres ``u`` (driver to driven) and tangent ``t`` (ẑ × u), the operating pressure angle ``alpha_w``
    (rad), the driven gear's operating pitch and base radii (mm), the circumferential backlash ``j_mm``
    at the built centre distance, ``refer`` = |ω_out / ω_driven| and the unit normals ``nu_f`` and ``nu_b``
    along which the driven gear's displacement relative to its driver's opens its forward and its
    backward limit."""
    out_speed = float(spec.shafts[-1].speed)
    rows = []
    for mesh in spec.meshes:
        gd, gn = spec.gear(mesh.driver), spec.gear(mesh.driven)
        i, j = gd.shaft, gn.shaft
        ci, cj = np.asarray(spec.shafts[i].centre, float), np.asarray(spec.shafts[j].centre, float)
        u = (cj - ci) / np.linalg.norm(cj - ci)
        t = np.array([-u[1], u[0]])
        a, s = mesh.centre_distance, gd.spec.system
        z1, z2 = gd.spec.teeth, gn.spec.teeth
        lash = involute.circumferential_backlash(z1, z2, s.module, s.pressure_angle, gd.spec.profile_shift,
                                                 gn.spec.profile_shift, s.backlash_per_gear, s.backlash_per_gear, a)
        aw = math.acos(min(1.0, (z1 + z2) * s.module / 2 * math.cos(s.pressure_angle) / a))
        rw = a * z2 / (z1 + z2)
        sj = float(spec.shafts[j].speed)
        sigma = math.copysign(1.0, sj)
        rows.append({"mesh": f"{mesh.driver}/{mesh.driven}", "i": i, "j": j, "u": u, "t": t, "alpha_w": aw,
                     "r_w": rw, "r_b": rw * math.cos(aw), "j_mm": lash, "refer": abs(out_speed / sj),
                     "nu_f": math.sin(aw) * u + sigma * math.cos(aw) * t,
                     "nu_b": math.sin(aw) * u - sigma * math.cos(aw) * t})
    return rows


def body_reach(spec) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """Shaft k -> (w_f, w_b): the output's forward and backward limits' change (rad) per mm of body k's
    displacement (x, y): Σ over its meshes of ± refer/r_b · ν (+ where it is driven, − where it drives)."""
    w = {sh.index: (np.zeros(2), np.zeros(2)) for sh in spec.shafts}
    for m in mesh_terms(spec):
        g = m["refer"] / m["r_b"]
        for k, sign in ((m["j"], 1.0), (m["i"], -1.0)):
            w[k][0][:] += sign * g * m["nu_f"]
            w[k][1][:] += sign * g * m["nu_b"]
    return w


def _body_play(plays: dict, k: int) -> tuple[str, Play] | None:
    """Shaft k's body and its play: its gear on a fixed pin, or its shaft (with its gears) in the plates."""
    for name in (f"gears{k}", f"shaft{k}"):
        if name in plays:
            return name, plays[name]
    return None


def worst_shifts(spec, radial_play_mm: float | dict | None = None) -> dict[str, dict[int, tuple[float, float]]]:
    """Where the model puts each body in its bore (mm, by shaft index) for the output's forward limit
    (``"coast"``: the flanks a forward turn closes) and its backward one (``"drive"``): ``c_k w_k / |w_k|``;
    ``radial_play_mm``: every body's play (default: the running fit's, ``running / 2``), or {shaft: mm}."""
    c = spec.running / 2 if radial_play_mm is None else radial_play_mm
    out: dict = {"coast": {}, "drive": {}}
    for k, (wf, wb) in body_reach(spec).items():
        ck = c.get(k, 0.0) if isinstance(c, dict) else c
        for key, w in (("coast", wf), ("drive", wb)):
            n = float(np.linalg.norm(w))
            out[key][k] = tuple(float(x) for x in (ck * w / n if n > 0 else np.zeros(2)))
    return out


def shares(kit) -> list[Share]:
    """The output's lost motion as shares (arc-minutes per mm), from the kit's train and running fits."""
    s = kit.params
    plays = running_fits(ModelBuilder(), kit, Result())
    out = []
    for m in mesh_terms(s):
        i, j, aw = m["i"], m["j"], m["alpha_w"]
        terms: dict = {}
        project_axis(terms, axis_features(f"shaft{j}"), m["u"])
        project_axis(terms, axis_features(f"shaft{i}"), m["u"], -1.0)
        terms = {k: 2 * math.tan(aw) * v for k, v in terms.items()}
        for part in (f"gears{i}", f"gears{j}"):
            terms[tooth(part)] = terms.get(tooth(part), 0.0) - 1 / math.cos(aw)
        out.append(Share(m["mesh"], m["mesh"], "backlash", m["j_mm"], m["refer"] / m["r_w"] * ARCMIN, terms))
    for k, (wf, wb) in body_reach(s).items():
        got = _body_play(plays, k)
        if got is None:
            continue
        name, p = got
        where = f"{name} on its pin" if name.startswith("gears") else f"{name} in the plates"
        out.append(Share(name, where, "bores", p.nominal, float(np.linalg.norm(wf) + np.linalg.norm(wb)) * ARCMIN,
                         p.terms))
    return out


def _sides(spec, kit) -> tuple[float, float]:
    """The bores' share below and above the output's nominal angle (as the trace measures it: the
    world's sense): its forward part ``Σ c_k |w_f,k|`` above when the output turns positive, below
    otherwise (a compound gear opens the two limits unevenly)."""
    plays = running_fits(ModelBuilder(), kit, Result())
    fwd = back = 0.0
    for k, (wf, wb) in body_reach(spec).items():
        got = _body_play(plays, k)
        if got is not None:
            c = max(got[1].nominal, 0.0)
            fwd += c * float(np.linalg.norm(wf))
            back += c * float(np.linalg.norm(wb))
    if fwd + back <= 0:
        return 0.5, 0.5
    f = fwd / (fwd + back)
    return (1 - f, f) if float(spec.shafts[-1].speed) > 0 else (f, 1 - f)


def lost_motion(spec, kit, te_drive_arcmin: np.ndarray | None = None, te_coast_arcmin: np.ndarray | None = None) -> dict:
    """The output's lost motion (arc-minutes: nominal, worst case, 95 % and median of prints at the
    printer's xy accuracy, a row per mesh and per body) and, with the measured transmission errors
    (arcmin), the band about nominal."""
    out = cost(shares(kit), spec.printer.xy_accuracy, "arcmin", te_drive_arcmin, te_coast_arcmin,
               sides=_sides(spec, kit))
    out["radial_play_mm"] = round(spec.running / 2, 6)
    out["model"] = ("first order: Σ meshes' backlash |ω_out/ω_driven|/r_w + Σ bodies' play c_k (|w_f,k| + |w_b,k|), "
                    "each body anywhere in its bore (a body in one mesh: 2c/(r_w cos α_w) of its driven gear); "
                    "docs/tolerance.md, What play costs")
    return out
