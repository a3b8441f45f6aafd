"""The gear chain (``kind: gear_chain``, with its belt variant) behind the Mechanism protocol: a
Fourier linkage whose links are turned by gear (or belt) stages, drawn by a pen."""

from __future__ import annotations

import html
import math
from pathlib import Path

import numpy as np

from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.findings import Result
from ...core.protocol import Motion, Trace
from ...errors import ConfigError, DesignError
from ...geometry.measure import empty_parts, oversize
from .kit import Kit, build_kit
from .resolve import ChainSpec, resolve_spec
from .schema import Design

__all__ = ["GearChain", "MECHANISM"]

CSV_HEADER = "theta_rad,x_mm,y_mm\n"
ROLE_COLOURS = {"gear": "#4c78a8", "link": "#f58518", "base": "#8c8c8c", "leg": "#b0b0b0", "axle": "#54a24b",
                "crank": "#e45756", "pen_holder": "#b279a2", "pulley": "#4c78a8", "idler": "#72b7b2"}


BED_RULES = ("bed-contact", "shells", "bore-open", "needs-supports")  # checks.bed and checks.bores


def _r6(x) -> float:
    return float(round(float(x), 6))


def size_key(spec: ChainSpec, name: str) -> str:
    """The config key a part's size traces back to."""
    mech = spec.mechanism
    if name.startswith("B"):
        j = int(name[1:])
        return {"curve": "curve.scale_mm_per_unit", "drawing": "curve.scale"}.get(mech.source, f"links[{j - 1}].length_mm")
    if name in ("G1", "drive"):
        return "drive.teeth"
    if name[0] in "DMG" and name[1:].isdigit():
        j = int(name[1:]) - (1 if name[0] == "G" else 0)
        return "teeth" if mech.auto_teeth else f"teeth[{j - 1}].{name[0]}"
    return {"base": "base", "crank": "base.crank_radius_mm", "pen_holder": "pen"}.get(name, name)


def oversize_parts(spec: ChainSpec, kit: Kit) -> list[tuple[str, str, np.ndarray]]:
    """Parts whose extents (any axis order) exceed the printer envelope: (name, key, extents)."""
    return [(p.name, size_key(spec, p.name), ext) for p, ext in oversize(kit.parts, kit.params.printer.envelope)]


def drawing_deviation(mech) -> dict:
    """The pen of the chain as built (its teeth's speeds, its links' lengths) against the user's
    samples: at each sample's crank angle (max, RMS) and as curves (Hausdorff), mm."""
    from ...design.drawing import measure
    from ...design.synthesis import trace
    from ...design.trace import built_chain

    d = mech.drawing
    chain = built_chain(mech)
    h, mx, rms = measure(chain, d)
    same = np.abs(trace(chain, d.theta) - d.samples)
    return {"target": "drawing", "drawing": d.source, "drawing_samples": int(len(d.samples)),
            "parametrisation": d.parametrisation, "max_deviation_mm": _r6(mx), "rms_mm": _r6(rms),
            "hausdorff_mm": _r6(h), "worst_theta_rad": _r6(d.theta[int(np.argmax(same))]),
            "tradeoff": [{"links": r.links, "hausdorff_mm": _r6(r.hausdorff_mm), "max_deviation_mm": _r6(r.max_mm),
                          "rms_mm": _r6(r.rms_mm), "shortest_link_mm": _r6(r.shortest_mm)} for r in d.rows]}


def pen_error_band(spec: ChainSpec, theta: np.ndarray):
    """The pen's error band from the kit's backlash and running-fit play (``design.play``), on the
    design's printer."""
    from ...design.play import pen_band

    p = spec.params
    return pen_band(spec.mechanism, p.joints.running_clearance / 2, theta, p.printer.xy_accuracy)


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


def crank_text(mech) -> str:
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


def tradeoff_text(d) -> list[str]:
    """The links-against-deviation table of a drawing (build prints it)."""
    lines = [f"links vs deviation from {d.source} ({len(d.samples)} samples, by {d.parametrisation.replace('_', ' ')}"
             f"{f', at scale {d.scale:g}' if d.scale != 1 else ''}):",
             f"{'links':>7}{'Hausdorff mm':>14}{'max mm':>10}{'rms mm':>10}{'shortest link mm':>18}"]
    for r in d.rows:
        lines.append(f"{r.links:>7}{r.hausdorff_mm:>14.3f}{r.max_mm:>10.3f}{r.rms_mm:>10.3f}{r.shortest_mm:>18.2f}"
                     + ("  <- chosen" if r.links == d.chosen else ""))
    return lines


class GearChain:
    kind = "gear_chain"
    title = "gear chain"
    schema = Design
    motion = Motion("crank angle", "rad", (0.0, 2 * math.pi))
    csv_header = CSV_HEADER
    trace_needs_kit = False
    role_colours = ROLE_COLOURS

    def resolve(self, raw: LoadedDesign) -> ChainSpec:
        return resolve_spec(raw)


    def build(self, spec: ChainSpec, progress=None) -> Kit:
        try:
            kit = build_kit(spec.mechanism, spec.params, progress)
        except DesignError as e:
            raise ConfigError(spec.path, e.key_path, e.problem) from None
        return kit

    def refuse(self, spec: ChainSpec, kit: Kit) -> None:
        """``build`` writes no kit with an empty part or a part larger than the printer (``check`` reports them)."""
        for part in empty_parts(kit.parts):
            raise ConfigError(spec.path, size_key(spec, part.name), f"part {part.name} comes out empty: a size in the "
                              "design leaves it no material")
        big = oversize_parts(spec, kit)
        if big:
            name, key, ext = big[0]
            env = " × ".join(f"{x:g}" for x in spec.params.printer.envelope)
            raise ConfigError(spec.path, key, f"part {name} measures {' × '.join(f'{x:.1f}' for x in ext[::-1])} mm "
                              f"and does not fit the printer's {env} mm envelope in any orientation"
                              + (f" (and {len(big) - 1} more parts)" if len(big) > 1 else ""))

    def findings(self, spec: ChainSpec):
        """What the design rules found before any geometry (build prints them)."""
        return list(spec.mechanism.findings)

    def design_summary(self, spec: ChainSpec, kit: Kit) -> dict:
        """The manifest's "design" entry: chain, stages, drive, stack, findings."""
        from ...design.trace import crank_turns

        mech, params = spec.mechanism, spec.params
        return {
            "name": params.name,
            "kind": self.kind,
            "config": spec.path.name,
            "printer": params.printer.name,
            "material": params.material,
            "density_g_cm3": _r6(params.density * 1000),
            "crank_angle_rad": 0.0,
            "crank_turns_per_drawing": str(crank_turns(mech)),
            "module_mm": params.system.module,
            "pressure_angle_deg": _r6(math.degrees(params.system.pressure_angle)),
            "teeth_mode": "auto" if mech.auto_teeth else "explicit",
            "ground_offset_mm": [_r6(mech.chain.offset.real), _r6(mech.chain.offset.imag)],
            "links": [{"j": j, "name": l.name, "speed": l.speed, "length_mm": _r6(l.length),
                       "initial_angle_deg": _r6(math.degrees(l.phase))} for j, l in enumerate(mech.chain.links, 1)],
            "stages": [{"j": s.j, "ratio": str(s.ratio), "teeth": {"D": s.D.teeth, "M": s.M.teeth, "G": s.G.teeth},
                        "profile_shift": {"D": _r6(s.D.profile_shift), "M": _r6(s.M.profile_shift),
                                          "G": _r6(s.G.profile_shift)},
                        "a_DM_mm": _r6(s.a_DM), "a_MG_mm": _r6(s.a_MG),
                        "idler_mm": [_r6(s.idler[0]), _r6(s.idler[1])]} for s in mech.stages],
            "drive": {"teeth": mech.drive.teeth, "centre_mm": [_r6(c) for c in mech.drive_centre]},
            "stack_mm": {"axial_gap": kit.stack.gap, "face_width": kit.stack.face, "plate": kit.stack.plate,
                         "layers": [_r6(kit.stack.layer(j)) for j in range(len(mech.stages) + 1)],
                         "plates": [_r6(kit.stack.plate_z(j)) for j in range(1, len(mech.chain.links) + 1)]},
            "findings": [{"severity": f.severity, "code": f.rule, "key": f.key, "message": f.message}
                         for f in mech.findings],
        }

    def kit_files(self, spec: ChainSpec, kit: Kit, raw: LoadedDesign) -> dict[str, bytes]:
        """The design and its printer profile, as a kit folder keeps them: design.yaml names
        printer.yaml beside it."""
        data = raw.document()
        data["printer"] = "printer.yaml"
        if isinstance(data.get("gears"), dict) and data["gears"].get("module_mm") == "auto":
            data["gears"]["module_mm"] = spec.params.system.module  # the module auto chose, pinned
        c = raw.design.curve
        if c is not None and c.drawn and c.scale == "auto":
            data["curve"] = {**data["curve"], "scale": spec.mechanism.drawing.scale}  # the scale auto chose, pinned
        files = {}
        if c is not None and c.drawn and (c.svg is not None or isinstance(c.points, str)):
            from ...config.drawing import curve_file

            key, suffix = ("svg", ".svg") if c.svg is not None else ("points", ".csv")
            src = curve_file(getattr(c, key), raw.path, f"curve.{key}", suffix)
            data["curve"] = {**data["curve"], key: f"curve{suffix}"}  # the kit keeps its own copy
            files[f"curve{suffix}"] = src.read_bytes()
        return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document()), **files}

    def plate_margin(self, spec: ChainSpec) -> float:
        return spec.params.checks.plate_margin

    def check(self, spec: ChainSpec, kit: Kit, samples: int | None = None, progress=None) -> Result:
        from .checks import check_kit

        return check_kit(kit, samples, progress)

    def tolerance_model(self, spec: ChainSpec, kit: Kit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: gears
        sit where their meshes push them in their bores; otherwise centred, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def tolerance_exact(self, spec: ChainSpec, kit: Kit, result: Result, model, seated: bool = True):
        """(task function, shared data) of the exact Monte Carlo: ``fn(shared, seed, index)`` makes
        print ``index`` (its meshes on the printed gear outlines, its fits and clearances by their
        margins) and says whether it jams (``exact``)."""
        from .exact import exact_print, exact_shared

        return exact_print, exact_shared(kit, result, model, seated)

    def trace(self, spec: ChainSpec, kit: Kit | None, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        """The pen of the chain as built over one crank turn vs its targets; trace.png/.svg/.gif into ``out``."""
        from ...design.synthesis import trace as trace_chain
        from ...design.trace import built_chain, built_speeds, crank_turns, deviation, target_paths

        mech = spec.mechanism
        samples = samples or 3600
        theta = 2 * np.pi * np.arange(samples) / samples
        pen = trace_chain(built_chain(mech), theta)
        targets = target_paths(mech, theta)
        speeds = built_speeds(mech)
        stats = {"samples": samples, "speeds": [str(w) for w in speeds], "crank_turns_per_drawing": str(crank_turns(mech)),
                 "closes_after_one_turn": all(w.denominator == 1 for w in speeds),
                 "vs_pruned": deviation(pen, targets["pruned"], theta).to_dict()}
        if "full" in targets:
            stats.update(deviation(pen, targets["full"], theta).to_dict())
            stats["pruned_vs_full"] = deviation(targets["pruned"], targets["full"], theta).to_dict()
        if mech.drawing is not None:
            stats.update(drawing_deviation(mech))
        band = pen_error_band(spec, theta)
        stats["pen_error_band_mm"] = band.to_dict()
        files = []
        if out is not None:
            from .trace_plots import band_figure, trace_animation, trace_figure

            head = {k: v for k, v in stats.items() if k.endswith("_mm") and not isinstance(v, dict)} or \
                {k: v for k, v in stats["vs_pruned"].items() if k.endswith("_mm")}
            if "worst_theta_rad" in stats:
                head["worst_theta_rad"] = stats["worst_theta_rad"]
            trace_figure(mech, head, out / "trace.png", out / "trace.svg",
                         f"{spec.params.name}: the pen over "
                         + ("one crank turn (mm)" if crank_turns(mech) == 1 else
                            f"one drawing, {crank_turns(mech)} crank turns (mm)"), band=band)
            band_figure(band, out / "pen_band.png", f"{spec.params.name}: the pen's error from the kit's backlash and "
                        f"running-fit play, on {spec.params.printer.name} (±{spec.params.printer.xy_accuracy:g} mm)")
            files = ["trace.png", "trace.svg", "pen_band.png"]
            if animate:
                trace_animation(mech, out / "trace.gif")
                files.append("trace.gif")
        return Trace(stats, files, columns=("theta_rad", "x_mm", "y_mm"),
                     data=np.column_stack([theta, pen.real, pen.imag]))

    def csv(self, trace: Trace) -> str:
        return CSV_HEADER + "".join(f"{t:.9f},{x:.6f},{y:.6f}\n" for t, x, y in trace.data)

    # --- what the CLI prints -------------------------------------------------------------------
    def bill_text(self, spec: ChainSpec, man: dict, dest, seconds: float) -> str:
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
            lines += tradeoff_text(mech.drawing)
        if crank_text(mech):
            lines.append(crank_text(mech))
        lines.append(f"wrote {dest}/ ({len(parts)} STL, manifest.json, assembly.glb) in {seconds:.2f} s"
                     + (f"; {warn} warning{'s' if warn != 1 else ''} above (`partgen check` will fail)" if warn else ""))
        return "\n".join(lines)

    def check_text(self, spec: ChainSpec, result: Result, folder, seconds: float) -> str:
        from ...design.trace import crank_turns

        f = result.figures
        turns = crank_turns(spec.mechanism)
        lines = [f"{spec.params.name}: {f['parts']} parts, {f['pairs']} pairs, {f['samples']} crank angles over "
                 + ("one turn" if turns == 1 else f"one drawing ({turns} crank turns)")]
        counts: dict = {}
        for x in result.findings:
            counts.setdefault(x.check, {"fail": 0, "warn": 0, "info": 0})[x.severity] += 1
        motion = f["motion"]
        close = motion.get("closest_approach")
        meshes = f["meshes"]
        rows = [
            ("design", "Eq 11-13, printer minimums", ""),
            ("interference", "no overlap over the motion",
             f"{motion['narrow_phase_2d']} exact 2-D tests, {motion['exact_3d']} 3-D"),
            ("clearance", f"≥ {spec.params.checks.min_clearance:g} mm between parts that must not touch",
             f"closest {close['mm']:.3f} mm: {close['parts'][0]}–{close['parts'][1]} at {close['theta_deg']:.0f}°"
             if close else ""),
            ("mesh", f"{len(meshes)} meshing pairs",
             f"contact ratio ≥ {min(r['contact_ratio'] for r in meshes):.2f}, backlash "
             f"{min(r['measured_backlash_mm'] for r in meshes):.3f}–{max(r['measured_backlash_mm'] for r in meshes):.3f} mm"
             if meshes else ""),
            ("fit", f"{f['fits']['count']} declared contacts", f"smallest radial gap {f['fits']['min_radial_gap_mm']:.3f} mm"
             if not math.isnan(f["fits"]["min_radial_gap_mm"]) else ""),
            ("printability", "envelope, holes, walls, tooth tips",
             f"hole ≥ Ø{f['printability'].get('smallest_hole_mm', 0):.2f}, wall ≥ "
             f"{f['printability'].get('thinnest_wall_mm', 0):.2f}, tip ≥ {f['printability'].get('narrowest_tip_mm', 0):.2f}"
             f" mm; {f.get('plates', '?')} build plate(s)"),
            ("bed", "flat on the bed, one shell, bores open",
             f"contact ≥ {f['printability'].get('least_bed_contact_mm2', 0):.0f} mm², "
             f"{sum(len(b) for b in f['printability'].get('bores', {}).values())} bores, "
             f"{len(f['printability'].get('needs_supports_mm2', {}))} part(s) need supports"),
        ]
        if "kit" in counts:
            rows.append(("kit", "files match the design", ""))
        lines.append(f"{'check':<14}{'result':<8}{'what':<44}figures")
        for name, what, figs in rows:
            c = counts.get(name, {})
            if name in ("printability", "bed"):  # the bed's rules apart from the other printability rules
                c = {sev: sum(x.check == "printability" and x.severity == sev and (x.rule in BED_RULES) == (name == "bed")
                              for x in result.findings) for sev in ("fail", "warn")}
            status = "FAIL" if c.get("fail") else ("warn" if c.get("warn") else "ok")
            lines.append(f"{name:<14}{status:<8}{what:<44}{figs}")
        fails = [x for x in result.findings if x.severity in ("fail", "warn")]
        if fails:
            lines.append("")
            for x in fails:
                where = f" @ ({', '.join(f'{c:.1f}' for c in x.location)}) mm" if x.location else ""
                lines.append(f"  {x.severity.upper():<5} {x.check}: {x.message}{where}")
        lines.append("")
        lines.append(f"{'OK' if result.ok else 'FAILED'}: {sum(x.severity == 'fail' for x in result.findings)} failures"
                     f" in {seconds:.1f} s" + (f"; build plates in {folder}/" if folder else ""))
        return "\n".join(lines)

    def trace_text(self, spec: ChainSpec, trace: Trace, folder) -> str:
        stats = trace.stats
        turns = stats.get("crank_turns_per_drawing", "1")
        over = "one crank turn" if turns == "1" else f"one drawing ({turns} crank turns)"
        lines = [f"{spec.params.name}: pen over {over}, {stats['samples']} samples; link speeds as built "
                 f"{', '.join(stats['speeds'])}"
                 + ("" if stats["closes_after_one_turn"] else " (fractional: the path does not close after one turn)"),
                 f"{'traced vs':<28}{'max (same θ) mm':>16}{'rms mm':>10}{'Hausdorff mm':>14}"]
        rows = [("the design's chain (pruned)", stats["vs_pruned"])]
        if stats.get("target") == "drawing":
            rows.insert(0, (f"the drawing ({stats['drawing_samples']} pts)", stats))
        elif "max_deviation_mm" in stats:
            rows.insert(0, ("the full Fourier series", stats))
            rows.append(("(pruned vs full)", stats["pruned_vs_full"]))
        for label, d in rows:
            lines.append(f"{label:<28}{d['max_deviation_mm']:>16.3f}{d['rms_mm']:>10.3f}{d['hausdorff_mm']:>14.3f}")
        band = stats.get("pen_error_band_mm")
        if band:
            lines.append(f"play at the pen (backlash and fits taken up), across the path: worst case "
                         f"{band['path_worst_case_max']:.2f} mm, 95 % of prints within {band['path_p95_max']:.2f} mm; "
                         f"from the nominal point at the same crank angle (a lag along the path too): "
                         f"{band['worst_case_max']:.2f} / {band['p95_max']:.2f} mm ({band['prints']} prints)")
        if folder:
            lines.append(f"plots: {folder}/{', '.join(trace.files)}")
        return "\n".join(lines)

    def assembly_steps(self, spec: ChainSpec, kit: Kit) -> list[tuple[str, tuple[str, ...]]]:
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

    # --- the report page -------------------------------------------------------------------------
    def report_sections(self, spec: ChainSpec, kit: Kit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
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
                  + (f" {html.escape(crank_text(mech)).capitalize()}." if crank_text(mech) else "") + "</p>")
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

    def subtitle(self, spec: ChainSpec) -> str:
        return f"{spec.path.name} — {len(spec.mechanism.chain.links)} links"


MECHANISM = GearChain()
