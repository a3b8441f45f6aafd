#!/usr/bin/env python
"""The sha256 of every file of every shipped kit: a refactor that should change nothing proves it.

    .venv/bin/python benchmarks/kit_hashes.py --write before.json      # record
    .venv/bin/python benchmarks/kit_hashes.py --compare before.json    # after the change

Each ``configs/*.yaml`` is built by the CLI in a fresh process (``partgen build CONFIG -o TMP -q``)
and every file of the kit is hashed (STLs, manifest.json, design.yaml, printer.yaml,
assembly.glb). ``--compare`` prints, per config, how many files are byte-identical and names the
ones that are not (or are new or gone); it exits 1 when any differ. ``--only NAME`` (repeatable)
limits the run to those configs (file stems).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PARTGEN = Path(sys.executable).with_name("partgen")


def kit_hashes(config: Path, scratch: Path) -> dict[str, str]:
    out = scratch / config.stem
    r = subprocess.run([str(PARTGEN), "build", str(config), "-o", str(out), "-q"], cwd=ROOT,
                       capture_output=True, text=True)
    if r.returncode != 0:
        return {"<build>": f"exit {r.returncode}: {r.stderr.strip()[-300:]}"}
    return {str(p.relative_to(out)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(out.rglob("*")) if p.is_file() and ".partgen" not in p.parts}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--write", type=Path)
    g.add_argument("--compare", type=Path)
    ap.add_argument("--only", action="append", default=[])
    a = ap.parse_args()
    configs = sorted((ROOT / "configs").glob("*.yaml"))
    if a.only:
        configs = [c for c in configs if c.stem in a.only]
    got: dict[str, dict[str, str]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for c in configs:
            t0 = time.perf_counter()
            got[c.stem] = kit_hashes(c, Path(tmp))
            print(f"  .. {c.stem}: {len(got[c.stem])} files in {time.perf_counter() - t0:.1f} s",
                  file=sys.stderr, flush=True)
    if a.write:
        a.write.write_text(json.dumps(got, indent=1, sort_keys=True))
        print(f"wrote {a.write}: {sum(map(len, got.values()))} files of {len(got)} kits")
        return 0
    before = json.loads(a.compare.read_text())
    differ = 0
    print(f"{'config':32} {'identical':>10} {'differ':>7}  files that differ")
    for stem, files in got.items():
        old = before.get(stem, {})
        names = sorted(set(files) | set(old))
        bad = [n for n in names if files.get(n) != old.get(n)]
        differ += len(bad)
        print(f"{stem:32} {len(names) - len(bad):>10} {len(bad):>7}  {', '.join(bad[:8])}{' ...' if len(bad) > 8 else ''}")
    print("all byte-identical" if not differ else f"{differ} files differ")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
