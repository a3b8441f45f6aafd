"""The gear train's trace: the output shaft's angle against the input's over one turn of the output,
from the printed outlines (``common/trace.py``: transmission error, the ratio measured, the backlash at
the output; its text), and what play costs at the output (``play.py``)."""

from __future__ import annotations

from pathlib import Path

from ....core.protocol import Trace
from ..common.trace import output_trace
from .checks import sample_thetas
from .kit import TrainKit
from .motion import turn_train
from .play import lost_motion
from .resolve import TrainSpec

__all__ = ["trace"]


def trace(spec: TrainSpec, kit: TrainKit, samples: int | None, out: Path | None) -> Trace:
    """The output shaft's angle against the input's over one turn of the output, from the printed outlines."""
    thetas = sample_thetas(spec, samples or 90)
    turned = turn_train(kit, thetas)
    o = len(spec.shafts) - 1
    drive, nominal, coast = turned["drive"][:, o], turned["nominal"][:, o], turned["coast"][:, o]
    return output_trace(spec, thetas, drive, nominal, coast, turned["overlap_mm2"], f"shaft {len(spec.shafts) - 1}",
                        out, lambda sp, te, coast: lost_motion(sp, kit, te, coast))
