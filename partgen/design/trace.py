"""The pen path of a chain as built — speeds from its tooth counts, not from the ideal ratios —
and how far it is from the target curve (pure math, mm and rad).

As built, link speeds follow from the gears (the student report's recurrence, equivalent to
Eq 11): with B1 turning at its design speed s_1 (per cycle of the drawing; the crank, through the
drive pair, turns s_1·T_G1/T_drive times per cycle: once for a curve with a once-per-cycle term,
twice for a 3:2 Lissajous figure led by L2),
``ω_{j+1} = ω_j + (T_D,j / T_G,j+1)·(ω_{j-1} − ω_j)``, ω_0 = 0 (the base).
Teeth that meet Eq 11 give back the integer design speeds exactly; others give fractional speeds
and a path that no longer closes after one crank turn.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from .mechanism import ChainDesign
from .synthesis import Chain, Link, links_from_curve, trace

__all__ = ["built_speeds", "built_chain", "crank_turns", "Deviation", "deviation", "hausdorff", "directed_hausdorff",
           "nearest_distances", "target_paths"]


def built_speeds(mech: ChainDesign) -> tuple[Fraction, ...]:
    """World speed of each link per cycle of the drawing as its gears make it, exact (B1 at its
    design speed: the crank turns as often as ``crank_turns`` says)."""
    w = [Fraction(0), Fraction(mech.chain.links[0].speed)]
    for td, tg in mech.couplings:
        w.append(w[-1] + Fraction(td, tg) * (w[-2] - w[-1]))
    return tuple(w[1:])


def crank_turns(mech: ChainDesign) -> Fraction:
    """Turns of the crank (the drive gear's axle) per cycle of the drawing: B1's speed times the
    drive pair's ratio T_G1 / T_drive (1:1 in every kit)."""
    return abs(Fraction(mech.chain.links[0].speed) * Fraction(mech.G1.teeth, mech.drive.teeth))


def built_chain(mech: ChainDesign) -> Chain:
    """The chain with the speeds its gears give (lengths and initial angles as assembled)."""
    links = tuple(Link(l.name, float(w), l.length, l.phase) for l, w in zip(mech.chain.links, built_speeds(mech)))
    return Chain(links, mech.chain.offset)


def target_paths(mech: ChainDesign, theta: np.ndarray) -> dict[str, np.ndarray]:
    """(n,) complex mm: the full Fourier series of the target curve ("full") and the chain the
    design asks for, with ideal speeds ("pruned")."""
    out = {"pruned": trace(mech.design_chain or mech.chain, theta)}
    if mech.curve is not None:
        out["full"] = mech.curve.evaluate(theta) * mech.scale
    return out


def nearest_distances(p: np.ndarray, q: np.ndarray, block: int = 64, chunk: int = 1024) -> np.ndarray:
    """For each point of ``p`` the distance to the nearest point of ``q`` (complex (n,), (m,) arrays;
    returns (n,) mm); exact.

    ``q`` is cut into blocks of ``block`` consecutive points, each with its centre and radius. A
    point of p is measured exactly against its nearest block's points, which bounds its distance
    from above; a block whose centre is farther than that bound plus its radius cannot hold a nearer
    point, and the rest (on a dense curve: one to three blocks) are measured too. The cost falls
    from n·m to about n·(m/block + 3·block)."""
    p, q = np.asarray(p, dtype=complex).ravel(), np.asarray(q, dtype=complex).ravel()
    if len(p) == 0 or len(q) == 0:
        raise ValueError("nearest_distances needs points in both sets")
    nb = -(-len(q) // block)
    padded = np.full(nb * block, np.nan + 1j * np.nan)
    padded[:len(q)] = q
    blocks = padded.reshape(nb, block)
    centre = np.nanmean(blocks.real, axis=1) + 1j * np.nanmean(blocks.imag, axis=1)
    radius = np.nanmax(np.abs(blocks - centre[:, None]), axis=1)
    out = np.empty(len(p))
    for s in range(0, len(p), chunk):
        pc = p[s:s + chunk]
        lower = np.abs(pc[:, None] - centre[None, :]) - radius[None, :]  # (c, nb)
        best = np.argmin(lower, axis=1)
        upper = np.nanmin(np.abs(pc[:, None] - blocks[best]), axis=1)
        i, k = np.nonzero(lower < upper[:, None])
        d = np.nanmin(np.abs(pc[i, None] - blocks[k]), axis=1)
        np.minimum.at(upper, i, d)
        out[s:s + chunk] = upper
    return out


def directed_hausdorff(p: np.ndarray, q: np.ndarray) -> float:
    """max over the points of p of the distance to the nearest point of q (complex arrays), mm."""
    return float(nearest_distances(p, q).max())


def hausdorff(a: np.ndarray, b: np.ndarray) -> float:
    """Symmetric Hausdorff distance between two point sets (complex (n,) arrays), mm."""
    return max(directed_hausdorff(a, b), directed_hausdorff(b, a))


@dataclass(frozen=True)
class Deviation:
    """Pointwise (same θ) maximum and RMS, and Hausdorff (shape, any θ) distances, mm."""

    max_mm: float
    rms_mm: float
    hausdorff_mm: float
    at_theta: float

    def to_dict(self) -> dict:
        return {"max_deviation_mm": round(self.max_mm, 6), "rms_mm": round(self.rms_mm, 6),
                "hausdorff_mm": round(self.hausdorff_mm, 6), "worst_theta_rad": round(self.at_theta, 6)}


def deviation(path: np.ndarray, target: np.ndarray, theta: np.ndarray) -> Deviation:
    """How far ``path`` is from ``target`` sampled at the same crank angles ``theta``."""
    d = np.abs(path - target)
    k = int(np.argmax(d))
    return Deviation(float(d[k]), float(np.sqrt(np.mean(d**2))), hausdorff(path, target), float(theta[k]))


def curve_links(mech: ChainDesign) -> tuple[complex, tuple[Link, ...]]:
    """All links of the target curve at print scale (for drawing what was dropped)."""
    if mech.curve is None:
        return mech.chain.offset, mech.chain.links
    return links_from_curve(mech.curve, mech.scale)
