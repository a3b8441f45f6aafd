#!/usr/bin/env python
"""Benchmark partgen's kit build against the floor of what manifold3d itself costs.

Run with the project's virtualenv (the `partgen` console script must sit next to sys.executable):

    .venv/bin/python benchmarks/bench_build.py            # full run, 3 fresh-process runs per kit
    .venv/bin/python benchmarks/bench_build.py --quick    # 1 run each, fewer repeats
    .venv/bin/python benchmarks/bench_build.py --profile  # also cProfile one in-process kit build

What it measures (all in one run, so ratios compare like with like on this machine):

1. each whole kit (configs/butterfly.yaml, configs/butterfly_liu2017.yaml) built by the CLI in a
   fresh process: wall time (median of --runs), parts / gears / triangles from manifest.json and
   the child's peak RSS; plus the bare `python -c "import partgen.pipeline"` startup, subtracted to
   give the kit time net of interpreter + import.
2. one gear of 15, 40 and 80 teeth built in-process by partgen (gear_body + to_mesh, best of K),
   next to the bare manifold3d cost of the same outline.
3. the floor: the default kit's 32 gears (teeth and profile shift from its manifest) made by a bare
   manifold3d loop from precomputed outlines (CrossSection - circle, extrude 6 mm, to_mesh), and
   partgen's own in-process path for the same gears (outline + gear_body + to_mesh).
4. the fresh-process floor (issue 26's yardstick): python, import numpy, manifold3d and trimesh, the 32
   gears from given outlines, each written as a binary STL by trimesh; and the same floor writing its
   STLs with numpy instead (no trimesh import), printed beside it. partgen's build forks one child
   at a time (core.background), so its CPU seconds (all its processes) are printed beside its wall.

Timings use time.perf_counter. Nothing here asserts on time: it prints figures and whether the
issue's target ("the whole kit within 3x the floor, under 2 s here") is met.
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_KIT = "configs/butterfly.yaml"
KITS = (DEFAULT_KIT, "configs/butterfly_liu2017.yaml")
SINGLE_GEARS = (15, 40, 80)
FACE_WIDTH = 6.0  # mm, extrusion height of every benchmarked gear
BORE_R, BORE_TOL = 5.1, 0.01  # mm: the circle subtracted from every benchmarked gear
TARGET_RATIO, TARGET_SECONDS = 3.0, 2.0
FRESH_TARGET = 1.5  # issue 26: the default chain's build at most 1.5x the 32-gear floor in fresh processes

try:
    import manifold3d as m3d
    import numpy as np

    from partgen.design import involute
    from partgen.design.gearing import GearSpec, ToothSystem, make_gear
    from partgen.geometry.gear import gear_body
    from partgen.geometry.outline import circle, segments_for
except ImportError as e:  # pragma: no cover - wrong interpreter
    sys.exit(f"bench_build: cannot import partgen/manifold3d ({e}); run it with the project's venv: "
             f".venv/bin/python benchmarks/{Path(__file__).name}")


# Every child may write its bytecode (.pyc), as Python does on a user's machine: with
# PYTHONDONTWRITEBYTECODE set (as in some sandboxes and CI images) partgen's ~30,000 lines would be
# compiled again in every fresh process, a cost no installed tool pays after its first run (the floor
# imports only installed libraries, whose bytecode pip wrote). The warm-up runs write it.
CHILD_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def say(msg: str) -> None:
    """Progress on stderr, so stdout holds only the report."""
    print(f"  .. {msg}", file=sys.stderr, flush=True)


# ----------------------------------------------------------------------------- fresh processes
class ChildRunner:
    """Runs a command with subprocess.run and measures its wall time and peak RSS (and, in
    ``last_cpu``, the CPU seconds of the run's processes: partgen's build forks one child at a time).

    Peak RSS comes from GNU time (`/usr/bin/time -f %M`, exact per child) when it works here;
    otherwise from resource.getrusage(RUSAGE_CHILDREN).ru_maxrss, which is the maximum over *all*
    children reaped so far: exact when this child set a new maximum, else only an upper bound
    (printed as "<=N"). Wall time is measured around subprocess.run in both cases (GNU time adds
    one fork/exec, ~1 ms, to every run alike, the import-only baseline included)."""

    def __init__(self, scratch: Path):
        self.scratch = scratch
        self.gnu_time = self._probe_gnu_time()
        self.method = ("/usr/bin/time -f %M (per child)" if self.gnu_time
                       else "getrusage(RUSAGE_CHILDREN).ru_maxrss delta")

    def _probe_gnu_time(self) -> str | None:
        exe = shutil.which("time", path="/usr/bin:/bin") or ("/usr/bin/time" if os.path.exists("/usr/bin/time") else None)
        if exe is None:
            return None
        out = self.scratch / "probe.rss"
        try:
            r = subprocess.run([exe, "-f", "%M", "-o", str(out), sys.executable, "-c", "pass"],
                               capture_output=True, timeout=30)
            int(out.read_text().strip().splitlines()[-1])
        except (OSError, ValueError, IndexError, subprocess.SubprocessError):
            return None
        return exe if r.returncode == 0 else None

    @staticmethod
    def _maxrss_mb(raw: int) -> float:
        return raw / 2**20 if sys.platform == "darwin" else raw / 1024  # bytes on macOS, KiB elsewhere

    def run(self, argv: list[str]) -> tuple[float, float, bool, subprocess.CompletedProcess]:
        """-> (wall s, peak RSS MB, RSS exact?, completed process)."""
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        before, cpu0 = usage.ru_maxrss, usage.ru_utime + usage.ru_stime
        rss_file = self.scratch / "child.rss"
        cmd = [self.gnu_time, "-f", "%M", "-o", str(rss_file), *argv] if self.gnu_time else argv
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, env=CHILD_ENV)
        wall = time.perf_counter() - t0
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)  # every process of the run, forked ones included
        self.last_cpu = usage.ru_utime + usage.ru_stime - cpu0
        if proc.returncode != 0:
            sys.exit(f"bench_build: {' '.join(argv)} failed ({proc.returncode}):\n{proc.stderr}")
        if self.gnu_time:
            return wall, int(rss_file.read_text().strip().splitlines()[-1]) / 1024, True, proc
        after = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        return wall, self._maxrss_mb(after), after > before, proc


def fmt_rss(mb: float, exact: bool) -> str:
    return f"{mb:.0f}" if exact else f"<={mb:.0f}"


def bench_import(runner: ChildRunner, runs: int) -> dict:
    argv = [sys.executable, "-c", "import partgen.pipeline"]
    runner.run(argv)  # warm-up: page cache, .pyc files
    walls, rss = [], []
    for _ in range(runs):
        w, mb, exact, _ = runner.run(argv)
        walls.append(w)
        rss.append((mb, exact))
    return {"walls": walls, "median": statistics.median(walls), "rss": max(rss)}


def bench_kit(runner: ChildRunner, script: Path, cfg: str, runs: int, scratch: Path) -> dict:
    walls, rss, cli_s, cpus, man = [], [], [], [], None
    runner.run([str(script), "build", cfg, "-o", str(scratch / f"{Path(cfg).stem}-warm"), "-q"])  # warm-up: .pyc, page cache, auto choices remembered
    for i in range(runs):
        dest = scratch / f"{Path(cfg).stem}-{i}"  # a folder that does not exist yet: the CLI creates it
        w, mb, exact, proc = runner.run([str(script), "build", cfg, "-o", str(dest), "-q"])
        walls.append(w)
        cpus.append(runner.last_cpu)
        rss.append((mb, exact))
        m = re.search(r"\bin ([0-9.]+) s\b", proc.stdout)
        if m:
            cli_s.append(float(m.group(1)))
        if man is None:
            man = json.loads((dest / "manifest.json").read_text())
        shutil.rmtree(dest, ignore_errors=True)
    parts = man["parts"]
    return {
        "cfg": cfg, "walls": walls, "median": statistics.median(walls), "rss": max(rss), "cpu": statistics.median(cpus),
        "cli_build_s": statistics.median(cli_s) if cli_s else None,
        "parts": sum(p["count"] for p in parts), "distinct": len(parts),
        "gears": sum(p["count"] for p in parts if p["role"] == "gear"),
        "triangles": sum(p["triangles"] * p["count"] for p in parts),
        "manifest": man,
    }


# ----------------------------------------------------------------------------- in-process gears
def best_of(fn, repeats: int) -> float:
    """Best wall time of ``repeats`` calls of fn(), s (one untimed warm-up call first)."""
    fn()
    best = math.inf
    for _ in range(repeats):
        gc.collect()
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def outline_args(spec: GearSpec) -> tuple:
    s = spec.system
    return (spec.teeth, s.module, s.pressure_angle, spec.profile_shift, s.backlash_per_gear, s.addendum_coeff,
            s.dedendum_coeff, s.cutter_tip_coeff, s.chord_tolerance)


def floor_gear(points: np.ndarray, hole_segments: int) -> m3d.Mesh:
    """The floor of one gear on manifold3d: CrossSection of a ready outline, minus a circle,
    extruded, meshed. Nothing else."""
    cs = m3d.CrossSection([points], m3d.FillRule.EvenOdd) - m3d.CrossSection.circle(BORE_R, hole_segments)
    return m3d.Manifold.extrude(cs, FACE_WIDTH).to_mesh()


def partgen_gear(spec: GearSpec) -> m3d.Mesh:
    """partgen's path for one gear: outline generation + gear_body (+ the shapely bore) + to_mesh."""
    return gear_body(spec, FACE_WIDTH, circle(BORE_R, BORE_TOL)).to_mesh()


def n_tri(mesh: m3d.Mesh) -> int:
    return int(np.asarray(mesh.tri_verts).shape[0])


def bench_single_gears(repeats: int, hole_segments: int) -> list[dict]:
    system = ToothSystem(module=1.25, pressure_angle=math.radians(20), profile_shift=None,
                         backlash_per_gear=0.05, chord_tolerance=0.001)
    rows = []
    for z in SINGLE_GEARS:
        spec = make_gear(z, system)
        pts = np.array(involute.gear_outline(*outline_args(spec)).points, dtype=float)
        solid = gear_body(spec, FACE_WIDTH, circle(BORE_R, BORE_TOL))
        rows.append({
            "teeth": z, "verts": len(pts), "tri": solid.num_tri(),
            "floor_tri": n_tri(floor_gear(pts, hole_segments)),
            "outline_s": best_of(lambda: involute.gear_outline(*outline_args(spec)), repeats),
            "partgen_s": best_of(lambda: partgen_gear(spec), repeats),
            "floor_s": best_of(lambda: floor_gear(pts, hole_segments), repeats),
        })
    return rows


def kit_gear_specs(manifest: dict, system: ToothSystem) -> list[GearSpec]:
    """The kit's gears, one spec per printed gear (a part's count repeats it)."""
    specs = []
    for p in manifest["parts"]:
        if p["role"] == "gear":
            g = p["gear"]
            specs += [GearSpec(int(g["teeth"]), system, float(g["profile_shift"]))] * int(p["count"])
    return specs


def bench_kit_gears(manifest: dict, repeats: int, hole_segments: int) -> dict:
    from partgen.mechanisms.gear_chain.resolve import load

    system = load(ROOT / DEFAULT_KIT).params.system  # the kit's exact tooth system (untimed)
    specs = kit_gear_specs(manifest, system)
    outlines = [np.array(involute.gear_outline(*outline_args(s)).points, dtype=float) for s in specs]  # untimed

    def floor_all():
        return [floor_gear(p, hole_segments) for p in outlines]

    def partgen_all():
        return [partgen_gear(s) for s in specs]

    def outlines_all():
        return [involute.gear_outline(*outline_args(s)) for s in specs]

    return {
        "n": len(specs), "teeth": [s.teeth for s in specs], "verts": sum(len(p) for p in outlines),
        "floor_tri": sum(n_tri(m) for m in floor_all()), "partgen_tri": sum(n_tri(m) for m in partgen_all()),
        "floor_s": best_of(floor_all, repeats),
        "partgen_s": best_of(partgen_all, repeats),
        "outline_s": best_of(outlines_all, repeats),
    }


FRESH_FLOOR = """
import sys, numpy as np, manifold3d as m3d, trimesh
data = np.load(sys.argv[1])
out = sys.argv[2]
hole = m3d.CrossSection.circle(float(data["bore_r"]), int(data["segments"]))
for i in range(int(data["n"])):
    cs = m3d.CrossSection([data[f"g{i}"]], m3d.FillRule.EvenOdd) - hole
    mesh = m3d.Manifold.extrude(cs, float(data["face"])).to_mesh()
    trimesh.Trimesh(np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts), process=False).export(f"{out}/g{i}.stl")
"""


# the same floor with the STLs written by numpy (normals as trimesh computes them), importing no trimesh:
# what a tool that writes its STLs itself, as partgen now does (export.stl), could reach
FRESH_FLOOR_NUMPY = """
import sys, numpy as np, manifold3d as m3d
data = np.load(sys.argv[1])
out = sys.argv[2]
rec = np.dtype([("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")])
hole = m3d.CrossSection.circle(float(data["bore_r"]), int(data["segments"]))
for i in range(int(data["n"])):
    cs = m3d.CrossSection([data[f"g{i}"]], m3d.FillRule.EvenOdd) - hole
    mesh = m3d.Manifold.extrude(cs, float(data["face"])).to_mesh()
    t = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3][np.asarray(mesh.tri_verts)]
    c = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    packed = np.zeros(len(t), dtype=rec)
    packed["n"] = c / np.maximum(np.linalg.norm(c, axis=1, keepdims=True), 1e-300)
    packed["v"] = t
    with open(f"{out}/g{i}.stl", "wb") as f:
        f.write(bytes(80) + np.uint32(len(t)).tobytes() + packed.tobytes())
"""


def bench_fresh_floor(runner: "ChildRunner", manifest: dict, runs: int, hole_segments: int, scratch: Path) -> dict:
    """The floor in a fresh process: start Python, import numpy, manifold3d and trimesh (the libraries
    the kit is made and written with), make the default kit's gears from their outlines (given, in
    an .npz) and write each as a binary STL with trimesh. Nothing a tool on this stack could skip."""
    from partgen.mechanisms.gear_chain.resolve import load

    system = load(ROOT / DEFAULT_KIT).params.system
    specs = kit_gear_specs(manifest, system)
    arrays = {f"g{i}": np.array(involute.gear_outline(*outline_args(s)).points, dtype=float) for i, s in enumerate(specs)}
    npz = scratch / "floor_outlines.npz"
    np.savez(npz, n=len(specs), bore_r=BORE_R, segments=hole_segments, face=FACE_WIDTH, **arrays)
    out = {"n": len(specs)}
    for key, text in (("trimesh", FRESH_FLOOR), ("numpy", FRESH_FLOOR_NUMPY)):
        script = scratch / f"floor_{key}.py"
        script.write_text(text)
        dest = scratch / f"floor-stl-{key}"
        dest.mkdir(exist_ok=True)
        argv = [sys.executable, str(script), str(npz), str(dest)]
        runner.run(argv)  # warm-up
        walls = [runner.run(argv)[0] for _ in range(runs)]
        out[key] = {"walls": walls, "median": statistics.median(walls)}
    out["median"] = out["trimesh"]["median"]  # the floor
    return out


# ----------------------------------------------------------------------------- profiling (--profile)
def profile_kit(scratch: Path, top: int) -> None:
    import cProfile
    import io
    import pstats

    from partgen import pipeline

    cfg = ROOT / DEFAULT_KIT
    pipeline.build(cfg, scratch / "prof-warm")  # warm: imports, caches
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    prof.enable()
    pipeline.build(cfg, scratch / "prof")
    prof.disable()
    wall = time.perf_counter() - t0
    buf = io.StringIO()
    pstats.Stats(prof, stream=buf).sort_stats("cumulative").print_stats(top)
    print(f"\ncProfile of partgen.pipeline.build({DEFAULT_KIT}) in-process, warm ({wall:.2f} s under the profiler), "
          f"top {top} by cumulative time:")
    print("\n".join(l for l in buf.getvalue().splitlines() if l.strip() and "function calls" not in l
                    and "Ordered by" not in l and "List reduced" not in l))

    # import cost is invisible to an in-process profile: ask a fresh interpreter
    r = subprocess.run([sys.executable, "-X", "importtime", "-c", "import partgen.pipeline"],
                       cwd=ROOT, capture_output=True, text=True)
    rows = []
    for line in r.stderr.splitlines():
        m = re.match(r"import time:\s+(\d+) \|\s+(\d+) \|(\s*)(\S+)", line)
        if m:
            rows.append((int(m.group(2)), len(m.group(3)) // 2, m.group(4)))
    tops = sorted((x for x in rows if x[1] <= 2), reverse=True)[:top]
    print(f"\n-X importtime of `import partgen.pipeline` (fresh process), top {top} cumulative, depth <= 2:")
    for us, depth, name in tops:
        print(f"  {us / 1e3:8.1f} ms  {'  ' * depth}{name}")


# ----------------------------------------------------------------------------- report
def table(headers: list[str], rows: list[list[str]], align: str) -> str:
    """A plain text table; align is one of '<' / '>' per column."""
    w = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(headers)]
    line = lambda cells: "  ".join(f"{c:{a}{n}}" for c, a, n in zip(cells, align, w)).rstrip()
    return "\n".join([line(headers), line(["-" * n for n in w])] + [line(r) for r in rows])


def verdict(ok: bool) -> str:
    return "MET" if ok else "NOT MET"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=3, help="fresh-process runs per kit, median reported (default 3)")
    ap.add_argument("--quick", action="store_true", help="1 fresh-process run per kit, fewer in-process repeats")
    ap.add_argument("--profile", action="store_true", help="also cProfile one in-process kit build (+ import times)")
    ap.add_argument("--profile-top", type=int, default=10, help="rows of the profile to print (default 10)")
    args = ap.parse_args(argv)
    runs = 1 if args.quick else max(1, args.runs)
    repeats = 2 if args.quick else 5

    script = Path(sys.executable).parent / "partgen"
    if not script.exists():
        sys.exit(f"bench_build: no `partgen` console script next to {sys.executable}; "
                 "run with the project's venv after `pip install -e .`")
    hole_segments = segments_for(BORE_R, BORE_TOL)  # partgen's circle(5.1, 0.01) has this many sides

    load_start = os.getloadavg() if hasattr(os, "getloadavg") else None
    t_start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="partgen-bench-") as tmp:
        scratch = Path(tmp)
        runner = ChildRunner(scratch)
        say(f"python -c 'import partgen.pipeline' x{runs}")
        imp = bench_import(runner, runs)
        kits = []
        for cfg in KITS:
            say(f"partgen build {cfg} x{runs} (fresh processes)")
            kits.append(bench_kit(runner, script, cfg, runs, scratch))
        say(f"single gears {SINGLE_GEARS}, best of {repeats}")
        singles = bench_single_gears(repeats, hole_segments)
        say(f"the default kit's {kits[0]['gears']} gears: bare manifold3d floor vs partgen, best of {repeats}")
        kg = bench_kit_gears(kits[0]["manifest"], repeats, hole_segments)
        say(f"the fresh-process floor x{runs}")
        fresh = bench_fresh_floor(runner, kits[0]["manifest"], runs, hole_segments, scratch)
        bench_s = time.perf_counter() - t_start

        floor = kg["floor_s"]
        imp_s = imp["median"]
        try:
            from importlib.metadata import version
            m3d_version = version("manifold3d")
        except Exception:
            m3d_version = "?"

        out = []
        out.append(f"partgen build benchmark — Python {platform.python_version()}, manifold3d {m3d_version}, "
                   f"{os.cpu_count()} CPUs, {platform.machine()} {platform.system()}")
        if load_start is not None:
            la = lambda l: "/".join(f"{x:.2f}" for x in l)
            out.append(f"load average (1/5/15 min) at start {la(load_start)}, at end {la(os.getloadavg())} "
                       f"— other work on the machine inflates every figure")
        out.append(f"fresh-process runs: {runs} (median), in-process repeats: best of {repeats}; "
                   f"peak RSS via {runner.method}")
        out.append(f"baseline (floor) = bare manifold3d making the default kit's {kg['n']} gears: "
                   f"{floor * 1e3:.1f} ms")

        # 1. whole kits
        rows = [["python -c 'import partgen.pipeline'", f"{imp_s:.3f}", f"{min(imp['walls']):.3f}",
                 f"{imp_s / floor:.1f}x", "-", "-", "-", "-", "-", "-", fmt_rss(*imp["rss"])]]
        for k in kits:
            net = k["median"] - imp_s
            rows.append([f"partgen build {k['cfg']}", f"{k['median']:.3f}", f"{min(k['walls']):.3f}",
                         f"{k['median'] / floor:.1f}x", f"{net:.3f}", f"{net / floor:.1f}x",
                         f"{k['cli_build_s']:.2f}" if k["cli_build_s"] is not None else "?",
                         f"{k['parts']} ({k['distinct']})", str(k["gears"]), f"{k['triangles']:,}",
                         fmt_rss(*k["rss"])])
        out.append("\n1. Whole kit, fresh process (wall time incl. interpreter start, imports, build, write)")
        out.append(table(["command", "median s", "min s", "x floor", "net s", "net x floor", "CLI says s",
                          "parts (distinct)", "gears", "triangles", "peak RSS MB"], rows, "<>>>>>>>>>>"))
        out.append("   net = median minus the import-only median; 'CLI says' = the CLI's own 'wrote ... in X s' "
                   "(load + build + write, after imports)")

        # 2. single gears
        rows = []
        for r in singles:
            rows.append([str(r["teeth"]), f"{r['verts']:,}", f"{r['tri']:,}", f"{r['partgen_s'] * 1e3:.2f}",
                         f"{r['outline_s'] * 1e3:.2f}", f"{r['floor_s'] * 1e3:.2f}",
                         f"{r['partgen_s'] / r['floor_s']:.2f}x", f"{r['floor_tri']:,}"])
        out.append(f"\n2. One gear in-process (module 1.25, 20 deg, auto shift, tol 0.001 mm, {FACE_WIDTH:g} mm, "
                   f"bore r {BORE_R:g} mm)")
        out.append(table(["teeth", "outline verts", "triangles", "partgen ms", "of which outline ms",
                          "floor ms", "partgen/floor", "floor triangles"], rows, ">>>>>>>>"))
        out.append("   partgen ms = gear_body(make_gear(z, ...), 6, circle(5.1, 0.01)).to_mesh(); "
                   "floor ms = CrossSection(same outline) - circle, extrude, to_mesh (outline precomputed)")

        # 3. the kit's gears: floor vs partgen
        teeth = kg["teeth"]
        summary = ", ".join(f"{z}x{teeth.count(z)}" if teeth.count(z) > 1 else str(z)
                            for z in sorted(set(teeth), reverse=True))
        rows = [
            ["bare manifold3d floor (outline given)", f"{floor * 1e3:.1f}", f"{floor / kg['n'] * 1e3:.2f}",
             f"{kg['floor_tri']:,}", "1.00x"],
            ["partgen outline + gear_body + to_mesh", f"{kg['partgen_s'] * 1e3:.1f}",
             f"{kg['partgen_s'] / kg['n'] * 1e3:.2f}", f"{kg['partgen_tri']:,}", f"{kg['partgen_s'] / floor:.2f}x"],
            ["  of which outline generation alone", f"{kg['outline_s'] * 1e3:.1f}",
             f"{kg['outline_s'] / kg['n'] * 1e3:.2f}", "-", f"{kg['outline_s'] / floor:.2f}x"],
        ]
        out.append(f"\n3. The default kit's {kg['n']} gears in-process (teeth {summary}; "
                   f"{kg['verts']:,} outline vertices in all)")
        out.append(table(["path", "total ms", "ms/gear", "triangles", "x floor"], rows, "<>>>>"))

        # the ratio: fresh process against fresh process
        ff, fn = fresh["median"], fresh["numpy"]["median"]
        out.append(f"\nFresh-process floor (the issue's): python + import numpy, manifold3d, trimesh + the default kit's "
                   f"{fresh['n']} gears made from given outlines and written as binary STL by trimesh: {ff:.3f} s "
                   f"(median of {runs})")
        out.append(f"The same floor writing its STLs with numpy (no trimesh import): {fn:.3f} s")
        rows = [[f"partgen build {k['cfg']}", f"{k['median']:.3f}", f"{k['cpu']:.3f}", f"{k['median'] / ff:.2f}x",
                 verdict(k["median"] <= FRESH_TARGET * ff), f"{k['median'] / fn:.2f}x"] for k in kits[:1]]
        out.append(table(["command", "median s", "CPU s (all processes)", "x fresh floor",
                          f"<= {FRESH_TARGET:g}x (issue 26)", "x numpy floor"], rows, "<>>>>>"))

        # targets
        out.append(f"\nTarget (issue): the whole kit within {TARGET_RATIO:g}x the floor "
                   f"(<= {TARGET_RATIO * floor:.3f} s here), under {TARGET_SECONDS:g} s here")
        rows = []
        for k in kits:
            for label, t in (("fresh process", k["median"]), ("net of import", k["median"] - imp_s)):
                rows.append([Path(k["cfg"]).name, label, f"{t:.3f}", f"{t / floor:.1f}x",
                             verdict(t <= TARGET_RATIO * floor), verdict(t < TARGET_SECONDS)])
        out.append(table(["kit", "timing", "s", "x floor", f"<= {TARGET_RATIO:g}x floor",
                          f"< {TARGET_SECONDS:g} s"], rows, "<<>>>>"))
        out.append(f"\n(benchmark itself took {bench_s:.1f} s)")
        print("\n".join(out), flush=True)

        if args.profile:
            profile_kit(scratch, args.profile_top)
    return 0


if __name__ == "__main__":
    sys.exit(main())
