"""The cross gear's mate: an ABENICS monopole (MP) gear, cut by the cross spherical (CS) gear's ring
teeth swept through the meshing motion (a generating cut, like a gear shaper's).

Construction (Abe, Tadakuma et al. 2021 "ABENICS"; the public generators — the ABENICS-Maker
Fusion 360 script and the gear_openscad ``mpl_gear`` module — cut it the same way: a blank engraved
by the CS gear's revolved ring gear turned through the mesh):

* Frames. The CS gear (``cross_gear.cross_gear``) sits at the origin, pole on +z, its two ring sets
  about x and y. The MP gear's centre lies on the CS's pole axis at ``A = r_cs + r_mp`` (pitch
  radii m z / 2) and its axis is parallel to x. Its teeth mesh with the CS's ring set about y: that
  set's section by the plane x = 0 (which holds y) is the CS's 2-D involute profile, and there the
  pair is a spur mesh. In the MP's own frame (the printed part) its axis is z.
* The meshing motion. The MP turns ψ about its axis, the CS turns −ψ z_mp / z_cs about x (the axis
  through its centre parallel to the MP's): ratio z_cs / z_mp.
* The CS's free motion. One MP constrains two of the CS's three rotations; the third — the CS
  turning about its ring axis y — leaves the ring set about y unchanged (a solid of revolution), so
  an MP cut by that ring set tolerates it by construction. (The CS is the ring set about x
  intersected with the ring set about y, grown by ``cross_gear.GROW``: it lies inside the cutter.)
* Which CS teeth. Off the plane x = 0 the CS's ring teeth differ from ring to ring (a ring near the
  equator of the set is a great circle, one near its pole a small circle), so an MP tooth space
  meets a different ring each time round. Every MP tooth space is cut by *every* ring that can
  reach the MP while the CS turns up to ±``turn`` about x: each such ring, turned to the pole,
  swept through its whole engagement, the sweep repeated round the MP (its teeth are identical, so
  it runs in any phase). In the plane x = 0 all rings coincide and the MP's section is the exact
  generated conjugate of the CS's profile (an involute pinion, undercut where z_mp < 17 at 20°);
  off it, the rings that fall away from the face cut a little more: backlash grows towards the
  MP's faces (``check`` measures it).
* Clearance. The cutter is the CS's profile grown by ``clearance`` mm (normal to the flanks) on top
  of the cross gear's GROW: the MP's flanks stand that far off the CS's.
* Truncation (exact). No point of the MP lies nearer the CS's centre than ``A − r_tip_mp``, and a
  ring keeps its distance from the CS's centre all round, so the cutter keeps only the part of each
  ring tooth beyond that radius.
* Planes. The motion is planar (two turns about parallel axes), so the cut is exact plane by
  plane: in the plane at face coordinate x a ring tooth's section is its mid-plane section with
  every point at distance v from the ring axis moved to sqrt(v² − x²) from it (``_cutter_at``),
  and the MP's section there is a 2-D generating cut (``mate_section``, shapely). The solid joins
  the sections of ``2 slices + 1`` planes, each outline resampled to the same points a pitch, by a
  ruled surface (``mate_gear``). The spaces widen as x² off the mid-plane, so a chord between
  planes lies in the space: the joint errs on the clearance side. (The same cut in 3-D — the rings
  posed at every step, unioned with manifold3d's batch booleans and subtracted from the blank —
  makes the same gear some fifty times slower and with ten times the triangles; ``check`` still
  measures the pair in 3-D, exactly, on the meshes.)
* Sampling. The sweep unions the cutter at MP steps of ``step`` rad; between steps the MP keeps a
  scallop of height ≈ d² / (8 ρ) (d the cutter tip's travel per step, ρ its tip radius): ``step``
  is chosen to keep it under a third of the clearance (``mate_step``).

mm, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import manifold3d as m3d
import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import Polygon

from ..design.gearing import GearSpec
from .cross_gear import GROW
from .gear import gear_outline

__all__ = ["MateSpec", "mate_pose", "cross_pose", "mate_gear", "mate_rings", "engagement", "mate_step",
           "mate_section", "rx", "ry"]


@dataclass(frozen=True)
class MateSpec:
    """An MP gear's design numbers (mm, rad): teeth, face width, bore diameter, the cutter's normal
    clearance, the CS's turn each way the teeth are cut for."""

    teeth: int
    face_width: float
    bore_diameter: float
    clearance: float
    turn: float

    def pitch_radius(self, cs: GearSpec) -> float:
        return cs.module * self.teeth / 2

    def tip_radius(self, cs: GearSpec) -> float:
        return self.pitch_radius(cs) + cs.system.addendum_coeff * cs.module

    def centre_distance(self, cs: GearSpec) -> float:
        return cs.pitch_radius + self.pitch_radius(cs)

    def ratio(self, cs: GearSpec) -> float:
        """MP turns per CS turn: z_cs / z_mp."""
        return cs.teeth / self.teeth


def rx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]], dtype=float)


def ry(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]], dtype=float)


def _pose(R: np.ndarray, t=(0.0, 0.0, 0.0)) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, t
    return T


def mate_pose(psi: float, cs: GearSpec, mate: MateSpec) -> np.ndarray:
    """(4, 4) pose of the MP gear (its frame: axis z, centre at the origin) in the CS's frame, the MP
    turned by ``psi`` about its axis: centre at (0, 0, A), its axis along x (its local x points
    back at the CS's centre)."""
    return _pose(rx(psi) @ ry(math.pi / 2), (0.0, 0.0, mate.centre_distance(cs)))


def cross_pose(psi: float, cs: GearSpec, mate: MateSpec, tilt: float = 0.0, extra: float = 0.0) -> np.ndarray:
    """(4, 4) pose of the CS gear meshed with the MP turned by ``psi``: turned −ψ z_mp / z_cs (+
    ``extra``) about x, after a turn ``tilt`` about its own ring axis y (its free motion)."""
    return _pose(rx(-psi * mate.teeth / cs.teeth + extra) @ ry(tilt))


def engagement(cs: GearSpec, mate: MateSpec) -> float:
    """Half the CS turn (rad) over which one CS tooth is inside the MP's tip circle: the angle from
    the line of centres where the two tip circles cross, plus the tooth's half angle at its tip and
    a quarter pitch."""
    A, Ra, ra = mate.centre_distance(cs), cs.tip_radius + GROW + mate.clearance, mate.tip_radius(cs)
    gamma = math.acos(min(1.0, (A * A + Ra * Ra - ra * ra) / (2 * A * Ra)))
    return gamma + cs.tip_thickness / (2 * cs.tip_radius) + 0.25 * 2 * math.pi / cs.teeth


def mate_step(cs: GearSpec, mate: MateSpec) -> float:
    """MP turn (rad) between the sweep's poses: the cutter's tip (radius ≈ the rack's tip fillet,
    at least 0.2 m) travelling d per step leaves a scallop d²/(8ρ); d ≤ sqrt(8 ρ c / 3) keeps it
    under a third of the clearance c (and at most 2°)."""
    rho = max(cs.system.cutter_tip_coeff, 0.2) * cs.module
    # the tip's speed relative to the MP: (ω_mp + ω_cs) × its distance from the pitch point
    reach = cs.tip_radius - cs.pitch_radius + (cs.tip_radius * math.sin(engagement(cs, mate)))
    speed = (1 + mate.teeth / cs.teeth) * reach  # mm per rad of MP turn
    d = math.sqrt(8 * rho * max(mate.clearance, 0.01) / 3)
    return min(math.radians(2.0), d / speed)


def _profile(cs: GearSpec, grow: float) -> Polygon:
    outline = Polygon(gear_outline(cs).points)
    return outline.buffer(grow, join_style="mitre") if grow else outline


def _pole_tooth(cs: GearSpec, mate: MateSpec) -> np.ndarray:
    """The cutter's 2-D tooth in the CS's (y, z) plane: tooth z/4 of the profile (on +z, the pole)
    grown by GROW + clearance, between the middles of its two spaces, beyond A − r_tip_mp − 0.1
    (n, 2) ccw."""
    pitch = 2 * math.pi / cs.teeth
    r_cut = mate.centre_distance(cs) - mate.tip_radius(cs) - 0.1
    R = cs.tip_radius * 1.2
    wedge = Polygon([(0, 0), (R * math.cos(math.pi / 2 - pitch / 2), R * math.sin(math.pi / 2 - pitch / 2)), (0, R * 1.1),
                     (R * math.cos(math.pi / 2 + pitch / 2), R * math.sin(math.pi / 2 + pitch / 2))])
    tooth = shapely.difference(shapely.intersection(_profile(cs, GROW + mate.clearance), wedge),
                               shapely.Point(0, 0).buffer(r_cut, 256))
    return np.asarray(shapely.geometry.polygon.orient(tooth, 1.0).exterior.coords)[:-1]


def mate_rings(cs: GearSpec, mate: MateSpec) -> list[tuple[int, np.ndarray]]:
    """The CS's ring teeth (of its ring set about y) that can reach the MP while the CS turns up to
    ±``mate.turn``: (k, section) for tooth k of the profile (at angle a = k·2π/z from the ring
    axis), the section in the ring's own (along the axis, from the axis) coordinates."""
    pitch = 2 * math.pi / cs.teeth
    pts = _pole_tooth(cs, mate)
    limit = mate.turn + engagement(cs, mate)
    out = []
    for k in range(1, cs.teeth // 2):
        a = k * pitch
        if abs(a - math.pi / 2) > limit + 1e-9:
            continue
        c, s = math.cos(a - math.pi / 2), math.sin(a - math.pi / 2)
        uv = pts @ np.array([[c, s], [-s, c]])  # the pole tooth turned to angle a
        if uv[:, 1].min() > 1e-6:
            out.append((k, uv))
    return out


def _cutter_at(cs: GearSpec, rings, x: float) -> list[np.ndarray]:
    """Each ring tooth's section by the plane at face coordinate ``x``, turned about x to the pole,
    in the CS's (y, z) — exact: a point at distance v from the ring axis in the plane x = 0 lies at
    sqrt(v² − x²) from it in the plane x (the ring keeps its distance from the CS's centre)."""
    out = []
    for k, uv in rings:
        a = 2 * math.pi * k / cs.teeth
        if uv[:, 1].min() <= abs(x):
            # the ring is smaller than the face reaches: keep the part of it that crosses this plane
            poly = shapely.intersection(Polygon(uv), shapely.box(-1e3, abs(x) + 1e-6, 1e3, 1e3))
            if poly.is_empty or poly.area < 1e-9:
                continue
            polys = getattr(poly, "geoms", [poly])
            uvs = [np.asarray(q.exterior.coords)[:-1] for q in polys if q.area > 1e-9]
        else:
            uvs = [uv]
        c, s = math.cos(math.pi / 2 - a), math.sin(math.pi / 2 - a)
        for q in uvs:
            y, z = q[:, 0], np.sqrt(np.maximum(q[:, 1] ** 2 - x * x, 0.0))
            out.append(np.column_stack([y * c - z * s, y * s + z * c]))  # turned by π/2 − a about x
    return out


def _sweep_poses(cs: GearSpec, mate: MateSpec, step: float, half: bool = False) -> list[np.ndarray]:
    """(3, 3) planar transforms CS (y, z) → MP (x, y) for the MP turns of one engagement (``half``:
    the turns ψ ≥ 0 only)."""
    e = engagement(cs, mate) * cs.teeth / mate.teeth
    n = math.ceil(e / step)
    out = []
    for psi in np.linspace(-e, e, 2 * n + 1)[n if half else 0:]:
        T = np.linalg.inv(mate_pose(psi, cs, mate)) @ cross_pose(psi, cs, mate)
        # a CS point (x, y, z) lands at T (x, y, z, 1); rotations about x keep x, so in the plane the
        # map (y, z) → MP (X, Y) is the 2-D affine part (the MP's local z is the CS's x)
        out.append(np.array([[T[0, 1], T[0, 2], T[0, 3]], [T[1, 1], T[1, 2], T[1, 3]], [0.0, 0.0, 1.0]]))
    return out


def mate_section(cs: GearSpec, mate: MateSpec, x: float = 0.0, step: float | None = None,
                 rings=None) -> Polygon:
    """The MP gear's section by the plane at face coordinate ``x`` (0: its mid-plane, the CS's
    plane x = 0) as a 2-D generating cut: the blank disc minus every ring tooth's section at every
    pose of its engagement, the cut repeated at every MP tooth. The MP's frame (x toward the CS's
    centre at ψ = 0, tooth spaces centred at angle π + k·2π/z_mp)."""
    step = step or mate_step(cs, mate)
    rings = rings if rings is not None else mate_rings(cs, mate)
    ra = mate.tip_radius(cs)
    window = shapely.Point(0, 0).buffer(ra + 0.5, 128)
    cutters = _cutter_at(cs, rings, x)
    # the cut is symmetric about the MP's plane y = 0 (the CS's mirror y → −y takes ring k to ring
    # z/2 − k and a turn ψ to −ψ; the rings kept are symmetric), so the poses ψ ≥ 0 are cut and
    # mirrored
    ks = sorted(k for k, _ in rings)
    mirror = ks == sorted(cs.teeth // 2 - k for k in ks)
    polys = []
    for M in _sweep_poses(cs, mate, step, half=mirror):
        for q in cutters:
            P = q @ M[:2, :2].T + M[:2, 2]
            if np.einsum("ij,ij->i", P, P).min() < (ra + 0.5) ** 2:  # a pose wholly outside the blank cuts nothing
                polys.append(P)
    space = shapely.union_all(shapely.polygons(polys))
    if mirror:
        space = shapely.union(space, affinity.scale(space, 1.0, -1.0, origin=(0, 0)))
    space = shapely.intersection(space, window)
    spaces = [affinity.rotate(space, 360.0 * k / mate.teeth, origin=(0, 0)) for k in range(mate.teeth)]
    disc = shapely.Point(0, 0).buffer(ra, max(256, 16 * mate.teeth))
    return shapely.difference(disc, shapely.union_all(spaces))


def _one_pitch(section: Polygon, teeth: int, n: int) -> np.ndarray:
    """``n`` points of the section's outline over one pitch, evenly spaced along it, from the
    middle of the space at angle π to the middle of the next (ccw): (n, 2)."""
    ring = shapely.LineString(np.asarray(shapely.geometry.polygon.orient(section, 1.0).exterior.coords))
    R = 1e3
    p = 2 * math.pi / teeth

    def at(angle):
        ray = shapely.LineString([(0, 0), (R * math.cos(angle), R * math.sin(angle))])
        hit = shapely.intersection(ring, ray)
        pts = [hit] if hit.geom_type == "Point" else list(getattr(hit, "geoms", []))
        if len(pts) != 1:
            raise ValueError(f"the mate's outline crosses the middle of a tooth space {len(pts)} times (expected once)")
        return ring.project(pts[0])

    s0, s1 = at(math.pi), at(math.pi + p)
    L = ring.length
    if s1 <= s0:
        s1 += L
    d = np.linspace(s0, s1, n + 1)[:-1] % L
    return np.array([ring.interpolate(t).coords[0] for t in d])


def mate_gear(cs: GearSpec, mate: MateSpec, step: float | None = None, slices: int = 5,
              per_pitch: int = 160) -> tuple[m3d.Manifold, dict]:
    """The MP gear in its own frame (axis z, face from −face/2 to +face/2, bore through) and figures
    of its cut. Its sections at ``2 slices + 1`` planes across the face are 2-D generating cuts
    (``mate_section``, exact in each plane up to the sweep's step), their outlines resampled to
    ``per_pitch`` points a pitch and joined plane to plane by a ruled surface: the tooth spaces
    widen as x² off the mid-plane, so a chord between planes lies in the space (the joint errs on
    the clearance side by at most (Δx)²/(8 ρ_ring) ≈ 1e-3 mm)."""
    step = step or mate_step(cs, mate)
    rings = mate_rings(cs, mate)
    half = mate.face_width / 2
    xs = np.linspace(0.0, half, slices + 1)
    outlines = {}
    for x in xs:
        sec = mate_section(cs, mate, float(x), step, rings)
        one = _one_pitch(sec, mate.teeth, per_pitch)
        full = np.concatenate([one @ np.array([[math.cos(t), math.sin(t)], [-math.sin(t), math.cos(t)]])
                               for t in 2 * math.pi * np.arange(mate.teeth) / mate.teeth])
        outlines[float(x)] = full
    zs = np.concatenate([-xs[::-1], xs[1:]])
    rings_xy = [outlines[abs(float(z))] for z in zs]
    m = len(rings_xy[0])
    verts = np.concatenate([np.column_stack([r, np.full(m, z)]) for r, z in zip(rings_xy, zs)])
    i = np.arange(m)
    j = (i + 1) % m
    tris = []
    for s in range(len(zs) - 1):
        a, b = s * m, (s + 1) * m
        tris.append(np.column_stack([a + i, a + j, b + j]))
        tris.append(np.column_stack([a + i, b + j, b + i]))
    cap = np.asarray(m3d.triangulate([rings_xy[0]]), dtype=np.int64)
    top = (len(zs) - 1) * m
    tris.append(cap[:, ::-1])  # the bottom face looks down
    tris.append(np.asarray(m3d.triangulate([rings_xy[-1]]), dtype=np.int64) + top)
    mesh = m3d.Mesh(vert_properties=verts.astype(np.float32), tri_verts=np.concatenate(tris).astype(np.uint32))
    body = m3d.Manifold(mesh)
    if body.status() != m3d.Error.NoError:
        raise ValueError(f"the mate's lofted mesh is not a solid: {body.status()}")
    bore = m3d.Manifold.cylinder(mate.face_width + 2.0, mate.bore_diameter / 2, mate.bore_diameter / 2, 64, True)
    solid = body - bore
    return solid, {"poses": len(_sweep_poses(cs, mate, step)), "step_deg": round(math.degrees(step), 4),
                   "rings": tuple(k for k, _ in rings), "planes": int(len(zs)),
                   "engagement_deg": round(math.degrees(engagement(cs, mate) * cs.teeth / mate.teeth), 3)}
