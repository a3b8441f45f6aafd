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
from .export.outputs import open_incremental

__all__ = ["CHUNK", "ToleranceRun", "tolerance", "sample", "nominal_model"]

CHUNK = 2000  # samples per task: a few tens of ms of numpy, well over the scheduler's per-task cost
FILES = ["chunks.jsonl", "result.json"]


@dataclass(frozen=True)
class ToleranceRun:
    loaded: object
    result: dict  # summarise(...) plus the run's settings and timings
    dest: Path | None


def nominal_model(loaded, accuracy_mm: float | None, check_samples: int | None = None):
    """(model, nominal check result, seconds of the check): the kit built once, checked once."""
    hook = tolerance_hook(loaded.mechanism)
    if hook is None:
        raise ConfigError(loaded.path, "kind", f"a {loaded.mechanism.kind} design offers no tolerance study yet "
                          "(`partgen tolerance` runs on kind: gear_chain)")
    kit = pipeline.make_kit(loaded)
    t0 = time.perf_counter()
    result = loaded.mechanism.check(loaded.spec, kit, check_samples, None)
    seconds = time.perf_counter() - t0
    acc = kit.printer.xy_accuracy if accuracy_mm is None else accuracy_mm
    return hook(loaded.spec, kit, result, acc), result, seconds


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
           header: dict | None = None, progress: bool = False, chunk: int = CHUNK) -> tuple[ChunkTally, dict]:
    """Draw ``samples`` of ``model`` on ``client``'s workers in chunks of ``chunk``; with a
    ``claim`` (an output folder checked before any work), append each chunk to its chunks.jsonl as
    it arrives (``resume``: keep the chunks a previous run with the same header finished there).
    Returns the tallies added in chunk order, and facts of the run (chunks, resumed_chunks,
    workers, seconds, dest)."""
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
    t1 = time.perf_counter()
    try:
        C.run(client, run_chunk, model, todo, keep, None, "tolerance")
    finally:
        if sink is not None:
            sink.close()
    info = {"chunks": len(sizes), "resumed_chunks": len(done), "computed_chunks": len(todo),
            "workers": len(client.scheduler_info().get("workers", {})),
            "seconds": round(time.perf_counter() - t1, 3), "dest": out}
    return add_tallies(got.values()), info


def tolerance(target, samples: int, accuracy_mm: float | None = None, seed: int = 0, workers: int | None = None,
              scheduler: str | None = None, dest=None, resume: bool = False, check_samples: int | None = None,
              over=None, progress: bool = False, processes: bool = True, write: bool = True,
              chunk: int = CHUNK) -> ToleranceRun:
    """The tolerance study of a design or kit folder: see the module's docstring. ``dest``: the
    folder for chunks.jsonl and result.json (default ``<kit>/tolerance`` or
    ``out/<name>/tolerance``); ``write=False``: nothing written."""
    if samples <= 0:
        raise OptionError("--samples", str(samples), "must be at least 1")
    if accuracy_mm is not None and not (math.isfinite(accuracy_mm) and 0 <= accuracy_mm <= 5):
        raise OptionError("--accuracy-mm", str(accuracy_mm), "must be a number of mm from 0 to 5")
    raw, kit_dir = pipeline._raw(target, over)
    loaded = pipeline.load(target, raw)
    if tolerance_hook(loaded.mechanism) is None:
        nominal_model(loaded, accuracy_mm)  # raises the clear error
    claim = None
    if write:
        claim = pipeline.output_claim(raw, Path(dest) if dest else (kit_dir / "tolerance" if kit_dir else None),
                                      "tolerance", "tolerance", "-o")
    t0 = time.perf_counter()
    with C.cluster(workers, scheduler, processes) as client:  # an unreachable scheduler: exit 2, nothing written
        t_cluster = time.perf_counter() - t0
        model, nominal, check_s = nominal_model(loaded, accuracy_mm, check_samples)
        header = {"study": "tolerance", "design": pipeline.design_digest(raw), "seed": int(seed)}
        total, info = sample(client, model, samples, seed, claim, resume, header, progress, chunk)
    summary = summarise(model, total)
    summary.update({"design": raw.design.name, "kind": loaded.mechanism.kind, "config": str(loaded.path),
                    "design_digest": header["design"], "model_digest": model.digest(), "seed": int(seed),
                    "chunk": int(chunk), "chunks": info["chunks"], "resumed_chunks": info["resumed_chunks"],
                    "nominal_check_ok": nominal.ok, "accuracy_source": "--accuracy-mm" if accuracy_mm is not None
                    else f"printer {raw.printer.name} xy_accuracy_mm",
                    "workers": info["workers"], "seconds": {"cluster": round(t_cluster, 3),
                                                            "nominal_check": round(check_s, 3),
                                                            "samples": info["seconds"]}})
    out = info["dest"]
    if out is not None:
        _write_atomic(out / "result.json", json.dumps(_json_safe(summary), indent=1))
    return ToleranceRun(loaded, summary, out)


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
