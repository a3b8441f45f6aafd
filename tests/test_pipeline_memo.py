"""pipeline.checked and pipeline.traced: a design's kit is checked, and its motion traced, once per
process for given samples (``check`` or ``trace`` then ``report`` share them); another design,
printer or sample count is checked or traced anew, and a caller's changes to its copy never reach
the next caller. A trace comes back with its figures' bytes written into the caller's folder."""

import json
from pathlib import Path

import numpy as np
import pytest

from partgen import pipeline
from partgen.core.findings import Finding
from partgen.core.protocol import Trace

ROOT = Path(__file__).resolve().parents[1]
PAIR = ROOT / "configs" / "gear_pair.yaml"
CHAIN = ROOT / "tests" / "designs" / "negative_clearance.yaml"  # a chain that loads in milliseconds


def test_a_check_is_made_once_per_design_and_samples(monkeypatch):
    loaded = pipeline.load(PAIR)
    kit = pipeline.make_kit(loaded)
    calls = []
    real = loaded.mechanism.check

    def counted(spec, kit, samples, progress):
        calls.append(samples)
        return real(spec, kit, samples, progress)
    monkeypatch.setattr(loaded.mechanism, "check", counted)  # the registered mechanism object, this test only
    pipeline._CHECKS.clear()
    first = pipeline.checked(loaded, kit, 8)
    first.add(Finding("x", "fail", "a caller's own finding"))  # a caller changes its copy
    again = pipeline.checked(loaded, kit, 8)
    assert calls == [8]
    assert not any(f.check == "x" for f in again.findings)
    assert again.figures == pipeline.checked(loaded, kit, 8).figures
    pipeline.checked(loaded, kit, 12)  # other samples: checked anew
    other = pipeline.load(PAIR, over=pipeline.overrides(["gears.face_width_mm=7"]))
    pipeline.checked(other, pipeline.make_kit(other), 8)  # another design: checked anew
    assert calls == [8, 12, 8]


@pytest.fixture
def no_traces():
    pipeline._TRACES.clear()
    yield
    pipeline._TRACES.clear()


def _counted_trace(monkeypatch, loaded, fake=None):
    """Count the registered mechanism's trace calls (this test only); ``fake(calls, out, animate)``
    stands in for the real trace."""
    calls = []
    real = loaded.mechanism.trace

    def counted(spec, kit, samples, out, animate=True):
        calls.append((samples, out, animate))
        return fake(calls, out, animate) if fake else real(spec, kit, samples, out, animate)
    monkeypatch.setattr(loaded.mechanism, "trace", counted)
    return calls


def test_a_trace_is_made_once_per_design_and_samples(monkeypatch, tmp_path, no_traces):
    """The chain traces its design: `trace` (animated) and then `report` (not) trace it once."""
    loaded = pipeline.load(CHAIN)
    calls = _counted_trace(monkeypatch, loaded)
    first = pipeline.traced(loaded, None, 64, None, True)
    again = pipeline.traced(pipeline.load(CHAIN), object(), 64, None, False)
    assert len(calls) == 1
    assert json.dumps(again.stats) == json.dumps(first.stats) and again.data.tobytes() == first.data.tobytes()
    pipeline.traced(loaded, None, 65, None)  # other samples: traced anew
    other = pipeline.load(CHAIN, over=pipeline.overrides(["curve.scale_mm_per_unit=33"]))
    pipeline.traced(other, None, 64, None)  # another design: traced anew
    assert len(calls) == 3
    assert len(pipeline._TRACES) == pipeline._TRACES_KEPT == 2  # bounded: the oldest went


def _figures(calls, out, animate):
    names = ["a.png"] + (["anim.gif"] if animate else [])
    for n in names if out is not None else ():
        (out / n).write_bytes(b"%s %d" % (n.encode(), len(calls)))
    return Trace({"n": len(calls), "rows": [1, 2]}, names if out is not None else [], columns=("x",),
                 data=np.arange(3.0) * len(calls), animation=("anim.gif",))


def test_figures_come_back_into_the_new_folder_and_the_copies_are_the_callers(monkeypatch, tmp_path, no_traces):
    loaded = pipeline.load(PAIR)
    calls = _counted_trace(monkeypatch, loaded, _figures)
    for d in "1234":
        (tmp_path / d).mkdir()
    pipeline.traced(loaded, None, 8, None, False)
    made = pipeline.traced(loaded, None, 8, tmp_path / "1", False)  # kept without figures: traced anew
    assert len(calls) == 2 and made.files == ("a.png",)
    made.stats["rows"].append(3)
    made.data[:] = -1.0
    hit = pipeline.traced(loaded, None, 8, tmp_path / "2", False)
    assert len(calls) == 2 and hit.files == ("a.png",)
    assert (tmp_path / "2" / "a.png").read_bytes() == (tmp_path / "1" / "a.png").read_bytes() == b"a.png 2"
    assert hit.stats == {"n": 2, "rows": [1, 2]} and hit.data.tolist() == [0.0, 2.0, 4.0]
    assert pipeline.traced(loaded, None, 8, None, True).files == () and len(calls) == 2  # a bare trace hits too
    # kept without its animation: an animated trace is made anew; kept with it, it is left out when not asked
    animated = pipeline.traced(loaded, None, 8, tmp_path / "3", True)
    assert len(calls) == 3 and animated.files == ("a.png", "anim.gif")
    still = pipeline.traced(loaded, None, 8, tmp_path / "4", False)
    assert len(calls) == 3 and still.files == ("a.png",)
    assert sorted(p.name for p in (tmp_path / "4").iterdir()) == ["a.png"]
