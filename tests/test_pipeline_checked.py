"""pipeline.checked: a design's kit is checked once per process for given samples (``check`` then
``report`` share it); another design, printer or sample count is checked anew, and a caller's
changes to its copy never reach the next caller."""

from pathlib import Path

from partgen import pipeline
from partgen.core.findings import Finding

ROOT = Path(__file__).resolve().parents[1]
PAIR = ROOT / "configs" / "gear_pair.yaml"


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
