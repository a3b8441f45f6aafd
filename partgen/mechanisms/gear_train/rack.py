"""A rack and pinion on a base: the pinion pressed on a D-flat shaft turning in the base, the rack
sliding along x on a strip of the base, held against the pinion by a rail behind it. Resolver, kit,
check (the mesh over the whole travel on the printed sections, the rack mesh rules, every pair of
parts, fits, printability) and trace (the rack's travel against the pinion's angle).

Frame: the pinion's centre at the origin, the rack's pitch line at y = −(r_p + x m), its teeth up;
turning by θ (counter-clockwise), the pinion moves the rack by r_p θ along +x. z: the base's top at
0; the pinion and the rack span [g, g + f]; the pinion rests on a thrust ring round its shaft, the
rack on a strip under its body, both [0, g]; the rail stands [0, g + f].

Bores (``shafts.bores: [pinion]``, hubs.py): a D-flat, a keyway, a nut trap in the pinion's bottom face
on a bought threaded rod, or a set screw through a hub under it (then the pinion, the rack, its strip
and the rail are raised by the hub's height b).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import Polygon, box

from ...checks.sequence import run_shared
from ...config.loader import LoadedDesign, printer_limits
from ...core.findings import Finding, Result
from ...core.parts import Contact, Part
from ...core.printer import PrinterLimits
from ...core.protocol import ParamsKit
from ...core.transforms import pose_z
from ...design import rules
from ...design.gearing import GearSpec, ToothSystem, make_gear
from ...checks.settings import CheckSettings
from ...design.rules import gear_rules
from ...design.rack import rack_contact_ratio, rack_outline, rack_tip_width
from ...design.rules import ToothSystemError, check_generable
from ...errors import ConfigError
from ...geometry.gear import gear_body
from ...geometry.measure import section
from ...geometry.outline import circle
from ...geometry.parts import DFit, shaft as shaft_solid
from ...geometry.solid import extrude, mesh_arrays, prisms, slab, union
from .hubs import HARDWARE_KEY, Hub, HubError, plan_hub, sizes_within
from .kit import FEATURE_TOL, hub_contacts, hubbed_gear, screw_and_nut, turning_shaft

__all__ = ["RackSpec", "RackKit", "resolve_rack", "build_rack", "check_rack", "turn_rack"]


@dataclass(frozen=True)
class RackSpec:
    name: str
    system: ToothSystem
    face_width: float
    pinion: GearSpec
    rack_teeth: int
    back: float
    travel: float
    shaft_radius: float
    running: float
    press: float
    extension: float
    gap: float
    plate_thickness: float
    margin: float
    checks: CheckSettings
    density: float
    material: str
    printer: PrinterLimits
    tol: float
    hub: Hub | None = None  # the pinion's bore (None: a D-flat, as given no shafts.bores)
    base: float = 0.0  # the pinion's set-screw hub under its gear: the pinion and the rack raised by it (mm)
    hub_radius: float = 0.0  # that hub's radius (mm; 0: none)

    @property
    def gear_z(self) -> float:
        """The pinion's and the rack's bottom face (z, mm)."""
        return self.gap + self.base

    @property
    def pitch_line(self) -> float:
        """y of the rack's pitch line, mm (the pinion's centre at the origin)."""
        return -(self.pinion.pitch_radius + self.pinion.profile_shift * self.system.module)

    @property
    def rack_offset(self) -> float:
        """x of the rack at rest so that a space of it lies under the pinion's tooth 0 (pointing down)."""
        return 0.0 if self.rack_teeth % 2 == 0 else math.pi * self.system.module / 2

    def rack_x(self, theta: float) -> float:
        return self.rack_offset + self.pinion.pitch_radius * theta

    @property
    def thetas_range(self) -> tuple[float, float]:
        h = self.travel / 2 / self.pinion.pitch_radius
        return -h, h

    @property
    def rack_length(self) -> float:
        return self.rack_teeth * math.pi * self.system.module


def resolve_rack(loaded: LoadedDesign) -> RackSpec:
    d, p = loaded.design, loaded.printer
    g, r, fr = d.gears, d.rack, d.frame
    m = g.module_mm
    system = ToothSystem(module=m, pressure_angle=math.radians(g.pressure_angle_deg), addendum_coeff=g.addendum_coeff,
                         dedendum_coeff=g.dedendum_coeff, backlash_per_gear=g.backlash_per_gear_mm,
                         profile_shift=None if g.profile_shift == "auto" else float(g.profile_shift),
                         chord_tolerance=g.chord_tolerance_mm)
    pinion = make_gear(r.pinion_teeth, system)
    try:
        check_generable(pinion)
    except ToothSystemError as e:
        raise ConfigError(loaded.path, "gears.profile_shift" if e.field == "profile_shift" else "rack.pinion_teeth",
                          e.problem) from None
    # the rack keeps every tooth in mesh over the travel: the travel plus the mesh zone either side
    teeth = math.ceil((r.travel_mm + 8 * m) / (math.pi * m)) + 1
    length = teeth * math.pi * m
    if length > math.hypot(*p.build_envelope_mm[:2]):
        raise ConfigError(loaded.path, "rack.travel_mm", f"the rack comes out {length:.0f} mm long: longer than the "
                          "printer's bed even on its diagonal")
    fits = p.fits

    def fit(v, which):
        if v != "printer":
            return float(v)
        if fits is None:
            raise ConfigError(loaded.path, f"shafts.{which}", "the printer profile gives no measured fits: give a number")
        return fits.running_clearance_diametral_mm if which.startswith("running") else fits.press_fit_clearance_diametral_mm
    running = fit(d.shafts.running_clearance_diametral_mm, "running_clearance_diametral_mm")
    press = fit(d.shafts.press_fit_clearance_diametral_mm, "press_fit_clearance_diametral_mm")
    r_shaft = d.shafts.diameter_mm / 2
    wall = printer_limits(p).min_wall
    if r_shaft + press / 2 + wall >= pinion.root_radius:
        raise ConfigError(loaded.path, "shafts.diameter_mm", f"a {pinion.teeth}-tooth pinion (root Ø"
                          f"{2 * pinion.root_radius:.2f} mm) leaves no {wall:g} mm wall round its D-bore")
    if 2 * r_shaft + running < p.min_hole_diameter_mm - 1e-6:
        raise ConfigError(loaded.path, "shafts.diameter_mm", f"the shaft's running hole (Ø{2 * r_shaft + running:.2f} mm)"
                          f" is below the printer's smallest running hole ({p.min_hole_diameter_mm:g} mm)")
    hub, base, hub_r = _hub(loaded, pinion, r_shaft, running, press, wall)
    c = d.checks
    checks = CheckSettings(c.samples, c.interference_tolerance_mm3, c.min_clearance_mm, c.min_contact_ratio,
                           c.min_tip_width_roads, c.plate_margin_mm)
    return RackSpec(d.name, system, g.face_width_mm, pinion, teeth, r.back_mm, r.travel_mm, r_shaft, running, press,
                    d.shafts.extension_mm, fr.axial_gap_mm, fr.plate_thickness_mm, fr.margin_mm, checks,
                    d.material.density_g_cm3 / 1000.0, d.material.name, printer_limits(p), g.chord_tolerance_mm, hub,
                    base, hub_r)


def _hub(loaded: LoadedDesign, pinion: GearSpec, r_shaft: float, running: float, press: float, wall: float):
    """The pinion's bore from ``shafts.bores`` ([pinion]) and, for a set screw, its hub under the gear
    (height: the pinion and the rack raised by it; radius). None when ``shafts.bores`` is absent."""
    d, g = loaded.design, loaded.design.gears
    if not d.shafts.bores:
        return None, 0.0, 0.0
    gap, f = d.frame.axial_gap_mm, g.face_width_mm
    slack = max(g.chord_tolerance_mm, 0.005) + FEATURE_TOL
    try:
        h = plan_hub(d.shafts.bores[0], r_shaft, running, press, wall, gap, d.shafts.nut, d.shafts.set_screw, slack)
    except HubError as e:
        raise ConfigError(loaded.path, f"shafts.{e.key}", e.problem) from None
    fits = lambda what, radius: sizes_within(h.kind, what, radius, r_shaft, running, press, wall, gap, slack)  # noqa: E731
    key = f"shafts.{HARDWARE_KEY[h.kind]}"
    what = {"keyway": "its keyway", "hex": f"its {h.nut} nut trap", "d_flat": "its D-bore",
            "set_screw": f"its {h.nut} set screw's nut slot"}[h.kind]
    root = pinion.root_radius
    if h.kind != "d_flat" and h.room >= root:
        raise ConfigError(loaded.path, key, f"a {pinion.teeth}-tooth pinion (root Ø{2 * root:.2f} mm) leaves less than "
                          f"the printer's {wall:g} mm wall around {what} (needs a root Ø{2 * h.room:.2f} mm): a thinner "
                          f"shaft or smaller hardware{fits('room', root)}, or more pinion teeth (rack.pinion_teeth)")
    if h.kind == "hex" and h.pocket_depth + wall > f:
        raise ConfigError(loaded.path, "shafts.nut", f"the pinion's {h.nut} nut trap ({h.pocket_depth:.2f} mm deep) and a "
                          f"{wall:g} mm wall need a face {h.pocket_depth + wall:.2f} mm wide: a smaller nut"
                          f"{fits('pocket_depth', f - wall)} or a wider face (gears.face_width_mm)")
    if h.kind != "set_screw":
        return h, 0.0, 0.0
    # a hub under the pinion (the rack and its strip are raised with it): within the pinion's root
    hub_r = min(max(h.bore + max(3 * wall, 2.5), h.hub_need), root)
    if hub_r < h.hub_need - 1e-9:
        raise ConfigError(loaded.path, "shafts.set_screw", f"the pinion's hub has room for Ø{2 * root:.2f} mm (its root "
                          f"circle), its {h.nut} set screw needs Ø{2 * h.hub_need:.2f} mm: a smaller screw"
                          f"{fits('hub_need', root)}, a thinner shaft or more pinion teeth (rack.pinion_teeth)")
    return h, h.height, hub_r


@dataclass(frozen=True)
class RackKit(ParamsKit):
    params: RackSpec
    parts: tuple[Part, ...]
    contacts: tuple[Contact, ...]

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.params
        a = -math.pi / 2 + float(theta)  # tooth 0 points down into a space of the rack at rest
        out = {"frame_bottom": np.eye(4), "pinion": pose_z(angle=a), "shaft": pose_z(angle=a),
               "rack": pose_z(s.rack_x(float(theta)), s.pitch_line, s.gear_z)}
        for n in ("nut", "set_screw"):  # a nut trap's nut, a set screw and its nut turn with the pinion
            if any(p.name == n for p in self.parts):
                out[n] = out["pinion"]
        return out


def build_rack(s: RackSpec, progress=None) -> RackKit:
    say = progress or (lambda name: None)
    tol = FEATURE_TOL
    g, f, t, m = s.gap, s.face_width, s.plate_thickness, s.system.module
    gz, h = s.gear_z, s.hub
    al = s.system.pressure_angle
    hf = s.system.dedendum_coeff * m
    root_y = s.pitch_line - hf
    back_y = root_y - s.back
    rail_w = max(3 * s.printer.min_wall, 3.0)
    gap = s.running / 2  # the rack's back face runs this far from the rail
    say("frame_bottom")
    half = s.rack_length / 2 + s.travel / 2 + s.margin  # the guide holds the rack over its whole travel
    plate = box(-half, back_y - gap - rail_w - s.margin, half, s.pinion.tip_radius + s.margin)
    hole = circle((h.radius if h else s.shaft_radius) + s.running / 2, tol, hole=True)
    ring = circle(min(s.pinion.root_radius - 0.5, s.shaft_radius + s.running / 2 + max(2 * s.printer.min_wall, 2.0)),
                  tol).difference(hole)
    strip = box(-half, back_y + 0.5, half, root_y - s.checks.min_clearance - 0.5)
    rail = box(-half, back_y - gap - rail_w, half, back_y - gap)
    base = union([slab(plate.difference(hole), -t, 0.0), prisms([(ring, 0.0, g), (strip, 0.0, gz), (rail, 0.0, gz + f)])])
    parts = [Part("frame_bottom", "frame", base)]
    say("pinion")
    if h is None or h.kind == "d_flat":
        parts.append(Part("pinion", "gear", gear_body(s.pinion, f, DFit(s.shaft_radius, s.press).hole(max(s.tol, 0.005)),
                                                      g), gear=s.pinion))
        parts.append(Part("shaft", "axle", shaft_solid(DFit(s.shaft_radius, 0.0), [("round", -t, g), ("D", g, g + f),
                                                                                    ("round", g + f, g + f + s.extension)],
                                                       tol)))
    else:
        pinion = hubbed_gear(s.pinion, f, h, s.press, s.running, s.hub_radius, g, gz, bool(s.base), s.tol)
        parts.append(Part("pinion", "gear", pinion, print_flip=s.base > 0, gear=s.pinion))
        parts += turning_shaft(h, "shaft", "nut", -t, gz + f + s.extension, (g, gz + f))
        if h.kind == "set_screw":
            parts += screw_and_nut(h, "set_screw", "nut", g)
    say("rack")
    outline = rack_outline(s.rack_teeth, m, al, s.system.backlash_per_gear, s.system.addendum_coeff,
                           s.system.dedendum_coeff, s.system.cutter_tip_coeff, s.back, s.system.chord_tolerance)
    parts.append(Part("rack", "rack", extrude(Polygon(outline), f)))
    held = (s.running if h is not None and h.kind == "hex" else s.press) / 2  # a threaded rod: a clearance
    contacts = (Contact("pinion", "shaft", "press", (g, gz + f), held),
                Contact("shaft", "frame_bottom", "running", (-t, 0.0), s.running / 2),
                Contact("pinion", "frame_bottom", "thrust"), Contact("rack", "frame_bottom", "thrust"))
    if h is not None:
        contacts += tuple(hub_contacts(h, "pinion", "shaft", "nut", "set_screw", "frame_bottom"))
    return RackKit(s, tuple(parts), contacts)


def _sections(kit: RackKit) -> tuple:
    s = kit.params
    z = s.gear_z + s.face_width / 2
    return section(kit.part("pinion").solid, z), section(kit.part("rack").solid, s.face_width / 2)


def _place(geom, angle: float, at) -> object:
    c, sn = math.cos(angle), math.sin(angle)
    R = np.array([[c, -sn], [sn, c]])
    return shapely.transform(geom, lambda p: p @ R.T + np.asarray(at))


def turn_rack(kit: RackKit, thetas: np.ndarray, tol: float = 1e-6) -> dict:
    """Over pinion angles ``thetas`` (n,) rad, from the printed sections: the rack's x (mm) when the
    pinion drives it (``drive``: the rack found moved back from its nominal place until it touches,
    the pinion turning forward; ``coast``: the other flanks), nominal x, and the overlap (mm²) at
    the nominal place."""
    s = kit.params
    pin, rack = _sections(kit)
    m = s.system.module
    window = box(-4 * m, s.pitch_line - 3 * m, 4 * m, s.pitch_line + 3 * m)
    nominal = np.array([s.rack_x(float(t)) for t in thetas])
    out = {"nominal": nominal, "drive": np.empty(len(thetas)), "coast": np.empty(len(thetas)),
           "overlap_mm2": np.zeros(len(thetas))}
    for i, t in enumerate(thetas):
        P = shapely.intersection(_place(pin, -math.pi / 2 + float(t), (0.0, 0.0)), window)
        shapely.prepare(P)
        piece = shapely.intersection(_place(rack, 0.0, (nominal[i], s.pitch_line)), window.buffer(2 * m))

        def area(d: float) -> float:
            q = shapely.affinity.translate(piece, d)
            return P.intersection(q).area if P.intersects(q) else 0.0
        out["overlap_mm2"][i] = area(0.0)
        for key, sense in (("drive", -1.0), ("coast", 1.0)):
            lo, hi = 0.0, math.pi * m / 2
            while hi - lo > tol:
                mid = (lo + hi) / 2
                lo, hi = (lo, mid) if area(sense * mid) > 1e-9 else (mid, hi)
            out[key][i] = nominal[i] + sense * lo
    return out


def check_rack(kit: RackKit, samples: int | None = None, progress=None) -> Result:
    s = kit.params
    res = Result()
    n = samples or s.checks.samples
    thetas = np.linspace(*s.thetas_range, n)
    m, al = s.system.module, s.system.pressure_angle
    p = s.pinion
    eps = rack_contact_ratio(p.teeth, m, al, p.profile_shift, s.system.addendum_coeff, s.system.addendum_coeff)
    tip_root = {"pinion->rack": (s.system.dedendum_coeff - s.system.addendum_coeff) * m,
                "rack->pinion": (p.pitch_radius + p.profile_shift * m - s.system.addendum_coeff * m) - p.root_radius}
    tip_w = rack_tip_width(m, al, s.system.backlash_per_gear, s.system.addendum_coeff)
    need_tip = gear_rules(s).min_tip_width
    rows = {"teeth": [p.teeth, s.rack_teeth], "contact_ratio": round(eps, 4),
            "tip_root_mm": {k: round(v, 4) for k, v in tip_root.items()}, "rack_tip_width_mm": round(tip_w, 4),
            "travel_mm": s.travel}
    if eps < s.checks.min_contact_ratio:
        res.add(Finding("mesh", "fail", f"pinion/rack: contact ratio {eps:.3f} < {s.checks.min_contact_ratio:g}",
                        ("pinion", "rack"), None, eps, "", rule="contact-ratio"))
    for k, v in tip_root.items():
        if v < rules.TIP_ROOT_COEFF * m:
            res.add(Finding("mesh", "fail", f"pinion/rack: tip clears root by {v:.3f} mm ({k})", ("pinion", "rack"), None,
                            v, "mm", rule="tip-root"))
    if tip_w < need_tip - 1e-9:
        res.add(Finding("printability", "fail", f"rack: tooth tips {tip_w:.3f} mm wide, under {need_tip:.3f} mm", ("rack",),
                        None, tip_w, "mm", rule="tip-width"))
    if p.undercut:
        res.add(Finding("design", "info", f"the pinion ({p.teeth} teeth) is undercut", ("pinion",)))
    ext = {q.name: (lambda v: v.max(axis=0) - v.min(axis=0))(mesh_arrays(q.solid)[0]) for q in kit.parts}
    got = run_shared(res, kit, thetas, "input angle", progress, mesh_owned={frozenset(("pinion", "rack"))},
                     extents=ext, bores=False)
    turned = turn_rack(kit, thetas)
    lash = turned["coast"] - turned["drive"]
    if turned["overlap_mm2"].max() > 1e-6:
        k = int(np.argmax(turned["overlap_mm2"]))
        res.add(Finding("mesh", "fail", f"pinion/rack: the printed teeth overlap by {turned['overlap_mm2'][k]:.4f} mm²",
                        ("pinion", "rack"), float(thetas[k]), float(turned["overlap_mm2"][k]), "mm2"))
    if lash.min() <= 0:
        res.add(Finding("mesh", "fail", "pinion/rack: no backlash", ("pinion", "rack"), None, float(lash.min()), "mm",
                        rule="backlash"))
    rows.update(backlash_mm={"min": round(float(lash.min()), 5), "max": round(float(lash.max()), 5),
                             "designed": 2 * s.system.backlash_per_gear},
                max_overlap_mm2=float(turned["overlap_mm2"].max()))
    res.figures.update(parts=len(kit.parts), samples=n, input_turns=round((thetas[-1] - thetas[0]) / (2 * math.pi), 4),
                       motion=got.motion, rack_mesh=rows, clearance_left_to_mesh_check=got.dropped,
                       fits={"count": len(got.fits), "rows": got.fits}, printability=got.printing,
                       output_backlash_mm={"min": float(lash.min()), "max": float(lash.max())})
    return res
