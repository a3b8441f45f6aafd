#!/usr/bin/env python
"""Benchmark `partgen tolerance` on the default chain (configs/butterfly.yaml, Fortus ±0.127 mm).

    .venv/bin/python benchmarks/bench_tolerance.py            # full run (~1 min)
    .venv/bin/python benchmarks/bench_tolerance.py --quick    # fewer repetitions

What it measures, in one run (time.perf_counter; nothing asserts on time):

1. One full check (check_kit, the config's 360 crank angles, in-process after the kit is built)
   against one sample: run_chunk on 10,000 samples in this process (median of 5), per sample.
   Target: a sample costs at most 1/20 of a check.
2. 10,000 samples on a LocalCluster (processes, one thread each) of 1 and of 2 workers: the
   sampling phase (tasks submitted → last result in; the model is sent once), the cluster's start
   and the nominal check, each timed; the speed-up of 2 workers over 1 on the sampling phase.
   Target: ≥ 1.7×. Also the same at 300,000 samples (where the tasks' work, not their dispatch,
   dominates), and the results of 1 and 2 workers compared (identical).
   At 10,000 samples, the sampling phase is split (Dask's task stream) into the tasks' compute and
   the rest (the model's broadcast, dispatch, results, the client): with that fixed part F and the
   1-worker compute W, no second worker can do better than (F + W) / (F + W/2).
3. The scheduler's cost per task: 2,000 empty tasks through the same path (submit, as_completed,
   result), per task; and the per-task compute at the default chunk (studies.CHUNK samples). These
   are the figures the 100-worker plan in benchmarks/README.md uses.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "configs" / "butterfly.yaml"


def _noop(shared, i):
    return i


def timed(fn, *a, **k):
    t = time.perf_counter()
    out = fn(*a, **k)
    return out, time.perf_counter() - t


def sampling(client, model, samples, seed=0):
    from partgen import studies
    from partgen.design.tolerance import summarise

    (total, info), s = timed(studies.sample, client, model, samples, seed)
    return summarise(model, total), s


def split(client, model, samples, seed):
    """(wall s, sum of the tasks' compute s) of one sampling run, from Dask's task stream."""
    from distributed import get_task_stream

    with get_task_stream(client) as ts:
        _, wall = sampling(client, model, samples, seed)
    compute = sum(s["stop"] - s["start"] for t in ts.data for s in t["startstops"] if s["action"] == "compute")
    return wall, compute


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    from partgen import cluster, pipeline
    from partgen.design.tolerance import run_chunk

    reps = 3 if args.quick else 5
    print(f"machine: {os.cpu_count()} cores, load {os.getloadavg()[0]:.2f} (1 min) at start")
    loaded = pipeline.load(CONFIG)
    kit, t_build = timed(pipeline.make_kit, loaded)
    result, t_check = timed(loaded.mechanism.check, loaded.spec, kit, None, None)
    model = loaded.mechanism.tolerance_model(loaded.spec, kit, result, kit.printer.xy_accuracy)
    print(f"default chain: build {t_build:.2f} s, check ({result.figures['samples']} angles) {t_check:.2f} s; "
          f"model: {len(model.features)} features, {len(model.margins)} margins")

    # 1. a sample against a check
    run_chunk(model, 0, 0, 1000)  # warm-up
    per = statistics.median(timed(run_chunk, model, 0, i, 10_000)[1] for i in range(reps)) / 10_000
    print(f"\n1. one sample {per * 1e6:.1f} µs (median of {reps} × 10,000 in one process); one check {t_check:.2f} s: "
          f"a sample costs 1/{t_check / per:,.0f} of a check (target ≤ 1/20: {'met' if t_check / per >= 20 else 'NOT met'})")

    # 2. 1 vs 2 workers
    print("\n2. LocalCluster, processes, 1 thread per worker")
    results = {}
    for samples in (10_000, 300_000):
        row = {}
        for workers in (1, 2):
            ctx = cluster.cluster(workers, None, True)
            cm, t_start = timed(ctx.__enter__)
            try:
                sampling(cm, model, 2000)  # warm the workers (imports, the model's first send)
                best = min((sampling(cm, model, samples, seed=1) for _ in range(reps if samples <= 10_000 else 3)),
                           key=lambda x: x[1])
                if samples <= 10_000:
                    parts = sorted(split(cm, model, samples, 1) for _ in range(reps))[reps // 2]  # the median run
                    print(f"   {samples:>9,} samples, {workers} worker(s), median of {reps}: {parts[0] * 1e3:.0f} ms, "
                          f"of which the tasks computed {parts[1] * 1e3:.0f} ms (summed over workers)")
                    if workers == 1:
                        fixed, work = parts[0] - parts[1], parts[1]
            finally:
                ctx.__exit__(None, None, None)
            row[workers] = best
            results[(samples, workers)] = best[0]
            print(f"   {samples:>9,} samples, {workers} worker(s): sampling {best[1]:.3f} s "
                  f"(cluster start {t_start:.2f} s, nominal check {t_check:.2f} s: wall ≈ "
                  f"{t_start + t_check + best[1]:.2f} s), P(jam) {100 * best[0]['overall']['probability']:.2f} %")
        sp = row[1][1] / row[2][1]
        print(f"   speed-up of 2 workers over 1 on the sampling: {sp:.2f}× (target ≥ 1.7×: {'met' if sp >= 1.7 else 'NOT met'})")
        if samples <= 10_000:
            print(f"   fixed part {fixed * 1e3:.0f} ms + compute {work * 1e3:.0f} ms on 1 worker: 2 workers that halve the "
                  f"compute and add nothing could reach at most {(fixed + work) / (fixed + work / 2):.2f}×")
        print(f"   1 and 2 workers give identical results: {results[(samples, 1)] == results[(samples, 2)]}")

    # 3. scheduler overhead per task, compute per task
    with cluster.cluster(2, None, True) as client:
        from partgen.cluster import run as crun

        crun(client, _noop, None, [(i, (i,)) for i in range(200)], lambda k, v: None, None, "warm")
        _, t = timed(crun, client, _noop, None, [(i, (i,)) for i in range(2000)], lambda k, v: None, None, "noop")
    from partgen.studies import CHUNK

    per_task = statistics.median(timed(run_chunk, model, 0, i, CHUNK)[1] for i in range(reps * 4))
    print(f"\n3. scheduler: {t / 2000 * 1e3:.2f} ms per empty task (2,000 tasks on 2 workers, {2000 / t:,.0f} tasks/s); "
          f"compute: {per_task * 1e3:.1f} ms per task of {CHUNK:,} samples (the default chunk)")
    print(f"machine load {os.getloadavg()[0]:.2f} (1 min) at the end")


if __name__ == "__main__":
    main()
