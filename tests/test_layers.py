"""The architecture holds: core → design → config/geometry → checks/export → mechanisms → pipeline →
cli. A lower layer never imports a higher one (root modules included, ``from .. import x`` read as
the module it names), mechanism folders never import each other, the shared kernels know no
mechanism, and the design math imports no mesh library, pydantic or YAML."""

import ast
from pathlib import Path

import pytest

PKG = Path(__file__).parent.parent / "partgen"

# what each unit may import from partgen besides itself; a unit is a sub-package or a root module
ALLOWED = {
    "errors": set(),
    "core": set(),
    "design": {"core", "errors"},
    "config": {"core", "design", "errors"},
    "geometry": {"core", "design", "errors"},
    "checks": {"core", "design", "geometry", "errors"},
    "export": {"core", "design", "geometry", "errors", "__init__"},  # __init__: the version string
    "testing": {"core", "design", "geometry", "export", "errors"},
    "mechanisms": {"core", "design", "config", "geometry", "checks", "export", "errors"},
    "pipeline": {"core", "config", "design", "export", "mechanisms", "errors"},  # design: check's quick tolerance study
    "cluster": {"errors"},
    "studies": {"core", "config", "design", "export", "mechanisms", "pipeline", "cluster", "errors"},
    "calibration": {"core", "config", "design", "geometry", "export", "errors"},
    "cli": {"pipeline", "studies", "calibration", "cluster", "export", "errors", "__init__"},
    "__init__": {"pipeline", "errors"},
    "__main__": {"cli"},
}
FORBIDDEN_LIBS = {
    "core": {"manifold3d", "trimesh", "shapely", "yaml", "pydantic", "matplotlib", "scipy"},
    "design": {"manifold3d", "trimesh", "shapely", "yaml", "pydantic", "matplotlib", "scipy"},
    "config": {"manifold3d", "trimesh", "shapely", "matplotlib"},
    "geometry": {"trimesh", "yaml", "pydantic", "matplotlib"},
    "checks": {"manifold3d", "trimesh", "yaml", "pydantic", "matplotlib"},
    "export": {"trimesh"},  # export.stl writes and weighs parts: build imports no trimesh (tests/cli/test_fast_start.py)
    "pipeline": {"manifold3d", "trimesh"},
    "cli": {"manifold3d"},
    "cluster": {"manifold3d"},
    "studies": {"manifold3d"},
    "calibration": {"manifold3d"},
}
MANIFOLD_ONLY_IN = {"geometry"}  # the one manifold3d importer (mechanisms may hold its solids, not make them)


def modules():
    """(unit, path) of every module of partgen: sub-packages and root modules."""
    for f in sorted(PKG.rglob("*.py")):
        rel = f.relative_to(PKG)
        yield (rel.parts[0] if len(rel.parts) > 1 else rel.stem), f


def imports(path: Path) -> list[tuple[int, str, tuple[str, ...]]]:
    """(relative level, module, imported names) of every import in a module."""
    out = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out += [(0, a.name, ()) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            out.append((node.level, node.module or "", tuple(a.name for a in node.names)))
    return out


def targets(path: Path, level: int, name: str, names: tuple[str, ...]) -> list[tuple[str, ...]]:
    """The partgen modules an import reaches, as paths inside the package (``("mechanisms", "wrist",
    "kit")``); ``from .. import x`` reaches x."""
    if level == 0:
        if not name.startswith("partgen"):
            return []
        base = name.split(".")[1:]
        return [tuple(base + [n]) if (PKG.joinpath(*base, n).is_dir() or PKG.joinpath(*base, f"{n}.py").is_file())
                else tuple(base) for n in names] or [tuple(base)]
    here = list(path.relative_to(PKG).parts[:-1])
    base = here[:len(here) - (level - 1)] if level > 1 else here
    if level - 1 > len(here):
        return [("..",)]
    base = base + (name.split(".") if name else [])
    out = []
    for n in names or ("",):
        if n and (PKG.joinpath(*base, n).is_dir() or PKG.joinpath(*base, f"{n}.py").is_file()):
            out.append(tuple(base + [n]))
        else:
            out.append(tuple(base))
    return out


def unit_of(target: tuple[str, ...]) -> str:
    if not target:
        return "__init__"
    return target[0][:-3] if target[0].endswith(".py") else target[0]


def _mechanisms_root(name: str) -> bool:
    """``mechanisms/<name>.py`` is a root module of mechanisms/ (a kernel the kinds share, like
    ``solid_pair`` or ``autoplay``), not a mechanism's folder."""
    return PKG.joinpath("mechanisms", f"{name}.py").is_file()


def violations() -> list[str]:
    bad = []
    for unit, f in modules():
        where = f.relative_to(PKG)
        for level, name, names in imports(f):
            if level == 0 and not name.startswith("partgen"):
                lib = name.split(".")[0]
                if lib in FORBIDDEN_LIBS.get(unit, ()):
                    bad.append(f"{where} imports {name}")
                if lib == "manifold3d" and unit not in MANIFOLD_ONLY_IN:
                    bad.append(f"{where} imports manifold3d (only geometry/ may)")
                continue
            for t in targets(f, level, name, names):
                u = unit_of(t)
                if t == ("..",):
                    bad.append(f"{where}: relative import above the package")
                    continue
                if u != unit and u not in ALLOWED[unit]:
                    bad.append(f"{where} imports partgen.{'.'.join(t)}")
                if unit == "mechanisms" and u == "mechanisms" and len(where.parts) > 2 and len(t) > 1 \
                        and t[1] != where.parts[1] and not _mechanisms_root(t[1]):
                    bad.append(f"{where} imports another mechanism: partgen.{'.'.join(t)}")
                if unit == "mechanisms" and len(where.parts) == 2 and where.name != "__init__.py" \
                        and u == "mechanisms" and len(t) > 1 and not _mechanisms_root(t[1]):
                    bad.append(f"{where} (shared by the kinds) imports a mechanism: partgen.{'.'.join(t)}")
    return bad


def test_every_unit_has_a_rule():
    assert {u for u, _ in modules()} <= set(ALLOWED)


def test_layers_hold():
    assert violations() == []


def test_the_checker_can_fail(tmp_path, monkeypatch):
    """Seed a package with each kind of breach and see every one found."""
    pkg = tmp_path / "partgen"
    for d in ("design", "core", "mechanisms/wrist", "mechanisms/gear_chain", "checks"):
        (pkg / d).mkdir(parents=True)
    (pkg / "design" / "m.py").write_text("from .. import geometry\nimport yaml\n")
    (pkg / "geometry").mkdir()
    (pkg / "core" / "t.py").write_text("from ..design import involute\n")
    (pkg / "mechanisms" / "wrist" / "kit.py").write_text("from ..gear_chain import kit\n")
    (pkg / "mechanisms" / "gear_chain" / "kit.py").write_text("import manifold3d\n")
    (pkg / "mechanisms" / "gear_chain" / "trace.py").write_text("from .. import shared\nfrom ..shared import f\n")
    (pkg / "mechanisms" / "shared.py").write_text("from .wrist import kit\n")
    (pkg / "checks" / "c.py").write_text("from ..mechanisms.wrist import kit\n")
    (pkg / "errors.py").write_text("from .pipeline import build\n")
    (pkg / "pipeline.py").write_text("")
    monkeypatch.setattr(__import__(__name__), "PKG", pkg)
    found = "\n".join(violations())
    for breach in ("design/m.py imports partgen.geometry", "design/m.py imports yaml", "core/t.py imports partgen.design",
                   "mechanisms/wrist/kit.py imports another mechanism", "mechanisms/gear_chain/kit.py imports manifold3d",
                   "checks/c.py imports partgen.mechanisms", "errors.py imports partgen.pipeline",
                   "mechanisms/shared.py (shared by the kinds) imports a mechanism: partgen.mechanisms.wrist"):
        assert breach in found, (breach, found)
    assert "gear_chain/trace.py" not in found, found  # a kind may call a kernel the kinds share


# the kinds and the words only a mechanism knows: its parts, roles and motions
MECHANISM_WORDS = ("gear_chain", "bennett", "butterfly", "wrist", "gear_pair", "gear_train", "crossed_helical",
                   "bevel", "planetary", "worm", "belt", "pulley", "slug", "binder", "pen_holder", "pen holder",
                   "crank", "idler", "counterweight", "cross gear", "cross_gear", "monopole")
SHARED = ("export", "checks", "core", "cli", "pipeline.py", "studies.py")


def shared_files(root: Path) -> list[Path]:
    """The shared code under ``root``: ``SHARED``, and the root modules of mechanisms/ (the kernels the
    kinds share: ``solid_pair``, ``autoplay``; the registry, ``__init__.py``, lists the kinds by name)."""
    out = []
    for name in SHARED:
        base = root / name
        out += [base] if base.is_file() else sorted(base.rglob("*.py"))
    return out + [p for p in sorted((root / "mechanisms").glob("*.py")) if p.name != "__init__.py"]


def mechanism_words_in(root: Path) -> list[str]:
    """``file:line: word`` for every mechanism word in the shared code under ``root`` (vendored
    third-party code aside)."""
    import re
    pattern = re.compile("|".join(re.escape(w) for w in MECHANISM_WORDS), re.I)
    found = []
    for path in shared_files(root):
        if "vendor" in path.parts:
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            for m in pattern.finditer(line):
                found.append(f"{path.relative_to(root)}:{n}: {m.group(0)}")
    return found


def test_shared_code_names_no_mechanism():
    """export/, checks/, core/, cli/, pipeline.py, studies.py and the root modules of mechanisms/
    (the kernels the kinds share, e.g. solid_pair.py) know no kind: no kind, part, role or motion of
    a mechanism is named there, in code or in prose (the registry's kinds come in as data; a
    mechanism says its own texts)."""
    from partgen.mechanisms import KINDS
    assert set(KINDS) <= {w for w in MECHANISM_WORDS} | {"bennett_butterfly"}
    assert PKG / "mechanisms" / "solid_pair.py" in shared_files(PKG)
    assert PKG / "mechanisms" / "__init__.py" not in shared_files(PKG)
    assert mechanism_words_in(PKG) == []


def test_the_word_check_can_fail(tmp_path):
    (tmp_path / "checks").mkdir()
    (tmp_path / "checks" / "x.py").write_text("def f(kit):\n    return kit.part('belt1')  # the belt\n")
    for name in SHARED:
        if not (tmp_path / name).exists() and not name.endswith(".py"):
            (tmp_path / name).mkdir()
        elif name.endswith(".py"):
            (tmp_path / name).write_text("")
    assert mechanism_words_in(tmp_path) == ["checks/x.py:2: belt", "checks/x.py:2: belt"]
    # a kernel the kinds share (a root module of mechanisms/) that names a kind is found; the registry is not
    (tmp_path / "mechanisms").mkdir()
    (tmp_path / "mechanisms" / "__init__.py").write_text('KINDS = ("bevel",)\n')
    (tmp_path / "mechanisms" / "pair.py").write_text("def f(spec):\n    return spec.kind == 'bevel'\n")
    assert mechanism_words_in(tmp_path) == ["checks/x.py:2: belt", "checks/x.py:2: belt", "mechanisms/pair.py:2: bevel"]
