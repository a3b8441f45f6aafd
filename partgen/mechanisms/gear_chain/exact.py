"""The gear chain's exact Monte Carlo: one perturbed print of the real mesh geometry per task.

Scope: the meshes, where the chain's linear model says it jams (tooth outlines and the positions of
the pivots on each plate). A print draws every feature of the linear model (``tolerance.py``) with
its σ (and the position coordinates a mesh's centre distance depends on that the model leaves out
because their first-order coefficient is 0: drawn with the position σ), then:

* **Meshes, exactly** (shapely, on the kit's own gear outlines). Each gear's outline is offset by
  half its tooth deviation (tip, root and flanks move out). A mesh's centre distance is a distance
  between two features of one plate (the drive pair: of the base); the printed one is the length of
  the nominal vector plus the two features' (x, y) deviations (not its projection); ``seated``
  (docs/tolerance.md) adds ``Σ κ_body · play_body`` over the mesh's floating bodies, with the same
  κ as the linear model (the least over the crank's turn) and the printed play (nominal + half the
  bore's deviation − half the pin's, taken ≥ 0). The mesh's frame is fixed to its carrier plate, so
  its centre distance does not change with the crank: the tooth phases the crank turn brings are
  those of one tooth pitch of the first gear, taken from the nominal assembly (crank angle 0) and
  advanced conjugately. At ``ANGLES`` positions of the first gear over that pitch the second must
  have an angle within ± 0.45 of its pitch at which the outlines do not overlap (the gear pair's
  golden-section search, ``checks.free_angle``). Tip-to-root interference shows as overlap too.
* **Running fits and clearances, by the linear margins** (the same draws): a fit's radial gap is
  ``(hole − pin)/2`` + half the hole's deviation − half the pin's, a circle-in-circle gap that is
  exact, not linearised; the clearances between passing parts (and Eq 12's tip circles) are gaps
  between circles and outlines moved along the line between them, which is how the linear model
  already takes them. A print whose mesh has no exact model (a belt stage) keeps its linear margins.

A print jams when any of these fails; ``why`` says which came first (fits, then clearances, then
meshes in the kit's order).
"""

from __future__ import annotations

import math
import time

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import Polygon, box

from ...design.tolerance import sigma_of
from ...geometry.gear import gear_outline
from ...checks.free_angle import free_angle as _free
from .tolerance import _Chain, _mesh_bodies, _mesh_terms, _pin_of, seat_factors

__all__ = ["ANGLES", "exact_shared", "exact_print"]

ANGLES = 12  # positions of the first gear of a mesh over one of its tooth pitches


def _centre_features(chain: _Chain, a: str, b: str):
    """(nominal centre vector in the carrier's frame, [(part feature, sign)]) of a mesh, or None."""
    names = {name[0]: name for name in (a, b)}
    if {a, b} == {"G1", "drive"}:
        return np.asarray(chain.kit.mechanism.drive_centre, dtype=float), [("base drive bearing", 1.0),
                                                                            ("base ground post", -1.0)]
    m = names.get("M")
    if m is None:
        return None
    j = int(m[1:])
    c = chain.idler[j]
    if "D" in names:
        return c, [(f"B{j} idler pin", 1.0), (f"B{j} proximal hole", -1.0)]
    if "G" in names:
        return np.array([chain.length[j], 0.0]) - c, [(f"B{j} distal post", 1.0), (f"B{j} idler pin", -1.0)]
    return None


def exact_shared(kit, result, model, seated: bool = True, angles: int = ANGLES) -> dict:
    """What every print task needs (picklable: outlines as WKB, numbers)."""
    chain = _Chain(kit)
    parts = {p.name: p for p in kit.parts}
    feats = [f.name for f in model.features]
    # every floating body's printed play: nominal + terms (feature -> mm per mm)
    fits = {tuple(r["parts"]): r for r in result.figures.get("fits", {}).get("rows", [])}
    plays = {}
    for c in kit.contacts:
        if c.kind != "running":
            continue
        hole, hf, pin, pf = _pin_of(c)
        nominal = fits.get((c.a, c.b), {}).get("radial_gap_mm", c.radial_gap)
        plays["drive" if c.a == "drive_axle" else c.a] = (float(nominal), {f"{hole} {hf}": 0.5, f"{pin} {pf}": -0.5})
    rows = result.figures.get("meshes", [])
    kappa = seat_factors(kit, [tuple(r["pair"]) for r in rows]) if seated else {}
    P = kit.poses(0.0)
    meshes, exact_units, extra = [], set(), []
    for row in rows:
        a, b = row["pair"]
        cf = _centre_features(chain, a, b)
        if cf is None or _mesh_terms(chain, a, b) is None:
            continue
        vec, pos = cf
        for name, _ in pos:
            for axis in ("x", "y"):
                if f"{name} {axis}" not in feats and f"{name} {axis}" not in extra:
                    extra.append(f"{name} {axis}")
        credit = [(float(kappa.get(body, 0.0)), plays[body]) for body, _ in (_mesh_bodies(chain, a, b, 0.0) or [])
                  if body in plays and kappa.get(body, 0.0) > 0.0]
        ga, gb = parts[a].gear, parts[b].gear
        rel = np.linalg.inv(P[a]) @ P[b]
        line = math.atan2(rel[1, 3], rel[0, 3])
        pa = affinity.rotate(Polygon(gear_outline(ga).points), -line, origin=(0, 0), use_radians=True)
        pb = affinity.rotate(Polygon(gear_outline(gb).points), math.atan2(rel[1, 0], rel[0, 0]) - line, origin=(0, 0),
                             use_radians=True)
        meshes.append({"pair": (a, b), "a": float(row["centre_distance_mm"]), "vec": vec.tolist(), "pos": pos,
                       "credit": credit, "za": ga.teeth, "zb": gb.teeth, "module": ga.system.module,
                       "tip_b": float(gb.tip_radius), "pa": shapely.to_wkb(pa), "pb": shapely.to_wkb(pb)})
        exact_units.add(f"{a}/{b}")
    keep = [k for k, m in enumerate(model.margins) if not (m.group == "mesh" and m.unit in exact_units)]
    return {"features": feats, "sigma": model.sigma.tolist(), "extra": extra,
            "pos_sigma": sigma_of("position", model.accuracy_mm),
            "coeff": model.coeff[:, keep], "nominal": model.nominal[keep],
            "groups": [model.margins[k].group for k in keep], "units": [model.margins[k].unit for k in keep],
            "meshes": meshes, "seated": bool(seated), "angles": int(angles)}


WHY = {"joint": "a bore grips its pin", "clearance": "parts collide", "mesh": "the teeth bind",
       "balance": "out of balance"}


def _mesh_jams(mesh: dict, d: dict, angles: int) -> bool:
    """Whether the printed mesh (deviations ``d``) binds somewhere over one tooth pitch of its first gear."""
    v = np.asarray(mesh["vec"]) + sum(sign * np.array([d[f"{n} x"], d[f"{n} y"]]) for n, sign in mesh["pos"])
    a = mesh["a"] + float(np.linalg.norm(v)) - float(np.linalg.norm(mesh["vec"]))
    for k, (nominal, terms) in mesh["credit"]:
        a += k * max(0.0, nominal + sum(c * d.get(f, 0.0) for f, c in terms.items()))
    A, B = mesh["pair"]
    pa = shapely.from_wkb(mesh["pa"]).buffer(0.5 * d.get(f"{A} teeth", 0.0), quad_segs=4)
    pb = shapely.from_wkb(mesh["pb"]).buffer(0.5 * d.get(f"{B} teeth", 0.0), quad_segs=4)
    za, zb, m = mesh["za"], mesh["zb"], mesh["module"]
    reach = 0.45 * 2 * math.pi / zb
    # gear b turns by at most a pitch (the conjugate advance) + the search's reach: only its teeth
    # facing gear a can enter the window
    h = 3 * m + mesh["tip_b"] * (1.5 * 2 * math.pi / zb) + 1.0
    pb = shapely.intersection(pb, box(-mesh["tip_b"] - 1.0, -h, -mesh["tip_b"] + 4 * m, h))
    ra = a * za / (za + zb)
    window = box(ra - 3 * m, -3 * m, ra + 3 * m, 3 * m)
    for t in np.linspace(0.0, 2 * math.pi / za, angles, endpoint=False):
        g1 = shapely.intersection(affinity.rotate(pa, float(t), origin=(0, 0), use_radians=True), window)
        shapely.prepare(g1)
        if not _free(g1, pb, a, -float(t) * za / zb, reach):
            return True
    return False


def exact_print(shared: dict, seed: int, index: int) -> dict:
    """Print ``index`` of the study with ``seed`` (its generator ``SeedSequence(seed, spawn_key=(1, index))``):
    {"index", "jam", "why", "seconds"}."""
    t0 = time.perf_counter()
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(1, index)))
    z = rng.standard_normal(len(shared["features"])) * np.asarray(shared["sigma"])
    d = dict(zip(shared["features"], z.tolist()))
    d.update(zip(shared["extra"], (rng.standard_normal(len(shared["extra"])) * shared["pos_sigma"]).tolist()))
    margins = shared["nominal"] + z @ shared["coeff"]
    why = None
    for group in ("joint", "clearance", "mesh", "balance"):
        bad = [u for u, g, mm in zip(shared["units"], shared["groups"], margins) if g == group and mm < 0.0]
        if bad:
            why = WHY[group]
            break
    if why is None:
        for mesh in shared["meshes"]:
            if _mesh_jams(mesh, d, shared["angles"]):
                why = "the teeth bind"
                break
    return {"index": index, "jam": why is not None, "why": why, "seconds": time.perf_counter() - t0}
