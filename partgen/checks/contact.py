"""How far a part turns (or slides) before it touches another: the one bisection every measured
backlash and every printed-outline transmission study uses.

``touches(d)`` says whether the moving part, turned or moved by ``d`` (rad or mm, in the sense the
caller measures), touches the other (overlap area or volume above the caller's threshold). The
contact is assumed monotone over the bracket: free at ``lo``, touching at ``hi`` (or beyond it)."""

from __future__ import annotations

from typing import Callable

__all__ = ["free_turn"]


def free_turn(touches: Callable[[float], bool], lo: float, hi: float, tol: float) -> float:
    """The largest ``d`` in ``[lo, hi]`` found free, to ``tol``: bisection, halving ``[lo, hi]`` until
    it is at most ``tol`` wide; ``lo`` when nothing in the bracket was found free."""
    while hi - lo > tol:
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if touches(mid) else (mid, hi)
    return lo
