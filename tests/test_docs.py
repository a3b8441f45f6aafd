"""The docs: the site builds with ``mkdocs build --strict`` (every link, every generated reference
page, every measured figure filled in from docs/figures.json), the generated config reference covers
every kind, the README is short and starts with the two commands, the second being what CI runs."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
BUILD_COMMAND = "python3 -m venv .venv && .venv/bin/pip install -q -e . && .venv/bin/partgen build configs/butterfly.yaml"


def hooks():
    spec = importlib.util.spec_from_file_location("docs_hooks", ROOT / "scripts" / "docs_hooks.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    dest = tmp_path_factory.mktemp("site")
    p = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(ROOT / "mkdocs.yml"), "-d",
                        str(dest)], cwd=ROOT, capture_output=True, text=True, timeout=120,
                       env={**os.environ, "NO_MKDOCS_2_WARNING": "1"})
    assert p.returncode == 0, p.stderr[-4000:]
    return dest


def test_site_builds_strict(site):
    for page in ("index.html", "quickstart/index.html", "mechanisms/gear_chain/index.html", "check/index.html",
                 "reference/config/index.html", "reference/commands/index.html", "reference/figures/index.html",
                 "architecture/index.html", "calibrate/index.html", "papers/index.html"):
        assert (site / page).is_file(), page
    for page in site.rglob("*.html"):
        assert "{{" not in page.read_text(), f"{page.relative_to(site)}: a placeholder left unfilled"


def test_every_kind_and_its_keys_in_the_config_reference(site):
    from partgen.mechanisms import REGISTRY

    html = (site / "reference" / "config" / "index.html").read_text()
    for kind, mech in REGISTRY.items():
        assert f'id="{kind}"' in html, kind
        section = html[html.index(f'id="{kind}"'):]
        for name, field in mech.schema.model_fields.items():
            assert f"<code>{field.alias or name}</code>" in section, (kind, name)
    shipped = {re.search(r"^kind:\s*(\w+)", p.read_text(), re.M).group(1) for p in (ROOT / "configs").glob("*.yaml")}
    assert shipped <= set(REGISTRY)


def test_architecture_picture_is_the_layer_table(site):
    allowed = hooks().allowed_layers()
    html = (site / "architecture" / "index.html").read_text()
    assert 'class="mermaid"' in html
    graph = hooks().layers_graph()
    for unit, deps in allowed.items():
        for dep in deps - {"errors"}:
            assert re.search(rf"^\s*{re.escape(unit.strip('_') or 'pkg')}_ --> {re.escape(dep.strip('_') or 'pkg')}_$",
                             graph, re.M), (unit, dep)


def test_an_unknown_figure_fails_the_build():
    from mkdocs.exceptions import PluginError

    h = hooks()
    with pytest.raises(PluginError, match="no_such_key"):
        h.fill("P(jam) is {{ fig.gear_pair.no_such_key }} %", "x.md")
    with pytest.raises(PluginError):
        h.fill("{{ table.nothing.here }}", "x.md")
    assert h.fill("{{ fig.gear_pair.tol_samples }}", "x.md") != "{{ fig.gear_pair.tol_samples }}"


def test_readme_is_short():
    assert len(README.read_text().splitlines()) <= 160


def test_readme_starts_with_the_two_commands_and_the_second_is_ci():
    text = README.read_text()
    head = re.match(r"# partgen\n\n```sh\n(.+)\n```\n\n```sh\n(.+)\n```\n", text)
    assert head, "README.md must start with its title and the two commands"
    build, tests = head.groups()
    assert build == BUILD_COMMAND
    ci = [line for line in (ROOT / ".ci" / "run").read_text().splitlines() if line.strip()][-1]
    assert tests == ci.strip()


def test_the_readmes_figure_is_the_benchmarks():
    """The README states the quick start's P(jam) by hand (it is not built): it must be the figure
    benchmarks/docs_figures.py last wrote (its `jam` section)."""
    import json
    stated = re.search(r"partgen estimates that ([0-9.]+) % of prints on the Ender-3 V3 jam", README.read_text())
    assert stated, "the README's quick start states its P(jam)"
    got = json.loads((ROOT / "docs" / "figures.json").read_text())["jam"]["desktop"]["ender3_v3"]["pct"]
    assert float(stated[1]) == got, (stated[1], got)


def test_the_docs_speak_to_a_user():
    for page in (ROOT / "docs").rglob("*.md"):
        text = page.read_text()
        for phrase in ("main's", "the issue's", "— in progress"):
            assert phrase not in text, (page.relative_to(ROOT), phrase)
