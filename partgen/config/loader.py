"""Read a design YAML and its printer profile into validated models; every failure is a ConfigError
naming the file, the key path and the problem."""

from __future__ import annotations

import copy
import difflib
import hashlib
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, TypeVar

from pydantic import BaseModel, ValidationError

from ..core.printer import PrinterLimits
from ..errors import ConfigError
from .overrides import NO_OVERRIDES, Overrides, UsageError, apply_sets, blame
from .schema import Printer
from .yamlio import dump_yaml, read_yaml_file

__all__ = ["LoadedDesign", "load_design", "read_yaml", "key_path", "PRINTERS_DIR", "shipped_printers",
           "printer_path", "printer_limits", "command_line_printer"]

PRINTERS_DIR = Path(__file__).resolve().parent.parent / "printers"

M = TypeVar("M", bound=BaseModel)


@dataclass(frozen=True)
class LoadedDesign:
    path: Path
    design: BaseModel  # the mechanism's schema (``partgen.mechanisms.<kind>.schema``)
    printer_path: Path
    printer: Printer
    data: dict | None = None  # the design as validated: the file with the command line's --set applied
    printer_data: dict | None = None  # the printer profile as validated (--printer's when given)
    _digest: list = field(default_factory=list, init=False, repr=False, compare=False)  # digest(), once made

    def document(self) -> dict:
        """A copy of the design's mapping as validated (what a kit folder's design.yaml records)."""
        return copy.deepcopy(self.data) if self.data is not None else read_yaml(self.path)

    def printer_document(self) -> dict:
        return copy.deepcopy(self.printer_data) if self.printer_data is not None else read_yaml(self.printer_path)

    def digest(self) -> str:
        """A fingerprint of the design as loaded (its YAML with the overrides, and its printer); made
        once (a loaded design is not changed: ``dataclasses.replace`` makes another, with its own)."""
        if not self._digest:
            self._digest.append(hashlib.sha256(dump_yaml(self.document()) + b"\0"
                                               + dump_yaml(self.printer_document())).hexdigest()[:16])
        return self._digest[0]


def read_yaml(path: Path) -> dict:
    """The YAML mapping in ``path``; ConfigError for a missing or unreadable file, bad syntax, a
    duplicate key or a non-mapping (see ``yamlio``)."""
    data = read_yaml_file(Path(path))
    if data is None:
        raise ConfigError(path, "", "the file is empty: expected a mapping of design keys")
    if not isinstance(data, dict):
        raise ConfigError(path, "", f"expected a mapping of keys at the top level, got a {type(data).__name__}")
    bad = [k for k in data if not isinstance(k, str)]
    if bad:
        raise ConfigError(path, str(bad[0]), "keys at the top level are names (text)")
    return data


def key_path(loc: tuple, data: Any) -> str:
    """``('teeth', 0, 'D')`` → ``teeth[0].D``, walking ``data`` so pydantic's union tags are dropped."""
    out, node = "", data
    for item in loc:
        if isinstance(node, dict) and item in node:
            out += f".{item}" if out else str(item)
            node = node[item]
        elif isinstance(node, list) and isinstance(item, int) and 0 <= item < len(node):
            out += f"[{item}]"
            node = node[item]
        elif isinstance(item, str) and not any(c in item for c in "[]()'") and node is not None and isinstance(node, dict):
            out += f".{item}" if out else item  # a missing key
            node = None
    return out


def _describe(err: dict, data: Any, errors: list[dict]) -> tuple[str, str]:
    path = key_path(tuple(err["loc"]), data)
    msg = err["msg"]
    if msg.startswith("Value error, "):
        msg = msg[len("Value error, "):]
    # a model-wide rule names the key it is about as "[key] problem"
    named = re.match(r"\[([A-Za-z_][\w.\[\]]*)\] (.*)\Z", msg, re.S)
    if named:
        path = f"{path}.{named[1]}" if path else named[1]
        msg = named[2]
    if err["type"] == "missing":
        return path, "required key is missing"
    if err["type"] == "extra_forbidden":
        # a misspelt key: suggest the missing sibling it was probably meant to be
        parent = tuple(err["loc"][:-1])
        missing = [str(e["loc"][-1]) for e in errors if e["type"] == "missing" and tuple(e["loc"][:-1]) == parent]
        close = difflib.get_close_matches(str(err["loc"][-1]), missing, n=1, cutoff=0.6)
        hint = f"; did you mean '{close[0]}'?" if close else " (not part of the schema; check its spelling)"
        return path, "unknown key" + hint
    got = err.get("input")
    if not isinstance(got, (dict, list)) and ", got " not in msg:
        msg += f", got {got!r}"
    return path, msg


def _rank(err: dict, data: Any) -> tuple:
    """Unknown keys first (a typo explains the 'missing' it causes), then the deepest key."""
    return (err["type"] != "extra_forbidden", -key_path(tuple(err["loc"]), data).count(".")
            - key_path(tuple(err["loc"]), data).count("["))


def validate(model: type[M], data: dict, path: Path) -> M:
    """``model`` from ``data``; the most telling error becomes a ConfigError with its key path."""
    try:
        return model.model_validate(data)
    except ValidationError as e:
        errors = sorted(e.errors(), key=lambda er: _rank(er, data))
        key, problem = _describe(errors[0], data, errors)
        # other problems, not counting the alternatives of a union the first error lies inside
        others = {_describe(er, data, errors)[0] for er in errors} - {key}
        others = {o for o in others if not (key.startswith(o) and key[len(o):len(o) + 1] in ".[")}
        if errors[0]["type"] == "extra_forbidden" and "did you mean" in problem:
            others -= {key.rsplit(".", 1)[0] + "." + problem.split("'")[1]}
        if others:
            problem += f" (and {len(others)} more problem{'s' if len(others) > 1 else ''})"
        raise ConfigError(path, key, problem) from None


def shipped_printers() -> list[str]:
    """Names of the printer profiles partgen ships (``printer: <name>``)."""
    return sorted(p.stem for p in PRINTERS_DIR.glob("*.yaml"))


def printer_path(value: str, design: Path, key: str = "printer", folders=()) -> Path:
    """The profile a design's ``printer`` names: a shipped name (``prusa_mk4``) or a ``.yaml`` path
    relative to the design that stays inside the design's folder (or one of ``folders``, which the
    user named on the command line). Nothing outside is ever opened."""
    if re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.-]*", value) and not value.endswith((".yaml", ".yml")):
        path = PRINTERS_DIR / f"{value}.yaml"
        if not path.is_file():
            names = shipped_printers()
            close = difflib.get_close_matches(value, names, n=1, cutoff=0.6)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise ConfigError(design, key, f"no shipped printer named {value!r}{hint} (shipped: {', '.join(names)}; "
                              "or give a .yaml profile beside the design)")
        return path
    if not value.endswith((".yaml", ".yml")):
        raise ConfigError(design, key, f"{value!r} is neither a shipped printer name nor a .yaml profile")
    given = Path(value)
    base = design.resolve().parent
    path = (base / given).resolve()
    roots = [base, PRINTERS_DIR, *(Path(f).resolve() for f in folders)]
    if not any(path == r or r in path.parents for r in roots):
        raise ConfigError(design, key, f"{value!r} lies outside the design's folder: a design reads only a shipped "
                          "printer (by name) or a profile in its own folder: copy the profile beside the design")
    if not path.is_file():
        raise ConfigError(design, key, f"no printer profile at {value!r} (looked for {path})")
    return path


def command_line_printer(value: str) -> Path:
    """``--printer NAME|FILE``: a shipped profile by name, or a .yaml file anywhere (the user named
    it on the command line; relative to the working folder)."""
    if re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.-]*", value) and not value.endswith((".yaml", ".yml")):
        path = PRINTERS_DIR / f"{value}.yaml"
        if path.is_file():
            return path
        names = shipped_printers()
        close = difflib.get_close_matches(value, names, n=1, cutoff=0.6)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise UsageError("--printer", value, f"no shipped printer of that name: {hint}(shipped: {', '.join(names)}; "
                         "or give a .yaml profile)")
    path = Path(value)
    if not path.is_file():
        raise UsageError("--printer", value, "no such printer profile: give a shipped name "
                         f"({', '.join(shipped_printers())}) or a .yaml file")
    return path.resolve()


def load_design(path: str | Path, kinds: Mapping[str, type[BaseModel]], over: Overrides = NO_OVERRIDES) -> LoadedDesign:
    """Design and printer profile of a design file; the printer path is relative to the design.
    ``kinds``: kind -> schema (the mechanisms' registry): an unknown or misspelt ``kind`` is one
    error on ``kind`` naming the kinds there are, before any other key is read. ``over``: the
    command line's --set (written into the mapping before it is validated) and --printer."""
    path = Path(path)
    data = read_yaml(path)
    if over.sets:
        data = apply_sets(data, over.sets, path)
    kind = data.get("kind")
    if not isinstance(kind, str) or kind not in kinds:
        names = ", ".join(kinds)
        if kind is None:
            raise blame(ConfigError(path, "kind", f"required key is missing: say which mechanism this is ({names})"),
                        over.sets)
        if not isinstance(kind, str):
            raise blame(ConfigError(path, "kind", f"should be one of {names}, got a {type(kind).__name__}"), over.sets)
        close = difflib.get_close_matches(kind, list(kinds), n=1, cutoff=0.6)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise blame(ConfigError(path, "kind", f"unknown mechanism {str(kind)[:40]!r}: {hint}(kinds: {names})"),
                    over.sets)
    try:
        design = validate(kinds[kind], data, path)
        ppath = command_line_printer(over.printer) if over.printer is not None else printer_path(design.printer, path)
    except ConfigError as e:
        raise blame(e, over.sets) from None
    pdata = read_yaml(ppath)
    printer = validate(Printer, pdata, ppath)
    return LoadedDesign(path, design, ppath, printer, data, pdata)


def printer_fit(loaded: "LoadedDesign", value, kind: str, key: str) -> float:
    """A clearance (diametral, mm) as the design gives it, or ``printer``: the ``kind`` fit
    ("running" or "press_fit") the printer profile's maker measured (``fits.<kind>_clearance_diametral_mm``).
    ConfigError on ``key`` when the profile gives none."""
    if value != "printer":
        return float(value)
    p = loaded.printer
    measured = None if p.fits is None else getattr(p.fits, f"{kind}_clearance_diametral_mm")
    if measured is None:
        raise ConfigError(loaded.path, key, f"'printer' takes the fit from the printer profile, but {p.name!r} "
                          f"({loaded.printer_path.name}) gives no fits.{kind}_clearance_diametral_mm: give a number "
                          "(mm, diametral)")
    return float(measured)


def printer_limits(p: Printer) -> PrinterLimits:
    """The validated printer profile as the kernels read it (mm)."""
    lw = p.line_width
    lines = p.min_wall_lines if p.min_wall_lines is not None else p.min_wall_mm / lw
    return PrinterLimits(name=p.name, envelope=tuple(p.build_envelope_mm), line_width=lw,
                         min_hole=p.min_hole_diameter_mm, min_gear=p.min_gear_diameter_mm,
                         min_link=p.min_link_length_mm, min_wall_lines=lines,
                         min_hole_to_size=p.min_hole_to_size_diameter_mm, nozzle=p.nozzle_diameter_mm,
                         layer_height=p.layer_height_mm, xy_accuracy=p.xy_accuracy_mm,
                         running_clearance=p.fits.running_clearance_diametral_mm if p.fits else None,
                         press_clearance=p.fits.press_fit_clearance_diametral_mm if p.fits else None,
                         overhang_deg=p.overhang_deg, plate_edge=p.plate_edge_mm, **biases_of(p))


def biases_of(p: Printer) -> dict:
    """The profile's biases as ``PrinterLimits`` fields (all 0, no compensation, when it gives none)."""
    b = p.biases
    out = {"measured": p.measured}
    if b is not None:
        out.update(hole_bias=b.hole_diametral_mm, pin_bias=b.pin_diametral_mm, outline_bias=b.outline_diametral_mm,
                   compensate=b.compensate)
    return out
