"""partgen: mechanism designs (YAML) to checked, print-ready part kits.

    from partgen import build, check
    loaded, kit, manifest, folder = build("configs/butterfly.yaml", "out/butterfly")
    loaded, kit, result, plates = check("configs/butterfly.yaml", samples=360)
    assert result.ok

The layers underneath (config, design, geometry, assembly, checks, export) can be used on their
own; ``partgen.testing`` measures printed meshes for your own CI gates.
"""

from .errors import ConfigError, DesignError, PartgenError
from .pipeline import build, check, load, report, trace_design

__all__ = ["build", "check", "load", "report", "trace_design", "PartgenError", "ConfigError", "DesignError"]
__version__ = "0.1.0"
