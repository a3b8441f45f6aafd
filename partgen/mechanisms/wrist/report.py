"""The wrist pair's report sections (the design's rings, the math, the parts, the check, the cross
gear and its mate), its subtitle, the bill `build` prints and the assembly steps."""

from __future__ import annotations

import math

from ...core.findings import Result
from ...core.protocol import Trace
from ...design import spherical as sph
from .kit import WristKit
from .spec import WristSpec

__all__ = ["COLOURS", "report_sections", "subtitle", "bill_text", "assembly_steps"]

COLOURS = {"gear1": "#4c78a8", "gear2": "#f58518", "cross_gear": "#54a24b", "cross_mate": "#e45756"}


def report_sections(spec: WristSpec, kit: WristKit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
    from ...export import report as R
    from ...export.render import render
    from ...geometry.solid import mesh_arrays

    stats = trace.stats
    meshes = {p.name: mesh_arrays(p.solid) for p in kit.parts}
    T = kit.pose2(kit.theta_max * 0.8, 0.6)
    v2, f2 = meshes["gear2"]
    bent = render([(*meshes["gear1"], COLOURS["gear1"]), (v2 @ T[:3, :3].T + T[:3, 3], f2, COLOURS["gear2"])],
                  (520, 520), elev=12, azim=-30)
    pics = (f'<div class="grid"><figure>{R.img(bent, "bent")}<figcaption>the pair bent by '
            f"{math.degrees(0.8 * kit.theta_max + float(sph.mating_angle(0.8 * kit.theta_max, spec.I))):.0f}°"
            "</figcaption></figure></div>")
    rows = [[r["k"], r["teeth"], r["theta_deg"], r["phi_deg"], r["lat_pitch_mm"],
             "–" if r["lat_pitch_off"] is None else f"{100 * r['lat_pitch_off']:+.2f} %"] for r in stats["rows"]]
    design = (R.table(["ring", "teeth", "θ on gear 1 °", "φ on gear 2 °", "latitudinal pitch mm", "vs longitudinal"],
                      rows)
              + f"<p>Nominal ratio I = {spec.I:g}, centre distance {spec.A:g} mm, longitudinal pitch "
              f"{spec.long_pitch:g} mm, dome teeth r = {spec.dome_radius:g} mm standing {spec.tooth_height:g} mm "
              f"proud, sockets cut with {spec.clearance:g} mm clearance over bends ≤ {math.degrees(spec.max_bend):g}°. "
              f"The ratio ODE agrees with its closed form tan(φ/2) = I tan(θ/2) to "
              f"{stats['ode_vs_closed_form_max']:.1e}; its valid range ends at θ = {stats['valid_end_deg']:.2f}°.</p>")
    f = result.figures
    play = [[p["theta_deg"], p["twist_play_deg"], p["bend_play_deg"]] for p in f["play"]]
    check_html = (f'<p class="{"ok" if result.ok else "fail"}">{f["poses"]} poses: largest overlap '
                  f'{f["max_overlap_mm3"]:.4f} mm³, least engaged tooth volume {f["min_engaged_mm3"]:.2f} mm³.</p>'
                  + R.table(["θ on gear 1 °", "twist play °", "bend play °"], play)
                  + "<p>Twist play is large: domes resist a twist about the line of centres only through the "
                  "teeth beside the contact, and near the pole the contact tooth sits on that axis.</p>")
    sections = [("Design", design), ("Math", R.img(files["wrist.png"], "ratio, mating angle, meridians")),
                ("Parts", pics), ("Check", check_html)]
    if spec.mate is not None:
        sections.append(("Cross gear and its mate", _mate_section(spec, kit, result, trace, files, meshes)))
    return sections


def _mate_section(spec: WristSpec, kit: WristKit, result: Result, trace: Trace, files: dict, meshes) -> str:
    """The cross gear and its mate in mesh (3-D), the mid-plane and the transmission error, the
    check's overlap and backlash, the trace's ratio."""
    from ...export import report as R
    from ...export.render import render
    from ...geometry.cross_mate import cross_pose, mate_pose

    cs, mate = spec.cross, spec.mate
    Tc, Tm = cross_pose(0.0, cs, mate, math.radians(-20.0)), mate_pose(0.0, cs, mate)
    (vc, fc), (vm, fm) = meshes["cross_gear"], meshes["cross_mate"]
    pic = render([(vc @ Tc[:3, :3].T + Tc[:3, 3], fc, COLOURS["cross_gear"]),
                  (vm @ Tm[:3, :3].T + Tm[:3, 3], fm, COLOURS["cross_mate"])], (520, 520), elev=20, azim=-60)
    html = (f'<div class="grid"><figure>{R.img(pic, "cross gear and mate")}<figcaption>the mate ({mate.teeth} teeth) '
            f"on the cross gear's pole, the cross gear tilted 20° about its ring axis (its free turn)</figcaption>"
            "</figure></div>")
    if "cross_mate.png" in files:
        html += R.img(files["cross_mate.png"], "mid-plane and transmission error")
    m = trace.stats.get("mate", {})
    if m:
        html += (f"<p>Ratio {m['ratio']:.9f} mate turns per cross-gear turn (design {m['ratio_design']:g}, off by "
                 f"{m['ratio_error']:.1e}), transmission error {m['te_pp_um']:.2f} µm peak to peak at the cross gear's "
                 f"pitch circle, backlash {m['backlash_mid_mm']:.3f} mm in the mid-plane.</p>")
    f = result.figures.get("mate")
    if f:
        html += (f'<p class="{"ok" if f["max_overlap_mm3"] <= f["epsilon_mm3"] else "fail"}">{f["poses"]} poses: largest '
                 f'overlap {f["max_overlap_mm3"]:.5f} mm³ (ε {f["epsilon_mm3"]:g} mm³).</p>'
                 + R.table(["mate turn ψ °", "cross gear tilt °", "backlash °", "backlash mm (mate pitch circle)"],
                           [[r["psi_deg"], r["tilt_deg"], r["backlash_deg"], r["backlash_mm"]] for r in f["backlash"]]))
    return html


def subtitle(spec: WristSpec) -> str:
    return f"wrist pair, I = {spec.I:g}"


def bill_text(spec: WristSpec, man: dict, dest, seconds: float) -> str:
    lines = [f"{p['name']:<8}{p['triangles']:>9} triangles {p['volume_mm3'] / 1000:8.2f} cm3 {p['mass_g']:7.1f} g  "
             f"{' x '.join(f'{x:.1f}' for x in p['bbox_mm'])} mm" for p in man["parts"]]
    lines.append(f"wrote {dest}/ in {seconds:.2f} s")
    return "\n".join(lines)


def assembly_steps(spec: WristSpec, kit) -> list[tuple[str, tuple[str, ...]]]:
    """Each gear pressed onto its D-shaft from its flat face, then brought into mesh."""
    have = {p.name for p in kit.parts}
    steps = [(f"Press gear1 onto a Ø{spec.shaft_diameter:g} mm D-shaft, the shaft entering its flat face, flat to "
              "flat.", ("gear1",)),
             ("Press gear2 onto the second shaft the same way; bring its sockets over gear1's dome teeth with the "
              "two spheres' centres together, and bend the pair through its workspace by hand.", ("gear2",))]
    if "cross_gear" in have:
        steps.append(("Press the cross gear onto its shaft by its flat face, the same way.", ("cross_gear",)))
    return steps
