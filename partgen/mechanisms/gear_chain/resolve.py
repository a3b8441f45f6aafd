"""Validated config → the design layer's inputs. The one place units are converted (deg → rad,
g/cm³ → g/mm³, radial → diametral clearance)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ...config.drawing import curve_file, inline_points, read_points_csv, read_svg_path
from ...design import curve as curves
from ...design import drawing
from ...design.belt import BeltProfile
from ...design.gearing import ToothSystem
from ...design.mechanism import BeltSettings, ChainDesign, MechanismInputs, auto_module, synthesize
from ...design.rules import ToothSystemError
from ...design.synthesis import Chain, Link, chain_order, links_from_curve, prune
from ...errors import ConfigError, DesignError
from ...config.loader import LoadedDesign, load_design, printer_fit, printer_limits
from ...config.schema import AUTO_PLAY_START_MM
from ...checks.settings import CheckSettings
from .params import Joints, KitParams

__all__ = ["resolve", "resolve_spec", "ChainSpec", "load"]


def _fourier(c) -> curves.FourierCurve:
    if c.polar is not None:
        return curves.from_polar(c.polar.constant, c.polar.sin, c.polar.cos)
    return curves.from_cartesian(c.cartesian.a, c.cartesian.b, c.cartesian.c, c.cartesian.d)


def _closed(z: np.ndarray, close: bool, where: Path, key: str) -> np.ndarray:
    """The samples of a closed curve: repeated points and a repeated first point dropped; an open
    curve refused unless ``close`` (then its ends are joined by a straight run of samples)."""
    if len(z) and np.ptp(z.real) + np.ptp(z.imag) <= 1e-6:
        raise ConfigError(where, key, "every point is in one place: the curve has no size")
    z = z[np.append(True, np.abs(np.diff(z)) > 0)]
    gap, step = drawing.closing(z)
    if gap <= 1e-9 * (np.ptp(z.real) + np.ptp(z.imag)):
        z = z[:-1]
        gap, step = drawing.closing(z)
    if len(z) < drawing.MIN_SAMPLES:
        raise ConfigError(where, key, f"{len(z)} distinct points: a closed curve needs at least {drawing.MIN_SAMPLES}")
    if gap > step * (1 + 1e-6):
        if not close:
            raise ConfigError(where, key, f"the curve is open: its last point is {gap:.3g} mm from its first, more than "
                              f"the largest step between samples ({step:.3g} mm); close it, or set curve.close: true to "
                              "join the ends with a straight line")
        k = int(np.ceil(gap / np.median(np.abs(np.diff(z)))))
        z = np.concatenate([z, z[-1] + (z[0] - z[-1]) * np.arange(1, k) / k])
    return z


def _samples(loaded: LoadedDesign) -> tuple[np.ndarray, str, str, str]:
    """The drawing's points (n, 2) mm at scale 1, its parametrisation, source file and key."""
    c = loaded.design.curve
    if c.svg is not None:
        key = "curve.svg"
        f = curve_file(c.svg, loaded.path, key, ".svg")
        xy, param, source = read_svg_path(f, c.svg_path_id, c.svg_mm_per_unit, loaded.path), "arc_length", f.name
    elif isinstance(c.points, str):
        key = "curve.points"
        f = curve_file(c.points, loaded.path, key, ".csv")
        xy, param, source = read_points_csv(f), "samples", f.name
    else:
        key = "curve.points"
        xy, param, source = inline_points(c.points, loaded.path), "samples", "inline"
    return xy, c.parametrisation or param, source, key


def _fitted(loaded: LoadedDesign, scale: float):
    """The drawing at ``scale``, drawn the way round that turns its lead link forwards: (offset,
    links, Drawing, lead link, key, "file: ")."""
    c = loaded.design.curve
    xy, param, source, key = _samples(loaded)
    where = f"{source}: " if source != "inline" else ""
    z = _closed((xy[:, 0] + 1j * xy[:, 1]) * scale, c.close, loaded.path, key)
    _, offset, links, theta = drawing.fit(z, param)
    head = drawing.lead(links)
    if head is not None and head.speed < 0:  # the crank turns the lead link forwards: draw the curve the other way
        z = np.concatenate([z[:1], z[:0:-1]])
        _, offset, links, theta = drawing.fit(z, param)
        head = drawing.lead(links)
    if head is None:
        raise ConfigError(loaded.path, key, f"{where}the curve has no rotating part")
    return offset, links, drawing.Drawing(z, theta, param, source), head, key, where


def _drawn(loaded: LoadedDesign, scale: float) -> tuple[Chain, drawing.Drawing]:
    """The chain of the fewest printable links that draws the design's drawing within its budget,
    led by the drawing's lowest harmonic (``drawing.lead``) and retimed to draw it once per cycle."""
    d, p = loaded.design, loaded.printer
    c = d.curve
    offset, links, dr, head, key, where = _fitted(loaded, scale)
    budget, most, shortest = c.max_deviation_mm, c.max_links, p.min_link_length_mm
    choice = drawing.choose(offset, links, dr, budget, most, shortest, lead=head.name)
    if choice.chosen is None:
        r = drawing.rescue(offset, links, dr, budget, most, shortest, lead=head.name)
        best = min(choice.rows, key=lambda x: x.hausdorff_mm, default=None)
        got = (f"the best, {best.links} links, is {best.hausdorff_mm:.3g} mm away" if best else
               f"its longest link would be {links[0].length:.3g} mm")
        fixes = []
        if r.up is not None:
            f = math.ceil(scale * r.up * 1000) / 1000
            fixes.append(f"curve.scale: {f:g} ({r.up_links} links; the drawing {r.up:.3g}× this size)")
        if r.down is not None:
            f = math.floor(scale * r.down * 1000) / 1000
            fixes.append(f"curve.scale: {f:g} ({r.down_links} links; the drawing {r.down:.3g}× this size)")
        if r.links is not None:
            fixes.append(f"curve.max_links: {r.links}")
        fix = ("; rerun with " + " or ".join(fixes)) if fixes else \
            "; no scale or link count up to 64 does: raise curve.max_deviation_mm"
        raise ConfigError(loaded.path, "curve.max_deviation_mm",
                          f"{where}no chain of at most {most} links of at least {shortest:g} mm (the printer's "
                          f"smallest link) comes within {budget:g} mm of the drawing: {got}{fix}")
    return drawing.retime(choice.chain, replace(dr, rows=choice.rows, chosen=choice.chosen.links))


def _chain(loaded: LoadedDesign) -> tuple[Chain, object, float, tuple[str, ...]]:
    d = loaded.design
    if d.curve is not None:
        c = d.curve
        fc = _fourier(c)
        offset, links = links_from_curve(fc, c.scale_mm_per_unit)
        names = {l.name for l in links}
        for i, n in enumerate(c.drop_links):
            if n not in names:
                raise ConfigError(loaded.path, f"curve.drop_links[{i}]",
                                  f"the curve has no link {n!r} (it has {', '.join(l.name for l in links)})")
        kept = chain_order(prune(links, c.drop_links))
        if not kept:
            raise ConfigError(loaded.path, "curve", "the curve has no rotating links left")
        return Chain(kept, offset), fc, c.scale_mm_per_unit, tuple(c.drop_links)
    links = tuple(Link(r.name, r.speed, r.length_mm, math.radians(r.initial_angle_deg)) for r in d.links)
    if not links:
        raise ConfigError(loaded.path, "links", "the design table has no links")
    if d.target is not None:
        return Chain(links, complex(*d.offset_mm)), _fourier(d.target), d.target.scale_mm_per_unit, ()
    return Chain(links, complex(*d.offset_mm)), None, 1.0, ()


def _sizes(loaded: LoadedDesign, chain: Chain, scale: float = 1.0) -> None:
    """Refuse, before any geometry, links no plate of this printer can span and chains whose links
    all fall under the printer's smallest link (a curve at a scale that makes it vanish)."""
    d, p = loaded.design, loaded.printer
    reach = math.hypot(*p.build_envelope_mm)
    longest = max(l.length for l in chain.links)
    for j, l in enumerate(chain.links):
        if l.length > reach:
            key = ("curve.scale" if d.curve.drawn else "curve.scale_mm_per_unit") if d.curve is not None \
                else f"links[{j}].length_mm"
            raise ConfigError(loaded.path, key, f"link {j + 1} ({l.name}) comes out {l.length:.1f} mm long: no plate "
                              f"that long fits the printer's {' × '.join(f'{x:g}' for x in p.build_envelope_mm)} mm "
                              "envelope")
    if d.curve is None or d.curve.drawn or longest >= p.min_link_length_mm:
        # a link carries its D and G gears, each at least the printer's smallest gear: a shorter
        # link cannot hold both, whatever the teeth (the chain's own rules refuse later, on teeth)
        for j, l in enumerate(chain.links):
            if l.length < p.min_gear_diameter_mm:
                if d.curve is not None and d.curve.drawn:
                    where = f"at curve.scale {scale:g} the drawing makes link {j + 1} ({l.name})"
                    fix, key = "enlarge the drawing (curve.scale)", "curve.scale"
                elif d.curve is not None:
                    where = f"at {d.curve.scale_mm_per_unit:g} mm per unit the curve makes link {j + 1} ({l.name})"
                    fix, key = "drop it (curve.drop_links) or change the curve's terms", "curve"
                else:
                    where = f"link {j + 1} ({l.name}) is"
                    fix, key = f"make it at least {p.min_gear_diameter_mm:g} mm", f"links[{j}].length_mm"
                raise ConfigError(loaded.path, key, f"{where} {l.length:.3f} mm long, too short to carry two gears "
                                  f"of the printer's smallest Ø{p.min_gear_diameter_mm:g} mm: {fix}")
    if d.curve is not None and not d.curve.drawn and longest < p.min_link_length_mm:
        need = d.curve.scale_mm_per_unit * p.min_link_length_mm / longest
        raise ConfigError(loaded.path, "curve.scale_mm_per_unit",
                          f"at {d.curve.scale_mm_per_unit:g} mm per unit the longest link is {longest:.3f} mm, under "
                          f"the printer's smallest link ({p.min_link_length_mm:g} mm): use at least {need:.3g} mm per unit")


def _fit(loaded: LoadedDesign, kind: str) -> float:
    """A joint clearance (diametral, mm): as given, or ``printer``: the fit the printer's profile measured."""
    j = loaded.design.joints
    value = j.running_diametral if kind == "running" else j.press_fit_diametral
    return printer_fit(loaded, value, kind, f"joints.{kind}_clearance_diametral_mm")


def resolve(loaded: LoadedDesign, drawing_scale: float | None = None) -> tuple[MechanismInputs, KitParams]:
    """The mechanism inputs and kit parameters of a loaded design (mm, rad). ``drawing_scale``: the
    enlargement of a drawing (``curve.scale``, or the one ``auto`` is trying)."""
    d, p = loaded.design, loaded.printer
    drawn = None
    if d.curve is not None and d.curve.drawn:
        s = drawing_scale if drawing_scale is not None else d.curve.scale
        if s == "auto":
            raise ValueError("curve.scale: auto is chosen by resolve_spec")
        chain, drawn = _drawn(loaded, s)
        drawn = replace(drawn, scale=s)
        fc, scale, dropped = None, 1.0, ()
        _sizes(loaded, chain, s)
    else:
        chain, fc, scale, dropped = _chain(loaded)
        _sizes(loaded, chain)
    g = d.gears
    backlash = g.backlash_per_gear_mm
    own_backlash = () if not isinstance(backlash, dict) else tuple(
        (k, float(v)) for k, v in backlash.items() if k != "default")
    backlash = backlash["default"] if isinstance(backlash, dict) else backlash
    system = ToothSystem(
        module=1.0 if g.module_mm == "auto" else g.module_mm,  # auto: chosen in resolve_spec
        pressure_angle=math.radians(g.pressure_angle_deg),
        addendum_coeff=g.addendum_coeff,
        dedendum_coeff=g.dedendum_coeff,
        cutter_tip_coeff=g.cutter_tip_radius_coeff,
        backlash_per_gear=AUTO_PLAY_START_MM if backlash == "auto" else backlash,
        profile_shift=None if g.profile_shift == "auto" else float(g.profile_shift),
        chord_tolerance=g.chord_tolerance_mm,
    )
    teeth = None if d.teeth == "auto" else tuple((t.D, t.M, t.G) for t in d.teeth)
    idlers = None if d.teeth == "auto" else tuple(tuple(t.idler_mm) if t.idler_mm else None for t in d.teeth)
    belts = None
    if d.belts is not None:
        b = d.belts
        belts = BeltSettings(BeltProfile(b.profile, b.pitch_mm, b.pitch_line_offset_mm, b.groove_depth_mm,
                                         b.groove_radius_mm, b.back_height_mm, b.width_mm),
                             tuple(b.stock_teeth), b.flange_height_mm, b.flange_thickness_mm, b.tensioner_radius_mm,
                             b.tensioner_gap_mm)
    source = "drawing" if drawn is not None else ("curve" if d.curve is not None else "table")
    inputs = MechanismInputs(chain, teeth, g.tip_gap_mm, g.idler_reach_mm, fc, scale, dropped, idlers, source, belts,
                             drawn)
    j = d.joints
    params = KitParams(
        name=d.name,
        system=system,
        face_width=g.face_width_mm,
        plate_thickness=d.plates.thickness_mm,
        boss_wall=d.plates.boss_wall_mm,
        hub_wall=g.hub_wall_mm,
        joints=Joints(j.axle_diameter_mm, _fit(loaded, "running"), _fit(loaded, "press_fit"), j.axial_gap_mm,
                      _own_running(j)),
        base_thickness=d.base.thickness_mm,
        leg_height=d.base.leg_height_mm,
        crank_radius=d.base.crank_radius_mm,
        pen_diameter=d.pen.diameter_mm,
        pen_holder_height=d.pen.holder_height_mm,
        density=d.material.density_g_cm3 / 1000.0,
        material=d.material.name,
        printer=printer_limits(p),
        drive_teeth=d.drive.teeth,
        drive_angle=math.radians(d.drive.angle_deg),
        checks=CheckSettings(d.checks.samples, d.checks.interference_tolerance_mm3, d.checks.min_clearance_mm,
                             d.checks.min_contact_ratio, d.checks.min_tip_width_roads, d.checks.plate_margin_mm),
        backlash_by=own_backlash,
    )
    return inputs, params


BACKLASH_KEY, RUNNING_KEY = "gears.backlash_per_gear_mm", "joints.running_clearance_diametral_mm"


def _own_running(j) -> tuple[tuple[str, float], ...]:
    """The joints named in a running-clearance mapping, with their own clearance (diametral)."""
    d = j.running_clearance_diametral_mm
    return () if not isinstance(d, dict) else tuple((k, float(v)) for k, v in d.items() if k != "default")


def running_joints(mech: ChainDesign) -> list[str]:
    """The parts that turn in a running fit (a joint's name in a running-clearance mapping)."""
    out = ["G1", "drive_axle"]
    for s in mech.stages:
        out += [f"M{s.j}", f"G{s.j + 1}"]
    for s in mech.belt_stages:
        out += [f"G{s.j + 1}"] + ([f"T{s.j}"] if s.tensioner is not None else [])
    return out


def _own_play(loaded: LoadedDesign, mech: ChainDesign, params: KitParams) -> ChainDesign:
    """The mechanism with each gear named in ``gears.backlash_per_gear_mm``'s mapping thinned by its
    own backlash (the teeth, centre distances and clockings do not depend on it); names checked,
    both mappings'; the rules a gear's own backlash breaks (tip width) become design warnings."""
    from ...design.drivetrain import design_finding
    from ...design.rules import gear_breaches, gear_rules

    gears = dict(mech.gears)
    for key, own, names in ((BACKLASH_KEY, params.backlash_by, list(gears)),
                            (RUNNING_KEY, params.joints.running_by, running_joints(mech))):
        for name, _ in own:
            if name not in names:
                what = "gear" if key == BACKLASH_KEY else "running joint (named by the part that turns in it)"
                raise ConfigError(loaded.path, f"{key}.{name}", f"the kit has no {what} {name!r}: it has "
                                  f"{', '.join(names)}")
    if not params.backlash_by:
        return mech
    own = dict(params.backlash_by)

    def thin(name: str, gear):
        if name not in own:
            return gear
        return replace(gear, system=replace(gear.system, backlash_per_gear=own[name]))

    stages = tuple(replace(s, D=thin(f"D{s.j}", s.D), M=thin(f"M{s.j}", s.M), G=thin(f"G{s.j + 1}", s.G))
                   for s in mech.stages)
    out = replace(mech, stages=stages, G1=thin("G1", mech.G1), drive=thin("drive", mech.drive))
    rules = gear_rules(params)
    found = [design_finding("warn", b.rule, f"{name} (its own backlash {own[name]:g} mm): {b.message}",
                            f"{BACKLASH_KEY}.{name}")
             for name, gear in out.gears if name in own for b in gear_breaches(gear, rules, name)]
    return replace(out, findings=(*out.findings, *found)) if found else out


TOOTH_KEYS = {"cutter_tip_coeff": "gears.cutter_tip_radius_coeff", "addendum_coeff": "gears.addendum_coeff",
              "profile_shift": "gears.profile_shift", "dedendum_coeff": "gears.dedendum_coeff"}


@dataclass(frozen=True)
class ChainSpec:
    """A gear chain ready to build: the synthesized mechanism and the kit's parameters."""

    path: Path
    mechanism: ChainDesign
    params: KitParams
    printer_path: Path


def _room(links) -> float:
    """How easily gears fit an order of links: the smallest link length over the span its stage's two
    smallest-possible gears need, ``1 + max(r, 1/r)`` gear sizes for Eq 11 ratio r (the last link
    carries no stage). Larger is easier; the order itself does not change the pen's path."""
    w = [0, *(l.speed for l in links)]
    room = math.inf
    for j in range(1, len(links)):
        r = abs((w[j + 1] - w[j]) / (w[j - 1] - w[j]))
        room = min(room, links[j - 1].length / (1 + max(r, 1 / r)))
    return room


def _auto_scale(loaded: LoadedDesign) -> ChainSpec:
    """``curve.scale: auto``: the first scale of ``drawing.scale_ladder`` (smallest first, three
    significant figures, at least 5 % apart) whose kit synthesizes — links printable, within the
    deviation budget, gears fitted to every link, the longest link within the printer's envelope.
    The scales are tried in that order only, so the same drawing gets the same scale anywhere. The
    build's findings say which scale was chosen and how many were tried."""
    from ...design.drivetrain import design_finding

    c, p = loaded.design.curve, loaded.printer
    offset, links, dr, head, key, where = _fitted(loaded, 1.0)
    reach = math.hypot(*p.build_envelope_mm)
    ladder = drawing.scale_ladder(offset, links, dr, c.max_deviation_mm, c.max_links, p.min_link_length_mm, reach,
                                  head.name)
    if not ladder:
        raise ConfigError(loaded.path, "curve.scale", f"{where}auto: no scale makes a chain of at most {c.max_links} "
                          f"links both printable (links ≥ {p.min_link_length_mm:g} mm, the longest ≤ {reach:.0f} mm) "
                          f"and within {c.max_deviation_mm:g} mm of the drawing: raise curve.max_deviation_mm or "
                          "curve.max_links")
    last = None
    for i, s in enumerate(ladder):
        try:
            spec = resolve_spec(loaded, s, advise=False)
        except ConfigError as e:
            last = e.problem
            continue
        warn = [f for f in spec.mechanism.findings if f.severity == "warn"]
        if warn:  # builds, but `check` would fail it
            last = f"{len(warn)} design warning(s), the first: {warn[0].message}"
            continue
        note = design_finding("info", "auto-scale", f"auto chose {s:g} (the drawing {s:g}× the file's size): the "
                              f"smallest of {len(ladder)} scales from {ladder[0]:g} (three significant figures, "
                              f"≥ {round((drawing.SCALE_STEP - 1) * 100):g} % apart) whose chain synthesizes without a "
                              f"design warning; {i + 1} tried", "curve.scale")
        mech = replace(spec.mechanism, findings=(note, *spec.mechanism.findings))
        return replace(spec, mechanism=mech)
    raise ConfigError(loaded.path, "curve.scale", f"auto: none of the {len(ladder)} scales {ladder[0]:g}–{ladder[-1]:g} "
                      f"builds without a design warning; at {ladder[-1]:g}: {last}") from None


def resolve_spec(loaded: LoadedDesign, drawing_scale: float | None = None, advise: bool = True) -> ChainSpec:
    """Resolve and synthesize a validated design; a ``DesignError`` becomes a ``ConfigError`` on its key.
    ``advise``: a refusal computes the settings that would work (``curve.scale: auto``'s search turns it off)."""
    c = loaded.design.curve
    if drawing_scale is None and c is not None and c.drawn and c.scale == "auto":
        return _auto_scale(loaded)
    inputs, params = resolve(loaded, drawing_scale)
    orders = [inputs.chain.links]
    if inputs.source == "drawing" and inputs.teeth is None:  # the first order whose gears fit each link
        found = drawing.drawable_orders(inputs.chain.links, limit=200, first=inputs.chain.links[0].name)
        orders = sorted(found, key=_room, reverse=True)[:24] or orders
    first = None
    for links in orders:
        trial = replace(inputs, chain=Chain(links, inputs.chain.offset))
        try:
            if loaded.design.gears.module_mm == "auto":
                mech, params = auto_module(trial, params, advise)
            else:
                mech = synthesize(trial, params, advise)
            break
        except ToothSystemError as e:  # the design names the tooth system's field; this is its key
            raise ConfigError(loaded.path, TOOTH_KEYS.get(e.field, "gears"), e.problem) from None
        except DesignError as e:
            first = first or e
    else:
        key = first.key_path
        if inputs.source in ("curve", "drawing") and key.startswith("links"):  # a curve design has no link table
            key = "curve"
        problem = first.problem + (f" (tried {len(orders)} orders of the links)" if len(orders) > 1 else "")
        raise ConfigError(loaded.path, key, problem) from None
    return ChainSpec(loaded.path, _own_play(loaded, mech, params), params, loaded.printer_path)


def load(path) -> ChainSpec:
    """Read, validate and synthesize a gear chain design file (for scripts and tests)."""
    from .schema import Design

    return resolve_spec(load_design(path, {"gear_chain": Design}))
