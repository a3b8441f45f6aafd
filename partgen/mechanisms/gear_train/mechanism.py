"""A gear train in a frame (``kind: gear_train``) behind the Mechanism protocol: designed from a table
of stages (teeth, ratios, centre distances, an overall ratio), built, checked over one turn of the
slowest shaft, traced on its printed outlines (output against input: transmission error in
arcminutes, the ratio measured, the backlash at the output) and reported."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...checks.footer import check_footer
from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.findings import Finding, Result
from ...core.protocol import Motion, Trace
from ...errors import DesignError
from ...geometry.measure import oversize
from .checks import check_train, sample_thetas
from .kit import TrainKit, TrainSpec, build_train, resolve_train
from .motion import turn_train
from .planetary import SLICE as _PLANETARY
from .planetary.kit import PlanetaryKit
from .planetary.resolve import PlanetarySpec
from .rack import SLICE as _RACK
from .rack.kit import RackKit
from .rack.resolve import RackSpec
from .schema import GearTrainDesign
from ...export.report import figure_png

__all__ = ["GearTrain", "MECHANISM"]

ARCMIN = 60 * 180 / math.pi  # arcminutes per radian


def _r6(x) -> float:
    return float(round(float(x), 6))


def _hub_summary(h, running: float) -> dict:
    """The bore's feature as built (mm): a keyway's slot, a nut trap, a set screw's hole and nut slot
    (``h``: a hubs.Hub, or None for a round or D-flat bore; ``running``: the diametral running clearance)."""
    if h is None or h.kind in ("round", "d_flat"):
        return {}
    if h.kind == "keyway":
        return {"keyway": {"width_mm": _r6(2 * h.key_half), "floor_from_axis_mm": _r6(h.key_floor),
                           "key_width_mm": _r6(2 * h.key_top_half), "key_top_from_axis_mm": _r6(h.key_top)}}
    if h.kind == "hex":
        return {"nut_trap": {"nut": f"{h.nut} ISO 4032", "across_flats_mm": _r6(h.pocket_s), "depth_mm": _r6(h.pocket_depth),
                             "rod_diameter_mm": _r6(h.thread)}}
    return {"set_screw": {"screw": f"{h.nut} × {h.screw_length:g} ISO 4026", "hole_diameter_mm": _r6(h.thread + running),
                          "axis_above_part_bottom_mm": _r6(h.screw_z), "nut": f"{h.nut} DIN 562",
                          "slot_mm": [_r6(h.pocket_depth), _r6(h.pocket_s)], "slot_inner_face_mm": _r6(h.slot_x0)}}


def _lost_motion_html(lm: dict, spec) -> str:
    """The report's "What play costs" of a train: the output's lost motion (arc-minutes) from each
    mesh's backlash and the bores' play, and the transmission-error band (play.lost_motion)."""
    from ...export import report as R

    band = lm.get("transmission_error_band_arcmin")
    rows = [[m["mesh"], f"{m['backlash_mm']:.3f}", f"{m['backlash_arcmin']:.2f}", f"{m['bores_arcmin']:.2f}"]
            for m in lm["meshes"]]
    return (f"<p>Lost motion at the output (the input held, how far the output turns freely): "
            f"<b>{lm['total']:.1f} arcmin</b> — each mesh's backlash {lm['backlash']:.1f} arcmin and the bores' "
            f"play {lm['bores']:.1f} arcmin (running clearance {2 * lm['radial_play_mm']:g} mm diametral, taken up "
            "along each mesh's line of centres), referred to the output through the shafts' speeds "
            "(docs/tolerance.md, What play costs).</p>"
            + (f"<p>Transmission-error band: the output stays within {band['low']:.1f} … {band['high']:.1f} arcmin of "
               f"its nominal angle (width {band['width']:.1f} arcmin): the measured drive- and coast-flank transmission "
               "error of the printed outlines, widened on each side by half the bores' share.</p>" if band else "")
            + R.table(["mesh", "backlash mm", "backlash at the output arcmin", "bores at the output arcmin"], rows,
                      left=1))

class GearTrain:
    kind = "gear_train"
    title = "gear train"
    schema = GearTrainDesign
    motion = Motion("input angle", "rad", (0.0, 2 * math.pi))
    csv_header = "input_rad,output_rad,transmission_error_arcmin,backlash_arcmin\n"
    trace_needs_kit = True
    role_colours = {"gear": "#4c78a8", "frame": "#8c8c8c", "axle": "#e45756", "threaded rod": "#b0b0b0",
                    "nut": "#6f6f6f", "set screw": "#3a3a3a"}

    def resolve(self, raw: LoadedDesign) -> TrainSpec | PlanetarySpec:
        if raw.design.rack is not None:
            return _RACK.resolve(raw)
        return _PLANETARY.resolve(raw) if raw.design.planetary is not None else resolve_train(raw)

    def build(self, spec: TrainSpec | PlanetarySpec, progress=None) -> TrainKit | PlanetaryKit:
        try:
            if isinstance(spec, RackSpec):
                return _RACK.build(spec, progress)
            return _PLANETARY.build(spec, progress) if isinstance(spec, PlanetarySpec) else build_train(spec, progress)
        except ValueError as e:
            raise DesignError(str(e), "shafts.diameter_mm") from None

    def refuse(self, spec: TrainSpec, kit: TrainKit) -> None:
        for part, ext in oversize(kit.parts, spec.printer.envelope):
            raise DesignError(f"{part.name} measures {ext.round(1)} mm and does not fit the printer in any orientation",
                              "gears.module_mm")

    def findings(self, spec: TrainSpec) -> list[Finding]:
        """What `build` warns about (the rules `check` fails on) and notes (undercut gears)."""
        from ...design import rules
        from ...design.rules import gear_rules

        gr = gear_rules(spec)
        out = []
        if isinstance(spec, TrainSpec):
            for k, m in enumerate(spec.meshes):
                a, b = spec.gear(m.driver), spec.gear(m.driven)
                for x in rules.mesh_breaches(a.spec, b.spec, m.centre_distance, gr, (a.name, b.name)):
                    out.append(Finding("design", "warn", x.message, (), key=f"train.stages[{k}]", rule=x.rule))
            gears = [(g.name, g.spec) for g in spec.gears]
        elif isinstance(spec, PlanetarySpec):
            gears = [("sun", spec.sun), ("planet", spec.planet)]
        else:
            gears = [("pinion", spec.pinion)]
        for name, g in gears:
            for x in rules.gear_breaches(g, gr, name):
                out.append(Finding("design", "warn", x.message, (), key="gears.module_mm", rule=x.rule))
            if g.undercut:
                out.append(Finding("design", "info", f"{name} ({g.teeth} teeth, x = {g.profile_shift:.3f}) is undercut",
                                   (), key="gears.profile_shift"))
        return out

    def design_summary(self, spec: TrainSpec, kit: TrainKit) -> dict:
        if isinstance(spec, PlanetarySpec):
            return _PLANETARY.design_summary(spec)
        if isinstance(spec, RackSpec):
            return _RACK.design_summary(spec)
        r = spec.ratio
        out = {"name": spec.name, "kind": self.kind, "module_mm": spec.system.module,
               "pressure_angle_deg": _r6(math.degrees(spec.system.pressure_angle)), "face_width_mm": spec.face_width,
               "ratio": f"{r.numerator}/{r.denominator}", "ratio_value": _r6(float(r)),
               "output_sense": "same as the input" if spec.shafts[-1].speed > 0 else "opposite to the input",
               "stages": [{"teeth": [st.driver, st.driven], "ratio": _r6(float(st.ratio)), "idler": st.idler,
                           "profile_shift": [_r6(spec.gear(m.driver).spec.profile_shift),
                                             _r6(spec.gear(m.driven).spec.profile_shift)],
                           "centre_distance_mm": _r6(m.centre_distance), "direction_deg": _r6(math.degrees(m.direction)),
                           "gears": [m.driver, m.driven]}
                          for st, m in zip(spec.stages, spec.meshes)],
               "shafts": [{"centre_mm": [_r6(c) for c in sh.centre], "bore": sh.bore,
                           "speed": f"{sh.speed.numerator}/{sh.speed.denominator}", "phase_deg": _r6(math.degrees(sh.phase)),
                           "hub_diameter_mm": _r6(2 * sh.hub_radius), **_hub_summary(sh.fit, spec.running)} for sh in spec.shafts],
               "hub_height_mm": _r6(spec.base),
               "shaft_diameter_mm": 2 * spec.shaft_radius, "printer": spec.printer.name, "material": spec.material,
               "density_g_cm3": _r6(spec.density * 1000)}
        if spec.helix:
            out.update(helix_angle_deg=_r6(math.degrees(spec.helix)), herringbone=spec.herringbone,
                       normal_module_mm=_r6(spec.normal_module), transverse_module_mm=_r6(spec.system.module),
                       profile_shift_plane="transverse (x_t = x_n cos β)",
                       hands=[{"gear": g.name, "hand": "right" if g.hand > 0 else "left"} for g in spec.gears])
        if spec.target_ratio is not None:
            out["target_ratio"] = spec.target_ratio
            out["ratio_error"] = _r6(float(r) / spec.target_ratio - 1)
        return out

    def kit_files(self, spec: TrainSpec, kit: TrainKit, raw: LoadedDesign) -> dict[str, bytes]:
        data = raw.document()
        data["printer"] = "printer.yaml"
        return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}

    def plate_margin(self, spec: TrainSpec) -> float:
        return spec.checks.plate_margin

    def check(self, spec: TrainSpec, kit: TrainKit, samples: int | None = None, progress=None) -> Result:
        if isinstance(spec, PlanetarySpec):
            return _PLANETARY.check(kit, samples, progress)
        if isinstance(spec, RackSpec):
            return _RACK.check(kit, samples, progress)
        return check_train(kit, samples, progress)

    def tolerance_model(self, spec, kit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (every mesh,
        fit and clearance; the planetary's assembly with printed teeth; the rack; ``seated``: bodies where
        their meshes push them in their bores, otherwise centred)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: TrainSpec, kit: TrainKit, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
        """Output angle against input angle over one turn of the output, from the printed outlines (a
        rack's travel against the pinion's angle over its travel)."""
        if isinstance(spec, RackSpec):
            return _RACK.trace(spec, kit, samples, out)
        if isinstance(spec, PlanetarySpec):
            thetas = np.linspace(0.0, spec.output_turn, samples or 90, endpoint=False)
            return _PLANETARY.trace(spec, kit, samples, out)
        if True:
            thetas = sample_thetas(spec, samples or 90)
            turned = turn_train(kit, thetas)
            o = len(spec.shafts) - 1
            drive, nominal, coast = turned["drive"][:, o], turned["nominal"][:, o], turned["coast"][:, o]
        te = (drive - nominal) * ARCMIN
        lash = np.abs(coast - drive) * ARCMIN
        slope = np.polyfit(thetas, drive, 1)[0]
        stats = {"kind": self.kind, "samples": len(thetas), "ratio_design": float(spec.ratio),
                 "output": "carrier" if isinstance(spec, PlanetarySpec) else f"shaft {len(spec.shafts) - 1}",
                 "ratio_measured": float(1.0 / abs(slope)),
                 "ratio_measured_error": float((1.0 / abs(slope)) / float(spec.ratio) - 1),
                 "transmission_error_arcmin": {"peak_to_peak": float(np.ptp(te)), "mean": float(te.mean())},
                 "backlash_arcmin": {"min": float(lash.min()), "max": float(lash.max()), "mean": float(lash.mean())},
                 "max_overlap_mm2": float(turned["overlap_mm2"].max())}
        if not isinstance(spec, PlanetarySpec):
            from .play import lost_motion

            stats["lost_motion_arcmin"] = lost_motion(spec, te, (coast - nominal) * ARCMIN)
        files = []
        if out is not None:
            (out / "transmission.png").write_bytes(_figure(spec, thetas, te, lash))
            files = ["transmission.png"]
        return Trace(stats, files, columns=("input_rad", "output_rad", "transmission_error_arcmin", "backlash_arcmin"),
                     data=np.column_stack([thetas, drive, te, lash]))

    def csv(self, trace: Trace) -> str:
        return self.csv_header + "".join(f"{a:.9f},{b:.9f},{c:.6f},{d:.6f}\n" for a, b, c, d in trace.data)

    def bill_text(self, spec: TrainSpec, man: dict, dest, seconds: float) -> str:
        if isinstance(spec, RackSpec):
            head = (f"{spec.name}: rack and pinion, {spec.pinion.teeth}-tooth pinion, {spec.rack_teeth}-tooth rack "
                    f"({spec.rack_length:.1f} mm), module {spec.system.module:g} mm, {spec.pinion.pitch_radius:.4f} mm per rad")
            r = None
        elif isinstance(spec, PlanetarySpec):
            t = spec.teeth
            head = (f"{spec.name}: planetary, sun {t.sun} / planet {t.planet} ×{t.planets} / ring {t.ring}, ratio "
                    f"{t.ratio:.4f}" + (f" (target {spec.target_ratio:g})" if spec.target_ratio else "")
                    + f", module {spec.system.module:g} mm")
        else:
            head, r = None, spec.ratio
        lines = [head] if head else [f"{spec.name}: ratio {r.numerator}/{r.denominator} = {float(r):.4f}"
                 + (f" (target {spec.target_ratio:g}, {100 * (float(r) / spec.target_ratio - 1):+.3f} %)"
                    if spec.target_ratio else "") + f", module {spec.system.module:g} mm, {len(spec.stages)} stage(s): "
                 + ", ".join(f"{st.driver}/{st.driven}" for st in spec.stages)]
        lines += [f"{p['name']:<14}{p['role']:<7}{p['count']:>3}{p['triangles']:>9} triangles {p['volume_mm3'] / 1000:8.2f} cm3 "
                  f"{p['mass_g']:7.1f} g  {' x '.join(f'{x:.1f}' for x in p['bbox_mm'])} mm" for p in man["parts"]]
        lines.append(f"wrote {dest}/ in {seconds:.2f} s")
        return "\n".join(lines)

    def check_text(self, spec: TrainSpec, result: Result, folder, seconds: float) -> str:
        f = result.figures
        if isinstance(spec, RackSpec):
            r = f["rack_mesh"]
            lines = [f"{spec.name}: {f['samples']} pinion angles over the rack's {spec.travel:g} mm travel",
                     f"  pinion/rack {r['teeth'][0]}/{r['teeth'][1]}: contact ratio {r['contact_ratio']:.3f}, backlash "
                     f"{r['backlash_mm']['min']:.3f}–{r['backlash_mm']['max']:.3f} mm (designed "
                     f"{r['backlash_mm']['designed']:.3f}), rack tips {r['rack_tip_width_mm']:.2f} mm"]
            return "\n".join(lines + check_footer(result, seconds, folder, bed=False))
        lines = [f"{spec.name}: {f['samples']} angles over one turn of the slowest shaft ({f['input_turns']:g} input turns)"]
        for row in f.get("meshes", []):
            lines.append(f"  {'/'.join(row['pair'])} {row['teeth'][0]}/{row['teeth'][1]}: centre distance "
                         f"{row['centre_distance_mm']:.3f} mm, backlash {row['backlash_mm']:.3f} mm (measured "
                         f"{row['measured_backlash_mm']:.3f}), contact ratio {row['contact_ratio']:.3f}")
        im = f.get("internal_mesh")
        if im:
            lines.append(f"  planet/ring {im['teeth'][0]}/{im['teeth'][1]} (internal): contact ratio {im['contact_ratio']:.3f}, "
                         f"tip-root {min(im['tip_root_mm'].values()):.3f} mm, planets' tips {im['planet_tip_gap_mm']:.2f} mm "
                         f"apart, assembly {im['assembly']}")
        b = f.get("output_backlash_arcmin", {})
        if b:
            lines.append(f"  backlash at the output {b['min']:.1f}–{b['max']:.1f} arcmin (printed outlines)")
        return "\n".join(lines + check_footer(result, seconds, folder, bed=False))

    def trace_text(self, spec: TrainSpec, trace: Trace, folder) -> str:
        s = trace.stats
        if isinstance(spec, RackSpec):
            lines = [f"{spec.name}: {s['ratio_measured']:.5f} mm of rack per rad (design {s['ratio_design']:.5f}), "
                     f"{s['samples']} angles over the travel",
                     f"  transmission error {s['transmission_error_um']['peak_to_peak']:.2f} µm peak to peak at the "
                     f"rack; backlash {s['backlash_mm']['min']:.3f}–{s['backlash_mm']['max']:.3f} mm"]
            return "\n".join(lines + ([f"plots: {folder}/{', '.join(trace.files)}"] if folder else []))
        lines = [f"{spec.name}: ratio measured {s['ratio_measured']:.5f} (design {s['ratio_design']:.5f}), "
                 f"{s['samples']} angles over one output turn",
                 f"  transmission error {s['transmission_error_arcmin']['peak_to_peak']:.2f} arcmin peak to peak at the "
                 f"output; backlash {s['backlash_arcmin']['min']:.1f}–{s['backlash_arcmin']['max']:.1f} arcmin"]
        lm = s.get("lost_motion_arcmin")
        if lm:
            band = lm["transmission_error_band_arcmin"]
            lines.append(f"  lost motion at the output {lm['total']:.1f} arcmin (backlash {lm['backlash']:.1f}, bores' play "
                         f"{lm['bores']:.1f}); output within {band['low']:.1f}…{band['high']:.1f} arcmin of nominal")
        if folder:
            lines.append(f"plots: {folder}/{', '.join(trace.files)}")
        return "\n".join(lines)

    def assembly_steps(self, spec, kit) -> list[tuple[str, tuple[str, ...]]]:
        """The frame's bottom plate first; then each shaft, bottom up in the train's order, with the
        gears it carries and the screw and nut that hold them; then the planets and their carrier, or
        the rack on its rail; the top plate last, over the shaft ends; anything else after, in kit
        order."""
        parts = {p.name: p for p in kit.parts}
        done: list[str] = []
        steps: list[tuple[str, tuple[str, ...]]] = []

        def step(text: str, names) -> None:
            names = tuple(n for n in names if n in parts and n not in done)
            if names:
                done.extend(names)
                steps.append((text, names))
        step("Stand frame_bottom on the table, its bores up.", ["frame_bottom"])
        shafts = [n for n in parts if n.startswith("shaft")]
        for k, sh in enumerate(shafts):
            i = sh[len("shaft"):]
            gears = [n for n in parts if parts[n].role == "gear" and n not in done and (
                n == f"gears{i}" or (i == "_in" and n == "sun") or (sh == "shaft" and n == "pinion"))]
            bought = [n for n in (f"set_screw{i}", f"nut{i}") if n in parts]
            text = f"Put {sh} in its bore in frame_bottom"
            if gears:
                text += f" and slide {' and '.join(gears)} onto it"
            if bought:
                text += ", held by " + " and ".join(n.rstrip('0123456789').replace('_', ' ') for n in bought)
            if k and gears and not sh.endswith("_out"):
                text += f": {gears[0]} meshes with the gear on {shafts[k - 1]}"
            if sh.endswith("_out") and "carrier" in parts:
                planets = [n for n in parts if n.startswith("planet")]
                step(f"Set {', '.join(planets)} round the sun, each in mesh with the sun and the ring.", planets)
                step("Lay the carrier over the planets, its pins through their bores.", ["carrier"])
                text = f"Press {sh} into the carrier"
            step(text + ".", [sh, *gears, *bought])
        step("Lay the rack in its rail in frame_bottom, in mesh with the pinion.", ["rack"])
        step("Close the frame: frame_top over the shaft ends, onto the spacers.", ["frame_top"])
        for n, p in parts.items():
            if n not in done:
                step(f"Fit {n} ({p.role.replace('_', ' ')}).", [n])
        return steps

    def report_sections(self, spec: TrainSpec, kit: TrainKit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        from ...export import report as R

        if isinstance(spec, RackSpec):
            st = trace.stats
            design = (f"<p>A {spec.pinion.teeth}-tooth pinion (x = {spec.pinion.profile_shift:.3f}) and a "
                      f"{spec.rack_teeth}-tooth rack, module {spec.system.module:g} mm, travel {spec.travel:g} mm; "
                      f"the rack moves {spec.pinion.pitch_radius:.4f} mm per radian of the pinion.</p>")
            check = (f'<p class="{"ok" if result.ok else "fail"}">{result.figures["samples"]} angles over the travel; '
                     f'measured {st["ratio_measured"]:.5f} mm/rad, transmission error '
                     f'{st["transmission_error_um"]["peak_to_peak"]:.2f} µm peak to peak, backlash '
                     f'{st["backlash_mm"]["min"]:.3f}–{st["backlash_mm"]["max"]:.3f} mm.</p>')
            return [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error")), ("Check", check)]
        if isinstance(spec, PlanetarySpec):
            t, st = spec.teeth, trace.stats
            design = R.table(["", "sun", "planet", "ring"], [["teeth", t.sun, t.planet, t.ring],
                                                             ["count", 1, t.planets, 1]]) + (
                f"<p>Ring fixed, sun input, carrier output: ratio 1 + {t.ring}/{t.sun} = {t.ratio:.5f}; "
                f"(z_sun + z_ring)/N = {(t.sun + t.ring) / t.planets:g}; planets at "
                f"{', '.join(f'{math.degrees(a):.2f}°' for a in spec.angles)}; module {spec.system.module:g} mm.</p>")
            check = (f'<p class="{"ok" if result.ok else "fail"}">{result.figures["samples"]} angles over one carrier '
                     f'turn; measured ratio {st["ratio_measured"]:.5f}, transmission error '
                     f'{st["transmission_error_arcmin"]["peak_to_peak"]:.2f} arcmin peak to peak, backlash at the carrier '
                     f'{st["backlash_arcmin"]["min"]:.1f}–{st["backlash_arcmin"]["max"]:.1f} arcmin.</p>')
            return [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error")), ("Check", check)]

        rows = [[k, f"{st.driver}/{st.driven}", round(float(st.ratio), 4),
                 f"{spec.gear(m.driver).spec.profile_shift:.3f}/{spec.gear(m.driven).spec.profile_shift:.3f}",
                 round(m.centre_distance, 3), "idler" if st.idler else "compound" if k else "input"]
                for k, (st, m) in enumerate(zip(spec.stages, spec.meshes))]
        r = spec.ratio
        design = R.table(["stage", "teeth", "ratio", "profile shift", "centre distance mm", "driven from"], rows) + (
            f"<p>Overall ratio {r.numerator}/{r.denominator} = {float(r):.5f}"
            + (f" (target {spec.target_ratio:g})" if spec.target_ratio else "")
            + f"; module {spec.system.module:g} mm, pressure angle {math.degrees(spec.system.pressure_angle):g}°, "
            f"face width {spec.face_width:g} mm, shafts Ø{2 * spec.shaft_radius:g} mm.</p>")
        t = trace.stats
        check = (f'<p class="{"ok" if result.ok else "fail"}">{result.figures["samples"]} angles over one turn of the '
                 f'slowest shaft; measured ratio {t["ratio_measured"]:.5f}, transmission error '
                 f'{t["transmission_error_arcmin"]["peak_to_peak"]:.2f} arcmin peak to peak, backlash at the output '
                 f'{t["backlash_arcmin"]["min"]:.1f}–{t["backlash_arcmin"]["max"]:.1f} arcmin.</p>')
        sections = [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error"))]
        lm = t.get("lost_motion_arcmin")
        if lm:
            sections.append(("What play costs", _lost_motion_html(lm, spec)))
        return sections + [("Check", check)]

    def subtitle(self, spec: TrainSpec) -> str:
        if isinstance(spec, RackSpec):
            return f"rack and pinion, {spec.pinion.teeth} teeth, {spec.travel:g} mm travel"
        if isinstance(spec, PlanetarySpec):
            return f"planetary set, {spec.teeth.planets} planets, ratio {spec.ratio:.4f}"
        r = spec.ratio
        return f"{len(spec.stages)}-stage gear train, ratio {r.numerator}/{r.denominator}"


def _figure(spec: TrainSpec, thetas: np.ndarray, te: np.ndarray, lash: np.ndarray, unit: str = "arcmin at the output"
            ) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4))
    deg = np.degrees(thetas)
    ax.plot(deg, te, label=f"transmission error (drive flanks), {unit}")
    ax.plot(deg, lash, label=f"backlash, {unit}")
    ax.set_xlabel("input angle (°)")
    ax.set_ylabel(unit)
    ax.set_title(f"{spec.name}: over one turn of the output, from the printed outlines")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return figure_png(fig, 110)


MECHANISM = GearTrain()
