"""The calibration coupon's solids (manifold3d), from ``design.coupon``: each part one closed shell,
lying on z = 0 in its print pose; numbers engraved into top faces."""

from __future__ import annotations

import manifold3d as m3d
import shapely
from shapely.geometry import Polygon, box

from ..design import involute
from ..design.coupon import (BAR, GEAR, HOLE_D, KEY_POST_H, KEY_TAB, POST_H, Coupon, DigitStyle, label_rects)
from .outline import circle
from .solid import extrude, slab, union

__all__ = ["TOL", "plate_solid", "key_solid", "gear_solid", "bar_solid", "coupon_solids", "engraving"]

TOL = 0.002  # mm: chord sagitta of every circle (holes circumscribe theirs: never smaller than nominal)


def engraving(labels, style: DigitStyle) -> Polygon:
    """The union of the labels' segments (shapely), each label ``(text, (x, y))``."""
    rects = [box(*r) for text, c in labels for r in label_rects(text, c, style)]
    return shapely.union_all(rects)


def _engrave(solid: m3d.Manifold, labels, style: DigitStyle, top: float) -> m3d.Manifold:
    cut = extrude(engraving(labels, style), style.depth + 1.0, top - style.depth)
    return solid - cut


def plate_solid(c: Coupon) -> m3d.Manifold:
    """The plate: fit holes 1–20 and caliper hole 22 through it, boss 21 (its number on its top) and the gear posts on it,
    every number engraved into its top."""
    w, d, t = c.plate
    outline = box(0.0, 0.0, w, d)
    holes = [circle(0.5 * h.diameter, TOL, h.centre, hole=True) for h in c.holes]
    base = slab(shapely.difference(outline, shapely.union_all(holes)), 0.0, t)
    (bc, bd, bh) = c.boss
    studs = [slab(circle(0.5 * bd, TOL, bc), t, t + bh)]
    studs += [slab(circle(0.5 * HOLE_D, TOL, p), t, t + POST_H) for p in c.posts]
    body = _engrave(union([base, *studs]), c.labels, c.style, t)
    return _engrave(body, [c.boss_label], c.style, t + bh)


def key_solid(style: DigitStyle) -> m3d.Manifold:
    """The key: a tab with a post of diameter ``HOLE_D`` (feature 27) near one end, 27 engraved."""
    L, W, T = KEY_TAB
    pc = (0.5 * W, 0.5 * W)
    body = union([slab(box(0.0, 0.0, L, W), 0.0, T), slab(circle(0.5 * HOLE_D, TOL, pc), T, T + KEY_POST_H)])
    xl = 0.5 * (pc[0] + 0.5 * HOLE_D + L)
    return _engrave(body, [("27", (xl, 0.5 * W))], style, T)


def gear_solid() -> m3d.Manifold:
    """One coupon gear: its involute outline (``design.involute.gear_outline``) with a bore of
    ``GEAR.bore_diameter``, ``GEAR.face_width`` thick."""
    g = involute.gear_outline(GEAR.teeth, GEAR.module, GEAR.alpha, GEAR.shift, tol=TOL)
    shape = shapely.difference(Polygon(g.points), circle(0.5 * GEAR.bore_diameter, TOL, hole=True))
    return slab(shape, 0.0, GEAR.face_width)


def bar_solid(style: DigitStyle) -> m3d.Manifold:
    """The caliper bar (feature 26): a block ``BAR`` with 26 engraved on top."""
    L, W, H = BAR
    return _engrave(slab(box(0.0, 0.0, L, W), 0.0, H), [("26", (0.5 * L, 0.5 * W))], style, H)


def coupon_solids(c: Coupon) -> dict[str, tuple[m3d.Manifold, int]]:
    """Every part of the coupon: name -> (solid, copies to print)."""
    return {"plate": (plate_solid(c), 1), "key": (key_solid(c.style), 2), "gear": (gear_solid(), 2),
            "bar": (bar_solid(c.style), 1)}
