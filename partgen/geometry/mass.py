"""Mass of a part as an FDM printer makes it, not of a solid: walls and top/bottom skins solid,
the interior filled to the infill fraction.

The interior is the solid eroded by a vertical cylinder (manifold3d's Minkowski difference): its
radius is the wall thickness (perimeters run around every outline, holes included), its half
height the skin thickness (top and bottom layers). At 100 % infill the mass is the solid's.
"""

from __future__ import annotations

from dataclasses import dataclass

import manifold3d as m3d
import numpy as np

from .solid import mesh_arrays

__all__ = ["PrintSettings", "MassModel", "volume_centroid", "printed_mass"]


@dataclass(frozen=True)
class PrintSettings:
    """wall, skin: mm; infill: fraction 0..1 of the interior that is plastic."""

    wall: float = 1.2
    skin: float = 1.0
    infill: float = 0.2
    segments: int = 48


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


def printed_mass(solid: m3d.Manifold, density: float, settings: PrintSettings,
                 interior: m3d.Manifold | None = None) -> MassModel:
    """The part's mass and centre of mass as printed. density: g/mm³. ``interior``: the infilled
    core if the caller can build it directly (faster than the Minkowski erosion for parts made of
    simple features); it must lie inside ``solid``."""
    if not 0 <= settings.infill <= 1:
        raise ValueError(f"infill must be a fraction in [0, 1], got {settings.infill}")
    vs, cs = volume_centroid(solid)
    if interior is None:
        core = m3d.Manifold.cylinder(2 * settings.skin, settings.wall, -1.0, settings.segments, True)
        interior = solid.minkowski_difference(core)
    vi, ci = volume_centroid(interior)
    shell = vs - vi
    cshell = (vs * cs - vi * ci) / shell if shell > 0 else cs
    mass = density * (shell + settings.infill * vi)
    centre = (density * shell * cshell + density * settings.infill * vi * ci) / mass
    return MassModel(vs, shell, vi, mass, tuple(float(x) for x in centre), density * vs, tuple(float(x) for x in cs),
                     tuple(float(x) for x in ci))
