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

__all__ = ["GearMeasurement", "section_outline", "measure_spur_gear", "mesh_problems"]


def section_outline(mesh: trimesh.Trimesh, z: float) -> Polygon:
    """Largest polygon (with the rings inside it as holes) of the mesh's section by the plane at
    height z, in the mesh's own x, y, mm."""
    sec = mesh.section(plane_origin=[0, 0, z], plane_normal=[0, 0, 1])
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


def mesh_problems(mesh: trimesh.Trimesh, envelope=(406.0, 355.0, 406.0)) -> list[str]:
    """What stops a mesh from printing as a solid: not one closed, oriented manifold shell once
    written as an STL and read back as a slicer does (export.verify), not watertight, inconsistent
    winding, non-positive volume, below the build plate, larger than the envelope in any axis
    order."""
    from .export.verify import mesh_report, read_stl

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
