"""partgen's errors: one base class; a ConfigError names the file and the key path."""

from __future__ import annotations

__all__ = ["PartgenError", "ConfigError", "DesignError", "MeshError"]


class PartgenError(Exception):
    """Base of every error partgen raises on purpose (a user's error, not a bug)."""


class ConfigError(PartgenError):
    """Bad input: names the YAML file, the key path (``gears.module_mm``) and the problem."""

    def __init__(self, file: str, key_path: str, problem: str):
        self.file, self.key_path, self.problem = str(file), key_path, problem
        where = f"{self.file}: {key_path}" if key_path else self.file
        super().__init__(f"{where}: {problem}")


class DesignError(PartgenError):
    """A design that cannot be built (no teeth give a ratio, an idler cannot reach).

    ``key_path`` names the config key the problem traces back to, when there is one.
    """

    def __init__(self, problem: str, key_path: str = ""):
        self.key_path, self.problem = key_path, problem
        super().__init__(f"{key_path}: {problem}" if key_path else problem)


class MeshError(RuntimeError):
    """A part whose mesh, as written, is not one closed, oriented manifold shell: a bug in partgen
    (not a user's error, so not a PartgenError), named by part and design."""
