#!/usr/bin/env python
"""Benchmark the exact Monte Carlo (`partgen tolerance --exact N`) on configs/gear_pair.yaml at ±0.3 mm.

    .venv/bin/python benchmarks/bench_exact.py            # N = 200 on 1 and on 2 workers
    .venv/bin/python benchmarks/bench_exact.py --prints 50

What it measures (time.perf_counter; nothing asserts on time):

1. One exact print (gear_pair.exact.exact_print in this process, the median of 20) against one
   `check` of the kit (the config's 180 angles, in-process after the kit is built): the ratio.
2. N exact prints on a LocalCluster (processes, one thread each) of 1 and of 2 workers: the
   phase from submitting the tasks to the last result (studies.exact_study), and the speed-up of 2
   workers over 1 (target ≥ 1.8×; the prints are independent and each ~0.05-0.1 s, so the
   scheduler's ~3 ms a task is a few per cent; each cluster first runs a few prints, untimed, so
   the workers' imports are not timed). The two runs' results are compared (identical:
   print i's deviations depend on the seed and i only).
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "configs" / "gear_pair.yaml"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--prints", type=int, default=200)
    ap.add_argument("--accuracy-mm", type=float, default=0.3)
    args = ap.parse_args()

    from partgen import cluster, pipeline, studies
    from partgen.mechanisms.gear_pair.exact import exact_print, exact_shared

    loaded = pipeline.load(CONFIG)
    kit = pipeline.make_kit(loaded)
    t0 = time.perf_counter()
    result = loaded.mechanism.check(loaded.spec, kit, None, None)
    check_s = time.perf_counter() - t0
    model = loaded.mechanism.tolerance_model(loaded.spec, kit, result, args.accuracy_mm)
    shared = exact_shared(kit, result, model)
    one = []
    for i in range(20):
        t = time.perf_counter()
        exact_print(shared, 0, i)
        one.append(time.perf_counter() - t)
    print_s = statistics.median(one)
    print(f"one check of the kit ({loaded.spec.samples} angles): {check_s:.3f} s")
    print(f"one exact print (median of 20, {shared['angles']} positions over a pitch): {print_s:.4f} s "
          f"= {print_s / check_s:.3f} of a check")

    got = {}
    for workers in (1, 2):
        with cluster.cluster(workers, processes=True) as client:
            studies.exact_study(client, loaded, kit, result, model, 4 * workers, 1)  # warm: imports, the shared data
            t = time.perf_counter()
            r = studies.exact_study(client, loaded, kit, result, model, args.prints, 0)
            got[workers] = (time.perf_counter() - t, r)
        print(f"{args.prints} exact prints on {workers} worker(s): {got[workers][0]:.2f} s, {r['seconds_per_print']:.4f} s a print inside its task "
              f"(P(jam) {100 * r['probability']:.2f} %, 95 % CI {100 * r['ci95'][0]:.2f}–{100 * r['ci95'][1]:.2f} %)")
    print(f"speed-up of 2 workers over 1: {got[1][0] / got[2][0]:.2f}x (target >= 1.8x)")
    same = {k: v for k, v in got[1][1].items() if k not in ("seconds", "workers", "seconds_per_print")} == \
        {k: v for k, v in got[2][1].items() if k not in ("seconds", "workers", "seconds_per_print")}
    print(f"1 and 2 workers give the same result: {same}")


if __name__ == "__main__":
    main()
