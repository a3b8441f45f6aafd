"""`partgen build / check / report` for a balanced Bennett butterfly (``kind: bennett_butterfly``)."""

from __future__ import annotations

import html
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .assembly import bennett as A
from .config.bennett import resolve_bennett
from .config.loader import LoadedDesign, read_yaml
from .config.yamlio import dump_yaml
from .errors import ConfigError, DesignError

__all__ = ["BennettLoaded", "build_bennett_kit", "check_bennett_design", "bill", "report_bennett"]


@dataclass(frozen=True)
class BennettLoaded:
    """What the CLI needs to know of a loaded Bennett design (mirrors pipeline.Loaded)."""

    path: Path
    printer_path: Path
    params: object
    mechanism: None = None
    kind: str = "bennett_butterfly"


def _kit(raw: LoadedDesign, progress=None) -> tuple[BennettLoaded, A.BennettKit]:
    p = resolve_bennett(raw)
    try:
        kit = A.build_bennett(p, progress)
    except DesignError as e:
        raise ConfigError(raw.path, e.key_path or "counterweights", e.problem) from None
    return BennettLoaded(raw.path, raw.printer_path, p), kit


def layout_yaml(kit: A.BennettKit) -> dict:
    """The kit's stack layout as the config's ``parts.layout`` (so a kit folder rebuilds without a search)."""
    return {"layers": {i: int(kit.layout.layer[i]) for i in range(1, 13)},
            "shifts_mm": {j: float(v) for j, v in sorted(kit.layout.shift.items()) if v}}


def bill(kit: A.BennettKit) -> list[dict]:
    """Every part with its masses (g): solid, as printed (FDM), counterweight fill; pins and fill bought."""
    p = kit.params
    rows = []
    for i, lm in kit.masses.items():
        rows.append({"part": f"link{i:02d}", "layer": kit.layout.layer[i], "solid_g": lm.solid_mass,
                     "printed_g": lm.fdm_mass, "fill_g": kit.fill["fdm"].get(i, 0.0),
                     "pins_g": sum(m for m, _ in kit.pins[i])})
    for part in kit.parts:
        if part.role == "pin":
            info = dict(part.info)
            rows.append({"part": part.name, "layer": None, "solid_g": None, "printed_g": None, "fill_g": 0.0,
                         "pins_g": p.pin_density * math.pi * p.pin_radius ** 2 * info["length_mm"],
                         "bought": f"{p.pin_radius * 2:g} × {info['length_mm']:.1f} mm {info['material']}"})
    return rows


def build_bennett_kit(raw: LoadedDesign, dest=None, progress=None):
    """Build the kit into ``dest`` (default out/<name>/): STLs, manifest (with the bill of masses and
    the chosen layout), GLB, and the design with its layout pinned."""
    from .export.kit import write_kit
    from .geometry.measure import oversize

    loaded, kit = _kit(raw, progress)
    p = kit.params
    for part, ext in oversize(kit.parts, p.printer.envelope, tol=0.0):
        raise ConfigError(raw.path, "linkage.a_mm", f"{part.name} measures {ext.round(1)} mm and does not fit "
                          "the printer in any orientation")
    data = read_yaml(raw.path)
    data["printer"] = "printer.yaml"
    data.setdefault("parts", {})["layout"] = layout_yaml(kit)
    files = {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(read_yaml(raw.printer_path))}
    design = {"name": p.name, "kind": "bennett_butterfly", "config": raw.path.name,
              "a_mm": p.bb.a, "b_mm": p.bb.b, "alpha_deg": math.degrees(p.bb.alpha),
              "beta_deg": math.degrees(p.bb.beta),
              "scales": [1.0, p.bb.s2, p.bb.s3, p.bb.s4], "home_angle_deg": math.degrees(p.home),
              "workspace_deg": [math.degrees(x) for x in p.workspace], "layout": layout_yaml(kit),
              "counterweights": {f"link{i:02d}": {"fill_g": kit.fill["fdm"][i], "fill": p.fill_name,
                                                  "pocket_offset_mm": kit.figures["pocket_offsets_mm"][i]}
                                 for i in p.cw_links},
              "bill": bill(kit), "infill_percent": 100 * p.infill, **{k: v for k, v in kit.figures.items()
                                                                     if k not in ("pocket_offsets_mm",)}}
    man = write_kit(kit, dest, design, files, progress=progress)
    return loaded, kit, man, dest.dest


def check_bennett_design(raw: LoadedDesign, kit_dir: Path | None = None):
    """Balance over the input grid, interference over the workspace, stacks, pockets, printer fit;
    for a kit folder also that its STLs are what its design.yaml builds."""
    from .checks.bennett import check_bennett
    from .checks.findings import Finding
    from .export.kit import printed

    loaded, kit = _kit(raw)
    result = check_bennett(kit)
    if kit_dir is not None:
        stale = [p.name for p in kit.parts if p.printed and (not (kit_dir / f"{p.name}.stl").is_file()
                                                           or (kit_dir / f"{p.name}.stl").read_bytes() != printed(p).stl)]
        if stale:
            result.add(Finding("kit", "fail", f"{len(stale)} STL files in {kit_dir} are missing or differ from what its "
                               f"design.yaml builds ({', '.join(stale[:4])}{' …' if len(stale) > 4 else ''}): rebuild it",
                               tuple(stale)))
    return loaded, kit, result, None


def report_bennett(raw: LoadedDesign, dest=None, say=lambda step: None) -> Path:
    """One page: the design, the linkage at a few poses (planar and spatial), the assembled kit, the
    balance (centre-of-mass trace under each mass model), the interference sweep, the bill of parts."""
    from .checks.bennett import check_bennett
    from .export import report as R
    from .export.bennett_plots import com_figure, poses_figure
    from .export.kit import atomic_dir
    from .export.render import render
    from .geometry.solid import mesh_arrays

    say("build")
    loaded, kit = _kit(raw)
    p = kit.params
    say("check")
    result = check_bennett(kit)
    f, b = result.figures, result.figures["balance_mm"]
    say("pictures")
    lo, hi = (math.degrees(x) for x in p.workspace)
    poses = poses_figure(p.bb, [lo, math.degrees(p.home), hi])
    ang = np.linspace(lo, hi, p.grid[1])
    labels = {"fdm": "as printed (FDM model), weights sized for it", "solid": "solid model (fills re-sized for it)",
              "fdm_infill_error": f"infill {100 * p.infill:g} → {100 * (p.infill + p.infill_error):g} %",
              "solid_weights_printed_fdm": "weights sized for solid parts, printed FDM",
              "what_if_mass_scale": f"what-if heavier links {dict(p.mass_scale)}"}
    com = com_figure(ang, f["balance_trace_mm"], p.tolerance, labels)
    placed = kit.poses(0.0)
    meshes = []
    for part in kit.parts:
        if part.role == "pin":
            continue
        v, fc = mesh_arrays(part.solid)
        T = placed[part.name]
        colour = "#bbbbbb" if part.name == "base" else ("#f58518" if part.name in
                                                        {f"link{i:02d}" for i in p.cw_links} else "#4c78a8")
        meshes.append((v @ T[:3, :3].T + T[:3, 3], fc, colour))
    kit_png = render(meshes, (640, 560), elev=30, azim=-60)
    top_png = render(meshes, (640, 560), elev=89, azim=-90)
    def g(x):
        return "" if not x else f"{x:.1f}"
    rows = [[r["part"], "–" if r["layer"] is None else r["layer"], r.get("bought", "printed"), g(r["solid_g"]),
             g(r["printed_g"]), g(r["fill_g"]), g(r["pins_g"])] for r in bill(kit)]
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
    balance = (f'<p class="{"ok" if result.ok else "fail"}">Worst distance of the common centre of mass from S over a '
               f"{p.grid[0]} × {p.grid[1]} grid (q1 over a turn × the workspace): as printed {b['fdm']:.4f} mm; the "
               f"solid model, fills re-sized for it {b['solid']:.4f} mm; infill {100 * p.infill_error:g} points off "
               f"{b['fdm_infill_error']:.3f} mm; counterweights sized for solid parts {b['solid_weights_printed_fdm']:.3f} mm"
               + (f"; what-if heavier links {b['what_if_mass_scale']:.3f} mm" if "what_if_mass_scale" in b else "")
               + f" (tolerance {p.tolerance:g} mm).</p>" + R.img(com, "centre of mass trace"))
    interference = (f"<p>{f['interference_samples']} shape angles at {f['step_deg']:.2f}° steps: the fastest point "
                    f"moves {f['fastest_point_mm_per_rad']:.0f} mm per radian, so no point moves more than a bar's radius "
                    f"({p.bar_radius:g} mm) between samples. Least clearance {f['least_clearance_mm']:.2f} mm "
                    f"({' – '.join(f['least_clearance_parts'])}, capsule hulls); stacked bosses measured exactly: "
                    f"{f['joint_stack_overlap_mm3']:.3f} mm³ overlap. Free from {f['free_range_deg'][0]:.1f}° to "
                    f"{f['free_range_deg'][1]:.1f}°.</p>"
                    + "".join(f"<p class='fail'>{x.check}: {html.escape(x.message)}</p>" for x in result.findings
                              if x.severity == "fail"))
    sections = [("Design", design), ("Poses", R.img(poses, "poses")),
                ("Kit", f'<div class="grid"><figure>{R.img(kit_png, "kit")}<figcaption>at home</figcaption></figure>'
                        f'<figure>{R.img(top_png, "kit from above")}<figcaption>from above</figcaption></figure></div>'),
                ("Balance", balance), ("Interference", interference),
                ("Bill of parts", R.table(["part", "layer", "kind", "solid g", "printed g", "fill g", "pins g"], rows))]
    out = dest.dest
    with atomic_dir(dest) as tmp:
        (tmp / "index.html").write_text(R.page(f"partgen report: {p.name}", sections, raw.path.name), encoding="utf-8")
    return out
