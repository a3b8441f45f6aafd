"""How a gear part holds its shaft (``shafts.bores``): the bore and hub feature of each kind, sized
from the shaft, the printer's fits and wall, and the bought hardware it takes.

Kinds (r the shaft's radius, d = 2r; clearances diametral, from the printer or the design):

* ``round``: the gear runs on a fixed pin, bore r + running/2.
* ``d_flat``: pressed on a turning shaft's D (flat 1 mm deep), bore r + press/2.
* ``keyway``: pressed on a turning shaft, bore r + press/2, and a keyway on the bore's +y side,
  d/4 + press wide, its floor d/8 + running/2 beyond the shaft's radius; the printed shaft carries an
  integral key d/4 wide standing d/8 proud of its radius along the gear part (a maker prints the key
  with the shaft: no loose key, and the shaft still passes the plates' round holes below it).
* ``hex``: a nut trap — an ISO 4032 nut (``shafts.nut``) pressed into a hexagonal pocket in the hub's
  bottom face (across flats s + press, nut height + running/2 deep); the gear screws onto a bought
  threaded rod of the nut's size that turns in the plates (bore and plate holes rod + running);
  lock it with a second nut or thread-locker.
* ``set_screw``: pressed on a round turning shaft, bore r + press/2, held by an ISO 4026 set screw
  (``shafts.set_screw``, M3 by default) through a radial hole (screw + running) in a hub below the
  gear, threaded through a DIN 562 square nut in a slot open at the hub's bottom face (s + press
  wide, nut height + press thick, its inner face one printer wall outside the bore).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["ISO4032_NUTS", "DIN562_NUTS", "SET_SCREW_LENGTHS", "Hub", "HubError", "plan_hub", "turning", "sizes_within",
           "HARDWARE_KEY"]

# the key (under ``shafts``) a bore kind's feature is sized by: the one to name when it does not fit
HARDWARE_KEY = {"round": "diameter_mm", "d_flat": "diameter_mm", "keyway": "diameter_mm", "hex": "nut",
                "set_screw": "set_screw"}

# thread Ø, across flats s, height m (mm)
ISO4032_NUTS = {"M3": (3.0, 5.5, 2.4), "M4": (4.0, 7.0, 3.2), "M5": (5.0, 8.0, 4.7), "M6": (6.0, 10.0, 5.2),
                "M8": (8.0, 13.0, 6.8)}
DIN562_NUTS = {"M3": (3.0, 5.5, 1.8), "M4": (4.0, 7.0, 2.2), "M5": (5.0, 8.0, 2.7), "M6": (6.0, 10.0, 3.2),
               "M8": (8.0, 13.0, 4.0)}
SET_SCREW_LENGTHS = (3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 16.0, 20.0, 25.0, 30.0)  # ISO 4026, mm
KEY_WIDTH = 0.25  # × d: the key's width
KEY_DEPTH = 0.125  # × d: how far the key stands proud of the shaft (the keyway's depth in the hub)
SCREW_RECESS = 0.5  # mm: the set screw's head end stays this far inside the hub's surface


class HubError(ValueError):
    """A hub feature that does not fit: ``key`` (under ``shafts``) and what would work."""

    def __init__(self, key: str, problem: str):
        super().__init__(problem)
        self.key, self.problem = key, problem


@dataclass(frozen=True)
class Hub:
    """One shaft's bore and hub feature (mm, in the gear part's frame, z from the part's bottom face).

    ``radius``: the shaft's (a hex bore's: the rod's); ``bore``: the bore's radius; ``room``: the
    radius every section the feature crosses must reach (the feature and one printer wall);
    ``hub_need``: the hub's least radius; ``height``: the hub's least height below the lowest gear."""

    kind: str
    radius: float
    bore: float
    room: float
    hub_need: float
    height: float = 0.0
    key_half: float = 0.0  # keyway: the slot's half width, its floor from the axis; the key's half width and top
    key_floor: float = 0.0
    key_top_half: float = 0.0
    key_top: float = 0.0
    nut: str = ""  # hex: the ISO 4032 nut; set_screw: the DIN 562 square nut and the screw
    nut_s: float = 0.0
    nut_m: float = 0.0
    thread: float = 0.0
    pocket_s: float = 0.0  # across flats (hex) or width (slot) of the nut's pocket
    pocket_depth: float = 0.0  # hex: the trap's depth; set_screw: the slot's thickness along x
    slot_x0: float = 0.0  # set_screw: the slot's inner face, the screw's axis height, its length
    screw_z: float = 0.0
    screw_length: float = 0.0
    nut_lift: float = 0.0  # set_screw: the nut's lowest face above the part's bottom face


def turning(kind: str) -> bool:
    """Whether a shaft of this bore kind turns with its gear (only ``round`` is a fixed pin)."""
    return kind != "round"


def _size(table: dict, name: str | None, key: str, what: str) -> tuple[float, float, float]:
    if name not in table:
        raise HubError(key, f"{name!r} is not among the {what} sizes here: use one of {', '.join(table)}")
    return table[name]


def plan_hub(kind: str, r: float, running: float, press: float, wall: float, gap: float, nut: str | None,
             screw: str, slack: float = 0.0) -> Hub:
    """The bore and hub feature of a shaft of radius ``r`` (``hex``: ignored, the nut's thread sets
    the rod); ``gap``: the axial gap a set screw's nut keeps above the part's bottom face; ``slack``:
    how far the printed round outlines stray from their circles (a bore's polygon circumscribes its
    circle, a hub's is inscribed in it), added to every wall next to one."""
    wall = wall + slack
    if kind == "round":
        b = r + running / 2
        return Hub(kind, r, b, b + wall, b + wall)
    if kind == "d_flat":
        b = r + press / 2
        return Hub(kind, r, b, b + wall, b + wall)
    if kind == "keyway":
        b = r + press / 2
        half, floor = (KEY_WIDTH * 2 * r + press) / 2, r + KEY_DEPTH * 2 * r + running / 2
        room = math.hypot(half, floor) + wall
        return Hub(kind, r, b, room, room, key_half=half, key_floor=floor, key_top_half=KEY_WIDTH * r,
                   key_top=r + KEY_DEPTH * 2 * r)
    if kind == "hex":
        if nut is None:
            raise HubError("nut", f"a hex bore takes an ISO 4032 nut on a threaded rod: give its size, one of "
                           f"{', '.join(ISO4032_NUTS)}")
        d, s, m = _size(ISO4032_NUTS, nut, "nut", "ISO 4032 nut")
        rod = d / 2
        b = rod + running / 2
        pocket = s + press
        room = max(pocket / math.sqrt(3.0), b) + wall
        return Hub(kind, rod, b, room, room, nut=nut, nut_s=s, nut_m=m, thread=d, pocket_s=pocket,
                   pocket_depth=m + running / 2)
    if kind == "set_screw":
        d, s, m = _size(DIN562_NUTS, screw, "set_screw", "set screw (DIN 562 square nut)")
        b = r + press / 2
        x0 = b + wall
        x1 = x0 + m + press
        pocket = s + press
        room = math.hypot(x1, pocket / 2) + wall
        need = x1 - r  # the screw from the shaft's surface through the whole nut
        length = next((L for L in SET_SCREW_LENGTHS if L >= need - 1e-9), None)
        if length is None:
            raise HubError("set_screw", f"no ISO 4026 {screw} set screw reaches {need:.1f} mm from the shaft through "
                           "its nut: a smaller screw")
        lift = gap
        z = lift + pocket / 2
        height = z + (d + running) / 2 + wall
        return Hub(kind, r, b, room, max(room, r + length + SCREW_RECESS), height, nut=screw, nut_s=s, nut_m=m,
                   thread=d, pocket_s=pocket, pocket_depth=m + press, slot_x0=x0, screw_z=z, screw_length=length,
                   nut_lift=lift)
    raise HubError("bores", f"unknown bore {kind!r}")


def sizes_within(kind: str, what: str, radius: float, r: float, running: float, press: float, wall: float, gap: float,
                 slack: float = 0.0) -> str:
    """The nut or set-screw sizes of a ``hex`` or ``set_screw`` bore whose ``what`` (``room`` or
    ``hub_need``) is at most ``radius``, as a clause for a message ("" for other kinds)."""
    if kind not in ("hex", "set_screw"):
        return ""
    table = ISO4032_NUTS if kind == "hex" else DIN562_NUTS
    ok = [m for m in table if getattr(plan_hub(kind, r, running, press, wall, gap, m, m, slack), what) <= radius]
    return f" ({', '.join(ok)} would fit)" if ok else " (no size here fits)"
