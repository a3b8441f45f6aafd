"""Seeded mutations of design files, and a worker that builds them in-process.

Used by tests/cli/test_bad_input.py (bounded) and benchmarks/bad_inputs.py (the whole space). Each
mutation changes one thing in a shipped design: a leaf set to a hostile value (negative, zero,
NaN, ±inf, 1e308, a tiny number, text, a bool, a list, a mapping, null), a key dropped, a
misspelt key added. The worker runs ``partgen build`` on each and prints one JSON line per case:
the exit code, whether a traceback was printed, whether anything was written on a failure.

    python tests/fuzzing.py --seed 1 --budget 50 CONFIG [CONFIG ...]
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import io
import json
import math
import os
import random
import shutil
import signal
import sys
import tempfile
import time
from pathlib import Path

import yaml

VALUES = [("negative", -1.5), ("zero", 0), ("nan", math.nan), ("inf", math.inf), ("-inf", -math.inf),
          ("huge", 1e308), ("-huge", -1e308), ("tiny", 1e-300), ("small", 0.011), ("big_int", 10**20), ("text", "abc"), ("bool", True),
          ("list", [1, 2]), ("mapping", {"a": 1}), ("null", None), ("empty_text", ""), ("long_list", list(range(300)))]


def leaves(node, path=(), text=""):
    """(path, key path text, value) of every leaf and of every mapping/list, depth first."""
    yield path, text, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from leaves(v, path + (k,), f"{text}.{k}" if text else str(k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaves(v, path + (i,), f"{text}[{i}]")


def _set(tree, path, value):
    node = tree
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value


def _drop(tree, path):
    node = tree
    for k in path[:-1]:
        node = node[k]
    del node[path[-1]]


def mutations(design: dict) -> list[tuple[str, str, dict]]:
    """(kind, key path, mutated design) for every mutation of ``design``."""
    out = []
    for path, key, value in leaves(design):
        if not path:
            continue
        if isinstance(value, dict):
            for k in list(value)[:1]:
                t = copy.deepcopy(design)
                _set(t, path + (f"{k}x",), 1)
                out.append(("misspelt_key", f"{key}.{k}x", t))
        if isinstance(path[-1], str):
            t = copy.deepcopy(design)
            _drop(t, path)
            out.append(("dropped_key", key, t))
        if isinstance(value, (dict, list)):
            t = copy.deepcopy(design)
            _set(t, path, [] if isinstance(value, list) else {})
            out.append(("emptied", key, t))
            continue
        for kind, v in VALUES:
            t = copy.deepcopy(design)
            _set(t, path, copy.deepcopy(v))
            out.append((kind, key, t))
    t = copy.deepcopy(design)
    t["kind"] = str(design.get("kind", "x"))[:-1]
    out.append(("misspelt_kind", "kind", t))
    return out


def dump(design: dict) -> str:
    """YAML text of a design; non-finite floats as YAML's .nan/.inf."""
    return yaml.safe_dump(design, sort_keys=False, allow_unicode=True)


class _Timeout(BaseException):  # not an Exception: main() must not take it for a bug
    pass


def run_case(main, cfg: Path, out: Path, seconds: float) -> dict:
    """Build ``cfg`` into ``out`` with ``main`` (in this process); what happened."""
    err, std = io.StringIO(), io.StringIO()

    def alarm(signum, frame):
        raise _Timeout()

    old = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    t0 = time.perf_counter()
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(std):
            code = main(["build", str(cfg), "-o", str(out / "kit"), "-q"])
    except _Timeout:
        code = "timeout"
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    text = err.getvalue()
    left = sorted(os.listdir(out))
    return {"code": code, "traceback": "Traceback" in text or "internal error" in text,
            "written": bool(left) and code != 0, "left": left[:5], "seconds": round(time.perf_counter() - t0, 3),
            "message": text.strip().splitlines()[-1][:300] if text.strip() else ""}


def all_cases(configs: list[Path], seed: int) -> list[tuple[Path, str, str, dict]]:
    """Every mutation of every config, in one seeded order."""
    cases = []
    for cfg in configs:
        design = yaml.safe_load(cfg.read_text(encoding="utf-8"))
        cases += [(cfg, kind, key, t) for kind, key, t in mutations(design)]
    random.Random(seed).shuffle(cases)
    return cases


def worker(configs: list[Path], seed: int, budget: float, case_seconds: float, limit: int | None,
           only: set[int] | None = None) -> None:
    from partgen.cli.main import main
    import partgen.pipeline  # noqa: F401  (what main imports first: not inside the first case's time limit)

    cases = all_cases(configs, seed)
    if limit:
        cases = cases[:limit]
    t_end = time.perf_counter() + budget
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for i, (cfg, kind, key, t) in enumerate(cases):
            if only is not None and i not in only:
                continue
            if time.perf_counter() > t_end:
                break
            folder = tmp / f"c{i}"
            folder.mkdir()
            path = folder / cfg.name
            path.write_text(dump(t), encoding="utf-8")
            for side in cfg.parent.glob("*"):  # the design's data (drawings/), copied: a design reads
                if side.is_dir() and not (folder / side.name).exists():  # only files inside its folder
                    shutil.copytree(side, folder / side.name)
            out = folder / "out"
            out.mkdir()
            print(json.dumps({"i": i, "config": cfg.name, "kind": kind, "key": key, "start": True}), flush=True)
            res = run_case(main, path, out, case_seconds)
            print(json.dumps({"i": i, "config": cfg.name, "kind": kind, "key": key, **res}), flush=True)
            shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("configs", nargs="+", type=Path)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--budget", type=float, default=60.0, help="seconds for the whole run")
    ap.add_argument("--case-seconds", type=float, default=60.0, help="a case taking longer is a hang")
    ap.add_argument("--limit", type=int, default=None, help="at most this many cases")
    ap.add_argument("--only", type=Path, default=None, help="a file of case indices (one per line) to run")
    a = ap.parse_args()
    only = {int(x) for x in a.only.read_text().split()} if a.only else None
    worker(a.configs, a.seed, a.budget, a.case_seconds, a.limit, only)
    sys.exit(0)
