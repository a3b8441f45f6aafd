"""A straight bevel pair (``kind: bevel``) behind the Mechanism protocol: built, checked exactly in
3-D (manifold3d intersections of the posed solids at phases over a tooth pitch), traced
(transmission error and the ratio measured from where gear 2's flank touches gear 1's) and reported.

The contact search: gear 2 is turned from its nominal angle about its own axis until its solid
first overlaps gear 1's (bisection on the exact intersection volume), both ways; each solid is first
cut to the teeth within two pitches of the pitch line (a wedge round its axis), so every test is a
small boolean.
"""

from __future__ import annotations

import html
import math
from pathlib import Path

import numpy as np

from ...checks.footer import check_footer
from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.findings import Finding, Result
from ...core.protocol import Motion, Trace
from ...errors import DesignError
from ...export.report import figure_png
from ...geometry.helical import sector_prism
from ...checks.contact3d import VOLUME_EPS, overlaps_over_pitch
from ...checks.contact3d import contact_angles as _contact_angles, measured_ratio as _measured_ratio
from ...checks.contact_pattern import CONTACT_GAP_MM, Face, contact_pattern, pattern_finding, pattern_text
from ...geometry.measure import intersection, min_gap, oversize
from .kit import BevelKit, BevelSpec, build_bevel, resolve_bevel
from .schema import BevelDesign

__all__ = ["Bevel", "MECHANISM", "mesh_overlaps", "contact_angles", "measured_ratio", "contact_along_face"]

WEDGE_PITCHES = 2  # each gear is cut to ± this many of its pitches round the pitch line (contact ratio < 2)


def _near_mesh(kit: BevelKit, theta: float):
    """(gear 1 cut, its pose, gear 2 cut, its nominal pose) at gear 1's turn ``theta``: each gear cut
    to a wedge of ± two pitches round the direction of the pitch line in its own frame."""
    s = kit.spec
    P = kit.poses(theta)
    out = []
    for name, tooth, angle in (("gear1", s.gear1, float(theta)), ("gear2", s.gear2, float(s.angle2(theta)))):
        R = 2 * s.pair.cone_distance
        wedge = sector_prism(R, -angle, WEDGE_PITCHES * 2 * math.pi / tooth.teeth, R)
        out += [kit.part(name).solid ^ wedge, P[name]]
    return out


def mesh_overlaps(kit: BevelKit, phases: int, nudge: float = 0.0, theta0: float = 0.0) -> np.ndarray:
    """Exact overlap volumes (mm³) of the two gears at ``phases`` turns of gear 1 spread over one
    of its tooth pitches from ``theta0``; ``nudge``: gear 2 turned that far (rad) from its nominal
    angle (``checks.contact3d.overlaps_over_pitch``)."""
    return overlaps_over_pitch(lambda t: _near_mesh(kit, t), kit.spec.gear1.teeth, phases, nudge, theta0)


def designed_backlash(spec: BevelSpec) -> float:
    """Circumferential backlash at the heel pitch circle (mm): the two gears' arc thinnings there."""
    return spec.gear1.backlash + spec.gear2.backlash


def _reach_guess(kit: BevelKit) -> tuple[float, float]:
    """Half a pitch of gear 2 (farther than any backlash) and the designed play at gear 2 (rad)."""
    s = kit.spec
    return math.pi / s.gear2.teeth, designed_backlash(s) / s.gear2.pitch_radius


def contact_angles(kit: BevelKit, thetas, tol: float = 1e-7) -> dict[str, np.ndarray]:
    """At gear 1's turns ``thetas``: how far gear 2 turns from its nominal angle (rad, about its own
    axis) before it touches gear 1, forwards (``ahead`` > 0) and backwards (``behind`` < 0), and the
    overlap (mm³) at the nominal angle (``checks.contact3d.contact_angles``)."""
    return _contact_angles(lambda t: _near_mesh(kit, t), thetas, *_reach_guess(kit), tol)


def measured_ratio(kit: BevelKit, turns: int = 1, tol: float = 1e-8) -> tuple[float, float, float]:
    """(ratio input/output measured, the driven flank's lag at θ = 0 and at θ = 2π·turns, rad)
    (``checks.contact3d.measured_ratio``)."""
    return _measured_ratio(lambda t: _near_mesh(kit, t), kit.spec.angle2, *_reach_guess(kit), turns, tol)


def contact_along_face(kit: BevelKit, thetas, play: dict) -> dict:
    """Where along the face, toe to heel, gear 2's loaded flank comes within ``CONTACT_GAP_MM`` (along its
    heel pitch circle) of gear 1's at gear 1's turns ``thetas``, ``play`` their ``contact_angles``
    (``checks.contact_pattern``). The coordinate: the cone distance in gear 2's frame, s = ρ sin δ_2 − a
    cos δ_2 (ρ from its axis, a along it from the apex), which is R − b on the toe's back cone and R on
    the heel's."""
    s = kit.spec
    d = s.gear2.pitch_angle
    sd, cd = math.sin(d), math.cos(d)

    def cone_distance(points: np.ndarray, Ta: np.ndarray, Tb: np.ndarray) -> np.ndarray:
        local = (points - Tb[:3, 3]) @ Tb[:3, :3]
        return np.hypot(local[:, 0], local[:, 1]) * sd - local[:, 2] * cd

    R, b = s.pair.cone_distance, s.gear2.face_width
    face = Face(cone_distance, R - b, R, ("the toe", "the heel"), "the face (toe to heel)")
    reach, _ = _reach_guess(kit)
    p = contact_pattern(lambda t: _near_mesh(kit, t), thetas, play["ahead"], play["overlap_mm3"],
                        CONTACT_GAP_MM / s.gear2.pitch_radius, [face], reach)[0]
    return {"gap_mm": CONTACT_GAP_MM, "gap_along": "gear 2's heel pitch circle", **p}


class Bevel:
    kind = "bevel"
    title = "straight bevel pair"
    schema = BevelDesign
    motion = Motion("input angle", "rad", (0.0, 2 * math.pi))
    csv_header = "input_rad,output_rad,transmission_error_rad,backlash_mm\n"
    trace_needs_kit = True
    role_colours = {"gear": "#4c78a8", "base": "#8c8c8c", "axle": "#e45756"}

    def resolve(self, raw: LoadedDesign) -> BevelSpec:
        return resolve_bevel(raw)

    def build(self, spec: BevelSpec, progress=None) -> BevelKit:
        try:
            return build_bevel(spec, progress)
        except ValueError as e:
            raise DesignError(str(e), "gears.teeth") from None

    def refuse(self, spec: BevelSpec, kit: BevelKit) -> None:
        for part, ext in oversize(kit.parts, spec.printer.envelope):
            raise DesignError(f"{part.name} measures {ext.round(1)} mm and does not fit the printer in any orientation",
                              "gears.module_mm")

    def findings(self, spec: BevelSpec):
        return []

    def _numbers(self, spec: BevelSpec) -> dict:
        r6 = lambda x: float(round(float(x), 6))  # noqa: E731
        p = spec.pair
        g = p.gears
        return {"teeth": list(p.teeth), "module_mm": p.module, "pressure_angle_deg": r6(math.degrees(p.pressure_angle)),
                "shaft_angle_deg": r6(math.degrees(p.shaft_angle)),
                "tooth_form": "spherical involute (exact; straight teeth through the apex)",
                "pitch_angle_deg": [r6(math.degrees(t.pitch_angle)) for t in g],
                "pitch_diameter_mm": [r6(2 * t.pitch_radius) for t in g],
                "tip_diameter_mm": [r6(2 * t.blank(0.0)[2, 0]) for t in g],
                "base_angle_deg": [r6(math.degrees(t.base_angle)) for t in g],
                "cone_distance_mm": r6(p.cone_distance), "face_width_mm": g[0].face_width,
                "contact_ratio": r6(p.contact_ratio()), "ratio": f"{p.teeth[1]}/{p.teeth[0]}",
                "apex_height_mm": r6(spec.z_apex)}

    def design_summary(self, spec: BevelSpec, kit: BevelKit) -> dict:
        return {"name": spec.name, "kind": self.kind, "printer": spec.printer.name,
                "material": spec.material, "density_g_cm3": float(round(spec.density * 1000, 6)), **self._numbers(spec)}

    def kit_files(self, spec: BevelSpec, kit: BevelKit, raw: LoadedDesign) -> dict[str, bytes]:
        data = raw.document()
        data["printer"] = "printer.yaml"
        return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}

    def plate_margin(self, spec: BevelSpec) -> float:
        return spec.plate_margin

    def check(self, spec: BevelSpec, kit: BevelKit, samples: int | None = None, progress=None) -> Result:
        """The gears never overlap at phases over a tooth pitch (exact 3-D), keep backlash both ways,
        clear the base, post, block and pin over a turn, and each bore clears its shaft."""
        res = Result()
        n = samples or spec.samples
        pitch = 2 * math.pi / spec.gear1.teeth
        thetas = pitch * np.arange(n) / n
        play = contact_angles(kit, thetas, 1e-5)  # 1e-5 rad at gear 2: 0.2 µm on its pitch circle
        if progress:
            progress(n, n)
        r2 = spec.gear2.pitch_radius
        bad = np.flatnonzero(play["overlap_mm3"] > VOLUME_EPS)
        if len(bad):
            k = bad[np.argmax(play["overlap_mm3"][bad])]
            res.add(Finding("interference", "fail", f"gear1 and gear2 overlap by {play['overlap_mm3'][k]:.4f} mm³ at "
                            f"{len(bad)} of {n} phases", ("gear1", "gear2"), float(thetas[k]),
                            float(play["overlap_mm3"][k]), "mm3", key="gears.backlash_per_gear_mm"))
        backlash = (play["ahead"] - play["behind"]) * r2
        if backlash.min() <= 0:
            res.add(Finding("mesh", "fail", "the teeth jam: no backlash left", ("gear1", "gear2"),
                            float(thetas[np.argmin(backlash)]), float(backlash.min()), "mm",
                            key="gears.backlash_per_gear_mm"))
        # the frame: the gears against the base (post, block) and the pin, exact 3-D, over a turn of gear 1
        closest = {}
        for t in np.linspace(0.0, 2 * math.pi, 4, endpoint=False):
            P = kit.poses(float(t))
            for g in ("gear1", "gear2"):
                for other in ("base", "pin2"):
                    v = intersection(kit.part(g).solid, P[g], kit.part(other).solid, P[other])[0]
                    if v > VOLUME_EPS:
                        res.add(Finding("interference", "fail", f"{g} and {other} overlap by {v:.4f} mm³",
                                        (g, other), float(t), v, "mm3", key="frame"))
                    gap = min_gap(kit.part(g).solid, P[g], kit.part(other).solid, P[other], 5.0)
                    closest[f"{g}-{other}"] = min(closest.get(f"{g}-{other}", math.inf), gap)
        radial = spec.running / 2
        if radial <= 0:
            res.add(Finding("fit", "fail", f"the bores grip their shafts ({radial:.3f} mm radial gap)", ("gear1", "base"),
                            value=radial, unit="mm", key="shafts.running_clearance_diametral_mm"))
        contact = contact_along_face(kit, thetas, play)
        res.add(pattern_finding(contact, ("gear1", "gear2"), "gears.teeth",
                                hint="the flanks are not conjugate along the face (the solids or their poses)"))
        te = play["ahead"] * r2
        res.figures.update(samples=n, phases_over="one tooth pitch of gear 1",
                           max_overlap_mm3=float(play["overlap_mm3"].max()), contact_along_face=contact,
                           backlash_mm={"min": float(backlash.min()), "max": float(backlash.max()),
                                        "designed": designed_backlash(spec)},
                           transmission_error_mm={"peak_to_peak": float(np.ptp(te)), "mean": float(te.mean())},
                           closest_mm={k: float(round(v, 4)) for k, v in closest.items()}, radial_gap_mm=float(radial))
        from ...checks.bed import bed_findings
        from ...checks.bores import bore_findings

        found, on_bed = bed_findings(kit.parts, kit.printer)
        res.add(*found)
        found, bores = bore_findings(kit.parts)
        res.add(*found)
        res.figures["printability"] = {**on_bed, "bores": bores}
        return res

    def tolerance_model(self, spec: BevelSpec, kit: BevelKit, result: Result, accuracy_mm: float,
                        seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: each
        gear where its mesh pushes it, sideways in its bore and back to its axial stop; otherwise centred
        where the check had it, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: BevelSpec, kit: BevelKit, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        """The transmission error over one tooth pitch of gear 1 (where gear 2's driven flank sits
        against its nominal angle, µm along its heel pitch circle), the backlash, and the ratio
        measured from gear 2's loaded angle after one whole turn of gear 1; transmission.png."""
        n = samples or spec.samples
        pitch = 2 * math.pi / spec.gear1.teeth
        thetas = pitch * np.arange(n + 1) / n
        play = contact_angles(kit, thetas, 1e-7)
        r2 = spec.gear2.pitch_radius
        te, backlash = play["ahead"], (play["ahead"] - play["behind"]) * r2
        ratio, _, _ = measured_ratio(kit)
        design = float(spec.pair.ratio)
        out_angle = spec.angle2(thetas) + te
        slope = np.diff(out_angle) / np.diff(thetas)
        local = float(np.abs(slope / spec.pair.speed2() - 1).max())
        stats = {"kind": self.kind, "samples": len(thetas), "ratio_design": design, "ratio_measured": ratio,
                 "ratio_relative_error": abs(ratio / design - 1), "instantaneous_ratio_deviation": local,
                 "transmission_error_rad": {"mean": float(te.mean()), "peak_to_peak": float(np.ptp(te))},
                 "transmission_error_mm": {"mean": float(te.mean() * r2), "peak_to_peak": float(np.ptp(te) * r2)},
                 "backlash_mm": {"min": float(backlash.min()), "max": float(backlash.max()),
                                 "designed": designed_backlash(spec)},
                 "contact_along_face": contact_along_face(kit, thetas[:-1], {k: v[:-1] for k, v in play.items()})}
        files = []
        if out is not None:
            (out / "transmission.png").write_bytes(_figure(spec, thetas, te * r2, backlash))
            files = ["transmission.png"]
        return Trace(stats, files, columns=("input_rad", "output_rad", "transmission_error_rad", "backlash_mm"),
                     data=np.column_stack([thetas, out_angle, te, backlash]))

    def csv(self, trace: Trace) -> str:
        return self.csv_header + "".join(f"{a:.9f},{b:.9f},{c:.9f},{d:.6f}\n" for a, b, c, d in trace.data)

    def assembly_steps(self, spec: BevelSpec, kit: BevelKit) -> list[tuple[str, tuple[str, ...]]]:
        return [("Stand the base on the table: gear 1's post up, gear 2's block beside it.", ("base",)),
                (f"Slide gear1 ({spec.gear1.teeth} teeth) down over the post, its teeth up.", ("gear1",)),
                (f"Push the pin into the block's hole, slide gear2 ({spec.gear2.teeth} teeth) onto it, hub first, "
                 "until its teeth sit in gear1's; turn gear1 by hand: both turn freely." +
                 (" Gear2 leans over gear1 (shafts past 90°): its weight slides it down the pin into the mesh "
                  "at rest; driven, the mesh's thrust pushes it back against its block." if spec.pair.axis2[2] < 0
                  else ""), ("pin2", "gear2"))]

    def bill_text(self, spec: BevelSpec, man: dict, dest, seconds: float) -> str:
        p = spec.pair
        what = "mitre pair" if p.teeth[0] == p.teeth[1] and abs(p.shaft_angle - math.pi / 2) < 1e-9 else "bevel pair"
        lines = [f"{spec.name}: straight {what} {p.teeth[0]}/{p.teeth[1]} teeth, module {p.module:g} mm at the heel, "
                 f"shafts at {math.degrees(p.shaft_angle):g}°, pitch cones {math.degrees(p.gears[0].pitch_angle):.3f}° "
                 f"+ {math.degrees(p.gears[1].pitch_angle):.3f}°, cone distance {p.cone_distance:.3f} mm, face "
                 f"{p.gears[0].face_width:g} mm; ratio {p.teeth[1]}:{p.teeth[0]} (input turns per output turn)",
                 "teeth: spherical involute (exact), straight through the apex (conical)"]
        lines += [f"{q['name']:<8}{q['role']:<6}{q['triangles']:>9} triangles {q['volume_mm3'] / 1000:8.2f} cm3 "
                  f"{q['mass_g']:7.1f} g  {' x '.join(f'{x:.1f}' for x in q['bbox_mm'])} mm" for q in man["parts"]]
        lines.append(f"wrote {dest}/ in {seconds:.2f} s")
        return "\n".join(lines)

    def check_text(self, spec: BevelSpec, result: Result, folder, seconds: float) -> str:
        f = result.figures
        b, te = f["backlash_mm"], f["transmission_error_mm"]
        lines = [f"{spec.name}: {f['samples']} phases over one tooth pitch of gear 1, exact 3-D",
                 f"  largest overlap {f['max_overlap_mm3']:.6f} mm³; backlash {b['min']:.3f}–{b['max']:.3f} mm along "
                 f"gear 2's heel pitch circle (designed {b['designed']:.3f} mm); transmission error "
                 f"{1000 * te['peak_to_peak']:.1f} µm peak to peak",
                 "  " + pattern_text(f["contact_along_face"]),
                 "  closest: " + ", ".join(f"{k} {v:.2f} mm" for k, v in f["closest_mm"].items())]
        return "\n".join(lines + check_footer(result, seconds, folder))

    def trace_text(self, spec: BevelSpec, trace: Trace, folder) -> str:
        s = trace.stats
        lines = [f"{spec.name}: ratio {s['ratio_measured']:.9f} measured after one turn of gear 1 (design "
                 f"{s['ratio_design']:.9f}, relative error {s['ratio_relative_error']:.1e}); between phases within "
                 f"{100 * s['instantaneous_ratio_deviation']:.3f} % of it",
                 f"  transmission error {1000 * s['transmission_error_mm']['peak_to_peak']:.1f} µm peak to peak along "
                 f"gear 2's heel pitch circle over a tooth ({s['samples']} phases); backlash "
                 f"{s['backlash_mm']['min']:.3f}–{s['backlash_mm']['max']:.3f} mm",
                 "  " + pattern_text(s["contact_along_face"])]
        if folder:
            lines.append(f"plots: {folder}/{', '.join(trace.files)}")
        return "\n".join(lines)

    def report_sections(self, spec: BevelSpec, kit: BevelKit, result: Result, trace: Trace,
                        files: dict) -> list[tuple[str, str]]:
        from ...export import report as R

        d = self._numbers(spec)
        design = R.table(["", "gear 1 (input)", "gear 2 (output)"],
                         [["teeth", *d["teeth"]], ["pitch cone angle °", *d["pitch_angle_deg"]],
                          ["heel pitch diameter mm", *d["pitch_diameter_mm"]],
                          ["heel tip diameter mm", *d["tip_diameter_mm"]],
                          ["base cone angle °", *d["base_angle_deg"]]]) \
            + (f"<p>Module {d['module_mm']:g} mm at the heel, pressure angle {d['pressure_angle_deg']:g}°, shafts at "
               f"{d['shaft_angle_deg']:g}°, cone distance {d['cone_distance_mm']:.3f} mm, face width "
               f"{d['face_width_mm']:g} mm, contact ratio {d['contact_ratio']:.2f}; ratio {d['ratio']}. Teeth: "
               f"{d['tooth_form']}.</p>")
        f, s = result.figures, trace.stats
        check = (f'<p class="{"ok" if result.ok else "fail"}">{f["samples"]} phases over a tooth pitch, exact 3-D: '
                 f'largest overlap {f["max_overlap_mm3"]:.6f} mm³, backlash {f["backlash_mm"]["min"]:.3f}–'
                 f'{f["backlash_mm"]["max"]:.3f} mm; ratio measured {s["ratio_measured"]:.9f} '
                 f'(relative error {s["ratio_relative_error"]:.1e}).</p>'
                 f'<p>{html.escape(pattern_text(f["contact_along_face"]).capitalize())}.</p>')
        return [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error")),
                ("Check", check)]

    def subtitle(self, spec: BevelSpec) -> str:
        p = spec.pair
        return f"{p.teeth[0]}/{p.teeth[1]} straight bevel pair at {math.degrees(p.shaft_angle):g}°"


def _figure(spec: BevelSpec, thetas: np.ndarray, te_mm: np.ndarray, backlash: np.ndarray) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4))
    deg = np.degrees(thetas)
    ax.plot(deg, 1000 * te_mm, "-o", ms=3, label="transmission error (driven flank), µm")
    ax.plot(deg, 1000 * backlash, "-s", ms=3, label="backlash, µm")
    ax.set_xlabel("gear 1 angle (°), one tooth pitch")
    ax.set_ylabel("µm along gear 2's heel pitch circle")
    ax.set_title(f"{spec.name}: exact 3-D contact of the printed solids")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return figure_png(fig, 110)


MECHANISM = Bevel()
