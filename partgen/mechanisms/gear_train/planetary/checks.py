"""The planetary set's check: the internal mesh's rules, the sun/planet meshes and every pair of parts
over a carrier turn, fits and printability (``checks.sequence``), every planet against sun and ring on
the printed sections (tip and trochoidal interference), the backlash at the carrier. Its text is the
turning train's (``common/checks.py``)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ....checks.sequence import run_shared
from ....core.findings import Finding, Result
from ....core.parts import Contact
from ....core.protocol import ParamsKit
from ....core.transforms import pose_z
from ....design import rules
from ....design.planetary import internal_contact_ratio, planet_clearance, ring_contact_on_pinion, ring_tip_radius
from .kit import PlanetaryKit
from .motion import turn_planetary

__all__ = ["check_planetary"]


@dataclass(frozen=True)
class _SunPlanetView(ParamsKit):
    """The sun and the planets as checks.meshing reads a kit (the ring mesh is checked here)."""

    kit: PlanetaryKit

    @property
    def params(self):
        return self.kit.params

    @property
    def parts(self):
        return tuple(p for p in self.kit.parts if p.name == "sun" or p.name.startswith("planet"))

    @property
    def contacts(self):
        return tuple(Contact("sun", f"planet{i}", "mesh") for i in range(len(self.params.angles)))

    def part(self, name):
        return self.kit.part(name)

    def poses(self, theta=0.0):
        s = self.params  # the sun's and the planets' poses as PlanetaryKit.poses has them, lifted to the gears
        lift = pose_z(0.0, 0.0, s.gear_z)
        out = {"sun": pose_z(angle=float(theta)) @ lift}
        for i in range(len(s.angles)):
            out[f"planet{i}"] = pose_z(*s.planet_centre(i, theta), 0.0, s.planet_angle(i, theta)) @ lift
        return out


def check_planetary(kit: PlanetaryKit, samples: int | None = None, progress=None) -> Result:
    s = kit.params
    res = Result()
    n = samples or s.checks.samples
    thetas = np.linspace(0.0, s.output_turn, n, endpoint=False)
    zs, zp, zr, N = s.teeth.sun, s.teeth.planet, s.teeth.ring, s.teeth.planets
    m, alpha = s.system.module, s.system.pressure_angle
    # the internal mesh's rules (the external sun/planet mesh: checks.meshing below)
    a = s.centre_distance
    need = rules.TIP_ROOT_COEFF * m
    r_ai = ring_tip_radius(zr, m, 0.0, s.system.addendum_coeff)
    r_inv = rules.form_radius(s.space)  # the ring's involute ends here, its tip corners are the cutter's fillets
    internal = {"teeth": [zp, zr], "tooth_difference": zr - zp, "centre_distance_mm": round(a, 6),
                "ring_involute_radius_mm": round(r_inv, 4),
                "contact_ratio": round(internal_contact_ratio(zp, zr, m, alpha, 0.0, 0.0, a, s.system.addendum_coeff,
                                                              r_inv), 4),
                "tip_root_mm": {"planet->ring": round(s.space.tip_radius - (a + s.planet.tip_radius), 4),
                                "ring->planet": round((r_ai - a) - s.planet.root_radius, 4)},
                "assembly": f"({zs} + {zr})/{N} = {(zs + zr) / N:g}"}
    for k, v in internal["tip_root_mm"].items():
        if v < need:
            res.add(Finding("mesh", "fail", f"planet/ring: tip clears root by {v:.3f} mm ({k})", ("planet0", "frame_bottom"),
                            None, v, "mm", rule="tip-root"))
    if internal["contact_ratio"] < s.checks.min_contact_ratio:
        res.add(Finding("mesh", "fail", f"planet/ring: contact ratio {internal['contact_ratio']:.3f} < "
                        f"{s.checks.min_contact_ratio:g}", ("planet0", "frame_bottom"), None, internal["contact_ratio"], "",
                        rule="contact-ratio"))
    r_c = ring_contact_on_pinion(zp, zr, m, alpha, 0.0, a, s.system.addendum_coeff, r_inv)
    if r_c < rules.form_radius(s.planet) - 1e-6:
        res.add(Finding("mesh", "fail", f"planet/ring: the ring's tip meets the planet at r = {r_c:.3f} mm, below its form "
                        "radius (involute interference)", ("planet0", "frame_bottom"), None, r_c, "mm", rule="involute"))
    gap = planet_clearance(list(s.angles), a, s.planet.tip_radius)
    internal["planet_tip_gap_mm"] = round(gap, 4)
    if gap < s.checks.min_clearance:
        res.add(Finding("clearance", "fail", f"neighbouring planets' tips come within {gap:.3f} mm", ("planet0", "planet1"),
                        None, gap, "mm"))
    for name, gear in (("sun", s.sun), ("planet0", s.planet)):
        if gear.undercut:
            res.add(Finding("design", "info", f"{name} ({gear.teeth} teeth) is undercut", (name,)))
    meshing = {frozenset(("sun", f"planet{i}")) for i in range(N)} | {frozenset((f"planet{i}", "frame_bottom"))
                                                                     for i in range(N)}
    got = run_shared(res, kit, thetas, "input angle", progress, mesh_view=_SunPlanetView(kit), mesh_owned=meshing,
                     prune=True, bores=False)
    # every planet against sun and ring on the printed sections (tip and trochoidal interference): both
    # meshes of a planet advance one planet tooth while the sun turns 2π / (z_s (1 − 1/i)) about the
    # carrier, so 8 angles over that span see every phase of every mesh
    few = np.linspace(0.0, 2 * math.pi / (zs * (1 - 1 / s.ratio)), 8, endpoint=False)
    turned = turn_planetary(kit, few, tol=1e-5)
    worst = turned["overlap_mm2"].max()
    if worst > 1e-6:
        k, j = np.unravel_index(np.argmax(turned["overlap_mm2"]), turned["overlap_mm2"].shape)
        what = f"sun/planet{j}" if j < N else f"planet{j - N}/ring"
        res.add(Finding("mesh", "fail", f"{what}: the printed teeth overlap by {worst:.4f} mm² of section (tip or "
                        "trochoidal interference)", (), float(few[k]), float(worst), "mm2"))
    lash = np.abs(turned["coast"] - turned["drive"])
    if lash.min() <= 0:
        res.add(Finding("mesh", "fail", "the set jams: no backlash at the carrier", (), None, float(lash.min()), "rad",
                        rule="backlash"))
    res.figures.update(parts=len(kit.parts), samples=n, input_turns=round(s.ratio, 6), motion=got.motion,
                       meshes=got.meshes, internal_mesh=internal, clearance_left_to_mesh_check=got.dropped,
                       fits={"count": len(got.fits), "rows": got.fits}, printability=got.printing,
                       output_backlash_arcmin={"min": round(float(np.degrees(lash.min()) * 60), 3),
                                               "max": round(float(np.degrees(lash.max()) * 60), 3), "angles": len(few)},
                       max_printed_overlap_mm2=float(worst))
    return res
