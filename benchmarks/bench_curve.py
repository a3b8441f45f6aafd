#!/usr/bin/env python
"""Benchmark a drawn curve from a 10,000-point CSV to a written kit against the default butterfly's
build, side by side in one run.

    .venv/bin/python benchmarks/bench_curve.py              # 3 runs each
    .venv/bin/python benchmarks/bench_curve.py --runs 1 --points 20000

The CSV is the shipped star (configs/drawings/star.csv) walked again at 10,000 equal steps along its
outline, in millimetres, written with a design beside it (configs/star.yaml's settings) into a
temporary folder. Each build runs in a fresh process (`partgen build CONFIG -o KIT -q`),
interleaved run by run so a busy machine slows both alike; the figure is the median wall time. It
prints the ratio drawn/butterfly with the issue's target (≤ 2×). It never fails on a time.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parents[1]
TARGET = 2.0


def run(argv: list[str]) -> float:
    t0 = time.perf_counter()
    r = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit(f"{' '.join(argv)} exited {r.returncode}:\n{r.stderr[-2000:]}")
    return wall


def write_drawing(folder: Path, points: int) -> Path:
    """A star outline resampled at ``points`` equal arc-length steps, and its design."""
    xy = np.loadtxt(ROOT / "configs" / "drawings" / "star.csv", delimiter=",", skiprows=1)
    z = np.append(xy[:, 0] + 1j * xy[:, 1], xy[0, 0] + 1j * xy[0, 1])
    s = np.concatenate([[0], np.cumsum(np.abs(np.diff(z)))])
    u = np.linspace(0, s[-1], points, endpoint=False)
    w = np.interp(u, s, z.real) + 1j * np.interp(u, s, z.imag)
    (folder / "star10k.csv").write_text("x_mm,y_mm\n" + "".join(f"{p.real:.6f},{p.imag:.6f}\n" for p in w))
    d = yaml.safe_load((ROOT / "configs" / "star.yaml").read_text())
    d["name"] = "star10k"
    d["curve"]["points"] = "star10k.csv"
    cfg = folder / "star10k.yaml"
    cfg.write_text(yaml.safe_dump(d, sort_keys=False))
    return cfg


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--points", type=int, default=10_000)
    args = ap.parse_args()
    exe = str(Path(sys.executable).with_name("partgen"))
    times: dict[str, list[float]] = {"butterfly": [], "drawn": []}
    with tempfile.TemporaryDirectory() as tmp:
        cfg = write_drawing(Path(tmp), args.points)
        for i in range(args.runs):
            print(f"run {i + 1}/{args.runs}", file=sys.stderr)
            times["butterfly"].append(run([exe, "build", "configs/butterfly.yaml", "-o", f"{tmp}/b{i}", "-q"]))
            times["drawn"].append(run([exe, "build", str(cfg), "-o", f"{tmp}/d{i}", "-q"]))
    med = {k: statistics.median(v) for k, v in times.items()}
    ratio = med["drawn"] / med["butterfly"]
    print(f"median of {args.runs} fresh-process builds each (s)")
    print(f"{'build':<36}{'median s':>10}{'runs':>26}")
    print(f"{'configs/butterfly.yaml':<36}{med['butterfly']:>10.2f}{', '.join(f'{x:.2f}' for x in times['butterfly']):>26}")
    print(f"{f'star from a {args.points}-point CSV':<36}{med['drawn']:>10.2f}{', '.join(f'{x:.2f}' for x in times['drawn']):>26}")
    print(f"ratio drawn / butterfly: {ratio:.2f} (target ≤ {TARGET:g}: {'met' if ratio <= TARGET else 'MISSED'})")


if __name__ == "__main__":
    main()
