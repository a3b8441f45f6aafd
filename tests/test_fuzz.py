"""A seeded, bounded fuzz of every shipped design (tests/fuzzing.py): each case is exit 0 or 2,
never a traceback or a crash, and a failed build writes nothing.

The worker runs in a child process, so a segmentation fault in the geometry kernel fails this test
with the case that caused it instead of killing the test run. A case still building after
``CASE_SECONDS`` (a valid wrist or Bennett design: those take tens of seconds) is stopped and must
also have left nothing behind; ``benchmarks/bad_inputs.py`` runs every case to the end.
"""

from __future__ import annotations

import json
import subprocess
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = sorted((ROOT / "configs").glob("*.yaml"))
CASES = 70  # the first 70 of the seeded order, whatever the machine's load (a wall-clock budget ran ~70 on
# 2 cores, fewer on a loaded machine); benchmarks/bad_inputs.py runs the large fuzz (469 cases)
BUDGET_S = 120.0  # a safety net only: 70 cases take ~6 s of CPU
CASE_SECONDS = 4.0


def test_fuzzed_designs_exit_0_or_2_and_write_nothing_on_failure():
    assert len(CONFIGS) >= 6
    proc = subprocess.run([sys.executable, str(ROOT / "tests" / "fuzzing.py"), *map(str, CONFIGS), "--seed", "20261122",
                           "--limit", str(CASES), "--budget", str(BUDGET_S), "--case-seconds", str(CASE_SECONDS)],
                          capture_output=True, text=True, timeout=BUDGET_S + 240, cwd=ROOT)
    lines = [json.loads(x) for x in proc.stdout.splitlines() if x.startswith("{")]
    started = {r["i"]: r for r in lines if r.get("start")}
    done = {r["i"]: r for r in lines if not r.get("start")}
    crashed = [started[i] for i in started if i not in done]
    assert proc.returncode == 0 and not crashed, f"the worker died (exit {proc.returncode}) on {crashed}: {proc.stderr[-2000:]}"
    bad = [r for r in done.values() if r["code"] not in (0, 2, "timeout") or r["traceback"] or r["written"]]
    assert not bad, "\n".join(f"{r['config']} {r['kind']} {r['key']}: exit {r['code']}, left {r['left']}: {r['message']}"
                              for r in bad)
    assert len(done) == CASES, f"{len(done)} of {CASES} cases ran within {BUDGET_S} s"
    codes = Counter(r["code"] for r in done.values())
    kinds = {(r["kind"], r["config"]) for r in done.values()}
    assert codes[2] >= 30 and len(kinds) >= 20, (codes, len(kinds))
    # a message names the key it is about: the mutated key, a key above it or below it
    wrong = []
    for r in done.values():
        if r["code"] != 2 or r["kind"] in ("misspelt_kind",):
            continue
        after = r["message"].split(f"{r['config']}: ", 1)[-1]
        named = after.split(": ", 1)[0]
        key = r["key"]
        if not (named == key or key.startswith(named + ".") or key.startswith(named + "[") or named.startswith(key)):
            wrong.append(f"{r['config']} {r['kind']} {key}: {r['message']}")
    assert len(wrong) <= len(done) // 20, "\n".join(wrong[:20])
