"""The gear train's report sections (design, trace, what play costs, check), its subtitle and the
bill's heading."""

from __future__ import annotations

import math

from ....core.findings import Result
from ....core.protocol import Trace
from ..common import report as common
from .kit import TrainKit
from .resolve import TrainSpec

__all__ = ["report_sections", "subtitle", "bill_text", "lost_motion_html"]


def lost_motion_html(lm: dict, spec) -> str:
    """The report's "What play costs" of a train: the output's lost motion (arc-minutes) from each
    mesh's backlash and each body's play in its bore, over prints, and the transmission-error band
    (play.lost_motion)."""
    return common.lost_motion_html(
        lm, "arcmin", "the output", "The input held, each mesh lets its driven gear turn through its backlash, "
        "referred to the output through the shafts' speeds; each body may sit anywhere in its bore, and one "
        "place opens the forward limit, another the backward one: a gear in one mesh adds twice its radial play "
        "over its driven gear's base radius.")


def report_sections(spec: TrainSpec, kit: TrainKit, result: Result, trace: Trace, files: dict
                    ) -> list[tuple[str, str]]:
    from ....export import report as R

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
        sections.append(("What play costs", lost_motion_html(lm, spec)))
    return sections + [("Check", check)]


def subtitle(spec: TrainSpec) -> str:
    r = spec.ratio
    return f"{len(spec.stages)}-stage gear train, ratio {r.numerator}/{r.denominator}"


def bill_text(spec: TrainSpec, man: dict, dest, seconds: float) -> str:
    r = spec.ratio
    head = (f"{spec.name}: ratio {r.numerator}/{r.denominator} = {float(r):.4f}"
            + (f" (target {spec.target_ratio:g}, {100 * (float(r) / spec.target_ratio - 1):+.3f} %)"
               if spec.target_ratio else "") + f", module {spec.system.module:g} mm, {len(spec.stages)} stage(s): "
            + ", ".join(f"{st.driver}/{st.driven}" for st in spec.stages))
    return common.bill_text(head, man, dest, seconds)
