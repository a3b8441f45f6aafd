"""config.yamlio reads a design with libyaml when it is there and falls back to the pure-Python
parser for text libyaml refuses: what a file means and how its errors read are the pure parser's
(``_FastLoader`` off gives the same answers)."""

from pathlib import Path

import pytest

from partgen.config import yamlio
from partgen.errors import ConfigError

ROOT = Path(__file__).resolve().parents[2]
TEXTS = ["a: [1, 2", "a:\n\tb: 1", "a: 1\na: 2", "a:\n  b: 1\n c: 2", "a: 'x", "[" * 40 + "]" * 40, "a: &x [*x]",
         "a: b: c", "\x00", "a: \x07", "- a\nb: 1", "a: !!python/object:os.system 1", "a: *nope", "a: 1\n---\nb: 2",
         "a: {b: 1, b: 2}", "? [1]\n: 2", "a: 1e3\nb: 012\nc: yes\nd: .inf\ne: 0x1F\nf: 2001-01-01", 'k: "\\q"',
         "a: |\n  x\n y", "\ufeffa: 1", "", "# only", "a: 1e400"]


def _read_all() -> list:
    out = []
    for t in TEXTS:
        try:
            out.append(("ok", repr(yamlio.parse_yaml(t, Path("x.yaml")))))
        except ConfigError as e:
            out.append(("error", str(e)))
    for f in sorted((ROOT / "configs").rglob("*.yaml")) + sorted((ROOT / "tests" / "designs").glob("*.yaml")):
        out.append(("ok", repr(yamlio.read_yaml_file(f))))
    return out


def test_libyaml_and_the_pure_parser_read_and_refuse_alike(monkeypatch):
    assert yamlio._FastLoader is not None  # PyYAML's wheels carry libyaml
    fast = _read_all()
    monkeypatch.setattr(yamlio, "_FastLoader", None)
    assert _read_all() == fast
    assert sum(kind == "error" for kind, _ in fast) >= 15


def test_refused_text_is_worded_by_the_pure_parser():
    """libyaml would say neither the character nor the alias's name."""
    with pytest.raises(ConfigError, match=r"line 2, column 1: found character '\\t' that cannot start any token"):
        yamlio.parse_yaml("a:\n\tb: 1", Path("x.yaml"))
    with pytest.raises(ConfigError, match="found undefined alias 'nope'"):
        yamlio.parse_yaml("a: *nope", Path("x.yaml"))
