#!/usr/bin/env python
"""Benchmark the Bennett butterfly kit against the default butterfly chain, side by side in one run.

    .venv/bin/python benchmarks/bench_bennett.py            # ~4 min
    .venv/bin/python benchmarks/bench_bennett.py --repeat 2

Every command runs in a fresh process (``python -m``-free: the installed ``partgen`` script next to
this interpreter), as a user runs it, so imports count:

    chain    partgen build configs/butterfly.yaml               (the baseline)
    build    partgen build configs/bennett_butterfly.yaml       (layout search, parts, pockets, kit)
    report   partgen report configs/bennett_butterfly.yaml      (the same build in memory, the check, pictures)
    check    partgen check KITDIR                               (for the figures; not a ratio the issue sets)

The chain runs before and after each Bennett command and a ratio is that command's time over the
mean of the two chain runs around it (the machine is shared: the baseline is measured under the
same load). Wall time (time.perf_counter) and CPU time of the child (user + sys) are both printed.
It also prints what the layout search achieved (least clearance over the workspace, free range
around home) from the check of the kit it built. Nothing here asserts: it prints figures.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PARTGEN = str(Path(sys.executable).with_name("partgen"))


def run(args: list[str]) -> tuple[float, float, subprocess.CompletedProcess]:
    """(wall s, child CPU s, result) of one fresh ``partgen`` process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    res = subprocess.run([PARTGEN, *args], cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if res.returncode not in (0, 1):
        sys.exit(f"partgen {' '.join(args)} exited {res.returncode}:\n{res.stderr[-2000:]}")
    return wall, cpu, res


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=1, help="times to run each Bennett command")
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="bench_bennett."))
    chain_cmd = ["build", "configs/butterfly.yaml", "-o", str(tmp / "chain"), "-q"]
    cmds = {"build": ["build", "configs/bennett_butterfly.yaml", "-o", str(tmp / "kit"), "-q"],
            "report": ["report", "configs/bennett_butterfly.yaml", "-o", str(tmp / "report")]}
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs; each command in a fresh process")
    chain = [run(chain_cmd)[:2]]
    rows = {k: [] for k in cmds}
    for _ in range(args.repeat):
        for name, cmd in cmds.items():
            wall, cpu, _ = run(cmd)
            chain.append(run(chain_cmd)[:2])
            base_w = (chain[-2][0] + chain[-1][0]) / 2
            base_c = (chain[-2][1] + chain[-1][1]) / 2
            rows[name].append((wall, cpu, wall / base_w, cpu / base_c))
            print(f"  {name:<7} {wall:6.1f} s wall {cpu:6.1f} s CPU   chain around it {base_w:5.2f} s wall "
                  f"{base_c:5.2f} s CPU   ratio {wall / base_w:5.1f}x wall {cpu / base_c:5.1f}x CPU", flush=True)
    print(f"chain build (baseline): {statistics.median(w for w, _ in chain):.2f} s wall, "
          f"{statistics.median(c for _, c in chain):.2f} s CPU (median of {len(chain)})")
    limits = {"build": 10, "report": 12}
    for name, r in rows.items():
        print(f"{name:<7} median ratio {statistics.median(x[2] for x in r):5.1f}x wall, "
              f"{statistics.median(x[3] for x in r):5.1f}x CPU (issue: at most {limits[name]}x)")
    wall, cpu, res = run(["check", str(tmp / "kit"), "--json"])
    f = json.loads(res.stdout)["figures"]
    b = f["balance_mm"]
    print(f"check of the kit ({wall:.1f} s): {'OK' if json.loads(res.stdout)['ok'] else 'FAILED'}; least clearance "
          f"{f['least_clearance_mm']:.2f} mm ({' – '.join(f['least_clearance_parts'])}) over "
          f"{f['interference_samples']} samples; free from {f['free_range_deg'][0]:.1f}° to {f['free_range_deg'][1]:.1f}°; "
          f"centre of mass {b['fdm']:.4f} mm from S (binder left out {b['no_binder']:.3f} mm)")
    print(f"peak RSS of a child {resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024:.0f} MB; kits in {tmp}")


if __name__ == "__main__":
    main()
