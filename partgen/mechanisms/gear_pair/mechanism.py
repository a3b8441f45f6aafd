"""A spur gear pair (``kind: gear_pair``) behind the Mechanism protocol: built, checked over one
revolution of the output, traced (transmission error from the printed outlines) and reported."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import box

from ...checks.footer import check_footer
from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.findings import Finding, Result
from ...core.protocol import Motion, Trace
from ...errors import DesignError
from ...geometry.measure import oversize, section
from .kit import PairKit, PairSpec, build_pair, resolve_pair
from .schema import GearPairDesign
from ...export.report import figure_png

__all__ = ["GearPair", "MECHANISM", "flank_play"]


def _outline(kit: PairKit, name: str):
    """The printed gear's section at half its face width, in its own frame (mm)."""
    part = next(p for p in kit.parts if p.name == name)
    return section(part.solid, kit.spec.face_width / 2)


def flank_play(kit: PairKit, thetas: np.ndarray, tol: float = 1e-6) -> dict[str, np.ndarray]:
    """Over gear 1's turns ``thetas`` (n,) rad, from the printed outlines: how far gear 2 can turn from
    its nominal angle before it touches gear 1, against (``ahead``, > 0: the flank gear 1 drives
    with) and along (``behind``, < 0) its motion, rad at gear 2; and the overlap area (mm²) at the
    nominal angle (0 when the pair runs free). Bisection to ``tol`` rad."""
    s = kit.spec
    p1, p2 = _outline(kit, "gear1"), _outline(kit, "gear2")
    r1 = s.centre_distance * s.gear1.teeth / (s.gear1.teeth + s.gear2.teeth)
    m = s.gear1.system.module
    window = box(r1 - 3 * m, -3 * m, r1 + 3 * m, 3 * m)  # the teeth in mesh lie inside it
    reach = math.pi / s.gear2.teeth  # half a pitch: farther than any backlash
    out = {"ahead": np.empty(len(thetas)), "behind": np.empty(len(thetas)), "overlap_mm2": np.empty(len(thetas))}
    for k, t in enumerate(thetas):
        g1 = shapely.intersection(affinity.rotate(p1, float(t), origin=(0, 0), use_radians=True), window)
        shapely.prepare(g1)
        phi = float(s.output_angle(t))

        def area(d: float) -> float:
            g2 = affinity.translate(affinity.rotate(p2, phi + d, origin=(0, 0), use_radians=True), s.centre_distance)
            return g1.intersection(g2).area if g1.intersects(g2) else 0.0

        out["overlap_mm2"][k] = area(0.0)
        for key, sign in (("ahead", 1.0), ("behind", -1.0)):
            lo, hi = 0.0, reach
            while hi - lo > tol:
                mid = (lo + hi) / 2
                lo, hi = (lo, mid) if area(sign * mid) > 1e-9 else (mid, hi)
            out[key][k] = sign * lo
    return out


class GearPair:
    kind = "gear_pair"
    title = "spur gear pair"
    schema = GearPairDesign
    motion = Motion("output angle", "rad", (0.0, 2 * math.pi))
    csv_header = "input_rad,output_rad,transmission_error_rad,backlash_mm\n"
    trace_needs_kit = True
    role_colours = {"gear": "#4c78a8", "base": "#8c8c8c"}

    def resolve(self, raw: LoadedDesign) -> PairSpec:
        return resolve_pair(raw)

    def build(self, spec: PairSpec, progress=None) -> PairKit:
        try:
            return build_pair(spec, progress)
        except ValueError as e:
            raise DesignError(str(e), "axles.diameter_mm") from None

    def refuse(self, spec: PairSpec, kit: PairKit) -> None:
        for part, ext in oversize(kit.parts, spec.printer.envelope):
            raise DesignError(f"{part.name} measures {ext.round(1)} mm and does not fit the printer in any orientation",
                              "gears.module_mm")

    def findings(self, spec: PairSpec):
        return []

    def design_summary(self, spec: PairSpec, kit: PairKit) -> dict:
        r6 = lambda x: float(round(float(x), 6))  # noqa: E731
        g1, g2 = spec.gear1, spec.gear2
        return {"name": spec.name, "kind": self.kind, "module_mm": g1.system.module,
                "pressure_angle_deg": r6(math.degrees(g1.system.pressure_angle)), "teeth": [g1.teeth, g2.teeth],
                "ratio": f"{g2.teeth}/{g1.teeth}", "profile_shift": [r6(g1.profile_shift), r6(g2.profile_shift)],
                "centre_distance_mm": r6(spec.centre_distance), "face_width_mm": spec.face_width,
                "axle_diameter_mm": 2 * spec.axle_radius, "bore_diameter_mm": r6(2 * spec.bore_radius),
                "printer": spec.printer.name, "material": spec.material, "density_g_cm3": r6(spec.density * 1000)}

    def kit_files(self, spec: PairSpec, kit: PairKit, raw: LoadedDesign) -> dict[str, bytes]:
        data = raw.document()
        data["printer"] = "printer.yaml"
        return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}

    def plate_margin(self, spec: PairSpec) -> float:
        return spec.plate_margin

    def _sweep(self, spec: PairSpec, kit: PairKit, samples: int | None, progress=None):
        n = samples or spec.samples
        thetas = np.linspace(0.0, 2 * math.pi * spec.gear2.teeth / spec.gear1.teeth, n, endpoint=False)
        chunks = [thetas[i:i + 16] for i in range(0, n, 16)]
        parts = []
        for i, c in enumerate(chunks):
            parts.append(flank_play(kit, c))
            if progress:
                progress(min((i + 1) * 16, n), n)
        return thetas, {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}

    def check(self, spec: PairSpec, kit: PairKit, samples: int | None = None, progress=None) -> Result:
        """Over one revolution of the output: the gears never overlap, they keep backlash on both
        flanks, and each bore clears its post."""
        res = Result()
        thetas, play = self._sweep(spec, kit, samples, progress)
        r2 = spec.centre_distance * spec.gear2.teeth / (spec.gear1.teeth + spec.gear2.teeth)
        bad = np.flatnonzero(play["overlap_mm2"] > 1e-6)
        if len(bad):
            k = bad[np.argmax(play["overlap_mm2"][bad])]
            res.add(Finding("interference", "fail", f"gear1 and gear2 overlap by {play['overlap_mm2'][k]:.4f} mm² of "
                            f"section at {len(bad)} of {len(thetas)} angles", ("gear1", "gear2"), float(thetas[k]),
                            float(play["overlap_mm2"][k] * spec.face_width), "mm3", key="gears"))
        backlash = (play["ahead"] - play["behind"]) * r2
        if backlash.min() <= 0:
            res.add(Finding("mesh", "fail", "the teeth jam: no backlash left", ("gear1", "gear2"),
                            float(thetas[np.argmin(backlash)]), float(backlash.min()), "mm", key="gears.backlash_per_gear_mm"))
        gaps = [spec.bore_of(g) - spec.axle_radius for g in ("gear1", "gear2")]
        radial = min(gaps)
        if radial <= 0:
            res.add(Finding("fit", "fail", f"the bores grip their posts ({radial:.3f} mm radial gap)", ("base", "gear1"),
                            value=radial, unit="mm", key="axles.clearance_diametral_mm"))
        te = play["ahead"] * r2
        res.figures.update(samples=len(thetas), output_turns=1, centre_distance_mm=round(spec.centre_distance, 6),
                           backlash_mm={"min": float(backlash.min()), "max": float(backlash.max()),
                                        "mean": float(backlash.mean()),
                                        "designed": spec.gear1.system.backlash_per_gear + spec.gear2.system.backlash_per_gear},
                           transmission_error_mm={"peak_to_peak": float(np.ptp(te)), "mean": float(te.mean())},
                           max_overlap_mm2=float(play["overlap_mm2"].max()), radial_gap_mm=float(radial),
                           radial_gaps_mm=[float(x) for x in gaps])
        from ...checks.bed import bed_findings
        from ...checks.bores import bore_findings

        found, on_bed = bed_findings(kit.parts, kit.printer)
        res.add(*found)
        found, bores = bore_findings(kit.parts)
        res.add(*found)
        res.figures["printability"] = {**on_bed, "bores": bores}
        return res

    def tolerance_model(self, spec: PairSpec, kit: PairKit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: gears
        sit where their meshes push them in their bores; otherwise centred, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def tolerance_exact(self, spec: PairSpec, kit: PairKit, result: Result, model, seated: bool = True):
        """(task function, shared data) of the exact Monte Carlo: ``fn(shared, seed, index)`` makes
        print ``index`` of the real geometry and says whether it jams (``exact``)."""
        from .exact import exact_print, exact_shared

        return exact_print, exact_shared(kit, result, model, seated)

    def trace(self, spec: PairSpec, kit: PairKit, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
        """The transmission error over one output revolution from the printed outlines: how far the
        driven gear lags its nominal angle with gear 1's flank against it (rad at the output, and
        mm along its pitch circle), and the backlash; transmission.png."""
        thetas, play = self._sweep(spec, kit, samples)
        r2 = spec.centre_distance * spec.gear2.teeth / (spec.gear1.teeth + spec.gear2.teeth)
        te, backlash = play["ahead"], (play["ahead"] - play["behind"]) * r2
        out_angle = thetas * spec.gear1.teeth / spec.gear2.teeth
        stats = {"kind": self.kind, "samples": len(thetas), "ratio": spec.gear2.teeth / spec.gear1.teeth,
                 "transmission_error_rad": {"mean": float(te.mean()), "peak_to_peak": float(np.ptp(te))},
                 "transmission_error_mm": {"mean": float(te.mean() * r2), "peak_to_peak": float(np.ptp(te) * r2)},
                 "backlash_mm": {"min": float(backlash.min()), "max": float(backlash.max()),
                                 "designed": 2 * spec.gear1.system.backlash_per_gear}}
        files = []
        if out is not None:
            (out / "transmission.png").write_bytes(_figure(spec, out_angle, te * r2, backlash))
            files = ["transmission.png"]
        return Trace(stats, files, columns=("input_rad", "output_rad", "transmission_error_rad", "backlash_mm"),
                     data=np.column_stack([thetas, out_angle, te, backlash]))

    def csv(self, trace: Trace) -> str:
        return self.csv_header + "".join(f"{a:.9f},{b:.9f},{c:.9f},{d:.6f}\n" for a, b, c, d in trace.data)

    def assembly_steps(self, spec: PairSpec, kit: PairKit) -> list[tuple[str, tuple[str, ...]]]:
        """The base, gear 1 on its post, gear 2 on the other post in mesh."""
        return [("Stand the base on the table, its two posts up.", ("base",)),
                (f"Slide gear1 ({spec.gear1.teeth} teeth) down over its post until it rests on the base.", ("gear1",)),
                (f"Slide gear2 ({spec.gear2.teeth} teeth) down over the other post, turning it until its teeth drop into "
                 "mesh with gear1's; "
                 "turn gear1 by hand: both turn freely.", ("gear2",))]

    def bill_text(self, spec: PairSpec, man: dict, dest, seconds: float) -> str:
        lines = [f"{spec.name}: {spec.gear1.teeth}/{spec.gear2.teeth} teeth, module {spec.gear1.system.module:g} mm, "
                 f"centre distance {spec.centre_distance:.3f} mm"]
        lines += [f"{p['name']:<8}{p['role']:<6}{p['triangles']:>9} triangles {p['volume_mm3'] / 1000:8.2f} cm3 "
                  f"{p['mass_g']:7.1f} g  {' x '.join(f'{x:.1f}' for x in p['bbox_mm'])} mm" for p in man["parts"]]
        lines.append(f"wrote {dest}/ in {seconds:.2f} s")
        return "\n".join(lines)

    def check_text(self, spec: PairSpec, result: Result, folder, seconds: float) -> str:
        f = result.figures
        b, te = f["backlash_mm"], f["transmission_error_mm"]
        lines = [f"{spec.name}: {f['samples']} angles over one turn of the output",
                 f"  backlash {b['min']:.3f}–{b['max']:.3f} mm (designed {b['designed']:.3f} mm); transmission error "
                 f"{1000 * te['peak_to_peak']:.1f} µm peak to peak; largest overlap {f['max_overlap_mm2']:.4f} mm²; "
                 f"bore over post {f['radial_gap_mm']:.3f} mm radial"]
        return "\n".join(lines + check_footer(result, seconds, folder))

    def trace_text(self, spec: PairSpec, trace: Trace, folder) -> str:
        s = trace.stats
        lines = [f"{spec.name}: ratio {s['ratio']:.4f}, {s['samples']} angles over one output turn",
                 f"  transmission error {1000 * s['transmission_error_mm']['peak_to_peak']:.1f} µm peak to peak along "
                 f"the output's pitch circle; backlash {s['backlash_mm']['min']:.3f}–{s['backlash_mm']['max']:.3f} mm"]
        if folder:
            lines.append(f"plots: {folder}/{', '.join(trace.files)}")
        return "\n".join(lines)

    def report_sections(self, spec: PairSpec, kit: PairKit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        from ...export import report as R

        f = result.figures
        design = R.table(["", "gear 1 (input)", "gear 2 (output)"],
                         [["teeth", spec.gear1.teeth, spec.gear2.teeth],
                          ["profile shift", round(spec.gear1.profile_shift, 4), round(spec.gear2.profile_shift, 4)],
                          ["tip diameter mm", round(2 * spec.gear1.tip_radius, 3), round(2 * spec.gear2.tip_radius, 3)]]) \
            + (f"<p>Module {spec.gear1.system.module:g} mm, pressure angle "
               f"{math.degrees(spec.gear1.system.pressure_angle):g}°, centre distance {spec.centre_distance:.3f} mm, "
               f"face width {spec.face_width:g} mm, posts Ø{2 * spec.axle_radius:g} mm.</p>")
        check = (f'<p class="{"ok" if result.ok else "fail"}">{f["samples"]} angles over one output turn: backlash '
                 f'{f["backlash_mm"]["min"]:.3f}–{f["backlash_mm"]["max"]:.3f} mm, transmission error '
                 f'{1000 * f["transmission_error_mm"]["peak_to_peak"]:.1f} µm peak to peak.</p>')
        return [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error")),
                ("Check", check)]

    def subtitle(self, spec: PairSpec) -> str:
        return f"{spec.gear1.teeth}/{spec.gear2.teeth} spur gear pair"


def _figure(spec: PairSpec, out_angle: np.ndarray, te_mm: np.ndarray, backlash: np.ndarray) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4))
    deg = np.degrees(out_angle)
    ax.plot(deg, 1000 * te_mm, label="transmission error (driven flank), µm")
    ax.plot(deg, 1000 * backlash, label="backlash, µm")
    ax.set_xlabel("output angle (°)")
    ax.set_ylabel("µm along the output's pitch circle")
    ax.set_title(f"{spec.name}: over one turn of the output, from the printed outlines")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return figure_png(fig, 110)


MECHANISM = GearPair()
