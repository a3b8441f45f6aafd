"""The planetary set's report sections (design, trace, what play costs, check), its subtitle and the bill's
heading."""

from __future__ import annotations

import math

from ....core.findings import Result
from ....core.protocol import Trace
from ..common import report as common
from .kit import PlanetaryKit
from .resolve import PlanetarySpec

__all__ = ["report_sections", "subtitle", "bill_text"]


def report_sections(spec: PlanetarySpec, kit: PlanetaryKit, result: Result, trace: Trace, files: dict
                    ) -> list[tuple[str, str]]:
    from ....export import report as R

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
    sections = [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error"))]
    lm = st.get("lost_motion_arcmin")
    if lm:
        sections.append(("What play costs", common.lost_motion_html(
            lm, "arcmin", "the carrier", "The sun held, each planet lets the carrier turn through its two meshes' "
            "backlash over r_sun + r_ring and twice its pin's play over the planets' radius; the sun and the "
            "carrier float on their shafts and share the load out among the planets: they add none.")))
    return sections + [("Check", check)]


def subtitle(spec: PlanetarySpec) -> str:
    return f"planetary set, {spec.teeth.planets} planets, ratio {spec.ratio:.4f}"


def bill_text(spec: PlanetarySpec, man: dict, dest, seconds: float) -> str:
    t = spec.teeth
    head = (f"{spec.name}: planetary, sun {t.sun} / planet {t.planet} ×{t.planets} / ring {t.ring}, ratio "
            f"{t.ratio:.4f}" + (f" (target {spec.target_ratio:g})" if spec.target_ratio else "")
            + f", module {spec.system.module:g} mm")
    return common.bill_text(head, man, dest, seconds)
