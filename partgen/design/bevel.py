"""A straight bevel gear pair on intersecting shafts at any shaft angle Σ (pure math: numpy; mm, rad).

Tooth form: **the spherical involute**, exact. Gear i (z_i teeth, module m at the heel, the outer
end) has pitch cone angle δ_i (tan δ_1 = sin Σ / (z_2/z_1 + cos Σ), δ_2 = Σ − δ_1, each below 90°:
90° is a crown gear, more an internal bevel), heel pitch radius r_i = m z_i / 2 and outer cone
distance R = r_i / sin δ_i (both gears' pitch cones share their apex and R). Its base cone has the
half-angle δ_b, sin δ_b = sin δ cos α: the plane of action (through the apex, along the pitch line,
at α to the plane tangent to both pitch cones) touches both base cones. Rolling that plane on the
base cone, each of its lines through the apex sweeps a tooth surface: the cone from the apex over
the **spherical involute** — on the unit sphere round the apex, with the generating great circle
rolled θ = φ sin δ_b from where it touches the base circle at azimuth φ, the point at polar angle
p (from the gear's body axis), cos p = cos δ_b cos θ, and azimuth

    ev(p) = θ / sin δ_b − atan(tan θ / sin δ_b)          (the spherical involute function)

(the planar involute function inv α = tan α − α in the limit of a small sphere patch). Two gears
with these flanks are exactly conjugate at any shaft angle: their contact is a line through the
apex on the plane of action, the ratio constant (Tredgold's back-cone tooth, which partgen made
before, approximates it to second order in the tooth height over R; the octoid, which a planar
generating crown cuts, is conjugate to its crown but not exactly involute, and its contact line
traces a figure-eight path — neither gains anything for a printed gear, where no cutter constrains
the form). A flank's azimuth from its tooth's centre line at polar angle p is

    ψ(p) = s / (2 r) + ev(δ) − ev(p),   s = π m / 2 − backlash (the heel pitch circle's arc),

radial (ψ(δ_b), a plane through the axis) below the base cone. The tip and root cones pass through
the apex (addendum and dedendum angles atan(h_a / R), atan(h_f / R)): every section of the tooth
by a sphere round the apex is the same spherical outline scaled, every section by a plane square to
the axis that outline's central projection from the apex (radius h tan p at h from the apex).

Frame (each gear's local): the common apex at the origin, the gear's axis +z pointing from its body
towards the apex (the body at z < 0), tooth 0 centred on +x. World: gear 1's axis z; gear 2's axis
u_2 = (−sin Σ, 0, cos Σ) through the apex; the pitch cones touch along (sin δ_1, 0, −cos δ_1) from
the apex, each gear's local +x turned towards that line. Kinematics: the pitch cones roll, so
ω_2 = −ω_1 z_1 / z_2 about u_2 (both axes pointing to the apex).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from . import involute

__all__ = ["BevelPair", "BevelTooth", "bevel_pair", "spherical_involute_function", "pitch_angle_limit"]


def spherical_involute_function(p, base_angle: float) -> np.ndarray:
    """ev(p): the azimuth (rad) of the spherical involute of the base cone ``base_angle`` δ_b at polar
    angle ``p`` (rad, ≥ δ_b) from where it leaves the base circle (0 at p = δ_b)."""
    cb, sb = math.cos(base_angle), math.sin(base_angle)
    c = np.clip(np.cos(np.asarray(p, dtype=float)) / cb, -1.0, 1.0)
    th = np.arccos(c)
    return th / sb - np.arctan(np.tan(th) / sb)


def pitch_angle_limit(teeth: tuple[int, int]) -> float:
    """The shaft angle Σ (rad) at which the pair's pitch cone on the gear with more teeth reaches 90°
    (a crown gear; beyond it an internal bevel): cos Σ = −z_small / z_large (π for equal teeth)."""
    z1, z2 = sorted(int(z) for z in teeth)
    return math.acos(-z1 / z2)


@dataclass(frozen=True)
class BevelTooth:
    """One gear of the pair: its teeth, pitch angle δ, outer cone distance R, module m (heel),
    pressure angle α, addendum and dedendum (mm, at the heel), face width b along the pitch cone,
    and the arc ``backlash`` it is thinned by at its heel pitch circle (mm)."""

    teeth: int
    pitch_angle: float
    cone_distance: float
    module: float
    pressure_angle: float
    addendum: float
    dedendum: float
    face_width: float
    backlash: float

    @property
    def pitch_radius(self) -> float:
        return self.module * self.teeth / 2

    @property
    def virtual_teeth(self) -> float:
        """z / cos δ: the teeth of Tredgold's equivalent spur gear (the back cone developed), for comparison."""
        return self.teeth / math.cos(self.pitch_angle)

    @property
    def base_angle(self) -> float:
        """δ_b, sin δ_b = sin δ cos α: the base cone's half-angle (rad)."""
        return math.asin(math.sin(self.pitch_angle) * math.cos(self.pressure_angle))

    @property
    def tip_cone(self) -> float:
        """δ + atan(h_a / R): the tip cone's half-angle (rad)."""
        return self.pitch_angle + math.atan(self.addendum / self.cone_distance)

    @property
    def root_cone(self) -> float:
        """δ − atan(h_f / R): the root cone's half-angle (rad)."""
        return self.pitch_angle - math.atan(self.dedendum / self.cone_distance)

    @property
    def heel_height(self) -> float:
        """H = R cos δ: the heel pitch circle's plane, this far from the apex along the axis."""
        return self.cone_distance * math.cos(self.pitch_angle)

    @property
    def tooth_thickness(self) -> float:
        """Arc thickness at the heel pitch circle, thinning included, mm."""
        return math.pi * self.module / 2 - self.backlash

    def flank_angle(self, polar) -> np.ndarray:
        """ψ(p): the azimuth (rad) from the tooth's centre line of the upper flank at polar angle ``polar``
        (rad, from the body axis; the lower flank: −ψ); below the base cone the flank is radial."""
        db = self.base_angle
        p = np.maximum(np.asarray(polar, dtype=float), db)
        return (self.tooth_thickness / (2 * self.pitch_radius) + float(spherical_involute_function(self.pitch_angle, db))
                - spherical_involute_function(p, db))

    def to_plane(self, polar, azimuth, height: float | None = None) -> np.ndarray:
        """(n, 2): the directions at ``polar`` (from the body axis) and ``azimuth`` projected from the apex
        onto the plane square to the axis ``height`` from it (default H, the heel pitch plane)."""
        h = self.heel_height if height is None else height
        p, a = np.broadcast_arrays(np.asarray(polar, dtype=float), np.asarray(azimuth, dtype=float))
        rad = h * np.tan(p)
        return np.column_stack([rad * np.cos(a), rad * np.sin(a)])

    def tip_angle(self) -> float:
        """Half the tooth's angular thickness (azimuth, rad) on the tip cone."""
        return float(self.flank_angle(self.tip_cone))

    def section(self, tol: float, height: float | None = None) -> np.ndarray:
        """(n, 2) mm counter-clockwise: the gear's section by the plane square to its axis ``height``
        from the apex (default the heel pitch plane): the central projection of the spherical outline —
        root arcs, flanks (spherical involutes, radial below the base cone), tip arcs; tooth 0 on +x.
        Points spaced so a chord sags at most ~0.8 ``tol`` in the heel pitch plane. ValueError for a
        pointed tooth or one that fills its space at the root."""
        z, db, pa, pf = self.teeth, self.base_angle, self.tip_cone, self.root_cone
        if pa >= math.pi / 2 - 1e-6:
            raise ValueError(f"the tip cone is {math.degrees(pa):.1f}° (90° or more): no section square to the axis")
        if pf <= 0:
            raise ValueError("the root cone closes on the axis")
        psi_a = self.tip_angle()
        lo = max(pf, db)
        psi_r = float(self.flank_angle(lo))
        if psi_a <= 0:
            raise ValueError(f"pointed teeth: {2 * self.cone_distance * math.sin(pa) * psi_a:.3f} mm at the heel's tip")
        if psi_r >= math.pi / z:
            raise ValueError("the teeth fill their spaces at the root")
        step_tol = 0.8 * tol
        # the flank by its roll θ (cos p = cos δ_b cos θ): dense, then thinned to chords within the tolerance
        cb = math.cos(db)
        th = np.linspace(math.acos(min(math.cos(lo) / cb, 1.0)), math.acos(math.cos(pa) / cb), 4001)
        polar = np.arccos(cb * np.cos(th))
        dense = self.to_plane(polar, self.flank_angle(polar))
        th = involute._adaptive(th, dense, step_tol)
        polar = np.arccos(np.clip(cb * np.cos(th), -1.0, 1.0))
        polar[0], polar[-1] = lo, pa
        ang = self.flank_angle(polar)
        if pf < db:  # radial below the base cone
            polar, ang = np.concatenate([[pf], polar]), np.concatenate([[psi_r], ang])
        upper = self.to_plane(polar, ang, height)  # root → tip
        lower = upper * np.array([1.0, -1.0])

        def arc(p: float, a0: float, a1: float) -> np.ndarray:  # azimuths a0 → a1 on the cone p
            r = self.heel_height * math.tan(p)
            n = max(2, math.ceil(abs(a1 - a0) / (2 * math.acos(max(1 - step_tol / r, -1.0)))) + 1)
            return self.to_plane(np.full(n, p), np.linspace(a0, a1, n), height)

        half = math.pi / z
        tooth = np.vstack([arc(pf, -half, -psi_r)[:-1], lower, arc(pa, -psi_a, psi_a)[1:-1], upper[::-1],
                           arc(pf, psi_r, half)[1:-1]])
        return involute.repeat_tooth(tooth, z)

    def blank(self, margin: float = 0.5) -> np.ndarray:
        """(6, 2) (ρ, a) counter-clockwise, a along the axis (apex at 0, the body at a < 0): the ring
        the teeth are cut to — the heel back cone from a quarter module below the root (so no edge of
        the ring lies on the root cone) to ``margin`` beyond the tip, the toe back cone likewise, flat
        faces square to the axis through those lower ends."""
        d, R = self.pitch_angle, self.cone_distance
        P = np.array([R * math.sin(d), -R * math.cos(d)])
        g = np.array([math.cos(d), math.sin(d)])  # the back cone's generator, away from the axis
        k = (R - self.face_width) / R
        below = self.dedendum + 0.25 * self.module
        hr, ht = P - below * g, P + (self.addendum + margin) * g
        tr, tt = k * P - k * below * g, k * P + (k * self.addendum + margin) * g
        return np.array([[0.0, hr[1]], hr, ht, tt, tr, [0.0, tr[1]]])

    @property
    def heel_root(self) -> np.ndarray:
        """(ρ, a) where the back face (the plane square to the axis) meets the heel back cone."""
        return self.blank()[1]

    @property
    def toe_root(self) -> np.ndarray:
        return self.blank()[4]


@dataclass(frozen=True)
class BevelPair:
    """Two straight bevel gears on shafts at ``shaft_angle`` Σ (rad) meeting at the common apex."""

    gears: tuple[BevelTooth, BevelTooth]
    shaft_angle: float

    @property
    def teeth(self) -> tuple[int, int]:
        return (self.gears[0].teeth, self.gears[1].teeth)

    @property
    def module(self) -> float:
        return self.gears[0].module

    @property
    def pressure_angle(self) -> float:
        return self.gears[0].pressure_angle

    @property
    def cone_distance(self) -> float:
        return self.gears[0].cone_distance

    @property
    def ratio(self) -> Fraction:
        """Speed ratio input / output, z_2 / z_1."""
        return Fraction(self.teeth[1], self.teeth[0])

    def speed2(self) -> float:
        """Gear 2's turn about its local z per turn of gear 1 about z: −z_1 / z_2."""
        return -self.teeth[0] / self.teeth[1]

    @property
    def axis2(self) -> np.ndarray:
        s = self.shaft_angle
        return np.array([-math.sin(s), 0.0, math.cos(s)])

    @property
    def pitch_line(self) -> np.ndarray:
        """The line the pitch cones touch along, from the apex (world)."""
        d = self.gears[0].pitch_angle
        return np.array([math.sin(d), 0.0, -math.cos(d)])

    def frame2(self) -> np.ndarray:
        """(3, 3) columns: gear 2's local x (towards the pitch line), y, z (u_2) in the world."""
        z2, p = self.axis2, self.pitch_line
        x2 = p - (p @ z2) * z2
        x2 /= np.linalg.norm(x2)
        return np.column_stack([x2, np.cross(z2, x2), z2])

    def _action(self) -> tuple[list[float], list[float]]:
        """On the unit sphere round the apex, along the plane of action's great circle: (λ_i, the arc
        from the pitch point to where it touches gear i's base circle, cos δ_i = cos δ_b,i cos λ_i;
        μ_i, the arc from that point to where gear i's tip cone crosses it, cos δ_a,i = cos δ_b,i cos μ_i)."""
        lam = [math.acos(min(math.cos(g.pitch_angle) / math.cos(g.base_angle), 1.0)) for g in self.gears]
        mu = [math.acos(min(math.cos(g.tip_cone) / math.cos(g.base_angle), 1.0)) for g in self.gears]
        return lam, mu

    def contact_ratio(self) -> float:
        """The arc of action on the plane of action's great circle (each tip cone to the pitch point)
        over the base pitch along it (2π sin δ_b / z, the same for both gears)."""
        lam, mu = self._action()
        g = self.gears[0]
        return sum(m - l for m, l in zip(mu, lam)) / (2 * math.pi * math.sin(g.base_angle) / g.teeth)

    def interference(self) -> list[int]:
        """The gears (0, 1) whose mate's tip reaches below the spherical involute on them (the arc of
        action's end beyond where it touches their base circle, or its contact under their root cone):
        undercut/interference."""
        lam, mu = self._action()
        bad = []
        for i in (0, 1):
            me, k = self.gears[i], 1 - i
            L = lam[i] - (mu[k] - lam[k])  # the end of the action, from gear i's base circle
            if L < 0 or math.acos(math.cos(me.base_angle) * math.cos(L)) < me.root_cone:
                bad.append(i)
        return bad


def bevel_pair(teeth: tuple[int, int], module: float, pressure_angle: float, shaft_angle: float,
               face_width: float, backlash: float = 0.0, ha: float = 1.0, hf: float = 1.25) -> BevelPair:
    """The pair of ``teeth`` (z_1, z_2) at ``module`` (heel), ``pressure_angle``, ``shaft_angle`` (rad),
    ``face_width`` (mm along the pitch cone), each gear thinned by ``backlash`` (mm arc at its heel
    pitch circle); addendum ``ha`` m and dedendum ``hf`` m at the heel."""
    z1, z2 = int(teeth[0]), int(teeth[1])
    d1 = math.atan2(math.sin(shaft_angle), z2 / z1 + math.cos(shaft_angle))
    d2 = shaft_angle - d1
    R = module * z1 / (2 * math.sin(d1))
    gears = tuple(BevelTooth(z, d, R, module, pressure_angle, ha * module, hf * module, face_width, backlash)
                  for z, d in ((z1, d1), (z2, d2)))
    return BevelPair(gears, shaft_angle)
