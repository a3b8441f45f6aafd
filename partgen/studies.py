"""Studies of many runs, on a Dask cluster (``partgen.cluster``): the tolerance Monte Carlo of one
kit (``tolerance``) and the design-space sweep (``sweep``, in ``partgen.sweep``).

``tolerance``: one nominal check of the kit gives the margins that decide whether it turns; the
mechanism's ``tolerance_model`` hook writes them as linear functions of the printed features'
deviations (``design.tolerance``); the samples are drawn in chunks of CHUNK, chunk i from
``SeedSequence(seed, spawn_key=(i,))``, on the cluster's workers. Each finished chunk is appended
to ``<out>/chunks.jsonl`` as it arrives; ``resume`` runs only the chunks not there yet. The tallies
are added in chunk order, so the result is the same for any number of workers.
"""

from __future__ import annotations

import json
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path

from . import cluster as C
from . import pipeline
from .core.protocol import tolerance_hook
from .design.tolerance import ChunkTally, MarginModel, add_tallies, chunk_sizes, run_chunk, summarise
from .errors import ConfigError, OptionError
from .export.biases import biased_model
from .export.outputs import open_incremental
from .export.studies import play_cost
from .export.prints import printed_groups, stale_files

__all__ = ["CHUNK", "default_chunk", "ToleranceRun", "tolerance", "sample", "nominal_model", "Vary", "parse_vary", "sweep_points", "sweep_point", "sweep"]

CHUNK = 5000  # samples per task, at least: ~30 ms of numpy, ~10x the ~3 ms of CPU the local client and scheduler spend on a task
TASKS = 16  # a study of many samples is cut into about this many tasks (at most MAX_CHUNK samples each)
MAX_CHUNK = 100_000
MAX_POINTS = 100_000  # design points of one sweep

TASK_MAX_BYTES = 2 << 30  # a task's arrays (run_chunk's draws, margins and their temporaries), at most
TASK_BYTES_PER_TERM = 12  # bytes a sample holds per feature and per margin at run_chunk's peak (measured: 11.3)


def default_chunk(samples: int) -> int:
    """Samples per task for a study of ``samples``: CHUNK, or a 1/TASKS share of a large study (so
    the scheduler's cost per task is a small part of it: 300,000 samples on 2 local workers ran
    1.69× faster than on 1 in chunks of 1,000 and 1.76-1.83× in chunks of ~20,000; 10,000 samples
    1.29×, 1.43× and 1.53× in chunks of 1,000, 2,500 and 5,000). It depends on the samples only,
    never on the workers: with the seed it fixes the result."""
    return int(min(MAX_CHUNK, max(CHUNK, math.ceil(samples / TASKS))))
FILES = ["chunks.jsonl", "result.json"]


@dataclass(frozen=True)
class ToleranceRun:
    loaded: object
    result: dict  # summarise(...) plus the run's settings and timings
    dest: Path | None


def modelled_kinds() -> list[str]:
    """The kinds whose mechanism offers a tolerance model."""
    from .mechanisms import REGISTRY

    return [k for k, m in REGISTRY.items() if tolerance_hook(m) is not None]


def nominal_model(loaded, accuracy_mm: float | None, check_samples: int | None = None, progress: bool = False,
                  kit=None, seated: bool = True):
    """(model, nominal check result, seconds of the check): the kit built once (or ``kit``), checked
    once (``progress``: a progress line over the check's samples of the motion, on a terminal). ``seated``:
    the gears sit where their meshes push them in their bores (docs/tolerance.md); ``worst_model``
    gives the same check's model with every gear centred."""
    hook = tolerance_hook(loaded.mechanism)
    if hook is None:
        raise ConfigError(loaded.path, "kind", f"a {loaded.mechanism.kind} design offers no tolerance study yet "
                          f"(`partgen tolerance` runs on kind: {', '.join(modelled_kinds())})")
    kit = kit if kit is not None else pipeline.make_kit(loaded)
    t0 = time.perf_counter()
    bar = C.Counter(f"nominal check, {loaded.mechanism.motion.label}", 1, progress)

    def angles(done: int, total: int) -> None:
        bar.total = total
        bar(done - bar.done)
    result = loaded.mechanism.check(loaded.spec, kit, check_samples, angles if bar.enabled else None)
    seconds = time.perf_counter() - t0
    acc = kit.printer.xy_accuracy if accuracy_mm is None else accuracy_mm
    return biased_model(hook(loaded.spec, kit, result, acc, seated=seated), kit), result, seconds


def worst_model(loaded, kit, result, accuracy_mm: float | None):
    """The model of the same nominal check with every gear centred on its post (no bore play
    credited): the worst case reported beside the headline figure."""
    acc = kit.printer.xy_accuracy if accuracy_mm is None else accuracy_mm
    return biased_model(tolerance_hook(loaded.mechanism)(loaded.spec, kit, result, acc, seated=False), kit)


def _write_atomic(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)


def _resume_state(path: Path, header: dict) -> dict[int, ChunkTally]:
    """The chunks a previous run of the same study finished (``OptionError`` on --resume when the
    folder holds another study)."""
    if not path.is_file():
        return {}
    lines = path.read_text(encoding="utf-8").splitlines()
    try:
        head = json.loads(lines[0]) if lines else {}
    except ValueError:
        head = {}
    if {k: head.get(k) for k in header} != header:
        diff = [k for k in header if head.get(k) != header[k]]
        raise OptionError("--resume", str(path.parent), "holds chunks of another study (its "
                          f"{', '.join(diff) or 'header'} differ): run without --resume to start over")
    done = {}
    for line in lines[1:]:
        try:
            t = ChunkTally.from_dict(json.loads(line))
        except (ValueError, KeyError, TypeError):
            continue  # a line cut short by an interruption: that chunk runs again
        done[t.index] = t
    return done


def sample(client, model: MarginModel, samples: int, seed: int, claim=None, resume: bool = False,
           header: dict | None = None, progress: bool = False, chunk: int | None = None) -> tuple[ChunkTally, dict]:
    """Draw ``samples`` of ``model`` on ``client``'s workers in chunks of ``chunk``; with a
    ``claim`` (an output folder checked before any work), append each chunk to its chunks.jsonl as
    it arrives (``resume``: keep the chunks a previous run with the same header finished there).
    Returns the tallies added in chunk order, and facts of the run (chunks, resumed_chunks,
    workers, seconds, dest)."""
    chunk = chunk or default_chunk(samples)
    F, K = model.coeff.shape
    need = min(chunk, samples) * (F + K) * TASK_BYTES_PER_TERM
    if need > TASK_MAX_BYTES:  # before anything is written or sent
        most = TASK_MAX_BYTES // ((F + K) * TASK_BYTES_PER_TERM)
        raise OptionError("--chunk", str(chunk), f"a task of {min(chunk, samples):,} samples of this model ({F} "
                          f"features, {K} margins) would need ~{need / 1e9:.1f} GB on its worker: at most "
                          f"{most:,} samples a task")
    sizes = chunk_sizes(samples, chunk)
    header = {**(header or {}), "model": model.digest(), "seed": int(seed), "samples": int(samples),
              "chunk": int(chunk)}
    done: dict[int, ChunkTally] = {}
    out = None
    if claim is not None:
        out = claim.dest
        if resume:
            done = _resume_state(out / "chunks.jsonl", header)
        open_incremental(claim, FILES, keep=resume and bool(done))
        if not done:
            (out / "chunks.jsonl").write_text(json.dumps(header) + "\n", encoding="utf-8")
    todo = [(i, (int(seed), i, n)) for i, n in enumerate(sizes) if i not in done]
    counter = C.Counter("samples", samples, progress, sum(t.n for t in done.values()))
    sink = open(out / "chunks.jsonl", "a", encoding="utf-8") if out is not None else None
    got = dict(done)

    def keep(key, tally):
        got[key] = tally
        if sink is not None:
            sink.write(json.dumps(tally.to_dict()) + "\n")
            sink.flush()
        counter(tally.n)
    workers = len(client.scheduler_info().get("workers", {}))  # asks the scheduler: not part of the timing
    t1 = time.perf_counter()
    try:
        C.run(client, run_chunk, model, todo, keep, None, "tolerance")
    except BaseException as e:
        if out is not None and not isinstance(e, Exception):  # ^C or SIGTERM: say what is kept, and how to go on
            e.partgen_note = (f"the {len(got)} finished chunk(s) of {len(sizes)} are kept in {out}/chunks.jsonl: run "
                              "the same command with --resume to go on from there")
        raise
    finally:
        if sink is not None:
            sink.close()
    info = {"chunks": len(sizes), "resumed_chunks": len(done), "computed_chunks": len(todo),
            "workers": workers,
            "seconds": round(time.perf_counter() - t1, 3), "dest": out}
    return add_tallies(got.values()), info


def tolerance(target, samples: int, accuracy_mm: float | None = None, seed: int = 0, workers: int | None = None,
              scheduler: str | None = None, dest=None, resume: bool = False, check_samples: int | None = None,
              over=None, progress: bool = False, processes: bool | None = None, write: bool = True,
              chunk: int | None = None, exact: int | None = None) -> ToleranceRun:
    """The tolerance study of a design or kit folder: see the module's docstring. ``dest``: the
    folder for chunks.jsonl and result.json (default ``<kit>/tolerance`` or
    ``out/<name>/tolerance``); ``write=False``: nothing written."""
    if samples <= 0:
        raise OptionError("--samples", str(samples), "must be at least 1")
    chunk = chunk or default_chunk(samples)
    if accuracy_mm is not None and not (math.isfinite(accuracy_mm) and 0 <= accuracy_mm <= 5):
        raise OptionError("--accuracy-mm", str(accuracy_mm), "must be a number of mm from 0 to 5")
    raw, kit_dir = pipeline._raw(target, over)
    loaded = pipeline.load(target, raw)
    if tolerance_hook(loaded.mechanism) is None:
        nominal_model(loaded, accuracy_mm)  # raises the clear error
    if exact is not None and (exact <= 0 or getattr(loaded.mechanism, EXACT_HOOK, None) is None):
        raise OptionError("--exact", str(exact), "must be at least 1 print" if exact <= 0 else
                          f"a {loaded.mechanism.kind} design has no exact Monte Carlo yet (kind: "
                          f"{', '.join(k for k, m in _registry().items() if getattr(m, EXACT_HOOK, None))})")
    claim = None
    if write:
        claim = pipeline.output_claim(raw, Path(dest) if dest else None, "tolerance", "tolerance", "-o",
                                      kit_dir=kit_dir, over=over)
    # an unreachable scheduler: exit 2, nothing written; a local cluster starts beside the build and check
    with C.starting(workers, scheduler, processes) as get_client:
        kit = pipeline.make_kit(loaded)
        model, nominal, check_s = nominal_model(loaded, accuracy_mm, check_samples, progress, kit=kit)
        worst = worst_model(loaded, kit, nominal, accuracy_mm)
        t1 = time.perf_counter()
        client = get_client()
        t_cluster = time.perf_counter() - t1  # the wait for the cluster after the nominal check
        header = {"study": "tolerance", "design": raw.digest(), "seed": int(seed)}
        total, info = sample(client, model, samples, seed, claim, resume, header, progress, chunk)
        worst_total, _ = sample(client, worst, samples, seed, None, False, None, False, chunk)
        exact_result = None
        if exact:
            exact_result = exact_study(client, loaded, kit, nominal, model, exact, seed, progress)
    summary = summarise(model, total)
    summary["seat"] = model.credits or "gears pushed apart in their bores by their meshes (docs/tolerance.md)"
    summary["worst_case"] = {"seat": worst.credits or "every gear centred on its post: no bore play credited",
                             "model_digest": worst.digest(), **summarise(worst, worst_total)["overall"]}
    summary.update({"design": raw.design.name, "kind": loaded.mechanism.kind, "config": str(loaded.path),
                    "design_digest": header["design"], "model_digest": model.digest(), "seed": int(seed),
                    "chunk": int(chunk), "chunks": info["chunks"], "resumed_chunks": info["resumed_chunks"],
                    "nominal_check_ok": nominal.ok, "accuracy_source": "--accuracy-mm" if accuracy_mm is not None
                    else f"printer {raw.printer.name} xy_accuracy_mm"
                    + ("" if raw.printer.measured else ": typical, not measured"),
                    "workers": info["workers"], "seconds": {"cluster_wait": round(t_cluster, 3),
                                                            "nominal_check": round(check_s, 3),
                                                            "samples": info["seconds"]}})
    if exact_result is not None:
        lin = summary["overall"]["ci95"]
        ex = exact_result["ci95"]
        exact_result["agrees"] = bool(ex[0] <= lin[1] and lin[0] <= ex[1])  # the 95 % intervals overlap
        summary["exact"] = exact_result
    if kit_dir is not None:  # the study is of the design the folder's design.yaml builds: say if its STLs differ
        summary["kit_stale_files"] = stale_files(pipeline.make_kit(loaded), kit_dir)
    out = info["dest"]
    if out is not None:
        _write_atomic(out / "result.json", json.dumps(_json_safe(summary), indent=1))
    return ToleranceRun(loaded, summary, out)


EXACT_HOOK = "tolerance_exact"
EXACT_PER_TASK = 5  # prints a task makes (a print is ~20-60 ms: the scheduler's ~3-5 ms a task is then ~3 %)


def _exact_batch(job: dict, seed: int, first: int, n: int) -> list[dict]:
    """Prints first .. first + n - 1 (each one's deviations depend on the seed and its index only),
    each with the CPU time its thread spent on it (``cpu_seconds``: beside its wall ``seconds``, what
    a busy machine took from it)."""
    out = []
    for i in range(first, first + n):
        c0 = time.thread_time()
        row = job["fn"](job["shared"], seed, i)
        out.append({**row, "cpu_seconds": time.thread_time() - c0})
    return out


def _registry():
    from .mechanisms import REGISTRY

    return REGISTRY


def exact_study(client, loaded, kit, nominal, model, prints: int, seed: int, progress: bool = False) -> dict:
    """The exact Monte Carlo: ``prints`` perturbed prints of the kit's real geometry, one task
    each on ``client``'s workers (the mechanism's ``tolerance_exact`` hook: the task function and
    what it shares), gears seated as the linear model's (docs/tolerance.md). Print i's deviations
    come from ``SeedSequence(seed, spawn_key=(1, i))``: the result does not depend on the workers."""
    from .design.tolerance import wilson

    fn, shared = getattr(loaded.mechanism, EXACT_HOOK)(loaded.spec, kit, nominal, model)
    got: dict[int, dict] = {}
    counter = C.Counter("exact prints", prints, progress)

    def keep(key, rows):
        for row in rows:
            got[row["index"]] = row
        counter(len(rows))
    workers = len(client.scheduler_info().get("workers", {}))
    t0 = time.perf_counter()
    tasks = [(k, (int(seed), first, min(EXACT_PER_TASK, prints - first)))
             for k, first in enumerate(range(0, prints, EXACT_PER_TASK))]
    C.run(client, _exact_batch, {"fn": fn, "shared": shared}, tasks, keep, None, "exact")
    wall = time.perf_counter() - t0
    rows = [got[i] for i in range(prints)]
    jams = sum(r["jam"] for r in rows)
    why: dict[str, int] = {}
    for r in rows:
        if r["why"]:
            why[r["why"]] = why.get(r["why"], 0) + 1
    lo, hi = wilson(jams, prints)
    return {"prints": prints, "jams": jams, "probability": jams / prints, "ci95": [lo, hi], "why": why,
            "workers": workers, "seconds": round(wall, 3),
            "seconds_per_print": round(sum(r["seconds"] for r in rows) / prints, 4),
            "cpu_seconds_per_print": round(sum(r.get("cpu_seconds", 0.0) for r in rows) / prints, 4)}


def _json_safe(v):
    if isinstance(v, dict):
        return {str(k): _json_safe(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_json_safe(x) for x in v]
    if hasattr(v, "item") and not isinstance(v, (str, bytes)):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


# --------------------------------------------------------------------------------------------- sweep
@dataclass(frozen=True)
class Vary:
    """One ``--vary KEY=START:STOP:STEPS``: a key path (as --set) and its range."""

    key: str
    start: float
    stop: float
    steps: int
    integer: bool  # START and STOP were whole numbers: every value is rounded to a whole number
    text: str

    def values(self) -> list:
        import numpy as np

        v = np.linspace(self.start, self.stop, self.steps) if self.steps > 1 else np.array([self.start])
        if self.integer:  # more steps than whole numbers in the range: each value once
            return list(dict.fromkeys(int(round(x)) for x in v))
        return [float(round(x, 9)) for x in v]


def parse_vary(text: str) -> Vary:
    """``KEY=START:STOP:STEPS`` → Vary; ``OptionError`` on --vary for anything else."""
    key, eq, rng = text.partition("=")
    key = key.strip()
    parts = rng.split(":")
    if not eq or not key or len(parts) != 3:
        raise OptionError("--vary", text, "expected KEY=START:STOP:STEPS (gears.module_mm=1.2:1.6:5)")
    try:
        lo, hi = float(parts[0]), float(parts[1])
    except ValueError:
        raise OptionError("--vary", text, "START and STOP must be numbers") from None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise OptionError("--vary", text, "START and STOP must be finite numbers")
    try:
        steps = int(parts[2], 10)
    except ValueError:
        raise OptionError("--vary", text, "STEPS must be a whole number of points") from None
    if not 1 <= steps <= 10_000:
        raise OptionError("--vary", text, "STEPS must be 1 to 10,000 points")
    integer = all(p.strip().lstrip("+-").isdigit() for p in parts[:2])
    return Vary(key, lo, hi, steps, integer, text)


def sweep_points(varies: list[Vary], random: int | None = None, seed: int = 0) -> list[dict]:
    """The design points: the grid of every --vary's values, or ``random`` points drawn uniformly in
    the box they span (seeded; whole-number keys drawn as whole numbers)."""
    import itertools

    import numpy as np

    if random is None:
        return [dict(zip([v.key for v in varies], combo)) for combo in itertools.product(*(v.values() for v in varies))]
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    out = []
    for _ in range(random):
        point = {}
        for v in varies:
            x = rng.uniform(min(v.start, v.stop), max(v.start, v.stop))
            point[v.key] = int(round(x)) if v.integer else float(round(x, 9))
        out.append(point)
    return out


def _sets(values: dict, base_sets=()) -> tuple:
    from .config.overrides import parse_set

    return tuple(base_sets) + tuple(parse_set(f"{k}={v!r}") for k, v in values.items())


def sweep_point(shared: dict, index: int, values: dict) -> dict:
    """One design point built and checked (a task: a pure function of the design and the values).
    A point the design refuses is a row with status "refused" and the reason."""
    from .config.overrides import Overrides
    from .errors import PartgenError

    t0 = time.perf_counter()
    row = {"point": index, "values": values, "status": "refused", "ok": False, "failures": None,
           "first_failure": None, "mass_g": None, "size_mm": None, "parts": None, "least_clearance_mm": None,
           "jam_probability": None, "jam_ci95_low": None, "jam_ci95_high": None}
    over = Overrides(_sets(values, shared["sets"]), shared["printer"])
    try:
        loaded = pipeline.load(shared["config"], over=over)
        kit = pipeline.make_kit(loaded)
        result = loaded.mechanism.check(loaded.spec, kit, shared["check_samples"], None)
    except PartgenError as e:
        row["first_failure"] = str(e)
        row["seconds"] = round(time.perf_counter() - t0, 3)
        return row
    fails = [f for f in result.findings if f.severity == "fail"]
    groups = printed_groups(kit)
    close = result.figures.get("motion", {}).get("closest_approach")
    row.update(status="pass" if result.ok else "fail", ok=result.ok, failures=len(fails),
               first_failure=f"{fails[0].check}: {fails[0].message}" if fails else None,
               mass_g=round(sum(len(g) * float(g[0].mesh.volume) for g in groups) * kit.density, 2),
               size_mm=round(max(float(max(g[0].mesh.extents)) for g in groups), 2), parts=len(kit.parts),
               least_clearance_mm=None if close is None else float(close["mm"]))
    m = shared["tolerance_samples"]
    hook = tolerance_hook(loaded.mechanism)
    if m and hook is not None:
        model = biased_model(hook(loaded.spec, kit, result, kit.printer.xy_accuracy if shared["accuracy"] is None
                                  else shared["accuracy"]), kit)
        total = add_tallies([run_chunk(model, shared["seed"], i, n) for i, n in enumerate(chunk_sizes(m, CHUNK))])
        s = summarise(model, total)
        row.update(jam_probability=s["overall"]["probability"], jam_ci95_low=s["overall"]["ci95"][0],
                   jam_ci95_high=s["overall"]["ci95"][1])
        # what the play costs: the trace's pen band or lost motion (export.studies.play_cost)
        trace = loaded.mechanism.trace(loaded.spec, kit, None, None, False)
        row.update(play_cost(trace.stats))
    row["seconds"] = round(time.perf_counter() - t0, 3)
    return row


def sweep(config, varies: list[str], dest, random: int | None = None, tolerance_samples: int | None = None,
          accuracy_mm: float | None = None, seed: int = 0, workers: int | None = None, scheduler: str | None = None,
          check_samples: int | None = None, over=None, progress: bool = False, processes: bool | None = None) -> dict:
    """A design-space study of ``config`` (see `partgen sweep`). Every --vary is checked before any
    work (its key must exist in the design's schema, START and STOP must validate there), so bad
    input writes nothing. Rows are appended to ``dest``/points.jsonl as they arrive; at the end
    points.csv and index.html are written."""
    from .config.overrides import Overrides
    from .export.studies import sweep_csv, sweep_page, tradeoff_csv, tradeoff_png
    from .mechanisms import REGISTRY, load_design

    if not varies:
        raise OptionError("--vary", "", "give at least one KEY=START:STOP:STEPS")
    vs = [parse_vary(t) for t in varies]
    if len({v.key for v in vs}) != len(vs):
        raise OptionError("--vary", varies[-1], "a key is varied twice")
    if random is not None and random <= 0:
        raise OptionError("--random", str(random), "must be at least 1 point")
    if tolerance_samples is not None and tolerance_samples <= 0:
        raise OptionError("--tolerance-samples", str(tolerance_samples), "must be at least 1")
    over = over or Overrides()
    raw = load_design(config, over)  # the design itself must be valid
    if tolerance_samples and tolerance_hook(REGISTRY[raw.design.kind]) is None:
        raise OptionError("--tolerance-samples", str(tolerance_samples), f"a {raw.design.kind} design offers no "
                          f"tolerance study yet (P(jam) is modelled for kind: {', '.join(modelled_kinds())})")
    for v in vs:
        for x in {v.start, v.stop}:
            val = int(round(x)) if v.integer else x
            try:
                load_design(config, Overrides(_sets({v.key: val}, over.sets), over.printer))
            except ConfigError as e:
                raise OptionError("--vary", v.text, f"{v.key}={val:g} is not a valid design value: "
                                  f"{getattr(e, 'problem', e)}") from None
    count = random if random is not None else math.prod(len(v.values()) for v in vs)
    if count > MAX_POINTS:  # counted before the grid is made: three --vary of 10,000 steps are 10¹² points
        raise OptionError("--vary", varies[-1], f"{count:,} points: at most {MAX_POINTS:,}")
    points = sweep_points(vs, random, seed)
    claim = pipeline.output_claim(raw, Path(dest) if dest else Path("out") / raw.design.name / "sweep", "sweep", None,
                                  "-o")
    shared = {"config": str(config), "sets": tuple(over.sets), "printer": over.printer, "check_samples": check_samples,
              "tolerance_samples": tolerance_samples, "accuracy": accuracy_mm, "seed": int(seed)}
    keys = [v.key for v in vs]
    t0 = time.perf_counter()
    with C.cluster(workers, scheduler, processes) as client:
        out = open_incremental(claim, ["points.jsonl", "points.csv", "index.html", "tradeoff.csv", "tradeoff.png"])
        rows: dict[int, dict] = {}
        counter = C.Counter("points", len(points), progress)
        with open(out / "points.jsonl", "w", encoding="utf-8") as sink:
            def keep(key, row):
                rows[key] = row
                sink.write(json.dumps(_json_safe(row)) + "\n")
                sink.flush()
                counter()
            C.run(client, sweep_point, shared, [(i, (i, p)) for i, p in enumerate(points)], keep, None, "sweep")
        nworkers = len(client.scheduler_info().get("workers", {}))
    ordered = [rows[i] for i in sorted(rows)]
    _write_atomic(out / "points.csv", sweep_csv(ordered, keys))
    sub = (f"{raw.path.name}: {len(points)} points, " + ", ".join(v.text for v in vs)
           + (f"; {random} random points, seed {seed}" if random else "")
           + (f"; P(jam) from {tolerance_samples:,} simulated prints each" if tolerance_samples else ""))
    target = getattr(getattr(raw.design, "tolerance", None), "max_jam_probability", None)
    _write_atomic(out / "index.html", sweep_page(ordered, keys, f"partgen sweep: {raw.design.name}", sub, target))
    trade = tradeoff_png(ordered, keys, target)
    if trade is not None:
        (out / "tradeoff.png").write_bytes(trade)
        _write_atomic(out / "tradeoff.csv", tradeoff_csv(ordered, keys))
    return {"design": raw.design.name, "points": len(points), "keys": keys, "dest": str(out), "workers": nworkers,
            "seconds": round(time.perf_counter() - t0, 3),
            "pass": sum(r["status"] == "pass" for r in ordered), "fail": sum(r["status"] == "fail" for r in ordered),
            "refused": sum(r["status"] == "refused" for r in ordered), "rows": ordered}
