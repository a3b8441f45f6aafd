"""Pictures of a kit drawn from its real meshes (matplotlib, no display needed)."""

from __future__ import annotations

from dataclasses import replace

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import trimesh  # noqa: E402
from matplotlib.patches import Polygon as MplPolygon  # noqa: E402

from .kit import Kit, build_kit  # noqa: E402
from ...design.synthesis import Chain  # noqa: E402
from ...geometry.solid import mesh_arrays  # noqa: E402

__all__ = ["stack_section", "ROLE_COLOURS"]

ROLE_COLOURS = {"gear": "#4c78a8", "link": "#f58518", "base": "#8c8c8c", "leg": "#b0b0b0", "axle": "#54a24b",
                "crank": "#e45756", "pen_holder": "#b279a2"}


def _posed(kit: Kit, theta: float, keep=lambda lo, hi: True):
    """(part, its mesh placed at θ) for every part whose placed bounding box passes ``keep(lo, hi)``."""
    poses = kit.poses(theta)
    for p in kit.parts:
        box = np.asarray(p.solid.bounding_box()).reshape(2, 3)
        corners = np.array([[x, y, z, 1.0] for x in box[:, 0] for y in box[:, 1] for z in box[:, 2]]) @ poses[p.name].T
        if not keep(corners[:, :3].min(axis=0), corners[:, :3].max(axis=0)):
            continue
        v, f = mesh_arrays(p.solid)
        m = trimesh.Trimesh(v, f, process=False)
        m.apply_transform(poses[p.name])
        yield p, m


def _straight(kit: Kit) -> Kit:
    """The same design rebuilt with every link's initial angle 0 and the drive gear at 180°, so at
    θ = 0 every joint and the drive axle lie on the x axis (the plane y = 0 cuts them all)."""
    mech = kit.mechanism
    links = tuple(replace(l, phase=0.0) for l in mech.chain.links)
    a = float(np.hypot(*mech.drive_centre))
    mech = replace(mech, chain=Chain(links, mech.chain.offset), drive_centre=(-a, 0.0))
    return build_kit(mech, replace(kit.params, drive_angle=float(np.pi)))


def stack_section(kit: Kit, path, title: str | None = None) -> None:
    """Section (plane y = 0) of the straightened assembly: the ground pivot with the drive, and
    the first joint, at true scale."""
    straight = _straight(kit)
    mech, st = kit.mechanism, kit.stack
    s1 = mech.chain.links[0].length
    a = float(np.hypot(*mech.drive_centre))
    windows = [(-a - 40.0, 45.0, "ground pivot, drive gear and crank"), (s1 - 45.0, s1 + 45.0, "joint 1 (end of B1)")]
    zlo, zhi = -kit.params.base_thickness - kit.params.leg_height - 2, st.layer(3) + 2
    widths = [w[1] - w[0] for w in windows]
    fig, axes = plt.subplots(1, 2, figsize=(14, 6.2), gridspec_kw={"width_ratios": widths})
    sections = []
    cut = lambda lo, hi: lo[1] <= 0.0 <= hi[1] and any(lo[0] <= x1 and hi[0] >= x0 for x0, x1, _ in windows)  # noqa: E731
    for part, mesh in _posed(straight, 0.0, cut):
        sec = mesh.section(plane_origin=[0, 0, 0], plane_normal=[0, 1, 0])
        if sec is not None:
            sections += [(part, np.asarray(r)[:, [0, 2]]) for r in sec.discrete]
    for ax, (x0, x1, name) in zip(axes, windows):
        seen = set()
        for part, xz in sections:
            if xz[:, 0].max() < x0 or xz[:, 0].min() > x1:
                continue
            label = part.role if part.role not in seen else None
            seen.add(part.role)
            ax.add_patch(MplPolygon(xz, closed=True, facecolor=ROLE_COLOURS.get(part.role, "#999"), edgecolor="k",
                                    linewidth=0.5, label=label))
        for j in (1, 2, 3):
            ax.axhspan(st.plate_z(j), st.plate_z(j) + st.plate, color="#f58518", alpha=0.06, lw=0)
            ax.text(x1 - 1, st.plate_z(j) + st.plate / 2, f"plate {j}", ha="right", va="center", fontsize=7)
        for j in (0, 1, 2):
            ax.text(x1 - 1, st.layer(j) + st.face / 2, f"gear layer {j}", ha="right", va="center", fontsize=7,
                    color="#4c78a8")
        ax.set_xlim(x0, x1)
        ax.set_ylim(zlo, zhi)
        ax.set_aspect("equal")
        ax.set_title(name, fontsize=10)
        ax.set_xlabel("x along the straightened chain (mm)")
        ax.legend(loc="lower right", fontsize=7)
    axes[0].set_ylabel("z (mm)")
    fig.suptitle(title or f"{kit.params.name}: true section through the joints (links straightened, crank angle 0)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
