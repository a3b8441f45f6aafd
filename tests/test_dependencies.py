"""Every command works after exactly the README's install (``pip install -e .``, no test extras).

Statically: nothing in partgen/ imports a package that is neither the standard library nor in
``[project.dependencies]``. End to end: build and report (which runs check and trace) run in a
child process in which the test extras cannot be imported: build, check (3MF plates), trace and
report on the gear pair, the cheapest kit (the exports are the same for every mechanism; what a
mechanism imports is the static test's).
"""

from __future__ import annotations

import ast
import importlib.metadata as md
import re
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "partgen"


def _project() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def _dist(req: str) -> str:
    return re.split(r"[<>=!~ \[;]", req, maxsplit=1)[0].lower().replace("_", "-")


def _modules_of(dists: set[str]) -> set[str]:
    """Top-level import names provided by these distributions (as installed here), from their
    file lists: a package folder, a module or an extension module at the top of site-packages."""
    out = set()
    for d in dists:
        try:
            files = md.distribution(d).files or []
        except md.PackageNotFoundError:
            continue
        for f in files:
            top = f.parts[0]
            if top.endswith((".dist-info", ".data", ".pth")) or top in ("..", "__pycache__"):
                continue
            name = top.split(".")[0]
            if len(f.parts) > 1 or top.endswith((".py", ".so", ".pyd")):
                out.add(name)
    return out


def _imports() -> dict[str, str]:
    """top-level module -> one file of partgen that imports it (absolute imports only)."""
    found = {}
    for f in sorted(PKG.rglob("*.py")):
        for node in ast.walk(ast.parse(f.read_text(encoding="utf-8"))):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module] if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module else []
            for n in names:
                found.setdefault(n.split(".")[0], str(f.relative_to(ROOT)))
    return found


def test_partgen_imports_only_the_standard_library_and_declared_dependencies():
    declared = {_dist(r) for r in _project()["dependencies"]}
    allowed = _modules_of(declared) | set(sys.stdlib_module_names) | {"partgen"}
    missing = {m: f for m, f in _imports().items() if m not in allowed}
    assert not missing, f"imported but not in [project.dependencies]: {missing}"


def test_the_checker_can_fail():
    assert "lxml" not in _modules_of({_dist(r) for r in _project()["dependencies"]})
    assert "scipy" in _modules_of({"scipy"})


def test_commands_run_without_the_test_extras(tmp_path):
    extras = {_dist(r) for r in _project()["optional-dependencies"]["test"]}
    blocked = sorted(_modules_of(extras) - _modules_of({_dist(r) for r in _project()["dependencies"]}))
    assert "pytest" in blocked and "lxml" in blocked
    code = (f"import sys\nfor m in {blocked!r}: sys.modules[m] = None\n"
            "from partgen.cli.main import main\n"
            f"pair = {str(tmp_path / 'pair')!r}\n"  # check (3MF plates) and report (check, trace, pictures): the
            f"assert main(['build', {str(ROOT / 'configs' / 'gear_pair.yaml')!r}, '-o', pair, '-q']) == 0\n"
            "assert main(['check', pair, '--samples', '12']) == 0\n"  # cheapest kit, the same export code
            f"assert main(['report', pair, '--samples', '12', '-o', {str(tmp_path / 'report')!r}]) == 0\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert (tmp_path / "report" / "index.html").stat().st_size > 10_000 and list((tmp_path / "pair" / "plates").glob("*.3mf"))
