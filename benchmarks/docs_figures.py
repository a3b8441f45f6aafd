"""Measure every figure the docs state and write them to docs/figures.json.

The docs never type a measured figure by hand: a page writes ``{{ fig.section.key }}`` (a number or a
word) or ``{{ table.name }}`` (a Markdown table), and the docs build (scripts/docs_hooks.py) puts in
what this script measured; an unknown key fails the strict build. Each section runs the commands a
user would (``partgen … --json``) on the shipped designs, in fresh processes, and keeps what they
print, rounded for reading.

    .venv/bin/python benchmarks/docs_figures.py                  # every section (a few minutes)
    .venv/bin/python benchmarks/docs_figures.py --only gear_pair # one section; the others are kept
    .venv/bin/python benchmarks/docs_figures.py --list           # the sections

Run it after a change that moves a figure (a design, a check, the tolerance model) and commit
docs/figures.json with the change. Every section records when it ran, with which partgen, and how long
it took (``fig.<section>._run``).
"""

from __future__ import annotations

import argparse
import math
import datetime
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "figures.json"
PRINTERS = sorted(p.stem for p in (ROOT / "partgen" / "printers").glob("*.yaml"))


def partgen(*args: str, ok=(0,)) -> dict:
    """``partgen ARGS --json`` in a fresh process; its JSON object."""
    cmd = [sys.executable, "-m", "partgen", *args, "--json"]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode not in ok:
        raise SystemExit(f"{' '.join(cmd[2:])}: exit {p.returncode}\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
    return json.loads(p.stdout)


def r(x: float, digits: int = 2) -> float | int:
    """Rounded for reading (``-0.0`` never shows; 0 digits gives a whole number)."""
    return int(round(float(x))) if digits <= 0 else round(float(x), digits) + 0.0


def pct(p: float, digits: int = 1) -> float:
    return r(100 * p, digits)


def table(columns: list[str], rows: list[list]) -> dict:
    return {"columns": columns, "rows": rows}


def manifest(tmp: Path, config: str, *extra: str) -> dict:
    dest = tmp / Path(config).stem
    partgen("build", config, "-o", str(dest), *extra)
    return json.loads((dest / "manifest.json").read_text())


# --- sections ---------------------------------------------------------------------------------------

def chain(tmp: Path) -> dict:
    """The default chain against the paper's, the pruned curve, the belt variant, the desktop kit."""
    t = partgen("trace", "configs/butterfly.yaml", "-o", str(tmp / "trace"))
    pruned = t["pruned_vs_full"]
    ours = manifest(tmp, "configs/butterfly.yaml")["design"]
    paper = manifest(tmp, "configs/butterfly_liu2017.yaml")["design"]
    rows = []
    for a, b in zip(paper["stages"], ours["stages"]):
        ta, tb = a["teeth"], b["teeth"]
        same = [k for k in "DMG" if ta[k] == tb[k]]
        rows.append([a["j"], a["ratio"], "/".join(str(ta[k]) for k in "DMG"), "/".join(str(tb[k]) for k in "DMG"),
                     "all" if len(same) == 3 else ", ".join(same) or "none"])
    belt = partgen("trace", "configs/butterfly_belt.yaml", "-o", str(tmp / "belt_trace"))["vs_pruned"]
    modules = []
    for p in PRINTERS:
        dest = tmp / p
        b = partgen("build", "configs/butterfly_desktop.yaml", "-o", str(dest), "--printer", p, ok=(0, 2))
        if b.get("ok") is False and "error" in b:
            modules.append([f"`{p}`", "refused: " + b["error"]["message"].split(": ", 2)[-1]])
        else:
            modules.append([f"`{p}`", json.loads((dest / "manifest.json").read_text())["design"]["module_mm"]])
    return {
        "links": len(t["speeds"]),
        "pruned_max_mm": r(pruned["max_deviation_mm"], 1), "pruned_rms_mm": r(pruned["rms_mm"], 1),
        "pruned_hausdorff_mm": r(pruned["hausdorff_mm"], 1),
        "default_module_mm": ours["module_mm"], "paper_module_mm": paper["module_mm"],
        "teeth": table(["link j", "Eq 11 ratio", "paper D/M/G", "default D/M/G", "same as the paper"], rows),
        "belt_max_mm": r(belt["max_deviation_mm"], 3), "belt_rms_mm": r(belt["rms_mm"], 2),
        "desktop_modules": table(["printer", "module chosen (mm)"], modules),
    }


def drawn(tmp: Path) -> dict:
    """The shipped drawings: links kept and the measured deviation of the kit's pen from the drawing."""
    rows, out = [], {}
    for name in ("heart", "star", "letter_e"):
        t = partgen("trace", f"configs/{name}.yaml", "-o", str(tmp / name))
        rows.append([f"`{name}.yaml`", t["drawing"], t["drawing_samples"], t["parametrisation"], len(t["speeds"]),
                     r(t["hausdorff_mm"], 1), r(t["max_deviation_mm"], 1), r(t["rms_mm"], 1)])
        out[name] = {"links": len(t["speeds"]), "hausdorff_mm": r(t["hausdorff_mm"], 1)}
    out["table"] = table(["design", "drawing", "samples", "by", "links", "Hausdorff mm", "max, same θ mm", "RMS mm"],
                         rows)
    return out


def gear_pair(tmp: Path) -> dict:
    """The gear pair's measured backlash and transmission error, and its tolerance study."""
    t = partgen("trace", "configs/gear_pair.yaml", "-o", str(tmp / "trace"))
    tol = partgen("tolerance", "configs/gear_pair.yaml", "--samples", "20000", "--workers", "1", "-o",
                  str(tmp / "tol"))
    wide = partgen("tolerance", "configs/gear_pair.yaml", "--samples", "20000", "--workers", "1",
                   "--accuracy-mm", "0.3", "-o", str(tmp / "tol3"))
    kinds = {k["kind"]: k["share"] for k in tol["sensitivity"]["by_kind"]}
    return {
        "backlash_min_mm": r(t["backlash_mm"]["min"], 3), "backlash_max_mm": r(t["backlash_mm"]["max"], 3),
        "te_pp_um": r(1000 * t["transmission_error_mm"]["peak_to_peak"], 1),
        "tol_samples": tol["samples"], "tol_accuracy_mm": tol["accuracy_mm"],
        "p_jam_pct": pct(tol["overall"]["probability"], 2),
        "p_jam_mesh_pct": pct(tol["groups"]["mesh"]["probability"], 2),
        "tooth_share_pct": pct(kinds.get("tooth", 0), 0), "position_share_pct": pct(kinds.get("position", 0), 0),
        "p_jam_03_pct": pct(wide["overall"]["probability"], 1),
    }


def gear_train(tmp: Path) -> dict:
    """Each shipped train traced on its printed outlines."""
    rows = []
    for name in ("reducer", "herringbone", "planetary", "rack"):
        t = partgen("trace", f"configs/gear_train_{name}.yaml", "-o", str(tmp / name))
        if "backlash_arcmin" in t:
            te = f"{r(t['transmission_error_arcmin']['peak_to_peak'])} arcmin"
            bl = f"{r(t['backlash_arcmin']['min'], 1)}–{r(t['backlash_arcmin']['max'], 1)} arcmin"
            ratio = f"{t['ratio_measured']:.5f} (design {r(t['ratio_design'], 4)})"
        else:
            te = f"{r(t['transmission_error_um']['peak_to_peak'], 1)} µm"
            bl = f"{r(t['backlash_mm']['min'], 3)}–{r(t['backlash_mm']['max'], 3)} mm"
            ratio = f"{t['ratio_measured']:.5f} {t.get('ratio_unit', '')} (design {r(t['ratio_design'], 4)})"
        rows.append([f"`gear_train_{name}`", ratio, te, bl, t["samples"]])
    return {"trace": table(["design", "ratio measured", "TE peak to peak", "backlash at the output", "angles"], rows)}


def tolerance(tmp: Path) -> dict:
    """P(jam) of the default chain and of the paper's design as printed."""
    out = {}
    for name in ("butterfly", "butterfly_liu2017"):
        t = partgen("tolerance", f"configs/{name}.yaml", "--samples", "10000", "--seed", "0", "-o", str(tmp / name))
        units = sorted(t["units"], key=lambda u: -u["probability"])
        worst = units[0]
        kinds = {k["kind"]: k["share"] for k in t["sensitivity"]["by_kind"]}
        g = t["groups"]
        joints = [u for u in t["units"] if u["group"] == "joint"]
        meshes = [u for u in t["units"] if u["group"] == "mesh"]
        out[name] = {
            "samples": t["samples"], "accuracy_mm": t["accuracy_mm"],
            "p_jam_pct": pct(t["overall"]["probability"], 0),
            "joint_pct": pct(g["joint"]["probability"], 1), "mesh_pct": pct(g["mesh"]["probability"], 1),
            "joints": len(joints), "meshes": len(meshes),
            "joint_each_pct": f"{pct(min(u['probability'] for u in joints))}–{pct(max(u['probability'] for u in joints))}"
            if joints else "–",
            "mesh_each_pct": f"{pct(min(u['probability'] for u in meshes))}–{pct(max(u['probability'] for u in meshes))}"
            if meshes else "–",
            "worst_unit": worst["unit"], "worst_pct": pct(worst["probability"]),
            "worst_ci_pct": f"{pct(worst['ci95'][0])}–{pct(worst['ci95'][1])}",
            "tooth_share_pct": pct(kinds.get("tooth", 0), 0), "position_share_pct": pct(kinds.get("position", 0), 0),
        }
    return out


def sweep(tmp: Path) -> dict:
    """The backlash × running-fit trade-off of the default chain."""
    s = partgen("sweep", "configs/butterfly.yaml", "--vary", "gears.backlash_per_gear_mm=0.05:0.15:3", "--vary",
                "joints.running_clearance_diametral_mm=0.1:0.3:3", "--tolerance-samples", "2000", "-o",
                str(tmp / "sweep"))
    rows = []
    for row in s["rows"]:
        v, p = row["values"], row.get("jam_probability")
        rows.append([v["gears.backlash_per_gear_mm"], v["joints.running_clearance_diametral_mm"], row["status"],
                     f"{pct(p)} %" if p is not None else "–", row.get("mass_g", "–")])
    return {"points": s["points"], "pass": s["pass"], "samples": 2000,
            "table": table(["backlash per gear mm", "running fit mm (diametral)", "check", "P(jam)", "mass g"], rows)}


def bennett(tmp: Path) -> dict:
    """The Bennett butterfly's balance, clearance, stance and pins, from its check; the pins' clearance
    auto chooses (mechanisms.autoplay, role running)."""
    key = "pin.clearance_diametral_mm"
    a = partgen("build", "configs/bennett_butterfly.yaml", "--set", f"{key}=auto", "-o", str(tmp / "auto"))["auto_play"]
    auto = {"value_mm": a["values"][key], "p_pct": r(100 * a["probability"]), "buys": a["buys"].get(key, 0),
            "samples": f"{a['samples']:,}", "fits": a["joints"]}
    f = partgen("check", "configs/bennett_butterfly.yaml", "-o", str(tmp / "kit"), "--no-plates")["figures"]
    b, base = f["balance_mm"], f["base"]
    short = [v for k, v in b.items() if k.startswith("one_slug_short")]
    pins = sorted(f["pins"]["count_by_length"].items(), key=lambda kv: float(kv[0]))
    return {
        "com_printed_mm": float(f"{b['fdm']:.1g}"), "com_solid_mm": r(b["solid"]),
        "com_infill_error_mm": r(b["fdm_infill_error"]), "com_no_binder_mm": r(b["no_binder"]),
        "com_slug_short_mm": f"{r(min(short), 0)}–{r(max(short), 0)}",
        "least_clearance_mm": r(f["least_clearance_mm"]), "least_clearance_parts": " and ".join(f["least_clearance_parts"]),
        "step_deg": r(f["step_deg"]), "free_from_deg": r(f["free_range_deg"][0], 1),
        "free_to_deg": r(f["free_range_deg"][1], 1),
        "tip_angle_deg": r(base["tip_angle_deg"], 0), "com_margin_mm": r(base["margin_mm"], 0),
        "com_height_mm": r(base["com_height_mm"], 0), "links_above_table_mm": r(base["links_above_table_mm"], 0),
        "total_g": r(base["total_g"], 0),
        "pins": ", ".join(f"{n} × {float(length):g}" for length, n in pins),
        "pin_count": sum(n for _, n in pins), "auto": auto,
    }


def calibrate(tmp: Path) -> dict:
    """The gear pair on the MK4 with the example coupon's biases, compensated in the STLs and not."""
    import yaml

    prof = tmp / "mk4_measured.yaml"
    partgen("calibrate", "--printer", "prusa_mk4", "configs/calibration/example_results.yaml", "-o", str(prof))
    raw = yaml.safe_load(prof.read_text())
    raw.setdefault("biases", {})["compensate"] = False
    loose = tmp / "mk4_uncompensated.yaml"
    loose.write_text(yaml.safe_dump(raw, sort_keys=False))
    out = {}
    for key, profile in (("compensated", prof), ("uncompensated", loose)):
        t = partgen("tolerance", "configs/gear_pair.yaml", "--printer", str(profile), "--samples", "20000",
                    "--workers", "1", "-o", str(tmp / key))
        out[f"p_jam_{key}_pct"] = pct(t["overall"]["probability"], 2)
    out["samples"] = 20000
    return out


def wrist(tmp: Path) -> dict:
    """The wrist pairs' check: poses, the least engaged volume, bend and twist play over the bend; the
    cross gear's mate: overlap, backlash, ratio and transmission error; the radial clearance auto
    chooses for the quasi-ellipsoidal pair."""
    rows, mates = [], []
    for name in ("wrist_sphere", "wrist_quasi_ellipsoid"):
        f = partgen("check", f"configs/{name}.yaml", "--no-plates", "-o", str(tmp / name))["figures"]
        play = f["play"]
        bend = [p["bend_play_deg"] for p in play]
        rows.append([f"`{name}.yaml`", f["poses"], r(f["min_engaged_mm3"], 0), f"{min(bend)}–{max(bend)}",
                     play[0]["twist_play_deg"], play[-1]["twist_play_deg"], play[-1]["theta_deg"]])
        if "mate" in f:  # the cross gear's mate: the check's overlap and backlash, the trace's ratio and error
            m = f["mate"]
            t = partgen("trace", f"configs/{name}.yaml", "-o", str(tmp / f"{name}_trace"))["mate"]
            mates.append([f"`{name}.yaml`", m["poses"], f"{m['max_overlap_mm3']:.5f}", m["epsilon_mm3"],
                          f"{m['backlash_min_mm']:.3f}–{m['backlash_max_mm']:.3f}", t["backlash_mid_mm"],
                          f"{t['ratio']:.9f}", f"{t['ratio_error']:.1e}", t["te_pp_um"]])
    # auto: the least radial socket clearance that meets the target (mechanisms.autoplay, role radial)
    key = "wrist.clearance_radial_mm"
    a = partgen("build", "configs/wrist_quasi_ellipsoid.yaml", "--set", f"{key}=auto", "-o", str(tmp / "wrist_auto"))
    a = a["auto_play"]
    auto = {"value_mm": a["values"][key], "p_pct": r(100 * a["probability"]), "buys": a["buys"].get(key, 0),
            "samples": f"{a['samples']:,}"}
    return {"auto": auto,
            "table": table(["design", "poses", "least engaged mm³", "bend play °", "twist play at the pole °",
                            "twist play at the edge °", "edge θ °"], rows),
            "mate": table(["design", "poses", "largest overlap mm³", "ε mm³", "backlash mm (3-D)",
                           "backlash mm (mid-plane)", "ratio", "ratio error", "transmission error µm p-p"], mates)}


def printers(tmp: Path) -> dict:
    """Which shipped printers each shipped design passes ``partgen check`` on, as it is (the wrist
    pairs left out: their check takes minutes each)."""
    rows = []
    for cfg in sorted((ROOT / "configs").glob("*.yaml")):
        if cfg.stem.startswith("wrist"):
            continue
        row = [f"`{cfg.name}`"]
        for p in PRINTERS:
            out = partgen("check", f"configs/{cfg.name}", "--printer", p, "--no-plates", "-o",
                          str(tmp / cfg.stem / p), ok=(0, 1, 2))
            if out.get("ok"):
                row.append("✓")
            elif "error" in out:
                row.append("refused")
            else:
                failed = dict.fromkeys(f.get("rule") or f.get("check") for f in out.get("findings", [])
                                       if f.get("severity") == "fail")
                row.append("✗ " + ", ".join(str(k) for k in failed))
        rows.append(row)
        print(f"  {cfg.name}: {' | '.join(row[1:])}", file=sys.stderr, flush=True)
    return {"table": table(["design", *[f"`{p}`" for p in PRINTERS]], rows)}


def bevel(tmp: Path) -> dict:
    """The bevel pairs: the shipped mitre pair and a 120° one, checked and traced; their flanks on the
    float32 mesh against the exact spherical involute (partgen.testing.measure_bevel_flanks)."""
    import numpy as np
    import trimesh
    import yaml

    from partgen import pipeline
    from partgen.geometry.solid import mesh_arrays
    from partgen.mechanisms.bevel.kit import build_bevel
    from partgen.testing import measure_bevel_flanks

    d = yaml.safe_load((ROOT / "configs" / "bevel_mitre.yaml").read_text())
    d.update(name="bevel_120", shaft_angle_deg=120.0)
    d["gears"]["face_width_mm"] = 7.0
    wide = tmp / "bevel_120.yaml"
    wide.write_text(yaml.safe_dump(d, sort_keys=False))
    out = {}
    for key, cfg in (("mitre", "configs/bevel_mitre.yaml"), ("s120", str(wide))):
        c = partgen("check", cfg, "-o", str(tmp / f"{key}_check"))
        t = partgen("trace", cfg, "-o", str(tmp / f"{key}_trace"))
        spec = pipeline.load(ROOT / cfg if not Path(cfg).is_absolute() else Path(cfg)).spec
        kit = build_bevel(spec)
        worst, mean = 0.0, []
        for name, g in (("gear1", spec.gear1), ("gear2", spec.gear2)):
            v, f = mesh_arrays(kit.part(name).solid)
            mesh = trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)
            m = measure_bevel_flanks(mesh, g.teeth, g.module, g.pressure_angle, g.pitch_angle, g.backlash,
                                     g.face_width, g.addendum, g.dedendum)
            worst, mean = max(worst, m.worst), mean + [float(m.deviation.mean())]
        f = c["figures"]
        out[key] = {"pitch_angles_deg": " + ".join(f"{math.degrees(g.pitch_angle):.2f}" for g in spec.pair.gears),
                    "base_angles_deg": " + ".join(f"{math.degrees(g.base_angle):.2f}" for g in spec.pair.gears),
                    "cone_distance_mm": r(spec.pair.cone_distance, 3), "contact_ratio": r(spec.pair.contact_ratio(), 2),
                    "flank_worst_um": r(1000 * worst, 2), "flank_mean_um": r(1000 * float(np.mean(mean)), 2),
                    "overlap_mm3": f["max_overlap_mm3"], "check_samples": f["samples"],
                    "backlash_min_mm": r(f["backlash_mm"]["min"], 3), "backlash_max_mm": r(f["backlash_mm"]["max"], 3),
                    "te_pp_um": r(1000 * t["transmission_error_mm"]["peak_to_peak"], 1),
                    "ratio_error": f"{t['ratio_relative_error']:.0e}" if t["ratio_relative_error"] else "0", "check_s": r(c["seconds"], 1)}
    return out


def jam(tmp: Path) -> dict:
    """P(jam) of every shipped design on its printer (and the desktop chain on every desktop
    printer): the linear study, 10,000 prints, seed 0 (benchmarks/shipped_jam.py), and the default
    chain as it was before its play was designed (backlash 0.05 mm per gear, fits 0.2 mm)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from shipped_jam import DESKTOP, figures as jam_of

    names = sorted(p.stem for p in (ROOT / "configs").glob("*.yaml"))
    jobs = [(n, None, ()) for n in names] + [("butterfly_desktop", p, ()) for p in DESKTOP]
    rows, over, desktop = [], [], {}
    for name, printer, sets in jobs:
        f = jam_of(name, 10_000, printer, sets)
        lo, hi = f["ci95"]
        if name == "butterfly_desktop" and printer is not None:  # the quick start's figure, printer by printer
            desktop[printer] = {"pct": pct(f["probability"], 2), "worst_pct": pct(f["worst"], 1)}
        if f["probability"] > 0.01:
            over.append(name)
        rows.append([f"`{name}.yaml`", f"{f['printer']} ±{f['accuracy_mm']:g}",
                     f"{100 * f['probability']:.2f} % ({100 * lo:.2f}–{100 * hi:.2f})"
                     + (" **over 1 %**" if f["probability"] > 0.01 else ""),
                     f"{100 * f['worst']:.2f} %", f["top"]])
    old = jam_of("butterfly", 10_000, None, ("gears.backlash_per_gear_mm=0.05", "joints.running_clearance_diametral_mm=0.2"))
    # the shipped designs' play as it was before it was designed for: what the change bought
    before = []
    for name, sets, why in (
            ("butterfly", ("gears.backlash_per_gear_mm=0.05", "joints.running_clearance_diametral_mm=0.2"), "0.05 mm backlash, 0.2 mm fits"),
            ("heart", ("gears.backlash_per_gear_mm=0.05", "joints.running_clearance_diametral_mm=0.2"), "0.05 mm backlash, 0.2 mm fits"),
            ("gear_train_reducer", ("shafts.running_clearance_diametral_mm=0.1",), "the Fortus profile's 0.1 mm running fits"),
            ("gear_train_planetary", ("gears.backlash_per_gear_mm=0.1",), "0.1 mm backlash per gear"),
            ("wrist_sphere", ("wrist.clearance_radial_mm=0.15",), "0.15 mm radial socket clearance"),
            ("bennett_butterfly", ("checks.balance_tolerance_mm=0.1",), "0.1 mm balance tolerance")):
        f = jam_of(name, 10_000, None, sets)
        now = next(row for row in rows if row[0] == f"`{name}.yaml`")
        before.append([f"`{name}.yaml`", why, f"{100 * f['probability']:.2f} %", now[2].split(" (")[0], f["top"]])
    return {"shipped": table(["design", "printer", "P(jam) seated (95 % CI)", "worst case", "jams most at"], rows),
            "before": table(["design", "as it was", "P(jam) then", "P(jam) now", "jammed most at"], before),
            "over_target": ", ".join(over) or "none", "designs": len(names), "desktop": desktop,
            "desktop_max_pct": max(d["pct"] for d in desktop.values()),
            "chain_as_it_was_pct": pct(old["probability"], 1), "chain_as_it_was_worst_pct": pct(old["worst"], 1)}


def exact(tmp: Path) -> dict:
    """The exact Monte Carlo against the linear study: `partgen tolerance --exact 200` on the gear
    pair at ±0.3 mm and on the default chain on its Fortus and at ±0.2 mm."""
    rows = []
    out = {}
    for key, config, extra in (("pair_03", "configs/gear_pair.yaml", ("--accuracy-mm", "0.3")),
                               ("chain", "configs/butterfly.yaml", ()),
                               ("chain_02", "configs/butterfly.yaml", ("--accuracy-mm", "0.2"))):
        t = partgen("tolerance", config, "--exact", "200", "--samples", "20000", "--seed", "0", *extra,
                    "-o", str(tmp / key))
        e, lin = t["exact"], t["overall"]
        lo, hi = lin["ci95"]
        elo, ehi = e["ci95"]
        agree = "agree" if e["agrees"] else "**disagree**"
        rows.append([f"`{Path(config).name}{' ' + ' '.join(extra) if extra else ''}`", f"±{t['accuracy_mm']:g}",
                     f"{100 * lin['probability']:.2f} % ({100 * lo:.2f}–{100 * hi:.2f})",
                     f"{100 * e['probability']:.2f} % ({100 * elo:.2f}–{100 * ehi:.2f})", agree,
                     f"{100 * t['worst_case']['probability']:.2f} %"])
        out[key] = {"linear_pct": pct(lin["probability"], 2), "exact_pct": pct(e["probability"], 2),
                    "exact_ci_pct": f"{pct(elo, 2)}–{pct(ehi, 2)}", "agree": agree == "agree"}
    out["table"] = table(["design", "accuracy", "linear, seated (20,000 prints)", "exact, seated (200 prints)",
                          "intervals", "worst case (linear)"], rows)
    return out


def play(tmp: Path) -> dict:
    """What play costs: the default chain's pen error band, the reducer's, the herringbone pair's, the
    planetary set's and the rack's lost motion, as `partgen trace --json` reports them; the trains'
    nominal lost motion measured exactly on the printed outlines (each body where the model puts it in
    its bore)."""
    t = partgen("trace", "configs/butterfly.yaml", "-o", str(tmp / "chain"))
    b = t["pen_error_band_mm"]
    free = b["link_free_angle_arcmin"]
    return {"chain": {"path_worst_mm": r(b["path_worst_case_max"], 1), "path_p95_mm": r(b["path_p95_max"], 1),
                      "path_p50_mm": r(b["path_p50_max"], 1), "point_worst_mm": r(b["worst_case_max"], 0),
                      "point_p95_mm": r(b["p95_max"], 0), "point_p50_mm": r(b["p50_max"], 0),
                      "free_min_arcmin": r(min(free), 0), "free_max_arcmin": r(max(free), 0),
                      "radial_play_mm": r(max(b["joint_radial_play_mm"]), 3), "prints": b["prints"]},
            "reducer": _stages_play(tmp, "reducer"), "herringbone": _stages_play(tmp, "herringbone"),
            "planetary": _planetary_play(tmp), "rack": _rack_play(tmp)}


def _stages_play(tmp: Path, name: str) -> dict:
    """A train of stages: trace's lost motion at the output; the output turned on the printed outlines
    with every body centred and with every body where the model puts it (``worst_shifts``) at 6 angles;
    the bores' share as the model counted it before (each body's play along its lines of centres only,
    ``2 tan α_w · 2c`` per mesh) and the compound gears' share against the sum of their meshes' parts
    (what a compound gear tilting on its pin could reach)."""
    import math

    import numpy as np

    from partgen import pipeline
    from partgen.mechanisms.gear_train.common.play import ARCMIN
    from partgen.mechanisms.gear_train.stages import play as splay
    from partgen.mechanisms.gear_train.stages.motion import printed_sections, turn_train

    t = partgen("trace", f"configs/gear_train_{name}.yaml", "-o", str(tmp / name))
    lm, band = t["lost_motion_arcmin"], t["lost_motion_arcmin"]["transmission_error_band_arcmin"]
    loaded = pipeline.load(f"configs/gear_train_{name}.yaml")
    kit, s = pipeline.make_kit(loaded), loaded.spec
    secs, o, sg = printed_sections(kit), len(s.shafts) - 1, math.copysign(1.0, float(s.shafts[-1].speed))
    th = np.linspace(0.0, s.output_turn, 6, endpoint=False)
    where = splay.worst_shifts(s)
    fwd = turn_train(kit, th, secs, 1e-7, shifts=where["coast"])
    back = turn_train(kit, th, secs, 1e-7, shifts=where["drive"])
    exact = sg * (fwd["coast"][:, o] - back["drive"][:, o]) * ARCMIN
    c, ms = s.running / 2, splay.mesh_terms(s)
    old = sum(2 * math.tan(m["alpha_w"]) * 2 * c / m["r_w"] * m["refer"] for m in ms) * ARCMIN
    reach = splay.body_reach(s)
    compound = [k for k in reach if sum(k in (m["i"], m["j"]) for m in ms) > 1]
    rows = {row["share"]: row for row in lm["shares"]}
    bodies = sum(row["at_output"] for row in lm["shares"] if row["kind"] == "bores")
    out = {"total_arcmin": r(lm["total"], 1), "backlash_arcmin": r(lm["backlash"], 1),
           "bores_arcmin": r(lm["bores"], 1), "worst_arcmin": r(lm["worst_case"], 1), "p95_arcmin": r(lm["p95"], 1),
           "p50_arcmin": r(lm["p50"], 1), "prints": lm["prints"], "accuracy_mm": lm["accuracy_mm"],
           "measured_min_arcmin": r(t["backlash_arcmin"]["min"], 1),
           "measured_max_arcmin": r(t["backlash_arcmin"]["max"], 1),
           "exact_min_arcmin": r(float(exact.min()), 1), "exact_max_arcmin": r(float(exact.max()), 1),
           "along_centres_arcmin": r(old, 1), "old_total_arcmin": r(lm["backlash"] + old, 1),
           "bores_ratio": r(lm["bores"] / old, 2), "alpha_w_deg": r(math.degrees(ms[-1]["alpha_w"]), 1),
           "te_band_arcmin": r(band["width"], 1), "te_band_p95_arcmin": r(band["p95_width"], 1),
           "te_band_worst_arcmin": r(band["worst_case_width"], 1),
           "bodies": ", ".join(f"{k.split(' ')[0]} {v['at_output']:.1f}" for k, v in rows.items() if v["kind"] == "bores")}
    assert abs(bodies - lm["bores"]) < 0.01
    for k in compound:  # its meshes' parts added as numbers: each 2c refer/r_b
        parts = sum(2 * c * m["refer"] / m["r_b"] for m in ms if k in (m["i"], m["j"])) * ARCMIN
        got = next(v["at_output"] for n, v in rows.items() if n.split(" ")[0] in (f"gears{k}", f"shaft{k}"))
        out.update(compound_arcmin=r(got, 1), compound_sum_arcmin=r(parts, 1))
    return out


def _planetary_play(tmp: Path) -> dict:
    import math

    import numpy as np

    from partgen import pipeline
    from partgen.mechanisms.gear_train.common.play import ARCMIN
    from partgen.mechanisms.gear_train.planetary.motion import turn_planetary

    t = partgen("trace", "configs/gear_train_planetary.yaml", "-o", str(tmp / "planetary"))
    lm, band = t["lost_motion_arcmin"], t["lost_motion_arcmin"]["transmission_error_band_arcmin"]
    loaded = pipeline.load("configs/gear_train_planetary.yaml")
    kit, c = pipeline.make_kit(loaded), loaded.spec.running / 2
    th = np.linspace(0.0, 2 * math.pi, 6, endpoint=False)
    fwd, back = (turn_planetary(kit, th, planet_shift=(0.0, sg * c)) for sg in (1.0, -1.0))
    exact = (np.maximum(fwd["coast"], back["coast"]) - np.minimum(fwd["drive"], back["drive"])) * ARCMIN
    rows = {row["share"]: row for row in lm["shares"]}
    return {"total_arcmin": r(lm["total"], 1), "backlash_arcmin": r(lm["backlash"], 1),
            "pins_arcmin": r(rows["a planet on its pin"]["at_output"], 1), "worst_arcmin": r(lm["worst_case"], 1),
            "p95_arcmin": r(lm["p95"], 1), "p50_arcmin": r(lm["p50"], 1), "prints": lm["prints"],
            "measured_min_arcmin": r(t["backlash_arcmin"]["min"], 1),
            "measured_max_arcmin": r(t["backlash_arcmin"]["max"], 1),
            "exact_min_arcmin": r(float(exact.min()), 1), "exact_max_arcmin": r(float(exact.max()), 1),
            "te_band_arcmin": r(band["width"], 1), "te_band_p95_arcmin": r(band["p95_width"], 1),
            "te_band_worst_arcmin": r(band["worst_case_width"], 1), "accuracy_mm": lm["accuracy_mm"]}


def _rack_play(tmp: Path) -> dict:
    import math

    import numpy as np

    from partgen import pipeline
    from partgen.mechanisms.gear_train.rack.motion import turn_rack

    t = partgen("trace", "configs/gear_train_rack.yaml", "-o", str(tmp / "rack"))
    lm, band = t["lost_motion_mm"], t["lost_motion_mm"]["transmission_error_band_mm"]
    loaded = pipeline.load("configs/gear_train_rack.yaml")
    kit, s = pipeline.make_kit(loaded), loaded.spec
    al, c = s.system.pressure_angle, s.running / 2
    th = np.linspace(*s.thetas_range, 9)
    fwd = turn_rack(kit, th, pinion_at=(c * math.cos(al), c * math.sin(al)), rack_dy=-c)
    back = turn_rack(kit, th, pinion_at=(-c * math.cos(al), c * math.sin(al)), rack_dy=-c)
    exact = fwd["coast"] - back["drive"]
    rows = {row["share"]: row for row in lm["shares"]}
    return {"total_mm": r(lm["total"], 3), "backlash_mm": r(lm["backlash"], 3),
            "shaft_mm": r(rows["the pinion's shaft in the base"]["at_output"], 3),
            "rail_mm": r(rows["the rack against its rail"]["at_output"], 3), "worst_mm": r(lm["worst_case"], 3),
            "p95_mm": r(lm["p95"], 3), "p50_mm": r(lm["p50"], 3), "pinion_arcmin": r(lm["pinion_arcmin"]["total"], 0),
            "pinion_p95_arcmin": r(lm["pinion_arcmin"]["p95"], 0),
            "measured_min_mm": r(t["backlash_mm"]["min"], 3), "measured_max_mm": r(t["backlash_mm"]["max"], 3),
            "exact_min_mm": r(float(exact.min()), 3), "exact_max_mm": r(float(exact.max()), 3),
            "te_band_um": r(1000 * band["width"], 0), "te_band_p95_um": r(1000 * band["p95_width"], 0),
            "te_band_worst_um": r(1000 * band["worst_case_width"], 0)}


def lissajous(tmp: Path) -> dict:
    """The 3:2 Lissajous drawing (configs/lissajous.yaml): the scale `auto` chose, the chain, and its
    check and trace."""
    import re

    t0 = time.perf_counter()
    b = partgen("build", "configs/lissajous.yaml", "-o", str(tmp / "kit"))
    build_s = time.perf_counter() - t0
    note = next(f["message"] for f in b["findings"] if f["key"] == "curve.scale")
    man = json.loads((tmp / "kit" / "manifest.json").read_text())["design"]
    c = partgen("check", str(tmp / "kit"), ok=(0, 1))
    t = partgen("trace", str(tmp / "kit"), "-o", str(tmp / "trace"))
    meshes = c["figures"]["meshes"]
    teeth = ", ".join("/".join(str(s["teeth"][k]) for k in ("D", "M", "G")) for s in man["stages"])
    return {"scale": float(re.search(r"auto chose ([0-9.]+)", note)[1]),
            "rungs_tried": int(re.search(r"(\d+) tried", note)[1]), "build_s": r(build_s, 0),
            "links": ", ".join(l["name"] for l in man["links"]),
            "link_mm": r(man["links"][0]["length_mm"], 2), "module_mm": man["module_mm"], "teeth": teeth,
            "crank_turns": man["crank_turns_per_drawing"], "check_exit": 0 if c["ok"] else 1,
            "contact_ratio_min": r(min(m["contact_ratio"] for m in meshes), 2),
            "backlash_min_mm": r(min(m["backlash_mm"] for m in meshes), 3),
            "backlash_max_mm": r(max(m["backlash_mm"] for m in meshes), 3),
            "closest_mm": r(c["figures"]["motion"]["closest_approach"]["mm"], 2)
            if isinstance(c["figures"]["motion"].get("closest_approach"), dict) else "–",
            "max_deviation_mm": f"{t['max_deviation_mm']:.1g}", "hausdorff_mm": r(t["hausdorff_mm"], 3)}


def autoplay(tmp: Path) -> dict:
    """auto play allocated per gear and per joint: total play and P(jam), uniform against allocated."""
    cases = [("chain", "configs/butterfly.yaml", ()),
             ("chain_both", "configs/butterfly.yaml", ("--set", "joints.running_clearance_diametral_mm=auto")),
             ("desktop", "configs/butterfly_desktop.yaml", ()),
             ("pair", "configs/gear_pair.yaml", ("--set", "gears.backlash_per_gear_mm=auto", "--set",
                                                 "axles.clearance_diametral_mm=auto", "--printer", "ender3_v3"))]
    out, rows = {}, []
    for name, config, extra in cases:
        dest = tmp / name
        a = partgen("build", config, "-o", str(dest), *extra)["auto_play"]
        pu = a["per_unit"]
        uniform = a.get("uniform", a)
        own = {k: v for d in pu.get("own", {}).values() for k, v in d.items()}
        t = partgen("tolerance", str(dest), "--samples", "10000", "--seed", "0", "-o", str(tmp / f"{name}_tol"))
        values = " / ".join(f"{v:g}" for v in a["values"].values())
        out[name] = {"adopted": pu["adopted"], "uniform_mm": values, "uniform_play_mm": r(pu["uniform_cost_mm"], 3),
                     "allocated_play_mm": r(pu["cost_mm"], 3), "saving_pct": r(pu["saving_pct"], 1),
                     "threshold_mm": r(pu["threshold_mm"], 3), "p_uniform_pct": pct(uniform["probability"], 2),
                     "p_allocated_pct": pct(pu["probability"], 2), "own": len(own),
                     "own_range_mm": f"{min(own.values()):g}–{max(own.values()):g}" if own else "–",
                     "p_kit_pct": pct(t["overall"]["probability"], 2), "exchanges": pu["exchanges"],
                     "held_out": (f"{pu['held_out']['uniform_jams']} → {pu['held_out']['jams']}"
                                  if pu.get("held_out") else "–")}
        o = out[name]
        rows.append([f"`{Path(config).name}`" + (" " + " ".join(x for x in extra if not x.startswith("--")) if extra else ""),
                     a["printer"], o["uniform_mm"], f"{o['uniform_play_mm']} → {o['allocated_play_mm']}",
                     f"{o['saving_pct']} % (threshold {o['threshold_mm']} mm)", "yes" if o["adopted"] else "no",
                     f"{o['p_uniform_pct']} % → {o['p_allocated_pct']} %", o["held_out"], f"{o['p_kit_pct']} %"])
    out["table"] = table(["design", "printer", "uniform auto (mm)", "total play uniform → allocated (mm)", "saved",
                          "adopted", "P(jam), the 20,000 prints auto chooses on",
                          "jams on 20,000 other prints", "the built kit's `tolerance` (10,000)"], rows)
    return out


def contact(tmp: Path) -> dict:
    """Contact along the face (checks.contact_pattern): the shipped mitre pair, crossed helical pair and
    worm from `check --json`; the mitre pair with gear 2 moved ±0.2 mm off the plane of the shafts
    (in-process, the test's mis-set), against the closed form of where its pattern ends."""
    import numpy as np
    import yaml

    from partgen import pipeline
    from partgen.checks.contact3d import turned
    from partgen.mechanisms.bevel.kit import BevelKit, build_bevel
    from partgen.mechanisms.bevel.contact import contact_along_face, contact_angles

    out = {}

    def pattern(p: dict) -> dict:
        return {"pct": r(100 * p["fraction"], 0), "from_pct": r(100 * p["from"], 0), "to_pct": r(100 * p["to"], 0),
                "sits": p["sits"], "one_phase_min_pct": r(100 * p["instantaneous"]["min"], 0),
                "one_phase_max_pct": r(100 * p["instantaneous"]["max"], 0), "face_mm": r(p["face_width_mm"], 1),
                "phases": p["phases"]}

    for key, cfg in (("mitre", "bevel_mitre"), ("crossed", "gear_train_crossed_helical"), ("worm", "gear_train_worm")):
        c = partgen("check", f"configs/{cfg}.yaml", "-o", str(tmp / key))
        f = c["figures"]["contact_along_face"]
        out["gap_mm"] = f["gap_mm"]
        if "gear2" in f:
            out[key] = pattern(f["gear2"])
            out[key + "_gear1"] = pattern(f["gear1"])
        else:
            out[key] = pattern(f)
        out[key]["check_s"] = r(c["seconds"], 1)
    # the shipped worm with a throated wheel (gears.throated), at the shipped chord tolerance
    d = yaml.safe_load((ROOT / "configs" / "gear_train_worm.yaml").read_text())
    d["name"], d["gears"]["throated"] = "worm_throated", True
    cfg = tmp / "worm_throated.yaml"
    cfg.write_text(yaml.safe_dump(d, sort_keys=False))
    c = partgen("check", str(cfg), "-o", str(tmp / "throated"))
    f = c["figures"]
    out["throated"] = {**pattern(f["contact_along_face"]["gear2"]), "check_s": r(c["seconds"], 1),
                       "overlap_mm3": f["max_overlap_mm3"], "backlash_min_mm": r(f["backlash_mm"]["min"], 3),
                       "backlash_max_mm": r(f["backlash_mm"]["max"], 3),
                       "backlash_designed_mm": r(f["backlash_mm"]["designed"], 3),
                       "te_pp_um": r(1000 * f["transmission_error_mm"]["peak_to_peak"], 1)}
    out["throated_gear1"] = pattern(f["contact_along_face"]["gear1"])
    spec = pipeline.load(ROOT / "configs" / "bevel_mitre.yaml").spec
    kit0 = build_bevel(spec)
    R, b, g = spec.pair.cone_distance, spec.gear2.face_width, out["gap_mm"]
    thetas = 2 * math.pi / spec.gear1.teeth * np.arange(4) / 4
    for name, e in (("offset_heel", 0.2), ("offset_toe", -0.2)):
        class Offset(BevelKit):
            def poses(self, theta: float = 0.0, e=e):
                P = super().poses(theta)
                T = P["gear2"].copy()
                T[1, 3] += e
                v = np.cross(spec.pair.axis2, (R - b / 2) * spec.pair.pitch_line)
                return {**P, "gear2": turned(T, -e * v[1] / (v @ v))}
        kit = Offset(kit0.spec, kit0.parts)
        play = contact_angles(kit, thetas, 1e-5)
        c = contact_along_face(kit, thetas, play)
        out[name] = pattern(c)
        s = R / (1 + g / e) if e > 0 else 1 / (1 / (R - b) + g / (e * R))
        out[name]["closed_form_pct"] = r(100 * (s - (R - b)) / b, 1)
        out[name]["measured_end_pct"] = r(100 * (c["from"] if e > 0 else c["to"]), 1)
        out[name]["backlash_mm"] = r(float(np.mean(play["ahead"] - play["behind"])) * spec.gear2.pitch_radius, 3)
    return out


def crossed(tmp: Path) -> dict:
    """The shipped crossed helical pair (45° + 45°) and worm, built, checked and traced (the CLI's
    JSON); each gear's flanks on its float32 mesh against the analytic helicoid (sections at
    three heights against the transverse involute turned by the helix; the worm's thread against its
    base circle's involute, as the tests measure them); the check's overlap with -0.1 mm backlash per
    gear; every STL read back; the pair at 60° (30° + 30°); the bevel's crown-gear limit for 15/25."""
    import dataclasses

    import numpy as np
    import trimesh
    import yaml
    from shapely import contains_xy

    from partgen import pipeline
    from partgen.geometry.solid import mesh_arrays
    from partgen.mechanisms.crossed_helical.contact import mesh_overlaps
    from partgen.mechanisms.crossed_helical.kit import build_crossed
    from partgen.mechanisms.crossed_helical.resolve import gear_spec
    from partgen.testing import measure_spur_gear, measure_worm_flanks, mesh_problems, section_outline

    def float32(solid) -> trimesh.Trimesh:
        v, f = mesh_arrays(solid)
        return trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)

    def helical_flanks(spec, kit) -> dict:
        """Both gears sectioned at three heights: the flank's worst deviation from the involute (µm,
        about its mean: measure_spur_gear), the tooth thickness against the design (µm) and tooth 0's
        centre against the helix's turn there (rad)."""
        worst, thick, turn, step = 0.0, 0.0, 0.0, 0.0
        for i, name in enumerate(("gear1", "gear2")):
            gear, b = (spec.gear1, spec.gear2)[i], spec.face_width[i]
            mesh = float32(kit.part(name).solid)
            twist = spec.pair.twist(i, b)
            for z in (-0.4 * b, 0.05 * b, 0.45 * b):
                out = section_outline(mesh, z)
                m = measure_spur_gear(out, gear.teeth, gear.module, gear.system.pressure_angle, centre=(0.0, 0.0))
                worst = max(worst, m.flank_deviation)
                thick = max(thick, abs(m.tooth_thickness - gear.tooth_thickness))
                turned, r_p = twist * z / b, gear.pitch_radius
                th = turned + np.linspace(-math.pi / gear.teeth, math.pi / gear.teeth, 20001)
                step = max(step, float(th[1] - th[0]) / 2)  # the centre's resolution
                centre = th[contains_xy(out, r_p * np.cos(th), r_p * np.sin(th))].mean()
                turn = max(turn, abs(centre - turned))
        return {"flank_um": r(1000 * worst, 1), "thickness_um": r(1000 * thick, 1),
                "turn": f"{turn:.0e} rad" if turn > step else f"{step:.0e} rad (the measurement's resolution)"}

    def thread_flanks(spec, kit) -> dict:
        """The worm's sections at three heights against the involute of its base circle turned by
        z tan β / r, along the flank's normal (µm; partgen.testing.measure_worm_flanks)."""
        b = spec.face_width[0]
        d = measure_worm_flanks(float32(kit.part("gear1").solid), spec.gear1, spec.pair.twist(0, b) / b,
                                (-0.3 * b, 0.02 * b, 0.4 * b))
        return {"flank_um": r(1000 * float(np.abs(d).max()), 1), "flank_mean_um": r(1000 * float(d.mean()), 1)}

    def shells(dest: Path, man: dict, envelope) -> str:
        ok = 0
        for p in man["parts"]:
            mesh = trimesh.load(dest / p["file"], file_type="stl")
            ok += not mesh_problems(mesh, envelope) and len(mesh.split(only_watertight=False)) == 1
        return f"{len(man['parts'])} STL, {'each' if ok == len(man['parts']) else f'{ok} of them'} one closed shell"

    out: dict = {}
    for key, cfg in (("pair", "configs/gear_train_crossed_helical.yaml"), ("worm", "configs/gear_train_worm.yaml")):
        dest = tmp / key
        partgen("build", cfg, "-o", str(dest))
        man = json.loads((dest / "manifest.json").read_text())
        d = man["design"]
        c = partgen("check", str(dest), "-o", str(tmp / f"{key}_plates"))
        t = partgen("trace", str(dest), "-o", str(tmp / f"{key}_trace"))
        f = c["figures"]
        loaded = pipeline.load(ROOT / cfg)
        spec, kit = loaded.spec, pipeline.make_kit(loaded)
        env = tuple(float(x) for x in kit.printer.envelope)
        tight = dataclasses.replace(spec, gear1=gear_spec(spec.pair, 0, -0.1, spec.tol),
                                    gear2=gear_spec(spec.pair, 1, -0.1, spec.tol))
        vols = mesh_overlaps(build_crossed(tight), f["samples"])
        out[key] = {
            "centre_distance_mm": r(d["centre_distance_mm"], 3), "shaft_height_mm": r(d["shaft_height_mm"], 1),
            "pitch1_mm": r(d["pitch_diameter_mm"][0], 1), "pitch2_mm": r(d["pitch_diameter_mm"][1], 1),
            "face1_mm": r(d["face_width_mm"][0], 1),
            "sliding_per_rolling": r(d["sliding_per_rolling"], 2),
            "check_samples": f["samples"], "overlap_mm3": f["max_overlap_mm3"],
            "tight_overlap_min_mm3": r(float(vols.min()), 2), "tight_phases_overlapping": int((vols > 0).sum()),
            "backlash_min_mm": r(f["backlash_mm"]["min"], 3), "backlash_max_mm": r(f["backlash_mm"]["max"], 3),
            "backlash_designed_mm": r(f["backlash_mm"]["designed"], 3),
            "te_pp_um": r(1000 * t["transmission_error_mm"]["peak_to_peak"], 1), "trace_samples": t["samples"],
            "te_check_pp_um": r(1000 * f["transmission_error_mm"]["peak_to_peak"], 1),
            "ratio_measured": r(t["ratio_measured"], 6),
            "ratio_error": f"{t['ratio_relative_error']:.0e}" if t["ratio_relative_error"] else "0",
            "ratio_local_pct": r(100 * t["instantaneous_ratio_deviation"], 2),
            "exits": "exit 0" if c["ok"] and t.get("ok", True) else "**not both exit 0**",
            "check_s": r(c["seconds"], 1), "shells": shells(dest, man, env),
            "triangles_k": r(sum(p["triangles"] for p in man["parts"] if p["name"] == "gear1") / 1000, 0),
            "chord_mm": spec.tol,
        }
        if key == "pair":
            out[key].update(helical_flanks(spec, kit))
            fine = pipeline.load(ROOT / cfg, over=pipeline.overrides(["gears.chord_tolerance_mm=0.001"]))
            out[key]["flank_fine_um"] = helical_flanks(fine.spec, pipeline.make_kit(fine))["flank_um"]
        else:
            out[key].update(thread_flanks(spec, kit))
            # the throated wheel's scallop between two of the generating cut's 12 poses per worm tooth
            # pitch, (p_t2 sin α_t / 12)² / (8 ρ), ρ the wheel's flank's radius of curvature at its
            # pitch circle (r sin α_t)
            sys2 = spec.pair.systems[1]
            rho = spec.pair.pitch_radius(1) * math.sin(sys2.pressure_angle)
            out[key]["scallop_um"] = r(1000 * (math.pi * sys2.module * math.sin(sys2.pressure_angle) / 12) ** 2 / (8 * rho), 2)
            out[key].update(lead_deg=r(d["lead_angle_deg"], 2), friction_angle_deg=r(d["friction_angle_deg"], 2),
                            friction=d["friction_coefficient"], self_locking="yes" if d["self_locking"] else "no",
                            efficiency_pct=pct(d["efficiency_gear1_driving"], 0))
    # the same code at 60° (30° + 30°): another frame, the same kinematic model
    data = yaml.safe_load((ROOT / "configs" / "gear_train_crossed_helical.yaml").read_text())
    data.update(name="crossed_60", shaft_angle_deg=60.0)
    data["gears"]["helix_angle_deg"] = [30.0, 30.0]
    cfg60 = tmp / "crossed_60.yaml"
    cfg60.write_text(yaml.safe_dump(data, sort_keys=False))
    f = partgen("check", str(cfg60), "-o", str(tmp / "s60"))["figures"]
    out["s60"] = {"overlap_mm3": f["max_overlap_mm3"], "backlash_min_mm": r(f["backlash_mm"]["min"], 3),
                  "backlash_max_mm": r(f["backlash_mm"]["max"], 3), "backlash_designed_mm": r(f["backlash_mm"]["designed"], 3)}
    # the page's bevel figures the bevel section does not measure: a pitch cone reaches 90° (a crown
    # gear) at cos Σ = −z_small / z_large; a gear's triangles at the shipped 0.001 mm chord tolerance
    out["bevel_crown_limit_15_25_deg"] = r(math.degrees(math.acos(-15 / 25)), 2)
    partgen("build", "configs/bevel_mitre.yaml", "-o", str(tmp / "mitre"))
    man = json.loads((tmp / "mitre" / "manifest.json").read_text())
    out["bevel_gear1_triangles_k"] = r(next(p["triangles"] for p in man["parts"] if p["name"] == "gear1") / 1000, 1)
    out["bevel_chord_mm"] = yaml.safe_load((ROOT / "configs" / "bevel_mitre.yaml").read_text())["gears"]["chord_tolerance_mm"]
    return out


SECTIONS = {"chain": chain, "drawn": drawn, "gear_pair": gear_pair, "gear_train": gear_train,
            "tolerance": tolerance, "autoplay": autoplay, "sweep": sweep, "bennett": bennett,
            "calibrate": calibrate, "wrist": wrist, "bevel": bevel, "crossed": crossed, "contact": contact,
            "printers": printers, "jam": jam, "exact": exact, "play": play, "lissajous": lissajous}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", nargs="+", choices=sorted(SECTIONS), help="run these sections; keep the others")
    ap.add_argument("--list", action="store_true", help="list the sections and exit")
    a = ap.parse_args(argv)
    if a.list:
        for k, f in SECTIONS.items():
            print(f"{k:12} {f.__doc__}")
        return 0
    from partgen import __version__

    for name in a.only or list(SECTIONS):
        t0 = time.perf_counter()
        print(f"{name} …", file=sys.stderr, flush=True)
        with tempfile.TemporaryDirectory(prefix=f"docs_figures_{name}_") as tmp:
            section = SECTIONS[name](Path(tmp))
        section["_run"] = {"date": datetime.date.today().isoformat(), "partgen": __version__,
                           "seconds": r(time.perf_counter() - t0, 1)}
        print(f"{name}: {section['_run']['seconds']} s", file=sys.stderr, flush=True)
        figures = json.loads(OUT.read_text()) if OUT.exists() else {}  # read now: keep what others wrote
        figures[name] = section
        OUT.write_text(json.dumps(figures, indent=1, ensure_ascii=False, sort_keys=True) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
