"""The planetary set turned on its printed sections: the carrier's angle against the sun's (the check's
backlash at the carrier and the teeth's overlap, the trace's transmission error)."""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import box

from ....checks.contact import free_turn
from ....geometry.measure import section
from ....geometry.outline import circle
from .kit import PlanetaryKit

__all__ = ["turn_planetary"]


def _place(geom, angle: float, centre) -> object:
    c, sn = math.cos(angle), math.sin(angle)
    R = np.array([[c, -sn], [sn, c]])
    return shapely.transform(geom, lambda p: p @ R.T + np.asarray(centre))


def _sections(kit: PlanetaryKit) -> dict:
    s = kit.params
    z = s.gear_z + s.face_width / 2
    ring = section(kit.part("frame_bottom").solid, z)
    r_out = s.space.tip_radius + 0.5 * s.system.module
    return {"sun": section(kit.part("sun").solid, z), "planet": section(kit.part("planet0").solid, z),
            "ring": shapely.intersection(ring, circle(r_out, 0.05))}


def _turner(geom, centre):
    """``geom`` turned about ``centre`` by an angle (rad): shapely.affinity.rotate's arithmetic, term for
    term (the same floats), without its per-call set-up — a bisection turns one piece many times."""
    x, y = shapely.get_coordinates(geom).T
    x0, y0 = float(centre[0]), float(centre[1])

    def turned(angle: float):
        cosp, sinp = math.cos(angle), math.sin(angle)
        if abs(cosp) < 2.5e-16:
            cosp = 0.0
        if abs(sinp) < 2.5e-16:
            sinp = 0.0
        xoff, yoff = x0 - x0 * cosp + y0 * sinp, y0 - x0 * sinp - y0 * cosp
        xy = np.stack([cosp * x + -sinp * y + xoff, sinp * x + cosp * y + yoff]).T
        return shapely.transform(geom, lambda _: xy)
    return turned

GUESS_SPAN = 5e-4  # rad: a bisection starts within this of a guess (the last angle's contact) when it brackets


def _contact(fixed, piece, centre, sense: float, reach: float, tol: float, guess: float | None = None) -> float:
    """How far (rad, ≥ 0) ``piece`` turns about ``centre`` in the ``sense`` ±1 before it touches ``fixed``
    (to ``tol``); ``guess``: where it likely is — the bisection starts within GUESS_SPAN of it when
    that brackets the contact (free at the low end, touching at the high end), else on [0, reach]."""
    shapely.prepare(fixed)  # indexed once: every step of the bisection tests it
    turn = _turner(piece, centre)

    def area(d: float) -> float:
        q = turn(sense * d)
        return fixed.intersection(q).area if fixed.intersects(q) else 0.0
    if area(0.0) > 1e-9:
        return 0.0
    lo, hi = 0.0, reach
    if guess is not None and GUESS_SPAN < guess < reach - GUESS_SPAN:
        a, b = guess - GUESS_SPAN, guess + GUESS_SPAN
        if area(b) > 1e-9:
            lo, hi = (a, b) if area(a) <= 1e-9 else (0.0, a)
        else:
            lo = b
    return free_turn(lambda d: area(d) > 1e-9, lo, hi, tol)


def turn_planetary(kit: PlanetaryKit, thetas: np.ndarray, tol: float = 1e-7, sections=None,
                   planet_shift: tuple[float, float] = (0.0, 0.0), sun_shift: tuple[float, float] = (0.0, 0.0)) -> dict:
    """The carrier's angle against the sun's from the printed sections, in the carrier's frame (where
    sun, planet and ring turn about fixed axes: the sun drives the planet, the planet the ring): each
    planet turned until it touches the sun, then the ring until it touches the planet; the carrier is
    held by the planet that bears first (the least lag). ``drive``: the sun driving a loaded carrier
    forward; ``coast``: the other flanks. Also the overlap (mm²) of sun/planet and planet/ring
    sections at the nominal angles (every planet, whole outlines: tip and trochoidal interference
    included). Returns {"nominal", "drive", "coast"} carrier angles (n,), "overlap_mm2" (n, 2N) and
    "ring_drive", "ring_coast": the ring's angle in the carrier's frame as found with the sun at its
    nominal place in that frame (n,) (the carrier's angle is worked out from it: the sun held in the
    world turns in the carrier's frame as the carrier lags). ``planet_shift``: every planet moved off
    its pin's centre by (radial, tangential) mm in the carrier's frame (tangential: the carrier's sense
    of turning); ``sun_shift``: the sun's centre moved by (x, y) mm — a body at one place in its bore's
    play (the lost-motion model's exact check, ``play.py``)."""
    s = kit.params
    secs = sections or _sections(kit)
    zp, zr = s.teeth.planet, s.teeth.ring
    n = len(thetas)
    N = len(s.angles)
    nominal = np.array([s.carrier(float(t)) for t in thetas])
    out = {"nominal": nominal, "drive": np.empty(n), "coast": np.empty(n), "overlap_mm2": np.zeros((n, 2 * N)),
           "ring_drive": np.empty(n), "ring_coast": np.empty(n)}
    reach_p, reach_r = math.pi / zp, math.pi / zr
    h = 3.5 * s.system.module  # the teeth in mesh lie within this of a pitch point
    rr = s.space.pitch_radius
    # what may turn into a window within a bisection's reach: a point ρ from its axis moves ρ × reach
    grow_p = min(2 * h, 1.01 * reach_p * s.planet.tip_radius + 0.1)
    grow_r = min(2 * h, 1.01 * reach_r * (s.space.tip_radius + 0.5 * s.system.module) + 0.1)
    windows = []  # per planet: its centre, the window round the sun's pitch point and the ring's, the ring's grown
    for gm in s.angles:
        u = np.array([math.cos(gm), math.sin(gm)])
        w2 = box(*(rr * u - h), *(rr * u + h))
        pc = s.centre_distance * u + planet_shift[0] * u + planet_shift[1] * np.array([-u[1], u[0]])
        windows.append(((float(pc[0]), float(pc[1])),
                        box(*(s.sun.pitch_radius * u - h), *(s.sun.pitch_radius * u + h)), w2, w2.buffer(grow_r)))
    # what both senses share at each angle: the sun's flanks in each window, each planet at its
    # nominal angle and the part of it that meets the sun
    # a planet moved t along its tangent starts turned t / r_p (its sun side back in the middle of the sun
    # mesh's backlash), the ring 2t / r_r (the planet's ring side moved 2t): each search starts free
    t_p = planet_shift[1]
    start_p, start_r = t_p / s.planet.pitch_radius, 2 * t_p / rr
    shared = []
    for k, th in enumerate(thetas):
        c = nominal[k]
        sun = _place(secs["sun"], th - c, sun_shift)
        ring0 = _place(secs["ring"], s.ring_phase - c + start_r, (0.0, 0.0))
        shapely.prepare(sun)  # indexed once per angle: each planet is tested against it
        shapely.prepare(ring0)
        row = []
        for i, (pc, w1, w2, _) in enumerate(windows):
            phi = s.planet_angle(i, float(th)) - c + start_p  # nominal, carrier frame
            planet = _place(secs["planet"], phi, pc)
            # whole outlines: tip and trochoidal interference anywhere
            out["overlap_mm2"][k, i] = sun.intersection(planet).area if sun.intersects(planet) else 0.0
            out["overlap_mm2"][k, N + i] = ring0.intersection(planet).area if ring0.intersects(planet) else 0.0
            fixed = shapely.intersection(sun, w1)
            shapely.prepare(fixed)
            row.append((phi, fixed, shapely.intersection(planet, w1.buffer(grow_p))))
        shared.append(row)
    for key, sense in (("drive", 1.0), ("coast", -1.0)):
        # in the carrier frame the sun turns positive, the planets and the ring negative; driven, each
        # lags: it is found turned from its nominal angle against its motion (positive) until it touches
        last: dict = {}  # (planet, sun or ring) -> the contact at the last angle: the next one's guess
        for k, th in enumerate(thetas):
            c = nominal[k]
            rings = []
            for i, (pc, w1, w2, w2_grown) in enumerate(windows):
                phi, fixed, piece = shared[k][i]
                last[i, 0] = _contact(fixed, piece, pc, sense, reach_p, tol, last.get((i, 0)))
                phi_act = phi + sense * last[i, 0]
                planet_act = shapely.intersection(_place(secs["planet"], phi_act, pc), w2)
                ring_nom = s.ring_phase - c + start_r + (zp / zr) * (phi_act - phi)
                ring = shapely.intersection(_place(secs["ring"], ring_nom, (0.0, 0.0)), w2_grown)
                last[i, 1] = _contact(planet_act, ring, (0.0, 0.0), sense, reach_r, tol, last.get((i, 1)))
                rings.append(ring_nom + sense * last[i, 1])
            # the carrier is held by the planet that bears first: the ring's least lag
            ring = min(rings) if sense > 0 else max(rings)
            out[f"ring_{key}"][k] = ring
            # the sun is held in the world, not in the carrier's frame: a carrier behind its nominal angle by
            # δ turns the sun (and the ring) forward by δ in that frame, and the planets carry the sun's turn
            # to the ring as −z_s/z_r of it; the ring found with the sun at its nominal place therefore sits
            # (1 + z_s/z_r) δ off: δ = (ring_phase − ring − c) · z_r / (z_s + z_r) (exact for teeth that
            # transmit uniformly; tests/mechanisms/gear_train/test_planetary_play.py places the sun there)
            out[key][k] = c + (s.ring_phase - ring - c) * zr / (s.teeth.sun + zr)
    return out
