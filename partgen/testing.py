"""Measurements of printed meshes, for tests and for users who gate their own designs in CI.

They read the mesh as written (section it, measure it) and compare with the formulas; nothing
here trusts the generator's own numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
import trimesh
from shapely.geometry import Polygon

from .design import involute

__all__ = ["as_trimesh", "GearMeasurement", "section_outline", "measure_spur_gear", "BevelFlanks", "measure_bevel_flanks",
           "measure_worm_flanks", "mesh_problems"]


def as_trimesh(mesh) -> trimesh.Trimesh:
    """A trimesh mesh of ``mesh`` (a ``trimesh.Trimesh``, returned as it is, or anything with
    ``vertices`` and ``faces``, such as the ``export.stl.Mesh`` a kit's parts are written from)."""
    if isinstance(mesh, trimesh.Trimesh):
        return mesh
    return trimesh.Trimesh(np.asarray(mesh.vertices), np.asarray(mesh.faces), process=False)


def section_outline(mesh, z: float) -> Polygon:
    """Largest polygon (with the rings inside it as holes) of the mesh's section by the plane at
    height z, in the mesh's own x, y, mm (``mesh``: as ``as_trimesh`` takes)."""
    sec = as_trimesh(mesh).section(plane_origin=[0, 0, z], plane_normal=[0, 0, 1])
    if sec is None:
        raise ValueError(f"the plane z = {z} misses the mesh")
    rings = sorted((Polygon(np.asarray(d)[:, :2]) for d in sec.discrete if len(d) >= 3), key=lambda p: -p.area)
    outer = rings[0]
    holes = [r.exterior.coords for r in rings[1:] if outer.contains(r.representative_point())]
    return Polygon(outer.exterior.coords, holes)


@dataclass(frozen=True)
class GearMeasurement:
    """What a gear's section measures: tip diameter, mean tooth thickness at the reference pitch
    circle (arc), teeth counted there, worst normal deviation of the flanks from the involute of
    the measured thickness (mm), and the centre found."""

    tip_diameter: float
    tooth_thickness: float
    teeth_found: int
    flank_deviation: float
    centre: tuple[float, float]


def measure_spur_gear(outline: Polygon, teeth: int, module: float, pressure_angle: float,
                      centre: tuple[float, float] | None = None, samples: int = 1 << 19) -> GearMeasurement:
    """Measure a gear section. ``outline`` is the section polygon (holes ignored); the centre is
    the exterior's centroid unless given. Flanks are compared with the analytic involute in the
    band from 0.25 m inside the pitch circle (or the base circle) to 0.15 m under the tip."""
    P = np.asarray(outline.exterior.coords)[:-1]
    c = np.asarray(centre if centre is not None else Polygon(P).centroid.coords[0])
    P = P - c
    r = np.hypot(P[:, 0], P[:, 1])
    rp = module * teeth / 2
    rb = rp * np.cos(pressure_angle)
    th = np.linspace(-np.pi, np.pi, samples, endpoint=False)
    inside = shapely.contains_xy(Polygon(P), rp * np.cos(th), rp * np.sin(th))
    k0 = int(np.argmin(inside))
    inside = np.roll(inside, -k0)
    d = np.diff(np.concatenate([inside, inside[:1]]).astype(np.int8))
    st, en = np.where(d == 1)[0] + 1, np.where(d == -1)[0] + 1
    if len(en) and len(st) and en[0] < st[0]:
        en = en[1:]
    n = min(len(st), len(en))
    step = 2 * np.pi / samples
    s = float(((en[:n] - st[:n]) * step * rp).mean()) if n else 0.0
    centres = th[k0] + (st[:n] + en[:n] - 1) / 2 * step
    # flank deviation: densify the polygon, fold every point into its tooth's frame
    Q = np.vstack([P, P[:1]])
    seg = np.diff(Q, axis=0)
    L = np.hypot(seg[:, 0], seg[:, 1])
    kk = np.maximum(1, np.ceil(L / 0.005).astype(int))
    idx = np.repeat(np.arange(len(seg)), kk)
    t = np.concatenate([np.arange(q) / q for q in kk])
    D = Q[idx] + seg[idx] * t[:, None]
    rr = np.hypot(D[:, 0], D[:, 1])
    ang = np.arctan2(D[:, 1], D[:, 0])
    pitch = 2 * np.pi / teeth
    c0 = centres[0] if n else 0.0
    phi = np.mod(ang - c0 + pitch / 2, pitch) - pitch / 2
    sel = (rr >= max(rp - 0.25 * module, rb * 1.0005)) & (rr <= r.max() - 0.15 * module)
    dev = 0.0
    if sel.sum() > 10 and n:
        ar = np.arccos(np.clip(rb / rr[sel], -1, 1))
        psi = s / (2 * rp) + involute.inv(pressure_angle) - involute.inv(ar)
        dn = (np.abs(phi[sel]) - psi) * rb
        dev = float(np.abs(dn - dn.mean()).max())
    return GearMeasurement(float(2 * r.max()), s, int(n), dev, (float(c[0]), float(c[1])))


@dataclass(frozen=True)
class BevelFlanks:
    """What a straight bevel gear's mesh measures against the analytic spherical involute tooth: the
    flank points sampled (every triangle's vertices, edge midpoints and inner points in the band
    measured), their normal deviations from the analytic flank (mm, + outside it: a thicker tooth),
    the teeth seen and the spheres' radii (from the apex) the points span."""

    deviation: np.ndarray
    teeth_seen: int
    radii: tuple[float, float]

    @property
    def worst(self) -> float:
        return float(np.abs(self.deviation).max())


def _spherical_involute_azimuth(p: np.ndarray, base: float) -> np.ndarray:
    """Azimuth of the spherical involute of the base cone ``base`` at polar angles ``p``, from the
    construction itself: the great circle touching the base circle at azimuth φ, rolled back by the
    arc it unwound, θ = φ sin δ_b, carries the point cos θ T − sin θ e (T the touching point, e the
    base circle's tangent there); cos p = cos θ cos δ_b gives θ, and the azimuth is the point's."""
    th = np.arccos(np.clip(np.cos(p) / np.cos(base), -1.0, 1.0))
    ph = th / np.sin(base)
    T = np.stack([np.sin(base) * np.cos(ph), np.sin(base) * np.sin(ph)])
    e = np.stack([-np.sin(ph), np.cos(ph)])
    P = np.cos(th) * T - np.sin(th) * e
    return np.arctan2(P[1], P[0])


def measure_bevel_flanks(mesh, teeth: int, module: float, pressure_angle: float,
                         pitch_angle: float, thinning: float, face_width: float, addendum: float,
                         dedendum: float, band_mm: float = 0.15, order: int = 4) -> BevelFlanks:
    """Measure a straight bevel gear's flanks on its mesh (in the gear's frame: the apex at the origin,
    the body at z < 0) against the exact spherical involute tooth, written here from its definition:
    the base cone sin δ_b = sin δ cos α, the flank at polar angle p (from the body axis) at azimuth
    ψ = s / (2 r) + ev(δ) − ev(p) from its tooth's centre, s = π m / 2 − thinning the heel pitch arc,
    r = m z / 2, R = r / sin δ. Every triangle is sampled on a barycentric grid of ``order`` (its
    vertices, edge points and inner points: the facets between the exact rays are measured, not
    only their corners); the points kept lie on the involute part of a flank (polar angle
    ``band_mm`` at the heel inside the base or root cone and the tip cone) and ``band_mm`` inside the
    heel and toe back cones. A point's deviation is its azimuth's from the flank, along the flank's
    normal on its sphere: ρ sin δ_b Δψ (the spur measure's r_b Δψ)."""
    V, F = np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces)
    w = np.array([(i, j, order - i - j) for i in range(order + 1) for j in range(order + 1 - i)], dtype=float) / order
    pts = np.einsum("kc,fcd->fkd", w, V[F]).reshape(-1, 3)
    rho = np.linalg.norm(pts, axis=1)
    p = np.arccos(np.clip(-pts[:, 2] / rho, -1.0, 1.0))
    az = np.arctan2(pts[:, 1], pts[:, 0])
    r = module * teeth / 2
    R = r / np.sin(pitch_angle)
    base = float(np.arcsin(np.sin(pitch_angle) * np.cos(pressure_angle)))
    tip, root = pitch_angle + np.arctan(addendum / R), pitch_angle - np.arctan(dedendum / R)
    band = band_mm / R
    back = np.cos(p - pitch_angle)
    sel = (p > max(base, root) + band) & (p < tip - band) & (rho < R / back - band_mm) \
        & (rho > (R - face_width) / back + band_mm)
    pitch = 2 * np.pi / teeth
    folded = np.abs((az[sel] + pitch / 2) % pitch - pitch / 2)
    ev = lambda q: _spherical_involute_azimuth(np.asarray(q, dtype=float), base)  # noqa: E731
    psi = (np.pi * module / 2 - thinning) / (2 * r) + ev(pitch_angle) - ev(p[sel])
    dev = rho[sel] * np.sin(base) * (folded - psi)
    seen = len(np.unique(np.round(az[sel] / pitch).astype(int) % teeth))
    return BevelFlanks(dev, seen, (float(rho[sel].min()), float(rho[sel].max())) if sel.any() else (0.0, 0.0))


def measure_worm_flanks(mesh, thread, twist_per_mm: float, heights) -> np.ndarray:
    """Measure a ZI worm's flanks on its mesh (in the worm's frame, its axis along z): its section at
    each of ``heights`` (mm), 20 points along each edge, against the involute of its base circle turned
    by ``twist_per_mm`` · z (rad/mm; tan β / r). ``thread``: its ``design.crossed_helical.ThreadSpec``
    (``root_radius``, ``tip_radius``, ``base_radius`` mm, ``flank_angle(r)`` rad). Points within 0.3 mm
    of the root and tip circles are left out. Returns each point's deviation (mm) along the flank's
    normal (tangent to the base circle): r_b (|φ| − ψ(r)), φ its polar angle from the thread's centre
    line; positive where the thread is thicker."""
    devs = []
    for z in heights:
        P = np.asarray(section_outline(mesh, z).exterior.coords)
        seg = np.diff(P, axis=0)
        dense = np.concatenate([P[:-1] + seg * s for s in np.linspace(0, 1, 20, endpoint=False)])
        r = np.hypot(*dense.T)
        band = (r > thread.root_radius + 0.3) & (r < thread.tip_radius - 0.3)
        a = np.arctan2(dense[band, 1], dense[band, 0]) - twist_per_mm * z
        phi = np.mod(a + np.pi, 2 * np.pi) - np.pi
        devs.append((np.abs(phi) - thread.flank_angle(r[band])) * thread.base_radius)
    return np.concatenate(devs)


def mesh_problems(mesh, envelope=(406.0, 355.0, 406.0)) -> list[str]:
    """What stops a mesh (as ``as_trimesh`` takes) from printing as a solid: not one closed, oriented
    manifold shell once written as an STL and read back as a slicer does (export.verify), not
    watertight, inconsistent winding, non-positive volume, below the build plate, larger than the
    envelope in any axis order."""
    from .export.verify import mesh_report, read_stl

    mesh = as_trimesh(mesh)
    out = list(mesh_report(*read_stl(trimesh.exchange.stl.export_stl(mesh))).problems())
    if not mesh.is_watertight:
        out.append("not watertight")
    if not mesh.is_winding_consistent:
        out.append("inconsistent winding")
    if not mesh.volume > 0:
        out.append(f"volume {mesh.volume:.3f} mm3")
    if mesh.bounds[0][2] < -1e-6:
        out.append(f"below the build plate (z min {mesh.bounds[0][2]:.3f})")
    if np.any(np.sort(mesh.extents) > np.sort(envelope) + 1e-6):
        out.append(f"extents {np.round(mesh.extents, 1)} exceed the envelope {envelope}")
    return out
