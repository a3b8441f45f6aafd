"""The wrist gear pair (``kind: wrist``) behind the Mechanism protocol: two spherical gears with
dome teeth and swept sockets that roll on each other over a bend workspace."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...checks.footer import check_footer
from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.findings import Result
from ...core.protocol import Motion, Trace
from ...design import spherical as sph
from ...design.spherical import RangeError
from .spec import WristSpec
from ...errors import DesignError
from ...geometry.measure import oversize
from .kit import WristKit, build_wrist, workspace_theta_max
from .resolve import resolve_wrist
from .schema import WristDesign

__all__ = ["Wrist", "MECHANISM"]

COLOURS = {"gear1": "#4c78a8", "gear2": "#f58518", "cross_gear": "#54a24b", "cross_mate": "#e45756"}



def wrist_sampling(samples: int | None) -> dict:
    """`check --samples N` on a wrist: about N poses on the (θ, ψ) grid in the default's proportion
    (6 bends × 16 azimuths), N/4 random poses, and the play measured at 4 bends (3 under 96 poses).
    None: the default (96 grid + 24 random poses, play at 4 bends)."""
    if samples is None:
        return {}
    n_theta = max(2, round(math.sqrt(samples * 6 / 16)))
    n_psi = max(4, round(samples / n_theta))
    return {"grid": (n_theta, n_psi), "random_poses": samples // 4, "play_thetas": 4 if samples >= 96 else 3}

def mate_sampling(samples: int | None) -> dict:
    """`check --samples N` on the cross gear's mate: about N/8 mate turns at each of three tilts (3
    to 13), the backlash at 3 turns (1 under 96 samples). None: the default (13 turns, 3)."""
    if samples is None:
        return {}
    return {"psi_samples": max(3, min(13, samples // 8)), "backlash_poses": 3 if samples >= 96 else 1}


class Wrist:
    kind = "wrist"
    title = "wrist gear pair"
    schema = WristDesign
    motion = Motion("θ on gear 1", "rad", (0.0, math.pi / 2))
    csv_header = "theta_rad,ratio,phi_rad\n"
    trace_needs_kit = False
    role_colours = {"wrist_gear": "#4c78a8"}

    def resolve(self, raw: LoadedDesign) -> WristSpec:
        spec = resolve_wrist(raw)
        return spec


    def animation_motion(self, spec: WristSpec, kit: WristKit) -> Motion:
        """The assembly's animation bends the pair over its workspace: θ from 0 to ``theta_max``."""
        return Motion(self.motion.label, self.motion.unit, (0.0, float(kit.theta_max)))

    def build(self, spec: WristSpec, progress=None) -> WristKit:
        try:
            kit = build_wrist(spec, progress)
        except (RangeError, ValueError) as e:
            raise DesignError(str(e), "wrist") from None
        return kit

    def refuse(self, spec: WristSpec, kit: WristKit) -> None:
        for p, ext in oversize(kit.parts, spec.printer.envelope):
            raise DesignError(f"{p.name} measures {ext.round(1)} mm and does not fit the printer in any orientation",
                              "wrist.centre_distance_mm")

    def findings(self, spec: WristSpec):
        return []

    def design_summary(self, spec: WristSpec, kit: WristKit) -> dict:
        return {"name": spec.name, "kind": self.kind, "nominal_ratio": spec.I,
                "centre_distance_mm": spec.A, "longitudinal_pitch_mm": spec.long_pitch, **kit.figures}

    def kit_files(self, spec: WristSpec, kit: WristKit, raw: LoadedDesign) -> dict[str, bytes]:
        data = raw.document()
        data["printer"] = "printer.yaml"
        return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}

    def plate_margin(self, spec: WristSpec) -> float:
        return 5.0

    def check(self, spec: WristSpec, kit: WristKit, samples: int | None = None, progress=None) -> Result:
        from .checks import check_wrist

        from ...checks.bed import bed_findings
        from ...checks.bores import bore_findings

        res = check_wrist(kit, progress=progress, **wrist_sampling(samples))
        if spec.mate is not None:
            from .mate import check_mate

            check_mate(kit, res, **mate_sampling(samples))
        found, on_bed = bed_findings(kit.parts, kit.printer)
        res.add(*found)
        found, bores = bore_findings(kit.parts)
        res.add(*found)
        res.figures["printability"] = {**on_bed, "bores": bores}
        return res

    def tolerance_model(self, spec: WristSpec, kit: WristKit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of each dome tooth in its socket over the workspace as a ``design.tolerance.MarginModel``
        (no bores run: ``seated`` changes nothing)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: WristSpec, kit, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
        """The ratio i(θ) and the mating angle φ(θ) over the valid range, the tooth rows; wrist.png/.svg."""
        samples = samples or 2000
        pair = sph.tooth_rows(spec.I, spec.A, spec.long_pitch, spec.ring_teeth)
        theta_max = workspace_theta_max(spec.I, spec.max_bend)
        end = sph.valid_end(spec.I)
        ts, i_ode = sph.ratio_ode(end, spec.I, samples)
        t = np.linspace(0, end, samples + 1)
        stats = {"kind": self.kind, "nominal_ratio": spec.I, "valid_end_deg": round(float(np.degrees(end)), 6),
                 "workspace_theta_max_deg": round(float(np.degrees(theta_max)), 6),
                 "ode_vs_closed_form_max": float(np.abs(i_ode - sph.ratio(ts, spec.I)).max()),
                 "mating_angle_methods_max_rad": float(np.abs(sph.mating_angle_meridian(t, spec.I)
                                                               - sph.mating_angle_latitude(t, spec.I)).max()),
                 "rows": [{"k": r.k, "teeth": r.teeth, "theta_deg": round(float(np.degrees(r.theta)), 4),
                           "phi_deg": round(float(np.degrees(r.phi)), 4), "lat_pitch_mm": round(r.lat_pitch_1, 4),
                           "lat_pitch_off": round(r.lat_pitch_1 / spec.long_pitch - 1, 5) if r.k else None}
                          for r in pair.rows]}
        files = []
        if out is not None:
            from .plots import wrist_figure

            wrist_figure(spec.I, spec.A, theta_max, pair.rows, out / "wrist.png", out / "wrist.svg",
                         f"{spec.name}: I = {spec.I:g}, centre distance {spec.A:g} mm")
            files = ["wrist.png", "wrist.svg"]
        if spec.mate is not None:
            from .mate import trace_mate

            mate = trace_mate(spec)
            stats["mate"] = mate["stats"]
            if out is not None:
                from .plots import mate_figure

                mate_figure(spec, mate["rows"], out / "cross_mate.png")
                files.append("cross_mate.png")
        data = np.column_stack([t, sph.ratio(t, spec.I), sph.mating_angle(t, spec.I)])
        return Trace(stats, files, columns=("theta_rad", "ratio", "phi_rad"), data=data)

    def csv(self, trace: Trace) -> str:
        return self.csv_header + "".join(f"{t:.9f},{i:.9f},{p:.9f}\n" for t, i, p in trace.data)

    def assembly_steps(self, spec: WristSpec, kit) -> list[tuple[str, tuple[str, ...]]]:
        """Each gear pressed onto its D-shaft from its flat face, then brought into mesh."""
        have = {p.name for p in kit.parts}
        steps = [(f"Press gear1 onto a Ø{spec.shaft_diameter:g} mm D-shaft, the shaft entering its flat face, flat to "
                  "flat.", ("gear1",)),
                 ("Press gear2 onto the second shaft the same way; bring its sockets over gear1's dome teeth with the "
                  "two spheres' centres together, and bend the pair through its workspace by hand.", ("gear2",))]
        if "cross_gear" in have:
            steps.append(("Press the cross gear onto its shaft by its flat face, the same way.", ("cross_gear",)))
        return steps

    def bill_text(self, spec: WristSpec, man: dict, dest, seconds: float) -> str:
        lines = [f"{p['name']:<8}{p['triangles']:>9} triangles {p['volume_mm3'] / 1000:8.2f} cm3 {p['mass_g']:7.1f} g  "
                 f"{' x '.join(f'{x:.1f}' for x in p['bbox_mm'])} mm" for p in man["parts"]]
        lines.append(f"wrote {dest}/ in {seconds:.2f} s")
        return "\n".join(lines)

    def check_text(self, spec: WristSpec, result: Result, folder, seconds: float) -> str:
        f = result.figures
        lines = [f"{spec.name}: {f['poses']} poses over the workspace (bend ≤ {f['workspace_bend_deg']:g}°: a "
                 f"{f['grid'][0]} × {f['grid'][1]} (θ, ψ) grid and {f['random']} random poses)",
                 f"  largest overlap {f['max_overlap_mm3']:.4f} mm³, least tooth volume engaged "
                 f"{f['min_engaged_mm3']:.2f} mm³",
                 f"  {'θ on gear 1':>12}{'twist play':>12}{'bend play':>11}"]
        lines += [f"  {r['theta_deg']:>11.1f}°{r['twist_play_deg']:>11.2f}°{r['bend_play_deg']:>10.2f}°" for r in f["play"]]
        if "mate" in f:
            m = f["mate"]
            lines.append(f"  cross gear and its mate: {m['poses']} poses, largest overlap {m['max_overlap_mm3']:.5f} mm³ "
                         f"(ε {m['epsilon_mm3']:g}), backlash {m['backlash_min_mm']:.3f}–{m['backlash_max_mm']:.3f} mm "
                         "at the mate's pitch circle")
        return "\n".join(lines + check_footer(result, seconds, folder))

    def trace_text(self, spec: WristSpec, trace: Trace, folder) -> str:
        stats = trace.stats
        lines = [f"{spec.name}: I = {stats['nominal_ratio']:g}; valid range θ ≤ {stats['valid_end_deg']:.3f}° "
                 f"(φ reaches 90°); workspace θ ≤ {stats['workspace_theta_max_deg']:.3f}°",
                 f"  ODE vs closed form: {stats['ode_vs_closed_form_max']:.1e}; mating angle, meridian vs latitude: "
                 f"{stats['mating_angle_methods_max_rad']:.1e} rad"]
        for r in stats["rows"][1:]:
            lines.append(f"  ring {r['k']}: {r['teeth']} teeth at θ = {r['theta_deg']:.3f}°, φ = {r['phi_deg']:.3f}°, "
                         f"latitudinal pitch {r['lat_pitch_mm']:.3f} mm ({100 * r['lat_pitch_off']:+.2f} % off the "
                         "longitudinal)")
        if "mate" in stats:
            m = stats["mate"]
            lines.append(f"  cross gear's mate (mid-plane): ratio {m['ratio']:.9f} (design {m['ratio_design']:g}, off by "
                         f"{m['ratio_error']:.1e}); transmission error {m['te_pp_um']:.2f} µm peak to peak at the cross "
                         f"gear's pitch circle; backlash {m['backlash_mid_mm']:.3f} mm")
        if folder:
            lines.append(f"plots: {folder}/{', '.join(trace.files)}")
        return "\n".join(lines)

    def report_sections(self, spec: WristSpec, kit: WristKit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
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
            sections.append(("Cross gear and its mate", self._mate_section(spec, kit, result, trace, files, meshes)))
        return sections

    def _mate_section(self, spec: WristSpec, kit: WristKit, result: Result, trace: Trace, files: dict, meshes) -> str:
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

    def subtitle(self, spec: WristSpec) -> str:
        return f"wrist pair, I = {spec.I:g}"


MECHANISM = Wrist()
