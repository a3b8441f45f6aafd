"""kind: gear_train against the issue's targets, measured in one run (in-process, best of --runs):

1. the planetary set (3 planets, ring, carrier, frame: configs/gear_train_planetary.yaml) builds in at
   most the default butterfly chain's build (configs/butterfly.yaml, 32 gears), and its `check` over
   a turn of the carrier takes at most 2.5× that build;
2. flank accuracy on the STL (float32, as written): spur (the reducer's gears) and each transverse
   section of a helical gear at three heights (against the involute turned by the helix) within
   1 µm at a chord tolerance of 0.001 mm.

    .venv/bin/python benchmarks/bench_gear_train.py [--runs 3]

It reports figures; it never fails on a time.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np
import trimesh

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from partgen import pipeline  # noqa: E402
from partgen.design.gear_train import transverse_system, twist_over  # noqa: E402
from partgen.design.gearing import GearSpec, ToothSystem  # noqa: E402
from partgen.geometry.gear import gear_body, helical_body  # noqa: E402
from partgen.geometry.outline import circle  # noqa: E402
from partgen.geometry.solid import mesh_arrays  # noqa: E402
from partgen.testing import measure_spur_gear, section_outline  # noqa: E402


def best(f, runs: int) -> float:
    out = math.inf
    for _ in range(runs):
        t = time.perf_counter()
        f()
        out = min(out, time.perf_counter() - t)
    return out


def stl_mesh(solid) -> trimesh.Trimesh:
    v, f = mesh_arrays(solid)
    return trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}, best of {args.runs}")
    chain = pipeline.load(ROOT / "configs" / "butterfly.yaml")
    planet = pipeline.load(ROOT / "configs" / "gear_train_planetary.yaml")
    t_chain = best(lambda: chain.mechanism.build(chain.spec), args.runs)
    t_pl = best(lambda: planet.mechanism.build(planet.spec), args.runs)
    kit = planet.mechanism.build(planet.spec)
    t_check = best(lambda: planet.mechanism.check(planet.spec, kit, None), max(1, args.runs - 1))
    print(f"butterfly chain build {t_chain:.2f} s; planetary build {t_pl:.2f} s ({t_pl / t_chain:.2f}× the chain's, "
          f"target ≤ 1); planetary check over a carrier turn ({planet.spec.checks.samples} angles) {t_check:.2f} s "
          f"({t_check / t_chain:.2f}× the chain's build, {t_check / t_pl:.2f}× its own; target ≤ 2.5)")
    a20 = math.radians(20)
    for z in (13, 40):
        spec = GearSpec(z, ToothSystem(2.0, a20, backlash_per_gear=0.1, profile_shift=None, chord_tolerance=0.001), 0.0)
        m = measure_spur_gear(section_outline(stl_mesh(gear_body(spec, 8, circle(4.0, 0.01, hole=True))), 4.0), z, 2.0,
                              a20, centre=(0.0, 0.0))
        print(f"spur {z} teeth: flank {1000 * m.flank_deviation:.3f} µm from the involute")
    t = transverse_system(2.0, a20, math.radians(30), "normal")
    spec = GearSpec(19, ToothSystem(t.module, t.pressure_angle, t.addendum_coeff, t.dedendum_coeff, t.cutter_tip_coeff,
                                    0.05, None, 0.001), 0.0)
    for hb in (False, True):
        solid = helical_body(spec, 10, circle(4.0, 0.01, hole=True), 0.0, twist_over(10, math.radians(30),
                                                                                     spec.pitch_radius), hb, 0.001)
        mesh = stl_mesh(solid)
        dev = [measure_spur_gear(section_outline(mesh, z), 19, t.module, t.pressure_angle, centre=(0.0, 0.0)).flank_deviation
               for z in (0.5, 3.7, 8.9)]
        print(f"{'herringbone' if hb else 'helical'} 19 teeth, 30° (normal module 2): flank at z = 0.5, 3.7, 8.9 mm: "
              + ", ".join(f"{1000 * d:.3f}" for d in dev) + " µm")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
