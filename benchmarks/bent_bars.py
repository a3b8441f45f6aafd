#!/usr/bin/env python
"""Random bent bars as a Bennett link draws them, each written as a float32 STL at a random print pose.

    .venv/bin/python benchmarks/bent_bars.py --trials 3000 --seed 7

A trial: a boss (radius 2.6 r, length 2.2 r, bore 1.3 r) and a bar of radius r (3-5 mm) leaving its
centre radially in its mid-plane, then 1-4 more runs of 3-60 mm, each turned about a random axis by
a bend drawn from four ranges (under 0.001 rad, under 0.1, under 0.7, under 2.2 rad: grazing, gentle,
sharp, folded). The link is built as the Bennett kit builds it (``geometry.bennett_link.link_solid``
at the first of ``LINK_PHASES`` whose float32 mesh stays sound), turned by a random rotation, written,
read back and counted: bad meshes (not one closed, oriented shell), phases needed beyond the first,
and vertices outside the capsule cover the checks use (``capsules``). ``--one-phase`` builds at the
first phase only, to show what the phases catch.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--trials", type=int, default=500)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--one-phase", action="store_true", help="build at the first tessellation phase only")
    args = ap.parse_args(argv)

    import trimesh
    from scipy.spatial.transform import Rotation

    from partgen.export.verify import mesh_report, read_stl
    from partgen.geometry import bennett_link as BL
    from partgen.geometry.capsules import segment_distance
    from partgen.geometry.solid import float32_sound, mesh_arrays

    rng = np.random.default_rng(args.seed)
    phases = BL.LINK_PHASES[:1] if args.one_phase else BL.LINK_PHASES
    bad = outside = rephased = 0
    t0 = time.perf_counter()
    for trial in range(args.trials):
        r = rng.uniform(3, 5)
        d = np.array([*rng.normal(size=2), 0.0])
        d /= np.linalg.norm(d)
        pts = [np.zeros(3), d * (3.6 * r + rng.uniform(0, 2))]
        for _ in range(int(rng.integers(1, 5))):
            bend = [rng.uniform(0, 1e-3), rng.uniform(0, 0.1), rng.uniform(0, 0.7), rng.uniform(0, 2.2)][rng.integers(4)]
            w = rng.normal(size=3)
            w -= (w @ d) * d
            w /= np.linalg.norm(w)
            d = np.cos(bend) * d + np.sin(bend) * w
            pts.append(pts[-1] + d * rng.uniform(3, 60))
        pts = np.array(pts) + rng.uniform(-150, 150, 3)
        bars = [BL.Bar(tuple(a), tuple(b), r) for a, b in zip(pts, pts[1:])]
        boss = BL.Boss(tuple(pts[0]), (0.0, 0.0, 1.0), 0.0, 2.6 * r, 2.2 * r, 1.3 * r)
        R = Rotation.random(random_state=int(rng.integers(1 << 31))).as_matrix()
        for n, phase in enumerate(phases):
            v, f = mesh_arrays(BL.link_solid([boss], bars, [], 48, phase))
            if float32_sound(v @ R.T, f):
                break
        rephased += n > 0
        stl = trimesh.exchange.stl.export_stl(trimesh.Trimesh(v @ R.T, f, process=False))
        rep = mesh_report(*read_stl(stl))
        if not rep.ok:
            bad += 1
            print(f"trial {trial}: {', '.join(rep.problems())}", file=sys.stderr)
        ends, radii, _ = BL.capsules([boss], bars)
        gap = segment_distance(ends[None, :, 0], ends[None, :, 1], v[:, None], v[:, None]) - radii[None]  # (V, K)
        outside += gap.min(axis=1).max() > 1e-6
    print(f"{args.trials} bent bars (seed {args.seed}, {'first phase only' if args.one_phase else 'phases as built'}): "
          f"bad meshes {bad}, built at a later phase {rephased}, outside their capsules {outside} "
          f"[{time.perf_counter() - t0:.0f} s]")
    return 0


if __name__ == "__main__":
    sys.exit(main())
