"""A wrist gear pair as parts: gear 1 (dome teeth) and gear 2 (swept sockets), and gear 2's pose
for any bend (θ, ψ) of the workspace; the kit as the protocol builds, refuses and files it."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from shapely.geometry import box

from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.protocol import Motion, ParamsKit
from ...design.spherical import RangeError
from ...errors import DesignError
from ...geometry.measure import refuse_oversize
from ...design import spherical as sph
from .spec import WristSpec
from ...geometry import wrist as W

from ...core.parts import Bore
from ...geometry.parts import DFit, Part
from ...geometry.printing import least_support_flip
from ...geometry.solid import SLIVER, extrude, float32_sound, print_arrays

__all__ = ["WristSpec", "WristKit", "build_wrist", "workspace_theta_max", "animation_motion", "build", "refuse",
           "design_summary", "kit_files", "plate_margin"]


CAP_TURNS_DEG = (0.0, 0.5, 1.0, 1.5)  # tessellation phases tried for a gear's cap (see build_wrist)


@dataclass(frozen=True)
class WristParams:
    name: str
    density: float
    material: str
    printer: object


@dataclass(frozen=True)
class WristKit(ParamsKit):
    spec: WristSpec
    pair: sph.WristPair
    parts: tuple[Part, ...]
    domes: tuple[W.Dome, ...]
    theta_max: float
    params: WristParams
    figures: dict = field(default_factory=dict)

    def pose2(self, theta: float, psi: float) -> np.ndarray:
        """(4, 4) pose of gear 2 for a bend (θ, ψ); gear 1 stays at the origin."""
        return sph.gear2_pose(theta, psi, self.spec.I, self.spec.A)

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        """Poses with the pair bent by θ on gear 1 (within the workspace: θ ≤ ``theta_max``) at
        azimuth ψ = 0; θ = 0 is the pair at rest (straight), the assembly the manifest places."""
        out = {"gear1": np.eye(4), "gear2": self.pose2(min(max(float(theta), 0.0), self.theta_max), 0.0)}
        shown_beside = np.eye(4)  # the cross gear is the other tooth form, not part of this pair
        shown_beside[0, 3] = -1.5 * self.spec.A
        out["cross_gear"] = shown_beside
        if self.spec.mate is not None:  # in mesh with the cross gear, on its pole
            from ...geometry.cross_mate import mate_pose
            out["cross_mate"] = shown_beside @ mate_pose(0.0, self.spec.cross, self.spec.mate)
        return out


def workspace_theta_max(I: float, max_bend: float) -> float:
    """Largest θ on gear 1 with θ + φ(θ) ≤ max_bend (the bend angle between the axes)."""
    lo, hi = 0.0, sph.valid_end(I)
    for _ in range(80):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if mid + float(sph.mating_angle(mid, I)) < max_bend else (lo, mid)
    return lo


def build_wrist(spec: WristSpec, progress=None) -> WristKit:
    say = progress or (lambda s: None)
    I, A = spec.I, spec.A
    pair = sph.tooth_rows(I, A, spec.long_pitch, spec.ring_teeth)
    theta_max = workspace_theta_max(I, spec.max_bend)
    parts, domes, pieces, n_poses, caps = _gear_parts(spec, pair, theta_max, 0, say)
    # A part whose mesh has two vertices a float32 STL cannot tell apart (a 3-D boolean of curved
    # solids leaves that now and then, or pinches where two sweep pieces share a sphere) is made
    # again with its surfaces of revolution turned about their axes and its spheres' facets turned
    # (the same gear, tessellated differently) or the cross gear grown by a little more. Each
    # attempt builds the parts afresh: manifold3d's lazy evaluation (and so its triangulation)
    # depends on what else holds a solid, so the first attempt is evaluated as a kit always was.
    for i in range(len(parts)):
        k = 0
        while not float32_sound(*print_arrays(parts[i].solid, parts[i].print_flip)[:2]) and k + 1 < len(CAP_TURNS_DEG):
            k += 1
            parts[i] = _gear_parts(spec, pair, theta_max, k)[0][i]
    end = sph.valid_end(I)
    alpha1, alpha2 = caps
    figures = {"rows": [{"k": r.k, "teeth": r.teeth, "theta_deg": round(math.degrees(r.theta), 4),
                         "phi_deg": round(math.degrees(r.phi), 4), "lat_pitch_mm": round(r.lat_pitch_1, 4),
                         "lat_pitch_vs_long": round(r.lat_pitch_1 / spec.long_pitch - 1, 5) if r.k else None}
                        for r in pair.rows],
               "theta_max_deg": round(math.degrees(theta_max), 4), "valid_end_deg": round(math.degrees(end), 4),
               "cap_deg": [round(math.degrees(alpha1), 4), round(math.degrees(alpha2), 4)],
               "sweep_pieces": pieces, "sweep_poses": n_poses}
    mate = next((p for p in parts if p.name == "cross_mate"), None)
    if mate is not None:  # how the mate was cut: sweep poses, step, the rings, the planes
        figures["mate"] = {k: list(v) if isinstance(v, tuple) else v for k, v in mate.info}
    return WristKit(spec, pair, tuple(parts), tuple(domes), theta_max,
                    WristParams(spec.name, spec.density, spec.material, spec.printer), figures)


def _gear_parts(spec: WristSpec, pair, theta_max: float, k: int = 0, say=lambda s: None):
    """The pair's parts (gear 1, gear 2, the cross gear if any), attempt ``k`` (see build_wrist):
    (parts, domes, sweep pieces, sweep poses, (cap angle of gear 1, of gear 2))."""
    I, A = spec.I, spec.A
    end = sph.valid_end(I)
    r_of1 = lambda a: sph.pitch_radii(np.clip(a, 0, end), I, A)[0]  # noqa: E731
    th_of = lambda b: 2 * np.arctan(np.tan(np.asarray(b) / 2) / I)  # noqa: E731  (gear 2's angle → θ)
    r_of2 = lambda b: sph.pitch_radii(np.clip(th_of(b), 0, end), I, A)[1]  # noqa: E731
    # the caps reach past the last ring and past the workspace's contact by a dome radius
    last = pair.rows[-1].theta
    ang_margin = (spec.dome_radius + spec.clearance) / float(r_of1(np.array([last]))[0])
    alpha1 = min(end, max(last, theta_max) + 2 * ang_margin)
    alpha2 = min(math.pi / 2, float(sph.mating_angle(alpha1, I)))
    fit = DFit(spec.shaft_diameter / 2, spec.press_clearance)
    turn = lambda cap: cap.rotate((0.0, 0.0, CAP_TURNS_DEG[k])) if k else cap  # noqa: E731
    facets = (17.0 * k, 29.0 * k, 0.0)  # the spheres of teeth and sockets tessellated differently
    parts = []
    say("gear1")
    cap1 = W.revolved_cap(r_of1, alpha1, -spec.base_height, fit.radius + 3.0, spec.tol)
    domes = W.dome_teeth([(r.theta, r.teeth) for r in pair.rows], r_of1, spec.dome_radius, spec.tooth_height)
    segs = max(24, int(round(2 * math.pi * spec.dome_radius / 0.5)))
    bore = extrude(fit.hole(0.01), spec.base_height + A / 4, -spec.base_height - 1.0)
    # the shaft comes up into each gear from its flat bottom, to the top of the bore cut
    shaft = (Bore("shaft", (0.0, 0.0, -spec.base_height), (0.0, 0.0, 1.0), fit.pin_diameter, spec.base_height + A / 4 - 1.0),)
    parts.append(Part("gear1", "wrist_gear", (turn(cap1) + W.domes_union(domes, 0.0, segs, facets)) - bore, bores=shaft))
    say("gear2 sockets")
    thetas = np.linspace(0.0, theta_max, spec.theta_steps)
    psis = 2 * np.pi * np.arange(spec.psi_steps) / spec.psi_steps
    poses = np.array([[np.linalg.inv(sph.gear2_pose(t, p, I, A)) for p in psis] for t in thetas])
    reach = float(r_of2(np.array([alpha2]))[0]) + 1.0
    sweep, pieces = W.socket_sweep(domes, poses, spec.clearance, reach, segs, turn=facets)
    cap2 = W.revolved_cap(r_of2, alpha2, -spec.base_height, fit.radius + 3.0, spec.tol)
    parts.append(Part("gear2", "wrist_gear", (turn(cap2) - sweep) - bore, bores=shaft))
    if spec.cross is not None:  # the second tooth form: an ABENICS cross gear on the same sphere
        say("cross gear")
        from ...geometry.cross_gear import GROW, cross_gear
        r = spec.cross.tip_radius * 1.05
        half = extrude(box(-r, -r, r, r), r + 1.0, 0.0)  # cut flat at the equator: it prints on that face
        solid = ((cross_gear(spec.cross, grow=GROW * (1 + k / 4)) ^ half)
                 - bore.translate((0, 0, spec.base_height))).simplify(SLIVER)
        parts.append(Part("cross_gear", "wrist_gear", solid, gear=spec.cross,
                          bores=(Bore("shaft", (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), fit.pin_diameter,
                                      spec.base_height + A / 4 - 1.0),)))
        if spec.mate is not None:  # its mate: an ABENICS monopole gear cut by the cross gear's ring teeth
            say("cross gear's mate")
            from ...geometry.cross_mate import mate_gear
            mate, mate_figures = mate_gear(spec.cross, spec.mate)
            half = spec.mate.face_width / 2
            parts.append(Part("cross_mate", "wrist_gear", mate, info=tuple(sorted(mate_figures.items())),
                              bores=(Bore("shaft", (0.0, 0.0, -half), (0.0, 0.0, 1.0), spec.mate.bore_diameter - 0.01,
                                          spec.mate.face_width),)))
    # each lies on its larger flat face unless the other needs less support
    parts = [replace(p, print_flip=least_support_flip(p.solid, spec.printer.overhang_deg)) for p in parts]
    return parts, domes, pieces, int(poses.shape[0] * poses.shape[1]), (alpha1, alpha2)


def animation_motion(motion: Motion, spec: WristSpec, kit: WristKit) -> Motion:
    """The assembly's animation bends the pair over its workspace: θ from 0 to ``theta_max``."""
    return Motion(motion.label, motion.unit, (0.0, float(kit.theta_max)))


def build(spec: WristSpec, progress=None) -> WristKit:
    try:
        kit = build_wrist(spec, progress)
    except (RangeError, ValueError) as e:
        raise DesignError(str(e), "wrist") from None
    return kit


def refuse(spec: WristSpec, kit: WristKit) -> None:
    refuse_oversize(kit.parts, spec.printer.envelope, "wrist.centre_distance_mm")


def design_summary(kind: str, spec: WristSpec, kit: WristKit) -> dict:
    return {"name": spec.name, "kind": kind, "nominal_ratio": spec.I,
            "centre_distance_mm": spec.A, "longitudinal_pitch_mm": spec.long_pitch, **kit.figures}


def kit_files(spec: WristSpec, kit: WristKit, raw: LoadedDesign) -> dict[str, bytes]:
    data = raw.document()
    data["printer"] = "printer.yaml"
    return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}


def plate_margin(spec: WristSpec) -> float:
    return 5.0
