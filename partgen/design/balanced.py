"""The planar Bennett-based balanced butterfly linkage (van der Wijk 2020) — pure math, mm, rad,
complex numbers as points of the plane.

Four-bar 1 (S-B2-D2-B3) is driven by the two inputs, the angles q1 of link 1 (S→B2) and q4 of
link 4 (S→B3); D2 closes it. The similarity conditions make the other three four-bars scaled,
translated copies of it: B8-D1-B1-S (scale s2 = l4b/l4a, S ↦ B8), D4-B7-S-B6 (s3 = l9/l1a,
S ↦ D4) and B5-S-B4-D3 (s4 = l1b/l1a, S ↦ B5); the parallelograms C1-B2-S-B7 and C2-B4-S-B1
give C1, C2. Then links 1, 4, 7, 10 are straight bars through S and links 7, 10 parallel to
links 3 and 2 — which the tests check rather than assume.

Balance: every link's centre of mass is a fixed affine combination of its joints, so the total
mass moment about S is a linear combination of the three vectors B2 − S, B3 − S and D2 − S, which
move independently. The common centre of mass stays at S exactly when the three coefficients
vanish: three linear conditions on the masses and their offsets (``balance_coefficients``). The
paper's Eq 9–11 are these conditions simplified under its assumption that four-bar 1's opposite
sides are equal (l1a = l3, l2 = l4a: a parallelogram in the planar form, and what every Bennett
linkage has, a, b, a, b); for any other four-bar they are different conditions and do not
balance it (``paper_mass_equations``; tests/design/test_balanced.py measures both cases).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Butterfly", "LINKS", "positions", "centre_of_mass", "balance_coefficients", "solve_masses",
           "paper_mass_equations"]

# link: (joints it carries, reference joint, the joint its centre-of-mass offset p points toward)
LINKS = {
    1: (("B5", "S", "B2"), "S", "B2"), 2: (("C1", "B2", "D2"), "D2", "B2"), 3: (("D2", "B3"), "B3", "D2"),
    4: (("B3", "S", "B8"), "S", "B3"), 5: (("B8", "D1"), "B8", "D1"), 6: (("D1", "B1", "C2"), "B1", "D1"),
    7: (("B1", "S", "B6"), "S", "B1"), 8: (("B6", "D4"), "B6", "D4"), 9: (("D4", "B7", "C1"), "D4", "B7"),
    10: (("B7", "S", "B4"), "S", "B4"), 11: (("C2", "B4", "D3"), "B4", "D3"), 12: (("D3", "B5"), "D3", "B5"),
}


@dataclass(frozen=True)
class Butterfly:
    """Four-bar 1's sides (mm) and the three similarity scales; every other length follows."""

    l1a: float
    l2: float
    l3: float
    l4a: float
    s2: float
    s3: float
    s4: float
    mode: int = 1  # which of the two ways four-bar 1 assembles (D2 left or right of B2→B3)

    @property
    def lengths(self) -> dict[str, float]:
        a, b, c, d = self.l1a, self.l2, self.l3, self.l4a
        return {"l1a": a, "l2": b, "l3": c, "l4a": d,
                "l1b": self.s4 * a, "l10b": self.s4 * b, "l11": self.s4 * c, "l12": self.s4 * d,
                "l5": self.s2 * a, "l6": self.s2 * b, "l7a": self.s2 * c, "l4b": self.s2 * d,
                "l9": self.s3 * a, "l10a": self.s3 * b, "l7b": self.s3 * c, "l8": self.s3 * d}


def positions(bf: Butterfly, q1: float, q4: float) -> dict[str, complex] | None:
    """Every joint at inputs (q1, q4), S at the origin; None where four-bar 1 cannot close."""
    S = 0j
    B2, B3 = bf.l1a * cmath.exp(1j * q1), bf.l4a * cmath.exp(1j * q4)
    d = abs(B3 - B2)
    if d < 1e-12 or d > bf.l2 + bf.l3 or d < abs(bf.l2 - bf.l3):
        return None
    u = (d * d + bf.l2 ** 2 - bf.l3 ** 2) / (2 * d)
    h = math.sqrt(max(bf.l2 ** 2 - u * u, 0.0))
    e = (B3 - B2) / d
    D2 = B2 + e * (u + 1j * bf.mode * h)
    L = bf.lengths
    B5, B8 = -L["l1b"] * cmath.exp(1j * q1), -L["l4b"] * cmath.exp(1j * q4)
    copy = lambda origin, s, P: origin + s * (P - S)  # noqa: E731
    D1, B1 = copy(B8, bf.s2, B2), copy(B8, bf.s2, D2)
    D4 = S - bf.s3 * (D2 - S)
    B7, B6 = copy(D4, bf.s3, B2), copy(D4, bf.s3, B3)
    B4, D3 = copy(B5, bf.s4, D2), copy(B5, bf.s4, B3)
    C1, C2 = B2 + (B7 - S), B4 + (B1 - S)
    return {"S": S, "B1": B1, "B2": B2, "B3": B3, "B4": B4, "B5": B5, "B6": B6, "B7": B7, "B8": B8,
            "D1": D1, "D2": D2, "D3": D3, "D4": D4, "C1": C1, "C2": C2}


def _com_of(link: int, pos: dict[str, complex], p: float) -> complex:
    _, ref, toward = LINKS[link]
    d = pos[toward] - pos[ref]
    return pos[ref] + p * d / abs(d)


def centre_of_mass(pos: dict[str, complex], masses: dict[int, float], offsets: dict[int, float]) -> complex:
    """The common centre of mass of links 1–12 (mm, complex)."""
    total = sum(masses.values())
    return sum(masses[i] * _com_of(i, pos, offsets[i]) for i in masses) / total


def balance_coefficients(bf: Butterfly, masses: dict[int, float], offsets: dict[int, float]) -> np.ndarray:
    """(3,) real coefficients of B2 − S, B3 − S and D2 − S in the total mass moment about S.

    Each link's centre of mass is a real affine combination of its joints, and every joint is a
    real combination of B2, B3, D2 (S = 0); the coefficients are found exactly by evaluating the
    moment on three configurations where (B2, B3, D2) are the unit basis (linearity, no motion
    needed). All three are 0 for a balanced linkage."""
    out = []
    for basis in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
        B2, B3, D2 = (complex(x) for x in basis)
        # joints as the linear maps of positions(): same formulas with B2, B3, D2 given
        L = bf.lengths
        B5, B8 = -bf.s4 * B2, -bf.s2 * B3
        D1, B1 = B8 + bf.s2 * B2, B8 + bf.s2 * D2
        D4 = -bf.s3 * D2
        B7, B6 = D4 + bf.s3 * B2, D4 + bf.s3 * B3
        B4, D3 = B5 + bf.s4 * D2, B5 + bf.s4 * B3
        pos = {"S": 0j, "B1": B1, "B2": B2, "B3": B3, "B4": B4, "B5": B5, "B6": B6, "B7": B7, "B8": B8,
               "D1": D1, "D2": D2, "D3": D3, "D4": D4, "C1": B2 + B7, "C2": B4 + B1}
        moment = 0j
        for i, (_, ref, toward) in LINKS.items():
            length = _link_length(i, L)
            moment += masses[i] * (pos[ref] + offsets[i] / length * (pos[toward] - pos[ref]))
        out.append(moment.real)
    return np.array(out)


def _link_length(i: int, L: dict[str, float]) -> float:
    """Distance between link i's reference joint and the joint its offset points toward."""
    return {1: L["l1a"], 2: L["l2"], 3: L["l3"], 4: L["l4a"], 5: L["l5"], 6: L["l6"], 7: L["l7a"], 8: L["l8"],
            9: L["l9"], 10: L["l10b"], 11: L["l11"], 12: L["l12"]}[i]


def solve_masses(bf: Butterfly, masses: dict[int, float], offsets: dict[int, float], free: tuple[int, int, int],
                 conditions=None) -> dict[int, float]:
    """The masses of the three ``free`` links that meet three linear ``conditions`` (others as
    given): by default the balance (``balance_coefficients``); ``paper_mass_equations`` gives the
    masses that meet the paper's Eq 9–11 instead."""
    conditions = conditions or balance_coefficients
    base = dict(masses)
    for i in free:
        base[i] = 0.0
    c0 = conditions(bf, base, offsets)
    cols = []
    for i in free:
        one = dict(base)
        one[i] = 1.0
        cols.append(conditions(bf, one, offsets) - c0)
    x = np.linalg.solve(np.column_stack(cols), -c0)
    out = dict(masses)
    out.update({i: float(v) for i, v in zip(free, x)})
    return out


def paper_mass_equations(bf: Butterfly, m: dict[int, float], p: dict[int, float]) -> np.ndarray:
    """Residuals of the paper's Eq 9–11 as transcribed in the spec (l11b read as l11).

    The paper derives them from its Eq 6–8 assuming four-bar 1's opposite sides equal (l1a = l3,
    l2 = l4a): under that assumption they are combinations of the three ``balance_coefficients``
    (the same conditions); without it they are not, and masses meeting them leave the centre of
    mass wandering."""
    L = bf.lengths
    e9 = (-(m[1] * p[1] / L["l1a"] + m[2] + m[3]) * L["l2"] - m[4] * p[4] + m[5] * (1 - p[5] / L["l5"]) * L["l6"]
          + m[8] * p[8] + m[9] * (1 - p[9] / L["l9"]) * L["l8"] + m[12] * p[12])
    e10 = (-m[1] * p[1] - m[2] * L["l1a"] - m[3] * p[3] - m[5] * p[5] - m[6] * L["l5"] - m[7] * p[7] + m[8] * L["l9"]
           + m[9] * (L["l9"] - p[9]) + m[11] * p[11] + m[12] * L["l11"])
    e11 = (m[1] * (p[1] / L["l1a"]) * L["l2"] + m[2] * p[2] + m[5] * (p[5] / L["l5"]) * L["l6"] + m[6] * p[6]
           + m[9] * (p[9] / L["l9"]) * L["l8"] - m[10] * p[10] - (m[11] + m[12]) * L["l12"])
    return np.array([e9, e10, e11])
