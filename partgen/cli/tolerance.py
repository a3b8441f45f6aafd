"""``partgen tolerance CONFIG|KITDIR --samples N``: the probability that a print of the kit jams.

Exit 0, or 1 when the overall jam probability is above ``--max-jam-probability``; 2 for bad input
(an unreachable ``--scheduler`` included, within 10 s)."""

from __future__ import annotations

import argparse
import math

from .common import add_common_options, bounded_int, overrides, print_json

__all__ = ["add_parser", "run", "text"]


def _unit_float(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (math.isfinite(v) and 0.0 <= v <= 1.0):
        raise argparse.ArgumentTypeError(f"{text} is out of range: give a probability from 0 to 1")
    return v


def _accuracy(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (math.isfinite(v) and 0.0 <= v <= 5.0):
        raise argparse.ArgumentTypeError(f"{text} is out of range: give 0 to 5 mm")
    return v


def add_workers_options(p) -> None:
    p.add_argument("--workers", type=bounded_int(1, 1024), default=None,
                   help="workers of the local Dask cluster (default: this machine's cores)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run on an existing Dask cluster (tcp://host:8786) instead of a local one")


def add_parser(sub) -> None:
    p = sub.add_parser("tolerance", help="Monte Carlo of print tolerances: the probability that the kit jams")
    p.add_argument("target", help="design YAML, or a kit folder written by `partgen build`")
    p.add_argument("--samples", type=bounded_int(1, 100_000_000), required=True, help="prints to simulate")
    p.add_argument("--accuracy-mm", type=_accuracy, default=None,
                   help="± accuracy of a printed dimension, 3σ (default: the printer profile's xy_accuracy_mm)")
    p.add_argument("--seed", type=bounded_int(0, 2 ** 63 - 1), default=0, help="random seed (default 0)")
    p.add_argument("--check-samples", type=bounded_int(4, 10_000), default=None,
                   help="samples of the motion in the nominal check (default: the config's checks.samples)")
    p.add_argument("--max-jam-probability", type=_unit_float, default=None, metavar="P",
                   help="exit 1 when the probability that the kit jams is above P")
    p.add_argument("--chunk", type=bounded_int(1, 10_000_000), default=None,
                   help="samples per task (default 5000, or a 16th of a study over 80,000 samples, at most 100,000; "
                        "with the seed it fixes the result: raise it for many workers)")
    p.add_argument("--exact", type=bounded_int(1, 1_000_000), default=None, metavar="N",
                   help="also N prints of the kit's real geometry (exact Monte Carlo, one task each on the cluster)")
    p.add_argument("--resume", action="store_true", help="continue an interrupted run with the same settings")
    add_common_options(p, "folder for chunks.jsonl and result.json (default <kit>/tolerance or out/<name>/tolerance)")
    add_workers_options(p)
    p.set_defaults(run=run)


def _pct(p: float) -> str:
    return f"{100 * p:.2f} %"


def text(r: dict, dest=None, limit: int = 12) -> str:
    o = r["overall"]
    w = max([16] + [len(u["unit"]) + 2 for u in r["units"][:limit]])  # the first column fits its longest name
    lines = [f"{r['design']}: {r['samples']:,} simulated prints at ±{r['accuracy_mm']:g} mm ({r['accuracy_source']}), "
             f"{r['features']} printed features, {r['margins']} margins",
             f"P(jam) = {_pct(o['probability'])}  (95 % CI {_pct(o['ci95'][0])} – {_pct(o['ci95'][1])}; "
             f"{o['jams']:,} of {r['samples']:,}; {r.get('seat') or 'gears seated by their meshes in their bores'})"]
    wc = r.get("worst_case")
    if wc and wc.get("seat") != r.get("seat"):  # a model that credits no play: the worst case is the headline
        lines.append(f"worst case, {wc.get('seat') or 'every gear centred on its post (no bore play credited)'}: P(jam) = "
                     f"{_pct(wc['probability'])}  (95 % CI {_pct(wc['ci95'][0])} – {_pct(wc['ci95'][1])})")
    ex = r.get("exact")
    if ex:
        lines.append(f"exact: P(jam) = {_pct(ex['probability'])}  (95 % CI {_pct(ex['ci95'][0])} – {_pct(ex['ci95'][1])}; "
                     f"{ex['jams']} of {ex['prints']:,} prints of the real geometry"
                     + (f": {', '.join(f'{k} {v}' for k, v in ex['why'].items())}" if ex["why"] else "")
                     + f") — {'agrees with' if ex['agrees'] else 'DISAGREES with'} the linear figure; "
                     f"{ex['seconds_per_print']:.3f} s a print, {ex['seconds']:.1f} s on {ex['workers']} worker(s)")
    lines += ["",
             f"{'where':<{w}}{'kind':<10}{'at':<9}{'nominal mm':>11}{'P(jam)':>10}   95 % CI"]
    for u in r["units"][:limit]:
        lines.append(f"{u['unit']:<{w}}{u['group']:<10}{u['where']:<9}{u['least_nominal_mm']:>11.4f}"
                     f"{_pct(u['probability']):>10}   {_pct(u['ci95'][0])} – {_pct(u['ci95'][1])}")
    if len(r["units"]) > limit:
        lines.append(f"  … {len(r['units']) - limit} more (--json lists all)")
    lines += ["", "what drives the jams (share of jams by feature kind): "
              + (", ".join(f"{k['kind']} {100 * k['share']:.1f} %" for k in r["sensitivity"]["by_kind"] if k["share"] > 0)
                 or "no jams")]
    if r["sensitivity"]["by_feature"]:
        lines.append("features: " + ", ".join(f"{f['feature']} {100 * f['share']:.1f} %"
                                              for f in r["sensitivity"]["by_feature"][:6]))
    stale = r.get("kit_stale_files")
    if stale:
        lines.append(f"warning: {len(stale)} STL files of the kit folder differ from what its design.yaml builds "
                     f"({', '.join(stale[:3])}{' …' if len(stale) > 3 else ''}): this is the study of the design; rebuild the kit")
    s = r["seconds"]
    lines.append(f"{r['chunks']} chunks on {r['workers']} worker(s) in {s['samples']:.2f} s (nominal check "
                 f"{s['nominal_check']:.1f} s; then {s['cluster_wait']:.1f} s waiting for the cluster)"
                 + (f"; {r['resumed_chunks']} chunks resumed" if r["resumed_chunks"] else "")
                 + (f"; wrote {dest}/result.json" if dest else ""))
    return "\n".join(lines)


def run(args) -> int:
    from .. import studies

    res = studies.tolerance(args.target, args.samples, args.accuracy_mm, args.seed, args.workers, args.scheduler,
                            args.out, args.resume, args.check_samples, overrides(args),
                            progress=not (args.json or args.quiet), exact=args.exact,
                            **({"chunk": args.chunk} if args.chunk else {}))
    r = res.result
    limit = args.max_jam_probability
    failed = limit is not None and r["overall"]["probability"] > limit
    if args.json:
        print_json({"ok": not failed, "max_jam_probability": limit, **r, "dest": str(res.dest) if res.dest else None})
    else:
        print(text(r, res.dest) if not args.quiet else text(r, res.dest).split("\n")[1])
        if failed:
            print(f"FAILED: P(jam) {_pct(r['overall']['probability'])} is above --max-jam-probability {limit:g}")
    return 1 if failed else 0
