"""Mass of a part as an FDM printer makes it, not of a solid: walls and top/bottom skins solid,
the interior filled to the infill fraction.

The interior is the solid eroded by a vertical cylinder: its radius is the wall thickness
(perimeters run around every outline, holes included), its half height the skin thickness (top and
bottom layers). It is computed as a slicer does: the part is cut into layers, each layer's outline
is offset inward by the wall (manifold3d's CrossSection offset), and a layer's interior is what
stays inside the inward offsets of every layer within a skin's height above and below it. This is
the erosion by the cylinder sampled at the layer height (it agrees with manifold3d's Minkowski
difference to 0.1 % on bars and bosses, at a hundredth of the time). At 100 % infill the mass is
the solid's.
"""

from __future__ import annotations

from dataclasses import dataclass

import manifold3d as m3d
import numpy as np

from .solid import mesh_arrays

__all__ = ["PrintSettings", "MassModel", "volume_centroid", "printed_mass"]


@dataclass(frozen=True)
class PrintSettings:
    """wall, skin, layer: mm; infill: fraction 0..1 of the interior that is plastic."""

    wall: float = 1.2
    skin: float = 1.0
    infill: float = 0.2
    segments: int = 48
    layer: float = 0.25


@dataclass(frozen=True)
class MassModel:
    """Volumes mm³, mass g, centres of mass (3,) mm in the part's frame."""

    solid_volume: float
    shell_volume: float
    interior_volume: float
    mass: float
    centre: tuple[float, float, float]
    solid_mass: float
    solid_centre: tuple[float, float, float]
    interior_centre: tuple[float, float, float]

    def mass_if_infill(self, infill: float, density: float) -> float:
        """The mass the same part would have at another infill fraction, g."""
        return density * (self.shell_volume + infill * self.interior_volume)


def volume_centroid(solid: m3d.Manifold) -> tuple[float, np.ndarray]:
    """Volume (mm³) and centroid (3,) of a closed solid by the divergence theorem (signed tetrahedra)."""
    v, f = mesh_arrays(solid)
    if len(f) == 0:
        return 0.0, np.zeros(3)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    vol6 = np.einsum("ij,ij->i", a, np.cross(b, c))  # 6 × signed volume of (0, a, b, c)
    volume = vol6.sum() / 6
    centroid = (vol6[:, None] * (a + b + c)).sum(axis=0) / (24 * volume)
    return float(volume), centroid


def _area_centroid(cs: m3d.CrossSection) -> tuple[float, np.ndarray]:
    """Area (mm²) and first moment (2,) of a cross-section (contours signed by orientation)."""
    polys = [np.asarray(poly, float) for poly in cs.to_polygons()]
    if not polys:
        return 0.0, np.zeros(2)
    p = np.concatenate(polys)
    q = np.concatenate([np.roll(x, -1, axis=0) for x in polys])
    cross = p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]
    return float(cross.sum() / 2), (p + q).T @ cross / 6


def _window_intersections(sections: list, k: int) -> list:
    """[∩ sections[i − k … i + k] for i in k … n − k − 1]: every window of 2k + 1 consecutive
    sections intersected, with three intersections per window (van Herk / Gil–Werman: within blocks
    of 2k + 1, running intersections from the block's start and from its end; a window is the
    suffix of one block met with the prefix of the next)."""
    n, w = len(sections), 2 * k + 1
    if k == 0:
        return list(sections)
    prefix, suffix = list(sections), list(sections)
    for start in range(0, n, w):
        end = min(start + w, n)
        for i in range(start + 1, end):
            prefix[i] = prefix[i - 1] ^ sections[i]
        for i in range(end - 2, start - 1, -1):
            suffix[i] = suffix[i + 1] ^ sections[i]
    out = []
    for i in range(k, n - k):
        lo, hi = i - k, i + k
        out.append(suffix[lo] if lo % w == 0 else suffix[lo] ^ prefix[hi])
    return out


COLLINEAR_MM = 1e-6  # a slice's vertex this close to the line through its neighbours adds nothing (area error ~1e-11)


def interior(solid: m3d.Manifold, settings: PrintSettings) -> tuple[float, np.ndarray]:
    """Volume (mm³) and centroid (3,) of the infilled interior, layer by layer (see the module)."""
    lo, hi = np.asarray(solid.bounding_box(), float).reshape(2, 3)[:, 2]
    h = settings.layer
    n = int(np.ceil((hi - lo) / h))
    zs = lo + h * (np.arange(n) + 0.5)
    # a slice keeps a vertex wherever a triangle edge crosses it, most of them in line with their
    # neighbours (a Bennett link's layers: 374 vertices, 93 not in line); the offset and the window
    # intersections cost by the vertex, so those in line (within COLLINEAR_MM) go first
    inner = [solid.slice(float(z)).simplify(COLLINEAR_MM).offset(-settings.wall, m3d.JoinType.Round, 2.0, settings.segments)
             for z in zs]
    k = int(round(settings.skin / h))
    vol, mom = 0.0, np.zeros(3)
    for i, core in zip(range(k, n - k), _window_intersections(inner, k)):
        a, m = _area_centroid(core)
        vol += h * a
        mom += h * np.array([m[0], m[1], a * zs[i]])
    return vol, (mom / vol if vol > 0 else np.zeros(3))


def printed_mass(solid: m3d.Manifold, density: float, settings: PrintSettings) -> MassModel:
    """The part's mass and centre of mass as printed (z up, as it lies on the plate). density: g/mm³."""
    if not 0 <= settings.infill <= 1:
        raise ValueError(f"infill must be a fraction in [0, 1], got {settings.infill}")
    vs, cs = volume_centroid(solid)
    vi, ci = interior(solid, settings)
    shell = vs - vi
    cshell = (vs * cs - vi * ci) / shell if shell > 0 else cs
    mass = density * (shell + settings.infill * vi)
    centre = (density * shell * cshell + density * settings.infill * vi * ci) / mass
    return MassModel(vs, shell, vi, mass, tuple(float(x) for x in centre), density * vs, tuple(float(x) for x in cs),
                     tuple(float(x) for x in ci))
