"""Same design, same kit, with the newest libraries? Builds every shipped design twice — with this
interpreter (the versions CI pins, constraints/ci.txt) and in a fresh virtualenv holding the newest
releases of partgen's dependencies — and reports any kit that differs: in its choices and
dimensions (the manifest's design summary and every part's name, count, triangles, volume, bounding
box and placement, compared at 1e-6 relative) and in its bytes (STL sha256).

    .venv/bin/python benchmarks/newest_versions.py                 # every configs/*.yaml (~5-10 min)
    .venv/bin/python benchmarks/newest_versions.py configs/gear_pair.yaml configs/bennett_butterfly.yaml
    .venv/bin/python benchmarks/newest_versions.py --other /path/to/venv/bin/python   # any two environments

Run it when a dependency releases (a scheduled job's work): a kit whose choices or dimensions differ
is a determinism bug to fix before the pins move; STL bytes that differ with equal dimensions are
expected across library versions (the README says which). Exit 0 when every kit's choices and
dimensions agree, 1 otherwise. Progress on stderr, the table on stdout.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEPS = ("numpy", "manifold3d", "shapely", "trimesh", "scipy")


def say(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


def newest_env(where: Path) -> Path:
    """A fresh virtualenv with partgen and the newest releases of everything it needs."""
    subprocess.run([sys.executable, "-m", "venv", str(where)], check=True)
    py = where / "bin" / "python"
    subprocess.run([str(py), "-m", "pip", "install", "-q", "--upgrade", "pip"], check=True)
    subprocess.run([str(py), "-m", "pip", "install", "-q", "--upgrade", "--upgrade-strategy", "eager", str(ROOT)],
                   check=True)
    return py


def versions(py: Path | str) -> dict[str, str]:
    code = ("import json\nfrom importlib.metadata import version\n"
            f"print(json.dumps({{n: version(n) for n in {DEPS!r}}}))")
    return json.loads(subprocess.run([str(py), "-c", code], check=True, capture_output=True, text=True).stdout)


def build(py: Path | str, cfg: Path, dest: Path) -> tuple[dict | None, float, str]:
    t = time.perf_counter()
    r = subprocess.run([str(py), "-m", "partgen", "build", str(cfg), "-o", str(dest), "-q"], capture_output=True,
                       text=True, cwd=ROOT)
    s = time.perf_counter() - t
    if r.returncode != 0:
        return None, s, (r.stderr or r.stdout).strip().splitlines()[-1:][0] if (r.stderr or r.stdout).strip() else "?"
    return json.loads((dest / "manifest.json").read_text()), s, ""


def _same(a, b, rel: float = 1e-6) -> bool:
    """Structural equality with floats compared at ``rel`` (relative, or absolute near 0)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k], rel) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y, rel) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return isinstance(a, (int, float)) and isinstance(b, (int, float)) and math.isclose(a, b, rel_tol=rel, abs_tol=rel)
    return a == b


MESH_ONLY = {"triangles"}  # how the kernel tessellated a part: a property of the STL, not of the design


def differences(ma: dict, mb: dict) -> list[str]:
    """What differs between two manifests in choices and dimensions (``built_with`` and the
    triangle counts left out: see ``MESH_ONLY``)."""
    out = []
    if not _same(ma["design"], mb["design"]):
        keys = sorted(k for k in ma["design"].keys() | mb["design"].keys()
                      if not _same(ma["design"].get(k), mb["design"].get(k)))
        out.append("design: " + ", ".join(keys))
    pa, pb = {p["name"]: p for p in ma["parts"]}, {p["name"]: p for p in mb["parts"]}
    if pa.keys() != pb.keys():
        out.append(f"parts: {sorted(pa.keys() ^ pb.keys())}")
    for n in sorted(pa.keys() & pb.keys()):
        bad = [k for k in pa[n] if k not in MESH_ONLY and not _same(pa[n][k], pb[n].get(k))]
        if bad:
            out.append(f"{n}: {', '.join(bad)}")
    if not _same(ma.get("purchased", []), mb.get("purchased", [])):
        out.append("purchased")
    return out


def stl_hashes(folder: Path) -> dict[str, str]:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.glob("*.stl"))}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("configs", nargs="*", help="designs to build (default: every configs/*.yaml)")
    ap.add_argument("--other", help="the second environment's python (default: a fresh venv of the newest releases)")
    args = ap.parse_args(argv)
    configs = [Path(c).resolve() for c in args.configs] or sorted((ROOT / "configs").glob("*.yaml"))
    with tempfile.TemporaryDirectory(prefix="partgen-newest-") as tmp:
        tmp = Path(tmp)
        if args.other:
            other = Path(args.other)
        else:
            say("installing the newest releases into a fresh virtualenv …")
            other = newest_env(tmp / "venv")
        va, vb = versions(sys.executable), versions(other)
        print("versions (pinned → other): " + ", ".join(
            f"{n} {va[n]}" + ("" if va[n] == vb[n] else f" → {vb[n]}") for n in DEPS))
        print()
        print(f"| {'design':28} | choices and dimensions | STL bytes identical | same triangles  | pinned s | other s |")
        print(f"|{'-' * 30}|------------------------|---------------------|-----------------|----------|---------|")
        bad = 0
        for cfg in configs:
            say(f"building {cfg.name} …")
            ma, sa, ea = build(sys.executable, cfg, tmp / "a" / cfg.stem)
            mb, sb, eb = build(other, cfg, tmp / "b" / cfg.stem)
            if ma is None or mb is None:
                same = "both refused" if ma is None and mb is None else f"refused: {ea or eb}"
                bad += (ma is None) != (mb is None)
                print(f"| {cfg.stem:28} | {same:22} | {'':19} | {'':15} | {sa:8.1f} | {sb:7.1f} |")
                continue
            diff = differences(ma, mb)
            bad += bool(diff)
            ha, hb = stl_hashes(tmp / "a" / cfg.stem), stl_hashes(tmp / "b" / cfg.stem)
            ident = sum(ha[k] == hb.get(k) for k in ha)
            tri = {p["name"]: p["triangles"] for p in ma["parts"]}
            same_tri = sum(tri[p["name"]] == p["triangles"] for p in mb["parts"] if p["name"] in tri)
            print(f"| {cfg.stem:28} | {'same' if not diff else 'DIFFER':22} | {f'{ident}/{len(ha)}':19} | "
                  f"{f'{same_tri}/{len(tri)}':15} | {sa:8.1f} | {sb:7.1f} |")
            for d in diff:
                print(f"|   {d}")
    print()
    print("every kit has the same choices and dimensions" if not bad else f"{bad} kit(s) differ: see above")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
