"""Checks of the balanced Bennett butterfly kit: the common centre of mass stays at S over a grid of
the two inputs (solid and as-printed mass models, an infill error, what-if heavier links), the
parts keep clear of each other over the workspace, the counterweight pockets hold their fill, and
every part fits the printer.

Interference sampling: link–link clearance depends only on the shape angle (q1 turns the linkage
rigidly about S's axis and the base is round about it). The step is chosen so that no point of any
part moves more than a bar's radius between samples (``assembly.bennett_layout.shape_samples``; the
speed bound is each link's reference-joint speed plus its angular speed times its reach, from the
parts themselves): two parts then close in on each other by at most a bar's diameter — the
thinnest feature — between samples, so one cannot pass through another unseen, and a sampled
clearance c guarantees at least c − (bar diameter) in between.
"""

from __future__ import annotations

import math

import numpy as np

from ..assembly import bennett as A
from ..design import bennett_butterfly as bbf
from ..geometry.measure import intersection, oversize
from .findings import Finding, Result

__all__ = ["check_bennett", "balance_figures"]


def _name(i: int) -> str:
    return "base" if i == A.BASE else f"link{i:02d}"


def balance_figures(kit: A.BennettKit) -> dict:
    """Worst distance (mm) of the common centre of mass from S over the grid, per model."""
    p = kit.params
    q1, q4 = A.grid(p)
    scale = dict(p.mass_scale)
    dev = {
        "solid": A.com_deviation(kit, "solid", q1, q4),
        "fdm": A.com_deviation(kit, "fdm", q1, q4),
        "fdm_infill_error": A.com_deviation(kit, "fdm", q1, q4, infill=min(1.0, p.infill + p.infill_error)),
        "solid_weights_printed_fdm": A.com_deviation(kit, "fdm", q1, q4, fill=kit.fill["solid"]),
    }
    if scale:
        dev["what_if_mass_scale"] = A.com_deviation(kit, "fdm", q1, q4, scale=scale)
    out = {k: float(v.max()) for k, v in dev.items()}
    out["grid"] = list(p.grid)
    out["trace"] = {k: v.reshape(p.grid).max(axis=0).tolist() for k, v in dev.items()}
    return out


def check_bennett(kit: A.BennettKit, progress=None) -> Result:
    say = progress or (lambda s: None)
    p, res = kit.params, Result()
    say("balance")
    bal = balance_figures(kit)
    res.figures["balance_mm"] = {k: v for k, v in bal.items() if k not in ("trace",)}
    res.figures["balance_trace_mm"] = bal["trace"]
    worst_key = "what_if_mass_scale" if "what_if_mass_scale" in bal else "fdm"
    worst = bal[worst_key]
    res.add(Finding("balance", "fail" if worst > p.tolerance else "info",
                    f"common centre of mass within {worst:.4f} mm of S over the {p.grid[0]}×{p.grid[1]} grid "
                    f"({'with ' + str(dict(p.mass_scale)) + ' heavier links' if worst_key != 'fdm' else 'as printed'}; "
                    f"tolerance {p.tolerance} mm)", value=worst, unit="mm"))
    res.add(Finding("balance", "info", f"a {100 * p.infill_error:g}-point infill error would move it up to "
                    f"{bal['fdm_infill_error']:.3f} mm; counterweights sized for solid parts would leave "
                    f"{bal['solid_weights_printed_fdm']:.3f} mm", value=bal["fdm_infill_error"], unit="mm"))
    for i, f in kit.fill["fdm"].items():
        need = f / p.fill_density
        have = kit.cups[i].pocket_volume
        res.add(Finding("counterweight", "fail" if need > have else "info",
                        f"{_name(i)}: {f:.2f} g of {p.fill_name} needs {need / 1000:.2f} cm³ of its "
                        f"{have / 1000:.2f} cm³ pocket", (_name(i),), value=need / have, unit="fraction"))
    say("interference")
    speed = A.point_speed(p, *p.workspace, A.part_reach(p, kit.layout, kit.bodies, kit.delta))
    angles, step = A.shape_samples(p, *p.workspace, speed)
    sweep = A.Sweep(p, angles, kit.bodies, kit.delta)
    clear = sweep.all(kit.layout)
    least = min(clear.items(), key=lambda kv: kv[1][0])
    res.figures.update({"interference_samples": len(angles), "step_deg": math.degrees(step),
                        "fastest_point_mm_per_rad": speed, "least_clearance_mm": least[1][0],
                        "least_clearance_parts": [_name(i) for i in least[0]],
                        "least_clearance_angle_deg": math.degrees(angles[least[1][1]])})
    for (a, b), (c, k) in sorted(clear.items()):
        if c < 0:
            res.add(Finding("interference", "fail", f"{_name(a)} and {_name(b)} overlap by {-c:.2f} mm (capsule "
                            f"hulls) at {math.degrees(angles[k]):.1f}° between links 1 and 4",
                            (_name(a), _name(b)), theta=float(angles[k]), value=c, unit="mm"))
    # how far the kit moves freely either side of home (capsule hulls), beyond the required workspace
    wide, _ = A.shape_samples(p, math.radians(5), math.radians(175), speed)
    prof = A.Sweep(p, wide, kit.bodies, kit.delta).profile(kit.layout)
    k0 = int(np.argmin(abs(wide - p.home)))
    lo = hi = k0
    if prof[k0] >= 0:
        while lo > 0 and prof[lo - 1] >= 0:
            lo -= 1
        while hi < len(wide) - 1 and prof[hi + 1] >= 0:
            hi += 1
        res.figures["free_range_deg"] = [math.degrees(wide[lo]), math.degrees(wide[hi])]
    else:
        res.figures["free_range_deg"] = [float("nan"), float("nan")]
    say("stacks")
    # parts sharing a joint: their features there are exempt from the capsule sweep; measure them
    # exactly (manifold intersection) at every sample
    solids = {int(pt.name[4:]): pt.solid for pt in kit.parts if pt.name.startswith("link")}
    solids[A.BASE] = next(pt.solid for pt in kit.parts if pt.name == "base")
    frames = sweep.frames
    worst_v = 0.0
    for j, (links, _, _) in bbf.JOINTS.items():
        members = kit.layout.members(j)
        for a, b in ((x, y) for x in members for y in members if x < y):
            for k in range(len(angles)):
                Ta = np.eye(4) if a == A.BASE else frames[a][k]
                Tb = np.eye(4) if b == A.BASE else frames[b][k]
                v = intersection(solids[a], Ta, solids[b], Tb)[0]
                worst_v = max(worst_v, v)
                if v > 1e-3:
                    res.add(Finding("interference", "fail", f"{_name(a)} and {_name(b)} overlap by {v:.3f} mm³ at "
                                    f"joint {j}, {math.degrees(angles[k]):.1f}° between links 1 and 4",
                                    (_name(a), _name(b)), theta=float(angles[k]), value=v, unit="mm3"))
                    break
    res.figures["joint_stack_overlap_mm3"] = worst_v
    say("fit")
    for pt, ext in oversize(kit.parts, p.printer.envelope, tol=0.0):
        res.add(Finding("fit", "fail", f"{pt.name} measures {ext.round(1)} mm: larger than the printer", (pt.name,)))
    return res
