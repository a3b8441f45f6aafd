"""A drawn closed curve (samples in mm) → the fewest rotating links that draw it within a budget
(pure numpy, mm and rad).

The parametrisation decides which Fourier terms appear, so it is a choice:

- ``samples``: sample i sits at crank angle θ_i = 2πi/n, in the order and spacing given. A curve
  exported from a parametric plot (``x(t), y(t)`` sampled uniformly in t) keeps exactly the terms
  it has: a 3:2 Lissajous figure is four links.
- ``arc_length``: θ grows in proportion to the distance along the curve (the pen moves at a steady
  speed). Right for a drawing, whose point spacing means nothing; it spreads a curve's energy over
  more harmonics.

The fit is the complex FFT of the curve sampled uniformly in θ: ``P(θ) = Σ C_k e^{ikθ}``, C_k the
link turning at speed k (``synthesis.Link``), C_0 the ground pivot's offset. Links are taken
longest first (the largest coefficients carry the most of the curve); the chain of the n longest
is traced and its distance to the input samples measured (Hausdorff between the two closed
polylines), not estimated from the dropped terms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import reduce

import numpy as np

from ..core.quantise import quantise

from .curve import FourierCurve
from .synthesis import Chain, Link, chain_order, link_name, trace

__all__ = ["Drawing", "Row", "Choice", "closing", "crank_angles", "fit", "polyline_hausdorff", "chain_path",
           "measure", "tradeoff", "choose", "rescue", "lead", "retime", "scale_ladder", "MAX_HARMONIC", "MIN_SAMPLES",
           "LEAD_FRACTION"]

MIN_SAMPLES = 16
MAX_HARMONIC = 512  # highest speed a fitted link may turn at (a gear ratio beyond this is no kit)
ARC_SAMPLES = 4096  # uniform-in-θ samples of an arc-length parametrisation (at least; more for long inputs)
LEAD_FRACTION = 0.1  # a harmonic leads (the crank turns its link) only if its link is this share of the longest


@dataclass(frozen=True, eq=False)
class Drawing:
    """The user's closed curve and the crank angle of each sample.

    samples : (n,) complex, mm (x + iy, at print size, drawing order).
    theta : (n,) float, rad, increasing in [0, 2π).
    """

    samples: np.ndarray
    theta: np.ndarray
    parametrisation: str
    source: str = ""  # the file (or "inline") the samples came from, for messages and plots
    rows: tuple = field(default=())  # the trade-off (tuple of Row) the choice was made from
    chosen: int = 0  # links kept
    rounds: int = 1  # times the samples go round the curve; ``samples`` and ``theta`` keep the first round
    scale: float = 1.0  # the enlargement of the file's points (curve.scale, given or chosen by auto)


@dataclass(frozen=True)
class Row:
    """The chain of the ``links`` longest printable links: its distance to the samples (mm)."""

    links: int
    hausdorff_mm: float
    max_mm: float  # same crank angle: |pen(θ_i) - sample_i|
    rms_mm: float
    shortest_mm: float  # its shortest link


@dataclass(frozen=True)
class Choice:
    chain: Chain
    rows: tuple[Row, ...]
    chosen: Row | None  # None: no chain within max_links meets the budget


def closing(z: np.ndarray) -> tuple[float, float]:
    """(gap between the last and first sample, largest step between consecutive samples), mm.
    z : (n,) complex, mm."""
    steps = np.abs(np.diff(z))
    return float(abs(z[0] - z[-1])), float(steps.max()) if len(steps) else 0.0


def crank_angles(z: np.ndarray, parametrisation: str) -> np.ndarray:
    """θ of each sample of a closed curve (n,) complex → (n,) rad in [0, 2π)."""
    n = len(z)
    if parametrisation == "samples":
        return 2 * np.pi * np.arange(n) / n
    if parametrisation != "arc_length":
        raise ValueError(f"unknown parametrisation {parametrisation!r}")
    seg = np.abs(np.diff(np.append(z, z[0])))
    s = np.concatenate([[0.0], np.cumsum(seg)[:-1]])
    return 2 * np.pi * s / seg.sum()


def _resample(z: np.ndarray, theta: np.ndarray, m: int) -> np.ndarray:
    """The closed polyline through z at θ, read at m angles 2πj/m (linear between samples)."""
    t = np.append(theta, 2 * np.pi)
    zz = np.append(z, z[0])
    u = 2 * np.pi * np.arange(m) / m
    return np.interp(u, t, zz.real) + 1j * np.interp(u, t, zz.imag)


def fit(z: np.ndarray, parametrisation: str) -> tuple[FourierCurve, complex, tuple[Link, ...], np.ndarray]:
    """Fourier series of a closed curve. z : (n,) complex, mm.

    Returns the series (mm), the ground offset C_0, every link with length > 0 (longest first) and
    the crank angles (n,) rad of the samples.
    """
    theta = crank_angles(z, parametrisation)
    if parametrisation == "samples":
        u = z
    else:
        u = _resample(z, theta, max(ARC_SAMPLES, 2 * len(z)))
    m = len(u)
    c = np.fft.fft(u) / m
    kmax = min((m - 1) // 2, MAX_HARMONIC)  # the Nyquist term (m even) has no sign: left out
    coeffs = np.concatenate([c[m - kmax:], c[:kmax + 1]])  # C_-K..C_K
    fc = FourierCurve(tuple(complex(v) for v in coeffs))
    tol = 1e-12 * max(float(np.abs(u - c[0]).max()), 1e-300)
    links = []
    for k in range(1, kmax + 1):
        for speed, ck in ((k, c[k]), (-k, c[m - k])):
            if abs(ck) > tol:
                links.append(Link(link_name(speed), speed, float(abs(ck)), float(np.angle(ck))))
    links.sort(key=lambda l: (-l.length, abs(l.speed), -l.speed))
    return fc, complex(c[0]), tuple(links), theta


def _zigzag(speeds) -> bool:
    """Every link's speed a strict extreme between its neighbours' (the base's 0 before the first):
    Eq 11's ratio (ω_{j+1} - ω_j)/(ω_{j-1} - ω_j) is then positive, which an idler train gives."""
    w = [0, *speeds]
    return all((w[j + 1] - w[j]) * (w[j - 1] - w[j]) > 0 for j in range(1, len(w) - 1))


def drawable_orders(links, limit: int = 24, budget: int = 20_000, first: str | None = None):
    """Orders of the links that gears can couple (every Eq 11 ratio positive), the most preferred
    first: a depth-first search over ``chain_order`` (longest first, +k and -k alternating), at most
    ``limit`` orders and ``budget`` steps. The pen's path does not depend on the order (a sum of
    vectors); which gears fit each link does.

    Always yields at least one: 0, max, min, 2nd max, 2nd min, … (min first when every speed is
    negative) zig-zags. ``first``: the name of the link that must come first (the crank's).
    """
    pref = list(chain_order(links))
    head = [l for l in pref if l.name == first]
    pref = [l for l in pref if l.name != first]
    count, found = [0], []

    def dfs(seq, rest):
        if not rest:
            found.append(tuple(seq))
            return len(found) >= limit
        for i, l in enumerate(rest):
            count[0] += 1
            if count[0] > budget:
                return True
            w = [0, *(x.speed for x in seq), l.speed]
            if len(w) >= 3 and (w[-1] - w[-2]) * (w[-3] - w[-2]) <= 0:
                continue
            if dfs(seq + [l], rest[:i] + rest[i + 1:]):
                return True
        return False

    if pref or head:
        dfs(head, pref)
    if not found and not head:
        by = sorted(pref, key=lambda l: l.speed)
        out, hi = [], bool(by) and by[-1].speed > 0
        while by:
            out.append(by.pop(-1 if hi else 0))
            hi = not hi
        found.append(tuple(out))
    return found  # empty only when ``first`` leaves no zig-zag


def drawable_order(links, budget: int = 20_000, first: str | None = None) -> tuple[Link, ...] | None:
    """The most preferred of ``drawable_orders`` (None when ``first`` leaves none)."""
    got = drawable_orders(links, 1, budget, first)
    return got[0] if got else None


def _point_segments(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance of each point p (k,) to the nearest segment a→b (m,), complex mm → (k,)."""
    ab = b - a
    l2 = np.maximum(np.abs(ab) ** 2, 1e-300)
    t = ((p[:, None] - a[None, :]) * np.conj(ab)[None, :]).real / l2[None, :]
    t = np.clip(t, 0.0, 1.0)
    return np.abs(p[:, None] - (a[None, :] + t * ab[None, :])).min(axis=1)


def _directed(p: np.ndarray, q: np.ndarray, upper: np.ndarray, chunk: int = 128) -> float:
    """max_i min dist(p_i, closed polyline q); ``upper`` (k,) bounds each point's distance from above
    (a distance to some point of q), so points that cannot raise the maximum are never measured."""
    a, b = q, np.roll(q, -1)
    order = np.argsort(-upper)
    best = 0.0
    for i in range(0, len(order), chunk):
        idx = order[i:i + chunk]
        if upper[idx[0]] <= best:
            break
        idx = idx[upper[idx] > best]
        best = max(best, float(_point_segments(p[idx], a, b).max()))
    return best


def polyline_hausdorff(p: np.ndarray, q: np.ndarray, p_theta=None, q_theta=None) -> float:
    """Hausdorff distance between two closed polylines (vertices (k,), (m,) complex, mm): the
    larger of the farthest vertex of each from the other's segments. With both curves' crank
    angles given, a vertex's distance to the other's point at the nearest angle bounds it first."""
    def bound(x, xt, y, yt):
        """(k,) distance of each vertex of x to some vertex of y: the vertex at the nearest angle
        and every s-th vertex of y (a coarse pass that catches a path drawn out of phase)."""
        st = max(1, len(y) // 512)
        out = np.full(len(x), np.inf)
        for i in range(0, len(x), 1024):
            out[i:i + 1024] = np.abs(x[i:i + 1024, None] - y[None, ::st]).min(axis=1)
        if xt is not None and yt is not None:
            j = np.searchsorted(yt, xt) % len(y)
            out = np.minimum(out, np.minimum(np.abs(x - y[j]), np.abs(x - y[j - 1])))
        return out

    return max(_directed(p, q, bound(p, p_theta, q, q_theta)), _directed(q, p, bound(q, q_theta, p, p_theta)))


def chain_path(chain: Chain, m: int) -> tuple[np.ndarray, np.ndarray]:
    """The pen at m crank angles 2πj/m: (θ (m,) rad, path (m,) complex mm)."""
    theta = 2 * np.pi * np.arange(m) / m
    return theta, trace(chain, theta)


def path_samples(d: Drawing) -> int:
    """Crank angles a chain's path is measured at: fine enough that its chords stay well inside any
    budget (a link of speed k and length r sags r(πk/m)²/2 between samples)."""
    return max(4096, len(d.samples))


def measure(chain: Chain, d: Drawing, m: int | None = None) -> tuple[float, float, float]:
    """(Hausdorff, max at the same θ, RMS at the same θ) of the chain's pen path vs the samples, mm."""
    m = m or path_samples(d)
    theta, path = chain_path(chain, m)
    same = np.abs(trace(chain, d.theta) - d.samples)
    h = polyline_hausdorff(d.samples, path, d.theta, theta)
    return h, float(same.max()), float(np.sqrt(np.mean(same ** 2)))


def candidates(links: tuple[Link, ...], min_link_mm: float, lead: str | None = None) -> list[Link]:
    """The links at least ``min_link_mm`` long, longest first; ``lead`` (a name) first whatever its
    length, or none at all when it is too short or missing."""
    ok = [l for l in links if l.length >= min_link_mm]
    if lead is None:
        return ok
    head = [l for l in ok if l.name == lead]
    return head + [l for l in ok if l.name != lead] if head else []


def tradeoff(offset: complex, links: tuple[Link, ...], d: Drawing, max_links: int,
             min_link_mm: float = 0.0, lead: str | None = None) -> tuple[Row, ...]:
    """One row per chain of the n longest links at least ``min_link_mm`` long, n = 1..max_links
    (with ``lead`` always first). ``links`` longest first."""
    ok = candidates(links, min_link_mm, lead)[:max_links]
    rows = []
    for n in range(1, len(ok) + 1):
        h, mx, rms = measure(Chain(tuple(ok[:n]), offset), d)  # the path does not depend on the order
        rows.append(Row(n, h, mx, rms, min(l.length for l in ok[:n])))
    return tuple(rows)


def choose(offset: complex, links: tuple[Link, ...], d: Drawing, max_deviation_mm: float, max_links: int,
           min_link_mm: float, lead: str | None = None) -> Choice:
    """The fewest printable links (longest first) whose chain lies within ``max_deviation_mm``
    (Hausdorff) of the samples; when none within ``max_links`` does, the best there is."""
    rows = tradeoff(offset, links, d, max_links, min_link_mm, lead)
    ok = candidates(links, min_link_mm, lead)
    meets = [r for r in rows if r.hausdorff_mm <= max_deviation_mm]
    row = meets[0] if meets else None
    n = row.links if row else (min(rows, key=lambda r: r.hausdorff_mm).links if rows else 0)
    order = drawable_order(ok[:n], first=lead) if n else ()
    return Choice(Chain(tuple(order or ok[:n]), offset), rows, row)


@dataclass(frozen=True)
class Rescue:
    """What would meet the budget: enlarge the drawing by ``up`` (the smallest factor ≥ 1) with
    ``up_links`` links, shrink it to ``down`` (the largest factor < 1) with ``down_links``, or
    allow ``links`` links at this size; None where none does (within the links measured)."""

    up: float | None
    up_links: int
    down: float | None
    down_links: int
    links: int | None


def rescue(offset: complex, links: tuple[Link, ...], d: Drawing, max_deviation_mm: float, max_links: int,
           min_link_mm: float, up_to: int = 64, lead: str | None = None) -> Rescue:
    """The scale factors nearest 1 either way, or the fewest links, that would meet the budget.

    Scaling the drawing by s scales every link and every deviation by s, so the chain of the n
    longest links (H(n) at s = 1, shortest link ℓ_n) is printable and within budget B for
    ``min_link/ℓ_n ≤ s ≤ B/H(n)``; n runs to ``max_links``. At s = 1, more links: the fewest n ≤
    ``up_to`` with ℓ_n ≥ min_link and H(n) ≤ B.
    """
    rows = tradeoff(offset, links, d, max_links, 0.0, lead)
    up = down = None
    for r in rows:
        lo, hi = min_link_mm / r.shortest_mm, (max_deviation_mm / r.hausdorff_mm if r.hausdorff_mm > 0 else math.inf)
        if lo > hi:
            continue
        if hi >= 1.0 and (up is None or max(1.0, lo) < up[0] - 1e-12):
            up = (max(1.0, lo), r.links)
        if lo < 1.0 and (down is None or min(hi, 1.0) > down[0] + 1e-12):
            down = (min(hi, 1.0), r.links)
    more = None
    ok = candidates(links, min_link_mm, lead)[:up_to]
    for n in range(max_links + 1, len(ok) + 1):  # links printable at this size, beyond max_links
        if measure(Chain(tuple(ok[:n]), offset), d)[0] <= max_deviation_mm:
            more = n
            break
    return Rescue(up[0] if up else None, up[1] if up else 0, down[0] if down else None, down[1] if down else 0, more)


def lead(links: tuple[Link, ...]) -> Link | None:
    """The link the crank turns: the drawing's lowest harmonic that matters.

    Of the links at least ``LEAD_FRACTION`` as long as the longest, the lowest |speed| k; of the
    two links ±k, the longer (lengths compared at 1e-6 mm; a tie goes to +k). A curve with a
    once-per-cycle term of that size leads with it (k = 1, the crank turns once per drawing); a
    3:2 Lissajous figure (speeds ±2, ±3) leads with L2 and its crank turns twice per drawing. When
    the lead turns backwards (-k) the caller draws the curve the other way round, which turns
    every speed's sign. None when there are no links."""
    if not links:
        return None
    longest = max(l.length for l in links)
    big = [l for l in links if quantise(l.length) >= quantise(LEAD_FRACTION * longest)]
    k = min(abs(l.speed) for l in big)
    pair = [l for l in links if abs(l.speed) == k]
    return min(pair, key=lambda l: (-quantise(l.length), -l.speed))


def retime(chain: Chain, d: Drawing) -> tuple[Chain, Drawing]:
    """One drawing per cycle of θ. When every speed of the chain is a multiple of g > 1 the pen
    goes round the curve g times while θ turns once (the samples went round g times): every speed
    is divided by g (θ' = gθ, the same path, drawn once per cycle) and the drawing keeps the
    samples of its first round (θ < 2π/g), their angles multiplied by g. g = 1: unchanged."""
    g = reduce(math.gcd, (abs(int(l.speed)) for l in chain.links), 0)
    if g <= 1:
        return chain, d
    links = tuple(Link(link_name(l.speed // g), l.speed // g, l.length, l.phase) for l in chain.links)
    keep = d.theta < 2 * np.pi / g - 1e-12
    return Chain(links, chain.offset), replace(d, samples=d.samples[keep], theta=d.theta[keep] * g, rounds=g)


SCALE_DIGITS = 3  # curve.scale: auto picks scales of three significant figures
SCALE_STEP = 1.05  # the ladder's step: each scale tried is at least 5 % above the last


def _round_up(x: float, digits: int = SCALE_DIGITS) -> float:
    """x > 0 rounded up to ``digits`` significant figures, from x quantised to 1e-6 of the last
    digit (so an ulp never moves it a step): 1.2301 → 1.24, 0.046 → 0.046, 27.9 → 27.9."""
    e = math.floor(math.log10(x)) - digits + 1
    unit = 10.0 ** e
    n = -(-quantise(x / unit) // 10**6)
    return float(n * 10**e) if e >= 0 else n / 10**(-e)


def scale_ladder(offset: complex, links: tuple[Link, ...], d: Drawing, max_deviation_mm: float, max_links: int,
                 min_link_mm: float, max_link_mm: float, lead_name: str | None = None,
                 tries: int = 40) -> tuple[float, ...]:
    """The scales ``curve.scale: auto`` tries, smallest first (``d`` and ``links`` at scale 1).

    Scaling by s scales every link and every deviation by s, so the chain of the n longest links
    (lead first; H(n) at s = 1, shortest link ℓ_n) is printable and within budget B for
    ``min_link/ℓ_n ≤ s ≤ B/H(n)``, and its longest link fits for ``s ≤ max_link/ℓ_1``. The ladder
    starts at the smallest such s over n ≤ ``max_links``, rounded up to three significant figures,
    and climbs by at least ``SCALE_STEP`` (each rounded up likewise) while some n's window still
    holds it, at most ``tries`` scales. Empty when no n has a window."""
    rows = tradeoff(offset, links, d, max_links, 0.0, lead_name)
    ok = candidates(links, 0.0, lead_name)
    longest = max((l.length for l in ok), default=0.0)
    windows = []
    for r in rows:
        lo = min_link_mm / r.shortest_mm
        hi = min(max_deviation_mm / r.hausdorff_mm if r.hausdorff_mm > 0 else math.inf,
                 max_link_mm / longest if longest > 0 else math.inf)
        if lo <= hi:
            windows.append((lo, hi))
    if not windows:
        return ()
    top = max(hi for _, hi in windows)
    s, out = _round_up(min(lo for lo, _ in windows)), []
    while len(out) < tries and s <= top * (1 + 1e-9):
        if any(lo * (1 - 1e-9) <= s <= hi * (1 + 1e-9) for lo, hi in windows):
            out.append(s)
        s = _round_up(s * SCALE_STEP)
    return tuple(out)
