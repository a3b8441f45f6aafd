"""The spur gear pair's check over one revolution of the output, from the printed outlines (the
gears' sections at half their face width): the flank play either way of the nominal angle, the
overlap, the backlash, the bores over their posts, the bed and bores; and the text `check` prints."""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import box

from ...checks.footer import check_footer
from ...core.findings import Finding, Result
from ...geometry.measure import section
from .kit import PairKit
from .resolve import PairSpec

__all__ = ["outline", "flank_play", "sweep", "check", "check_text"]

_SWEEPS: list[tuple] = []  # (kit, thetas' bytes, play): the last sweeps, newest last
_SWEEPS_KEPT = 2


def outline(kit: PairKit, name: str):
    """The printed gear's section at half its face width, in its own frame (mm)."""
    part = next(p for p in kit.parts if p.name == name)
    return section(part.solid, kit.spec.face_width / 2)


def flank_play(kit: PairKit, thetas: np.ndarray, tol: float = 1e-6) -> dict[str, np.ndarray]:
    """Over gear 1's turns ``thetas`` (n,) rad, from the printed outlines: how far gear 2 can turn from
    its nominal angle before it touches gear 1, against (``ahead``, > 0: the flank gear 1 drives
    with) and along (``behind``, < 0) its motion, rad at gear 2; and the overlap area (mm²) at the
    nominal angle (0 when the pair runs free). Bisection to ``tol`` rad."""
    s = kit.spec
    p1, p2 = outline(kit, "gear1"), outline(kit, "gear2")
    r1 = s.centre_distance * s.gear1.teeth / (s.gear1.teeth + s.gear2.teeth)
    m = s.gear1.system.module
    window = box(r1 - 3 * m, -3 * m, r1 + 3 * m, 3 * m)  # the teeth in mesh lie inside it
    reach = math.pi / s.gear2.teeth  # half a pitch: farther than any backlash
    out = {"ahead": np.empty(len(thetas)), "behind": np.empty(len(thetas)), "overlap_mm2": np.empty(len(thetas))}
    for k, t in enumerate(thetas):
        g1 = shapely.intersection(affinity.rotate(p1, float(t), origin=(0, 0), use_radians=True), window)
        shapely.prepare(g1)
        phi = float(s.output_angle(t))

        def area(d: float) -> float:
            g2 = _turned_and_moved(p2, phi + d, s.centre_distance)
            return g1.intersection(g2).area if g1.intersects(g2) else 0.0

        out["overlap_mm2"][k] = area(0.0)
        for key, sign in (("ahead", 1.0), ("behind", -1.0)):
            lo, hi = 0.0, reach
            while hi - lo > tol:
                mid = (lo + hi) / 2
                lo, hi = (lo, mid) if area(sign * mid) > 1e-9 else (mid, hi)
            out[key][k] = sign * lo
    return out


def _turned_and_moved(geom, angle: float, dx: float):
    """``geom`` turned by ``angle`` rad about the origin, then moved ``dx`` along x: the same
    coordinates bit for bit as ``affinity.translate(affinity.rotate(geom, angle, origin=(0, 0),
    use_radians=True), dx)`` (shapely's own arithmetic, its zero offsets and its clamping of tiny
    sines and cosines included), in one pass over the coordinates instead of two."""
    cosp, sinp = math.cos(angle), math.sin(angle)
    if abs(cosp) < 2.5e-16:
        cosp = 0.0
    if abs(sinp) < 2.5e-16:
        sinp = 0.0

    def place(coords):
        x, y = coords.T
        # rotate: a·x + b·y + 0.0 (its offset about the origin); translate: 1·x' + 0·y' + dx, which
        # is x' + dx bit for bit (and 0·x' + 1·y' + 0.0 is y' + 0.0)
        return np.stack([(cosp * x + -sinp * y + 0.0) + dx, (sinp * x + cosp * y + 0.0) + 0.0]).T

    return shapely.transform(geom, place)


def sweep(spec: PairSpec, kit: PairKit, samples: int | None, progress=None):
    """(gear 1's angles over one output turn, their ``flank_play``) at ``samples`` angles (the
    design's own when None). The last two sweeps are kept in memory, each keyed on the kit object
    itself and the angles' bytes (the tolerance is always flank_play's default): `report` runs the
    check and the trace over the same kit, and a process running `trace` and then `report` on one kit
    sweeps it once (a kit is frozen; another kit, even an equal one, is swept anew)."""
    n = samples or spec.samples
    thetas = np.linspace(0.0, 2 * math.pi * spec.gear2.teeth / spec.gear1.teeth, n, endpoint=False)
    key = thetas.tobytes()
    for k, (memo_kit, memo_key, memo_play) in enumerate(_SWEEPS):
        if memo_kit is kit and memo_key == key:
            _SWEEPS.append(_SWEEPS.pop(k))
            if progress:
                progress(n, n)
            return thetas, {name: v.copy() for name, v in memo_play.items()}
    chunks = [thetas[i:i + 16] for i in range(0, n, 16)]
    parts = []
    for i, c in enumerate(chunks):
        parts.append(flank_play(kit, c))
        if progress:
            progress(min((i + 1) * 16, n), n)
    play = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    _SWEEPS.append((kit, key, {name: v.copy() for name, v in play.items()}))
    del _SWEEPS[:-_SWEEPS_KEPT]
    return thetas, play


def check(spec: PairSpec, kit: PairKit, samples: int | None = None, progress=None) -> Result:
    """Over one revolution of the output: the gears never overlap, they keep backlash on both
    flanks, and each bore clears its post."""
    res = Result()
    thetas, play = sweep(spec, kit, samples, progress)
    r2 = spec.centre_distance * spec.gear2.teeth / (spec.gear1.teeth + spec.gear2.teeth)
    bad = np.flatnonzero(play["overlap_mm2"] > 1e-6)
    if len(bad):
        k = bad[np.argmax(play["overlap_mm2"][bad])]
        res.add(Finding("interference", "fail", f"gear1 and gear2 overlap by {play['overlap_mm2'][k]:.4f} mm² of "
                        f"section at {len(bad)} of {len(thetas)} angles", ("gear1", "gear2"), float(thetas[k]),
                        float(play["overlap_mm2"][k] * spec.face_width), "mm3", key="gears"))
    backlash = (play["ahead"] - play["behind"]) * r2
    if backlash.min() <= 0:
        res.add(Finding("mesh", "fail", "the teeth jam: no backlash left", ("gear1", "gear2"),
                        float(thetas[np.argmin(backlash)]), float(backlash.min()), "mm", key="gears.backlash_per_gear_mm"))
    gaps = [spec.bore_of(g) - spec.axle_radius for g in ("gear1", "gear2")]
    radial = min(gaps)
    if radial <= 0:
        res.add(Finding("fit", "fail", f"the bores grip their posts ({radial:.3f} mm radial gap)", ("base", "gear1"),
                        value=radial, unit="mm", key="axles.clearance_diametral_mm"))
    te = play["ahead"] * r2
    res.figures.update(samples=len(thetas), output_turns=1, centre_distance_mm=round(spec.centre_distance, 6),
                       backlash_mm={"min": float(backlash.min()), "max": float(backlash.max()),
                                    "mean": float(backlash.mean()),
                                    "designed": spec.gear1.system.backlash_per_gear + spec.gear2.system.backlash_per_gear},
                       transmission_error_mm={"peak_to_peak": float(np.ptp(te)), "mean": float(te.mean())},
                       max_overlap_mm2=float(play["overlap_mm2"].max()), radial_gap_mm=float(radial),
                       radial_gaps_mm=[float(x) for x in gaps])
    from ...checks.bed import add_bed_and_bores

    add_bed_and_bores(res, kit.parts, kit.printer)
    return res


def check_text(spec: PairSpec, result: Result, folder, seconds: float) -> str:
    f = result.figures
    b, te = f["backlash_mm"], f["transmission_error_mm"]
    lines = [f"{spec.name}: {f['samples']} angles over one turn of the output",
             f"  backlash {b['min']:.3f}–{b['max']:.3f} mm (designed {b['designed']:.3f} mm); transmission error "
             f"{1000 * te['peak_to_peak']:.1f} µm peak to peak; largest overlap {f['max_overlap_mm2']:.4f} mm²; "
             f"bore over post {f['radial_gap_mm']:.3f} mm radial"]
    return "\n".join(lines + check_footer(result, seconds, folder))
