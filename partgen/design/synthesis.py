"""Curve → serial chain of rotating links: extraction, pruning, chain order, tracing.

A link turns at an integer world speed ``speed`` (crank speed 1) and points at ``phase`` when the
crank angle is 0, so its vector at crank angle θ is ``length · e^{i(speed·θ + phase)}``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Sequence

import numpy as np

from .curve import FourierCurve

__all__ = ["Link", "Chain", "links_from_curve", "prune", "chain_order", "trace"]

ZERO_LENGTH = 1e-12  # curve units: a coefficient below this is no link


@dataclass(frozen=True)
class Link:
    """One rotating link B_j: ``name`` like "L3" (speed +3) or "M3" (speed -3); length in mm."""

    name: str
    speed: int
    length: float
    phase: float

    def vector(self, theta: np.ndarray) -> np.ndarray:
        """Link vector at crank angles. theta : (n,) rad → (n,) complex, mm."""
        return self.length * np.exp(1j * (self.speed * np.asarray(theta, dtype=float) + self.phase))


@dataclass(frozen=True)
class Chain:
    """Links B_1..B_n from the ground pivot out, and the ground pivot's offset (complex, mm)."""

    links: tuple[Link, ...]
    offset: complex = 0j

    @property
    def speeds(self) -> tuple[int, ...]:
        return tuple(link.speed for link in self.links)


def link_name(speed: int) -> str:
    """"L3" for +3, "M3" for -3."""
    return f"{'L' if speed > 0 else 'M'}{abs(speed)}"


def links_from_curve(curve: FourierCurve, scale: float = 1.0) -> tuple[complex, tuple[Link, ...]]:
    """All non-zero rotating links of a curve, scaled by ``scale`` (mm per curve unit).

    Returns the ground offset C_0·scale (complex, mm) and the links in the order L_1, M_1, L_2, ….
    """
    links = []
    for k in range(1, curve.order + 1):
        for speed in (k, -k):
            c = curve.coefficient(speed)
            if abs(c) > ZERO_LENGTH:
                links.append(Link(link_name(speed), speed, abs(c) * scale, float(np.angle(c))))
    return curve.coefficient(0) * scale, tuple(links)


def prune(links: Iterable[Link], drop: Sequence[str]) -> tuple[Link, ...]:
    """The links without those named in ``drop``; an unknown name is a ``KeyError``."""
    links = tuple(links)
    names = {link.name for link in links}
    missing = [n for n in drop if n not in names]
    if missing:
        raise KeyError(f"no link named {', '.join(missing)} (the curve has {', '.join(sorted(names))})")
    return tuple(link for link in links if link.name not in set(drop))


def chain_order(links: Iterable[Link]) -> tuple[Link, ...]:
    """Longest first, alternating a +k link and a -k link, starting with +k (paper's §Chain order).

    Ties in length (to 1e-9 mm) go to the lower |k|. When one sign runs out the rest follow in
    length order.
    """

    def key(link: Link):
        return (-round(link.length, 9), abs(link.speed))

    plus = sorted((l for l in links if l.speed > 0), key=key)
    minus = sorted((l for l in links if l.speed < 0), key=key)
    out: list[Link] = []
    while plus or minus:
        if plus:
            out.append(plus.pop(0))
        if minus:
            out.append(minus.pop(0))
    return tuple(out)


def trace(chain: Chain, theta: np.ndarray) -> np.ndarray:
    """Pen (distal end of the last link). theta : (n,) rad → (n,) complex, mm."""
    theta = np.asarray(theta, dtype=float)
    p = np.full(theta.shape, chain.offset, dtype=complex)
    for link in chain.links:
        p = p + link.vector(theta)
    return p
