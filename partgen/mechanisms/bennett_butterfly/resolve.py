"""A validated Bennett butterfly design → the kit's parameters (deg → rad, g/cm³ → g/mm³)."""

from __future__ import annotations

import math

from ...design.bennett_butterfly import BennettButterfly
from .params import BennettParams
from ...errors import ConfigError, DesignError
from ...config.loader import LoadedDesign, printer_fit, printer_limits

__all__ = ["resolve_bennett", "MIN_TWIST_DEG"]

MIN_TWIST_DEG = 1.0  # degrees: the smallest twist α or β partgen builds (see resolve_bennett)


def resolve_bennett(loaded: LoadedDesign) -> BennettParams:
    d, p = loaded.design, loaded.printer
    k, parts, cw = d.linkage, d.parts, d.counterweights
    s1 = k.scales[0]
    try:
        if k.beta_deg is None:
            bb = BennettButterfly.from_twist(k.a_mm, k.b_mm, math.radians(k.alpha_deg), k.scales[1] / s1,
                                             k.scales[2] / s1, k.scales[3] / s1)
        else:
            bb = BennettButterfly(k.a_mm, k.b_mm, math.radians(k.alpha_deg), math.radians(k.beta_deg),
                                  k.scales[1] / s1, k.scales[2] / s1, k.scales[3] / s1)
    except DesignError as e:
        raise ConfigError(loaded.path, "linkage.beta_deg" if k.beta_deg is not None else "linkage.b_mm", e.problem) from None
    # a Bennett linkage is spatial by its twists: within a degree of 0° or 180° its joint axes are
    # all but parallel, features meant to stand apart come within hundredths of a millimetre of each
    # other, and the parts are not sound solids (0.011° made link04 two touching bodies); 1° builds
    for key, twist in (("linkage.alpha_deg", bb.alpha),
                       ("linkage.beta_deg" if k.beta_deg is not None else "linkage.b_mm", bb.beta)):
        deg = math.degrees(twist)
        if min(deg, 180.0 - deg) < MIN_TWIST_DEG:
            what = "α" if key == "linkage.alpha_deg" else "β (from sin β = b/a sin α)"
            raise ConfigError(loaded.path, key, f"a twist {what} of {deg:.4g}° makes the linkage all but planar: partgen "
                              f"builds Bennett linkages with twists from {MIN_TWIST_DEG:g}° to {180 - MIN_TWIST_DEG:g}°")
    if parts.bar_diameter_mm > parts.boss_length_mm:
        raise ConfigError(loaded.path, "parts.bar_diameter_mm", f"{parts.bar_diameter_mm} mm is thicker than a boss is long "
                          f"({parts.boss_length_mm} mm): a bar would stand proud of its boss into the next one on the pin")
    if d.pin.clearance_diametral_mm == "auto":  # pipeline.load puts auto play's number in its place first
        raise ConfigError(loaded.path, "pin.clearance_diametral_mm", "auto is chosen when partgen loads the design "
                          "(mechanisms.autoplay); this design was resolved without it")
    pin_clearance = printer_fit(loaded, d.pin.clearance_diametral_mm, "running", "pin.clearance_diametral_mm")
    if len(set(cw.links)) != 3:
        raise ConfigError(loaded.path, "counterweights.links", "three different links")
    if d.pin.diameter_mm + pin_clearance >= parts.boss_diameter_mm - 2 * p.min_wall:
        raise ConfigError(loaded.path, "pin.diameter_mm", f"the bore leaves less than the printer's {p.min_wall} mm "
                          f"wall in a {parts.boss_diameter_mm} mm boss")
    if d.pin.diameter_mm + pin_clearance < p.min_hole_diameter_mm:
        raise ConfigError(loaded.path, "pin.diameter_mm", f"the bore is below the printer's smallest reliable hole "
                          f"({p.min_hole_diameter_mm} mm)")
    need = 2 * parts.boss_length_mm + parts.axial_gap_mm
    if max(d.pin.stock_lengths_mm) < need:
        raise ConfigError(loaded.path, "pin.stock_lengths_mm", f"the longest stock pin ({max(d.pin.stock_lengths_mm):g} mm) "
                          f"is shorter than two stacked bosses ({need:g} mm)")
    if d.base.foot_diameter_mm < parts.boss_diameter_mm:
        raise ConfigError(loaded.path, "base.foot_diameter_mm", f"{d.base.foot_diameter_mm:g} mm is narrower than the "
                          f"post ({parts.boss_diameter_mm:g} mm) it carries")
    fixed = None
    if parts.layout != "auto":
        missing = sorted(set(range(1, 13)) - set(parts.layout.layers))
        if missing:
            raise ConfigError(loaded.path, "parts.layout.layers", f"no layer for links {missing}")
        fixed = (dict(parts.layout.layers), dict(parts.layout.shifts_mm))
    return BennettParams(
        name=d.name, bb=bb, home=math.radians(k.home_angle_deg),
        workspace=(math.radians(k.workspace_deg[0]), math.radians(k.workspace_deg[1])),
        boss_radius=parts.boss_diameter_mm / 2, boss_length=parts.boss_length_mm, axial_gap=parts.axial_gap_mm,
        bar_radius=parts.bar_diameter_mm / 2, pin_radius=d.pin.diameter_mm / 2,
        pin_clearance=pin_clearance, pin_density=d.pin.density_g_cm3 / 1000.0, pin_kind=d.pin.kind,
        offset_step=parts.offset_step_mm, offset_max=parts.offset_max_mm, cw_links=tuple(cw.links),
        cw_distance=tuple(cw.distance_mm), cw_wall=cw.wall_mm, cw_clearance=cw.clearance_diametral_mm,
        slug_kind=cw.slugs.kind, slug_diameter=cw.slugs.diameter_mm, slug_lengths=tuple(sorted(cw.slugs.lengths_mm)),
        slug_density=cw.slugs.density_g_cm3 / 1000.0, binder_name=cw.binder.name,
        binder_density=cw.binder.density_g_cm3 / 1000.0, pin_stock=tuple(sorted(d.pin.stock_lengths_mm)),
        density=d.material.density_g_cm3 / 1000.0, material=d.material.name, print_wall=d.print.wall_mm,
        print_skin=d.print.skin_mm, infill=d.print.infill_percent / 100.0,
        overhang_angle=math.radians(d.print.overhang_angle_deg), min_contact=d.print.min_bed_contact_mm2,
        base_height=d.base.height_mm, foot_radius=d.base.foot_diameter_mm / 2, foot_thickness=d.base.foot_thickness_mm,
        min_tip_angle=math.radians(d.base.min_tip_angle_deg),
        tolerance=d.checks.balance_tolerance_mm, grid=tuple(d.checks.grid),
        infill_error=d.checks.infill_error_percent_points / 100.0, layers=parts.layers, fixed_layout=fixed,
        mass_scale=tuple(sorted(d.checks.mass_scale.items())),
        printer=printer_limits(p), segments=parts.segments)
