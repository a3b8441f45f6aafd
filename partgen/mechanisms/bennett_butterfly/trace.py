"""The trace of the balanced Bennett butterfly: the common centre of mass over the workspace (its
worst distance from S over a turn of q1, per shape angle), the poses and com figures, the CSV and
the text `trace` prints."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...core.protocol import Trace
from . import kit as A
from .params import BennettParams
from .parts import home_inputs

__all__ = ["trace", "csv", "trace_text"]


def trace(kind: str, spec: BennettParams, kit: A.BennettKit, samples: int | None, out: Path | None,
          animate: bool = True) -> Trace:
    """The linkage over its workspace: the poses (planar and spatial) and the path of the common
    centre of mass (its worst distance from S over a turn of q1, per shape angle); poses.png, com.png."""
    p = kit.params
    n = samples or p.grid[1]
    nq = p.grid[0]
    ang = np.linspace(*p.workspace, n)
    q1 = np.linspace(0, 2 * np.pi, nq, endpoint=False)
    Q1, S = np.meshgrid(q1, ang, indexing="ij")
    a1, a4 = home_inputs(S.ravel(), Q1.ravel())
    fdm = A.com_deviation(kit, "fdm", a1, a4).reshape(nq, n).max(axis=0)
    solid = A.com_deviation(kit, "solid", a1, a4).reshape(nq, n).max(axis=0)
    stats = {"kind": kind, "samples": int(n), "q1_samples": int(nq),
             "workspace_deg": [math.degrees(x) for x in p.workspace],
             "com_from_S_max_mm": float(fdm.max()), "com_from_S_solid_max_mm": float(solid.max()),
             "worst_angle_deg": float(np.degrees(ang[int(np.argmax(fdm))])), "tolerance_mm": p.tolerance}
    files = []
    if out is not None:
        from .plots import com_figure, poses_figure

        lo, hi = (math.degrees(x) for x in p.workspace)
        (out / "poses.png").write_bytes(poses_figure(p.bb, [lo, math.degrees(p.home), hi]))
        (out / "com.png").write_bytes(com_figure(np.degrees(ang), {"fdm": fdm.tolist(), "solid": solid.tolist()},
                                                 p.tolerance, {"fdm": "as printed (FDM model)",
                                                               "solid": "printed solid (100 % infill)"}))
        files = ["poses.png", "com.png"]
    return Trace(stats, files, columns=("angle_rad", "com_from_S_mm", "com_from_S_solid_mm"),
                 data=np.column_stack([ang, fdm, solid]))


def csv(header: str, trace: Trace) -> str:
    return header + "".join(f"{a:.9f},{f:.6f},{s:.6f}\n" for a, f, s in trace.data)


def trace_text(spec, trace: Trace, folder) -> str:
    s = trace.stats
    lines = [f"{spec.name}: {s['samples']} shape angles from {s['workspace_deg'][0]:g}° to {s['workspace_deg'][1]:g}°, "
             f"each over {s['q1_samples']} turns of q1",
             f"  centre of mass from S: as printed ≤ {s['com_from_S_max_mm']:.4f} mm (worst at "
             f"{s['worst_angle_deg']:.1f}°, tolerance {s['tolerance_mm']:g} mm); printed solid ≤ "
             f"{s['com_from_S_solid_max_mm']:.4f} mm"]
    if folder:
        lines.append(f"plots: {folder}/{', '.join(trace.files)}")
    return "\n".join(lines)
