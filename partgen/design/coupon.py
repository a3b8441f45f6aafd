"""The calibration coupon of a printer, as numbers (pure: mm, no geometry kernel).

One plate carries every fixed feature, read top to bottom, left to right, each numbered on the part:

* running row (1–13): holes of diameter ``HOLE_D + c`` for diametral clearances c = 0.00 … 0.60 mm
  in 0.05 mm steps; the loose *key*'s post (diameter ``HOLE_D``) is turned in each;
* press row (14–20): holes of ``HOLE_D + c`` for c = -0.15 … +0.15 mm (negative: interference);
  the key's post is pressed into each;
* caliper boss (21) and hole (22), both ``CALIPER_D`` across;
* gear posts (23–25 name the three *gaps* between four posts): two identical spur gears (module 1,
  10 teeth, auto profile shift) set on neighbouring posts mesh with total circumferential backlash
  0.10, 0.20, 0.30 mm when pushed together (each gear's bore takes up its running clearance
  ``GEAR_BORE_CLEARANCE_MM`` towards the other);

and three loose parts: the key (its post is feature 27), two gears, and a caliper bar (26). The
sizes are the same for every printer but the digits, whose stroke is two of its lines.

Numbers are engraved (cut into the top face) as seven-segment digits built from rectangles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from . import involute

__all__ = ["HOLE_D", "CALIPER_D", "RUNNING", "PRESS", "GEAR_BACKLASH", "GEAR", "Hole", "Coupon", "coupon_design",
           "DigitStyle", "digit_style", "SEGMENTS", "label_rects", "gear_centre_distance", "FEATURES"]

HOLE_D = 5.0        # mm: the key's post and the nominal of every fit hole
CALIPER_D = 10.0    # mm: caliper hole and boss
RUNNING = tuple(round(0.05 * i, 2) for i in range(13))          # diametral clearance, mm: features 1..13
PRESS = tuple(round(-0.15 + 0.05 * i, 2) for i in range(7))     # diametral clearance, mm: features 14..20
GEAR_BACKLASH = (0.10, 0.20, 0.30)                              # total circumferential backlash, mm: 23..25
GEAR_BORE_CLEARANCE_MM = 0.4                                     # diametral, gear bore on its post

PLATE_T = 3.0        # plate thickness
PITCH = 6.5          # hole pitch along a row
EDGE = 1.6           # plate border beyond the outermost features
POST_H = 7.0         # gear posts above the plate
BOSS_H = 6.0         # caliper boss above the plate
BAR = (30.0, 10.0, 4.0)        # caliper bar length, width, height
KEY_TAB = (15.0, 8.0, 2.5)     # key tab length, width, thickness
KEY_POST_H = 7.0               # key post above the tab


@dataclass(frozen=True)
class GearSpecC:
    """The coupon's gears: teeth, module (mm), pressure angle (rad), profile shift, face width (mm)."""

    teeth: int = 10
    module: float = 1.0
    alpha: float = math.radians(20.0)
    face_width: float = 4.0

    @property
    def shift(self) -> float:
        return involute.auto_profile_shift(self.teeth, self.alpha)

    @property
    def tip_radius(self) -> float:
        return 0.5 * involute.tip_diameter(self.teeth, self.module, self.shift)

    @property
    def bore_diameter(self) -> float:
        return HOLE_D + GEAR_BORE_CLEARANCE_MM


GEAR = GearSpecC()

# feature number -> (what, kind) : what the instruction sheet and the results template call it
FEATURES: dict[int, tuple[str, str]] = {
    **{i + 1: (f"running hole {HOLE_D + c:.2f} mm (clearance {c:.2f} mm diametral)", "running")
       for i, c in enumerate(RUNNING)},
    **{14 + i: (f"press hole {HOLE_D + c:.2f} mm (clearance {c:+.2f} mm diametral)", "press")
       for i, c in enumerate(PRESS)},
    21: (f"caliper boss, {CALIPER_D:g} mm", "boss"),
    22: (f"caliper hole, {CALIPER_D:g} mm", "hole"),
    **{23 + i: (f"gear posts, backlash {j:.2f} mm", "gear") for i, j in enumerate(GEAR_BACKLASH)},
    26: (f"caliper bar, {BAR[0]:g} x {BAR[1]:g} mm", "bar"),
    27: (f"key post, {HOLE_D:g} mm", "pin"),
}


def gear_centre_distance(backlash: float, gear: GearSpecC = GEAR) -> float:
    """Centre distance (mm) at which two coupon gears mesh with ``backlash`` (total, circumferential,
    on the operating pitch circle), by bisection on ``involute.circumferential_backlash``."""
    z, m, a0, x = gear.teeth, gear.module, gear.alpha, gear.shift
    lo = involute.centre_distance(z, z, m, a0, x, x)
    hi = lo + 2.0
    f = lambda a: involute.circumferential_backlash(z, z, m, a0, x, x, 0.0, 0.0, a) - backlash  # noqa: E731
    if f(lo) > 1e-12:
        raise ValueError(f"backlash {backlash} mm is below the tight mesh's")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) > 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@dataclass(frozen=True)
class DigitStyle:
    """Seven-segment digits: stroke, height, width, gap between digits, engraving depth (mm)."""

    stroke: float
    height: float
    width: float
    depth: float

    @property
    def gap(self) -> float:
        return self.stroke

    def label_width(self, text: str) -> float:
        return len(text) * self.width + (len(text) - 1) * self.gap


def digit_style(line_width: float, layer_height: float) -> DigitStyle:
    """Digits a printer draws legibly: strokes of two lines (0.5–1.0 mm), 4.5 strokes tall (at least
    3.5 mm), 0.6 as wide as tall; engraved max(0.6 mm, 3 layers) deep."""
    s = min(max(2.0 * line_width, 0.5), 1.0)
    h = max(3.5, 4.5 * s)
    return DigitStyle(s, h, 0.6 * h, max(0.6, 3.0 * layer_height))


#: segments of each digit (a top, b top right, c bottom right, d bottom, e bottom left, f top left, g middle)
SEGMENTS = {"0": "abcdef", "1": "bc", "2": "abged", "3": "abgcd", "4": "fgbc", "5": "afgcd", "6": "afgedc",
            "7": "abc", "8": "abcdefg", "9": "abcdfg"}


def label_rects(text: str, centre: tuple[float, float], style: DigitStyle) -> list[tuple[float, float, float, float]]:
    """Rectangles (x0, y0, x1, y1), mm, of ``text`` (digits) centred on ``centre``, upright (+y up)."""
    s, h, w = style.stroke, style.height, style.width
    x = centre[0] - 0.5 * style.label_width(text)
    y0 = centre[1] - 0.5 * h
    out = []
    for ch in text:
        if ch not in SEGMENTS:
            raise ValueError(f"no seven-segment form for {ch!r}")
        seg = {"a": (x, y0 + h - s, x + w, y0 + h), "g": (x, y0 + 0.5 * (h - s), x + w, y0 + 0.5 * (h + s)),
               "d": (x, y0, x + w, y0 + s),
               "f": (x, y0 + 0.5 * (h - s), x + s, y0 + h), "b": (x + w - s, y0 + 0.5 * (h - s), x + w, y0 + h),
               "e": (x, y0, x + s, y0 + 0.5 * (h + s)), "c": (x + w - s, y0, x + w, y0 + 0.5 * (h + s))}
        out += [seg[k] for k in SEGMENTS[ch]]
        x += w + style.gap
    return out


@dataclass(frozen=True)
class Hole:
    """A numbered round feature on the plate: number, centre (x, y), diameter (mm)."""

    number: int
    centre: tuple[float, float]
    diameter: float


@dataclass(frozen=True)
class Coupon:
    """Where everything sits on the plate (its lower-left corner at the origin, mm).

    plate : (width, depth, thickness).  holes : fit holes 1–20 and the caliper hole 21.
    boss : the caliper boss 21 (centre, diameter, height above the plate; its number on its top).  posts : gear post centres
    (four, on one line), diameter ``HOLE_D``, ``POST_H`` tall.  labels : (text, centre) engraved on
    the plate's top.  style : the digits.
    """

    plate: tuple[float, float, float]
    holes: tuple[Hole, ...]
    boss: tuple[tuple[float, float], float, float]
    posts: tuple[tuple[float, float], ...]
    labels: tuple[tuple[str, tuple[float, float]], ...]
    style: DigitStyle
    gear_distances: tuple[float, ...]
    boss_label: tuple[str, tuple[float, float]] = ("21", (0.0, 0.0))

    @property
    def running_holes(self) -> tuple[Hole, ...]:
        return tuple(h for h in self.holes if 1 <= h.number <= 13)

    @property
    def press_holes(self) -> tuple[Hole, ...]:
        return tuple(h for h in self.holes if 14 <= h.number <= 20)


def coupon_design(line_width: float, layer_height: float) -> Coupon:
    """The coupon for a printer of this line width and layer height (mm)."""
    st = digit_style(line_width, layer_height)
    dmax = HOLE_D + max(RUNNING)
    label_dy = 0.5 * dmax + 0.7 + 0.5 * st.height  # hole centre to its label's centre
    row_h = dmax + 0.7 + st.height + 0.6
    per_row = 10
    width = 2 * EDGE + (per_row - 1) * PITCH + dmax
    x0 = EDGE + 0.5 * dmax
    # bottom row: boss 21 (its number on its top), hole 22 (its number below it), four gear posts
    low_h = max(CALIPER_D + 0.8 + st.height, 2 * GEAR.tip_radius) + 0.4
    depth = 2 * EDGE + 2 * row_h + low_h
    y_row = [depth - EDGE - 0.5 * dmax, depth - EDGE - 0.5 * dmax - row_h]
    holes, labels = [], []
    diam = [HOLE_D + c for c in RUNNING] + [HOLE_D + c for c in PRESS]
    for i, d in enumerate(diam):
        n = i + 1
        c = (x0 + (i % per_row) * PITCH, y_row[i // per_row])
        holes.append(Hole(n, c, d))
        labels.append((str(n), (c[0], c[1] - label_dy)))
    yb = EDGE + st.height + 0.8 + 0.5 * CALIPER_D
    xb = EDGE + 0.5 * CALIPER_D
    boss = ((xb, yb), CALIPER_D, BOSS_H)
    xh = xb + CALIPER_D + 1.0
    holes.append(Hole(22, (xh, yb), CALIPER_D))
    labels.append(("22", (xh, EDGE + 0.5 * st.height)))
    dist = tuple(gear_centre_distance(j) + GEAR_BORE_CLEARANCE_MM for j in GEAR_BACKLASH)
    xp = max(xh + 0.5 * CALIPER_D + 0.8 + 0.5 * HOLE_D, xb + 0.5 * CALIPER_D + 0.8 + GEAR.tip_radius)
    posts = [(xp, yb)]
    for i, a in enumerate(dist):
        posts.append((posts[-1][0] + a, yb))
        mid = 0.5 * (posts[-2][0] + posts[-1][0])
        labels.append((str(23 + i), (mid, yb - 0.5 * HOLE_D - 0.3 - 0.5 * st.height)))
    if posts[-1][0] + 0.5 * HOLE_D > width - EDGE:
        raise ValueError("coupon layout: the gear posts run off the plate")  # a bug in the constants
    return Coupon((width, depth, PLATE_T), tuple(holes), boss, tuple(posts), tuple(labels), st, dist,
                  ("21", (xb, yb)))
