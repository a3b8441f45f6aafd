"""partgen's errors: one base class; a ConfigError names the file and the key path."""

from __future__ import annotations

__all__ = ["PartgenError", "ConfigError", "OptionError", "DesignError", "MeshError"]


class PartgenError(Exception):
    """Base of every error partgen raises on purpose (a user's error, not a bug)."""


class ConfigError(PartgenError):
    """Bad input: names the YAML file, the key path (``gears.module_mm``) and the problem."""

    def __init__(self, file: str, key_path: str, problem: str):
        self.file, self.key_path, self.problem = str(file), key_path, problem
        where = f"{self.file}: {key_path}" if key_path else self.file
        super().__init__(f"{where}: {problem}")


class OptionError(PartgenError):
    """Bad input on the command line: names the option (``-o``, ``--samples``), the value given and
    the problem."""

    def __init__(self, option: str, value: str, problem: str):
        self.option, self.value, self.problem = option, str(value), problem
        super().__init__(f"{option} {self.value}: {problem}" if self.value else f"{option}: {problem}")


class DesignError(PartgenError):
    """A design that cannot be built (no teeth give a ratio, an idler cannot reach).

    ``key_path`` names the config key the problem traces back to, when there is one.
    """

    def __init__(self, problem: str, key_path: str = ""):
        self.key_path, self.problem = key_path, problem
        super().__init__(f"{key_path}: {problem}" if key_path else problem)


class MeshError(RuntimeError):
    """partgen made a part whose mesh is not one closed, oriented shell: a bug, not the user's input
    (exit 3). The message names the part and the design; the part is never written."""
