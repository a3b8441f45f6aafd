"""One vocabulary for what a design rule or a check found: ``Finding`` and a run's ``Result``.

Severities: ``fail`` (the kit does not hold: `check` exits 1; `build` still writes the kit and
prints it as a warning), ``warn`` (worth a look, does not fail), ``info`` (a fact, e.g. an undercut
gear).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

__all__ = ["Finding", "Result", "SEVERITIES"]

SEVERITIES = ("fail", "warn", "info")


@dataclass(frozen=True)
class Finding:
    """One result of a design rule or a check.

    check: what found it: "design", "interference", "clearance", "mesh", "fit", "printability",
        "kit", "balance", ... (a mechanism may add its own).
    severity: one of SEVERITIES.
    parts: the parts involved; theta: the motion parameter, rad (None if it does not depend on it);
    value: the measured number (unit in ``unit``); location: world point (x, y, z), mm.
    key: the config key path it traces back to (``gears.module_mm``), when there is one.
    rule: the rule's code (``tip-root``, ``wall``, ...): the same code for the build's warning and
        the check's failure.
    """

    check: str
    severity: str
    message: str
    parts: tuple[str, ...] = ()
    theta: float | None = None
    value: float | None = None
    unit: str = ""
    location: tuple[float, float, float] | None = None
    key: str = ""
    rule: str = ""

    def __post_init__(self):
        if self.severity not in SEVERITIES:
            raise ValueError(f"severity must be one of {SEVERITIES}, got {self.severity!r}")

    def to_dict(self) -> dict:
        d = {"check": self.check, "severity": self.severity, "message": self.message, "parts": list(self.parts)}
        if self.key:
            d["key"] = self.key
        if self.rule:
            d["rule"] = self.rule
        if self.theta is not None:
            d["theta_deg"] = round(math.degrees(self.theta), 4)
        if self.value is not None and math.isfinite(self.value):
            d["value"] = round(float(self.value), 6)
            d["unit"] = self.unit
        if self.location is not None:
            d["location_mm"] = [round(float(c), 4) for c in self.location]
        return d


@dataclass
class Result:
    """All findings of a run, and the figures a person wants to see (counts, timings, minima)."""

    findings: list[Finding] = field(default_factory=list)
    figures: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return not any(f.severity == "fail" for f in self.findings)

    def add(self, *found: Finding) -> None:
        self.findings.extend(found)
