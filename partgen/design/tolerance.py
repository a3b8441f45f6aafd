"""A Monte Carlo of print tolerances on a kit's margins (pure numpy: mm).

A mechanism turns when every *margin* that decides it stays ≥ 0: each running fit's radial gap,
each mesh's backlash and tip-to-root clearances, and the least clearances between moving parts
over the motion. A mechanism's ``tolerance_model`` reads those margins off one nominal check of
its kit and writes each as a linear function of the deviations of the printed features::

    margin_k = nominal_k + Σ_f coeff[f, k] · δ_f,      δ_f ~ N(0, sigma_f²) independent

(first order: print deviations are a few hundredths of a millimetre against features of
millimetres). A sample draws every δ_f; the kit *jams* in a sample when any margin goes below 0.
``run_chunk`` draws a chunk of samples in one numpy pass; its tallies add up over chunks in
chunk order, so the result depends on (model, seed, chunk size) only, never on who ran which
chunk.

Feature kinds and their distributions (``A``: the printer's xy accuracy, ±, taken as 3σ of a
printed dimension, as printer makers quote it):

=========== ========================================================= =====================
kind        what deviates                                             σ
=========== ========================================================= =====================
hole        a bore's diameter (a running fit's hole)                  A / 3
pin         a pin's or post's diameter                                A / 3
tooth       a gear's outline, as its diameter (tip, root and both     A / 3 (the flanks move
            flanks move out by half of it: tooth thickness, backlash)  by half)
position    one coordinate (x or y, in its part's frame) of a hole,   A / (3·√2): the distance
            pin or post centre                                        of two features, A / 3
outline     a non-gear part's outline, as a diameter                  A / 3
height      a printed height (a part's thickness, a spacer's height)  A / 3 (profiles give no
                                                                      z accuracy)
process     a printing process figure that is not a dimension (a      its own σ, given with the
            part's infill fraction)                                   feature (``sigma``)
=========== ========================================================= =====================

A margin's group says what fails: a ``joint`` (a fit grips its pin), a ``mesh``, a ``clearance``
between passing parts, or the ``balance`` of a balanced linkage (its centre of mass off its pivot
by more than the design allows).

Where a gear sits in its bore (``Play``, ``seat_factor``; docs/tolerance.md): a mesh that runs out
of backlash touches on both flanks, and the two flank forces push its gears apart along the line
of centres (their tangential parts cancel, whatever the driving sense), taking up the bores' radial
play until the mesh runs free or the bore bottoms. A body with one mesh gives that mesh all of its
play (κ = 1); a body with several (an idler, a link with its gear and an idler pin) moves along
the sum of their separating directions and gives each mesh κ = min_k n̂·u_k of it at once. A model
made with ``seated=False`` credits no play (each gear centred on its post: the worst case).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["KINDS", "GROUPS", "Feature", "Margin", "Play", "seat_factor", "seat_credit", "MarginModel", "ModelBuilder", "sigma_of", "run_chunk", "ChunkTally", "add_tallies",
           "wilson", "summarise", "chunk_sizes", "least_play", "PLAY_STEP_MM", "AUTO_SAMPLES"]

KINDS = ("hole", "pin", "tooth", "position", "outline", "height", "process")
GROUPS = ("joint", "mesh", "clearance", "balance")
Z95 = 1.959963984540054  # two-sided 95 % normal quantile


def sigma_of(kind: str, accuracy_mm: float) -> float:
    """σ (mm) of a feature of ``kind`` for a printer accuracy of ± ``accuracy_mm`` (3σ of a dimension)."""
    if kind not in KINDS:
        raise ValueError(f"unknown feature kind {kind!r}")
    if kind == "process":
        raise ValueError("a process feature carries its own sigma")
    s = accuracy_mm / 3.0
    return s / math.sqrt(2.0) if kind == "position" else s


@dataclass(frozen=True)
class Feature:
    """One printed feature's deviation: ``name`` (``"G2 bore"``), ``kind`` (one of KINDS), ``part``."""

    name: str
    kind: str
    part: str
    sigma: float | None = None  # σ of a ``process`` feature (its own units); None: from the kind and accuracy


@dataclass(frozen=True)
class Margin:
    """One margin that decides whether the kit turns.

    unit : what it belongs to, reported as one row: a joint (``"G2 on B1"``), a mesh
        (``"D1/M1"``) or a pair of parts that pass each other (``"D10–G11"``).
    group : "joint", "mesh" or "clearance".
    what : which margin of the unit ("radial gap", "backlash", "tip-root D1→M1", "gap", "axial gap").
    nominal : its value in the nominal kit, mm.
    where : the link (or "base") it sits on, for the reader.
    per_backlash : mm of this margin per mm of ``backlash_per_gear`` (each gear of a mesh thinned
        by Δ at its reference pitch circle opens the backlash on the operating pitch circle by
        Δ·(r_w/r)·2 = 2Δ·cos α/cos α_w; 0 for any other margin): what ``least_play`` moves.
    """

    unit: str
    group: str
    what: str
    nominal: float
    where: str = ""
    per_backlash: float = 0.0


@dataclass(frozen=True)
class Play:
    """A floating body's radial play in its bore: ``nominal`` mm + Σ terms[feature] · δ_feature
    (terms as ``ModelBuilder.add`` takes them: ``(name, kind, part) -> mm per mm``)."""

    nominal: float
    terms: dict


def seat_factor(directions) -> float:
    """κ: the share of a body's radial play that each of its meshes gets at once when the meshes'
    two-flank forces push it. ``directions``: the unit separating directions (from each mate
    towards this body, in one frame) of its meshes; the body moves along their sum n̂ and mesh k's
    centre distance grows by κ_k = n̂·u_k of its play; the least of them is returned (0 when they
    cancel: an idler on the line of its two mates can give neither any play)."""
    u = np.asarray(directions, dtype=float).reshape(-1, 2)
    u = u / np.linalg.norm(u, axis=1, keepdims=True)
    if len(u) == 1:
        return 1.0
    s = u.sum(axis=0)
    n = float(np.linalg.norm(s))
    if n < 1e-9:
        return 0.0
    return max(0.0, float((u @ (s / n)).min()))


def seat_credit(plays) -> tuple[float, dict]:
    """Σ κ · play over ``plays`` [(κ, Play)]: the growth of a mesh's centre distance when its
    bodies sit where their meshes push them, as (nominal mm, terms)."""
    nominal, terms = 0.0, {}
    for k, play in plays:
        if k == 0.0:
            continue
        nominal += k * play.nominal
        for key, c in play.terms.items():
            terms[key] = terms.get(key, 0.0) + k * c
    return nominal, terms


@dataclass(frozen=True, eq=False)
class MarginModel:
    """Margins as linear functions of feature deviations.

    features : (F,) Feature.  margins : (K,) Margin.
    coeff : (F, K) float, mm of margin per mm of deviation.  sigma : (F,) float, mm.
    nominal : (K,) float, mm.  accuracy_mm : the ± accuracy the sigmas came from.
    """

    features: tuple[Feature, ...]
    margins: tuple[Margin, ...]
    coeff: np.ndarray
    sigma: np.ndarray
    nominal: np.ndarray
    accuracy_mm: float
    source: str = ""
    credits: str = ""  # what the model credits, for the reader ("gears seated by their meshes in their bores")

    def __post_init__(self):
        F, K = len(self.features), len(self.margins)
        if self.coeff.shape != (F, K):
            raise ValueError(f"coeff must be ({F}, {K}), got {self.coeff.shape}")
        if self.sigma.shape != (F,) or self.nominal.shape != (K,):
            raise ValueError("sigma must be (F,) and nominal (K,)")

    @property
    def units(self) -> list[str]:
        """Distinct units (joints, meshes, pairs) in first-seen order."""
        return list(dict.fromkeys(m.unit for m in self.margins))

    @property
    def unit_index(self) -> np.ndarray:
        """(K,) int: the unit of each margin, an index into ``units``."""
        idx = {u: i for i, u in enumerate(self.units)}
        return np.array([idx[m.unit] for m in self.margins], dtype=int)

    def digest(self) -> str:
        """A fingerprint of the model (resume refuses chunks of another model)."""
        import hashlib

        h = hashlib.sha256()
        for a in (self.coeff, self.sigma, self.nominal):
            h.update(np.ascontiguousarray(a, dtype=np.float64).tobytes())
        h.update("|".join(f.name for f in self.features).encode())
        h.update("|".join(f"{m.unit}:{m.what}" for m in self.margins).encode())
        return h.hexdigest()[:16]


class ModelBuilder:
    """A mechanism's margins as they are named: ``add(margin, {(feature name, kind, part): mm of
    margin per mm of deviation})``, then ``model(accuracy, source)``. A ``process`` feature's key
    carries its σ as a fourth item: ``(name, "process", part, sigma)``, margin per unit of it."""

    def __init__(self):
        self.features: dict[str, Feature] = {}
        self.margins: list[Margin] = []
        self.cols: list[dict[str, float]] = []

    def add(self, margin: Margin, terms: dict[tuple[str, str, str], float]) -> None:
        col: dict[str, float] = {}
        for key, c in terms.items():
            if c == 0.0:
                continue
            name, kind, part = key[:3]
            self.features.setdefault(name, Feature(name, kind, part, *key[3:4]))
            col[name] = col.get(name, 0.0) + c
        self.margins.append(margin)
        self.cols.append(col)

    def model(self, accuracy: float, source: str, credits: str = "") -> MarginModel:
        feats = tuple(self.features.values())
        idx = {f.name: i for i, f in enumerate(feats)}
        coeff = np.zeros((len(feats), len(self.margins)))
        for k, col in enumerate(self.cols):
            for name, c in col.items():
                coeff[idx[name], k] = c
        sigma = np.array([f.sigma if f.sigma is not None else sigma_of(f.kind, accuracy) for f in feats])
        nominal = np.array([m.nominal for m in self.margins], dtype=float)
        return MarginModel(feats, tuple(self.margins), coeff, sigma, nominal, float(accuracy), source, credits)


@dataclass(frozen=True)
class ChunkTally:
    """What one chunk of samples found (adds up over chunks).

    index, n : the chunk's index and its number of samples.
    jams : samples in which any margin < 0.
    unit_jams : (U,) samples in which the unit jams (any of its margins < 0).
    group_jams : (3,) samples in which any joint, any mesh, any pair (GROUPS) jams.
    margin_jams : (K,) samples in which each margin < 0.
    share : (F,) each feature's share of the jams: for every margin that goes below 0 in a
        sample, the features that pushed it down share one jam in proportion to how far each did.
    """

    index: int
    n: int
    jams: int
    unit_jams: np.ndarray
    group_jams: np.ndarray
    margin_jams: np.ndarray
    share: np.ndarray

    def to_dict(self) -> dict:
        return {"index": self.index, "n": self.n, "jams": self.jams, "unit_jams": self.unit_jams.tolist(),
                "group_jams": self.group_jams.tolist(),
                "margin_jams": self.margin_jams.tolist(), "share": [float(x) for x in self.share]}

    @classmethod
    def from_dict(cls, d: dict) -> "ChunkTally":
        return cls(int(d["index"]), int(d["n"]), int(d["jams"]), np.asarray(d["unit_jams"], dtype=np.int64),
                   np.asarray(d["group_jams"], dtype=np.int64), np.asarray(d["margin_jams"], dtype=np.int64),
                   np.asarray(d["share"], dtype=np.float64))


def chunk_sizes(samples: int, chunk: int) -> list[int]:
    """The sizes of the chunks ``samples`` splits into (all ``chunk`` but the last)."""
    if samples <= 0 or chunk <= 0:
        raise ValueError("samples and chunk must be > 0")
    full, rest = divmod(samples, chunk)
    return [chunk] * full + ([rest] if rest else [])


def run_chunk(model: MarginModel, seed: int, index: int, n: int) -> ChunkTally:
    """Draw chunk ``index`` of ``n`` samples (its generator: ``SeedSequence(seed, spawn_key=(index,))``,
    the same stream ``SeedSequence(seed).spawn`` gives the index-th child) and tally its jams."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(index,)))
    F, K = model.coeff.shape
    z = rng.standard_normal((n, F))
    scaled = model.coeff * model.sigma[:, None]  # (F, K): mm of margin per standard deviation
    m = model.nominal[None, :] + z @ scaled  # (n, K)
    jam = m < 0.0
    uidx = model.unit_index
    U = int(uidx.max()) + 1 if K else 0
    unit_jam = np.zeros((n, U), dtype=bool)
    for k in range(K):
        unit_jam[:, uidx[k]] |= jam[:, k]
    share = np.zeros(F)
    for k in np.flatnonzero(jam.any(axis=0)):
        rows = np.flatnonzero(jam[:, k])
        push = np.maximum(-(z[rows] * scaled[:, k]), 0.0)  # (r, F): how far each feature pushed it down
        tot = push.sum(axis=1, keepdims=True)
        share += (push / np.where(tot > 0, tot, 1.0)).sum(axis=0)
    groups = np.array([[m.group == g for m in model.margins] for g in GROUPS], dtype=bool)  # (3, K)
    group_jams = np.array([int(jam[:, sel].any(axis=1).sum()) for sel in groups], dtype=np.int64)
    return ChunkTally(index, n, int(jam.any(axis=1).sum()), unit_jam.sum(axis=0).astype(np.int64), group_jams,
                      jam.sum(axis=0).astype(np.int64), share)


def add_tallies(tallies) -> ChunkTally:
    """The sum of chunk tallies, added in chunk-index order (so the float sums do not depend on the
    order the chunks finished in)."""
    ts = sorted(tallies, key=lambda t: t.index)
    if not ts:
        raise ValueError("no chunks")
    out = ts[0]
    for t in ts[1:]:
        out = ChunkTally(-1, out.n + t.n, out.jams + t.jams, out.unit_jams + t.unit_jams,
                         out.group_jams + t.group_jams, out.margin_jams + t.margin_jams, out.share + t.share)
    return out


def wilson(k: int, n: int, z: float = Z95) -> tuple[float, float]:
    """Wilson score interval of a proportion k/n (95 % by default)."""
    if n <= 0:
        return (0.0, 1.0)
    if k == 0:
        return (0.0, z * z / (n + z * z))
    if k == n:
        return (n / (n + z * z), 1.0)
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return (max(0.0, centre - half), min(1.0, centre + half))


def _prob(k: int, n: int) -> dict:
    lo, hi = wilson(k, n)
    return {"jams": int(k), "probability": k / n if n else 0.0, "ci95": [lo, hi]}


def summarise(model: MarginModel, total: ChunkTally, top: int = 12) -> dict:
    """The study's result (JSON-able): overall, per unit (joints, meshes, pairs: worst first), per
    margin, and the sensitivity ranking by feature kind and by feature."""
    n = total.n
    units = model.units
    uidx = model.unit_index
    rows = []
    for u, name in enumerate(units):
        ks = np.flatnonzero(uidx == u)
        first = model.margins[ks[0]]
        rows.append({"unit": name, "group": first.group, "where": first.where,
                     "least_nominal_mm": float(min(model.nominal[k] for k in ks)),
                     "margins": {model.margins[k].what: float(model.nominal[k]) for k in ks},
                     **_prob(int(total.unit_jams[u]), n)})
    rows.sort(key=lambda r: (-r["jams"], r["least_nominal_mm"]))
    shares = total.share
    all_share = float(shares.sum())
    kinds = {}
    for f, s in zip(model.features, shares):
        kinds[f.kind] = kinds.get(f.kind, 0.0) + float(s)
    by_kind = sorted(({"kind": k, "share": (v / all_share) if all_share else 0.0} for k, v in kinds.items()),
                     key=lambda r: -r["share"])
    order = np.argsort(-shares, kind="stable")[:top]
    by_feature = [{"feature": model.features[i].name, "kind": model.features[i].kind,
                   "share": float(shares[i] / all_share) if all_share else 0.0} for i in order if shares[i] > 0]
    groups = {}
    for i, g in enumerate(GROUPS):
        members = [r for r in rows if r["group"] == g]
        groups[g] = {"count": len(members), "worst": members[0]["unit"] if members and members[0]["jams"] else None,
                     **_prob(int(total.group_jams[i]), n)}
    return {"samples": n, "accuracy_mm": model.accuracy_mm, "features": len(model.features),
            "margins": len(model.margins), "overall": _prob(total.jams, n), "groups": groups, "units": rows,
            "sensitivity": {"by_kind": by_kind, "by_feature": by_feature}}


def with_means(model: MarginModel, mean: np.ndarray, why: str = "") -> MarginModel:
    """``model`` with each feature's deviation drawn around ``mean`` (F,), mm, rather than 0: a printer's
    measured bias (a hole prints 0.12 mm small: mean -0.12). The margins are linear in the deviations,
    so δ = mean + σ·z moves margin k's nominal by Σ_f coeff[f, k]·mean_f exactly; the spread is unchanged."""
    mean = np.asarray(mean, dtype=float)
    if mean.shape != model.sigma.shape or not np.all(np.isfinite(mean)):
        raise ValueError(f"mean must be ({len(model.features)},) finite mm")
    if not np.any(mean):
        return model
    return MarginModel(model.features, model.margins, model.coeff, model.sigma, model.nominal + mean @ model.coeff,
                       model.accuracy_mm, model.source + (f"; {why}" if why else ""), model.credits)


PLAY_STEP_MM = 0.005  # auto play is a whole number of these (quantised: the same kit on any machine)
PLAY_MAX_MM = 0.5
AUTO_SAMPLES = 20_000  # prints the auto choice is made on (seed 0, chunk 0): ~0.1 s for the default chain


def least_play(model: MarginModel, start_mm: float, target: float, samples: int = AUTO_SAMPLES, seed: int = 0,
               step: float = PLAY_STEP_MM, most: float = PLAY_MAX_MM) -> dict:
    """The least ``backlash_per_gear`` (a whole number of ``step`` from ``step`` to ``most``) with at most
    ``floor(target · samples)`` jams among ``samples`` fixed prints (seed, chunk 0) of ``model``,
    which was made from a kit with ``start_mm``; each margin moves by ``per_backlash`` · (value −
    start). The same draws for every value, so the jams only fall as the play grows: a bisection
    finds the least value exactly; ties cannot arise (one value per count). When even ``most`` is
    not enough (other margins jam more often than the target), the least value whose jams are
    those of ``most``, with ``reached: False``."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    z = rng.standard_normal((samples, len(model.features)))
    base = model.nominal[None, :] + z @ (model.coeff * model.sigma[:, None])
    slope = np.array([m.per_backlash for m in model.margins])
    allowed = int(math.floor(target * samples + 1e-9))
    steps = max(1, int(round(most / step)))

    def jams(k: int) -> int:
        return int(((base + slope[None, :] * (k * step - start_mm)) < 0.0).any(axis=1).sum())
    lo, hi = 1, steps  # at least one step: the nominal kit, every gear centred, keeps some backlash
    floor = jams(hi)
    reached = floor <= allowed
    if not reached:  # other margins (fits, clearances) jam more than the target: the least play that
        allowed = floor  # reaches what the most play reaches (more play would buy nothing)
    while lo < hi:
        mid = (lo + hi) // 2
        if jams(mid) <= allowed:
            hi = mid
        else:
            lo = mid + 1
    k = lo
    j = jams(k)
    lo95, hi95 = wilson(j, samples)
    return {"backlash_per_gear_mm": round(k * step, 6), "reached": reached, "target": target, "samples": samples,
            "seed": seed, "jams": j, "probability": j / samples, "ci95": [lo95, hi95],
            }
