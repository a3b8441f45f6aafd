"""A crossed helical pair (``kind: crossed_helical``) behind the Mechanism protocol: built, checked
exactly in 3-D (manifold3d intersections of the posed solids at phases over a tooth pitch), traced
(transmission error and the ratio measured from where gear 2's flank touches gear 1's) and reported.

The contact search: gear 2 is turned from its nominal angle about its own axis until its solid
first overlaps gear 1's (bisection on the exact intersection volume), both ways; each solid is first
cut to the few teeth that can reach the mesh at that phase (a sector of ± the face's twist and
three pitches round the pitch point), so every test is a small boolean.
"""

from __future__ import annotations

import html
import math
from pathlib import Path

import numpy as np

from ...checks.footer import check_footer
from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.findings import Result
from ...core.quantise import r6
from ...core.protocol import Motion, Trace
from ...errors import DesignError
from ...export.report import transmission_figure
from ...checks.contact3d import overlaps_over_pitch, pair_check
from ...checks.contact3d import contact_angles as _contact_angles, measured_ratio as _measured_ratio
from ...checks.contact_pattern import CONTACT_GAP_MM, Face, contact_pattern, pattern_finding, pattern_text
from ...geometry.measure import oversize
from ...geometry.helical import cylinder_along
from ...design.crossed_helical import efficiency, friction_angle
from .kit import CrossedKit, CrossedSpec, build_crossed, is_worm, resolve_crossed
from .schema import CrossedHelicalDesign

__all__ = ["CrossedHelical", "MECHANISM", "mesh_overlaps", "contact_angles", "contact_along_face"]


def _near_mesh(kit: CrossedKit, theta: float):
    """(gear 1 cut, its pose, gear 2 cut, its nominal pose) at gear 1's turn ``theta``: each gear
    cut to the other's tip cylinder (0.5 mm larger, 1 mm longer), the only place they can touch."""
    s = kit.spec
    P = kit.poses(theta)
    out = []
    for i, (name, other) in enumerate((("gear1", "gear2"), ("gear2", "gear1"))):
        j = 1 - i
        g = (s.gear1, s.gear2)[j]
        local = np.linalg.inv(P[name]) @ P[other]
        cut = kit.part(name).solid ^ cylinder_along(g.tip_radius + 0.5, s.face_width[j] + 1.0, 0.05, local)
        out += [cut, P[name]]
    return out


def mesh_overlaps(kit: CrossedKit, phases: int, nudge: float = 0.0, theta0: float = 0.0) -> np.ndarray:
    """Exact overlap volumes (mm³) of the two gears at ``phases`` turns of gear 1 spread over one
    of its tooth pitches from ``theta0``; ``nudge``: gear 2 turned that far (rad) from its nominal
    angle (``checks.contact3d.overlaps_over_pitch``)."""
    return overlaps_over_pitch(lambda t: _near_mesh(kit, t), kit.spec.gear1.teeth, phases, nudge, theta0)


def _reach_guess(kit: CrossedKit) -> tuple[float, float]:
    """Half a pitch of gear 2 (farther than any backlash) and the designed play at gear 2 (rad)."""
    s = kit.spec
    return math.pi / s.gear2.teeth, MECHANISM._designed_backlash(s) / s.pair.pitch_radius(1)


def contact_angles(kit: CrossedKit, thetas, tol: float = 1e-7) -> dict[str, np.ndarray]:
    """At gear 1's turns ``thetas``: how far gear 2 turns from its nominal angle (rad, about its own
    axis) before it touches gear 1, forwards (``ahead`` > 0) and backwards (``behind`` < 0), and the
    overlap (mm³) at the nominal angle (``checks.contact3d.contact_angles``)."""
    return _contact_angles(lambda t: _near_mesh(kit, t), thetas, *_reach_guess(kit), tol)


def measured_ratio(kit: CrossedKit, turns: int = 1, tol: float = 1e-8) -> tuple[float, float, float]:
    """(ratio input/output measured, the driven flank's lag at θ = 0 and at θ = 2π·turns, rad)
    (``checks.contact3d.measured_ratio``)."""
    return _measured_ratio(lambda t: _near_mesh(kit, t), kit.spec.angle2, *_reach_guess(kit), turns, tol)


def _along_axis(which: int):
    """A face coordinate: the points along gear ``which``'s axis (0: gear 1, 1: gear 2) from its mid-plane, mm."""
    def coord(points: np.ndarray, Ta: np.ndarray, Tb: np.ndarray) -> np.ndarray:
        T = (Ta, Tb)[which]
        return (points - T[:3, 3]) @ T[:3, 2]
    return coord


def contact_along_face(kit: CrossedKit, thetas, play: dict) -> dict:
    """Where along the faces gear 2's loaded flank comes within ``CONTACT_GAP_MM`` (along its pitch
    circle) of gear 1's at gear 1's turns ``thetas``, ``play`` their ``contact_angles``
    (``checks.contact_pattern``): along gear 2's face (its axis, from the block1 end to the block2 end:
    the figure the finding judges) and along gear 1's (its axis, bottom to top: a worm's length), as
    ``{"gear2": ..., "gear1": ...}``."""
    s = kit.spec
    b1, b2 = s.face_width
    worm = is_worm(s.pair)
    faces = [Face(_along_axis(1), -b2 / 2, b2 / 2, ("the block1 end", "the block2 end"),
                  "the wheel's face" if worm else "gear 2's face"),
             Face(_along_axis(0), -b1 / 2, b1 / 2, ("the bottom", "the top"),
                  "the worm's length" if worm else "gear 1's face")]
    reach, _ = _reach_guess(kit)
    p2, p1 = contact_pattern(lambda t: _near_mesh(kit, t), thetas, play["ahead"], play["overlap_mm3"],
                             CONTACT_GAP_MM / s.pair.pitch_radius(1), faces, reach)
    return {"gap_mm": CONTACT_GAP_MM, "gap_along": "gear 2's pitch circle", "gear2": p2, "gear1": p1}


class CrossedHelical:
    kind = "crossed_helical"
    title = "crossed helical pair"
    schema = CrossedHelicalDesign
    motion = Motion("input angle", "rad", (0.0, 2 * math.pi))
    csv_header = "input_rad,output_rad,transmission_error_rad,backlash_mm\n"
    trace_needs_kit = True
    role_colours = {"gear": "#4c78a8", "base": "#8c8c8c", "axle": "#e45756"}

    def resolve(self, raw: LoadedDesign) -> CrossedSpec:
        return resolve_crossed(raw)

    def build(self, spec: CrossedSpec, progress=None) -> CrossedKit:
        try:
            return build_crossed(spec, progress)
        except ValueError as e:
            raise DesignError(str(e), "shafts.diameter_mm") from None

    def refuse(self, spec: CrossedSpec, kit: CrossedKit) -> None:
        for part, ext in oversize(kit.parts, spec.printer.envelope):
            raise DesignError(f"{part.name} measures {ext.round(1)} mm and does not fit the printer in any orientation",
                              "gears.normal_module_mm")

    def findings(self, spec: CrossedSpec):
        return []

    def _numbers(self, spec: CrossedSpec) -> dict:
        p = spec.pair
        return {"teeth": list(p.teeth), "normal_module_mm": p.normal_module,
                "normal_pressure_angle_deg": r6(math.degrees(p.normal_pressure_angle)),
                "helix_angle_deg": [r6(math.degrees(b)) for b in p.helix], "hand": "right",
                "shaft_angle_deg": r6(math.degrees(p.shaft_angle)),
                "transverse_module_mm": [r6(s.module) for s in p.systems],
                "transverse_pressure_angle_deg": [r6(math.degrees(s.pressure_angle)) for s in p.systems],
                "pitch_diameter_mm": [r6(2 * p.pitch_radius(i)) for i in range(2)],
                "tip_diameter_mm": [r6(2 * spec.gear1.tip_radius), r6(2 * spec.gear2.tip_radius)],
                "centre_distance_mm": r6(spec.centre_distance), "ratio": f"{p.teeth[1]}/{p.teeth[0]}",
                "face_width_mm": list(spec.face_width), "shaft_height_mm": r6(spec.z_c),
                "sliding_per_rolling": r6(p.sliding_speed() / p.pitch_radius(0)), "throated_wheel": spec.throated,
                **self._locking(spec)}

    def _locking(self, spec: CrossedSpec) -> dict:
        """Efficiency both ways and the self-locking answer for the stated friction (gear 1 a worm:
        lead angle γ = 90° − β_1 against the friction angle φ' = atan(μ / cos α_n))."""
        p, mu = spec.pair, spec.friction
        fwd, back = efficiency(p, mu), efficiency(p, mu, backwards=True)
        out = {"worm": "ZI (involute helicoid)" if is_worm(p) else None,
               "friction_coefficient": mu, "friction_angle_deg": round(math.degrees(friction_angle(p, mu)), 4),
               "efficiency_gear1_driving": round(fwd, 4), "efficiency_gear2_driving": round(back, 4),
               "self_locking": back <= 0}
        if is_worm(p):
            out["lead_angle_deg"] = round(90.0 - math.degrees(abs(p.helix[0])), 6)
        return out

    def _locking_text(self, spec: CrossedSpec) -> str:
        k = self._locking(spec)
        lead = (f"worm {k['worm']}, lead angle {k['lead_angle_deg']:g}°; " if k["worm"] else "")
        return (f"{lead}friction μ {k['friction_coefficient']:g} (stated, checks.friction_coefficient): friction angle "
                f"{k['friction_angle_deg']:.2f}°, efficiency {100 * k['efficiency_gear1_driving']:.0f} % driving gear 1, "
                + ("self-locking: gear 2 cannot drive gear 1" if k["self_locking"] else
                   f"{100 * k['efficiency_gear2_driving']:.0f} % driving gear 2: not self-locking"))

    def design_summary(self, spec: CrossedSpec, kit: CrossedKit) -> dict:
        return {"name": spec.name, "kind": self.kind, "printer": spec.printer.name,
                "material": spec.material, "density_g_cm3": float(round(spec.density * 1000, 6)), **self._numbers(spec)}

    def kit_files(self, spec: CrossedSpec, kit: CrossedKit, raw: LoadedDesign) -> dict[str, bytes]:
        data = raw.document()
        data["printer"] = "printer.yaml"
        return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}

    def plate_margin(self, spec: CrossedSpec) -> float:
        return spec.plate_margin

    def _designed_backlash(self, spec: CrossedSpec) -> float:
        """Circumferential backlash along gear 2's reference pitch circle (mm): each gear's transverse
        thinning is j cos β_i in the normal plane, and a turn of gear 2 moves its flank 1/cos β_2 as
        far along its pitch circle as along the normal: (j_1 cos β_1 + j_2 cos β_2) / cos β_2."""
        b1, b2 = spec.pair.helix
        j1, j2 = spec.gear1.system.backlash_per_gear, spec.gear2.system.backlash_per_gear
        return (j1 * math.cos(b1) + j2 * math.cos(b2)) / math.cos(b2)

    def check(self, spec: CrossedSpec, kit: CrossedKit, samples: int | None = None, progress=None) -> Result:
        """The gears never overlap at phases over a tooth pitch (exact 3-D), keep backlash both ways,
        clear the base, post, blocks and pin over a turn, and each bore clears its shaft."""
        res = Result()
        n = samples or spec.samples
        pitch = 2 * math.pi / spec.gear1.teeth
        thetas = pitch * np.arange(n) / n
        play = contact_angles(kit, thetas, 1e-5)  # 1e-5 rad at gear 2: 0.2 µm on its pitch circle
        if progress:
            progress(n, n)
        contact = contact_along_face(kit, thetas, play)
        pair_check(res, kit, thetas, play, spec.pair.pitch_radius(1), spec.running, self._designed_backlash(spec),
                   contact, pattern_finding(contact["gear2"], ("gear1", "gear2"), "gears.face_width_mm[1]",
                                            hint=self._point_contact(spec)),
                   {"centre_distance_mm": round(spec.centre_distance, 6)})
        return res

    def _point_contact(self, spec: CrossedSpec) -> str:
        """What a short contact pattern means here (the finding's hint)."""
        if spec.throated:
            return "a throated wheel should bear across its face: its cut or the poses are off"
        if is_worm(spec.pair):
            return ("a plain helical wheel touches the worm at a point, which crosses little of the wheel's face "
                    "over a turn (a throated wheel wraps round the worm)")
        return "crossed helical gears touch at a point: their path of contact crosses only part of the face"

    def tolerance_model(self, spec: CrossedSpec, kit: CrossedKit, result: Result, accuracy_mm: float,
                        seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: the
        gears sit where their mesh pushes them in their bores; otherwise centred, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def trace(self, spec: CrossedSpec, kit: CrossedKit, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        """The transmission error over one tooth pitch of gear 1 (where gear 2's driven flank sits
        against its nominal angle, µm along its pitch circle), the backlash, and the ratio measured
        from gear 2's loaded angle after one whole turn of gear 1; transmission.png."""
        n = samples or spec.samples
        pitch = 2 * math.pi / spec.gear1.teeth
        thetas = pitch * np.arange(n + 1) / n
        play = contact_angles(kit, thetas, 1e-7)
        r2 = spec.pair.pitch_radius(1)
        te, backlash = play["ahead"], (play["ahead"] - play["behind"]) * r2
        ratio, _, _ = measured_ratio(kit)
        design = float(spec.pair.ratio)
        out_angle = spec.angle2(thetas) + te
        # the instantaneous ratio between samples: gear 2's loaded angle's slope, against the nominal
        slope = np.diff(out_angle) / np.diff(thetas)
        local = float(np.abs(slope / spec.pair.speed2() - 1).max())
        stats = {"kind": self.kind, "samples": len(thetas), "ratio_design": design, "ratio_measured": ratio,
                 "ratio_relative_error": abs(ratio / design - 1), "instantaneous_ratio_deviation": local,
                 "transmission_error_rad": {"mean": float(te.mean()), "peak_to_peak": float(np.ptp(te))},
                 "transmission_error_mm": {"mean": float(te.mean() * r2), "peak_to_peak": float(np.ptp(te) * r2)},
                 "backlash_mm": {"min": float(backlash.min()), "max": float(backlash.max()),
                                 "designed": self._designed_backlash(spec)},
                 "contact_along_face": contact_along_face(kit, thetas[:-1], {k: v[:-1] for k, v in play.items()})}
        files = []
        if out is not None:
            (out / "transmission.png").write_bytes(transmission_figure(
                f"{spec.name}: exact 3-D contact of the printed solids", thetas, te * r2, backlash,
                "gear 1 angle (°), one tooth pitch", "µm along gear 2's pitch circle"))
            files = ["transmission.png"]
        return Trace(stats, files, columns=("input_rad", "output_rad", "transmission_error_rad", "backlash_mm"),
                     data=np.column_stack([thetas, out_angle, te, backlash]))

    def csv(self, trace: Trace) -> str:
        return self.csv_header + "".join(f"{a:.9f},{b:.9f},{c:.9f},{d:.6f}\n" for a, b, c, d in trace.data)

    def assembly_steps(self, spec: CrossedSpec, kit: CrossedKit) -> list[tuple[str, tuple[str, ...]]]:
        return [("Stand the base on the table: gear 1's post up, gear 2's two blocks beside it.", ("base",)),
                (f"Slide gear1 ({spec.gear1.teeth} teeth) down over the post until its collar rests on the base.",
                 ("gear1",)),
                (f"Hold gear2 ({spec.gear2.teeth} teeth) between the blocks, its teeth in gear1's, and press the pin "
                 "through the first block, the gear and the second block; turn gear1 by hand: both turn freely.",
                 ("gear2", "pin2"))]

    def bill_text(self, spec: CrossedSpec, man: dict, dest, seconds: float) -> str:
        p = spec.pair
        wheel = "throated wheel (cut by the worm's envelope)" if spec.throated else "helical wheel"
        what = (f"a {p.teeth[0]}-start ZI worm and a {p.teeth[1]}-tooth {wheel}" if is_worm(p) else
                f"crossed helical pair {p.teeth[0]}/{p.teeth[1]} teeth")
        lines = [f"{spec.name}: {what}, normal module {p.normal_module:g} mm, helix {math.degrees(p.helix[0]):g}° + "
                 f"{math.degrees(p.helix[1]):g}° (right hand) on shafts at {math.degrees(p.shaft_angle):g}°, "
                 f"{spec.centre_distance:.3f} mm apart; ratio {p.teeth[1]}:{p.teeth[0]} (input turns per output turn)"]
        lines.append(self._locking_text(spec))
        lines += [f"{q['name']:<8}{q['role']:<6}{q['triangles']:>9} triangles {q['volume_mm3'] / 1000:8.2f} cm3 "
                  f"{q['mass_g']:7.1f} g  {' x '.join(f'{x:.1f}' for x in q['bbox_mm'])} mm" for q in man["parts"]]
        lines.append(f"wrote {dest}/ in {seconds:.2f} s")
        return "\n".join(lines)

    def check_text(self, spec: CrossedSpec, result: Result, folder, seconds: float) -> str:
        f = result.figures
        b, te = f["backlash_mm"], f["transmission_error_mm"]
        lines = [f"{spec.name}: {f['samples']} phases over one tooth pitch of gear 1, exact 3-D",
                 f"  largest overlap {f['max_overlap_mm3']:.6f} mm³; backlash {b['min']:.3f}–{b['max']:.3f} mm along "
                 f"gear 2's pitch circle (designed {b['designed']:.3f} mm); transmission error "
                 f"{1000 * te['peak_to_peak']:.1f} µm peak to peak",
                 *("  " + pattern_text(f["contact_along_face"][g]) for g in ("gear2", "gear1")),
                 "  closest: " + ", ".join(f"{k} {v:.2f} mm" for k, v in f["closest_mm"].items()),
                 "  " + self._locking_text(spec)]
        return "\n".join(lines + check_footer(result, seconds, folder))

    def trace_text(self, spec: CrossedSpec, trace: Trace, folder) -> str:
        s = trace.stats
        lines = [f"{spec.name}: ratio {s['ratio_measured']:.9f} measured after one turn of gear 1 (design "
                 f"{s['ratio_design']:.9f}, relative error {s['ratio_relative_error']:.1e}); between phases within "
                 f"{100 * s['instantaneous_ratio_deviation']:.3f} % of it",
                 f"  transmission error {1000 * s['transmission_error_mm']['peak_to_peak']:.1f} µm peak to peak along "
                 f"gear 2's pitch circle over a tooth ({s['samples']} phases); backlash "
                 f"{s['backlash_mm']['min']:.3f}–{s['backlash_mm']['max']:.3f} mm",
                 *("  " + pattern_text(s["contact_along_face"][g]) for g in ("gear2", "gear1"))]
        if folder:
            lines.append(f"plots: {folder}/{', '.join(trace.files)}")
        return "\n".join(lines)

    def report_sections(self, spec: CrossedSpec, kit: CrossedKit, result: Result, trace: Trace,
                        files: dict) -> list[tuple[str, str]]:
        from ...export import report as R

        d = self._numbers(spec)
        design = R.table(["", "gear 1 (input)", "gear 2 (output)"],
                         [["teeth", *d["teeth"]], ["helix angle °", *d["helix_angle_deg"]],
                          ["transverse module mm", *d["transverse_module_mm"]],
                          ["pitch diameter mm", *d["pitch_diameter_mm"]], ["tip diameter mm", *d["tip_diameter_mm"]],
                          ["face width mm", *d["face_width_mm"]]]) \
            + (f"<p>Normal module {d['normal_module_mm']:g} mm, normal pressure angle "
               f"{d['normal_pressure_angle_deg']:g}°, shafts at {d['shaft_angle_deg']:g}°, "
               f"{d['centre_distance_mm']:.3f} mm apart; ratio {d['ratio']}; both right hand. Sliding at the pitch "
               f"point {d['sliding_per_rolling']:.3f} mm per mm of gear 1's pitch circle. "
               f"{self._locking_text(spec).capitalize()}.</p>")
        f, s = result.figures, trace.stats
        check = (f'<p class="{"ok" if result.ok else "fail"}">{f["samples"]} phases over a tooth pitch, exact 3-D: '
                 f'largest overlap {f["max_overlap_mm3"]:.6f} mm³, backlash {f["backlash_mm"]["min"]:.3f}–'
                 f'{f["backlash_mm"]["max"]:.3f} mm; ratio measured {s["ratio_measured"]:.9f} '
                 f'(relative error {s["ratio_relative_error"]:.1e}).</p>'
                 + "".join(f'<p>{html.escape(pattern_text(f["contact_along_face"][g]).capitalize())}.</p>'
                           for g in ("gear2", "gear1")))
        return [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error")),
                ("Check", check)]

    def subtitle(self, spec: CrossedSpec) -> str:
        if is_worm(spec.pair):
            return f"{spec.gear1.teeth}-start worm and {spec.gear2.teeth}-tooth wheel"
        return f"{spec.gear1.teeth}/{spec.gear2.teeth} crossed helical pair"


MECHANISM = CrossedHelical()
