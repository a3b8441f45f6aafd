#!/usr/bin/env python
"""A seeded sweep of random but plausible designs, as a user tweaking a shipped YAML would make
them: each is built, every STL it writes is read back and verified, and a sample is checked.

    .venv/bin/python benchmarks/sweep.py --designs 300 --seed 1 --mechanism chain
    .venv/bin/python benchmarks/sweep.py --designs 50 --mechanism wrist
    .venv/bin/python benchmarks/sweep.py --designs 5 --mechanism bennett
    .venv/bin/python benchmarks/sweep.py --designs 100 --check-every 5    # check every 5th chain kit

Designs vary the shipped configs' numbers within plausible ranges (the chain: module 1.1–2 mm,
pressure angle 14.5–25°, addendum and dedendum, profile shift, face width, backlash, plate
thickness, clearances 0–0.5 mm radial or diametral, axle 10–12 mm, axial gap, scale, base, crank
and pen sizes, butterfly.yaml or its belt variant; the wrist: its sizes and clearances with a
coarse socket sweep; Bennett: the pinned layout of tests/designs/bennett_fixed.yaml with its part
sizes varied, so no layout search runs). Numbers are rounded as a person types them (0.505,
38.67, 10.99), which is where float32 STLs and coincident radii bite.

Outcomes, one per design: built (every STL one closed, oriented manifold shell read back from the
file, its volume equal to the manifest's), refused (bad input or a design no choice can build: exit
2), crashed (any other exception), bad mesh (build raised MeshError, or a written STL fails the
read-back). A checked chain kit's failed findings are counted by rule, and split into those build
warned about (a design finding naming that rule) and those it did not ("unwarned": the bug).

The script prints counts and never fails on them; tests/test_bench_sweep.py holds the same runner to
zero bad meshes, crashes and unwarned check failures on a small seeded sample.
"""

from __future__ import annotations

import argparse
import collections
import copy
import json
import shutil
import signal
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

from partgen.design.rules import CODES as RULES  # noqa: F401 (the rule codes a check finding can carry)

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "configs"
PRINTER = CONFIGS / "printers" / "fortus450mc.yaml"
MECHANISMS = ("chain", "wrist", "bennett")


def _typed(x: float, digits: int) -> float:
    """A number as a person types it."""
    return float(round(float(x), digits))


def _base(name: str) -> dict:
    d = yaml.safe_load((CONFIGS / f"{name}.yaml").read_text())
    d["printer"] = str(PRINTER)
    return d


def chain_design(rng: np.random.Generator, i: int) -> dict:
    """A random butterfly chain (one in four on GT2 belts)."""
    belt = rng.random() < 0.25
    d = _base("butterfly_belt" if belt else "butterfly")
    u = lambda lo, hi, nd=2: _typed(rng.uniform(lo, hi), nd)  # noqa: E731
    d["name"] = f"chain{i:05d}"
    d["curve"]["scale_mm_per_unit"] = u(25, 45)
    g = d["gears"]
    g["module_mm"] = u(1.1, 2.0)
    g["pressure_angle_deg"] = u(14.5, 25, 1)
    if rng.random() < 0.3:
        g["addendum_coeff"] = u(0.8, 1.2)
    if rng.random() < 0.3:
        g["dedendum_coeff"] = u(1.15, 1.4)
    if rng.random() < 0.2:
        g["profile_shift"] = u(0.0, 0.6)
    g["backlash_per_gear_mm"] = u(0.0, 0.15, 3)
    g["face_width_mm"] = u(8.5, 11, 1) if belt else u(4, 10, 1)
    g["hub_wall_mm"] = u(2, 4, 1)
    g["tip_gap_mm"] = u(0.5, 2, 1)
    g["idler_reach_mm"] = u(0.5, 2, 1)
    d["drive"]["teeth"] = int(rng.integers(30, 51))
    d["drive"]["angle_deg"] = float(rng.choice([-90, -60, -120, 180, 0]))
    d["plates"] = {"thickness_mm": u(3, 6, 1), "boss_wall_mm": u(3, 5, 1)}
    j = {"axle_diameter_mm": u(10, 12)}
    for fit in ("running_clearance", "press_fit_clearance"):
        j[f"{fit}_{rng.choice(['radial', 'diametral'])}_mm"] = u(0.0, 0.5)
    j["axial_gap_mm"] = u(0.3, 0.8, 3)
    d["joints"] = j
    d["base"] = {"thickness_mm": u(4, 10, 1), "leg_height_mm": u(45, 70, 1), "crank_radius_mm": u(25, 45, 1)}
    d["pen"] = {"diameter_mm": u(6, 12, 1), "holder_height_mm": u(12, 30, 1)}
    return d


def wrist_design(rng: np.random.Generator, i: int, coarse: bool = True) -> dict:
    """A random wrist pair: the sphere (with a cross gear half the time) or the quasi-ellipsoid."""
    sphere = rng.random() < 0.5
    d = _base("wrist_sphere" if sphere else "wrist_quasi_ellipsoid")
    u = lambda lo, hi, nd=2: _typed(rng.uniform(lo, hi), nd)  # noqa: E731
    d["name"] = f"wrist{i:05d}"
    w = d["wrist"]
    if not sphere:
        w["nominal_ratio"] = u(0.6, 0.9, 3)
    w["centre_distance_mm"] = u(50, 70, 1)
    w["longitudinal_pitch_mm"] = u(5, 7)
    w["tooth"] = {"shape": "dome", "radius_mm": u(2.4, 3.2), "height_mm": u(2.2, 3.0)}
    w["clearance_radial_mm"] = u(0.1, 0.3)
    w["max_bend_deg"] = u(40, 55, 1)
    if coarse:
        w["sweep"] = {"theta_steps": int(rng.integers(3, 5)), "psi_steps": int(rng.integers(8, 13))}
    w["shaft_diameter_mm"] = u(8, 12)
    w["press_fit_clearance_diametral_mm"] = u(0.0, 0.2)
    w["base_height_mm"] = u(6, 10, 1)
    w["chord_tolerance_mm"] = u(0.02, 0.05, 3)
    if sphere and rng.random() < 0.5:
        teeth = int(rng.choice([20, 24, 28]))
        w["cross_gear"] = {"teeth": teeth, "module_mm": w["centre_distance_mm"] / teeth,
                           "pressure_angle_deg": u(15, 25, 1), "backlash_per_gear_mm": u(0.0, 0.1, 3)}
    else:
        w.pop("cross_gear", None)
    return d


def bennett_design(rng: np.random.Generator, i: int) -> dict:
    """The default Bennett butterfly with its layout pinned (no search) and its parts' sizes varied
    a little (larger changes move the counterweights far and the sizing takes minutes)."""
    d = yaml.safe_load((ROOT / "tests" / "designs" / "bennett_fixed.yaml").read_text())
    d["printer"] = str(PRINTER)
    u = lambda lo, hi, nd=2: _typed(rng.uniform(lo, hi), nd)  # noqa: E731
    d["name"] = f"bennett{i:05d}"
    p = d["parts"]
    p["bar_diameter_mm"] = u(7.5, 8.0)
    p["boss_diameter_mm"] = u(19.5, 20.5)
    p["axial_gap_mm"] = u(0.5, 0.7, 3)
    d["pin"]["clearance_diametral_mm"] = u(0.2, 0.4)
    return d


GENERATORS = {"chain": chain_design, "wrist": wrist_design, "bennett": bennett_design}


@dataclass
class Outcome:
    """What became of one design."""

    mechanism: str
    name: str
    status: str  # built | refused | crashed | bad_mesh
    detail: str = ""
    warned: tuple[str, ...] = ()  # the rules build warned about
    checked: bool = False
    fails: tuple[tuple[str, bool], ...] = ()  # (rule, warned by build) of each failed check finding
    messages: tuple[str, ...] = ()  # the failed findings' messages
    seconds: float = 0.0
    parts: int = 0
    design: dict = field(default_factory=dict, repr=False)


def verify_written(dest: Path, man: dict) -> list[str]:
    """Problems of the STLs in a written kit: read each back, merge as a slicer does, and compare
    its volume with the manifest's."""
    from partgen.export.verify import mesh_report, read_stl

    out = []
    for p in man["parts"]:
        rep = mesh_report(*read_stl((dest / p["file"]).read_bytes()))
        if not rep.ok:
            out.append(f"{p['name']}: {', '.join(rep.problems())}")
        elif abs(rep.volume_mm3 - p["volume_mm3"]) > 1e-3 + 1e-7 * abs(p["volume_mm3"]):
            out.append(f"{p['name']}: volume {rep.volume_mm3:.4f} mm³ read back, manifest says {p['volume_mm3']}")
    return out


def finding_rule(f) -> str:
    """The rule a check finding is about: its ``rule`` when it names one, else its check."""
    return getattr(f, "rule", "") or f.check


def run_one(mechanism: str, design: dict, workdir: Path, check: bool = False, samples: int = 36) -> Outcome:
    """Build one design (and check it if asked), classifying what happens."""
    from partgen import pipeline
    from partgen.errors import MeshError, PartgenError

    workdir.mkdir(parents=True, exist_ok=True)
    path = workdir / f"{design['name']}.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False))
    dest = workdir / design["name"]
    t0 = time.perf_counter()
    out = Outcome(mechanism, design["name"], "built", design=design)
    try:
        loaded, kit, man, dest = pipeline.build(path, dest)
    except MeshError as e:
        out.status, out.detail = "bad_mesh", str(e)
    except PartgenError as e:
        out.status, out.detail = "refused", str(e)
    except Exception as e:  # noqa: BLE001 - the sweep counts crashes, it does not hide them
        out.status, out.detail = "crashed", f"{type(e).__name__}: {e}\n{traceback.format_exc(limit=-4)}"
    if out.status == "built":
        out.parts = len(man["parts"])
        bad = verify_written(dest, man)
        if bad:
            out.status, out.detail = "bad_mesh", "; ".join(bad)
        out.warned = tuple(sorted({f.rule for f in loaded.mechanism.findings(loaded.spec) if f.severity == "warn"}))
    if out.status == "built" and check and mechanism == "chain":
        try:
            _, _, result, _ = pipeline.check(dest, samples=samples, write_plates=False)
            out.checked = True
            failed = [f for f in result.findings if f.severity == "fail"]
            out.fails = tuple((finding_rule(f), finding_rule(f) in out.warned or f.check == "design") for f in failed)
            out.messages = tuple(f.message for f in failed)
        except Exception as e:  # noqa: BLE001
            out.status, out.detail = "crashed", f"check: {type(e).__name__}: {e}\n{traceback.format_exc(limit=-4)}"
    out.seconds = time.perf_counter() - t0
    return out


def designs(mechanism: str, n: int, seed: int):
    """The n designs of a mechanism for a seed (the same every run)."""
    rng = np.random.default_rng([seed, MECHANISMS.index(mechanism)])
    return [GENERATORS[mechanism](rng, i) for i in range(n)]


def summarize(outcomes: list[Outcome]) -> dict:
    """Counts per mechanism: built / refused / crashed / bad meshes / checked / check failures by rule."""
    out = {}
    for mech in MECHANISMS:
        rows = [o for o in outcomes if o.mechanism == mech]
        if not rows:
            continue
        c = collections.Counter(o.status for o in rows)
        fails = collections.Counter(rule for o in rows for rule, _ in o.fails)
        unwarned = collections.Counter(rule for o in rows for rule, w in o.fails if not w)
        out[mech] = {"designs": len(rows), "built": c["built"], "refused": c["refused"], "crashed": c["crashed"],
                     "bad_mesh": c["bad_mesh"], "checked": sum(o.checked for o in rows),
                     "checked_failing": sum(bool(o.fails) for o in rows),
                     "checked_failing_unwarned": sum(any(not w for _, w in o.fails) for o in rows),
                     "check_failures_by_rule": dict(fails), "unwarned_failures_by_rule": dict(unwarned),
                     "refusals": dict(collections.Counter(_refusal_kind(o.detail) for o in rows
                                                          if o.status == "refused").most_common(8)),
                     "seconds": round(sum(o.seconds for o in rows), 1)}
    return out


def _refusal_kind(msg: str) -> str:
    """A refusal's key path and the first words of its problem ("file: key: problem")."""
    parts = msg.split(": ", 2)
    key, problem = (parts[1], parts[2]) if len(parts) == 3 else ("", parts[-1])
    return f"{key}: {' '.join(problem.split()[:6])}"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--designs", type=int, default=20, help="designs per mechanism")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--mechanism", choices=MECHANISMS + ("all",), default="all")
    ap.add_argument("--check-every", type=int, default=5, help="check every k-th built chain kit (0: none)")
    ap.add_argument("--samples", type=int, default=36, help="crank angles of each check")
    ap.add_argument("--start", type=int, default=0, help="skip the first designs of the seed (to resume)")
    ap.add_argument("--json", type=Path, help="also write every outcome to this file")
    ap.add_argument("--verbose", action="store_true", help="print every bad mesh, crash and unwarned failure")
    args = ap.parse_args(argv)
    mechs = MECHANISMS if args.mechanism == "all" else (args.mechanism,)
    outcomes: list[Outcome] = []
    t0 = time.perf_counter()
    signal.signal(signal.SIGTERM, signal.default_int_handler)  # a stopped run reports what it finished
    with tempfile.TemporaryDirectory(prefix="partgen-sweep-") as tmp:
        try:
            for mech in mechs:
                built = 0
                for k, d in enumerate(designs(mech, args.start + args.designs, args.seed)[args.start:]):
                    work = Path(tmp) / d["name"]
                    work.mkdir()
                    check = args.check_every > 0 and mech == "chain" and built % args.check_every == 0
                    o = run_one(mech, d, work, check, args.samples)
                    built += o.status == "built"
                    outcomes.append(o)
                    shutil.rmtree(work, ignore_errors=True)
                    mark = {"built": ".", "refused": "r", "crashed": "C", "bad_mesh": "M"}[o.status]
                    if o.status == "built" and any(not w for _, w in o.fails):
                        mark = "F"
                    print(mark, end="", file=sys.stderr, flush=True)
                    if args.verbose and (o.status in ("crashed", "bad_mesh") or any(not w for _, w in o.fails)):
                        print(f"\n{o.name} {o.status}: {o.detail[:600]} "
                              f"{[m for (r, w), m in zip(o.fails, o.messages) if not w][:6]}\n"
                              f"  {json.dumps(o.design.get('gears') or o.design.get('wrist') or o.design.get('parts'))}\n"
                              f"  {json.dumps(o.design.get('joints', {}))} {json.dumps(o.design.get('plates', {}))} "
                              f"{json.dumps(o.design.get('curve', {}).get('scale_mm_per_unit'))}", file=sys.stderr)
                print(file=sys.stderr)
        except KeyboardInterrupt:
            print(f"\ninterrupted: the counts below are of the {len(outcomes)} designs finished", file=sys.stderr)
    summary = summarize(outcomes)
    print(f"seed {args.seed}, designs {args.start}..{args.start + args.designs - 1} per mechanism, "
          f"{time.perf_counter() - t0:.0f} s")
    for mech, s in summary.items():
        print(f"{mech:8s} designs {s['designs']:5d}  built {s['built']:5d}  refused {s['refused']:5d}  "
              f"crashed {s['crashed']:3d}  bad meshes {s['bad_mesh']:3d}  checked {s['checked']:4d}  "
              f"failing check {s['checked_failing']:3d} (unwarned {s['checked_failing_unwarned']})  [{s['seconds']} s]")
        if s["check_failures_by_rule"]:
            print(f"         check failures by rule: {s['check_failures_by_rule']}; "
                  f"unwarned: {s['unwarned_failures_by_rule']}")
        if s["refusals"]:
            print(f"         refusals: {s['refusals']}")
    if args.json:
        args.json.write_text(json.dumps({"summary": summary, "outcomes": [
            {k: v for k, v in o.__dict__.items()} for o in outcomes]}, indent=1, default=str))
    return 0


if __name__ == "__main__":
    sys.exit(main())
