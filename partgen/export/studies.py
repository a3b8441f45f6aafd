"""What the studies write: the tolerance section of a report, and a sweep's table (CSV) and its HTML
page of plots."""

from __future__ import annotations

import csv
import html
import io
import json
import math
from pathlib import Path

from . import report as R

__all__ = ["saved_tolerance", "tolerance_section", "tolerance_bars", "SWEEP_COLUMNS", "sweep_csv", "sweep_page"]

SWEEP_COLUMNS = ("point", "status", "ok", "failures", "first_failure", "mass_g", "size_mm", "parts",
                 "least_clearance_mm", "jam_probability", "jam_ci95_low", "jam_ci95_high", "seconds")
METRICS = (("mass_g", "mass of the printed parts (g)"), ("size_mm", "largest part (mm)"),
           ("least_clearance_mm", "least clearance over the motion (mm)"), ("jam_probability", "P(jam)"))


def saved_tolerance(folder: Path, digest: str) -> dict | None:
    """The result `partgen tolerance` wrote into ``folder`` (its result.json), if it was made from the
    design whose digest is ``digest`` (``LoadedDesign.digest()``: the same design and printer)."""
    try:
        data = json.loads((Path(folder) / "result.json").read_text(encoding="utf-8"))
    except (OSError, ValueError, UnicodeDecodeError):
        return None
    return data if isinstance(data, dict) and data.get("design_digest") == digest else None


def tolerance_bars(result: dict, top: int = 15) -> bytes:
    """A PNG: P(jam) with its 95 % interval for the worst ``top`` joints, meshes and pairs."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = result["units"][:top][::-1]
    colours = {"joint": "#4c78a8", "mesh": "#f58518", "clearance": "#e45756"}
    fig, ax = plt.subplots(figsize=(7.5, 0.32 * len(rows) + 1.2))
    p = [r["probability"] for r in rows]
    err = [[r["probability"] - r["ci95"][0] for r in rows], [r["ci95"][1] - r["probability"] for r in rows]]
    ax.barh(range(len(rows)), p, xerr=err, color=[colours.get(r["group"], "#999") for r in rows], capsize=2)
    ax.set_yticks(range(len(rows)), [f"{r['unit']} ({r['group']})" for r in rows], fontsize=8)
    ax.set_xlabel("probability of jamming (95 % interval)")
    ax.set_xlim(0, max(0.05, min(1.0, max(r["ci95"][1] for r in rows) * 1.1)) if rows else 1)
    ax.grid(axis="x", alpha=0.3)
    return R.figure_png(fig, 110, "tight")


def tolerance_section(result: dict) -> tuple[str, str]:
    """("Tolerance", html) of a `partgen tolerance` result."""
    o = result["overall"]
    lo, hi = o["ci95"]
    head = (f"<p>{result['samples']:,} simulated prints at ±{result['accuracy_mm']:g} mm "
            f"({html.escape(str(result.get('accuracy_source', '')))}; 3σ of a printed dimension), "
            f"{result['features']} printed features, {result['margins']} margins that decide whether the kit turns. "
            f'<span class="{"ok" if o["probability"] == 0 else "fail"}">P(jam) = {100 * o["probability"]:.2f} %</span> '
            f"(95 % Wilson interval {100 * lo:.2f}–{100 * hi:.2f} %). Seed {result.get('seed', 0)}.</p>")
    wc, ex = result.get("worst_case"), result.get("exact")
    if wc:  # docs/tolerance.md: the headline seats the gears where their meshes push them
        seat = result.get("seat") or "gears seated by their meshes in their bores"
        head += (f"<p>{html.escape(seat[:1].upper() + seat[1:])} (docs/tolerance.md). Worst case, "
                 f"{html.escape(wc.get('seat') or 'every gear centred on its post (no bore play credited)')}: "
                 f"P(jam) = {100 * wc['probability']:.2f} % "
                 f"({100 * wc['ci95'][0]:.2f}–{100 * wc['ci95'][1]:.2f} %).</p>")
    if ex:
        head += (f"<p>Exact Monte Carlo, {ex['prints']:,} prints of the real geometry: P(jam) = "
                 f"{100 * ex['probability']:.2f} % ({100 * ex['ci95'][0]:.2f}–{100 * ex['ci95'][1]:.2f} %), "
                 f"{'agreeing with' if ex['agrees'] else 'not agreeing with'} the linear figure.</p>")
    rows = [[u["unit"], u["group"], u["where"], round(u["least_nominal_mm"], 4), f"{100 * u['probability']:.2f} %",
             f"{100 * u['ci95'][0]:.2f}–{100 * u['ci95'][1]:.2f} %"] for u in result["units"][:20]]
    kinds = [[k["kind"], f"{100 * k['share']:.1f} %"] for k in result["sensitivity"]["by_kind"]]
    feats = [[f["feature"], f["kind"], f"{100 * f['share']:.1f} %"] for f in result["sensitivity"]["by_feature"]]
    body = (head + f"<figure>{R.img(tolerance_bars(result), 'jam probability per joint, mesh and pair')}</figure>"
            + R.table(["where", "kind", "at", "nominal margin mm", "P(jam)", "95 % interval"], rows, left=3)
            + "<p>What drives the jams: each jam is shared among the features that pushed its margin below zero, "
              "in proportion to how far each did.</p>"
            + '<div class="grid">' + R.table(["feature kind", "share of jams"], kinds)
            + R.table(["feature", "kind", "share of jams"], feats, left=2) + "</div>")
    return ("Tolerance", body)


def _value(v):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return ""
    return v


def sweep_csv(rows: list[dict], keys: list[str]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(list(keys) + list(SWEEP_COLUMNS))
    for r in rows:
        w.writerow([_value(r["values"][k]) for k in keys] + [_value(r.get(c)) for c in SWEEP_COLUMNS])
    return buf.getvalue()


def _plot(rows: list[dict], key: str, metric: str, label: str) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(4.6, 3.2))
    for status, colour, marker in (("pass", "#1a7f37", "o"), ("fail", "#cf222e", "x"), ("refused", "#8c8c8c", "s")):
        pts = [(r["values"][key], r.get(metric)) for r in rows if r["status"] == status and r.get(metric) is not None]
        if pts:
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], c=colour, marker=marker, s=22, label=status)
    if metric == "jam_probability":
        for r in rows:
            if r.get("jam_probability") is not None:
                ax.plot([r["values"][key]] * 2, [r["jam_ci95_low"], r["jam_ci95_high"]], c="#555", lw=0.8)
    ax.set_xlabel(key)
    ax.set_ylabel(label)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return R.figure_png(fig, 110, "tight")


def sweep_page(rows: list[dict], keys: list[str], title: str, subtitle: str) -> str:
    """One self-contained HTML page: pass/fail and every metric against each varied key, the table."""
    n = len(rows)
    counts = {s: sum(r["status"] == s for r in rows) for s in ("pass", "fail", "refused")}
    intro = (f"<p>{n} design points: <span class=\"ok\">{counts['pass']} pass</span>, <span class=\"fail\">"
             f"{counts['fail']} fail</span> `partgen check`, {counts['refused']} refused (the design cannot be built)."
             "</p>")
    sections = [("Summary", intro)]
    for key in keys:
        figs = []
        for metric, label in METRICS:
            if any(r.get(metric) is not None for r in rows):
                figs.append(f"<figure>{R.img(_plot(rows, key, metric, label), f'{label} against {key}')}</figure>")
        sections.append((f"Against {key}", '<div class="grid">' + "".join(figs) + "</div>"))
    table = [[r["point"], *[r["values"][k] for k in keys], r["status"], r.get("mass_g") or "", r.get("size_mm") or "",
              r.get("least_clearance_mm") if r.get("least_clearance_mm") is not None else "",
              "" if r.get("jam_probability") is None else f"{100 * r['jam_probability']:.2f} %",
              html.escape(r.get("first_failure") or "")] for r in rows]
    sections.append(("Points", R.table(["point", *keys, "status", "mass g", "largest part mm", "least clearance mm",
                                        "P(jam)", "first failure"], table, left=1, raw={len(keys) + 7})))
    return R.page(title, sections, subtitle)
