"""The gear chain's report: the bill `build` prints (with a drawing's links-against-deviation table
and how often the crank turns), the report's sections (design, stacking, trace, what play costs,
check), its subtitle and the assembly steps."""

from __future__ import annotations

import html
import math
from pathlib import Path

from ...core.findings import Result
from ...core.protocol import Trace
from .kit import Kit
from .resolve import ChainSpec

__all__ = ["bill_text", "report_sections", "subtitle", "assembly_steps"]


def _play_html(band: dict, files: dict, params) -> str:
    """The report's "What play costs": the pen's error band from the kit's backlash and running-fit
    play (design.play), across the path and from the nominal point, its figure, and each link's free
    angle."""
    from ...export import report as R

    r2 = lambda x: f"{float(x):.2f}"  # noqa: E731
    rows = [["across the path (what the drawing shows)", r2(band["path_worst_case_max"]), r2(band["path_p95_max"]),
             r2(band["path_p50_max"])],
            ["from the nominal point at the same crank angle (a lag along the path too)", r2(band["worst_case_max"]),
             r2(band["p95_max"]), r2(band["p50_max"])]]
    links = [[j, f"{a:.1f}", f"{c:.3f}"] for j, (a, c) in
             enumerate(zip(band["link_free_angle_arcmin"], band["joint_radial_play_mm"]), 1)]
    fig = (f'<figure>{R.img(files["pen_band.png"], "the pen error band over the crank turn", width=640)}'
           "<figcaption>The pen's error over one crank turn: worst case and 95 % of prints across the nominal path; "
           "the worst case from the nominal point, dashed.</figcaption></figure>" if "pen_band.png" in files else "")
    return (f"<p>The pen's error band from the kit's backlash ({params.system.backlash_per_gear:g} mm per gear) and "
            f"running-fit play ({params.joints.running_clearance:g} mm diametral) on {html.escape(params.printer.name)} "
            f"(±{params.printer.xy_accuracy:g} mm): every backlash and play taken up in the worst direction (worst "
            f"case) and the band 95 % of {band['prints']:,} simulated prints stay in, each print held at a random place "
            "in its play (docs/tolerance.md, What play costs). The trace above draws both bands beside the nominal "
            "path.</p>"
            + R.table(["pen error (mm)", "worst case", "95 % of prints", "median print"], rows, left=1) + fig
            + '<div class="grid">' + R.table(["link", "free angle ± arcmin", "its bore's radial play mm"], links)
            + "</div>")


def _crank_text(mech) -> str:
    """How often the crank turns per drawing and why ("" for the usual once)."""
    from ...design.trace import crank_turns

    n, d = crank_turns(mech), mech.drawing
    rounds = (f"; the samples go round the curve {d.rounds} times, so one drawing is their first round and every "
              f"speed is 1/{d.rounds} of the fit's" if d is not None and d.rounds > 1 else "")
    if n == 1 and not rounds:
        return ""
    l1 = mech.chain.links[0]
    return (f"the crank turns {n} times per drawing: link 1 ({l1.name}) turns at the drawing's lowest harmonic, "
            f"{abs(l1.speed)} turns per cycle, through the 1:1 drive pair{rounds}")


def _tradeoff_text(d) -> list[str]:
    """The links-against-deviation table of a drawing (build prints it)."""
    lines = [f"links vs deviation from {d.source} ({len(d.samples)} samples, by {d.parametrisation.replace('_', ' ')}"
             f"{f', at scale {d.scale:g}' if d.scale != 1 else ''}):",
             f"{'links':>7}{'Hausdorff mm':>14}{'max mm':>10}{'rms mm':>10}{'shortest link mm':>18}"]
    for r in d.rows:
        lines.append(f"{r.links:>7}{r.hausdorff_mm:>14.3f}{r.max_mm:>10.3f}{r.rms_mm:>10.3f}{r.shortest_mm:>18.2f}"
                     + ("  <- chosen" if r.links == d.chosen else ""))
    return lines


def bill_text(spec: ChainSpec, man: dict, dest, seconds: float) -> str:
    mech = spec.mechanism
    parts = man["parts"]
    n_gears = sum(p["count"] for p in parts if p["role"] == "gear")
    mass = sum(p["mass_g"] * p["count"] for p in parts)
    lines = [f"{spec.params.name}: {len(mech.chain.links)} links, {n_gears} gears, "
             f"{sum(p['count'] for p in parts)} parts ({len(parts)} distinct), {mass:.0f} g of {spec.params.material}",
             f"{'part':<12}{'role':<11}{'count':>5}{'triangles':>11}{'volume cm3':>12}{'mass g':>9}  bbox mm"]
    for p in parts:
        lines.append(f"{p['name']:<12}{p['role']:<11}{p['count']:>5}{p['triangles']:>11}"
                     f"{p['volume_mm3'] / 1000:>12.2f}{p['mass_g']:>9.1f}  {' x '.join(f'{x:.1f}' for x in p['bbox_mm'])}")
    warn = sum(f.severity == "warn" for f in mech.findings)
    if mech.drawing is not None:
        lines += _tradeoff_text(mech.drawing)
    if _crank_text(mech):
        lines.append(_crank_text(mech))
    lines.append(f"wrote {dest}/ ({len(parts)} STL, manifest.json, assembly.glb) in {seconds:.2f} s"
                 + (f"; {warn} warning{'s' if warn != 1 else ''} above (`partgen check` will fail)" if warn else ""))
    return "\n".join(lines)


def report_sections(spec: ChainSpec, kit: Kit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
    """Design, stacking, trace and check sections (the pipeline adds the bill of parts, what to
    buy and the build plates). ``files``: the trace's files (name -> bytes)."""
    import tempfile

    from ...design.trace import built_speeds
    from ...export import report as R
    from .plots import stack_section

    mech, params = spec.mechanism, spec.params
    with tempfile.TemporaryDirectory() as tmpdir:
        stack_section(kit, Path(tmpdir) / "stack.png")
        stack_png = (Path(tmpdir) / "stack.png").read_bytes()
    r3 = lambda x: round(float(x), 3)  # noqa: E731
    speeds = built_speeds(mech)
    links = [[j, l.name, l.speed, r3(l.length), r3(math.degrees(l.phase)), str(w)]
             for j, (l, w) in enumerate(zip(mech.chain.links, speeds), 1)]
    stages = [[s.j, str(s.ratio), f"{s.D.teeth} / {s.M.teeth} / {s.G.teeth}",
               f"{s.D.profile_shift:.3f} / {s.M.profile_shift:.3f} / {s.G.profile_shift:.3f}",
               r3(s.a_DM), r3(s.a_MG), f"({s.idler[0]:.2f}, {s.idler[1]:.2f})"] for s in mech.stages]
    belts = [[s.j, str(s.ratio), f"{s.D.teeth} / {s.G.teeth}", s.belt_teeth, r3(s.slack),
              "–" if s.tensioner is None else f"({s.tensioner[0]:.2f}, {s.tensioner[1]:.2f})", r3(s.link_change)]
             for s in mech.belt_stages]
    design = (R.table(["link", "name", "speed", "length mm", "initial angle °", "speed as built"], links, left=2)
              + (R.table(["stage", "Eq 11 ratio", "teeth D / M / G", "profile shift D / M / G", "a_DM mm", "a_MG mm",
                          "idler (link frame) mm"], stages, left=1) if stages else "")
              + (R.table(["stage", "Eq 11 ratio", "pulley teeth D / G", "belt teeth", "slack taken up mm",
                          "tensioner (link frame) mm", "link change mm"], belts, left=1) if belts else "")
              + f"<p>Module {params.system.module:g} mm, pressure angle {math.degrees(params.system.pressure_angle):g}°, "
              f"backlash {params.system.backlash_per_gear:g} mm per gear, face width {params.face_width:g} mm, "
              f"printer {html.escape(params.printer.name)}, material {html.escape(params.material)}."
              + (f" {html.escape(_crank_text(mech)).capitalize()}." if _crank_text(mech) else "") + "</p>")
    stack_html = f'<figure>{R.img(stack_png, "section through the joints")}<figcaption>True section through ' \
                 "the joints, links straightened.</figcaption></figure>"
    stats = trace.stats
    dev = [["your drawing" if stats.get("target") == "drawing" else "the full Fourier series",
            stats.get("max_deviation_mm", "–"), stats.get("rms_mm", "–"), stats.get("hausdorff_mm", "–")],
           ["the design's chain (pruned)", stats["vs_pruned"]["max_deviation_mm"], stats["vs_pruned"]["rms_mm"],
            stats["vs_pruned"]["hausdorff_mm"]]]
    tradeoff = ""
    if mech.drawing is not None:
        d = mech.drawing
        tradeoff = (f"<p>Links against deviation from {html.escape(d.source)} ({len(d.samples)} samples, by "
                    f"{d.parametrisation.replace('_', ' ')}): the chain of the n longest printable links, its pen "
                    f"path measured against the samples; {d.chosen} chosen (the fewest within the budget).</p>"
                    + R.table(["links", "Hausdorff mm", "max, same θ (mm)", "rms (mm)", "shortest link mm"],
                              [[r.links, r3(r.hausdorff_mm), r3(r.max_mm), r3(r.rms_mm), r3(r.shortest_mm)]
                               for r in d.rows]))
    trace_html = (R.table(["traced (as built) vs", "max, same θ (mm)", "rms (mm)", "Hausdorff (mm)"], dev) + tradeoff
                  + f'<div class="grid"><figure>{R.img(files["trace.png"], "trace", width=640)}</figure>'
                  + (f'<figure>{R.img(files["trace.gif"], "animation", "image/gif", width=440)}<figcaption>One '
                     "crank turn.</figcaption></figure>" if "trace.gif" in files else "") + "</div>")
    fails = [[f.check, f'<span class="{f.severity}">{f.severity}</span>', f.message,  # R.table escapes it
              "" if f.theta is None else f"{math.degrees(f.theta):.1f}"] for f in result.findings]
    fig = result.figures
    close = fig["motion"].get("closest_approach")
    summary = (f'<p class="{"ok" if result.ok else "fail"}">'
               f'{"Every check holds" if result.ok else "The kit fails its checks"}'
               f" — {fig['samples']} crank angles, {fig['pairs']} part pairs, {len(fig['meshes'])} meshes, "
               f"{fig['fits']['count']} fits; closest approach "
               + (f"{close['mm']:.3f} mm ({close['parts'][0]}–{close['parts'][1]})" if close else "–")
               + f"; {fig.get('plates', '?')} build plate(s).</p>")
    mesh_rows = [[" / ".join(r["pair"]), " / ".join(map(str, r["teeth"])), r["centre_distance_mm"], r["backlash_mm"],
                  r["measured_backlash_mm"], r["contact_ratio"]] for r in fig["meshes"]]
    check_html = (summary
                  + (R.table(["check", "severity", "finding", "crank °"], fails, left=3, raw={1}) if fails else "")
                  + R.table(["mesh", "teeth", "centre distance mm", "backlash mm", "measured mm", "contact ratio"],
                            mesh_rows))
    sections = [("Design", design), ("Stacking", stack_html), ("Trace", trace_html)]
    band = stats.get("pen_error_band_mm")
    if band:
        sections.append(("What play costs", _play_html(band, files, params)))
    return sections + [("Check", check_html)]


def subtitle(spec: ChainSpec) -> str:
    return f"{spec.path.name} — {len(spec.mechanism.chain.links)} links"


def assembly_steps(spec: ChainSpec, kit: Kit) -> list[tuple[str, tuple[str, ...]]]:
    """The chain put together from the base up: base and legs, the drive axle and gear, link 1
    with its gears, each further link in chain order with its gears (D on the post of the link
    below, M or the belt's tensioner on its own plate, G under it), the crank, the pen holder."""
    have = {p.name for p in kit.parts}
    n = len(spec.mechanism.chain.links)
    legs = tuple(sorted((x for x in have if x.startswith("leg")), key=lambda x: int(x[3:])))
    steps = [(f"Press the pegs of the {len(legs)} legs up into the base's holes and stand it on them: the "
              "ground post points up.", ("base",) + legs),
             ("Put the drive axle down through the base's drive bore, its round part in the bore, and slide the "
              "drive gear onto its upper D end, resting on the base's thrust ring.", ("drive_axle", "drive"))]
    for j in range(1, n + 1):
        below = "the ground post" if j == 1 else f"B{j - 1}'s distal post"
        mate = "the drive gear" if j == 1 else (f"M{j - 1}" if f"M{j - 1}" in have else f"D{j - 1}")
        names = [f"G{j}", f"B{j}"]
        text = [f"Slide G{j} down over {below}, collar and D-boss up, its teeth in mesh with {mate}; press "
                f"link B{j}'s proximal D-hole onto the boss."]
        if f"belt{j - 1}" in have:
            text[0] = (f"Slide pulley G{j} down over {below}, collar and D-boss up; press link B{j}'s proximal "
                       f"D-hole onto the boss; loop belt{j - 1} over D{j - 1} and G{j}"
                       + (f" and set the tensioner T{j - 1} on B{j - 1}." if f"T{j - 1}" in have else "."))
            names += [f"belt{j - 1}"] + ([f"T{j - 1}"] if f"T{j - 1}" in have else [])
        if f"D{j}" in have:
            text.append(f"Press D{j} onto the D end of {below} above B{j}.")
            names.append(f"D{j}")
        if f"M{j}" in have:
            text.append(f"Put M{j} on B{j}'s idler post, in mesh with D{j}.")
            names.append(f"M{j}")
        steps.append((f"Link {j}: " + " ".join(text), tuple(x for x in names if x in have)))
    steps += [("Press the crank onto the drive axle's lower D end under the base, the handle pointing down.",
               ("crank",)),
              (f"Press the pen holder's D-spigot down into link B{n}'s distal hole and push the pen into its bore, "
               "point up.", ("pen_holder",))]
    return steps
