"""What every sub-slice's report and bill share: the bill ``build`` prints (a line per part under the
sub-slice's heading) and the assembly steps (the frame, each shaft with its gears and hardware, the
planets and carrier or the rack, the top plate)."""

from __future__ import annotations

__all__ = ["bill_text", "assembly_steps", "lost_motion_html"]

UNITS = {"arcmin": ("arcmin", "{:.1f}"), "mm": ("mm", "{:.3f}")}


def lost_motion_html(lm: dict, unit: str = "arcmin", output: str = "the output", note: str = "") -> str:
    """The report's "What play costs" of a train (``common/play.py``, ``stages/play.py``): the lost motion at
    ``output`` (in ``unit``, "arcmin" or "mm") from each mesh's backlash and the bores' play, over prints
    when the figures have them, the transmission-error band, and a table of where it comes from (a row
    per share: each mesh's backlash, each body's play); ``note``: a sentence after the headline."""
    from ....export import report as R

    u, f = UNITS[unit]
    v = lambda x: f.format(float(x))  # noqa: E731
    band = lm.get(f"transmission_error_band_{unit}")
    html = (f"<p>Lost motion at {output} (the input held, how far {output} moves freely): "
            f"<b>{v(lm['total'])} {u}</b> — each mesh's backlash {v(lm['backlash'])} {u} and the bores' "
            f"play {v(lm['bores'])} {u} (running clearance {2 * lm['radial_play_mm']:g} mm diametral; "
            f"docs/tolerance.md, What play costs).{(' ' + note) if note else ''}</p>")
    if "worst_case" in lm:
        html += (f"<p>Over prints at the printer's ±{lm['accuracy_mm']:g} mm (the tolerance model's features, "
                 f"{lm['prints']:,} prints): worst case <b>{v(lm['worst_case'])} {u}</b> (every feature at its limit, "
                 f"the way that adds play), 95 % of prints under <b>{v(lm['p95'])} {u}</b>, median {v(lm['p50'])} "
                 f"{u}.</p>")
    if band:
        html += (f"<p>Transmission-error band: {output} stays within {v(band['low'])} … {v(band['high'])} {u} of "
                 f"its nominal place (width {v(band['width'])} {u}): the measured drive- and coast-flank transmission "
                 "error of the printed outlines, widened by the bores' share, split between its two sides as the play "
                 "opens each limit"
                 + (f"; {v(band['p95_width'])} {u} wide for 95 % of prints, {v(band['worst_case_width'])} {u} at worst"
                    if "p95_width" in band else "") + ".</p>")
    rows = [[r["share"] + (f" (×{r['count']})" if r["count"] > 1 else ""),
             "backlash" if r["kind"] == "backlash" else "radial play", f"{r['mm']:.3f}", v(r["at_output"])]
            for r in lm.get("shares", [])]
    return html + R.table(["from", "what", "mm", f"at {output} {u}"], rows, left=2)


def bill_text(head: str, man: dict, dest, seconds: float) -> str:
    """What `build` prints: ``head`` (the sub-slice's line about the design), a line per part, where it wrote."""
    lines = [head]
    lines += [f"{p['name']:<14}{p['role']:<7}{p['count']:>3}{p['triangles']:>9} triangles {p['volume_mm3'] / 1000:8.2f} cm3 "
              f"{p['mass_g']:7.1f} g  {' x '.join(f'{x:.1f}' for x in p['bbox_mm'])} mm" for p in man["parts"]]
    lines.append(f"wrote {dest}/ in {seconds:.2f} s")
    return "\n".join(lines)


def assembly_steps(spec, kit) -> list[tuple[str, tuple[str, ...]]]:
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
