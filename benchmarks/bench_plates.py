"""Build plates of the default kit: packing time and plate count with free turns about z against the
packer that tries only the four quarter turns of each part's pose (``layout(free=False)``), run
side by side; and the plate 3MF's size (one mesh per distinct part, copies as build items) against
the same writer given one full mesh per copy (the format before).

    .venv/bin/python benchmarks/bench_plates.py [--runs N] [--config configs/butterfly.yaml]

Reports figures only; it never fails on a time. Times depend on machine load (printed).
"""

from __future__ import annotations

import argparse
import io
import math
import os
import sys
import time
import zipfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from partgen import pipeline
from partgen.mechanisms.gear_chain.resolve import load as chain_load  # noqa: E402
from partgen.mechanisms.gear_chain.kit import build_kit  # noqa: E402
from partgen.export import plates as P  # noqa: E402
from partgen.export.kit import group_parts, printed  # noqa: E402
from partgen.export.threemf import Object3MF, write_3mf  # noqa: E402

BEDS = [("Fortus 450mc", (406.0, 355.0)), ("250 x 210 (Prusa MK4 size)", (250.0, 210.0)),
        ("220 x 220 (Ender-3 size)", (220.0, 220.0)), ("180 x 180 (A1 mini size)", (180.0, 180.0))]


def best_of(runs, fn):
    out, best = None, math.inf
    for _ in range(runs):
        t = time.perf_counter()
        try:
            out = fn()
        except P.DoesNotFit as e:
            out = e
        best = min(best, time.perf_counter() - t)
    return out, best


def xml_size(data: bytes) -> int:
    return zipfile.ZipFile(io.BytesIO(data)).getinfo("3D/3dmodel.model").file_size


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3, help="best of N per figure (default 3)")
    ap.add_argument("--config", default=str(ROOT / "configs" / "butterfly.yaml"))
    args = ap.parse_args()
    print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}, {os.cpu_count()} cores; "
          f"best of {args.runs}", file=sys.stderr)
    loaded = chain_load(args.config)
    kit = build_kit(loaded.mechanism, loaded.params)
    groups = group_parts([printed(p) for p in kit.parts if p.printed])
    items = [(g[0].part.name, g[0].mesh, len(g)) for g in groups]
    meshes = {n: m for n, m, _ in items}
    margin = loaded.spec.params.checks.plate_margin
    area = sum(P.footprint(m, margin).area * c for _, m, c in items)
    print(f"{loaded.spec.params.name}: {len(items)} distinct parts, {sum(c for *_, c in items)} copies, "
          f"margin {margin:g} mm\n")
    print(f"{'bed':28s} {'area bound':>10s} | {'quarter turns':>22s} | {'free turns':>22s} | time ratio")
    layouts = {}
    for label, bed in BEDS:
        bound = math.ceil(area / (bed[0] * bed[1]))
        cols = []
        times = []
        for free in (False, True):
            lay, sec = best_of(args.runs, lambda: P.layout(items, bed, margin, free=free))
            times.append(sec)
            if isinstance(lay, P.DoesNotFit):
                cols.append(f"{lay.part} does not fit {sec:6.2f} s")
            else:
                cols.append(f"{len(lay.plates)} plate(s) {sec:6.2f} s")
                if free:
                    layouts[label] = lay
        print(f"{label:28s} {bound:10d} | {cols[0]:>22s} | {cols[1]:>22s} | {times[1] / times[0]:5.2f}x")

    print("\n3MF of each plate: one mesh per copy (before) vs one per distinct part, copies as build items")
    print(f"{'bed':28s} {'plate':>5s} {'copies':>6s} {'parts':>5s} | {'before MB (XML)':>16s} | "
          f"{'after MB (XML)':>15s} | size ratio | write s before/after")
    for label, lay in layouts.items():
        for i, plate in enumerate(lay.plates, 1):
            def before():
                objs = [Object3MF(n, np.asarray(m.vertices), np.asarray(m.faces), (np.eye(4),))
                        for n, m in P.plate_meshes(P.Layout((plate,), lay.size), meshes)[0]]
                return write_3mf(objs, {"Title": loaded.spec.params.name})
            old, t_old = best_of(args.runs, before)
            new, t_new = best_of(args.runs, lambda: P.plate_3mf(plate, meshes, loaded.spec.params.name,
                                                                 loaded.spec.params.material))
            print(f"{label:28s} {i:5d} {len(plate):6d} {len({p.name for p in plate}):5d} | "
                  f"{len(old) / 1e6:6.2f} ({xml_size(old) / 1e6:6.2f}) | {len(new) / 1e6:6.2f} "
                  f"({xml_size(new) / 1e6:6.2f}) | {len(new) / len(old):10.2f} | {t_old:.2f}/{t_new:.2f}")


if __name__ == "__main__":
    main()
