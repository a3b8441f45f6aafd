"""A validated wrist design → the wrist assembly's spec (deg → rad, diametral clearances)."""

from __future__ import annotations

import math

from ..design.mechanism import PrinterLimits
from ..design.spherical import WristSpec
from .loader import LoadedDesign

__all__ = ["resolve_wrist"]


def resolve_wrist(loaded: LoadedDesign) -> WristSpec:
    d, w, p = loaded.design, loaded.design.wrist, loaded.printer
    return WristSpec(
        name=d.name, I=w.nominal_ratio, A=w.centre_distance_mm, long_pitch=w.longitudinal_pitch_mm,
        ring_teeth=tuple(w.ring_teeth), dome_radius=w.tooth.radius_mm, tooth_height=w.tooth.height_mm,
        clearance=w.clearance_radial_mm, max_bend=math.radians(w.max_bend_deg), theta_steps=w.sweep.theta_steps,
        psi_steps=w.sweep.psi_steps, shaft_diameter=w.shaft_diameter_mm,
        press_clearance=w.press_fit_clearance_diametral_mm, base_height=w.base_height_mm, tol=w.chord_tolerance_mm,
        density=d.material.density_g_cm3 / 1000.0, material=d.material.name,
        printer=PrinterLimits(p.name, tuple(p.build_envelope_mm), p.resolution_mm, p.min_hole_diameter_mm,
                              p.min_gear_diameter_mm, p.min_link_length_mm, p.min_wall_mm))
