"""A validated wrist design → the wrist assembly's spec (deg → rad, diametral clearances)."""

from __future__ import annotations

import math

from ...design.gearing import ToothSystem, make_gear
from ...design.involute import max_tip_fillet_coeff
from ...errors import ConfigError
from .spec import WristSpec
from ...geometry.cross_mate import MateSpec
from ...config.loader import LoadedDesign, printer_fit, printer_limits

__all__ = ["resolve_wrist", "findings"]

MIN_BEND_DEG = 10.0  # degrees: the least workspace bend partgen builds sockets for (see resolve_wrist)


def resolve_wrist(loaded: LoadedDesign) -> WristSpec:
    d, w, p = loaded.design, loaded.design.wrist, loaded.printer
    # each gear's pitch surface must hold its shaft with a wall, and a tooth: the smaller radius
    # is at the pole (i(0) = I, so r1 = A I/(1+I), r2 = A/(1+I))
    r_min = w.centre_distance_mm * min(w.nominal_ratio, 1.0) / (1.0 + w.nominal_ratio)
    need = w.shaft_diameter_mm / 2 + 3.0 + w.tooth.radius_mm
    if r_min < need:
        raise ConfigError(loaded.path, "wrist.centre_distance_mm",
                          f"{w.centre_distance_mm:g} mm makes a pitch radius of {r_min:.2f} mm at the pole, too small for "
                          f"the {w.shaft_diameter_mm:g} mm shaft, a 3 mm wall and a {w.tooth.radius_mm:g} mm tooth: use "
                          f"at least {w.centre_distance_mm * need / r_min:.1f} mm")
    # a dome tooth is the cap of a ball standing height_mm proud of the pitch surface: it must be
    # rooted in the surface on a footprint the printer can lay down (diameter 2·sqrt(h(2r − h)))
    r, h, wall = w.tooth.radius_mm, w.tooth.height_mm, p.min_wall
    key = "wrist.tooth.radius_mm" if r < wall / 2 else "wrist.tooth.height_mm"  # blame the absurd one
    if h >= 2 * r:
        raise ConfigError(loaded.path, key, f"a dome of radius {r:g} mm cannot stand {h:g} mm proud (its diameter is "
                          f"{2 * r:g} mm): the ball would float above the surface; keep height_mm under 2 × radius_mm")
    foot = 2 * math.sqrt(h * (2 * r - h))
    if foot < wall:
        h_min = r - math.sqrt(r * r - wall * wall / 4) if r >= wall / 2 else math.inf
        r_min = (h * h + wall * wall / 4) / (2 * h)
        raise ConfigError(loaded.path, key,
                          f"a dome of radius {r:g} mm standing {h:g} mm proud meets the surface on a circle of "
                          f"Ø{foot:.3f} mm, under the printer's {wall:g} mm wall: use a radius of at least {r_min:.2f} mm"
                          + (f" or a height of at least {h_min:.2f} mm" if math.isfinite(h_min) else ""))
    # gear 2's sockets are the sweep of gear 1's teeth over the bends; under 10° its poses nearly
    # coincide and the swept sockets are not a sound solid (2° left gear2 with edges of four faces)
    if w.max_bend_deg < MIN_BEND_DEG:
        raise ConfigError(loaded.path, "wrist.max_bend_deg", f"{w.max_bend_deg:g}° is under the {MIN_BEND_DEG:g}° "
                          "partgen builds a wrist for (a pair that bends less needs no spherical gears)")
    reach = max(p.build_envelope_mm)
    if w.centre_distance_mm > 2 * reach:
        raise ConfigError(loaded.path, "wrist.centre_distance_mm", f"{w.centre_distance_mm:g} mm makes gears larger than "
                          f"the printer's {reach:g} mm envelope")
    cross = mate = None
    if w.cross_gear is not None:
        c = w.cross_gear
        if w.nominal_ratio != 1.0:
            raise ConfigError(loaded.path, "wrist.cross_gear", "a cross gear needs a spherical pitch (nominal_ratio 1)")
        if abs(c.module_mm * c.teeth / 2 - w.centre_distance_mm / 2) > 1e-9:
            raise ConfigError(loaded.path, "wrist.cross_gear.module_mm",
                              f"pitch radius m·z/2 = {c.module_mm * c.teeth / 2:g} mm must be the sphere's "
                              f"{w.centre_distance_mm / 2:g} mm (half the centre distance)")
        alpha = math.radians(c.pressure_angle_deg)
        # the ISO 53 rack's 0.38 m tip fillet, or the largest that fits a steeper rack (25° takes 0.33)
        rho = min(0.38, 0.999 * max_tip_fillet_coeff(alpha, 1.25, 0.0))
        cross = make_gear(c.teeth, ToothSystem(module=c.module_mm, pressure_angle=alpha, cutter_tip_coeff=rho,
                                               profile_shift=0.0, backlash_per_gear=c.backlash_per_gear_mm,
                                               chord_tolerance=max(w.chord_tolerance_mm, 0.01)))
        if c.mate is not None:
            mate = _resolve_mate(loaded, c, cross)
    return WristSpec(
        name=d.name, I=w.nominal_ratio, A=w.centre_distance_mm, long_pitch=w.longitudinal_pitch_mm,
        ring_teeth=tuple(w.ring_teeth), dome_radius=w.tooth.radius_mm, tooth_height=w.tooth.height_mm,
        clearance=_clearance(loaded), max_bend=math.radians(w.max_bend_deg), theta_steps=w.sweep.theta_steps,
        psi_steps=w.sweep.psi_steps, shaft_diameter=w.shaft_diameter_mm,
        press_clearance=printer_fit(loaded, w.press_fit_clearance_diametral_mm, "press_fit",
                                    "wrist.press_fit_clearance_diametral_mm"), base_height=w.base_height_mm, tol=w.chord_tolerance_mm,
        density=d.material.density_g_cm3 / 1000.0, material=d.material.name,
        printer=printer_limits(p), cross=cross, mate=mate)


def _clearance(loaded: LoadedDesign) -> float:
    """``wrist.clearance_radial_mm`` in mm (radial): the number, or half the printer's running fit
    (diametral). ``auto`` never reaches here: loading a design (``pipeline.load``) puts auto play's
    numbers in its place (mechanisms.autoplay)."""
    c = loaded.design.wrist.clearance_radial_mm
    if c == "printer":
        return printer_fit(loaded, c, "running", "wrist.clearance_radial_mm") / 2
    if c == "auto":
        raise ConfigError(loaded.path, "wrist.clearance_radial_mm", "auto is chosen when partgen loads the design "
                          "(mechanisms.autoplay); this design was resolved without it")
    return c


def _resolve_mate(loaded: LoadedDesign, c, cross) -> MateSpec:
    """``wrist.cross_gear.mate`` → MateSpec, refusing what cannot be cut or printed (exit 2, key path)."""
    mt, key = c.mate, "wrist.cross_gear.mate"
    m = c.module_mm
    root = m * mt.teeth / 2 - 1.25 * m
    if mt.teeth > c.teeth:
        raise ConfigError(loaded.path, f"{key}.teeth", f"{mt.teeth} teeth: at most the cross gear's {c.teeth} (the mate "
                          "sits on the cross gear's pole and must not wrap it)")
    if mt.bore_diameter_mm / 2 + 1.5 > root:
        raise ConfigError(loaded.path, f"{key}.bore_diameter_mm",
                          f"Ø{mt.bore_diameter_mm:g} mm leaves under a 1.5 mm wall below the mate's root circle "
                          f"(Ø{2 * root:.2f} mm): use at most {max(0.0, 2 * (root - 1.5)):.2f} mm")
    if mt.face_width_mm > cross.pitch_radius:
        raise ConfigError(loaded.path, f"{key}.face_width_mm", f"{mt.face_width_mm:g} mm is wider than the cross gear's "
                          f"{cross.pitch_radius:g} mm pitch radius: the mate's faces would run off the ring teeth")
    if mt.clearance_normal_mm > 0.25 * m:
        raise ConfigError(loaded.path, f"{key}.clearance_normal_mm", f"{mt.clearance_normal_mm:g} mm is over a quarter "
                          f"of the module ({0.25 * m:g} mm): the mate's teeth would be cut away")
    return MateSpec(teeth=mt.teeth, face_width=mt.face_width_mm, bore_diameter=mt.bore_diameter_mm,
                    clearance=mt.clearance_normal_mm, turn=math.radians(mt.turn_deg))


def findings(spec) -> list:
    return []
