"""The balanced Bennett butterfly (``kind: bennett_butterfly``) behind the Mechanism protocol: its
bill, what to buy, its check and trace texts and its report sections."""

from __future__ import annotations

import html
import math
from pathlib import Path

import numpy as np

from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.protocol import Motion, Trace
from .params import BennettParams
from ...errors import DesignError
from . import kit as A
from .parts import home_inputs
from .resolve import resolve_bennett
from .schema import BennettDesign

__all__ = ["BennettButterfly", "MECHANISM", "bill", "bought", "layout_yaml"]


def layout_yaml(kit: A.BennettKit) -> dict:
    """The kit's stack layout as the config's ``parts.layout`` (so a kit folder rebuilds without a search)."""
    return {"layers": {i: int(kit.layout.layer[i]) for i in range(1, 13)},
            "shifts_mm": {j: float(v) for j, v in sorted(kit.layout.shift.items()) if v}}


def _r(x, nd=4):
    return [round(float(v), nd) for v in x] if np.ndim(x) else round(float(x), nd)


def bill(kit: A.BennettKit) -> list[dict]:
    """Every printed part: its masses (g) solid and as printed (FDM) with their centres in its STL
    frame, its pocket's fill and its pins (g), how it prints (support mm², bed contact mm², height)."""
    rows = []
    parts = [(f"link{i:02d}", kit.masses[i], kit.layout.layer[i], kit.pins[i]) for i in range(1, 13)]
    parts.append(("base", kit.base_mass, 0, kit.pins[A.BASE]))
    for name, lm, layer, pins in parts:
        pose = kit.printing[name]
        T = np.linalg.inv(pose.body_from_print)
        stl = lambda c: T[:3, :3] @ np.asarray(c, float) + T[:3, 3]  # noqa: E731
        i = None if name == "base" else int(name[4:])
        rows.append({"part": name, "layer": layer, "solid_g": lm.solid_mass, "solid_centre_mm": _r(stl(lm.solid_centre)),
                     "printed_g": lm.fdm_mass, "printed_centre_mm": _r(stl(lm.fdm_centre)),
                     "fill_g": kit.fills[i].mass if i in kit.fills else 0.0, "pins_g": sum(m for m, _ in pins),
                     "support_mm2": round(pose.overhang_mm2, 1), "bed_contact_mm2": round(pose.contact_mm2, 1),
                     "print_height_mm": round(pose.height_mm, 1)})
    return rows


def bought(kit: A.BennettKit) -> list[dict]:
    """What to buy: the pins by stock length, each pocket's slugs and the binder (quantity, stock size)."""
    p = kit.params
    pins: dict[float, list[str]] = {}
    for part in kit.parts:
        if part.role == "pin":
            info = dict(part.info)
            pins.setdefault(info["length_mm"], []).append(info["joint"])
    rows = [{"item": f"{p.pin_kind} Ø{2 * p.pin_radius:g} × {L:g} mm", "quantity": len(js), "for": ", ".join(js),
             "mass_g": len(js) * p.pin_density * math.pi * p.pin_radius ** 2 * L} for L, js in sorted(pins.items())]
    slugs: dict[float, list[tuple[str, int]]] = {}
    for i, f in sorted(kit.fills.items()):
        slugs.setdefault(f.length, []).append((f"link{i:02d}", f.count))
    for L, uses in sorted(slugs.items()):
        f = _slug_fill(kit, L)
        rows.append({"item": f"{p.slug_kind} Ø{f.diameter:g} × {L:g} mm", "quantity": sum(n for _, n in uses),
                     "for": ", ".join(f"{n} in {name}" for name, n in uses),
                     "mass_g": sum(n for _, n in uses) * f.slug_mass})
    binder = sum(f.binder_volume for f in kit.fills.values())
    rows.append({"item": p.binder_name, "quantity": f"{binder / 1000:.2f} cm³",
                 "for": "the slugs' clearance in the three pockets", "mass_g": sum(f.binder_mass for f in kit.fills.values())})
    return rows


def _slug_fill(kit: A.BennettKit, length: float):
    return next(f for f in kit.fills.values() if f.length == length)


def _design(kit: A.BennettKit) -> dict:
    from .checks import balance_figures

    p = kit.params
    bal = {k: v for k, v in balance_figures(kit).items() if k not in ("trace", "grid")}
    fills = {}
    for part in kit.parts:
        if part.role == "counterweight fill":
            info = dict(part.info)
            fills[info["part"]] = {k: v for k, v in info.items() if k != "part"}
            fills[info["part"]]["pocket_offset_mm"] = kit.figures["pocket_offsets_mm"][int(info["part"][4:])]
    return {"name": p.name, "kind": "bennett_butterfly",
            "a_mm": p.bb.a, "b_mm": p.bb.b, "alpha_deg": math.degrees(p.bb.alpha), "beta_deg": math.degrees(p.bb.beta),
            "scales": [1.0, p.bb.s2, p.bb.s3, p.bb.s4], "home_angle_deg": math.degrees(p.home),
            "workspace_deg": [math.degrees(x) for x in p.workspace], "layout": layout_yaml(kit),
            "counterweights": fills, "bill": bill(kit), "bought": bought(kit), "infill_percent": 100 * p.infill,
            "overhang_angle_deg": math.degrees(p.overhang_angle), "balance_tolerance_mm": p.tolerance,
            "balance_mm": bal, **{k: v for k, v in kit.figures.items() if k not in ("pocket_offsets_mm", "next_pockets")}}


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


def check_text(p, result, seconds: float) -> str:
    """What `check` prints for a Bennett kit."""
    f = result.figures
    b = f["balance_mm"]
    short = max(v for k, v in b.items() if k.startswith("one_slug_short"))
    st = f["base"]
    lines = [f"{p.name}: balance over a {b['grid'][0]} × {b['grid'][1]} grid of (q1, angle between links 1 "
             f"and 4); interference over {f['interference_samples']} shape angles, step {f['step_deg']:.2f}°",
             f"  centre of mass from S: as printed {b['fdm']:.4f} mm, printed solid {b['solid']:.4f} mm, "
             f"infill off by {100 * p.infill_error:g} points {b['fdm_infill_error']:.3f} mm, "
             f"binder left out {b['no_binder']:.3f} mm, a pocket one slug short {short:.1f} mm"
             + (f", what-if heavier links {b['what_if_mass_scale']:.3f} mm" if "what_if_mass_scale" in b else ""),
             f"  least clearance {f['least_clearance_mm']:.2f} mm ({' – '.join(f['least_clearance_parts'])} at "
             f"{f['least_clearance_angle_deg']:.1f}°); stacked bosses overlap {f['joint_stack_overlap_mm3']:.3f} mm³; "
             + (f"moves freely from {f['free_range_deg'][0]:.1f}° to {f['free_range_deg'][1]:.1f}°"
                if math.isfinite(f["free_range_deg"][0]) else "capsule hulls overlap at the home pose"),
             f"  pins (stock lengths): {', '.join(f'{n} × {k} mm' for k, n in f['pins']['count_by_length'].items())}; "
             f"base: {st['footprint_mm2']:.0f} mm² on the bed, stands to {st['tip_angle_deg']:.1f}° of tilt, links "
             f"{st['links_above_table_mm']:.0f} mm above the table",
             "  support (mm²): " + ", ".join(f"{k} {v['support_mm2']:.0f}" for k, v in f["printing"].items())]
    lines += [f"  FAIL  {x.check}: {x.message}" for x in result.findings if x.severity == "fail"]
    lines.append(f"{'OK' if result.ok else 'FAILED'} in {seconds:.1f} s")
    return "\n".join(lines)


def report_sections(kit: A.BennettKit, result) -> list[tuple[str, str]]:
    """One page: the design, the linkage at a few poses (planar and spatial), the assembled kit, the
    balance (centre-of-mass trace, the fill's sensitivity), the interference sweep, the base, how
    each part prints, the bill of parts and what to buy."""
    from ...export import report as R
    from .plots import com_figure, poses_figure
    from ...export.render import render
    from ...geometry.solid import mesh_arrays

    p = kit.params
    f, b = result.figures, result.figures["balance_mm"]
    lo, hi = (math.degrees(x) for x in p.workspace)
    poses = poses_figure(p.bb, [lo, math.degrees(p.home), hi])
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


class BennettButterfly:
    kind = "bennett_butterfly"
    title = "balanced Bennett butterfly"
    schema = BennettDesign
    motion = Motion("angle between links 1 and 4", "rad", (0.0, math.pi))
    csv_header = "angle_rad,com_from_S_mm,com_from_S_solid_mm\n"
    trace_needs_kit = True
    role_colours = {"bennett_link": "#4c78a8", "bennett_base": "#bbbbbb"}

    def resolve(self, raw: LoadedDesign) -> BennettParams:
        return resolve_bennett(raw)


    def build(self, spec: BennettParams, progress=None) -> A.BennettKit:

        try:
            kit = A.build_bennett(spec, progress)
        except DesignError as e:
            raise DesignError(e.problem, e.key_path or "counterweights") from None
        return kit

    def refuse(self, spec: BennettParams, kit: A.BennettKit) -> None:
        from ...geometry.measure import oversize

        for part, ext in oversize(kit.parts, spec.printer.envelope, tol=0.0):
            raise DesignError(f"{part.name} measures {ext.round(1)} mm and does not fit the printer in any orientation",
                              "linkage.a_mm")

    def findings(self, spec: BennettParams):
        return []

    def design_summary(self, spec: BennettParams, kit: A.BennettKit) -> dict:
        return _design(kit)

    def kit_files(self, spec: BennettParams, kit: A.BennettKit, raw: LoadedDesign) -> dict[str, bytes]:
        """design.yaml with the chosen layout pinned (a kit folder rebuilds without a search), printer.yaml."""
        data = raw.document()
        data["printer"] = "printer.yaml"
        data.setdefault("parts", {})["layout"] = layout_yaml(kit)
        return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}

    def plate_margin(self, spec: BennettParams) -> float:
        return 5.0

    def check(self, spec: BennettParams, kit: A.BennettKit, samples: int | None = None, progress=None):
        """Balance over the input grid, interference over the workspace, stacks, pins, printing, the base."""
        from .checks import check_bennett

        steps = 7  # the named steps check_bennett announces
        done = [0]

        def say(step: str) -> None:
            done[0] += 1
            if progress:
                progress(min(done[0], steps), steps)
        return check_bennett(kit, say)

    def tolerance_model(self, spec, kit, result, accuracy_mm: float, seated: bool = True):
        """What makes a print fail as a ``design.tolerance.MarginModel``: pins in their bores, the Bennett
        loops closing on their joints' play, and the balance as printed (no gear sits in a bore:
        ``seated`` changes nothing)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: BennettParams, kit: A.BennettKit, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        """The linkage over its workspace: the poses (planar and spatial) and the path of the common
        centre of mass (its worst distance from S over a turn of q1, per shape angle); poses.png, com.png."""
        p = kit.params
        n = samples or p.grid[1]
        nq = p.grid[0]
        ang = np.linspace(*p.workspace, n)
        q1 = np.linspace(0, 2 * np.pi, nq, endpoint=False)
        Q1, S = np.meshgrid(q1, ang, indexing="ij")
        a1, a4 = home_inputs(S.ravel(), Q1.ravel())
        fdm = A.com_deviation(kit, "fdm", a1, a4).reshape(nq, n).max(axis=0)
        solid = A.com_deviation(kit, "solid", a1, a4).reshape(nq, n).max(axis=0)
        stats = {"kind": self.kind, "samples": int(n), "q1_samples": int(nq),
                 "workspace_deg": [math.degrees(x) for x in p.workspace],
                 "com_from_S_max_mm": float(fdm.max()), "com_from_S_solid_max_mm": float(solid.max()),
                 "worst_angle_deg": float(np.degrees(ang[int(np.argmax(fdm))])), "tolerance_mm": p.tolerance}
        files = []
        if out is not None:
            from .plots import com_figure, poses_figure

            lo, hi = (math.degrees(x) for x in p.workspace)
            (out / "poses.png").write_bytes(poses_figure(p.bb, [lo, math.degrees(p.home), hi]))
            (out / "com.png").write_bytes(com_figure(np.degrees(ang), {"fdm": fdm.tolist(), "solid": solid.tolist()},
                                                     p.tolerance, {"fdm": "as printed (FDM model)",
                                                                   "solid": "printed solid (100 % infill)"}))
            files = ["poses.png", "com.png"]
        return Trace(stats, files, columns=("angle_rad", "com_from_S_mm", "com_from_S_solid_mm"),
                     data=np.column_stack([ang, fdm, solid]))

    def csv(self, trace: Trace) -> str:
        return self.csv_header + "".join(f"{a:.9f},{f:.6f},{s:.6f}\n" for a, f, s in trace.data)

    def assembly_steps(self, spec, kit) -> list[tuple[str, tuple[str, ...]]]:
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

    def bill_text(self, spec, man: dict, dest, seconds: float) -> str:
        return bill_text(man, dest, seconds)

    def check_text(self, spec, result, folder, seconds: float) -> str:
        return check_text(spec, result, seconds) + (f"; {result.figures.get('plates', '?')} build plate(s) in {folder}/"
                                                    if folder else "")

    def trace_text(self, spec, trace: Trace, folder) -> str:
        s = trace.stats
        lines = [f"{spec.name}: {s['samples']} shape angles from {s['workspace_deg'][0]:g}° to {s['workspace_deg'][1]:g}°, "
                 f"each over {s['q1_samples']} turns of q1",
                 f"  centre of mass from S: as printed ≤ {s['com_from_S_max_mm']:.4f} mm (worst at "
                 f"{s['worst_angle_deg']:.1f}°, tolerance {s['tolerance_mm']:g} mm); printed solid ≤ "
                 f"{s['com_from_S_solid_max_mm']:.4f} mm"]
        if folder:
            lines.append(f"plots: {folder}/{', '.join(trace.files)}")
        return "\n".join(lines)

    def report_sections(self, spec, kit, result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        from ...export import report as R

        sections = report_sections(kit, result)
        if "com.png" in files:
            sections.insert(2, ("Trace", R.img(files["com.png"], "centre of mass over the workspace")))
        return sections

    def subtitle(self, spec) -> str:
        return "Bennett butterfly"


MECHANISM = BennettButterfly()
