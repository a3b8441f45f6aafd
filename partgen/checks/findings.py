"""A check's result: findings with what failed, where and at which crank angle."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

__all__ = ["Finding", "Result"]


@dataclass(frozen=True)
class Finding:
    """One result of a check.

    check: "interference", "fit", "mesh", "clearance", "printability", "design".
    severity: "fail" (the kit does not hold), "warn", "info".
    parts: the parts involved; theta: crank angle, rad (None if it does not depend on it);
    value: the measured number (unit in ``unit``); location: world point (x, y, z), mm.
    rule: the rule of ``design.rules`` it is about (``tip-root``, ``wall``, …), when it is one: the
    code `build` names when it warns about the same rule.
    """

    check: str
    severity: str
    message: str
    parts: tuple[str, ...] = ()
    theta: float | None = None
    value: float | None = None
    unit: str = ""
    location: tuple[float, float, float] | None = None
    rule: str = ""

    def to_dict(self) -> dict:
        d = {"check": self.check, "severity": self.severity, "message": self.message, "parts": list(self.parts)}
        if self.theta is not None:
            d["theta_deg"] = round(math.degrees(self.theta), 4)
        if self.value is not None:
            d["value"] = round(float(self.value), 6)
            d["unit"] = self.unit
        if self.location is not None:
            d["location_mm"] = [round(float(c), 4) for c in self.location]
        if self.rule:
            d["rule"] = self.rule
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
