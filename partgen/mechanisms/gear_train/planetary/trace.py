"""The planetary set's trace: the carrier's angle against the sun's over one carrier turn, from the
printed sections (``common/trace.py``: transmission error, the ratio measured, the backlash at the
carrier; its text), and what play costs at the carrier (``play.py``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....core.protocol import Trace
from ..common.trace import output_trace
from .kit import PlanetaryKit
from .motion import turn_planetary
from .play import lost_motion
from .resolve import PlanetarySpec

__all__ = ["trace"]


def trace(spec: PlanetarySpec, kit: PlanetaryKit, samples: int | None, out: Path | None) -> Trace:
    """The carrier's angle against the sun's over one turn of the carrier, from the printed outlines."""
    thetas = np.linspace(0.0, spec.output_turn, samples or 90, endpoint=False)
    turned = turn_planetary(kit, thetas)
    return output_trace(spec, thetas, turned["drive"], turned["nominal"], turned["coast"], turned["overlap_mm2"],
                        "carrier", out, lambda sp, te, coast: lost_motion(sp, kit, te, coast))
