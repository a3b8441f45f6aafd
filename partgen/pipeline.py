"""The whole job, layer by layer: config → design → geometry/assembly → export.

``load`` and ``build`` raise ``ConfigError`` (file + key path) for anything the user can fix; the
CLI turns those into exit code 2.
"""

from __future__ import annotations

import html
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .assembly.kit import Kit, build_kit
from .config.loader import load_design, read_yaml
from .config.yamlio import dump_yaml
from .config.resolve import resolve
from .design.drivetrain import Finding
from .design.mechanism import KitParams, Mechanism, synthesize
from .errors import ConfigError, DesignError
from .export.kit import write_kit
from .export.outputs import claim_output
from .geometry.measure import empty_parts, oversize

__all__ = ["Loaded", "load", "build", "design_summary", "oversize_parts"]


@dataclass(frozen=True)
class Loaded:
    path: Path
    mechanism: Mechanism
    params: KitParams
    printer_path: Path


def load(path: str | Path) -> Loaded:
    """Read, validate and synthesize a design; ConfigError for any user error."""
    loaded = load_design(path)
    inputs, params = resolve(loaded)
    try:
        mech = synthesize(inputs, params)
    except DesignError as e:
        key = e.key_path
        if inputs.source == "curve" and key.startswith("links"):  # a curve design has no link table
            key = "curve"
        raise ConfigError(loaded.path, key, e.problem) from None
    return Loaded(loaded.path, mech, params, loaded.printer_path)


def _size_key(kit: Kit, name: str) -> str:
    mech = kit.mechanism
    if name.startswith("B"):
        j = int(name[1:])
        return "curve.scale_mm_per_unit" if mech.source == "curve" else f"links[{j - 1}].length_mm"
    if name in ("G1", "drive"):
        return "drive.teeth"
    if name[0] in "DMG" and name[1:].isdigit():
        j = int(name[1:]) - (1 if name[0] == "G" else 0)
        return "teeth" if mech.auto_teeth else f"teeth[{j - 1}].{name[0]}"
    return {"base": "base", "crank": "base.crank_radius_mm", "pen_holder": "pen"}.get(name, name)


def oversize_parts(kit: Kit) -> list[tuple[str, str, np.ndarray]]:
    """Parts whose extents (any axis order) exceed the printer envelope: (name, key, extents)."""
    return [(p.name, _size_key(kit, p.name), ext) for p, ext in oversize(kit.parts, kit.params.printer.envelope)]


def design_summary(loaded: Loaded, kit: Kit) -> dict:
    """The manifest's "design" entry: chain, stages, drive, stack, findings."""
    mech, params = loaded.mechanism, loaded.params
    r6 = lambda x: float(round(float(x), 6))
    return {
        "name": params.name,
        "config": loaded.path.name,
        "printer": params.printer.name,
        "material": params.material,
        "density_g_cm3": r6(params.density * 1000),
        "crank_angle_rad": 0.0,
        "module_mm": params.system.module,
        "pressure_angle_deg": r6(math.degrees(params.system.pressure_angle)),
        "teeth_mode": "auto" if mech.auto_teeth else "explicit",
        "ground_offset_mm": [r6(mech.chain.offset.real), r6(mech.chain.offset.imag)],
        "links": [{"j": j, "name": l.name, "speed": l.speed, "length_mm": r6(l.length),
                   "initial_angle_deg": r6(math.degrees(l.phase))} for j, l in enumerate(mech.chain.links, 1)],
        "stages": [{"j": s.j, "ratio": str(s.ratio), "teeth": {"D": s.D.teeth, "M": s.M.teeth, "G": s.G.teeth},
                    "profile_shift": {"D": r6(s.D.profile_shift), "M": r6(s.M.profile_shift), "G": r6(s.G.profile_shift)},
                    "a_DM_mm": r6(s.a_DM), "a_MG_mm": r6(s.a_MG),
                    "idler_mm": [r6(s.idler[0]), r6(s.idler[1])]} for s in mech.stages],
        "drive": {"teeth": mech.drive.teeth, "centre_mm": [r6(c) for c in mech.drive_centre]},
        "stack_mm": {"axial_gap": kit.stack.gap, "face_width": kit.stack.face, "plate": kit.stack.plate,
                     "layers": [r6(kit.stack.layer(j)) for j in range(len(mech.stages) + 1)],
                     "plates": [r6(kit.stack.plate_z(j)) for j in range(1, len(mech.chain.links) + 1)]},
        "findings": [finding_dict(f) for f in mech.findings],
    }


def finding_dict(f: Finding) -> dict:
    return {"severity": f.severity, "code": f.rule, "key": f.key, "message": f.message}


def output_claim(raw, dest, kind: str, default_sub: str | None, option: str, notify=None):
    """Claim the output folder of a command before any work: ``dest`` or out/<name>[/<sub>]."""
    if dest is None:
        dest = Path("out") / raw.design.name / default_sub if default_sub else Path("out") / raw.design.name
    return claim_output(dest, kind, option, (raw.path, raw.printer_path), notify)


def build(path: str | Path, dest: str | Path | None = None, progress=None, notify=None) -> tuple[Loaded, Kit, dict, Path]:
    """Build the kit of a design into ``dest`` (default out/<name>/). Returns what it made."""
    raw = load_design(path)
    claim = output_claim(raw, dest, "kit", None, "-o", notify)
    if raw.design.__class__.__name__ == "WristDesign":
        return build_wrist_kit(raw, claim, progress)
    if raw.design.__class__.__name__ == "BennettDesign":
        from .pipeline_bennett import build_bennett_kit
        return build_bennett_kit(raw, claim, progress)
    loaded = load(path)
    try:
        kit = build_kit(loaded.mechanism, loaded.params, progress)
    except DesignError as e:
        raise ConfigError(loaded.path, e.key_path, e.problem) from None
    for part in empty_parts(kit.parts):
        raise ConfigError(loaded.path, _size_key(kit, part.name), f"part {part.name} comes out empty: a size in the "
                          "design leaves it no material")
    big = oversize_parts(kit)
    if big:
        name, key, ext = big[0]
        env = " × ".join(f"{x:g}" for x in loaded.params.printer.envelope)
        raise ConfigError(loaded.path, key, f"part {name} measures {' × '.join(f'{x:.1f}' for x in ext[::-1])} mm "
                          f"and does not fit the printer's {env} mm envelope in any orientation"
                          + (f" (and {len(big) - 1} more parts)" if len(big) > 1 else ""))
    man = write_kit(kit, claim, design_summary(loaded, kit), design_files(loaded), progress=progress)
    return loaded, kit, man, claim.dest


def design_files(loaded: Loaded) -> dict[str, bytes]:
    """The design and its printer profile, as a kit folder keeps them (so `check KITDIR` can
    re-derive the kit): design.yaml names printer.yaml beside it."""
    data = read_yaml(loaded.path)
    data["printer"] = "printer.yaml"
    return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(read_yaml(loaded.printer_path))}


def check(target: str | Path, samples: int | None = None, progress=None, plates_dir: str | Path | None = None,
          write_plates: bool = True, notify=None):
    """Check a design (CONFIG) or a built kit (KITDIR, re-derived from its design.yaml and compared
    byte for byte). Lays the parts out on build plates and writes a 3MF and a picture per plate.
    Returns (Loaded, Kit, Result, plates folder or None)."""
    from .core.findings import Finding
    from .checks.run import check_kit
    from .export.kit import atomic_dir, group_parts, printed
    from .export.plates import plate_3mf

    target = Path(target)
    kit_dir = target if target.is_dir() else None
    raw = load_design(target / "design.yaml" if kit_dir else target)
    claim = None
    if write_plates and raw.design.__class__.__name__ not in ("WristDesign", "BennettDesign"):
        claim = output_claim(raw, Path(plates_dir) if plates_dir else (kit_dir / "plates" if kit_dir else None),
                             "plates", "plates", "--plates", notify)
    if raw.design.__class__.__name__ == "WristDesign":
        return check_wrist_design(raw, progress)
    if raw.design.__class__.__name__ == "BennettDesign":
        from .pipeline_bennett import check_bennett_design
        return check_bennett_design(raw, kit_dir)
    loaded = load(target / "design.yaml" if kit_dir else target)
    try:
        kit = build_kit(loaded.mechanism, loaded.params)
    except DesignError as e:
        raise ConfigError(loaded.path, e.key_path, e.problem) from None
    result = check_kit(kit, samples, progress)
    groups = group_parts([printed(p) for p in kit.parts if p.printed])
    if kit_dir is not None:
        stale = [f"{g[0].part.name}.stl" for g in groups
                 if not (kit_dir / f"{g[0].part.name}.stl").is_file()
                 or (kit_dir / f"{g[0].part.name}.stl").read_bytes() != g[0].stl]
        if stale:
            result.add(Finding("kit", "fail", f"{len(stale)} STL files in {kit_dir} are missing or differ from what its "
                               f"design.yaml builds ({', '.join(stale[:4])}{' …' if len(stale) > 4 else ''}): rebuild it",
                               tuple(s[:-4] for s in stale)))
    lay, picture = plan_plates(loaded, groups, result)
    folder = None
    if lay is not None and claim is not None:
        meshes = {g[0].part.name: g[0].mesh for g in groups}
        folder = claim.dest
        with atomic_dir(claim) as tmp:
            pr, n = loaded.params.printer, len(lay.plates)
            for i, plate in enumerate(lay.plates, 1):
                (tmp / f"plate{i}.3mf").write_bytes(plate_3mf(plate, meshes, loaded.params.name, loaded.params.material,
                                                              f"build plate {i} of {n} for the {pr.name} "
                                                              f"({lay.size[0]:g} x {lay.size[1]:g} mm)"))
            picture(tmp / "plates.png")
    return loaded, kit, result, folder


def plan_plates(loaded: Loaded, groups, result):
    """Pack the printed parts on build plates; adds a finding if one cannot fit. Returns the
    layout (or None) and a function that draws it to a PNG path."""
    from .core.findings import Finding
    from .export.plates import footprint, layout, plate_picture

    env = loaded.params.printer.envelope
    margin = loaded.params.checks.plate_margin
    meshes = {g[0].part.name: g[0].mesh for g in groups}
    try:
        lay = layout([(g[0].part.name, g[0].mesh, len(g)) for g in groups], (env[0], env[1]), margin)
    except ValueError as e:
        result.add(Finding("printability", "fail", f"build plates: {e}", getattr(e, "parts", ())))
        return None, None
    result.figures["plates"] = len(lay.plates)

    def picture(path):
        plate_picture(lay, {n: footprint(m, margin) for n, m in meshes.items()}, path,
                      f"{loaded.params.name}: {len(lay.plates)} build plate(s), {env[0]:g} × {env[1]:g} mm")
    return lay, picture


def trace_design(path: str | Path, samples: int = 3600, plots_dir: str | Path | None = None, animate: bool = True):
    """Trace the pen of a design as built over one crank turn and compare it with its targets.

    Returns (Loaded, theta (n,), pen (n,) complex mm, stats dict, plots folder or None)."""
    from .design.synthesis import trace as trace_chain
    from .design.trace import built_chain, built_speeds, deviation, target_paths
    from .export.kit import atomic_dir
    from .export.trace_plots import trace_animation, trace_figure

    raw = load_design(path)
    if plots_dir is not False:
        plots_dir = output_claim(raw, plots_dir, "trace", "trace", "--plots")
    if raw.design.__class__.__name__ == "WristDesign":
        return trace_wrist(raw, plots_dir)
    if raw.design.__class__.__name__ == "BennettDesign":
        raise ConfigError(raw.path, "kind", "a bennett_butterfly draws no curve to trace: `partgen report` draws its "
                          "poses and its centre-of-mass trace")
    loaded = load(path)
    mech = loaded.mechanism
    theta = 2 * np.pi * np.arange(samples) / samples
    pen = trace_chain(built_chain(mech), theta)
    targets = target_paths(mech, theta)
    speeds = built_speeds(mech)
    stats = {"samples": samples, "speeds": [str(w) for w in speeds],
             "closes_after_one_turn": all(w.denominator == 1 for w in speeds),
             "vs_pruned": deviation(pen, targets["pruned"], theta).to_dict()}
    if "full" in targets:
        stats.update(deviation(pen, targets["full"], theta).to_dict())
        stats["pruned_vs_full"] = deviation(targets["pruned"], targets["full"], theta).to_dict()
    folder = None
    if plots_dir is not False:
        folder = plots_dir.dest
        with atomic_dir(plots_dir) as tmp:
            head = {k: v for k, v in stats.items() if k.endswith("_mm")} or \
                {k: v for k, v in stats["vs_pruned"].items() if k.endswith("_mm")}
            if "worst_theta_rad" in stats:
                head["worst_theta_rad"] = stats["worst_theta_rad"]
            trace_figure(mech, head, tmp / "trace.png", tmp / "trace.svg",
                         f"{loaded.params.name}: the pen over one crank turn (mm)")
            if animate:
                trace_animation(mech, tmp / "trace.gif")
    return loaded, theta, pen, stats, folder


def report(path: str | Path, dest: str | Path | None = None, samples: int | None = None, progress=None) -> Path:
    """Write DIR/index.html (default out/<name>/report/): one self-contained page with the design,
    the bill of parts with pictures, the stacking, the trace, the check and the build plates."""
    import math
    import tempfile

    from .design.trace import built_speeds
    from .export import report as R
    from .export.kit import atomic_dir
    from .export.plots import ROLE_COLOURS, stack_section
    from .export.render import render

    say = progress or (lambda step: None)
    raw = load_design(path)
    dest = output_claim(raw, dest, "report", "report", "-o")
    if raw.design.__class__.__name__ == "WristDesign":
        return report_wrist(raw, dest, say)
    if raw.design.__class__.__name__ == "BennettDesign":
        from .pipeline_bennett import report_bennett
        return report_bennett(raw, dest, say)
    say("check")
    loaded, kit, result, _ = check(path, samples, write_plates=False)
    mech, params = loaded.mechanism, loaded.params
    from .export.kit import group_parts, printed
    groups = group_parts([printed(p) for p in kit.parts if p.printed])
    with tempfile.TemporaryDirectory() as tmpdir:
        tmp = Path(tmpdir)
        say("trace")
        _, _, _, stats, tdir = trace_design(path, 3600, tmp / "trace")
        trace_png, trace_gif = (tdir / "trace.png").read_bytes(), (tdir / "trace.gif").read_bytes()
        say("stacking")
        stack_section(kit, tmp / "stack.png")
        stack_png = (tmp / "stack.png").read_bytes()
        _, picture = plan_plates(loaded, groups, result)
        plates_png = None
        if picture is not None:
            picture(tmp / "plates.png")
            plates_png = (tmp / "plates.png").read_bytes()
    say("pictures")
    pics = {}
    for g in groups:
        m = g[0].mesh
        pics[g[0].part.name] = render([(m.vertices, m.faces, ROLE_COLOURS.get(g[0].part.role, "#999"))], (300, 240))
    poses = kit.poses(0.0)
    scene = []
    for g in groups:
        for it in g:
            T = poses[it.part.name] @ it.local_from_print
            scene.append((g[0].mesh.vertices @ T[:3, :3].T + T[:3, 3], g[0].mesh.faces, ROLE_COLOURS.get(it.part.role, "#999")))
    assembly_png = render(scene, (1100, 720), elev=35, azim=-70)

    r6 = lambda x: round(float(x), 3)  # noqa: E731
    speeds = built_speeds(mech)
    links = [[j, l.name, l.speed, r6(l.length), r6(math.degrees(l.phase)), str(w)]
             for j, (l, w) in enumerate(zip(mech.chain.links, speeds), 1)]
    stages = [[s.j, str(s.ratio), f"{s.D.teeth} / {s.M.teeth} / {s.G.teeth}",
               f"{s.D.profile_shift:.3f} / {s.M.profile_shift:.3f} / {s.G.profile_shift:.3f}",
               r6(s.a_DM), r6(s.a_MG), f"({s.idler[0]:.2f}, {s.idler[1]:.2f})"] for s in mech.stages]
    belts = [[s.j, str(s.ratio), f"{s.D.teeth} / {s.G.teeth}", s.belt_teeth, r6(s.slack),
              "–" if s.tensioner is None else f"({s.tensioner[0]:.2f}, {s.tensioner[1]:.2f})", r6(s.link_change)]
             for s in mech.belt_stages]
    design = (R.table(["link", "name", "speed", "length mm", "initial angle °", "speed as built"], links, left=2)
              + (R.table(["stage", "Eq 11 ratio", "teeth D / M / G", "profile shift D / M / G", "a_DM mm", "a_MG mm",
                          "idler (link frame) mm"], stages, left=1) if stages else "")
              + (R.table(["stage", "Eq 11 ratio", "pulley teeth D / G", "belt teeth", "slack taken up mm",
                          "tensioner (link frame) mm", "link change mm"], belts, left=1) if belts else "")
              + f"<p>Module {params.system.module:g} mm, pressure angle {math.degrees(params.system.pressure_angle):g}°, "
              f"backlash {params.system.backlash_per_gear:g} mm per gear, face width {params.face_width:g} mm, "
              f"printer {html.escape(params.printer.name)}, material {html.escape(params.material)}.</p>")
    rows = []
    density = params.density
    for g in groups:
        p, m = g[0].part, g[0].mesh
        gear = p.gear
        rows.append([R.img(pics[p.name], p.name), p.name, p.role, len(g), " × ".join(f"{x:.1f}" for x in m.extents),
                     r6(m.volume / 1000), r6(m.volume * density),
                     f"{gear.teeth} t, x = {gear.profile_shift:.3f}" if gear else ""])
    total = sum(len(g) * g[0].mesh.volume * density for g in groups)
    parts_html = (f'<figure>{R.img(assembly_png, "assembly at crank angle 0")}<figcaption>The assembly at crank '
                  f"angle 0 ({sum(len(g) for g in groups)} parts, {total:.0f} g).</figcaption></figure>"
                  f'<div class="parts">' + R.table(["picture", "part", "role", "count", "size mm (as printed)",
                                                    "volume cm³", "mass g", "gear"], rows, left=3, raw={0}) + "</div>")
    stack_html = f'<figure>{R.img(stack_png, "section through the joints")}<figcaption>True section through the ' \
                 "joints, links straightened.</figcaption></figure>"
    dev = [["the full Fourier series", stats.get("max_deviation_mm", "–"), stats.get("rms_mm", "–"),
            stats.get("hausdorff_mm", "–")],
           ["the design's chain (pruned)", stats["vs_pruned"]["max_deviation_mm"], stats["vs_pruned"]["rms_mm"],
            stats["vs_pruned"]["hausdorff_mm"]]]
    trace_html = (R.table(["traced (as built) vs", "max, same θ (mm)", "rms (mm)", "Hausdorff (mm)"], dev)
                  + f'<div class="grid"><figure>{R.img(trace_png, "trace", width=640)}</figure>'
                  f'<figure>{R.img(trace_gif, "animation", "image/gif", width=440)}<figcaption>One crank turn.'
                  "</figcaption></figure></div>")
    fails = [[f.check, f'<span class="{f.severity}">{f.severity}</span>', html.escape(f.message),
              "" if f.theta is None else f"{math.degrees(f.theta):.1f}"] for f in result.findings]
    fig = result.figures
    close = fig["motion"].get("closest_approach")
    summary = (f'<p class="{"ok" if result.ok else "fail"}">{"Every check holds" if result.ok else "The kit fails its checks"}'
               f" — {fig['samples']} crank angles, {fig['pairs']} part pairs, {len(fig['meshes'])} meshes, "
               f"{fig['fits']['count']} fits; closest approach "
               + (f"{close['mm']:.3f} mm ({close['parts'][0]}–{close['parts'][1]})" if close else "–")
               + f"; {fig.get('plates', '?')} build plate(s).</p>")
    mesh_rows = [[" / ".join(r["pair"]), " / ".join(map(str, r["teeth"])), r["centre_distance_mm"], r["backlash_mm"],
                  r["measured_backlash_mm"], r["contact_ratio"]] for r in fig["meshes"]]
    check_html = (summary + (R.table(["check", "severity", "finding", "crank °"], fails, left=3, raw={1}) if fails else "")
                  + R.table(["mesh", "teeth", "centre distance mm", "backlash mm", "measured mm", "contact ratio"],
                            mesh_rows)
                  + (f"<figure>{R.img(plates_png, 'build plates')}</figure>" if plates_png else ""))
    sections = [("Design", design), ("Bill of parts", parts_html), ("Stacking", stack_html), ("Trace", trace_html),
                ("Check", check_html)]
    out = dest.dest
    with atomic_dir(dest) as tmp:
        (tmp / "index.html").write_text(R.page(f"partgen report: {params.name}", sections,
                                               f"{loaded.path.name} — {mech.stages and len(mech.chain.links)} links"),
                                        encoding="utf-8")
    return out



def build_wrist_kit(raw, dest=None, progress=None):
    """Build a wrist gear pair (kind: wrist) into ``dest``: gear1.stl, gear2.stl, manifest, GLB."""
    from .assembly.wrist import build_wrist
    from .config.wrist import resolve_wrist
    from .design.spherical import RangeError

    spec = resolve_wrist(raw)
    try:
        kit = build_wrist(spec, progress)
    except (RangeError, ValueError) as e:
        raise ConfigError(raw.path, "wrist", str(e)) from None
    for p, ext in oversize(kit.parts, spec.printer.envelope):
        raise ConfigError(raw.path, "wrist.centre_distance_mm", f"{p.name} measures {ext.round(1)} mm and does not "
                          "fit the printer in any orientation")
    loaded = Loaded(raw.path, None, kit.params, raw.printer_path)
    design = {"name": spec.name, "kind": "wrist", "config": raw.path.name, "nominal_ratio": spec.I,
              "centre_distance_mm": spec.A, "longitudinal_pitch_mm": spec.long_pitch, **kit.figures}
    man = write_kit(kit, dest, design, design_files(loaded), progress=progress)
    return loaded, kit, man, dest.dest

def check_wrist_design(raw, progress=None):
    """`partgen check` of a wrist pair: the workspace sweep, engagement and play."""
    from .assembly.wrist import build_wrist
    from .checks.wrist import check_wrist
    from .config.wrist import resolve_wrist

    spec = resolve_wrist(raw)
    kit = build_wrist(spec)
    result = check_wrist(kit, progress=progress)
    return Loaded(raw.path, None, kit.params, raw.printer_path), kit, result, None


def trace_wrist(raw, plots_dir=None):
    """The wrist pair's ratio, mating angle and meridians (plots) and its tooth-row figures."""
    from .assembly.wrist import workspace_theta_max
    from .config.wrist import resolve_wrist
    from .design import spherical as sph
    from .export.kit import atomic_dir
    from .export.wrist_plots import wrist_figure

    spec = resolve_wrist(raw)
    pair = sph.tooth_rows(spec.I, spec.A, spec.long_pitch, spec.ring_teeth)
    theta_max = workspace_theta_max(spec.I, spec.max_bend)
    end = sph.valid_end(spec.I)
    ts, i_ode = sph.ratio_ode(end, spec.I, 2000)
    t = np.linspace(0, end, 2001)
    stats = {"kind": "wrist", "nominal_ratio": spec.I, "valid_end_deg": round(float(np.degrees(end)), 6),
             "workspace_theta_max_deg": round(float(np.degrees(theta_max)), 6),
             "ode_vs_closed_form_max": float(np.abs(i_ode - sph.ratio(ts, spec.I)).max()),
             "mating_angle_methods_max_rad": float(np.abs(sph.mating_angle_meridian(t, spec.I)
                                                           - sph.mating_angle_latitude(t, spec.I)).max()),
             "rows": [{"k": r.k, "teeth": r.teeth, "theta_deg": round(float(np.degrees(r.theta)), 4),
                       "phi_deg": round(float(np.degrees(r.phi)), 4), "lat_pitch_mm": round(r.lat_pitch_1, 4),
                       "lat_pitch_off": round(r.lat_pitch_1 / spec.long_pitch - 1, 5) if r.k else None} for r in pair.rows]}
    folder = None
    if plots_dir is not False:
        claim = atomic_dir(plots_dir, "trace", "--plots")
        folder = claim.dest
        with claim as tmp:
            wrist_figure(spec.I, spec.A, theta_max, pair.rows, tmp / "wrist.png", tmp / "wrist.svg",
                         f"{spec.name}: I = {spec.I:g}, centre distance {spec.A:g} mm")
    from .assembly.wrist import WristParams
    loaded = Loaded(raw.path, None, WristParams(spec.name, spec.density, spec.material, spec.printer), raw.printer_path)
    return loaded, t, None, stats, folder

def report_wrist(raw, dest=None, say=lambda step: None) -> Path:
    """The report page of a wrist pair: its math (like the paper's figures), pictures of the gears
    and of the pair bent, the check over the workspace with the play."""
    import math
    import tempfile

    from .assembly.wrist import build_wrist
    from .checks.wrist import check_wrist
    from .config.wrist import resolve_wrist
    from .design import spherical as sph
    from .export import report as R
    from .export.kit import atomic_dir
    from .export.render import render
    from .geometry.solid import mesh_arrays

    spec = resolve_wrist(raw)
    say("build")
    kit = build_wrist(spec)
    say("check")
    result = check_wrist(kit)
    with tempfile.TemporaryDirectory() as tmpdir:
        say("trace")
        _, _, _, stats, folder = trace_wrist(raw, Path(tmpdir) / "trace")
        math_png = (folder / "wrist.png").read_bytes()
    say("pictures")
    colours = {"gear1": "#4c78a8", "gear2": "#f58518", "cross_gear": "#54a24b"}
    meshes = {p.name: mesh_arrays(p.solid) for p in kit.parts}
    pics = [f"<figure>{R.img(render([(v, f, colours[n])], (320, 300), elev=35, azim=-55), n)}<figcaption>{n}"
            f"</figcaption></figure>" for n, (v, f) in meshes.items()]
    T = kit.pose2(kit.theta_max * 0.8, 0.6)
    v2, f2 = meshes["gear2"]
    bent = render([(*meshes["gear1"], colours["gear1"]), (v2 @ T[:3, :3].T + T[:3, 3], f2, colours["gear2"])], (520, 520),
                  elev=12, azim=-30)
    pics.append(f"<figure>{R.img(bent, 'bent')}<figcaption>the pair bent by "
                f"{math.degrees(0.8 * kit.theta_max + float(sph.mating_angle(0.8 * kit.theta_max, spec.I))):.0f}°"
                "</figcaption></figure>")
    rows = [[r["k"], r["teeth"], r["theta_deg"], r["phi_deg"], r["lat_pitch_mm"],
             "–" if r["lat_pitch_off"] is None else f"{100 * r['lat_pitch_off']:+.2f} %"] for r in stats["rows"]]
    design = (R.table(["ring", "teeth", "θ on gear 1 °", "φ on gear 2 °", "latitudinal pitch mm", "vs longitudinal"], rows)
              + f"<p>Nominal ratio I = {spec.I:g}, centre distance {spec.A:g} mm, longitudinal pitch {spec.long_pitch:g} mm, "
              f"dome teeth r = {spec.dome_radius:g} mm standing {spec.tooth_height:g} mm proud, sockets cut with "
              f"{spec.clearance:g} mm clearance over bends ≤ {math.degrees(spec.max_bend):g}°. The ratio ODE agrees with its "
              f"closed form tan(φ/2) = I tan(θ/2) to {stats['ode_vs_closed_form_max']:.1e}; its valid range ends at "
              f"θ = {stats['valid_end_deg']:.2f}°.</p>")
    f = result.figures
    play = [[p["theta_deg"], p["twist_play_deg"], p["bend_play_deg"]] for p in f["play"]]
    check_html = (f'<p class="{"ok" if result.ok else "fail"}">{f["poses"]} poses: largest overlap {f["max_overlap_mm3"]:.4f} mm³, '
                  f"least engaged tooth volume {f['min_engaged_mm3']:.2f} mm³.</p>"
                  + R.table(["θ on gear 1 °", "twist play °", "bend play °"], play)
                  + "<p>Twist play is large: domes resist a twist about the line of centres only through the teeth "
                  "beside the contact, and near the pole the contact tooth sits on that axis.</p>")
    sections = [("Design", design), ("Math", R.img(math_png, "ratio, mating angle, meridians")),
                ("Parts", f'<div class="grid">{"".join(pics)}</div>'), ("Check", check_html)]
    out = dest.dest
    with atomic_dir(dest) as tmp:
        (tmp / "index.html").write_text(R.page(f"partgen report: {spec.name}", sections, raw.path.name), encoding="utf-8")
    return out
