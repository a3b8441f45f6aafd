"""Interference and clearance of every pair of parts over the mechanism's motion.

Broad phase: every part is a stack of z-prisms (``geometry.measure.slabs``), and parts only turn
about z and move in xy, so two parts can meet only where their slabs share z. For those slab
pairs the bounding circles are tested at all sampled angles at once (numpy). Narrow phase: the
surviving slab pairs' sections are intersected in 2-D (exact for prisms: area × shared height);
a pair that overlaps by more than the tolerance is measured in 3-D with manifold3d at its worst
angle. Pairs the design means to touch (fits, thrust faces, meshes) are left to their own checks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
import shapely.ops

from ..core.protocol import CheckedKit as Kit  # what the shared checks read of a kit
from ..geometry.measure import Slab, intersection, min_gap, place2d, slabs
from ..core.findings import Finding

CLEARANCE_SLACK = 1e-9  # mm: a gap equal to the least clearance (sums of layer heights in floats) passes

__all__ = ["ENVELOPE_HEIGHTS", "PartGeometry", "prepare", "sample_angles", "pose_array", "sweep"]


@dataclass(frozen=True)
class PartGeometry:
    name: str
    solid: object
    slabs: tuple[Slab, ...]


ENVELOPE_HEIGHTS = 5  # sections per slab of a twisted part (both faces and three between)


def prepare(kit: Kit, twisted: frozenset[str] | set[str] = frozenset(), grow: float = 0.0) -> dict[str, PartGeometry]:
    """Slabs of every part (each distinct solid sliced once); the parts named in ``twisted`` (helical
    gears: not z-prisms) as envelopes, each slab the union of its sections at ENVELOPE_HEIGHTS
    heights grown by ``grow`` mm, so the prism the sweep sees holds the twisted solid."""
    cache: dict[int, tuple[Slab, ...]] = {}
    out = {}
    for p in kit.parts:
        if id(p.solid) not in cache:
            cache[id(p.solid)] = slabs(p.solid, ENVELOPE_HEIGHTS, grow) if p.name in twisted else slabs(p.solid)
        out[p.name] = PartGeometry(p.name, p.solid, cache[id(p.solid)])
    return out


def sample_angles(n: int) -> np.ndarray:
    """n values of the motion parameter over one full cycle (one turn), rad."""
    return 2 * np.pi * np.arange(n) / n


def pose_array(kit: Kit, names: list[str], thetas: np.ndarray) -> np.ndarray:
    """(N, P, 4, 4) poses of the named parts at each value of the motion parameter."""
    poses = kit.poses_over(np.asarray(thetas, dtype=float))
    return np.stack([poses[n] for n in names], axis=1) if names else np.empty((len(thetas), 0, 4, 4))


def declared_pairs(kit: Kit) -> set[frozenset]:
    return {frozenset((c.a, c.b)) for c in kit.contacts}


@dataclass
class _Worst:
    volume: float = 0.0
    n_vol: int = -1
    angles: int = 0  # sampled angles at which the pair overlaps (any of its slab pairs)
    last_n: int = -1
    where2d: tuple | None = None
    gap: float = math.inf
    n_gap: int = -1
    where_gap: tuple | None = None


def _radii(shape, centre) -> tuple[float, float]:
    """The least and greatest distance (mm) of a section's points from ``centre`` (2,)."""
    xy = shapely.get_coordinates(shape)
    far = float(np.hypot(xy[:, 0] - centre[0], xy[:, 1] - centre[1]).max())  # a polygon's farthest point is a vertex
    return float(shapely.distance(shape, shapely.Point(*centre))), far


def _apart(tri, rel: np.ndarray, reach: float) -> np.ndarray:
    """(K,) bool: slab pairs that can never come within ``reach``: b's origin stays put in a's frame
    over the motion (b turns about it relative to a: two parts turning about one axis, or one still),
    so b sweeps the annulus of its own radii about that point, and a's radii about it lie ``reach``
    or more outside that annulus (|p − q| ≥ ||p − o| − |q − o|| for any p of a and q of b)."""
    out = np.zeros(len(tri), dtype=bool)
    fixed = np.all(np.abs(rel[:, :, :3, 3] - rel[:1, :, :3, 3]) < 1e-9, axis=(0, 2)) & \
        np.all(np.abs(rel[:, :, 2, 2] - 1.0) < 1e-12, axis=0)
    for k in np.flatnonzero(fixed):
        _, _, sa, sb, _ = tri[k]
        o = rel[0, k, :2, 3]
        a_lo, a_hi = _radii(sa.shape, o)
        b_lo, b_hi = _radii(sb.shape, (0.0, 0.0))
        out[k] = max(a_lo - b_hi, b_lo - a_hi) >= reach + 1e-9
    return out


def sweep(kit: Kit, geo: dict[str, PartGeometry], thetas: np.ndarray, progress=None,
          prune: bool = False, label: str = "motion parameter") -> tuple[list[Finding], dict]:
    """Interference and clearance findings over the sampled values of the motion parameter (``label``:
    what the mechanism calls it, e.g. the angle of its input), and figures. ``prune``:
    leave out of the narrow phase the slab pairs that turn about one axis and whose radii about it
    stay ``reach`` apart (``_apart``): the same findings, without measuring gaps that cannot matter
    (the figure ``closest_approach`` then names the closest of the pairs measured)."""
    settings = kit.params.checks
    names = [p.name for p in kit.parts]
    P = pose_array(kit, names, thetas)
    zoff = P[0, :, 2, 3]
    skip = declared_pairs(kit)
    reach = max(settings.min_clearance, 1.0)  # measure gaps below this; report the smallest

    # static slab pairs that share z (same-height) and pairs separated only by a thin z-gap
    tri, zsep = [], []
    for a in range(len(names)):
        for b in range(a + 1, len(names)):
            if frozenset((names[a], names[b])) in skip:
                continue
            ga, gb = geo[names[a]], geo[names[b]]
            za = (ga.slabs[0].z0 + zoff[a], ga.slabs[-1].z1 + zoff[a])
            zb = (gb.slabs[0].z0 + zoff[b], gb.slabs[-1].z1 + zoff[b])
            dz = max(za[0] - zb[1], zb[0] - za[1])
            if dz > reach:
                continue
            if dz >= -1e-9:
                # facing slabs across the gap: the top one of the lower part, the bottom one of the upper
                lo, hi = (a, b) if za[1] <= zb[0] + 1e-9 else (b, a)
                zsep.append((lo, hi, max(dz, 0.0), geo[names[lo]].slabs[-1], geo[names[hi]].slabs[0]))
                continue
            for sa in ga.slabs:
                for sb in gb.slabs:
                    h = min(sa.z1 + zoff[a], sb.z1 + zoff[b]) - max(sa.z0 + zoff[a], sb.z0 + zoff[b])
                    if h > 1e-9:
                        tri.append((a, b, sa, sb, h))
    worst: dict[tuple[int, int], _Worst] = {}

    def centres(part_idx, local):
        sel = P[:, part_idx]  # (N, K, 4, 4)
        R, t = sel[:, :, :2, :2], sel[:, :, :2, 3]
        return np.einsum("nkij,kj->nki", R, local) + t

    if tri:
        ia = np.array([t[0] for t in tri])
        ib = np.array([t[1] for t in tri])
        wa = centres(ia, np.array([t[2].centre for t in tri]))
        wb = centres(ib, np.array([t[3].centre for t in tri]))
        bound = np.linalg.norm(wa - wb, axis=2) - np.array([t[2].radius + t[3].radius for t in tri])
        # a slab pair whose relation cannot change needs one angle: the two parts are rigidly
        # joined, or one slab is a disc turning about its own centre relative to the other
        same = np.zeros(len(tri), dtype=bool)
        rel = np.einsum("nkij,nkjl->nkil", np.linalg.inv(P[:, ia]), P[:, ib])
        same |= np.all(np.abs(rel - rel[:1]).reshape(len(thetas), len(tri), -1) < 1e-9, axis=(0, 2))
        for k, (a, b, sa, sb, h) in enumerate(tri):
            for disc_slab, disc_part, other_part in ((sa, a, b), (sb, b, a)):
                if same[k] or not disc_slab.disc:
                    continue
                c = P[:, disc_part] @ np.array([*disc_slab.centre, 0.0, 1.0])  # (N, 4) world
                local = np.einsum("nij,nj->ni", np.linalg.inv(P[:, other_part]), c)
                same[k] = np.all(np.abs(local - local[:1]) < 1e-9)
        bound[1:, same] = np.inf
        hits = np.argwhere(bound < reach)
        narrow = len(hits)  # the figure: slab pairs × angles the bounding circles let through
        if prune:
            hits = hits[~_apart(tri, rel, reach)[hits[:, 1]]]
        placed: dict = {}
        kept: dict = {}  # the placed slabs of parts that never move (the same pose at every angle)
        still = np.all(P == P[:1], axis=(0, 2, 3))  # (parts,): bitwise the same pose, so the same placed shape

        def shape(n, part, slab):
            cache, key = (kept, (part, id(slab))) if still[part] else (placed, (n, part, id(slab)))
            if key not in cache:
                cache[key] = place2d(slab.shape, P[n, part])
                shapely.prepare(cache[key])  # indexed: dwithin and intersects on it are fast
            return cache[key]

        for count, n in enumerate(np.unique(hits[:, 0])):
            if progress:
                progress(count, len(thetas))
            placed.clear()
            for k in hits[hits[:, 0] == n][:, 1]:
                a, b, sa, sb, h = tri[k]
                A, B = shape(n, a, sa), shape(n, b, sb)
                w = worst.setdefault((a, b), _Worst())
                if w.gap < math.inf and not shapely.dwithin(A, B, w.gap):
                    continue  # farther apart than this pair's closest so far: no overlap, no new gap
                common = shapely.intersection(A, B)
                vol = common.area * h
                zmid = max(sa.z0 + zoff[a], sb.z0 + zoff[b]) + h / 2
                if vol > settings.interference_tolerance:
                    if w.last_n != n:
                        w.angles, w.last_n = w.angles + 1, int(n)
                    if vol > w.volume:
                        c = common.centroid
                        w.volume, w.n_vol, w.where2d = vol, int(n), (c.x, c.y, zmid)
                    gap = 0.0
                else:
                    gap = shapely.distance(A, B)
                if gap < w.gap:
                    p, q = shapely.ops.nearest_points(A, B) if gap > 0 else (common.centroid, common.centroid)
                    w.gap, w.n_gap, w.where_gap = gap, int(n), ((p.x + q.x) / 2, (p.y + q.y) / 2, zmid)
    if progress:
        progress(len(thetas), len(thetas))

    findings: list[Finding] = []
    tests = 0
    for (a, b), w in sorted(worst.items(), key=lambda kv: -kv[1].volume):
        if w.n_vol < 0:
            continue
        ga, gb = geo[names[a]], geo[names[b]]
        vol, centre = intersection(ga.solid, P[w.n_vol, a], gb.solid, P[w.n_vol, b])
        tests += 1
        if vol <= settings.interference_tolerance:
            continue
        findings.append(Finding(
            "interference", "fail",
            f"{names[a]} and {names[b]} overlap by {vol:.3f} mm³ at {label} {math.degrees(thetas[w.n_vol]):.1f}° "
            f"(overlapping at {w.angles} of {len(thetas)} sampled angles)",
            (names[a], names[b]), float(thetas[w.n_vol]), vol, "mm3",
            tuple(centre) if centre is not None else w.where2d))

    # clearance: same-height pairs found in 2-D, measured in 3-D (manifold3d min_gap) at their
    # closest angle; thin z-gaps from the stack. ``gaps``: every pair closer than ``reach``, in the
    # plane (xy) or along z (the tolerance study perturbs them)
    closest = None
    gaps: list[dict] = []
    for (a, b), w in worst.items():
        if w.n_vol >= 0 or w.n_gap < 0:
            continue
        if w.gap < reach:
            w.gap = min_gap(geo[names[a]].solid, P[w.n_gap, a], geo[names[b]].solid, P[w.n_gap, b], reach + 1.0)
            tests += 1
            if w.gap < reach:
                gaps.append({"parts": [names[a], names[b]], "mm": round(float(w.gap), 5), "axis": "xy",
                             "theta_deg": round(math.degrees(thetas[w.n_gap]), 3),
                             "location_mm": [round(float(c), 3) for c in w.where_gap]})
        if closest is None or w.gap < closest[0]:
            closest = (w.gap, names[a], names[b], float(thetas[w.n_gap]), w.where_gap)
        if w.gap < settings.min_clearance - CLEARANCE_SLACK:
            findings.append(Finding(
                "clearance", "fail",
                f"{names[a]} and {names[b]} come within {w.gap:.3f} mm at {label} "
                f"{math.degrees(thetas[w.n_gap]):.1f}° (needs {settings.min_clearance:g} mm)",
                (names[a], names[b]), float(thetas[w.n_gap]), w.gap, "mm", w.where_gap))
    if zsep:
        lo = np.array([z[0] for z in zsep])
        hi = np.array([z[1] for z in zsep])
        wl = centres(lo, np.array([z[3].centre for z in zsep]))
        wh = centres(hi, np.array([z[4].centre for z in zsep]))
        over = np.linalg.norm(wl - wh, axis=2) < np.array([z[3].radius + z[4].radius for z in zsep])
        for k, (l, h_, dz, sl, sh) in enumerate(zsep):
            hit = np.flatnonzero(over[:, k])
            if not len(hit):
                continue
            n = int(hit[0])
            A, B = place2d(sl.shape, P[n, l]), place2d(sh.shape, P[n, h_])
            if not shapely.intersects(A, B):
                continue  # footprints apart: farther than dz
            c = shapely.intersection(A, B).centroid
            where = (c.x, c.y, sl.z1 + zoff[l] + dz / 2)
            gaps.append({"parts": [names[l], names[h_]], "mm": round(float(dz), 5), "axis": "z",
                         "theta_deg": round(math.degrees(thetas[n]), 3), "location_mm": [round(float(q), 3) for q in where]})
            if closest is None or dz < closest[0]:
                closest = (dz, names[l], names[h_], float(thetas[n]), where)
            if dz < settings.min_clearance - CLEARANCE_SLACK:
                findings.append(Finding(
                    "clearance", "fail", f"{names[l]} and {names[h_]} are only {dz:.3f} mm apart along z "
                    f"(needs {settings.min_clearance:g} mm)", (names[l], names[h_]), float(thetas[n]), dz, "mm", where))
    figures = {"samples": len(thetas), "slab_pairs": len(tri), "narrow_phase_2d": int(narrow) if tri else 0,
               "exact_3d": tests, "gaps": sorted(gaps, key=lambda g: g["mm"])}
    if closest is not None:
        figures["closest_approach"] = {"mm": round(closest[0], 4), "parts": [closest[1], closest[2]],
                                       "theta_deg": round(math.degrees(closest[3]), 2),
                                       "location_mm": [round(float(c), 3) for c in closest[4]]}
    return findings, figures
