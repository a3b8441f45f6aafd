"""Validated config → the design layer's inputs. The one place units are converted (deg → rad,
g/cm³ → g/mm³, radial → diametral clearance)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ...design import curve as curves
from ...design.belt import BeltProfile
from ...design.gearing import ToothSystem
from ...design.mechanism import (BeltSettings, CheckSettings, Joints, KitParams, Mechanism, MechanismInputs, auto_module,
                                 synthesize)
from ...design.rules import ToothSystemError
from ...design.synthesis import Chain, Link, chain_order, links_from_curve, prune
from ...errors import ConfigError, DesignError
from ...config.loader import LoadedDesign, load_design, printer_limits

__all__ = ["resolve", "resolve_spec", "ChainSpec", "load"]


def _fourier(c) -> curves.FourierCurve:
    if c.polar is not None:
        return curves.from_polar(c.polar.constant, c.polar.sin, c.polar.cos)
    return curves.from_cartesian(c.cartesian.a, c.cartesian.b, c.cartesian.c, c.cartesian.d)


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


def _sizes(loaded: LoadedDesign, chain: Chain) -> None:
    """Refuse, before any geometry, links no plate of this printer can span and chains whose links
    all fall under the printer's smallest link (a curve at a scale that makes it vanish)."""
    d, p = loaded.design, loaded.printer
    reach = math.hypot(*p.build_envelope_mm)
    longest = max(l.length for l in chain.links)
    for j, l in enumerate(chain.links):
        if l.length > reach:
            key = "curve.scale_mm_per_unit" if d.curve is not None else f"links[{j}].length_mm"
            raise ConfigError(loaded.path, key, f"link {j + 1} ({l.name}) comes out {l.length:.1f} mm long: no plate "
                              f"that long fits the printer's {' × '.join(f'{x:g}' for x in p.build_envelope_mm)} mm "
                              "envelope")
    if d.curve is None or longest >= p.min_link_length_mm:
        # a link carries its D and G gears, each at least the printer's smallest gear: a shorter
        # link cannot hold both, whatever the teeth (the chain's own rules refuse later, on teeth)
        for j, l in enumerate(chain.links):
            if l.length < p.min_gear_diameter_mm:
                where = (f"at {d.curve.scale_mm_per_unit:g} mm per unit the curve makes link {j + 1} ({l.name})"
                         if d.curve is not None else f"link {j + 1} ({l.name}) is")
                fix = ("drop it (curve.drop_links) or change the curve's terms" if d.curve is not None
                       else f"make it at least {p.min_gear_diameter_mm:g} mm")
                raise ConfigError(loaded.path, "curve" if d.curve is not None else f"links[{j}].length_mm",
                                  f"{where} {l.length:.3f} mm long, too short to carry two gears of the printer's "
                                  f"smallest Ø{p.min_gear_diameter_mm:g} mm: {fix}")
    if d.curve is not None and longest < p.min_link_length_mm:
        need = d.curve.scale_mm_per_unit * p.min_link_length_mm / longest
        raise ConfigError(loaded.path, "curve.scale_mm_per_unit",
                          f"at {d.curve.scale_mm_per_unit:g} mm per unit the longest link is {longest:.3f} mm, under "
                          f"the printer's smallest link ({p.min_link_length_mm:g} mm): use at least {need:.3g} mm per unit")


def _fit(loaded: LoadedDesign, kind: str) -> float:
    """A joint clearance (diametral, mm): as given, or ``printer``: the fit the printer's profile measured."""
    j, p = loaded.design.joints, loaded.printer
    value = j.running_diametral if kind == "running" else j.press_fit_diametral
    if value != "printer":
        return float(value)
    measured = None if p.fits is None else getattr(p.fits, f"{kind}_clearance_diametral_mm")
    if measured is None:
        raise ConfigError(loaded.path, f"joints.{kind}_clearance_diametral_mm",
                          f"'printer' takes the fit from the printer profile, but {p.name!r} ({loaded.printer_path.name}) "
                          f"gives no fits.{kind}_clearance_diametral_mm: give a number (mm, diametral)")
    return float(measured)


def resolve(loaded: LoadedDesign) -> tuple[MechanismInputs, KitParams]:
    """The mechanism inputs and kit parameters of a loaded design (mm, rad)."""
    d, p = loaded.design, loaded.printer
    chain, fc, scale, dropped = _chain(loaded)
    _sizes(loaded, chain)
    g = d.gears
    system = ToothSystem(
        module=1.0 if g.module_mm == "auto" else g.module_mm,  # auto: chosen in resolve_spec
        pressure_angle=math.radians(g.pressure_angle_deg),
        addendum_coeff=g.addendum_coeff,
        dedendum_coeff=g.dedendum_coeff,
        cutter_tip_coeff=g.cutter_tip_radius_coeff,
        backlash_per_gear=g.backlash_per_gear_mm,
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
    inputs = MechanismInputs(chain, teeth, g.tip_gap_mm, g.idler_reach_mm, fc, scale, dropped, idlers,
                             "curve" if d.curve is not None else "table", belts)
    j = d.joints
    params = KitParams(
        name=d.name,
        system=system,
        face_width=g.face_width_mm,
        plate_thickness=d.plates.thickness_mm,
        boss_wall=d.plates.boss_wall_mm,
        hub_wall=g.hub_wall_mm,
        joints=Joints(j.axle_diameter_mm, _fit(loaded, "running"), _fit(loaded, "press_fit"), j.axial_gap_mm),
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
    )
    return inputs, params


TOOTH_KEYS = {"cutter_tip_coeff": "gears.cutter_tip_radius_coeff", "addendum_coeff": "gears.addendum_coeff",
              "profile_shift": "gears.profile_shift", "dedendum_coeff": "gears.dedendum_coeff"}


@dataclass(frozen=True)
class ChainSpec:
    """A gear chain ready to build: the synthesized mechanism and the kit's parameters."""

    path: Path
    mechanism: Mechanism
    params: KitParams
    printer_path: Path


def resolve_spec(loaded: LoadedDesign) -> ChainSpec:
    """Resolve and synthesize a validated design; a ``DesignError`` becomes a ``ConfigError`` on its key."""
    inputs, params = resolve(loaded)
    try:
        if loaded.design.gears.module_mm == "auto":
            mech, params = auto_module(inputs, params)
        else:
            mech = synthesize(inputs, params)
    except ToothSystemError as e:  # the design names the tooth system's field; this is its key
        raise ConfigError(loaded.path, TOOTH_KEYS.get(e.field, "gears"), e.problem) from None
    except DesignError as e:
        key = e.key_path
        if inputs.source == "curve" and key.startswith("links"):  # a curve design has no link table
            key = "curve"
        raise ConfigError(loaded.path, key, e.problem) from None
    return ChainSpec(loaded.path, mech, params, loaded.printer_path)


def load(path) -> ChainSpec:
    """Read, validate and synthesize a gear chain design file (for scripts and tests)."""
    from .schema import Design

    return resolve_spec(load_design(path, {"gear_chain": Design}))
