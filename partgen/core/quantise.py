"""Quantised comparison: how every search and ``auto`` choice of partgen compares its scores.

A score computed in floating point differs in its last bits between machines and library builds
(BLAS kernels, SIMD widths, the order a sum is taken in). A search that compares raw floats can
therefore pick another layout, another turn or another module on another machine when two
candidates are equal but for those bits. Every choice compares scores quantised to a stated
resolution instead, so candidates within the resolution are ties, and ties are broken by the
order each search states (its candidates' order, or a further key).

``RESOLUTION_MM`` = 1e-6 mm (a nanometre: a thousand times finer than any printer, a million times
coarser than the last bits of a mm-sized float). Angles (rad) and areas (mm²) use the same
resolution in their own unit. Quantisation is ``round(x / step)`` to an integer: two values that
differ by less than ``step`` can still straddle a rounding boundary, but only when they lie within
a few ulps of one — about 1e-10 of the cases a perturbation test can hit, and nothing a search's
inputs are chosen near.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["RESOLUTION_MM", "quantise", "quantised", "close", "r6"]

RESOLUTION_MM = 1e-6


def quantise(x: float, step: float = RESOLUTION_MM) -> int:
    """``x`` as a whole number of ``step`` (int; ±inf and nan stay floats so they still order)."""
    x = float(x)
    if not math.isfinite(x):
        return x  # type: ignore[return-value]
    return int(round(x / step))


def quantised(values, step: float = RESOLUTION_MM) -> tuple:
    """A tuple of scores, each quantised (ints compare exactly, so tuples of them too)."""
    return tuple(quantise(v, step) if isinstance(v, (float, int, np.floating, np.integer)) else v for v in values)


def close(a: float, b: float, step: float = RESOLUTION_MM) -> bool:
    """Whether ``a`` and ``b`` are one value at ``step`` resolution."""
    return quantise(a, step) == quantise(b, step)


def r6(x) -> float:
    """``x`` rounded to 6 decimals, a Python float: how manifests and JSON reports write a length
    (mm: a micrometre's thousandth) or an angle."""
    return float(round(float(x), 6))
