"""Write a printer's calibration coupon: one STL per distinct part, a 3MF of the one build plate, a
picture, a one-page instruction sheet (HTML) and a results template (YAML) — all or nothing, into a
folder partgen made (``outputs.claim_output``: a user's folder is never overwritten)."""

from __future__ import annotations

import html
from pathlib import Path

from ..design.coupon import (BAR, CALIPER_D, FEATURES, GEAR, GEAR_BACKLASH, GEAR_BORE_CLEARANCE_MM, HOLE_D, PRESS,
                             RUNNING, Coupon)
from ..errors import MeshError
from ..geometry.solid import print_arrays
from .outputs import OutputClaim
from .plates import footprint, layout, plate_3mf, plate_meshes
from .render import render
from .stl import Mesh, stl_bytes, stored_mesh
from .verify import mesh_report, read_stl

__all__ = ["BED_MM", "MARGIN_MM", "TEMPLATE_VERSION", "coupon_meshes", "coupon_layout", "results_template",
           "instructions_html", "write_coupon"]

BED_MM = (80.0, 60.0)  # the most bed the coupon may take
MARGIN_MM = 2.0        # between parts on the plate
TEMPLATE_VERSION = 1
COLOURS = {"plate": "#4a90d9", "key": "#e0a030", "gear": "#50a860", "bar": "#b060c0"}


def coupon_meshes(solids: dict) -> dict[str, tuple[Mesh, bytes, int]]:
    """name -> (mesh as its STL stores it, STL bytes, copies); raises MeshError unless every STL is
    one closed, oriented manifold shell."""
    out = {}
    for name, (solid, count) in solids.items():
        v, f, _ = print_arrays(solid, False)
        mesh = stored_mesh(v, f)
        stl = stl_bytes(mesh)
        rep = mesh_report(*read_stl(stl))
        if not rep.ok:
            raise MeshError(f"coupon part {name}: not one closed, oriented manifold shell "
                            f"({', '.join(rep.problems())}) — a bug in partgen; nothing was written")
        out[name] = (mesh, stl, count)
    return out


def coupon_layout(meshes: dict):
    """Every copy packed on one ``BED_MM`` plate (``MARGIN_MM`` apart); ValueError if it takes more."""
    lay = layout([(n, m, k) for n, (m, _, k) in meshes.items()], BED_MM, MARGIN_MM)
    if len(lay.plates) != 1:
        raise ValueError(f"the coupon takes {len(lay.plates)} plates of {BED_MM[0]:g} x {BED_MM[1]:g} mm")
    return lay


def _picture(lay, meshes: dict, title: str) -> bytes:
    placed = plate_meshes(lay, {n: m for n, (m, _, _) in meshes.items()})[0]
    return render([(m.vertices, m.faces, COLOURS.get(name.split("#")[0], "#999999")) for name, m in placed],
                  size_px=(720, 560), elev=50.0, azim=-80.0, title=title)


def results_template(printer: str, printer_name: str) -> str:
    """The YAML the maker fills in (``partgen calibrate`` reads it back)."""
    lines = ["# partgen calibration results: fill in after printing the coupon (see instructions.html),",
             "# then run:  partgen calibrate --printer " + printer + " results.yaml -o my_printer.yaml",
             f"coupon: {TEMPLATE_VERSION}                # the coupon's layout version: leave it",
             f"printer: {printer}    # {printer_name}",
             "printed_on: null          # the date you printed it, e.g. 2025-06-01",
             "filament: null            # e.g. PLA, brand and colour",
             "slicer: null              # e.g. PrusaSlicer 2.8, 0.20 mm, XY hole/contour compensation 0",
             "running:                  # key post turned in holes 1-13: binds | stiff | free (leave null if not tried)"]
    lines += [f"  {i + 1}: null    # hole {HOLE_D + c:.2f} mm, clearance {c:.2f} mm diametral"
              for i, c in enumerate(RUNNING)]
    lines.append("press:                    # key post pressed into holes 14-20: too_tight | holds | loose")
    lines += [f"  {14 + i}: null   # hole {HOLE_D + c:.2f} mm, clearance {c:+.2f} mm diametral"
              for i, c in enumerate(PRESS)]
    lines.append("gears:                    # both gears on the two posts either side of 23-25, pushed together, "
                 "turned: binds | smooth | loose")
    lines += [f"  {23 + i}: null   # backlash {j:.2f} mm" for i, j in enumerate(GEAR_BACKLASH)]
    lines += ["calipers:                 # mm; give one reading or a list of repeats, e.g. [9.82, 9.84]",
              f"  boss_21_diameter_mm: null        # nominal {CALIPER_D:.2f}",
              f"  hole_22_diameter_mm: null        # nominal {CALIPER_D:.2f}",
              f"  bar_26_length_mm: null           # nominal {BAR[0]:.2f}",
              f"  bar_26_width_mm: null            # nominal {BAR[1]:.2f}",
              f"  key_27_post_diameter_mm: null    # nominal {HOLE_D:.2f}", ""]
    return "\n".join(lines)


def instructions_html(printer: str, printer_name: str, c: Coupon, meshes: dict, typical: bool) -> str:
    """The one-page instruction sheet: the picture, what to try, what to write down."""
    e = html.escape
    rows = "".join(f"<tr><td>{n}</td><td>{e(what)}</td></tr>" for n, (what, _) in FEATURES.items())
    parts = ", ".join(f"{e(n)} ×{k}" for n, (_, _, k) in meshes.items())
    w, d, _ = c.plate
    note = ("<p class=note>The profile's fits and accuracy are <b>typical values, not measurements</b> of your "
            "machine: this coupon replaces them with yours.</p>" if typical else "")
    return f"""<!doctype html>
<html><head><meta charset="utf-8"><title>partgen calibration coupon: {e(printer_name)}</title>
<style>body{{font:14px/1.4 sans-serif;max-width:60em;margin:1em auto}} td,th{{padding:1px 8px;text-align:left}}
table{{border-collapse:collapse;font-size:12px}} tr:nth-child(even){{background:#f2f2f2}} .note{{color:#844}}
img{{float:right;width:26em;margin-left:1em}}</style></head><body>
<h1>Calibrate your {e(printer_name)}</h1>
<img src="coupon.png" alt="the coupon on its build plate">
{note}
<p><b>Print</b> <code>coupon.3mf</code> (or the STLs: {parts}) with the filament and slicer settings you will print
kits with, <b>XY hole and contour compensation at 0</b>, no brim, 15–20 % infill. The plate is {w:.1f} × {d:.1f} mm;
everything fits an 80 × 60 mm patch of the bed. Let it cool before you take it off.</p>
<h2>What to try</h2>
<ol>
<li><b>Running fits, holes 1–13</b> (clearance 0.00 to 0.60 mm diametral, one key post {HOLE_D:g} mm). Push the
post of the first key into each hole from the top and turn it. Write <code>binds</code> (will not go in or will not
turn), <code>stiff</code> (turns with effort) or <code>free</code> (turns freely).</li>
<li><b>Press fits, holes 14–20</b> (clearance −0.15 to +0.15 mm), with the second key. Tightest first: write
<code>too_tight</code> (cannot be pressed in by hand), <code>holds</code> (presses in and the plate hangs from it)
or <code>loose</code> (falls out or turns).</li>
<li><b>Gears, 23–25</b>. Put the two gears on the posts either side of a number, push them towards each other and
turn one. Write <code>binds</code>, <code>smooth</code> or <code>loose</code> (turns with visible play). The numbers
are total backlash {', '.join(f'{j:.2f}' for j in GEAR_BACKLASH)} mm with the gears pushed together (their bores
have {GEAR_BORE_CLEARANCE_MM:g} mm clearance on the posts).</li>
<li><b>Calipers</b>: boss 21 and hole 22 ({CALIPER_D:g} mm), the bar 26 ({BAR[0]:g} × {BAR[1]:g} mm, length and width)
and the key post 27 ({HOLE_D:g} mm). Measure mid-height, away from the first layer; two or three readings each
(a list) are better than one.</li>
</ol>
<h2>What to write down</h2>
<p>Fill in <code>results.yaml</code> (every entry is named by the number on the part), then run</p>
<pre>partgen calibrate --printer {e(printer)} results.yaml -o my_printer.yaml</pre>
<p>and build with <code>--printer my_printer.yaml</code>. A calibrated profile makes partgen open holes and trim
outlines by what you measured: leave the slicer's XY compensation at 0 from then on.</p>
<h2>Features</h2><table><tr><th>#</th><th>feature</th></tr>{rows}</table>
<p>Gears: {GEAR.teeth} teeth, module {GEAR.module:g} mm, 20°, bore {GEAR.bore_diameter:.2f} mm.</p>
</body></html>
"""


def write_coupon(claim: OutputClaim, c: Coupon, solids: dict, printer: str, printer_name: str,
                 typical: bool) -> dict:
    """Write the coupon into ``claim`` (checked before the work began), atomically. Returns a summary
    (parts, plate size, mass at 1.24 g/cm³)."""
    meshes = coupon_meshes(solids)
    lay = coupon_layout(meshes)
    plate = lay.plates[0]
    mm = {n: m for n, (m, _, _) in meshes.items()}
    files = {f"{n}.stl": stl for n, (_, stl, _) in meshes.items()}
    files["coupon.3mf"] = plate_3mf(plate, mm, f"calibration coupon: {printer_name}", "",
                                    f"partgen calibration coupon for the {printer_name}, "
                                    f"on a {BED_MM[0]:g} x {BED_MM[1]:g} mm patch of the bed")
    files["coupon.png"] = _picture(lay, meshes, f"calibration coupon: {printer_name}")
    files["instructions.html"] = instructions_html(printer, printer_name, c, meshes, typical).encode()
    files["results.yaml"] = results_template(printer, printer_name).encode()
    with claim as tmp:
        for name, data in files.items():
            (Path(tmp) / name).write_bytes(data)
    volume = sum(m.volume * k for m, _, k in meshes.values())
    hulls = [footprint(mm[p.name], 0.0) for p in plate]
    return {"parts": {n: k for n, (_, _, k) in meshes.items()}, "volume_mm3": float(volume),
            "mass_pla_g": float(volume * 1.24e-3), "plate_mm": [c.plate[0], c.plate[1]],
            "footprint_mm2": float(sum(h.area for h in hulls))}
