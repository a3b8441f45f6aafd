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

__all__ = ["saved_tolerance", "tolerance_section", "tolerance_bars", "SWEEP_COLUMNS", "sweep_csv", "sweep_page",
           "PLAY_COSTS", "play_cost", "tradeoff_rows", "tradeoff_csv", "tradeoff_png"]

SWEEP_COLUMNS = ("point", "status", "ok", "failures", "first_failure", "mass_g", "size_mm", "parts",
                 "least_clearance_mm", "jam_probability", "jam_ci95_low", "jam_ci95_high", "pen_error_mm",
                 "pen_error_p95_mm", "lost_motion_arcmin", "lost_motion_mm", "seconds")
# what play costs, by what a trace measures (design.play: the chain's pen across its path; a gear
# train's lost motion at the output, a rack's along its travel): (column, label), the first one a sweep's
# points have is plotted
PLAY_COSTS = (("pen_error_p95_mm", "pen error across the path, 95 % of prints (mm)"),
              ("lost_motion_arcmin", "lost motion at the output (arcmin)"),
              ("lost_motion_mm", "lost motion at the rack (mm of travel)"))


def play_cost(stats: dict) -> dict:
    """What play costs in a trace's figures: the pen's error across the path (worst case and 95 % of
    prints, mm) or the output's lost motion (arcmin; a rack's in mm of travel); {} when the trace measures
    none."""
    out = {}
    band = stats.get("pen_error_band_mm")
    if isinstance(band, dict) and "path_p95_max" in band:
        out.update(pen_error_mm=band["path_worst_case_max"], pen_error_p95_mm=band["path_p95_max"])
    lm = stats.get("lost_motion_arcmin")
    if isinstance(lm, dict) and "total" in lm:
        out["lost_motion_arcmin"] = lm["total"]
    lm = stats.get("lost_motion_mm")
    if isinstance(lm, dict) and "total" in lm:
        out["lost_motion_mm"] = lm["total"]
    return out


def tradeoff_rows(rows: list[dict]) -> tuple[str, str, list[dict]] | None:
    """(column, label, rows with P(jam) and that cost, least cost first) of a sweep's points, or None."""
    for col, label in PLAY_COSTS:
        got = [r for r in rows if r.get(col) is not None and r.get("jam_probability") is not None]
        if got:
            return col, label, sorted(got, key=lambda r: (r[col], r["point"]))
    return None


def tradeoff_csv(rows: list[dict], keys: list[str]) -> str:
    """The trade-off's table: each point's values, what its play costs and its P(jam), least cost first."""
    got = tradeoff_rows(rows)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    col = got[0] if got else "play_cost"
    extra = ["pen_error_mm"] if col == "pen_error_p95_mm" else []
    w.writerow(["point", *keys, col, *extra, "jam_probability", "jam_ci95_low", "jam_ci95_high", "status"])
    for r in (got[2] if got else []):
        w.writerow([r["point"], *[_value(r["values"][k]) for k in keys], _value(r[col]),
                    *[_value(r.get(e)) for e in extra], _value(r["jam_probability"]), _value(r["jam_ci95_low"]),
                    _value(r["jam_ci95_high"]), r["status"]])
    return buf.getvalue()


def tradeoff_png(rows: list[dict], keys: list[str], target: float | None = None) -> bytes | None:
    """A PNG: P(jam) (95 % interval) against what play costs, one point per design, labelled with
    its values; the target as a line. None when the points carry no play cost."""
    got = tradeoff_rows(rows)
    if got is None:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    col, label, pts = got
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    x = [r[col] for r in pts]
    y = [r["jam_probability"] for r in pts]
    err = [[max(0.0, p - r["jam_ci95_low"]) for p, r in zip(y, pts)], [max(0.0, r["jam_ci95_high"] - p)
                                                                         for p, r in zip(y, pts)]]
    colours = ["#1a7f37" if r["status"] == "pass" else "#cf222e" for r in pts]
    ax.errorbar(x, y, yerr=err, fmt="none", ecolor="#888", lw=0.8, capsize=2)
    ax.scatter(x, y, c=colours, s=26, zorder=3)
    for r in pts:
        ax.annotate(", ".join(f"{r['values'][k]:g}" if isinstance(r["values"][k], float) else str(r["values"][k])
                              for k in keys), (r[col], r["jam_probability"]), fontsize=6, xytext=(3, 3),
                    textcoords="offset points", color="#444")
    if target is not None:
        ax.axhline(target, color="#f58518", lw=1, ls="--", label=f"target {100 * target:g} %")
        ax.legend(fontsize=7)
    ax.set_xlabel(label)
    ax.set_ylabel("P(jam)")
    ax.set_title(f"P(jam) against what play costs (labels: {', '.join(keys)})", fontsize=8)
    ax.grid(alpha=0.3)
    return R.figure_png(fig, 110, "tight")
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


def sweep_page(rows: list[dict], keys: list[str], title: str, subtitle: str, target: float | None = None) -> str:
    """One self-contained HTML page: pass/fail and every metric against each varied key, the trade-off
    of P(jam) against what play costs (when the points have both), the table."""
    n = len(rows)
    counts = {s: sum(r["status"] == s for r in rows) for s in ("pass", "fail", "refused")}
    intro = (f"<p>{n} design points: <span class=\"ok\">{counts['pass']} pass</span>, <span class=\"fail\">"
             f"{counts['fail']} fail</span> `partgen check`, {counts['refused']} refused (the design cannot be built)."
             "</p>")
    sections = [("Summary", intro)]
    trade = tradeoff_png(rows, keys, target)
    if trade is not None:
        col, label, pts = tradeoff_rows(rows)
        tab = [[r["point"], *[r["values"][k] for k in keys], r[col], f"{100 * r['jam_probability']:.2f} %",
                f"{100 * r['jam_ci95_low']:.2f}–{100 * r['jam_ci95_high']:.2f} %", r["status"]] for r in pts]
        sections.append(("The trade-off: P(jam) against what play costs",
                         "<p>More play: fewer prints jam, and the kit moves further from its nominal motion. Each point "
                         f"is a design; x: {html.escape(label)}; y: P(jam) with its 95 % interval (tradeoff.csv, "
                         "tradeoff.png).</p>" + f"<figure>{R.img(trade, 'P(jam) against ' + label)}</figure>"
                         + R.table(["point", *keys, label, "P(jam)", "95 % interval", "status"], tab, left=1)))
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
