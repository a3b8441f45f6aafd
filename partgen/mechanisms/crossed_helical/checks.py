"""The crossed helical pair's check over a tooth pitch of gear 1 (exact 3-D, contact.py): the
gears never overlap and keep backlash both ways, clear the base, post, blocks and pin over a turn,
each bore clears its shaft, the contact along the faces, the bed and bores; and the text `check`
prints, the efficiency and self-locking last (``mechanisms.solid_pair``'s, with the pair's
``contact.PAIR``)."""

from __future__ import annotations

from ...core.findings import Result
from .. import solid_pair
from .contact import PAIR
from .kit import CrossedKit, locking_text
from .resolve import CrossedSpec

__all__ = ["check", "check_text"]


def check(spec: CrossedSpec, kit: CrossedKit, samples: int | None = None, progress=None) -> Result:
    return solid_pair.check(PAIR, spec, kit, samples, progress)


def check_text(spec: CrossedSpec, result: Result, folder, seconds: float) -> str:
    return solid_pair.check_text(PAIR, spec, result, folder, seconds, (locking_text(spec),))
