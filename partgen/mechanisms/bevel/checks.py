"""The straight bevel pair's check over a tooth pitch of gear 1 (exact 3-D, contact.py): the
gears never overlap and keep backlash both ways, clear the base, post, block and pin over a turn,
each bore clears its shaft, the contact along the face, the bed and bores; and the text `check`
prints (both ``mechanisms.solid_pair``'s, with the pair's ``contact.PAIR``)."""

from __future__ import annotations

from ...core.findings import Result
from .. import solid_pair
from .contact import PAIR
from .kit import BevelKit
from .resolve import BevelSpec

__all__ = ["check", "check_text"]


def check(spec: BevelSpec, kit: BevelKit, samples: int | None = None, progress=None) -> Result:
    return solid_pair.check(PAIR, spec, kit, samples, progress)


def check_text(spec: BevelSpec, result: Result, folder, seconds: float) -> str:
    return solid_pair.check_text(PAIR, spec, result, folder, seconds)
