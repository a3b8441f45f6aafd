"""What the shared checks (motion sweep, meshing, fits, printability) hold a kit to: a kit whose
mechanism uses them carries these as ``kit.params.checks``."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["CheckSettings"]


@dataclass(frozen=True)
class CheckSettings:
    """What `partgen check` holds a kit to (mm, mm³): the resolved ``config.schema.MotionChecks`` (whose
    defaults are the ones a design gets; these are the same, for a kit made in code)."""

    samples: int = 360
    interference_tolerance: float = 0.001
    min_clearance: float = 0.3
    min_contact_ratio: float = 1.2
    min_tip_width_roads: float = 3.0
    plate_margin: float = 5.0
