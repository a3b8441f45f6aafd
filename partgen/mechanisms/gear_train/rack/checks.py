"""The rack and pinion's check: the rack mesh's rules, every pair of parts over the travel, fits and
printability (``checks.sequence``), the mesh over the whole travel on the printed sections; and the
text ``check`` prints."""

from __future__ import annotations

import math

import numpy as np

from ....checks.footer import check_footer
from ....checks.sequence import run_shared
from ....core.findings import Finding, Result
from ....design import rules
from ....design.rack import rack_contact_ratio, rack_tip_width
from ....design.rules import gear_rules
from ....geometry.solid import mesh_arrays
from .kit import RackKit
from .motion import turn_rack
from .resolve import RackSpec

__all__ = ["check_rack", "check_text"]


def check_rack(kit: RackKit, samples: int | None = None, progress=None) -> Result:
    s = kit.params
    res = Result()
    n = samples or s.checks.samples
    thetas = np.linspace(*s.thetas_range, n)
    m, al = s.system.module, s.system.pressure_angle
    p = s.pinion
    eps = rack_contact_ratio(p.teeth, m, al, p.profile_shift, s.system.addendum_coeff, s.system.addendum_coeff)
    tip_root = {"pinion->rack": (s.system.dedendum_coeff - s.system.addendum_coeff) * m,
                "rack->pinion": (p.pitch_radius + p.profile_shift * m - s.system.addendum_coeff * m) - p.root_radius}
    tip_w = rack_tip_width(m, al, s.system.backlash_per_gear, s.system.addendum_coeff)
    need_tip = gear_rules(s).min_tip_width
    rows = {"teeth": [p.teeth, s.rack_teeth], "contact_ratio": round(eps, 4),
            "tip_root_mm": {k: round(v, 4) for k, v in tip_root.items()}, "rack_tip_width_mm": round(tip_w, 4),
            "travel_mm": s.travel}
    if eps < s.checks.min_contact_ratio:
        res.add(Finding("mesh", "fail", f"pinion/rack: contact ratio {eps:.3f} < {s.checks.min_contact_ratio:g}",
                        ("pinion", "rack"), None, eps, "", rule="contact-ratio"))
    for k, v in tip_root.items():
        if v < rules.TIP_ROOT_COEFF * m:
            res.add(Finding("mesh", "fail", f"pinion/rack: tip clears root by {v:.3f} mm ({k})", ("pinion", "rack"), None,
                            v, "mm", rule="tip-root"))
    if tip_w < need_tip - 1e-9:
        res.add(Finding("printability", "fail", f"rack: tooth tips {tip_w:.3f} mm wide, under {need_tip:.3f} mm", ("rack",),
                        None, tip_w, "mm", rule="tip-width"))
    if p.undercut:
        res.add(Finding("design", "info", f"the pinion ({p.teeth} teeth) is undercut", ("pinion",)))
    ext = {q.name: (lambda v: v.max(axis=0) - v.min(axis=0))(mesh_arrays(q.solid)[0]) for q in kit.parts}
    got = run_shared(res, kit, thetas, "input angle", progress, mesh_owned={frozenset(("pinion", "rack"))},
                     extents=ext, bores=False)
    turned = turn_rack(kit, thetas)
    lash = turned["coast"] - turned["drive"]
    if turned["overlap_mm2"].max() > 1e-6:
        k = int(np.argmax(turned["overlap_mm2"]))
        res.add(Finding("mesh", "fail", f"pinion/rack: the printed teeth overlap by {turned['overlap_mm2'][k]:.4f} mm²",
                        ("pinion", "rack"), float(thetas[k]), float(turned["overlap_mm2"][k]), "mm2"))
    if lash.min() <= 0:
        res.add(Finding("mesh", "fail", "pinion/rack: no backlash", ("pinion", "rack"), None, float(lash.min()), "mm",
                        rule="backlash"))
    rows.update(backlash_mm={"min": round(float(lash.min()), 5), "max": round(float(lash.max()), 5),
                             "designed": 2 * s.system.backlash_per_gear},
                max_overlap_mm2=float(turned["overlap_mm2"].max()))
    res.figures.update(parts=len(kit.parts), samples=n, input_turns=round((thetas[-1] - thetas[0]) / (2 * math.pi), 4),
                       motion=got.motion, rack_mesh=rows, clearance_left_to_mesh_check=got.dropped,
                       fits={"count": len(got.fits), "rows": got.fits}, printability=got.printing,
                       output_backlash_mm={"min": float(lash.min()), "max": float(lash.max())})
    return res


def check_text(spec: RackSpec, result: Result, folder, seconds: float) -> str:
    f = result.figures
    r = f["rack_mesh"]
    lines = [f"{spec.name}: {f['samples']} pinion angles over the rack's {spec.travel:g} mm travel",
             f"  pinion/rack {r['teeth'][0]}/{r['teeth'][1]}: contact ratio {r['contact_ratio']:.3f}, backlash "
             f"{r['backlash_mm']['min']:.3f}–{r['backlash_mm']['max']:.3f} mm (designed "
             f"{r['backlash_mm']['designed']:.3f}), rack tips {r['rack_tip_width_mm']:.2f} mm"]
    return "\n".join(lines + check_footer(result, seconds, folder, bed=False))
