"""partgen: mechanism designs (YAML) to checked, print-ready part kits.

    from . import build, check
    loaded, kit, manifest, folder = build("configs/butterfly.yaml", "out/butterfly")
    loaded, kit, result, plates = check("configs/butterfly.yaml", samples=360)
    assert result.ok

The layers underneath (config, design, geometry, assembly, checks, export) can be used on their
own; ``partgen.testing`` measures printed meshes for your own CI gates.
"""

from .errors import ConfigError, DesignError, MeshError, OptionError, PartgenError

__all__ = ["build", "check", "load", "report", "trace", "PartgenError", "ConfigError", "OptionError",
           "DesignError", "MeshError", "__version__"]
__version__ = "0.1.0"


def __getattr__(name: str):
    """The pipeline's functions, imported on first use (it loads the geometry kernel)."""
    if name in ("build", "check", "load", "report", "trace"):
        from . import pipeline
        return getattr(pipeline, name)
    raise AttributeError(f"module 'partgen' has no attribute {name!r}")
