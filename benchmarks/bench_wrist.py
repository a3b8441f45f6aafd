#!/usr/bin/env python
"""Benchmark the wrist gear pair: cutting gear 2's sockets by sweeping gear 1's dome teeth over the
(θ, ψ) workspace, against a naive sweep measured in the same run.

Run with the project's virtualenv:

    .venv/bin/python benchmarks/bench_wrist.py            # full run (~3-4 min)
    .venv/bin/python benchmarks/bench_wrist.py --quick    # smaller resolutions (~1 min)

Every measurement runs in its own fresh child process (this script re-run with --child), so peak
memory never accumulates from one measurement to the next. Peak RSS is the child's ru_maxrss as
returned by os.wait4() for that child alone (exact per child, the same figure as `/usr/bin/time -f
%M`). Times are taken inside the child with time.perf_counter, after the imports. manifold3d is lazy:
each gear is forced with `solid.num_tri()` inside the timed region.

What it measures:

1. build_wrist(spec) at the configs' default resolution (8 × 24) for configs/wrist_sphere.yaml and
   configs/wrist_quasi_ellipsoid.yaml: the pair's time and peak RSS, split into the shared set-up,
   gear 1 and gear 2 (the socket sweep + cap - sweep - bore). The split uses build_wrist's own
   progress messages ("gear1", "gear2 sockets") as timestamps, then forces gear 1 and then gear 2.
   Target (from the issue): each pair under 20 s and under 1 GB here.
2. growth with the sweep resolution (theta_steps × psi_steps, wrist_sphere.yaml): time, peak RSS,
   sweep pieces and gear-2 triangles, with growth exponents fitted against the number of poses.
3. the baseline: a NAIVE sweep, swapped in for partgen.geometry.wrist.socket_sweep so the rest of
   build_wrist is unchanged: every dome at every pose (no reach clip), spheres only (no hull between
   consecutive θ), all pieces in ONE Manifold.batch_boolean union (no batches). Each naive child runs
   under RLIMIT_AS (post-import address space + --naive-mem MB) and a --naive-timeout wall limit;
   one that dies is reported as "exceeded" and larger resolutions are then skipped.
4. at the default resolution: how much the clip removes (pieces kept / dome × pose pieces total).
5. the baseline of the sweep's grouping: the sweep as it was before (every dome's pieces in pose
   order, unioned 256 at a time into one growing accumulator) swapped in, against ours, same run.
6. `partgen build CONFIG -q` end to end in a fresh process, against issue 30's 8 s (2 cores).
The cross gear and its mate (wrist_sphere) are timed alone (1b, 1c).

Nothing here asserts on time: it prints figures and whether the target is met.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import resource
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ("configs/wrist_sphere.yaml", "configs/wrist_quasi_ellipsoid.yaml")
GROWTH_CONFIG = CONFIGS[0]
TARGET_SECONDS, TARGET_MB = 20.0, 1024.0
CLI_TARGET_SECONDS = 8.0  # issue 30: each shipped wrist builds in <= 8 s on 2 cores
FULL_GROWTH = ((4, 12), (6, 18), (8, 24), (12, 36), (16, 48))
FULL_NAIVE = ((4, 12), (8, 24), (12, 36))
QUICK_GROWTH = ((4, 12), (6, 18), (8, 24))
QUICK_NAIVE = ((4, 12), (8, 24))


def say(msg: str) -> None:
    """Progress on stderr, so stdout holds only the report."""
    print(f"  .. {msg}", file=sys.stderr, flush=True)


# ============================================================================ child side
def _vm_size_mb() -> float | None:
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmSize:"):
                return int(line.split()[1]) / 1024
    except OSError:
        pass
    return None


def child_main(job: dict) -> None:
    """One measurement in this (fresh) process; writes a JSON result to job["out"]."""
    t_imp = time.perf_counter()
    import dataclasses

    import manifold3d as m3d
    import numpy as np

    import partgen.geometry.wrist as W
    from partgen.mechanisms.wrist.kit import build_wrist
    from partgen.mechanisms import load_design
    from partgen.mechanisms.wrist.resolve import resolve_wrist
    t_imp = time.perf_counter() - t_imp
    res: dict = {"job": job, "t_import": t_imp}

    def write(status: str) -> None:
        res["status"] = status
        res["rss_self_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        Path(job["out"]).write_text(json.dumps(res))

    if job["mode"] == "import":
        write("ok")
        return

    if job.get("cap_mb"):
        base = _vm_size_mb()
        if base is not None:
            lim = int((base + job["cap_mb"]) * 2**20)
            resource.setrlimit(resource.RLIMIT_AS, (lim, lim))
            res["as_limit_mb"] = base + job["cap_mb"]

    spec = resolve_wrist(load_design(str(ROOT / job["config"])))
    if job["mode"] == "cross":  # the second tooth form alone
        from partgen.geometry.cross_gear import cross_gear
        t0 = time.perf_counter()
        g = cross_gear(spec.cross)
        res.update(t_total=time.perf_counter() - t0, tri=g.num_tri(), teeth=spec.cross.teeth)
        res["t_total"] = time.perf_counter() - t0
        write("ok")
        return
    if job["mode"] == "mate":  # the cross gear's mate alone
        from partgen.geometry.cross_mate import mate_gear
        t0 = time.perf_counter()
        g, fig = mate_gear(spec.cross, spec.mate)
        res.update(tri=g.num_tri(), teeth=spec.mate.teeth, poses=fig["poses"], planes=fig["planes"])
        res["t_total"] = time.perf_counter() - t0
        write("ok")
        return
    spec = dataclasses.replace(spec, cross=None, mate=None)  # the dome pair only: the cross gear is measured alone
    if job.get("theta") is not None:
        spec = dataclasses.replace(spec, theta_steps=job["theta"], psi_steps=job["psi"])
    res["res"] = [spec.theta_steps, spec.psi_steps]

    ours = W.socket_sweep
    sweep_info: dict = {}

    def naive_sweep(domes, poses, grow, reach, segments, batch=None, turn=None):
        """Unclipped, spheres only, one single batch_boolean union of every piece."""
        pieces = []
        for T in np.asarray(poses).reshape(-1, 4, 4):
            R, t = T[:3, :3], T[:3, 3]
            for d in domes:
                p = R @ np.asarray(d.centre) + t
                pieces.append(m3d.Manifold.sphere(d.radius + grow, segments).translate(tuple(float(x) for x in p)))
        return m3d.Manifold.batch_boolean(pieces, m3d.OpType.Add), len(pieces)

    def before_sweep(domes, poses, grow, reach, segments, batch=256, turn=(0.0, 0.0, 0.0)):
        """The sweep as it was before this benchmark's change (the baseline of section 5): every
        dome's pieces in pose order, unioned 256 at a time into one growing accumulator."""
        pieces, acc, count = [], None, 0

        def flush():
            nonlocal acc, pieces
            if pieces:
                part = m3d.Manifold.batch_boolean(pieces, m3d.OpType.Add)
                acc = part if acc is None else m3d.Manifold.batch_boolean([acc, part], m3d.OpType.Add)
                pieces = []
        for b in range(poses.shape[1]):
            for d in domes:
                c, r, prev = np.array(d.centre), d.radius + grow, None
                for a in range(poses.shape[0]):
                    T = poses[a, b]
                    p = T[:3, :3] @ c + T[:3, 3]
                    if np.linalg.norm(p) - r > reach:
                        prev = None
                        continue
                    s = W._ball(r, segments, turn).translate(tuple(p))
                    pieces.append(s if prev is None else m3d.Manifold.batch_hull([prev, s]))
                    count += 1
                    prev = s
                    if len(pieces) >= batch:
                        flush()
        flush()
        return (acc if acc is not None else m3d.Manifold()), count

    impl = {"naive": naive_sweep, "before": before_sweep}.get(job["mode"], ours)

    def timed_sweep(domes, poses, grow, reach, segments, *a, **k):
        t = time.perf_counter()
        out = impl(domes, poses, grow, reach, segments, *a, **k)
        sweep_info.update(call_s=time.perf_counter() - t, domes=len(domes),
                          poses=int(np.prod(np.asarray(poses).shape[:2])), reach=float(reach), segments=segments)
        return out

    W.socket_sweep = timed_sweep  # build_wrist looks it up as W.socket_sweep at call time
    marks: dict = {}
    try:
        t0 = time.perf_counter()
        kit = build_wrist(spec, progress=lambda s: marks.setdefault(s, time.perf_counter()))
        t_ret = time.perf_counter()
        tri1 = kit.parts[0].solid.num_tri()
        t_g1 = time.perf_counter()
        tri2 = kit.parts[1].solid.num_tri()
        t_end = time.perf_counter()
    except MemoryError:
        write("exceeded (MemoryError)")
        return
    finally:
        W.socket_sweep = ours
    g1_mark, g2_mark = marks.get("gear1", t0), marks.get("gear2 sockets", t0)
    res.update(
        t_total=t_end - t0,
        t_setup=g1_mark - t0,
        t_gear1=(g2_mark - g1_mark) + (t_g1 - t_ret),
        t_gear2=(t_ret - g2_mark) + (t_end - t_g1),
        t_sweep_call=sweep_info.get("call_s"),
        t_gear2_eval=t_end - t_g1,
        tri1=tri1, tri2=tri2, vol2=kit.parts[1].solid.volume(),
        pieces=kit.figures["sweep_pieces"], poses=kit.figures["sweep_poses"], domes=len(kit.domes),
        reach=sweep_info.get("reach"), segments=sweep_info.get("segments"),
    )
    res["pieces_total"] = res["domes"] * res["poses"]
    write("ok")


# ============================================================================ parent side
class Runner:
    """Runs one child per measurement: wall time, and peak RSS from os.wait4 (that child only)."""

    def __init__(self, scratch: Path, timeout: float):
        self.scratch, self.timeout, self.n = scratch, timeout, 0

    def run(self, job: dict, timeout: float | None = None) -> dict:
        self.n += 1
        out = self.scratch / f"r{self.n}.json"
        log = self.scratch / f"r{self.n}.log"
        job = dict(job, out=str(out))
        limit = timeout or self.timeout
        with open(log, "w") as lf:
            t0 = time.perf_counter()
            proc = subprocess.Popen([sys.executable, __file__, "--child", json.dumps(job)], cwd=ROOT,
                                    stdout=lf, stderr=lf, start_new_session=True)
            timed_out = False
            while True:
                pid, status, ru = os.wait4(proc.pid, os.WNOHANG)
                if pid:
                    break
                if time.perf_counter() - t0 > limit and not timed_out:
                    timed_out = True
                    os.killpg(proc.pid, signal.SIGKILL)  # the child's own session: only what we started
                time.sleep(0.01)
            wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)  # reaped by wait4; keep Popen from waiting
        r = json.loads(out.read_text()) if out.exists() else {"job": job}
        r["wall"], r["rss_mb"] = wall, ru.ru_maxrss / (2**20 if sys.platform == "darwin" else 1024)
        if timed_out:
            r["status"] = f"exceeded (> {limit:.0f} s)"
        elif "status" not in r:
            code = proc.returncode
            tail = log.read_text().strip().splitlines()[-1:] or [""]
            why = "MemoryError" if "MemoryError" in log.read_text() or "bad_alloc" in log.read_text() else (
                f"signal {-code}" if code < 0 else f"exit {code}")
            r["status"] = f"exceeded ({why})" if job.get("cap_mb") else f"FAILED ({why}: {tail[0][:80]})"
        return r


def fit_exponent(xs, ys) -> float | None:
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x and y and x > 0 and y > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx else None


def ok(r: dict) -> bool:
    return r.get("status") == "ok"


def f_s(v, w=7) -> str:
    return f"{v:{w}.2f}" if v is not None else f"{'-':>{w}}"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="smaller growth and naive resolutions (~1 min)")
    ap.add_argument("--naive-mem", type=float, default=2048.0,
                    help="address-space cap of each naive child, MB above its post-import size (default 2048)")
    ap.add_argument("--naive-timeout", type=float, default=60.0, help="wall limit of each naive child, s (default 60)")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        child_main(json.loads(args.child))
        return 0

    try:
        import manifold3d  # noqa: F401
        import partgen  # noqa: F401
    except ImportError as e:
        sys.exit(f"bench_wrist: cannot import partgen/manifold3d ({e}); run it with the project's venv: "
                 f".venv/bin/python benchmarks/{Path(__file__).name}")
    try:
        from importlib.metadata import version
        m3d_v = version("manifold3d")
    except Exception:  # pragma: no cover
        m3d_v = "?"

    growth = QUICK_GROWTH if args.quick else FULL_GROWTH
    naive_res = QUICK_NAIVE if args.quick else FULL_NAIVE
    load0 = os.getloadavg() if hasattr(os, "getloadavg") else None
    t_start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="bench_wrist-") as tmp:
        run = Runner(Path(tmp), timeout=600.0)
        say("bare import (fresh process)")
        imp = run.run({"mode": "import"})

        defaults = {}
        for cfg in CONFIGS:
            say(f"1. {cfg} at its default resolution")
            defaults[cfg] = run.run({"mode": "ours", "config": cfg, "theta": None, "psi": None})
            if not ok(defaults[cfg]):
                sys.exit(f"bench_wrist: {cfg} failed: {defaults[cfg]['status']}")
        default_res = tuple(defaults[GROWTH_CONFIG]["res"])
        say("1b. the cross gear of wrist_sphere alone")
        cross = run.run({"mode": "cross", "config": "configs/wrist_sphere.yaml"})
        say("1c. the cross gear's mate of wrist_sphere alone")
        mate = run.run({"mode": "mate", "config": "configs/wrist_sphere.yaml"})
        before = {}
        for cfg in CONFIGS:
            say(f"5. {cfg}: the sweep as it was before (baseline), default resolution")
            before[cfg] = run.run({"mode": "before", "config": cfg, "theta": None, "psi": None})
        cli = {}
        for cfg in CONFIGS:
            say(f"6. `partgen build {cfg} -q` end to end")
            t0 = time.perf_counter()
            proc = subprocess.Popen([sys.executable, "-m", "partgen", "build", cfg, "-o", str(Path(tmp) / Path(cfg).stem),
                                     "-q"], cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            _, status, ru = os.wait4(proc.pid, 0)  # that child's own CPU time: the figure a busy machine keeps
            proc.returncode = os.waitstatus_to_exitcode(status)
            cli[cfg] = (time.perf_counter() - t0, proc.returncode, ru.ru_utime + ru.ru_stime)

        ours_at: dict = {default_res: defaults[GROWTH_CONFIG]}
        for th, ps in growth:
            if (th, ps) in ours_at:
                continue
            say(f"2. growth: {GROWTH_CONFIG} at {th}x{ps}")
            ours_at[(th, ps)] = run.run({"mode": "ours", "config": GROWTH_CONFIG, "theta": th, "psi": ps})

        naive_at: dict = {}
        dead = None
        for th, ps in naive_res:
            if dead:
                naive_at[(th, ps)] = {"status": f"skipped (naive died at {dead[0]}x{dead[1]})"}
                continue
            say(f"3. naive sweep: {GROWTH_CONFIG} at {th}x{ps} (cap +{args.naive_mem:.0f} MB, {args.naive_timeout:.0f} s)")
            r = run.run({"mode": "naive", "config": GROWTH_CONFIG, "theta": th, "psi": ps, "cap_mb": args.naive_mem},
                        timeout=args.naive_timeout)
            naive_at[(th, ps)] = r
            if not ok(r):
                dead = (th, ps)
            if (th, ps) not in ours_at:
                say(f"   ours at {th}x{ps} for the ratio")
                ours_at[(th, ps)] = run.run({"mode": "ours", "config": GROWTH_CONFIG, "theta": th, "psi": ps})
    elapsed = time.perf_counter() - t_start

    # ------------------------------------------------------------------ report
    o = []
    o.append(f"partgen wrist benchmark — Python {platform.python_version()}, manifold3d {m3d_v}, "
             f"{os.cpu_count()} CPUs, {platform.machine()} {platform.system()}"
             f"{' (--quick)' if args.quick else ''}")
    if load0:
        la = lambda v: "/".join(f"{x:.2f}" for x in v)  # noqa: E731
        o.append(f"load average (1/5/15 min) at start {la(load0)}, at end {la(os.getloadavg())}")
    o.append("every figure is one fresh child process; time = in-child build_wrist + num_tri() of both gears "
             "(after imports);")
    o.append("wall = whole child incl. interpreter start-up + imports; peak RSS = that child's ru_maxrss (os.wait4).")
    o.append(f"bare `import partgen...` child: wall {imp['wall']:.2f} s, peak RSS {imp['rss_mb']:.0f} MB")
    o.append("")

    o.append("1. the pair at the default resolution")
    hdr = (f"  {'config':<24} {'res':>6} {'pair s':>7} {'setup':>6} {'gear1':>6} {'gear2':>6} {'(sweep':>7} "
           f"{'eval)':>6} {'wall s':>7} {'RSS MB':>7} {'tri1':>7} {'tri2':>7}  target (<{TARGET_SECONDS:.0f} s, <1 GB)")
    o.append(hdr)
    all_met = True
    for cfg, r in defaults.items():
        met_t, met_m = r["t_total"] < TARGET_SECONDS, r["rss_mb"] < TARGET_MB
        met_w = r["wall"] < TARGET_SECONDS
        all_met &= met_t and met_m
        o.append(f"  {Path(cfg).stem:<24} {'x'.join(map(str, r['res'])):>6} {r['t_total']:7.2f} {r['t_setup']:6.2f} "
                 f"{r['t_gear1']:6.2f} {r['t_gear2']:6.2f} {r['t_sweep_call']:7.2f} {r['t_gear2_eval']:6.2f} "
                 f"{r['wall']:7.2f} {r['rss_mb']:7.0f} {r['tri1']:7d} {r['tri2']:7d}  "
                 f"time {'met' if met_t else 'MISSED'} (wall {'met' if met_w else 'missed'}), "
                 f"memory {'met' if met_m else 'MISSED'}")
    o.append("  gear2 = sweep() call (spheres + hulls + lazy union tree) + evaluation of cap - sweep - bore (num_tri).")
    o.append(f"  target: {'MET' if all_met else 'NOT MET'} for both pairs (in-child time and peak RSS).")
    if ok(cross):
        met = cross["t_total"] < 20 and cross["rss_mb"] < 1024
        o.append(f"  cross gear (wrist_sphere, {cross['teeth']} teeth): {cross['t_total']:.2f} s, peak RSS "
                 f"{cross['rss_mb']:.0f} MB, {cross['tri']} triangles — target {'MET' if met else 'NOT MET'}")
    else:
        o.append(f"  cross gear: {cross['status']}")
    if ok(mate):
        o.append(f"  cross gear's mate ({mate['teeth']} teeth, {mate['poses']} sweep poses, {mate['planes']} planes): "
                 f"{mate['t_total']:.2f} s, peak RSS {mate['rss_mb']:.0f} MB, {mate['tri']} triangles")
    else:
        o.append(f"  cross gear's mate: {mate['status']}")
    o.append("")
    o.append("5. the dome pair at the default resolution: the sweep as it was before (every piece in pose order into one "
             "accumulator, 256 at a time) vs ours, same run")
    o.append(f"  {'config':<24} {'before s':>9} {'ours s':>7} {'before/ours':>11} {'before MB':>10} {'ours MB':>8} "
             f"{'before mm3':>11} {'ours mm3':>10}")
    for cfg in CONFIGS:
        b, r_ = before[cfg], defaults[cfg]
        if ok(b):
            o.append(f"  {Path(cfg).stem:<24} {b['t_total']:9.2f} {r_['t_total']:7.2f} {b['t_total'] / r_['t_total']:11.2f} "
                     f"{b['rss_mb']:10.0f} {r_['rss_mb']:8.0f} {b['vol2']:11.2f} {r_['vol2']:10.2f}")
        else:
            o.append(f"  {Path(cfg).stem:<24} before: {b['status']}")
    o.append("")
    o.append(f"6. `partgen build CONFIG -q` end to end (a fresh process: imports, the kit, the files), target "
             f"<= {CLI_TARGET_SECONDS:.0f} s")
    o.append("  wall: as measured (a loaded machine stretches it); CPU: the child's user + sys time, what the wall is "
             "on an idle machine (the build runs on one thread)")
    for cfg, (sec, code, cpu) in cli.items():
        o.append(f"  {Path(cfg).stem:<24} wall {sec:6.2f} s  CPU {cpu:6.2f} s  exit {code}  "
                 f"wall {'met' if code == 0 and sec <= CLI_TARGET_SECONDS else 'missed'}, "
                 f"CPU {'met' if code == 0 and cpu <= CLI_TARGET_SECONDS else 'MISSED'}")
    o.append("")

    o.append("4. the clip at the default resolution (pieces kept / dome x pose pieces total)")
    for cfg, r in defaults.items():
        o.append(f"  {Path(cfg).stem:<24} {r['domes']} domes x {r['poses']} poses = {r['pieces_total']} pieces; "
                 f"kept {r['pieces']} ({100 * r['pieces'] / r['pieces_total']:.1f} %), clip removes "
                 f"{r['pieces_total'] - r['pieces']} ({100 * (1 - r['pieces'] / r['pieces_total']):.1f} %); "
                 f"reach {r['reach']:.2f} mm")
    o.append("")

    o.append(f"2. growth with the sweep resolution ({Path(GROWTH_CONFIG).stem}; x default = ratio to "
             f"{'x'.join(map(str, default_res))} in this run)")
    o.append(f"  {'res':>6} {'poses':>6} {'pieces':>7} {'pair s':>7} {'gear2 s':>8} {'x default':>9} {'RSS MB':>7} "
             f"{'x default':>9} {'tri2':>7} {'gear2 mm3':>10}")
    base = ours_at[default_res]
    rows = sorted(ours_at.items(), key=lambda kv: kv[0][0] * kv[0][1])
    for (th, ps), r in rows:
        if not ok(r):
            o.append(f"  {f'{th}x{ps}':>6} {th * ps:6d}  {r['status']}")
            continue
        o.append(f"  {f'{th}x{ps}':>6} {r['poses']:6d} {r['pieces']:7d} {r['t_total']:7.2f} {r['t_gear2']:8.2f} "
                 f"{r['t_total'] / base['t_total']:9.2f} {r['rss_mb']:7.0f} {r['rss_mb'] / base['rss_mb']:9.2f} "
                 f"{r['tri2']:7d} {r['vol2']:10.1f}")
    good = [r for _, r in rows if ok(r)]
    xs = [r["poses"] for r in good]
    rss_above = [max(r["rss_mb"] - imp["rss_mb"], 1e-3) for r in good]

    def e(v):
        return f"{v:.2f}" if v is not None else "-"
    o.append(f"  growth exponents vs poses (y ∝ poses^e, least squares over {len(good)} points): "
             f"pair time {e(fit_exponent(xs, [r['t_total'] for r in good]))}, "
             f"gear-2 time {e(fit_exponent(xs, [r['t_gear2'] for r in good]))}, "
             f"peak RSS {e(fit_exponent(xs, [r['rss_mb'] for r in good]))} "
             f"(above bare import {e(fit_exponent(xs, rss_above))}), "
             f"pieces {e(fit_exponent(xs, [r['pieces'] for r in good]))}, "
             f"gear-2 triangles {e(fit_exponent(xs, [r['tri2'] for r in good]))}")
    big = [r for r in good if r["poses"] >= base["poses"]]
    if len(big) >= 2:
        o.append(f"  from {'x'.join(map(str, default_res))} up ({len(big)} points): pair time "
                 f"{e(fit_exponent([r['poses'] for r in big], [r['t_total'] for r in big]))}, gear-2 time "
                 f"{e(fit_exponent([r['poses'] for r in big], [r['t_gear2'] for r in big]))}, peak RSS "
                 f"{e(fit_exponent([r['poses'] for r in big], [r['rss_mb'] for r in big]))}")
    o.append("")

    o.append(f"3. baseline: NAIVE sweep (no clip, spheres only, one batch_boolean) vs ours, "
             f"{Path(GROWTH_CONFIG).stem}, same resolution")
    o.append(f"  {'res':>6} {'pieces':>7} {'naive s':>8} {'ours s':>7} {'naive/ours':>10} {'naive MB':>9} {'ours MB':>8} "
             f"{'naive/ours':>10} {'naive tri2':>10} {'naive mm3':>10} {'ours mm3':>10}")
    nv_ok = []
    for (th, ps), nr in naive_at.items():
        orr = ours_at.get((th, ps), {})
        tag = f"{th}x{ps}"
        if not ok(nr):
            extra = f" after {nr['wall']:.1f} s, peak RSS {nr['rss_mb']:.0f} MB" if "wall" in nr else ""
            o.append(f"  {tag:>6} {th * ps * (defaults[GROWTH_CONFIG]['domes']):7d}  naive {nr['status']}{extra}"
                     + (f"; ours {orr['t_total']:.2f} s, {orr['rss_mb']:.0f} MB" if ok(orr) else ""))
            continue
        nv_ok.append(nr)
        o.append(f"  {tag:>6} {nr['pieces']:7d} {nr['t_total']:8.2f} {f_s(orr.get('t_total'))} "
                 f"{nr['t_total'] / orr['t_total']:10.2f} {nr['rss_mb']:9.0f} {orr['rss_mb']:8.0f} "
                 f"{nr['rss_mb'] / orr['rss_mb']:10.2f} {nr['tri2']:10d} {nr['vol2']:10.1f} {orr['vol2']:10.1f}")
    if len(nv_ok) >= 2:
        o.append(f"  naive growth exponents vs poses: time {e(fit_exponent([r['poses'] for r in nv_ok], [r['t_total'] for r in nv_ok]))}, "
                 f"peak RSS {e(fit_exponent([r['poses'] for r in nv_ok], [r['rss_mb'] for r in nv_ok]))}")
    o.append(f"  naive children run under RLIMIT_AS = post-import size + {args.naive_mem:.0f} MB and a "
             f"{args.naive_timeout:.0f} s wall limit; 'exceeded' = killed by one of them.")
    o.append("  the naive cut samples θ (no hulls), so its sockets are slightly smaller: gear 2 keeps a little more volume.")
    o.append("")
    o.append(f"total benchmark time {elapsed:.0f} s")
    print("\n".join(o))
    return 0


if __name__ == "__main__":
    sys.exit(main())
