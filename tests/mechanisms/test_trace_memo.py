"""``mechanisms.trace_memo``: the last traces a process made, kept in memory (report's trace of the
kit it checks, a `trace` then a `report` of one kit in one process). A hit needs the same kind, the
very kit object, an equal design and the same samples; it hands back a copy and writes the first
trace's figure bytes into the new folder; the memo is bounded."""

import dataclasses
import json

import numpy as np
import pytest

from partgen import pipeline
from partgen.core.protocol import Trace
from partgen.mechanisms import trace_memo
from partgen.mechanisms.wrist import trace as wrist_trace
from helpers import ROOT


@dataclasses.dataclass(frozen=True)
class Spec:
    name: str


class Kit:
    pass


@pytest.fixture(autouse=True)
def empty():
    trace_memo._TRACES.clear()
    yield
    trace_memo._TRACES.clear()


def counting(calls):
    def compute(folder):
        calls.append(folder)
        if folder is not None:
            (folder / "a.png").write_bytes(b"png %d" % len(calls))
        return Trace({"n": len(calls), "rows": [1, 2]}, ["a.png"] if folder else [], columns=("x",),
                     data=np.arange(3.0) * len(calls))
    return compute


def test_a_hit_needs_the_kind_the_kit_object_an_equal_design_and_the_samples(tmp_path):
    calls, kit = [], Kit()
    f = counting(calls)
    first = trace_memo.remembered("k", Spec("a"), kit, 8, None, f)
    assert len(calls) == 1 and first.stats["n"] == 1
    again = trace_memo.remembered("k", Spec("a"), kit, 8, None, f)  # an equal design, another object
    assert len(calls) == 1 and again.stats == first.stats and again.data.tobytes() == first.data.tobytes()
    for kind, spec, k, samples in (("other", Spec("a"), kit, 8), ("k", Spec("b"), kit, 8), ("k", Spec("a"), Kit(), 8),
                                   ("k", Spec("a"), kit, 9)):
        n = len(calls)
        trace_memo.remembered(kind, spec, k, samples, None, f)
        assert len(calls) == n + 1, (kind, spec, samples)
    assert len(trace_memo._TRACES) == trace_memo.KEPT == 2  # bounded: the oldest went


def test_the_figures_come_back_into_the_new_folder_and_the_copies_are_the_callers(tmp_path):
    calls, kit = [], Kit()
    f = counting(calls)
    trace_memo.remembered("k", Spec("a"), kit, None, None, f)
    (tmp_path / "1").mkdir(), (tmp_path / "2").mkdir()
    made = trace_memo.remembered("k", Spec("a"), kit, None, tmp_path / "1", f)  # no figures kept: a miss
    assert len(calls) == 2 and made.files == ("a.png",)
    made.stats["rows"].append(3)
    made.data[:] = -1.0
    hit = trace_memo.remembered("k", Spec("a"), kit, None, tmp_path / "2", f)
    assert len(calls) == 2 and hit.files == ("a.png",)
    assert (tmp_path / "2" / "a.png").read_bytes() == (tmp_path / "1" / "a.png").read_bytes() == b"png 2"
    assert hit.stats == {"n": 2, "rows": [1, 2]} and hit.data.tolist() == [0.0, 2.0, 4.0]
    bare = trace_memo.remembered("k", Spec("a"), kit, None, None, f)  # with figures kept, a bare trace hits too
    assert len(calls) == 2 and bare.files == ()


def test_an_incomparable_design_misses():
    class Raises:
        def __eq__(self, other):
            raise ValueError("ambiguous")
    calls, kit = [], Kit()
    f = counting(calls)
    for spec in (object(), object(), Raises(), Raises()):
        trace_memo.remembered("k", spec, kit, 4, None, f)
    assert len(calls) == 4


def test_the_wrist_traces_its_design_once_with_the_same_figures(tmp_path, monkeypatch):
    """(the wrist's trace reads the design alone: `report`, which passes the kit, shares `trace`'s)"""
    loaded = pipeline.load(ROOT / "tests" / "designs" / "wrist_small.yaml")
    calls = []
    real = wrist_trace._trace
    monkeypatch.setattr(wrist_trace, "_trace", lambda *a: calls.append(a) or real(*a))
    (tmp_path / "t").mkdir(), (tmp_path / "r").mkdir()
    first = loaded.mechanism.trace(loaded.spec, None, 64, tmp_path / "t", True)
    again = loaded.mechanism.trace(pipeline.load(ROOT / "tests" / "designs" / "wrist_small.yaml").spec, object(), 64,
                                   tmp_path / "r", False)
    assert len(calls) == 1
    assert json.dumps(again.stats) == json.dumps(first.stats) and again.data.tobytes() == first.data.tobytes()
    assert again.files == first.files and "wrist.png" in first.files
    assert all((tmp_path / "r" / n).read_bytes() == (tmp_path / "t" / n).read_bytes() for n in first.files)
    loaded.mechanism.trace(loaded.spec, None, 65, None, True)  # other samples: traced anew
    assert len(calls) == 2


def test_a_figure_made_on_request_is_needed_or_left_out(tmp_path):
    calls, kit = [], Kit()

    def compute(folder):
        calls.append(folder)
        names = ["a.png", "anim.gif"] if len(calls) == 2 else ["a.png"]
        for n in names:
            (folder / n).write_bytes(n.encode())
        return Trace({}, names)
    for d in "123":
        (tmp_path / d).mkdir()
    trace_memo.remembered("k", Spec("a"), kit, None, tmp_path / "1", compute, without=("anim.gif",))
    trace_memo.remembered("k", Spec("a"), kit, None, tmp_path / "2", compute, needs=("anim.gif",))  # kept: no gif
    assert len(calls) == 2
    bare = trace_memo.remembered("k", Spec("a"), kit, None, tmp_path / "3", compute, without=("anim.gif",))
    assert len(calls) == 2 and bare.files == ("a.png",) and sorted(p.name for p in (tmp_path / "3").iterdir()) == ["a.png"]


@dataclasses.dataclass(frozen=True, eq=False)
class Drawn:
    samples: np.ndarray
    scale: float


def test_designs_are_the_same_field_by_field_arrays_by_bytes_floats_by_bits():
    same = trace_memo._same
    assert same(Drawn(np.arange(3.0), 1.0), Drawn(np.arange(3.0), 1.0))  # eq=False: compared by fields
    assert not same(Drawn(np.arange(3.0), 1.0), Drawn(np.arange(3.0) + 1e-15, 1.0))
    assert not same(Drawn(np.arange(3.0), 0.0), Drawn(np.arange(3.0), -0.0))
    assert not same(Drawn(np.arange(3.0), 1.0), Drawn(np.arange(3), 1.0))  # another dtype
    assert same((1, {"a": [2.5]}), (1, {"a": [2.5]})) and not same((1, {"a": [2.5]}), (1, {"b": [2.5]}))
    assert not same(object(), object())


def test_the_chain_traces_its_design_once(monkeypatch):
    """(the gear chain's trace reads the design alone: `report`, which passes the kit, shares
    `trace`'s; its figures and animation: test_a_figure_made_on_request_is_needed_or_left_out)"""
    from partgen.mechanisms.gear_chain import trace as chain_trace

    cfg = ROOT / "tests" / "designs" / "negative_clearance.yaml"  # a chain that loads in milliseconds
    calls = []
    real = chain_trace._trace
    monkeypatch.setattr(chain_trace, "_trace", lambda *a: calls.append(a) or real(*a))
    mech = pipeline.load(cfg).mechanism
    first = mech.trace(pipeline.load(cfg).spec, None, 64, None, True)
    again = mech.trace(pipeline.load(cfg).spec, object(), 64, None, False)
    assert len(calls) == 1
    assert json.dumps(again.stats) == json.dumps(first.stats) and again.data.tobytes() == first.data.tobytes()
    spec = pipeline.load(cfg).spec
    other = dataclasses.replace(spec, mechanism=dataclasses.replace(spec.mechanism, scale=spec.mechanism.scale * 2))
    mech.trace(other, None, 64, None, True)  # another design
    assert len(calls) == 2
