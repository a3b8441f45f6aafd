#!/usr/bin/env python
"""P(jam) of every shipped design on its printer: the table docs/tolerance.md records.

    .venv/bin/python benchmarks/shipped_jam.py                    # 10,000 prints each, seed 0
    .venv/bin/python benchmarks/shipped_jam.py --samples 2000 heart star
    .venv/bin/python benchmarks/shipped_jam.py --printers         # butterfly_desktop on every desktop printer too

Each design is built and checked once in this process (its `auto` play resolved as `build` does), then
the linear study runs in one numpy pass (no Dask): the seated headline with its 95 % Wilson interval,
the worst case (no bore play credited), and the unit that jams most. The same figures as `partgen
tolerance CONFIG --samples N` with one chunk (its chunking changes the draws, not the model), in a
fraction of the time. Rows over the target (1 %) are marked; butterfly_liu2017 is the paper's design
and is expected to fail.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DESKTOP = ("prusa_mk4", "bambu_x1c", "bambu_a1_mini", "prusa_core_one", "voron24_350", "ender3_v3")


def figures(name: str, samples: int, printer: str | None = None, sets: tuple[str, ...] = ()) -> dict:
    from partgen import pipeline, studies
    from partgen.config.overrides import Overrides, parse_set
    from partgen.design.tolerance import run_chunk, summarise

    over = Overrides(tuple(parse_set(x) for x in sets), printer)
    t0 = time.perf_counter()
    loaded = pipeline.load(ROOT / "configs" / f"{name}.yaml", over=over)
    kit = pipeline.make_kit(loaded)
    model, result, _ = studies.nominal_model(loaded, None, kit=kit)
    worst = studies.worst_model(loaded, kit, result, None)
    s = summarise(model, run_chunk(model, 0, 0, samples))
    w = summarise(worst, run_chunk(worst, 0, 0, samples))
    top = next((u["unit"] for u in s["units"] if u["jams"]), "-")
    return {"design": name, "printer": kit.printer.name, "accuracy_mm": model.accuracy_mm, **s["overall"],
            "worst": w["overall"]["probability"], "top": top, "seconds": time.perf_counter() - t0}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="*", help="config names (default: every configs/*.yaml)")
    ap.add_argument("--samples", type=int, default=10_000)
    ap.add_argument("--printers", action="store_true", help="also butterfly_desktop on each desktop printer")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="a design change, as `--set`")
    a = ap.parse_args()
    names = a.names or sorted(p.stem for p in (ROOT / "configs").glob("*.yaml"))
    jobs = [(n, None) for n in names]
    if a.printers:
        jobs += [("butterfly_desktop", p) for p in DESKTOP]
    print(f"| design | printer | P(jam) seated (95 % CI) | worst case | jams most at |   ({a.samples:,} prints, seed 0)")
    print("|---|---|---|---|---|")
    for name, printer in jobs:
        r = figures(name, a.samples, printer, tuple(a.set))
        lo, hi = r["ci95"]
        flag = "" if r["probability"] <= 0.01 else " **over 1 %**"
        print(f"| `{name}.yaml` | {r['printer']} ±{r['accuracy_mm']:g} | {100 * r['probability']:.2f} % "
              f"({100 * lo:.2f}–{100 * hi:.2f}){flag} | {100 * r['worst']:.2f} % | {r['top']} |", flush=True)


if __name__ == "__main__":
    main()
