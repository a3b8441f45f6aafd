"""core.cache: partgen's remembered decisions (auto play) — the same answer as computing it, under
a key that changes with the design, and nothing when the cache is off or unreadable."""

import json
import re
from pathlib import Path

import pytest

from partgen import pipeline
from partgen.core import cache
from partgen.mechanisms import autoplay


@pytest.fixture
def own_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("PARTGEN_CACHE_DIR", str(tmp_path / "c"))
    monkeypatch.delenv("PARTGEN_CACHE", raising=False)
    return tmp_path / "c"


def test_remember_recall_and_keys(own_cache):
    assert cache.recall("t", b"a") is None
    cache.remember("t", b"a", {"x": 0.1, "y": [1, 2]})
    assert cache.recall("t", b"a") == {"x": 0.1, "y": [1, 2]}
    assert cache.recall("t", b"b") is None and cache.recall("u", b"a") is None
    files = list(own_cache.rglob("*"))
    assert all(f.suffix == ".json" or f.is_dir() for f in files) and not any(f.name.startswith(".tmp") for f in files)


def test_off_and_unreadable(own_cache, monkeypatch):
    cache.remember("t", b"a", 1)
    (path,) = own_cache.rglob("*.json")
    path.write_text("{not json")
    assert cache.recall("t", b"a") is None  # a broken file is a miss, not an error
    monkeypatch.setenv("PARTGEN_CACHE", "0")
    cache.remember("t", b"z", 2)
    assert cache.recall("t", b"z") is None and cache.cache_dir() is None
    assert not any("z" == json.loads(p.read_text()).get("value") for p in own_cache.rglob("*.json") if p != path)


def test_auto_play_remembered_is_what_the_search_chooses(own_cache, monkeypatch, tmp_path):
    """A second process (the in-process memo cleared) reads the choice instead of searching, and
    gets the same number and allocation; a changed design is another key: searched again."""
    text = (Path(__file__).resolve().parents[2] / "configs" / "gear_pair.yaml").read_text()
    assert "backlash_per_gear_mm" in text
    design = tmp_path / "pair.yaml"
    design.write_text(re.sub(r"backlash_per_gear_mm: [0-9.]+", "backlash_per_gear_mm: auto", text, count=1))
    autoplay._DONE.clear()
    first = pipeline.load(design)
    assert first.auto is not None
    calls = []
    real = autoplay.least_allocation
    monkeypatch.setattr(autoplay, "least_allocation", lambda *a, **k: calls.append(1) or real(*a, **k))
    autoplay._DONE.clear()
    again = pipeline.load(design)
    assert calls == [] and again.auto == first.auto
    assert again.spec == first.spec
    design.write_text(design.read_text() + "\n# edited\n")
    autoplay._DONE.clear()
    pipeline.load(design)
    assert calls == []  # a comment is not the design: the same document, the same key
    text2 = design.read_text()
    design.write_text(re.sub(r"name:\s*(\S+)", r"name: \1_b", text2, count=1))
    autoplay._DONE.clear()

    class Searched(Exception):
        """The search reached its allocation step: stopped there (its end is the first load's)."""

    def stop(*a, **k):
        calls.append(1)
        raise Searched
    monkeypatch.setattr(autoplay, "least_allocation", stop)
    with pytest.raises(Searched):
        pipeline.load(design)
    assert calls == [1]  # another design: searched
