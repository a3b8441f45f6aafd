#!/usr/bin/env python
"""Benchmark the Bennett butterfly kit: the layout search, the parts' FDM mass model and the check,
each next to a baseline measured in the same run.

    .venv/bin/python benchmarks/bench_bennett.py          # ~3 min
    .venv/bin/python benchmarks/bench_bennett.py --quick  # one search round, ~1 min

What it measures (wall time with time.perf_counter, after imports; peak RSS of this process):

1. the layout search (``choose_offsets``) over the default config's coarse samples, with its
   caches (per-part capsules and per-pair clearances keyed by the parts' states) against the same
   search with the caches emptied before every trial (the baseline: every trial re-derives every
   part's capsules and every pair).
2. the FDM mass model of the twelve links: the interior layer by layer (slices offset inward by the
   wall, intersected over the skin's height) against manifold3d's Minkowski erosion of the whole
   link by the wall/skin cylinder (the baseline), with the masses they give side by side.
3. the whole `build_bennett` of the default config, and `check_bennett` on it (balance grid,
   workspace sweep, exact pin stacks at every sample).

Nothing here asserts on time: it prints figures.
"""

from __future__ import annotations

import argparse
import resource
import time

import numpy as np

from partgen.assembly import bennett as A
from partgen.checks.bennett import check_bennett
from partgen.config.bennett import resolve_bennett
from partgen.config.loader import load_design
import manifold3d as m3d

from partgen.geometry.bennett_link import link_solid
from partgen.geometry.mass import printed_mass, volume_centroid


def rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    rounds = 1 if args.quick else 6
    p = resolve_bennett(load_design("configs/bennett_butterfly.yaml"))
    bodies = A.bbf.body_joints(p.bb)
    # the samples the build's search uses: the check's step for the starting layout, every fourth
    reach = A.part_reach(p, A.default_layout(), bodies)
    angles, step = A.shape_samples(p, *p.workspace, A.point_speed(p, *p.workspace, reach))
    coarse = A.coarse_samples(angles)
    print(f"1. layout search: {len(coarse)} shape angles, {rounds} round(s) at most")
    t = time.perf_counter()
    lay, clear = A.choose_offsets(p, coarse, bodies, layers=p.layers, rounds=rounds)
    cached = time.perf_counter() - t
    real_init = A.Sweep.__init__

    def uncached_init(self, *a, **k):
        real_init(self, *a, **k)
        self.cache, self.pairs = _Forget(), _Forget()
    A.Sweep.__init__ = uncached_init
    t = time.perf_counter()
    lay0, clear0 = A.choose_offsets(p, coarse, bodies, layers=p.layers, rounds=min(rounds, 1))
    plain = time.perf_counter() - t
    A.Sweep.__init__ = real_init
    t = time.perf_counter()
    lay1, _ = A.choose_offsets(p, coarse, bodies, layers=p.layers, rounds=min(rounds, 1))
    cached1 = time.perf_counter() - t
    print(f"   with caches     {cached:7.2f} s for the whole search; least clearance {clear:.2f} mm")
    print(f"   one round:  with caches {cached1:6.2f} s   baseline (no caches) {plain:6.2f} s   "
          f"ratio {plain / cached1:5.1f}x   same layout: {lay1 == lay0}")

    print("2. FDM mass model of the 12 links (layers vs Minkowski erosion)")
    kit = A.build_bennett(p, lay=lay)
    tf = tm = 0.0
    rows = []
    for i in range(1, 13):
        bosses, bars, cups = A.link_features(p, i, lay, bodies[i], kit.delta)
        solid = link_solid(bosses, bars, cups, p.segments)
        st = A.print_settings(p)
        t = time.perf_counter()
        a = printed_mass(solid, p.density, st)
        tf += time.perf_counter() - t
        t = time.perf_counter()
        vi, ci = volume_centroid(solid.minkowski_difference(m3d.Manifold.cylinder(2 * st.skin, st.wall, -1.0, 48, True)))
        vs, cs = volume_centroid(solid)
        mb = p.density * (vs - (1 - st.infill) * vi)
        cb = (p.density * (vs * cs - vi * ci) + p.density * st.infill * vi * ci) / mb
        tm += time.perf_counter() - t
        rows.append((i, a.mass, mb, np.linalg.norm(np.subtract(a.centre, cb))))
    for i, ma, mb, dc in rows:
        print(f"   link{i:02d}  layers {ma:7.2f} g   erosion {mb:7.2f} g   ({100 * (ma / mb - 1):+5.2f} %)  "
              f"centres {dc:5.2f} mm apart")
    print(f"   layers {tf:6.2f} s   erosion (baseline) {tm:6.2f} s   ratio {tm / tf:5.1f}x")

    print("3. the whole build (search, refine with the pockets placed, parts) and its check")
    t = time.perf_counter()
    kit = A.build_bennett(p)
    print(f"   build {time.perf_counter() - t:6.2f} s")
    t = time.perf_counter()
    r = check_bennett(kit)
    print(f"   {time.perf_counter() - t:6.2f} s, ok = {r.ok}, {r.figures['interference_samples']} shape angles, "
          f"least clearance {r.figures['least_clearance_mm']:.2f} mm")
    print(f"peak RSS {rss_mb():.0f} MB")


class _Forget(dict):
    """A dict that never keeps anything (the baseline's caches)."""

    def __setitem__(self, key, value):
        pass


if __name__ == "__main__":
    main()
