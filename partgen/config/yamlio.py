"""Read a YAML file the way a design must be read: safely and as YAML 1.2.

* Only regular files, at most ``MAX_BYTES``; FIFOs, devices, folders are refused before opening
  (a FIFO would block, ``/dev/zero`` would never end).
* YAML 1.2 core schema for plain scalars: ``1e-3`` is a number (PyYAML's YAML 1.1 resolver
  needs a dot), ``012`` is twelve, ``yes``/``no``/``on`` and dates are strings, ``.inf`` and
  ``.nan`` are read (and refused later by the schema, which wants finite numbers).
* A key given twice in one mapping is an error (YAML forbids it; PyYAML keeps the last silently).
* Nesting deeper than ``MAX_DEPTH`` is refused while parsing (libyaml's composer recurses in C and
  crashes on deep nesting), and aliases may not expand past ``MAX_VALUES`` values (alias bombs)
  or refer to themselves.

Errors are ``ConfigError(file, key path, problem)``; the content of the file is never echoed
beyond the key path.
"""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

import yaml
from yaml.constructor import SafeConstructor
from yaml.nodes import MappingNode, ScalarNode, SequenceNode
from yaml.resolver import BaseResolver

from ..errors import ConfigError

__all__ = ["read_yaml_file", "parse_yaml", "dump_yaml", "MAX_BYTES", "MAX_DEPTH", "MAX_VALUES"]

MAX_BYTES = 10 * 1024 * 1024
MAX_DEPTH = 32
MAX_VALUES = 1_000_000


class _Resolver12(BaseResolver):
    """The YAML 1.2 core schema's implicit tags."""


_Resolver12.add_implicit_resolver("tag:yaml.org,2002:bool", re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$"),
                                  list("tTfF"))
_Resolver12.add_implicit_resolver("tag:yaml.org,2002:int", re.compile(r"^(?:[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+)$"),
                                  list("-+0123456789"))
_Resolver12.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$"),
    list("-+0123456789."))
_Resolver12.add_implicit_resolver("tag:yaml.org,2002:null", re.compile(r"^(?:~|null|Null|NULL|)$"), ["~", "n", "N", ""])


class _Constructor12(SafeConstructor):
    def construct_yaml_int(self, node):
        value = self.construct_scalar(node)
        if value.startswith("0o"):
            return int(value[2:], 8)
        if value.startswith("0x"):
            return int(value[2:], 16)
        return int(value, 10)

    def construct_yaml_float(self, node):
        value = self.construct_scalar(node).lower()
        if value.endswith(".inf"):
            return float("-inf") if value.startswith("-") else float("inf")
        if value == ".nan":
            return float("nan")
        return float(value)


_Constructor12.add_constructor("tag:yaml.org,2002:int", _Constructor12.construct_yaml_int)
_Constructor12.add_constructor("tag:yaml.org,2002:float", _Constructor12.construct_yaml_float)

from yaml.composer import Composer
from yaml.parser import Parser
from yaml.reader import Reader
from yaml.scanner import Scanner


class _Loader(Reader, Scanner, Parser, Composer, _Constructor12, _Resolver12):
    """The pure-Python parser: what decides what a file means, and words its errors."""

    def __init__(self, stream):
        Reader.__init__(self, stream)
        Scanner.__init__(self)
        Parser.__init__(self)
        Composer.__init__(self)
        _Constructor12.__init__(self)
        _Resolver12.__init__(self)


try:  # libyaml's parser (a tenth of the time): a file it reads is read by it; one it refuses is read again by _Loader
    from yaml.cyaml import CParser
except ImportError:  # pragma: no cover
    _FastLoader = None
else:
    class _FastLoader(CParser, _Constructor12, _Resolver12):  # type: ignore[no-redef]
        def __init__(self, stream):
            CParser.__init__(self, stream)
            _Constructor12.__init__(self)
            _Resolver12.__init__(self)


class _Refused(Exception):
    """libyaml refused the text: the pure-Python parser reads it again (and words the error)."""


def _mark(e: yaml.YAMLError) -> str:
    mark = getattr(e, "problem_mark", None)
    return f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""


def _prescan(text: str, path: Path, loader) -> None:
    """Refuse deep nesting before a composer sees it (libyaml's recurses in C)."""
    depth = 0
    try:
        for ev in yaml.parse(text, Loader=loader):
            if isinstance(ev, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
                depth += 1
                if depth > MAX_DEPTH:
                    line = ev.start_mark.line + 1 if ev.start_mark else "?"
                    raise ConfigError(path, "", f"nested more than {MAX_DEPTH} levels deep (line {line}): a design "
                                      "is a few levels of keys")
            elif isinstance(ev, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
                depth -= 1
    except yaml.YAMLError as e:
        if loader is not _Loader:
            raise _Refused from None
        problem = getattr(e, "problem", None) or str(e).splitlines()[0]
        raise ConfigError(path, "", f"invalid YAML{_mark(e)}: {problem}") from None


def _key_text(node) -> str:
    return node.value if isinstance(node, ScalarNode) else "?"


def _walk(root, path: Path) -> None:
    """Duplicate keys (with their key path), self-referring aliases and alias bombs."""
    sizes: dict[int, int] = {}
    busy: set[int] = set()

    def size(node, where: str) -> int:
        k = id(node)
        if k in sizes:
            return sizes[k]
        if k in busy:
            raise ConfigError(path, where, "an alias refers to the value that contains it")
        busy.add(k)
        n = 1
        if isinstance(node, MappingNode):
            seen: dict[tuple, int] = {}
            for key, value in node.value:
                name = _key_text(key)
                sub = f"{where}.{name}" if where else name
                ident = (key.tag, key.value) if isinstance(key, ScalarNode) else ("?", id(key))
                if ident in seen:
                    raise ConfigError(path, sub, f"given twice in one mapping (lines {seen[ident]} and "
                                      f"{key.start_mark.line + 1}): YAML keys must be unique")
                seen[ident] = key.start_mark.line + 1
                n += size(key, sub) + size(value, sub)
        elif isinstance(node, SequenceNode):
            for i, item in enumerate(node.value):
                n += size(item, f"{where}[{i}]")
        if n > MAX_VALUES:
            raise ConfigError(path, where, f"expands to more than {MAX_VALUES:,} values (aliases?): too large")
        busy.discard(k)
        sizes[k] = n
        return n

    size(root, "")


def parse_yaml(text: str, path: Path):
    """The data of a YAML 1.2 document (see the module doc); ConfigError naming ``path``. Read by
    libyaml when it is there; text libyaml refuses is read by the pure-Python parser, whose reading
    and error messages (line, column, the character) are the ones that count."""
    if _FastLoader is not None:
        try:
            return _parse(text, path, _FastLoader)
        except _Refused:
            pass
    return _parse(text, path, _Loader)


def _parse(text: str, path: Path, loader_class):
    _prescan(text, path, loader_class)
    loader = loader_class(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        _walk(node, path)
        return loader.construct_document(node)
    except yaml.YAMLError as e:
        if loader_class is not _Loader:
            raise _Refused from None
        problem = getattr(e, "problem", None) or str(e).splitlines()[0]
        raise ConfigError(path, "", f"invalid YAML{_mark(e)}: {problem}") from None
    except (ValueError, OverflowError) as e:  # a scalar the constructor cannot convert
        raise ConfigError(path, "", f"invalid YAML: {e}") from None
    finally:
        loader.dispose()


def read_yaml_file(path: Path):
    """Read and parse ``path`` (a regular file of at most MAX_BYTES, UTF-8)."""
    path = Path(path)
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise ConfigError(path, "", "no such file") from None
    except NotADirectoryError:
        raise ConfigError(path, "", "no such file (a part of the path is a file, not a folder)") from None
    except OSError as e:
        raise ConfigError(path, "", f"cannot read: {e.strerror}") from None
    if stat.S_ISDIR(st.st_mode):
        raise ConfigError(path, "", "is a folder, not a design file")
    if not stat.S_ISREG(st.st_mode):
        raise ConfigError(path, "", "is not a regular file (a pipe, a device or a socket): give a YAML file")
    if st.st_size > MAX_BYTES:
        raise ConfigError(path, "", f"is {st.st_size / 2**20:.1f} MB; a design file is at most {MAX_BYTES // 2**20} MB")
    try:
        with open(path, "rb") as f:
            raw = f.read(MAX_BYTES + 1)
    except OSError as e:
        raise ConfigError(path, "", f"cannot read: {e.strerror}") from None
    if len(raw) > MAX_BYTES:
        raise ConfigError(path, "", f"is larger than {MAX_BYTES // 2**20} MB")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ConfigError(path, "", f"is not UTF-8 text (byte {e.start}): give a YAML file") from None
    if "\x00" in text:
        raise ConfigError(path, "", "holds NUL bytes: it is not a text file")
    return parse_yaml(text, path)


class _Dumper(yaml.emitter.Emitter, yaml.serializer.Serializer, yaml.representer.SafeRepresenter, _Resolver12):
    """SafeDumper with the YAML 1.2 resolver: a string that reads as a 1.2 number (``1e3``) is quoted."""

    def __init__(self, stream, default_style=None, default_flow_style=False, canonical=None, indent=None, width=None,
                 allow_unicode=None, line_break=None, encoding=None, explicit_start=None, explicit_end=None,
                 version=None, tags=None, sort_keys=True):
        yaml.emitter.Emitter.__init__(self, stream, canonical=canonical, indent=indent, width=width,
                                      allow_unicode=allow_unicode, line_break=line_break)
        yaml.serializer.Serializer.__init__(self, encoding=encoding, explicit_start=explicit_start,
                                            explicit_end=explicit_end, version=version, tags=tags)
        yaml.representer.SafeRepresenter.__init__(self, default_style=default_style,
                                                  default_flow_style=default_flow_style, sort_keys=sort_keys)
        _Resolver12.__init__(self)


def dump_yaml(data) -> bytes:
    """``data`` as YAML text (UTF-8) that ``parse_yaml`` reads back to the same values."""
    return yaml.dump(data, Dumper=_Dumper, sort_keys=False, allow_unicode=True).encode()
