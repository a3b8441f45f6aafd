"""What a printed coupon's results say about the printer (pure: mm).

Observations (``Observations``) are what the maker wrote down: a state per fit hole and gear
grade, and caliper readings. ``calibrate`` turns them into the profile's numbers:

* biases, as a diameter, printed minus modelled: hole = hole 22 − 10; pin = mean of (boss 21 − 10,
  key post 27 − 5); outline = mean of (bar 26 length − 30, width − 10). Each feature's readings
  are averaged first.
* fits, *as printed* (what the kit's printed hole and pin differ by once ``build`` compensates the
  biases): the modelled clearance of the tightest hole the key turns ``free`` in (running) or
  ``holds`` in (press), plus hole bias, minus pin bias. A calibrated profile compensates (holes
  opened by the hole bias, pins trimmed by the pin bias), so its kits are modelled with exactly the
  clearance that worked on the coupon.
* xy accuracy (± 3σ): 3 × the pooled standard deviation of repeated readings about each feature's
  mean (at least 0.02 mm: a caliper's resolution); None when no feature was read twice.
* gear backlash: the modelled backlash of the tightest gear grade that turns ``smooth``.

A state sequence that goes backwards with the clearance (a looser hole binds while a tighter one
turns) is inconsistent: ``Inconsistent`` names the entry.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .coupon import BAR, CALIPER_D, GEAR_BACKLASH, HOLE_D, PRESS, RUNNING

__all__ = ["RUNNING_STATES", "PRESS_STATES", "GEAR_STATES", "CALIPERS", "PLAUSIBLE_MM", "Observations",
           "Calibrated", "Inconsistent", "calibrate"]

RUNNING_STATES = ("binds", "stiff", "free")        # tight to loose
PRESS_STATES = ("too_tight", "holds", "loose")
GEAR_STATES = ("binds", "smooth", "loose")
# caliper entry -> (nominal mm, kind)
CALIPERS = {"boss_21_diameter_mm": (CALIPER_D, "pin"), "hole_22_diameter_mm": (CALIPER_D, "hole"),
            "bar_26_length_mm": (BAR[0], "outline"), "bar_26_width_mm": (BAR[1], "outline"),
            "key_27_post_diameter_mm": (HOLE_D, "pin")}
PLAUSIBLE_MM = 1.0  # a reading further than this from its nominal is a misreading or the wrong feature
MIN_ACCURACY_MM = 0.02


class Inconsistent(ValueError):
    """Observations that contradict each other; ``key`` names the entry (``running.9``)."""

    def __init__(self, key: str, problem: str):
        super().__init__(f"{key}: {problem}")
        self.key, self.problem = key, problem


@dataclass(frozen=True)
class Observations:
    """running: {hole 1-13: state}; press: {14-20: state}; gears: {23-25: state};
    calipers: {entry: readings (mm)}. Holes not tried are left out."""

    running: dict[int, str]
    press: dict[int, str]
    gears: dict[int, str]
    calipers: dict[str, tuple[float, ...]]


@dataclass(frozen=True)
class Calibrated:
    """The profile's measured numbers (mm): fits as printed, biases (printed minus modelled, as a
    diameter), xy accuracy (None: not measured), and what they came from."""

    running_clearance: float
    press_clearance: float
    hole_bias: float
    pin_bias: float
    outline_bias: float
    xy_accuracy: float | None
    gear_backlash: float | None
    running_hole: int
    press_hole: int
    gear_grade: int | None


def _order(section: str, obs: dict[int, str], states: tuple[str, ...], first: int, values) -> None:
    """Raise Inconsistent unless the states never go back towards tight as the clearance grows."""
    seen = sorted(obs.items())
    for (n0, s0), (n1, s1) in zip(seen, seen[1:]):
        if states.index(s1) < states.index(s0):
            v0, v1 = values[n0 - first], values[n1 - first]
            raise Inconsistent(f"{section}.{n1}", f"'{s1}' at {v1:+.2f} mm, but the tighter {n0} ({v0:+.2f} mm) is "
                               f"'{s0}': a looser one cannot be tighter; try both again")


def _first(section: str, obs: dict[int, str], state: str, what: str) -> int:
    got = [n for n, s in sorted(obs.items()) if s == state]
    if not got:
        raise Inconsistent(section, f"no entry is '{state}': {what}")
    return got[0]


def _mean(xs) -> float:
    return sum(xs) / len(xs)


def calibrate(o: Observations) -> Calibrated:
    """The profile's numbers from a coupon's observations (see the module)."""
    _order("running", o.running, RUNNING_STATES, 1, RUNNING)
    _order("press", o.press, PRESS_STATES, 14, PRESS)
    _order("gears", o.gears, GEAR_STATES, 23, GEAR_BACKLASH)
    for key, xs in o.calipers.items():
        nominal = CALIPERS[key][0]
        for x in xs:
            if not (math.isfinite(x) and abs(x - nominal) <= PLAUSIBLE_MM):
                raise Inconsistent(f"calipers.{key}", f"{x!r} mm is no reading of a {nominal:g} mm feature "
                                   f"(more than {PLAUSIBLE_MM:g} mm off): measure it again")
    for key in ("boss_21_diameter_mm", "hole_22_diameter_mm", "bar_26_length_mm", "bar_26_width_mm"):
        if key not in o.calipers:
            raise Inconsistent(f"calipers.{key}", "required: a caliper reading (mm)")
    run = _first("running", o.running, "free", "the running fit is the tightest hole the key turns freely in")
    press = _first("press", o.press, "holds", "the press fit is the tightest hole the key presses into and holds")
    dev = {k: _mean(xs) - CALIPERS[k][0] for k, xs in o.calipers.items()}
    hole = dev["hole_22_diameter_mm"]
    pin = _mean([dev[k] for k in ("boss_21_diameter_mm", "key_27_post_diameter_mm") if k in dev])
    outline = _mean([dev["bar_26_length_mm"], dev["bar_26_width_mm"]])
    resid = [x - _mean(xs) for xs in o.calipers.values() for x in xs]
    dof = sum(len(xs) - 1 for xs in o.calipers.values())
    acc = max(3.0 * math.sqrt(sum(r * r for r in resid) / dof), MIN_ACCURACY_MM) if dof > 0 else None
    smooth = [n for n, s in sorted(o.gears.items()) if s == "smooth"]
    grade = smooth[0] if smooth else None
    c_run = RUNNING[run - 1] + hole - pin
    c_press = PRESS[press - 14] + hole - pin
    if c_run < 0:
        raise Inconsistent(f"running.{run}", f"turns freely, yet the calipers say the printed hole is "
                           f"{-c_run:.3f} mm smaller than the printed pin: re-measure hole 22, boss 21 and key 27")
    return Calibrated(c_run, c_press, hole, pin, outline, acc,
                      GEAR_BACKLASH[grade - 23] if grade else None, run, press, grade)
