"""Trigonometric plane curves as sums of rotating vectors (Liu, Wang, McCarthy 2017, Eq 1-4).

A curve ``x(θ) = Σ a_k cos kθ + b_k sin kθ``, ``y(θ) = Σ c_k cos kθ + d_k sin kθ`` written as the
complex point ``P(θ) = x + iy`` is a finite Fourier series ``P(θ) = Σ_n C_n e^{inθ}``,
n = -K..K. ``C_k`` (k > 0) is the link ``L_k`` turning at +k, ``C_{-k}`` the link ``M_k`` turning
at -k, ``C_0`` the fixed offset of the ground pivot. A link's length is ``|C|`` and its angle at
θ = 0 is ``arg C``.

Sign note (documented in README): the paper's Eq 2 writes ``L_k e^{i(kθ - ψ_k)}``, but its Eq 4,
Table 1 and Table 3 all use ``ψ_k = arg(C_k)``, i.e. ``e^{i(kθ + ψ_k)}``; and Eq 4's plain arctan
loses the quadrant (M_3's phase is π, arctan gives 0). We use ``arg C`` with atan2.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

__all__ = ["FourierCurve", "from_polar", "from_cartesian"]


@dataclass(frozen=True)
class FourierCurve:
    """``P(θ) = Σ_n coeffs[n] e^{inθ}`` in curve units.

    coeffs : (2K+1,) complex, index ``n + K`` holds ``C_n`` for n = -K..K.
    """

    coeffs: tuple[complex, ...]

    @property
    def order(self) -> int:
        """K, the highest harmonic."""
        return (len(self.coeffs) - 1) // 2

    def coefficient(self, n: int) -> complex:
        """C_n (0 outside -K..K)."""
        k = self.order
        return self.coeffs[n + k] if -k <= n <= k else 0j

    def evaluate(self, theta: np.ndarray) -> np.ndarray:
        """Points of the curve. theta : (n,) rad → (n,) complex, curve units."""
        theta = np.asarray(theta, dtype=float)
        k = self.order
        n = np.arange(-k, k + 1)
        return np.exp(1j * np.outer(theta, n)) @ np.asarray(self.coeffs, dtype=complex)


def from_polar(constant: float, sin: Mapping[int, float], cos: Mapping[int, float]) -> FourierCurve:
    """Curve of the polar form ``ρ(θ) = constant + Σ sin[k] sin kθ + cos[k] cos kθ``, P = ρ e^{iθ}.

    ρ's exponential coefficients are r_0 = constant, r_{±k} = (cos[k] ∓ i sin[k]) / 2; multiplying
    by e^{iθ} shifts them by one: C_n = r_{n-1}. Exact, no sampling.
    """
    harmonics = [k for k in (*sin, *cos)]
    if any(k < 1 for k in harmonics):
        raise ValueError("polar harmonics must be >= 1")
    kmax = max(harmonics, default=0)
    order = kmax + 1
    c = np.zeros(2 * order + 1, dtype=complex)
    c[0 + 1 + order] = constant
    for k in range(1, kmax + 1):
        ck, sk = cos.get(k, 0.0), sin.get(k, 0.0)
        c[k + 1 + order] = (ck - 1j * sk) / 2
        c[-k + 1 + order] = (ck + 1j * sk) / 2
    return FourierCurve(tuple(complex(v) for v in c))


def from_cartesian(a, b, c, d) -> FourierCurve:
    """Curve of the Cartesian form (Eq 1); a, b, c, d : (K+1,) float, index k (b_0, d_0 unused).

    C_k = ((a_k + d_k) + i(c_k - b_k)) / 2 and C_{-k} = ((a_k - d_k) + i(c_k + b_k)) / 2, whose
    moduli are the paper's Eq 3 ``L_k`` and ``M_k``.
    """
    a, b, c, d = (np.asarray(v, dtype=float) for v in (a, b, c, d))
    if not (a.shape == b.shape == c.shape == d.shape) or a.ndim != 1:
        raise ValueError("a, b, c, d must be 1-D arrays of one length")
    order = len(a) - 1
    out = np.zeros(2 * order + 1, dtype=complex)
    out[order] = a[0] + 1j * c[0]
    for k in range(1, order + 1):
        out[order + k] = ((a[k] + d[k]) + 1j * (c[k] - b[k])) / 2
        out[order - k] = ((a[k] - d[k]) + 1j * (c[k] + b[k])) / 2
    return FourierCurve(tuple(complex(v) for v in out))
