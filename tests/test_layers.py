"""The architecture holds: data flows config → design → geometry → assembly → export, a lower
layer never imports a higher one, and the design math imports no mesh or CAD library."""

import ast
from pathlib import Path

import pytest

PKG = Path(__file__).parent.parent / "partgen"
LAYERS = ["design", "config", "geometry", "assembly", "checks", "export", "cli"]
# what each layer may import from partgen (besides itself and errors) and which libraries it must not
ALLOWED = {
    "design": set(),
    "config": {"design"},
    "geometry": {"design"},
    "assembly": {"design", "geometry"},
    "checks": {"design", "geometry", "assembly"},
    "export": {"design", "geometry", "assembly"},
}
FORBIDDEN_LIBS = {
    "design": {"manifold3d", "trimesh", "shapely", "yaml", "pydantic", "matplotlib", "scipy"},
    "config": {"manifold3d", "trimesh", "shapely", "matplotlib"},
    "geometry": {"trimesh", "yaml", "pydantic", "matplotlib"},
    "assembly": {"trimesh", "yaml", "pydantic", "matplotlib"},
    "checks": {"manifold3d", "trimesh", "yaml", "pydantic", "matplotlib"},
}


def imports(path: Path) -> set[tuple[int, str]]:
    """(relative level, dotted name) of every import in a module."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out |= {(0, a.name) for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            out.add((node.level, node.module or ""))
    return out


def partgen_layer(level: int, name: str, here: str) -> str | None:
    if level == 0:
        return name.split(".")[1] if name.startswith("partgen.") else None
    if level == 1:
        return here
    return name.split(".")[0] if name else None


@pytest.mark.parametrize("layer", list(ALLOWED))
def test_lower_layers_never_import_higher_ones(layer):
    for f in sorted((PKG / layer).glob("*.py")):
        for level, name in imports(f):
            target = partgen_layer(level, name, layer)
            if target in (None, layer, "errors", "core"):
                continue
            assert target in ALLOWED[layer], f"{f.relative_to(PKG)} imports partgen.{target}"


@pytest.mark.parametrize("layer", list(FORBIDDEN_LIBS))
def test_layers_do_not_import_foreign_libraries(layer):
    for f in sorted((PKG / layer).glob("*.py")):
        for level, name in imports(f):
            if level == 0:
                assert name.split(".")[0] not in FORBIDDEN_LIBS[layer], f"{f.relative_to(PKG)} imports {name}"


def test_the_checker_can_fail(tmp_path):
    bad = tmp_path / "m.py"
    bad.write_text("from ..geometry import parts\nimport trimesh\n")
    found = imports(bad)
    assert (2, "geometry") in found and (0, "trimesh") in found
    assert partgen_layer(2, "geometry", "design") == "geometry" not in ALLOWED["design"]
