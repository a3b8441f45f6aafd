"""mkdocs hook: the reference pages the code knows, generated at every docs build (never a
hand-kept copy): the config reference of every kind from its pydantic schema (every field with its
description, unit and default), the printer profile fields, the shipped printers, every command's
options from the CLI's own parser, and the manifest schema.

Generated pages are added to the site as virtual files (nothing is written into docs/)."""

from __future__ import annotations

import json
import types
import typing
from pathlib import Path

from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parent.parent


def _unit(name: str) -> str:
    for suffix, unit in (("_mm2", "mm²"), ("_mm", "mm"), ("_deg", "°"), ("_g_cm3", "g/cm³"), ("_g", "g"),
                         ("_s", "s"), ("_rad", "rad"), ("_pct", "%"), ("_roads", "printer lines")):
        if name.endswith(suffix):
            return unit
    return ""


def _type(ann, ns: str = "") -> str:
    """A short, readable form of a field's annotation (models link to their table in section ``ns``)."""
    origin = typing.get_origin(ann)
    args = typing.get_args(ann)
    if origin is typing.Annotated:
        return _type(args[0], ns)
    if origin is typing.Literal:
        return " \\| ".join(f"`{a!r}`" if not isinstance(a, str) else f"`{a}`" for a in args)
    if origin in (typing.Union, types.UnionType):
        return " \\| ".join(_type(a, ns) for a in args if a is not type(None)) + (" \\| null" if type(None) in args else "")
    if origin in (list, tuple):
        inner = ", ".join(_type(a, ns) for a in args if a is not Ellipsis) if args else ""
        return f"list of {inner}" if inner else "list"
    if origin is dict:
        return f"mapping {_type(args[0], ns)} → {_type(args[1], ns)}" if args else "mapping"
    if isinstance(ann, type):
        from pydantic import BaseModel

        if issubclass(ann, BaseModel):
            return f"[{ann.__name__}](#{ns}{ann.__name__.lower()})"
        return {"float": "number", "int": "whole number", "str": "text", "bool": "true/false"}.get(ann.__name__,
                                                                                                    ann.__name__)
    return str(ann).replace("typing.", "")


def _models(model) -> list:
    """The model and every model its fields hold, each once, in reading order."""
    from pydantic import BaseModel

    out, todo = [], [model]
    while todo:
        m = todo.pop(0)
        if m in out:
            continue
        out.append(m)
        for f in m.model_fields.values():
            stack = [f.annotation]
            while stack:
                a = stack.pop()
                if isinstance(a, type) and issubclass(a, BaseModel):
                    todo.append(a)
                stack += list(typing.get_args(a))
    return out


def _default(f) -> str:
    from pydantic_core import PydanticUndefined

    if f.is_required():
        return "required"
    d = f.default if f.default is not PydanticUndefined else (f.default_factory() if f.default_factory else None)
    if hasattr(d, "model_dump"):
        return "(see below)"
    return f"`{json.dumps(d, default=str)}`" if d is not None else "none"


def model_table(model, heading: int = 3, ns: str = "") -> str:
    """Markdown tables of ``model`` and the models it holds; anchors ``{ns}{model name}``."""
    lines = []
    for m in _models(model):
        lines += [f"{'#' * heading} {m.__name__} {{#{ns}{m.__name__.lower()}}}", ""]
        if m.__doc__ and m.__doc__.strip() and not m.__doc__.startswith(("!!! abstract", "Usage docs")):
            lines += [" ".join(m.__doc__.split()), ""]
        lines += ["| key | type | unit | default | what it is |", "|---|---|---|---|---|"]
        for name, f in m.model_fields.items():
            key = f.alias or name
            desc = " ".join((f.description or "").split()).replace("|", "\\|")
            lines.append(f"| `{key}` | {_type(f.annotation, ns)} | {_unit(key)} | {_default(f)} | {desc} |")
        lines.append("")
    return "\n".join(lines)


def config_reference() -> str:
    from partgen.config.schema import Printer
    from partgen.mechanisms import REGISTRY

    out = ["# Config reference", "",
           "Generated from the pydantic schemas at every docs build: every key a design file may hold, per "
           "`kind`, with its type, unit, default and meaning. Unknown keys are an error (exit 2) naming the "
           "key path. Lengths are mm and angles degrees where the key says so (`_mm`, `_deg`); radial or "
           "diametral is in the key's name.", ""]
    for kind, mech in REGISTRY.items():
        out += [f"## kind: {kind} {{#{kind}}}", "", model_table(mech.schema, 3, f"{kind}-")]
    out += ["## Printer profiles", "", "A printer profile (`printer: NAME` or a `.yaml` file beside the design).", "",
            model_table(Printer, 3, "printer-")]
    return "\n".join(out)


def printers_page() -> str:
    import yaml

    rows = []
    for p in sorted((ROOT / "partgen" / "printers").glob("*.yaml")):
        d = yaml.safe_load(p.read_text())
        env = d.get("build_envelope_mm", ["", "", ""])
        rows.append(f"| `{p.stem}` | {d.get('name', '')} | {' × '.join(str(x) for x in env)} | "
                    f"{d.get('line_width_mm', d.get('resolution_mm', ''))} | {d.get('xy_accuracy_mm', '')} | "
                    f"{'measured' if d.get('measured') else 'typical'} |")
    return "\n".join(["# Shipped printers", "",
                      "Read from `partgen/printers/*.yaml` at every docs build. `typical`: the values are typical "
                      "for the machine, not measured on yours: see [Calibrate your printer](../calibrate.md).", "",
                      "| name | printer | build envelope mm | line width mm | xy accuracy ± mm | values |",
                      "|---|---|---|---|---|---|", *rows, ""])


def commands_page() -> str:
    import argparse

    from partgen.cli.main import parser

    ap = parser()
    out = ["# Commands", "", "Generated from the command line's own parser at every docs build.", "",
           "Every command takes `-o/--out DIR`, `-q/--quiet`, `--json`; design commands also `--printer` and "
           "`--set KEY=VALUE`. Exit codes: 0 ok, 1 a check failed, 2 bad input (one message naming the file and "
           "key path, or the option), 3 an internal error, 130/143 interrupted.", ""]
    sub = next(a for a in ap._actions if isinstance(a, argparse._SubParsersAction))
    helps = {c.dest: c.help for c in sub._choices_actions}
    for name, p in sub.choices.items():
        out += [f"## partgen {name}", "", helps.get(name) or "", "", "```text", p.format_usage().strip(), "```", "",
                "| option | what it does |", "|---|---|"]
        for a in p._actions:
            if isinstance(a, argparse._HelpAction):
                continue
            flag = ", ".join(f"`{o}`" for o in a.option_strings) or f"`{a.dest}`"
            h = (a.help or "").replace("|", "\\|") % {"default": a.default} if a.help and "%(" in a.help else \
                (a.help or "").replace("|", "\\|")
            out.append(f"| {flag} | {h} |")
        out.append("")
    return "\n".join(out)


def manifest_page() -> str:
    schema = json.loads((ROOT / "docs" / "manifest.schema.json").read_text())

    def rows(props: dict, required: set, prefix: str = "") -> list[str]:
        out = []
        for k, v in props.items():
            t = v.get("type", "object" if "properties" in v else ("see $defs" if "$ref" in v else ""))
            out.append(f"| `{prefix}{k}` | {t} | {'yes' if k in required else ''} | "
                       f"{' '.join(v.get('description', '').split())} |")
        return out

    out = ["# Manifest", "", "Generated from `docs/manifest.schema.json` (the JSON Schema a test validates every "
           "shipped kit's `manifest.json` against).", "", " ".join(schema.get("description", "").split()), "",
           "| key | type | required | what it is |", "|---|---|---|---|"]
    out += rows(schema["properties"], set(schema.get("required", [])))
    part = schema["$defs"]["part"]
    out += ["", "## A part (`parts[]`)", "", "| key | type | required | what it is |", "|---|---|---|---|"]
    out += rows(part["properties"], set(part.get("required", [])))
    return "\n".join(out) + "\n"


PAGES = {"reference/config.md": config_reference, "reference/printers.md": printers_page,
         "reference/commands.md": commands_page, "reference/manifest.md": manifest_page}


def on_files(files, config):
    for path, make in PAGES.items():
        files.append(File.generated(config, path, content=make()))
    return files
