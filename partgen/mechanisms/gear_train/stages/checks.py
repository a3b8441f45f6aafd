"""Every check of a gear train kit, through the shared kernels: the gear rules of each gear and mesh
(design.rules), each mesh over a full turn of the slowest shaft (checks.meshing: centre distance,
backlash by formula and measured, contact ratio, tip clearance, involute interference, tooth
overlap at every sampled phase), every pair of parts over that turn (checks.motion), the fits,
printability and the bed; and the printed outlines turned (motion.turn_train) for the backlash at
the output."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ....checks.motion import prepare
from ....checks.sequence import run_shared
from ....core.findings import Finding, Result
from ....core.parts import Contact, Part
from ....core.protocol import ParamsKit
from ....core.transforms import pose_z
from ....design import rules
from ....design.rules import gear_rules
from ....design.gear_train import overlap_ratio
from ....geometry.measure import intersection
from .kit import TrainKit
from .resolve import TrainSpec
from .motion import turn_train

__all__ = ["MeshView", "check_train", "sample_thetas", "exact_mesh_overlap"]


@dataclass(frozen=True)
class MeshView(ParamsKit):
    """The train's gears one by one (a compound part's two gears apart) as checks.meshing reads a kit:
    a part per gear, posed at its part's pose raised to its layer, and a mesh contact per stage."""

    kit: TrainKit

    @property
    def params(self) -> TrainSpec:
        return self.kit.params

    @property
    def parts(self) -> tuple[Part, ...]:
        return tuple(Part(g.name, "gear", None, gear=g.spec) for g in self.params.gears)

    @property
    def contacts(self) -> tuple[Contact, ...]:
        return tuple(Contact(m.driver, m.driven, "mesh") for m in self.params.meshes)

    def part(self, name: str) -> Part:
        return next(p for p in self.parts if p.name == name)

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.params
        return {g.name: pose_z(*s.shafts[g.shaft].centre, s.layer_z(g.layer), s.angle(s.shafts[g.shaft], theta))
                for g in s.gears}


def sample_thetas(spec: TrainSpec, samples: int | None) -> np.ndarray:
    """Input angles (rad) over one full turn of the slowest shaft."""
    n = samples or spec.checks.samples
    return np.linspace(0.0, spec.output_turn, n, endpoint=False)


def exact_mesh_overlap(kit: TrainKit, mesh, phases: int, nudge: float = 0.0) -> np.ndarray:
    """The exact overlap volume (mm³, manifold3d, the printed solids as they are: twisted, not prisms)
    of the two gear parts of ``mesh`` at ``phases`` input angles spread over one tooth pitch of its
    driver (a mesh repeats tooth by tooth, so these cover a full turn); ``nudge``: the driven part
    turned that far (rad) from its nominal angle (a test that the check can fail)."""
    s = kit.params
    gd, gn = s.gear(mesh.driver), s.gear(mesh.driven)
    pd, pn = kit.part(f"gears{gd.shaft}"), kit.part(f"gears{gn.shaft}")
    step = 2 * math.pi / gd.spec.teeth / abs(float(s.shafts[gd.shaft].speed))
    out = np.empty(phases)
    for i, t in enumerate(step * np.arange(phases) / phases):
        P = kit.poses(float(t))
        Tn = P[pn.name] @ pose_z(angle=nudge)
        out[i] = intersection(pd.solid, P[pd.name], pn.solid, Tn)[0]
    return out


def check_train(kit: TrainKit, samples: int | None = None, progress=None) -> Result:
    s = kit.params
    res = Result()
    t0 = time.perf_counter()
    thetas = sample_thetas(s, samples)
    view = MeshView(kit)
    mesh_rules = gear_rules(s)
    for g in s.gears:  # tip widths of the gears of compound parts (single gears: the printability check's)
        if kit.part(f"gears{g.shaft}").gear is None:
            for b in rules.gear_breaches(g.spec, mesh_rules, g.name):
                res.add(Finding("printability", "fail", b.message, (f"gears{g.shaft}",), None, b.value, "mm", rule=b.rule))
        if g.spec.undercut:
            res.add(Finding("design", "info", f"{g.name} ({g.spec.teeth} teeth, x = {g.spec.profile_shift:.3f}) is "
                            "undercut", (f"gears{g.shaft}",)))
    if s.target_ratio is not None:
        err = float(s.ratio) / s.target_ratio - 1
        res.figures["ratio"] = {"design": f"{s.ratio.numerator}/{s.ratio.denominator}", "value": float(s.ratio),
                                "target": s.target_ratio, "relative_error": err}
    # helical and herringbone parts are not z-prisms: the sweep sees each slab as the union of its
    # sections at five heights over the slab grown by the chord tolerance (the mesh's facets stray
    # about a tenth of it outside the sampled sections): an envelope; what it flags is measured
    # exactly in 3-D, and the meshes themselves below
    geo = prepare(kit, {f"gears{g.shaft}" for g in s.gears if g.hand}, s.system.chord_tolerance)
    # meshing teeth come within their backlash by design: their clearance is the mesh check's;
    # the bores: every shaft's way through the gears and the plates open
    meshing_parts = {frozenset((f"gears{s.gear(m.driver).shaft}", f"gears{s.gear(m.driven).shaft}")) for m in s.meshes}
    t1 = time.perf_counter()
    got = run_shared(res, kit, thetas, "input angle", progress, geo=geo, mesh_view=view, mesh_owned=meshing_parts)
    t4 = time.perf_counter()
    few = thetas[:: max(1, len(thetas) // 8)][:8]
    turned = turn_train(kit, few, tol=1e-6)
    out = len(s.shafts) - 1
    lash = np.abs(turned["coast"][:, out] - turned["drive"][:, out])
    if turned["overlap_mm2"].max() > 1e-6:
        k = int(np.argmax(turned["overlap_mm2"].max(axis=1)))
        res.add(Finding("mesh", "fail", f"the printed gears overlap by {turned['overlap_mm2'][k].max():.4f} mm² of "
                        "section at their nominal angles", (), float(few[k]), float(turned["overlap_mm2"][k].max()),
                        "mm2"))
    if lash.min() <= 0:
        res.add(Finding("mesh", "fail", "the train jams: no backlash at the output", (), None, float(lash.min()), "rad",
                        rule="backlash"))
    if s.helix:  # twisted solids: the meshes' overlap measured exactly in 3-D, phase by phase
        exact = []
        for m in s.meshes:
            vol = exact_mesh_overlap(kit, m, 12)
            exact.append({"pair": [m.driver, m.driven], "phases": 12, "max_overlap_mm3": round(float(vol.max()), 6),
                          "overlap_ratio": round(overlap_ratio(s.face_width / (2 if s.herringbone else 1), s.helix,
                                                               s.normal_module), 4)})
            if vol.max() > s.checks.interference_tolerance:
                res.add(Finding("mesh", "fail", f"{m.driver}/{m.driven}: the twisted teeth overlap by {vol.max():.4f} mm³ "
                                "(exact, in 3-D)", (f"gears{s.gear(m.driver).shaft}", f"gears{s.gear(m.driven).shaft}"),
                                None, float(vol.max()), "mm3"))
        res.figures["helical_meshes"] = exact
    t5 = time.perf_counter()
    res.figures.update(
        parts=len(kit.parts), samples=len(thetas), output_turns=1, input_turns=round(s.output_turn / (2 * math.pi), 6),
        motion=got.motion, meshes=got.meshes, clearance_left_to_mesh_check=got.dropped,
        fits={"count": len(got.fits), "rows": got.fits}, printability=got.printing,
        output_backlash_arcmin={"min": round(float(np.degrees(lash.min()) * 60), 3),
                                "max": round(float(np.degrees(lash.max()) * 60), 3), "angles": len(few)},
        seconds={"prepare": round(t1 - t0, 3), "motion": got.seconds["motion"], "meshes": got.seconds["meshes"],
                 "fits_and_printability": got.seconds["fits_and_printability"], "printed_backlash": round(t5 - t4, 3)})
    return res
