"""Checks of the balanced Bennett butterfly kit: the common centre of mass stays at S over a grid of
the two inputs (as printed, with the fill as it sits; and what an infill error, a missing slug, the
binder left out, what-if heavier links would do), the parts keep clear of each other over the
workspace, every pin is a stock length fully engaged in its stack, every part prints (one shell,
flat on the bed, the support it needs reported), the base stands (open bore, footprint under the
centre of mass with margin, links above the table), and every part fits the printer.

Interference sampling: link–link clearance depends only on the shape angle (q1 turns the linkage
rigidly about S's axis and the base is round about it). The step is chosen so that no point of any
part moves more than a bar's radius between samples (``assembly.bennett_layout.shape_samples``; the
speed bound is each link's reference-joint speed plus its angular speed times its reach, from the
parts themselves): two parts then close in on each other by at most a bar's diameter — the
thinnest feature — between samples, so one cannot pass through another unseen, and a sampled
clearance c guarantees at least c − (bar diameter) in between.
"""

from __future__ import annotations

import math

import numpy as np
from shapely.geometry import Point

from . import kit as A
from .params import BennettParams
from ...design import bennett_butterfly as bbf
from ...geometry.bennett_link import tube
from ...geometry.measure import intersection, oversize
from ...geometry.printing import bore_open, footprint, shells
from ...geometry.solid import mesh_arrays
from ...core.findings import Finding, Result

__all__ = ["check", "check_text", "check_bennett", "balance_figures", "stability"]


def _name(i: int) -> str:
    return "base" if i == A.BASE else f"link{i:02d}"


def balance_figures(kit: A.BennettKit) -> dict:
    """Worst distance (mm) of the common centre of mass from S over the grid: as built (FDM, the fill
    as it sits) and the what-ifs."""
    p = kit.params
    q1, q4 = A.grid(p)
    scale = dict(p.mass_scale)
    dev = {
        "fdm": A.com_deviation(kit, "fdm", q1, q4),
        "solid": A.com_deviation(kit, "solid", q1, q4),
        "fdm_infill_error": A.com_deviation(kit, "fdm", q1, q4, infill=min(1.0, p.infill + p.infill_error)),
        "no_binder": A.com_deviation(kit, "fdm", q1, q4, fill=A.fill_points(kit, binder=False)),
    }
    for i in kit.fills:
        dev[f"one_slug_short_{_name(i)}"] = A.com_deviation(kit, "fdm", q1, q4, fill=A.fill_points(kit, short=i))
    if scale:
        dev["what_if_mass_scale"] = A.com_deviation(kit, "fdm", q1, q4, scale=scale)
    out = {k: float(v.max()) for k, v in dev.items()}
    out["grid"] = list(p.grid)
    out["trace"] = {k: v.reshape(p.grid).max(axis=0).tolist() for k, v in dev.items()}
    return out


def stability(kit: A.BennettKit) -> dict:
    """The kit on its base, over the balance grid: the whole kit's centre of mass (links, pins,
    fills, the base) projected on the bed against the base's footprint: its least distance inside
    the footprint's edge (mm), its height over the bed (mm), the tilt the kit takes before it tips
    (deg), the footprint's area (mm²)."""
    p = kit.params
    q1, q4 = A.grid(p)
    P = bbf.pose(p.bb, q1, q4)
    frames = bbf.link_frames(P)
    fills = A.fill_points(kit)
    total, moment = 0.0, 0.0
    for i, lm in kit.masses.items():
        pts = [(lm.fdm_mass, lm.fdm_centre)] + kit.pins[i] + fills.get(i, [])
        for m, c in pts:
            T = frames[i]
            total, moment = total + m, moment + m * (T[:, :3, :3] @ np.asarray(c, float) + T[:, :3, 3])
    for m, c in [(kit.base_mass.fdm_mass, kit.base_mass.fdm_centre)] + kit.pins[A.BASE]:
        total, moment = total + m, moment + m * np.asarray(c, float)
    com = moment / total
    v, f = mesh_arrays(kit.solids[A.BASE])
    fp = footprint(v, f)
    z_bed = float(v[:, 2].min())
    margin = min(fp.exterior.distance(Point(x, y)) * (1 if fp.contains(Point(x, y)) else -1) for x, y in com[:, :2])
    height = float((com[:, 2] - z_bed).max())
    return {"footprint_mm2": float(fp.area), "margin_mm": float(margin), "com_height_mm": height,
            "tip_angle_deg": math.degrees(math.atan2(margin, height)), "bed_z_mm": z_bed, "total_g": float(total)}


def check_bennett(kit: A.BennettKit, progress=None) -> Result:
    say = progress or (lambda s: None)
    p, res = kit.params, Result()
    say("balance")
    bal = balance_figures(kit)
    res.figures["balance_mm"] = {k: v for k, v in bal.items() if k not in ("trace",)}
    res.figures["balance_trace_mm"] = bal["trace"]
    worst_key = "what_if_mass_scale" if "what_if_mass_scale" in bal else "fdm"
    worst = bal[worst_key]
    res.add(Finding("balance", "fail" if worst > p.tolerance else "info",
                    f"common centre of mass within {worst:.4f} mm of S over the {p.grid[0]}×{p.grid[1]} grid "
                    f"({'with ' + str(dict(p.mass_scale)) + ' heavier links' if worst_key != 'fdm' else 'as printed'}, "
                    f"the fills as they sit; tolerance {p.tolerance} mm)", value=worst, unit="mm"))
    short = max(v for k, v in bal.items() if k.startswith("one_slug_short"))
    res.add(Finding("balance", "info", f"a {100 * p.infill_error:g}-point infill error would move it up to "
                    f"{bal['fdm_infill_error']:.3f} mm; the binder left out {bal['no_binder']:.3f} mm; a pocket one "
                    f"slug short up to {short:.1f} mm; printed solid {bal['solid']:.3f} mm",
                    value=bal["fdm_infill_error"], unit="mm"))
    for i, f in kit.fills.items():
        cup = kit.cups[i]
        fits = abs(cup.pocket_depth - f.depth) < 1e-9 and abs(cup.pocket_radius - f.bore_radius) < 1e-9
        res.add(Finding("counterweight", "info" if fits else "fail",
                        f"{_name(i)}: {f.count} × Ø{f.diameter:g} × {f.length:g} mm {p.slug_kind} "
                        f"({f.steel_mass:.1f} g) and {f.binder_mass:.2f} g of {p.binder_name} fill its "
                        f"Ø{2 * cup.pocket_radius:.2f} × {cup.pocket_depth:.1f} mm pocket" + ("" if fits else
                        " — the pocket as built does not hold them exactly"), (_name(i),), value=f.mass, unit="g"))
    say("pins")
    _check_pins(kit, res)
    say("printing")
    _check_printing(kit, res)
    say("interference")
    speed = A.point_speed(p, *p.workspace, A.part_reach(p, kit.layout, kit.bodies, kit.pockets))
    angles, step = A.shape_samples(p, *p.workspace, speed)
    sweep = A.Sweep(p, angles, kit.bodies, kit.pockets)
    clear = sweep.all(kit.layout)
    least = min(clear.items(), key=lambda kv: kv[1][0])
    res.figures.update({"interference_samples": len(angles), "step_deg": math.degrees(step),
                        "fastest_point_mm_per_rad": speed, "least_clearance_mm": least[1][0],
                        "least_clearance_parts": [_name(i) for i in least[0]],
                        "least_clearance_angle_deg": math.degrees(angles[least[1][1]])})
    for (a, b), (c, k) in sorted(clear.items()):
        if c < 0:
            res.add(Finding("interference", "fail", f"{_name(a)} and {_name(b)} overlap by {-c:.2f} mm (capsule "
                            f"hulls) at {math.degrees(angles[k]):.1f}° between links 1 and 4",
                            (_name(a), _name(b)), theta=float(angles[k]), value=c, unit="mm"))
    # how far the kit moves freely either side of home (capsule hulls), beyond the required workspace
    wide, _ = A.shape_samples(p, math.radians(5), math.radians(175), speed)
    prof = A.Sweep(p, wide, kit.bodies, kit.pockets, below=0.5).profile(kit.layout)
    k0 = int(np.argmin(abs(wide - p.home)))
    lo = hi = k0
    if prof[k0] >= 0:
        while lo > 0 and prof[lo - 1] >= 0:
            lo -= 1
        while hi < len(wide) - 1 and prof[hi + 1] >= 0:
            hi += 1
        res.figures["free_range_deg"] = [math.degrees(wide[lo]), math.degrees(wide[hi])]
    else:
        res.figures["free_range_deg"] = [float("nan"), float("nan")]
    say("base")
    _check_base(kit, sweep, res)
    say("stacks")
    _check_stacks(kit, sweep.frames, angles, res)
    say("fit")
    for pt, ext in oversize(kit.parts, p.printer.envelope, tol=0.0):
        res.add(Finding("fit", "fail", f"{pt.name} measures {ext.round(1)} mm: larger than the printer", (pt.name,)))
    return res


def _check_pins(kit: A.BennettKit, res: Result) -> None:
    """Every pin a stock length, and fully engaged: measured on the solids, the bosses of its stack
    cover it from one end to the other but for the axial gaps, and it does not stand proud."""
    p = kit.params
    lengths = {}
    for j in bbf.JOINTS:
        st = A.stack(p, kit.layout, j)
        lo, hi = st.pin
        lengths[j] = st.length
        if not any(abs(st.length - s) < 1e-9 for s in p.pin_stock) or abs(hi - lo - st.length) > 1e-9:
            res.add(Finding("pins", "fail", f"pin {j} is {hi - lo:.2f} mm long, not a stock length "
                            f"{list(p.pin_stock)}", (f"pin_{j}",), value=hi - lo, unit="mm"))
        short = {}
        for i, (a, b) in st.spans.items():
            pt, ax = (np.zeros(3), np.array([0.0, 0, 1])) if i == A.BASE else kit.bodies[i][j]
            # a ring just outside the bore over the boss's span: the member's solid must fill it
            ring = tube(pt, ax, p.bore_radius + 0.05, p.bore_radius + 1.0, a, b, 32)
            full = ring.volume()
            short[i] = 1.0 - (kit.solids[i] ^ ring).volume() / full
        if st.pin != (min(a for a, _ in st.spans.values()), max(b for _, b in st.spans.values())) or max(short.values()) > 0.01:
            res.add(Finding("pins", "fail", f"pin {j} ({st.length:g} mm) is not held over its length: "
                            + ", ".join(f"{_name(i)} leaves {100 * x:.0f} % of its span around it open"
                                        for i, x in short.items() if x > 0.01), (f"pin_{j}",), value=max(short.values())))
    for i in range(1, 13):  # a pin runs through every boss of its stack: nothing else of a link may be in its way
        ends, radii, tags = A.part_capsules(p, kit.layout, kit.bodies, i, kit.pockets)
        room, what = A.own_clearance(p, kit.layout, kit.bodies, i, ends, radii, tags)
        if room < 0:
            res.add(Finding("pins", "fail", f"{_name(i)}: {what} are {-room:.2f} mm too close (pins need "
                            f"{p.printer.min_wall if p.printer else 1.0:g} mm of wall between their bores and a pin's "
                            "whole length clear of the link's other features)", (_name(i),), value=room, unit="mm"))
    counts: dict[float, int] = {}
    for v in lengths.values():
        counts[v] = counts.get(v, 0) + 1
    res.figures["pins"] = {"lengths_mm": lengths, "count_by_length": {f"{k:g}": n for k, n in sorted(counts.items())}}


def _check_printing(kit: A.BennettKit, res: Result) -> None:
    """Each printed part in its print orientation: one shell, flat on the bed over at least the
    configured area; the support it needs reported."""
    p = kit.params
    table = {}
    for part in (x for x in kit.parts if x.printed):
        pose = kit.printing[part.name]
        v, f = mesh_arrays(part.solid)
        sh = shells(v, f)
        table[part.name] = {"support_mm2": round(pose.overhang_mm2, 1), "contact_mm2": round(pose.contact_mm2, 1),
                            "height_mm": round(pose.height_mm, 1), "shells": len(sh)}
        if len(sh) != 1:
            res.add(Finding("printing", "fail", f"{part.name} is {len(sh)} shells ({sum(x < 0 for x in sh)} sealed "
                            "voids): it would not print as one solid", (part.name,), value=len(sh)))
        if pose.contact_mm2 < p.min_contact:
            # a stand must stand on the bed; a link without a flat face that large prints on its supports
            res.add(Finding("printing", "fail" if part.role == "bennett_base" else "warn",
                            f"{part.name} rests on {pose.contact_mm2:.1f} mm² of the bed, under {p.min_contact:g} mm²"
                            + ("" if part.role == "bennett_base" else ": it has no flat face that large and prints on "
                               "its supports (a raft)"), (part.name,), value=pose.contact_mm2, unit="mm2"))
    res.figures["printing"] = table
    res.add(Finding("printing", "info", "support beyond " f"{math.degrees(p.overhang_angle):g}° in each part's best "
                    "orientation: " + ", ".join(f"{k} {t['support_mm2']:.0f} mm²" for k, t in table.items()),
                    value=sum(t["support_mm2"] for t in table.values()), unit="mm2"))


def _check_base(kit: A.BennettKit, sweep: A.Sweep, res: Result) -> None:
    """The base: its S bore open from above for the pin's depth; the kit stands on it (the centre of
    mass over the footprint, the tilt it takes); every link above the table over the workspace."""
    p = kit.params
    lo, hi = A.stack(p, kit.layout, "S14").spans[A.BASE]
    top = float(mesh_arrays(kit.solids[A.BASE])[0][:, 2].max())
    # a rod a hair thinner than the pin, from above the base down to the pin's lower end
    blocked = bore_open(kit.solids[A.BASE], (0.0, 0.0, top + 5.0), (0.0, 0.0, -1.0), p.pin_radius - 0.05,
                        top + 5.0 - lo - 0.01)
    if blocked > 1e-6:
        res.add(Finding("base", "fail", f"the S pin cannot go into the base: {blocked:.1f} mm³ of it in the way",
                        ("base",), value=blocked, unit="mm3"))
    st = stability(kit)
    caps = sweep.capsules(kit.layout)
    lowest = min(float((c.ends[..., 2] - c.radii[None, :, None]).min()) for k, c in caps.items() if k != A.BASE)
    st["links_above_table_mm"] = lowest - st["bed_z_mm"]
    res.figures["base"] = st
    if st["tip_angle_deg"] < math.degrees(p.min_tip_angle):
        need = 2 * (st["com_height_mm"] * math.tan(p.min_tip_angle) + (p.foot_radius - st["margin_mm"]))
        res.add(Finding("base", "fail", f"the kit tips over at {st['tip_angle_deg']:.1f}° of tilt (centre of mass "
                        f"{st['com_height_mm']:.0f} mm up, {st['margin_mm']:.1f} mm inside the footprint's edge), under "
                        f"{math.degrees(p.min_tip_angle):g}°: make base.foot_diameter_mm at least {need:.0f}",
                        ("base",), value=st["tip_angle_deg"], unit="deg"))
    if st["links_above_table_mm"] < 0:
        res.add(Finding("base", "fail", f"a link dips {-st['links_above_table_mm']:.1f} mm below the table the base "
                        "stands on: make base.height_mm longer", ("base",), value=st["links_above_table_mm"], unit="mm"))


def _check_stacks(kit: A.BennettKit, frames: dict, angles: np.ndarray, res: Result) -> None:
    """Parts sharing a joint: their features there are exempt from the capsule sweep; measure them
    exactly (manifold intersection) at every sample, each part cropped to a cylinder around the joint
    that holds every exempt feature (bosses, the pin, the bars as they leave a boss)."""
    p = kit.params
    reach = p.boss_radius + 2 * p.bar_radius + 1.0
    worst_v = 0.0
    for j, (links, _, _) in bbf.JOINTS.items():
        st = A.stack(p, kit.layout, j)
        lo, hi = st.pin
        near = {}
        for i in st.members:
            pt, ax = (np.zeros(3), np.array([0.0, 0, 1])) if i == A.BASE else kit.bodies[i][j]
            zone = tube(pt, ax, 0.0, reach, lo - reach, hi + reach, 32)
            near[i] = kit.solids[i] ^ zone
        for a, b in ((x, y) for x in st.members for y in st.members if x < y):
            for k in range(len(angles)):
                Ta = np.eye(4) if a == A.BASE else frames[a][k]
                Tb = np.eye(4) if b == A.BASE else frames[b][k]
                v = intersection(near[a], Ta, near[b], Tb)[0]
                worst_v = max(worst_v, v)
                if v > 1e-3:
                    res.add(Finding("interference", "fail", f"{_name(a)} and {_name(b)} overlap by {v:.3f} mm³ at "
                                    f"joint {j}, {math.degrees(angles[k]):.1f}° between links 1 and 4",
                                    (_name(a), _name(b)), theta=float(angles[k]), value=v, unit="mm3"))
                    break
    res.figures["joint_stack_overlap_mm3"] = worst_v


def check(spec: BennettParams, kit: A.BennettKit, samples: int | None = None, progress=None):
    """Balance over the input grid, interference over the workspace, stacks, pins, printing, the base."""
    steps = 7  # the named steps check_bennett announces
    done = [0]

    def say(step: str) -> None:
        done[0] += 1
        if progress:
            progress(min(done[0], steps), steps)
    return check_bennett(kit, say)


def _check_text(p, result, seconds: float) -> str:
    """What `check` prints for a Bennett kit."""
    f = result.figures
    b = f["balance_mm"]
    short = max(v for k, v in b.items() if k.startswith("one_slug_short"))
    st = f["base"]
    lines = [f"{p.name}: balance over a {b['grid'][0]} × {b['grid'][1]} grid of (q1, angle between links 1 "
             f"and 4); interference over {f['interference_samples']} shape angles, step {f['step_deg']:.2f}°",
             f"  centre of mass from S: as printed {b['fdm']:.4f} mm, printed solid {b['solid']:.4f} mm, "
             f"infill off by {100 * p.infill_error:g} points {b['fdm_infill_error']:.3f} mm, "
             f"binder left out {b['no_binder']:.3f} mm, a pocket one slug short {short:.1f} mm"
             + (f", what-if heavier links {b['what_if_mass_scale']:.3f} mm" if "what_if_mass_scale" in b else ""),
             f"  least clearance {f['least_clearance_mm']:.2f} mm ({' – '.join(f['least_clearance_parts'])} at "
             f"{f['least_clearance_angle_deg']:.1f}°); stacked bosses overlap {f['joint_stack_overlap_mm3']:.3f} mm³; "
             + (f"moves freely from {f['free_range_deg'][0]:.1f}° to {f['free_range_deg'][1]:.1f}°"
                if math.isfinite(f["free_range_deg"][0]) else "capsule hulls overlap at the home pose"),
             f"  pins (stock lengths): {', '.join(f'{n} × {k} mm' for k, n in f['pins']['count_by_length'].items())}; "
             f"base: {st['footprint_mm2']:.0f} mm² on the bed, stands to {st['tip_angle_deg']:.1f}° of tilt, links "
             f"{st['links_above_table_mm']:.0f} mm above the table",
             "  support (mm²): " + ", ".join(f"{k} {v['support_mm2']:.0f}" for k, v in f["printing"].items())]
    lines += [f"  FAIL  {x.check}: {x.message}" for x in result.findings if x.severity == "fail"]
    lines.append(f"{'OK' if result.ok else 'FAILED'} in {seconds:.1f} s")
    return "\n".join(lines)


def check_text(spec, result, folder, seconds: float) -> str:
    return _check_text(spec, result, seconds) + (f"; {result.figures.get('plates', '?')} build plate(s) in {folder}/"
                                                 if folder else "")
