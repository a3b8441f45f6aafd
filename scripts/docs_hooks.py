"""mkdocs hook: the reference pages the code knows, generated at every docs build (never a
hand-kept copy): the config reference of every kind from its pydantic schema (every field with its
description, unit and default), the printer profile fields, the shipped printers, every command's
options from the CLI's own parser, the manifest schema, and the figures the pages state.

Generated pages are added to the site as virtual files (nothing is written into docs/).

Pages never type a measured figure by hand: they write ``{{ fig.section.key }}`` (a number or a word)
or ``{{ table.section.name }}`` (a Markdown table), filled in from docs/figures.json, which
benchmarks/docs_figures.py writes by running the shipped designs; ``{{ gen.name }}`` is a block made
from the code at build time (the architecture page's picture of the layers from tests/test_layers.py's
``ALLOWED``). An unknown key fails the build."""

from __future__ import annotations

import ast
import json
import re
import types
import typing
from pathlib import Path

from mkdocs.exceptions import PluginError
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
    from partgen.config.schema import nested_models

    return nested_models(model)


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


FIGURES = ROOT / "docs" / "figures.json"
PLACEHOLDER = re.compile(r"\{\{\s*(fig|table|gen)\.([A-Za-z0-9_.]+)\s*\}\}")


def figures() -> dict:
    return json.loads(FIGURES.read_text()) if FIGURES.exists() else {}


def _lookup(data: dict, key: str):
    for part in key.split("."):
        if not isinstance(data, dict) or part not in data:
            raise KeyError(key)
        data = data[part]
    return data


def _scalar(v) -> str:
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):  # as docs_figures.py rounded it: 27.0 stays 27.0
        return f"{v:,}" if abs(v) >= 10000 else (repr(v) if "e" not in repr(v) else f"{v:.10f}".rstrip("0"))
    if isinstance(v, int):
        return f"{v:,}"
    if isinstance(v, str):
        return v
    raise TypeError(f"not a scalar: {type(v).__name__}")


def _table(t: dict, section: str, where: str = "") -> str:
    cell = lambda v: _scalar(v).replace("|", "\\|")  # noqa: E731
    run = figures().get(section, {}).get("_run", {})
    out = ["| " + " | ".join(t["columns"]) + " |", "|" + "---|" * len(t["columns"])]
    out += ["| " + " | ".join(cell(v) for v in row) + " |" for row in t["rows"]]
    out += ["", f"*Measured by `benchmarks/docs_figures.py` ({section}, {run.get('date', '?')}); "
                f"see [Figures]({'../' * where.count('/')}reference/figures.md).*"]
    return "\n".join(out)


def allowed_layers() -> dict[str, set[str]]:
    """tests/test_layers.py's ``ALLOWED`` table, read (not imported: it is a test module)."""
    tree = ast.parse((ROOT / "tests" / "test_layers.py").read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "ALLOWED" for t in node.targets):
            return ast.literal_eval(node.value)
    raise PluginError("tests/test_layers.py has no ALLOWED table")


def _node(unit: str) -> str:
    label = {"__init__": "partgen/__init__.py", "__main__": "python -m partgen"}.get(unit)
    if label is None:
        label = f"{unit}/" if (ROOT / "partgen" / unit).is_dir() else f"{unit}.py"
    return f'{unit.strip("_") or "pkg"}_["{label}"]'


def layers_graph() -> str:
    """A mermaid graph: an arrow from each unit to every unit it may import (``errors``, which every
    unit may import, left out)."""
    allowed = allowed_layers()
    lines = ["```mermaid", "graph TD"]
    for unit in allowed:
        if unit == "errors":
            continue
        lines.append(f"  {_node(unit)}")
    for unit, deps in allowed.items():
        for dep in sorted(deps - {"errors"}):
            lines.append(f"  {_node(unit).split('[')[0]} --> {_node(dep).split('[')[0]}")
    lines.append("```")
    return "\n".join(lines)


def layers_table() -> str:
    allowed = allowed_layers()
    rows = ["| unit | may import from partgen |", "|---|---|"]
    for unit, deps in allowed.items():
        rows.append(f"| `{_node(unit).split(chr(34))[1]}` | {', '.join(f'`{d}`' for d in sorted(deps)) or 'nothing'} |")
    return "\n".join(rows)


def _first_sentence(path: Path) -> str:
    """The first paragraph of a module's docstring, cut at a sentence's end near 240 characters."""
    try:
        doc = ast.get_docstring(ast.parse(path.read_text())) or ""
    except (SyntaxError, FileNotFoundError):
        return ""
    text = " ".join(doc.split("\n\n")[0].split())
    if len(text) > 240:
        cut = max(text.rfind(". ", 0, 240), text.rfind("; ", 0, 240))
        text = text[:cut + 1] if cut > 60 else text[:text.rfind(" ", 0, 240)] + " …"
    return text.replace("``", "`").replace("|", "\\|")


def modules_list() -> str:
    """Every unit's modules with the first sentence of their docstrings."""
    pkg = ROOT / "partgen"
    out = []
    for unit in allowed_layers():
        d = pkg / unit
        if d.is_dir():
            out += [f"### `{unit}/`", "", _first_sentence(d / "__init__.py") or "(no package docstring)", ""]
            for f in sorted(d.glob("*.py")):
                if f.name != "__init__.py":
                    out.append(f"- `{f.name}` — {_first_sentence(f)}")
            for sub in sorted(p for p in d.iterdir() if p.is_dir() and (p / "__init__.py").exists()):
                mods = ", ".join(f"`{f.name}`" for f in sorted(sub.glob("*.py")) if f.name != "__init__.py")
                out.append(f"- `{sub.name}/` — {_first_sentence(sub / '__init__.py')} ({mods})")
            out.append("")
        elif (pkg / f"{unit}.py").exists():
            out += [f"### `{unit}.py`", "", _first_sentence(pkg / f"{unit}.py"), ""]
    return "\n".join(out)


def registry_list() -> str:
    from partgen.mechanisms import REGISTRY

    return ", ".join(f"`{k}`" for k in REGISTRY)


KIND_PAGES = {"gear_chain": "mechanisms/gear_chain.md", "wrist": "mechanisms/wrist.md",
              "bennett_butterfly": "mechanisms/bennett_butterfly.md", "gear_pair": "mechanisms/gear_pair.md",
              "gear_train": "mechanisms/gear_train.md"}


def configs_table(where: str = "") -> str:
    """The shipped designs: file, kind, printer and description, read from configs/*.yaml."""
    import yaml

    up = "../" * where.count("/")
    rows = ["| design | kind | printer | what it is |", "|---|---|---|---|"]
    for p in sorted((ROOT / "configs").glob("*.yaml")):
        d = yaml.safe_load(p.read_text()) or {}
        kind = d.get("kind", "")
        page = "mechanisms/belt.md" if "belts" in d else KIND_PAGES.get(kind)
        link = f"[`{kind}`]({up}{page})" if page else f"`{kind}`"
        rows.append(f"| `configs/{p.name}` | {link} | `{d.get('printer', '')}` | "
                    f"{' '.join(str(d.get('description', '')).split())} |")
    return "\n".join(rows)


GENERATED = {"configs": configs_table, "layers_graph": layers_graph, "layers_table": layers_table, "modules": modules_list,
             "kinds": registry_list}


def fill(markdown: str, where: str) -> str:
    """Put the figures and generated blocks into a page; an unknown key is an error naming the page."""
    data = figures()

    def one(m) -> str:
        kind, key = m.groups()
        try:
            if kind == "gen":
                make = GENERATED[key]
                return make(where) if "where" in make.__code__.co_varnames else make()
            value = _lookup(data, key)
            if kind == "table":
                return _table(value, key.split(".")[0], where)
            return _scalar(value)
        except (KeyError, TypeError) as e:
            raise PluginError(f"{where}: {{{{ {kind}.{key} }}}}: no such figure in docs/figures.json ({e}); "
                              "run benchmarks/docs_figures.py") from None

    return PLACEHOLDER.sub(one, markdown)


def figures_page() -> str:
    data = figures()
    out = ["# Figures", "", "Every measured figure the pages state, as `benchmarks/docs_figures.py` last wrote it "
           "into `docs/figures.json` (it runs the shipped designs through the commands, in fresh processes). "
           "Rerun it after a change that moves a figure.", ""]
    for section, values in data.items():
        run = values.get("_run", {})
        doc = getattr(__import__("docs_figures").SECTIONS.get(section), "__doc__", "") if _bench() else ""
        out += [f"## {section}", "", doc or "", "",
                f"Run {run.get('date', '?')} with partgen {run.get('partgen', '?')} in {run.get('seconds', '?')} s.", "",
                "| figure | value |", "|---|---|"]

        def walk(d, prefix):
            for k, v in d.items():
                if k == "_run":
                    continue
                if isinstance(v, dict) and "columns" in v:
                    out.append(f"| `table.{prefix}{k}` | (a table of {len(v['rows'])} rows) |")
                elif isinstance(v, dict):
                    walk(v, f"{prefix}{k}.")
                else:
                    out.append(f"| `fig.{prefix}{k}` | {_scalar(v)} |")

        walk(values, f"{section}.")
        out.append("")
    return "\n".join(out)


def _bench() -> bool:
    import sys

    path = str(ROOT / "benchmarks")
    if path not in sys.path:
        sys.path.insert(0, path)
    try:
        __import__("docs_figures")
        return True
    except ImportError:
        return False


PAGES = {"reference/config.md": config_reference, "reference/printers.md": printers_page,
         "reference/commands.md": commands_page, "reference/manifest.md": manifest_page,
         "reference/figures.md": figures_page}


def on_page_markdown(markdown, page, config, files):
    return fill(markdown, page.file.src_uri)


def on_files(files, config):
    for path, make in PAGES.items():
        files.append(File.generated(config, path, content=make()))
    return files
