"""What every sub-slice's resolver shares: the shafts' fits (a number, or ``printer``: the printer
profile's measured fit, through ``config.loader.printer_fit``), the checks' settings, and the design
findings of the gear rules."""

from __future__ import annotations

from ....checks.settings import CheckSettings
from ....config.loader import LoadedDesign, printer_fit
from ....core.findings import Finding
from ....design import rules

__all__ = ["shaft_fits", "check_settings", "gear_findings"]


def shaft_fits(loaded: LoadedDesign) -> tuple[float, float]:
    """The shafts' diametral running and press-fit clearances (mm): the design's numbers, or ``printer``:
    the printer profile's measured fits."""
    s = loaded.design.shafts
    return (printer_fit(loaded, s.running_clearance_diametral_mm, "running", "shafts.running_clearance_diametral_mm"),
            printer_fit(loaded, s.press_fit_clearance_diametral_mm, "press_fit",
                        "shafts.press_fit_clearance_diametral_mm"))


def check_settings(c) -> CheckSettings:
    """What check holds the kit to, from the design's ``checks`` (``schema.TrainChecks``)."""
    return CheckSettings(c.samples, c.interference_tolerance_mm3, c.min_clearance_mm, c.min_contact_ratio,
                         c.min_tip_width_roads, c.plate_margin_mm)


def gear_findings(gr, gears) -> list[Finding]:
    """What `build` warns about for each (name, GearSpec) of ``gears`` under the gear rules ``gr`` (the
    rules `check` fails on), and notes (undercut gears)."""
    out = []
    for name, g in gears:
        for x in rules.gear_breaches(g, gr, name):
            out.append(Finding("design", "warn", x.message, (), key="gears.module_mm", rule=x.rule))
        if g.undercut:
            out.append(Finding("design", "info", f"{name} ({g.teeth} teeth, x = {g.profile_shift:.3f}) is undercut",
                               (), key="gears.profile_shift"))
    return out
