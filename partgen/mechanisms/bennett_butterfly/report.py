"""The report of the balanced Bennett butterfly: the bill `build` prints, the report's sections (the
design, the poses, the kit, the balance, the interference sweep, the base, the bill of parts and what
to buy), its subtitle and the assembly steps."""

from __future__ import annotations

import html
import math

import numpy as np

from ...core.protocol import Trace
from . import kit as A
from .kit import bill, bought

__all__ = ["bill_text", "report_sections", "subtitle", "assembly_steps"]


def bill_text(man: dict, dest, seconds: float) -> str:
    """What `build` prints: every printed part (layer, masses, fill, the support it needs) and what to buy."""
    d = man["design"]
    rows = d["bill"]
    lines = [f"{d['name']}: Bennett a = {d['a_mm']:g} mm, b = {d['b_mm']:g} mm, α = {d['alpha_deg']:g}°, "
             f"β = {d['beta_deg']:.2f}°, scales {', '.join(f'{s:g}' for s in d['scales'])}",
             f"{'part':<10}{'layer':>6}{'solid g':>9}{'printed g':>11}{'fill g':>8}{'support mm²':>13}{'on bed mm²':>12}"
             f"  (printed at {d['infill_percent']:g} % infill; support beyond {d['overhang_angle_deg']:g}°)"]
    for r in rows:
        lines.append(f"{r['part']:<10}{r['layer']:>6}{r['solid_g']:>9.1f}{r['printed_g']:>11.1f}"
                     + (f"{r['fill_g']:>8.1f}" if r["fill_g"] else f"{'':>8}")
                     + f"{r['support_mm2']:>13.0f}{r['bed_contact_mm2']:>12.0f}")
    bal = d["balance_mm"]
    short = max(v for k, v in bal.items() if k.startswith("one_slug_short"))
    lines.append(f"centre of mass within {bal['fdm']:.4f} mm of S as printed (tolerance {d['balance_tolerance_mm']:g} "
                 f"mm); binder left out {bal['no_binder']:.2f} mm, one slug short {short:.1f} mm")
    lines.append(f"wrote {dest}/ ({len(man['parts'])} STL in their print orientations, manifest.json, assembly.glb, "
                 f"design.yaml with the layout pinned) in {seconds:.1f} s")
    return "\n".join(lines)


def _page(kit: A.BennettKit, result, files: dict | None = None) -> list[tuple[str, str]]:
    """One page: the design, the linkage at a few poses (planar and spatial), the assembled kit, the
    balance (centre-of-mass trace, the fill's sensitivity), the interference sweep, the base, how
    each part prints, the bill of parts and what to buy. ``files``: the trace's figures (its
    poses.png is this page's: drawn once)."""
    from ...export import report as R
    from .plots import com_figure, poses_figure
    from ...export.render import render
    from ...geometry.solid import mesh_arrays

    p = kit.params
    f, b = result.figures, result.figures["balance_mm"]
    lo, hi = (math.degrees(x) for x in p.workspace)
    poses = (files or {}).get("poses.png") or poses_figure(p.bb, [lo, math.degrees(p.home), hi])
    ang = np.linspace(lo, hi, p.grid[1])
    labels = {"fdm": "as printed (FDM model), the fills as they sit", "solid": "printed solid (100 % infill)",
              "fdm_infill_error": f"infill {100 * p.infill:g} → {100 * (p.infill + p.infill_error):g} %",
              "no_binder": "the binder left out", "what_if_mass_scale": f"what-if heavier links {dict(p.mass_scale)}"}
    labels.update({k: f"{k[len('one_slug_short_'):]} one slug short" for k in f["balance_trace_mm"]
                   if k.startswith("one_slug_short_")})
    com = com_figure(ang, f["balance_trace_mm"], p.tolerance, labels)
    placed = kit.poses(0.0)
    meshes = []
    for part in kit.parts:
        if part.role == "pin":
            continue
        v, fc = mesh_arrays(part.solid)
        T = placed[part.name]
        colour = {"bennett_base": "#bbbbbb", "counterweight fill": "#555555"}.get(part.role, "#f58518" if part.name in
                                                                                  {f"link{i:02d}" for i in p.cw_links} else "#4c78a8")
        meshes.append((v @ T[:3, :3].T + T[:3, 3], fc, colour))
    kit_png = render(meshes, (640, 560), elev=30, azim=-60)
    top_png = render(meshes, (640, 560), elev=89, azim=-90)

    def g(x):
        return "" if not x else f"{x:.1f}"
    rows = [[r["part"], r["layer"], g(r["solid_g"]), g(r["printed_g"]), g(r["fill_g"]), g(r["pins_g"]),
             f"{r['support_mm2']:.0f}", f"{r['bed_contact_mm2']:.0f}", f"{r['print_height_mm']:.0f}"] for r in bill(kit)]
    buy = [[x["item"], x["quantity"], x["for"], f"{x['mass_g']:.1f}"] for x in bought(kit)]
    lay = kit.layout
    shifts = {i: ", ".join(f"{j} {v:+g} mm" for j, v in sorted(lay.shift.items()) if v and i in lay.members(j))
              for i in range(1, 13)}
    design = (f"<p>Bennett 1: a = {p.bb.a:g} mm, b = {p.bb.b:g} mm, α = {math.degrees(p.bb.alpha):g}°, β = "
              f"{math.degrees(p.bb.beta):.2f}° (from sin β = (b/a) sin α); the other three Bennetts are translated "
              f"copies scaled {p.bb.s2:g}, {p.bb.s3:g}, {p.bb.s4:g}. Home pose {math.degrees(p.home):g}° between "
              f"links 1 and 4; the kit must move freely from {lo:g}° to {hi:g}° and turn freely about S. The four "
              "joints at S are four revolutes on different axes through S (a spherical four-bar); see the README for "
              "why one pin cannot work.</p>"
              + R.table(["link", "layer", "shift of its stacks"],
                        [[f"link{i:02d}", lay.layer[i], shifts[i]] for i in range(1, 13)]))
    short = {k[len("one_slug_short_"):]: v for k, v in b.items() if k.startswith("one_slug_short_")}
    fills = "".join(f"<li>{html.escape(x.message)}</li>" for x in result.findings if x.check == "counterweight")
    balance = (f'<p class="{"ok" if result.ok else "fail"}">Worst distance of the common centre of mass from S over a '
               f"{p.grid[0]} × {p.grid[1]} grid (q1 over a turn × the workspace): as printed, the fills as they sit "
               f"(slugs and binder filling each pocket, centred in it) {b['fdm']:.4f} mm (tolerance {p.tolerance:g} mm); "
               f"printed solid {b['solid']:.3f} mm; infill {100 * p.infill_error:g} points off {b['fdm_infill_error']:.3f} mm"
               + (f"; what-if heavier links {b['what_if_mass_scale']:.3f} mm" if "what_if_mass_scale" in b else "")
               + ".</p><p>The fill is exact only as built: with the binder left out "
               f"{b['no_binder']:.3f} mm; one slug short (the top one missing) "
               + ", ".join(f"in {k} {v:.2f} mm" for k, v in short.items()) + f".</p><ul>{fills}</ul>"
               + R.img(com, "centre of mass trace"))
    interference = (f"<p>{f['interference_samples']} shape angles at {f['step_deg']:.2f}° steps: the fastest point "
                    f"moves {f['fastest_point_mm_per_rad']:.0f} mm per radian, so no point moves more than a bar's radius "
                    f"({p.bar_radius:g} mm) between samples. Least clearance {f['least_clearance_mm']:.2f} mm "
                    f"({' – '.join(f['least_clearance_parts'])}, capsule hulls); stacked bosses measured exactly: "
                    f"{f['joint_stack_overlap_mm3']:.3f} mm³ overlap. Free from {f['free_range_deg'][0]:.1f}° to "
                    f"{f['free_range_deg'][1]:.1f}°.</p>"
                    + "".join(f"<p class='fail'>{x.check}: {html.escape(x.message)}</p>" for x in result.findings
                              if x.severity == "fail"))
    st = f["base"]
    base = (f"<p>A post on a Ø{2 * p.foot_radius:g} mm foot, printed standing on it ({st['footprint_mm2']:.0f} mm² flat on "
            f"the bed), the S pin's bore open at the top. The whole kit ({st['total_g']:.0f} g) has its centre of mass "
            f"{st['com_height_mm']:.0f} mm over the bed and at least {st['margin_mm']:.1f} mm inside the foot's edge in "
            f"every pose of the grid: it stands tilted up to {st['tip_angle_deg']:.1f}° (required "
            f"{math.degrees(p.min_tip_angle):g}°). The links stay {st['links_above_table_mm']:.0f} mm above the table.</p>")
    sections = [("Design", design), ("Poses", R.img(poses, "poses")),
                ("Kit", f'<div class="grid"><figure>{R.img(kit_png, "kit")}<figcaption>at home</figcaption></figure>'
                        f'<figure>{R.img(top_png, "kit from above")}<figcaption>from above</figcaption></figure></div>'),
                ("Balance", balance), ("Interference", interference), ("Base", base),
                ("Bill of parts", f"<p>Each part prints in the orientation that needs the least support beyond "
                                  f"{math.degrees(p.overhang_angle):g}° among its flat faces (the STLs are written so).</p>"
                 + R.table(["part", "layer", "solid g", "printed g", "fill g", "pins g", "support mm²", "on bed mm²",
                            "height mm"], rows)),
                ("Bought parts", R.table(["item", "quantity", "for", "g"], buy))]
    return sections


def report_sections(spec, kit, result, trace: Trace, files: dict) -> list[tuple[str, str]]:
    from ...export import report as R

    sections = _page(kit, result, files)
    if "com.png" in files:
        sections.insert(2, ("Trace", R.img(files["com.png"], "centre of mass over the workspace")))
    return sections


def subtitle(spec) -> str:
    return "Bennett butterfly"


def assembly_steps(spec, kit) -> list[tuple[str, tuple[str, ...]]]:
    """Fill the counterweight pockets; the base; then the four Bennett loops around S in turn, each
    link pinned to the ones already there; the two cross joints last."""
    from ...design import bennett_butterfly as bbf

    have = {p.name for p in kit.parts}
    link = lambda i: f"link{i:02d}"  # noqa: E731
    fills = tuple(sorted(x for x in have if x.startswith("fill_")))
    steps = [("Fill each link's counterweight pocket with its slugs and binder and let the binder set.",
              fills)] if fills else []
    steps.append(("Stand the base on the table, its S bore up.", ("base",)))
    placed, done = set(), set()
    for loop in ((1, 2, 3, 4), (4, 5, 6, 7), (7, 8, 9, 10), (10, 11, 12, 1)):
        joints = [j for j, ((a, b), _, _) in bbf.JOINTS.items() if a in loop and b in loop and j not in done]
        done.update(joints)
        new = [i for i in loop if i not in placed]
        placed.update(loop)
        pins = tuple(f"pin_{j}" for j in joints if f"pin_{j}" in have)
        steps.append((f"Bennett loop of links {', '.join(str(i) for i in loop)}: lay "
                      f"{', '.join(link(i) for i in new)} in place and push the pins of joints {', '.join(joints)} "
                      "through their stacks" + (" (the S stack into the base)" if "S14" in joints else "") + ".",
                      tuple(link(i) for i in new) + pins))
    rest = [j for j in bbf.JOINTS if j not in done]
    if rest:
        steps.append((f"Close the cross joints {', '.join(rest)} with their pins.",
                      tuple(f"pin_{j}" for j in rest if f"pin_{j}" in have)))
    return steps
