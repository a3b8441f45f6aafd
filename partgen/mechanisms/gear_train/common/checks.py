"""What ``check`` prints for a turning train (the stages' and the planetary's: each mesh, the internal
mesh, the backlash at the output; the rack's own is ``rack/checks.py``)."""

from __future__ import annotations

from ....checks.footer import check_footer
from ....core.findings import Result

__all__ = ["check_text"]


def check_text(spec, result: Result, folder, seconds: float) -> str:
    f = result.figures
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
