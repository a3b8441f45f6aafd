"""The gear train's kit: a frame of two plates with spacers, a shaft per gear axis, a gear part per
shaft (two gears on one hub where the stage is compound), the bought hardware; their poses over the
input's turn; the manifest's design."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ....core.parts import Bore, Contact, Part
from ....core.protocol import ParamsKit
from ....core.transforms import pose_z
from ....geometry.gear import gear_body, helical_body
from ....geometry.outline import circle, hull_of_discs
from ....geometry.parts import DFit, shaft as shaft_solid
from ....geometry.solid import prisms, slab, union
from ..common import KIND
from ..common.hubs import turning
from ..common.kit import FEATURE_TOL, hub_cutters, hub_hole, hub_summary, r6, screw_and_nut, turning_shaft
from .resolve import FLAT_DEPTH, Shaft, TrainSpec

__all__ = ["TrainKit", "build_train", "design_summary"]


@dataclass(frozen=True)
class TrainKit(ParamsKit):
    """The frame, the shafts and the gear parts; poses over the input's turn θ (rad)."""

    params: TrainSpec
    parts: tuple[Part, ...]
    contacts: tuple[Contact, ...]
    spacers: tuple[tuple[float, float], ...]

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.params
        out = {"frame_bottom": np.eye(4), "frame_top": np.eye(4)}
        for sh in s.shafts:
            a = s.angle(sh, float(theta))
            out[f"gears{sh.index}"] = pose_z(sh.centre[0], sh.centre[1], 0.0, a)
            out[f"shaft{sh.index}"] = pose_z(sh.centre[0], sh.centre[1], 0.0, a if turning(sh.bore) else 0.0)
            if sh.bore in ("hex", "set_screw"):  # the bought nut (and screw) turn with the gear part
                out[f"nut{sh.index}"] = out[f"gears{sh.index}"]
                if sh.bore == "set_screw":
                    out[f"set_screw{sh.index}"] = out[f"gears{sh.index}"]
        return out


def _spacer_centres(s: TrainSpec) -> list[tuple[float, float]]:
    """Four spacers at the corners of the box around every tip circle, each outside every tip circle
    by at least the frame's margin (a corner is √2 (r + margin + spacer) from any circle's centre
    along the diagonal, at least r + margin + spacer in each axis)."""
    tips = [(s.shafts[g.shaft].centre, g.spec.tip_radius) for g in s.gears]
    d = s.margin + s.spacer_radius
    x0 = min(c[0] - r for c, r in tips) - d
    x1 = max(c[0] + r for c, r in tips) + d
    y0 = min(c[1] - r for c, r in tips) - d
    y1 = max(c[1] + r for c, r in tips) + d
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


def _bore(s: TrainSpec, sh: Shaft):
    """The gear part's bore: round over a fixed pin, a D over a turning shaft's flat (on local -y), a
    round bore with its keyway (on local +y), or round (a nut trap's, a set screw's)."""
    tol = max(s.tol, 0.005)
    if sh.bore == "d_flat":
        return DFit(s.shaft_radius, s.press).hole(tol)
    if sh.fit is not None:
        return hub_hole(sh.fit, s.press, tol)
    return circle(s.bore_radius(sh), tol, hole=True)


def _part_span(s: TrainSpec, sh: Shaft) -> tuple[float, float]:
    """The gear part's bottom and top (z, mm, world): from its thrust ring, or its lowest gear."""
    lo = s.layer_z(sh.layers[0])
    return (s.gap if lo > s.gap + 1e-9 else lo), s.layer_z(sh.layers[1]) + s.face_width


def _cutters(s: TrainSpec, sh: Shaft) -> list:
    """What the gear part loses for its hardware: a nut trap in its bottom face, or a set screw's
    radial hole (on local +x) and its nut's slot open at the bottom face."""
    z0, _ = _part_span(s, sh)
    return hub_cutters(s.hub(sh), z0, sh.hub_radius + 1.0, s.running)


def _gear_part(s: TrainSpec, sh: Shaft) -> Part:
    mine = sorted((g for g in s.gears if g.shaft == sh.index), key=lambda g: g.layer)
    hole = _bore(s, sh)
    tol = FEATURE_TOL
    solids = [helical_body(g.spec, s.face_width, hole, s.layer_z(g.layer), s.twist(g), s.herringbone,
                           s.system.chord_tolerance) if g.hand else gear_body(g.spec, s.face_width, hole, s.layer_z(g.layer))
              for g in mine]
    web = []
    lo = s.layer_z(mine[0].layer)
    if lo > s.gap + 1e-9:  # a hub down to the thrust ring
        web.append((circle(sh.hub_radius, tol).difference(hole), s.gap, lo))
    for a, b in zip(mine[:-1], mine[1:]):  # the web joining a compound shaft's two gears through the gap
        r = min(a.spec.root_radius, b.spec.root_radius)
        web.append((circle(r, tol).difference(hole), s.layer_z(a.layer) + s.face_width, s.layer_z(b.layer)))
    solid = union(solids + ([prisms(web)] if web else []))
    cut = _cutters(s, sh)
    if cut:
        solid = solid - union(cut)
    flip = lo > s.gap + 1e-9  # its lowest gear stands on a hub: print it upside down, top gear face on the bed
    z_lo, z_hi = _part_span(s, sh)
    pin = 2 * (s.shaft_radius - FLAT_DEPTH) if sh.bore == "d_flat" else 2 * s.radius(sh)
    return Part(f"gears{sh.index}", "gear", solid, print_flip=flip, gear=mine[0].spec if len(mine) == 1 else None,
                bores=(Bore("shaft", (0.0, 0.0, z_lo), (0.0, 0.0, 1.0), pin, z_hi - z_lo),))


def _shaft_parts(s: TrainSpec, sh: Shaft, z_lo: float, z_hi: float) -> list[Part]:
    """Shaft ``sh`` from under the bottom plate up (a fixed pin to the top plate's top, a turning shaft
    ``extension`` above it): printed — round, with a D-flat or with its integral key along the gear
    part — or bought: a hex bore's threaded rod and its nut; a set screw and its square nut."""
    t, zt, tol = s.plate_thickness, s.top_z, FEATURE_TOL
    fit, h, name = DFit(s.shaft_radius, 0.0), s.hub(sh), f"shaft{sh.index}"
    top = zt + t + (s.extension if turning(sh.bore) else 0.0)
    if sh.bore == "d_flat":  # round in the plates, D under the gear part, round above it through the top plate
        return [Part(name, "axle", shaft_solid(fit, [("round", -t, z_lo), ("D", z_lo, z_hi), ("round", z_hi, top)], tol))]
    if sh.bore == "round":
        return [Part(name, "axle", shaft_solid(fit, [("round", -t, top)], tol))]
    return turning_shaft(h, name, f"nut{sh.index}", -t, top, (z_lo, z_hi))


def _set_screw_parts(s: TrainSpec, sh: Shaft) -> list[Part]:
    """A set screw's bought parts, posed with the gear part: the screw (from the shaft's surface out,
    along local +x) and its square nut in the slot."""
    z0, _ = _part_span(s, sh)
    return screw_and_nut(s.hub(sh), f"set_screw{sh.index}", f"nut{sh.index}", z0)


def build_train(s: TrainSpec, progress=None) -> TrainKit:
    say = progress or (lambda name: None)
    tol = FEATURE_TOL
    t, zt = s.plate_thickness, s.top_z
    spacers = _spacer_centres(s)
    peg = s.spacer_radius / 2
    discs = [(sh.centre, max(g.spec.tip_radius for g in s.gears if g.shaft == sh.index) + s.margin) for sh in s.shafts]
    discs += [(c, s.spacer_radius + 2.0) for c in spacers]
    outline = hull_of_discs(discs, tol)
    hole_r = {sh.index: s.radius(sh) + (s.press if sh.bore == "round" else s.running) / 2 for sh in s.shafts}
    holes = [circle(hole_r[sh.index], tol, sh.centre, hole=True) for sh in s.shafts]
    bottom = outline
    for h in holes:
        bottom = bottom.difference(h)
    say("frame_bottom")
    rings = [(circle(sh.hub_radius, tol, sh.centre).difference(holes[sh.index]), 0.0, s.gap) for sh in s.shafts]
    columns = [(circle(s.spacer_radius, tol, c), 0.0, zt) for c in spacers]
    pegs = [(circle(peg, tol, c), zt, zt + t) for c in spacers]
    down, up = (0.0, 0.0, -1.0), (0.0, 0.0, 1.0)  # the round part of every shaft runs through both plates
    parts = [Part("frame_bottom", "frame", union([slab(bottom, -t, 0.0), prisms(rings + columns + pegs)]),
                  bores=tuple(Bore(f"shaft{sh.index}", (sh.centre[0], sh.centre[1], -t), up, 2 * s.radius(sh), t + s.gap)
                              for sh in s.shafts))]
    say("frame_top")
    top = outline
    for h in holes + [circle(peg + s.press / 2, tol, c, hole=True) for c in spacers]:
        top = top.difference(h)
    parts.append(Part("frame_top", "frame", slab(top, zt, zt + t),
                      bores=tuple(Bore(f"shaft{sh.index}", (sh.centre[0], sh.centre[1], zt + t), down, 2 * s.radius(sh), t)
                                  for sh in s.shafts)))
    contacts = []
    for sh in s.shafts:
        say(f"gears{sh.index}")
        gp = _gear_part(s, sh)
        parts.append(gp)
        z_lo, z_hi = _part_span(s, sh)
        say(f"shaft{sh.index}")
        parts += _shaft_parts(s, sh, z_lo, z_hi)
        if sh.bore == "set_screw":
            parts += _set_screw_parts(s, sh)
        g, sn = gp.name, f"shaft{sh.index}"
        if sh.bore == "round":
            contacts.append(Contact(g, sn, "running", (z_lo, z_hi), s.running / 2))
            contacts += [Contact(sn, "frame_bottom", "press", (-t, 0.0), s.press / 2),
                         Contact(sn, "frame_top", "press", (zt, zt + t), s.press / 2)]
        else:  # fixed to a turning shaft (a hex bore's rod: held by the nut, its bore a clearance)
            gap = (s.running if sh.bore == "hex" else s.press) / 2
            contacts.append(Contact(g, sn, "press", (z_lo, z_hi), gap))
            contacts += [Contact(sn, "frame_bottom", "running", (-t, 0.0), s.running / 2),
                         Contact(sn, "frame_top", "running", (zt, zt + t), s.running / 2)]
        contacts.append(Contact(g, "frame_bottom", "thrust"))
        if sh.bore == "hex":  # the nut: in its trap, on its rod, on the thrust ring with the gear part
            contacts += [Contact(f"nut{sh.index}", g, "thrust"), Contact(f"nut{sh.index}", sn, "thrust"),
                         Contact(f"nut{sh.index}", "frame_bottom", "thrust")]
        if sh.bore == "set_screw":  # the screw in its hole, through its nut, on the shaft; the nut in its slot
            n_, c_ = f"nut{sh.index}", f"set_screw{sh.index}"
            contacts += [Contact(n_, g, "thrust"), Contact(c_, g, "thrust"), Contact(c_, n_, "thrust"),
                         Contact(c_, sn, "thrust")]
    contacts.append(Contact("frame_top", "frame_bottom", "press", (zt, zt + t), s.press / 2))
    return TrainKit(s, tuple(parts), tuple(contacts), tuple(spacers))


def design_summary(spec: TrainSpec) -> dict:
    r = spec.ratio
    out = {"name": spec.name, "kind": KIND, "module_mm": spec.system.module,
           "pressure_angle_deg": r6(math.degrees(spec.system.pressure_angle)), "face_width_mm": spec.face_width,
           "ratio": f"{r.numerator}/{r.denominator}", "ratio_value": r6(float(r)),
           "output_sense": "same as the input" if spec.shafts[-1].speed > 0 else "opposite to the input",
           "stages": [{"teeth": [st.driver, st.driven], "ratio": r6(float(st.ratio)), "idler": st.idler,
                       "profile_shift": [r6(spec.gear(m.driver).spec.profile_shift),
                                         r6(spec.gear(m.driven).spec.profile_shift)],
                       "centre_distance_mm": r6(m.centre_distance), "direction_deg": r6(math.degrees(m.direction)),
                       "gears": [m.driver, m.driven]}
                      for st, m in zip(spec.stages, spec.meshes)],
           "shafts": [{"centre_mm": [r6(c) for c in sh.centre], "bore": sh.bore,
                       "speed": f"{sh.speed.numerator}/{sh.speed.denominator}", "phase_deg": r6(math.degrees(sh.phase)),
                       "hub_diameter_mm": r6(2 * sh.hub_radius), **hub_summary(sh.fit, spec.running)} for sh in spec.shafts],
           "hub_height_mm": r6(spec.base),
           "shaft_diameter_mm": 2 * spec.shaft_radius, "printer": spec.printer.name, "material": spec.material,
           "density_g_cm3": r6(spec.density * 1000)}
    if spec.helix:
        out.update(helix_angle_deg=r6(math.degrees(spec.helix)), herringbone=spec.herringbone,
                   normal_module_mm=r6(spec.normal_module), transverse_module_mm=r6(spec.system.module),
                   profile_shift_plane="transverse (x_t = x_n cos β)",
                   hands=[{"gear": g.name, "hand": "right" if g.hand > 0 else "left"} for g in spec.gears])
    if spec.target_ratio is not None:
        out["target_ratio"] = spec.target_ratio
        out["ratio_error"] = r6(float(r) / spec.target_ratio - 1)
    return out
