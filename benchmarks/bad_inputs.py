"""Every bad input we know how to make, tried as a new user and a hostile file would; prints how
each kind was handled. It never fails on a figure: it reports them.

    .venv/bin/python benchmarks/bad_inputs.py                       # everything (hours: valid mutants build)
    .venv/bin/python benchmarks/bad_inputs.py --max-per-config 150  # a seeded sample per shipped design
    .venv/bin/python benchmarks/bad_inputs.py --only-named          # only the file and command-line cases

Two families:
* **mutants** of every shipped design (tests/fuzzing.py): one leaf set to a hostile value, a key
  dropped, a misspelt key added, a list emptied, ``kind`` misspelt. Run in a worker process that
  is restarted after the case that killed it (so a segmentation fault is counted, not fatal).
* **named** cases of the file and the command line, each run as its own process: a FIFO, a
  device, a folder, a 20 MB file, binary, deep nesting, an alias bomb, a duplicate key, a printer
  outside the design's folder, out-of-range --samples, the output rules (-o a file, the current
  folder, the design's folder, a user's folder, --csv onto a user's file or into a missing folder).

A case is **handled** when it exits 0 (a valid design, built) or 2 with one ``partgen: error:``
line naming the file and the key (or option), no traceback, and nothing written; otherwise it is
a crash (exit 3, a traceback, a signal), a hang (past --case-seconds), a wrong key, or a write.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections import Counter, defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
import fuzzing  # noqa: E402

PARTGEN = Path(sys.executable).parent / "partgen"


def run_mutants(configs, seed, case_seconds, max_per_config):
    """Run the worker over every mutant (or a seeded sample per design), restarting it after the
    case that killed it."""
    cases = fuzzing.all_cases(configs, seed)
    seen, todo = Counter(), []
    for i, c in enumerate(cases):
        if not max_per_config or seen[c[0]] < max_per_config:
            seen[c[0]] += 1
            todo.append(i)
    results = {}
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        only = Path(tmp) / "only.txt"
        while len(results) < len(todo):
            left = [i for i in todo if i not in results]
            only.write_text("\n".join(map(str, left)))
            proc = subprocess.Popen([sys.executable, str(ROOT / "tests" / "fuzzing.py"), *map(str, configs), "--seed",
                                     str(seed), "--budget", "1e9", "--case-seconds", str(case_seconds), "--only",
                                     str(only)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT)
            last = None
            for line in proc.stdout:
                if not line.startswith("{"):
                    continue
                r = json.loads(line)
                if r.get("start"):
                    last = r
                    continue
                results[r["i"]] = r
                print(f"\r  mutants: {len(results)}/{len(todo)}  {time.perf_counter() - t0:6.0f} s", end="",
                      file=sys.stderr, flush=True)
            proc.wait()
            if last is not None and last["i"] not in results:  # the worker died on this case
                results[last["i"]] = {**last, "code": proc.returncode, "traceback": True, "written": False,
                                      "message": f"the process died with {proc.returncode}"}
            elif len(results) < len(todo):
                raise RuntimeError(f"the worker stopped early: {proc.stderr.read()[-2000:]}")
    print(file=sys.stderr)
    return list(results.values())


def named_cases(tmp: Path) -> list[tuple[str, list[str], str, Path | None]]:
    """(kind, argv, what the message must name, folder that must stay as it is) of every named case."""
    good = (ROOT / "configs" / "butterfly.yaml").read_text()
    cases = []

    def design(name: str, text: str) -> Path:
        p = tmp / f"{name}.yaml"
        p.write_text(text)
        return p

    fifo = tmp / "fifo.yaml"
    os.mkfifo(fifo)
    big = tmp / "big.yaml"
    big.write_text(good + "\nextra: [" + ", ".join("1.5" for _ in range(4_000_000)) + "]\n")
    binary = tmp / "binary.yaml"
    binary.write_bytes(os.urandom(4096))
    mine = tmp / "mine"
    mine.mkdir()
    (mine / "thesis.txt").write_text("years of work\n")
    userfile = tmp / "notes.csv"
    userfile.write_text("x,y\n")
    out = tmp / "out"
    out.mkdir()
    build = lambda cfg, *extra: ["build", str(cfg), "-o", str(out / "kit"), "-q", *extra]  # noqa: E731
    cases += [
        ("file: a FIFO", build(fifo), "not a regular file", out),
        ("file: /dev/zero", build("/dev/zero"), "not a regular file", out),
        ("file: a folder", build(tmp), "folder", out),
        ("file: over 10 MB", build(big), "MB", out),
        ("file: binary", build(binary), "binary.yaml", out),
        ("file: missing", build(tmp / "nope.yaml"), "no such file", out),
        ("yaml: nested 100000 deep", build(design("deep", "a: " + "[" * 100000 + "]" * 100000)), "nested", out),
        ("yaml: alias bomb", build(design("bomb", "a: &a [1,1,1,1,1,1,1,1,1,1]\n" + "".join(
            f"{c}: &{c} [{', '.join(['*' + p] * 10)}]\n" for p, c in zip("abcdefgh", "bcdefghi")))), "values", out),
        ("yaml: duplicate key", build(design("dup", good.replace("gears:\n", "gears:\n  module_mm: 1.5\n", 1))),
         "given twice", out),
        ("yaml: python tag", build(design("tag", good + "\nx: !!python/object/apply:os.system ['true']\n")),
         "invalid YAML", out),
        ("printer: /etc/passwd", build(design("etc", good.replace("printer: fortus450mc", "printer: /etc/passwd")
                                              )), "printer", out),
        ("printer: ../ escape", build(design("esc", good.replace("printer: fortus450mc", "printer: ../x/p.yaml"))),
         "printer", out),
        ("printer: unknown name", build(design("unk", good.replace("printer: fortus450mc", "printer: fortus"))),
         "printer", out),
        ("kind: misspelt", build(design("kind", good.replace("kind: gear_chain", "kind: gear_chian"))), "kind", out),
        ("option: --samples 0", ["check", str(ROOT / "configs" / "butterfly.yaml"), "--samples", "0"], "--samples",
         None),
        ("option: --samples 10**8", ["check", str(ROOT / "configs" / "butterfly.yaml"), "--samples", "100000000"],
         "--samples", None),
        ("option: trace --samples 10**9", ["trace", str(ROOT / "configs" / "butterfly.yaml"), "--samples",
                                           "1000000000"], "--samples", None),
        ("output: -o a file", ["build", str(ROOT / "configs" / "butterfly.yaml"), "-o", str(userfile)], "-o", tmp),
        ("output: -o a user's folder", ["build", str(ROOT / "configs" / "butterfly.yaml"), "-o", str(mine)], "-o",
         tmp),
        ("output: -o the design's folder", ["build", str(design("here", good)), "-o", str(tmp)], "-o", tmp),
        ("output: --plates a user's folder", ["check", str(ROOT / "configs" / "butterfly.yaml"), "--samples", "8",
                                             "--plates", str(mine)], "--plates", tmp),
        ("output: --csv onto a user's file", ["trace", str(ROOT / "configs" / "butterfly.yaml"), "--no-plots",
                                              "--csv", str(userfile)], "--csv", tmp),
        ("output: --csv into a missing folder", ["trace", str(ROOT / "configs" / "butterfly.yaml"), "--no-plots",
                                                 "--csv", str(tmp / "no" / "p.csv")], "--csv", tmp),
        ("output: report -o a user's folder", ["report", str(ROOT / "configs" / "butterfly.yaml"), "-o", str(mine)],
         "-o", tmp),
    ]
    for n in (".", "..", "-rf", "../escape", "a/b"):
        d = good.replace("name: butterfly", f"name: '{n}'")
        cases.append((f"name: {n!r}", ["build", str(design(f"name{len(cases)}", d)), "-q"], "name", None))
    return cases


def snapshot(folder: Path) -> dict:
    return {str(p.relative_to(folder)): (p.stat().st_size if p.is_file() else -1) for p in sorted(folder.rglob("*"))
            if not p.is_fifo()}


def run_named(case_seconds):
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for kind, argv, must, watch in named_cases(tmp):
            before = snapshot(watch) if watch else None
            t0 = time.perf_counter()
            try:
                p = subprocess.run([str(PARTGEN), *argv], capture_output=True, text=True, timeout=case_seconds,
                                   cwd=tmp)
                code, err = p.returncode, p.stderr
            except subprocess.TimeoutExpired:
                code, err = "timeout", ""
            after = snapshot(watch) if watch else None
            rows.append({"kind": kind, "code": code, "traceback": "Traceback" in err,
                         "written": before != after, "named": must in err, "message": err.strip()[-200:],
                         "seconds": round(time.perf_counter() - t0, 2)})
            print(f"  {kind}: exit {code}", file=sys.stderr)
    return rows


def classify(r: dict, key_ok: bool) -> str:
    if r["code"] == "timeout":
        return "hang"
    if r["code"] not in (0, 2) or r["traceback"]:
        return "crash"
    if r["written"]:
        return "written"
    if r["code"] == 2 and not key_ok:
        return "wrong key"
    return "handled"


def mutant_key_ok(r: dict) -> bool:
    if r["code"] != 2 or r["kind"] == "misspelt_kind":
        return True
    after = r["message"].split(f"{r['config']}: ", 1)[-1]
    named = after.split(": ", 1)[0]
    key = r["key"]
    return named == key or key.startswith(named + ".") or key.startswith(named + "[") or named.startswith(key)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--max-per-config", type=int, default=0, help="a seeded sample of mutants per design (0: all)")
    ap.add_argument("--case-seconds", type=float, default=300.0)
    ap.add_argument("--only-named", action="store_true")
    ap.add_argument("--configs", nargs="*", type=Path, default=sorted((ROOT / "configs").glob("*.yaml")))
    ap.add_argument("--json", type=Path, default=None, help="also write every row here")
    a = ap.parse_args()
    named = run_named(a.case_seconds)
    mutants = [] if a.only_named else run_mutants(a.configs, a.seed, a.case_seconds, a.max_per_config)
    table = defaultdict(Counter)
    for r in named:
        table[r["kind"]][classify(r, r["named"])] += 1
    for r in mutants:
        table[(r["config"].split(".")[0], r["kind"])][classify(r, mutant_key_ok(r))] += 1
    cols = ["handled", "wrong key", "crash", "hang", "written"]
    print(f"{'kind of bad input':<52}" + "".join(f"{c:>10}" for c in cols))
    for kind in sorted(table, key=str):
        label = kind if isinstance(kind, str) else f"{kind[0]}: {kind[1]}"
        print(f"{label:<52}" + "".join(f"{table[kind][c]:>10}" for c in cols))
    total = Counter()
    for c in table.values():
        total.update(c)
    n = sum(total.values())
    kinds_all = sum(1 for c in table.values() if c["handled"] == sum(c.values()))
    print(f"\n{n} cases of {len(table)} distinct kinds: " + ", ".join(f"{total[c]} {c}" for c in cols))
    print(f"kinds handled in every case: {kinds_all} of {len(table)}")
    bad = [r for r in named + mutants if classify(r, r.get("named", True) if "config" not in r else mutant_key_ok(r))
           != "handled"]
    for r in bad[:40]:
        print(f"  {r.get('config', '')} {r['kind']} {r.get('key', '')}: exit {r['code']}: {r['message'][-160:]}")
    if a.json:
        a.json.write_text(json.dumps({"named": named, "mutants": mutants}, indent=1))


if __name__ == "__main__":
    main()
