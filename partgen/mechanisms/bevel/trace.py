"""The straight bevel pair's trace over a tooth pitch of gear 1 (exact 3-D, contact.py): the
transmission error along gear 2's heel pitch circle, the backlash, the measured ratio and the
contact along the face; the figure, the CSV and the text `trace` prints (``mechanisms.solid_pair``'s,
with the pair's ``contact.PAIR``)."""

from __future__ import annotations

from pathlib import Path

from ...core.protocol import Trace
from .. import solid_pair
from .contact import PAIR
from .kit import BevelKit
from .resolve import BevelSpec

__all__ = ["trace", "csv", "trace_text"]


def trace(kind: str, spec: BevelSpec, kit: BevelKit, samples: int | None, out: Path | None,
          animate: bool = True) -> Trace:
    return solid_pair.trace(PAIR, kind, spec, kit, samples, out)


def csv(header: str, trace: Trace) -> str:
    return solid_pair.transmission_csv(header, trace)


def trace_text(spec: BevelSpec, trace: Trace, folder) -> str:
    return solid_pair.trace_text(PAIR, spec, trace, folder)
