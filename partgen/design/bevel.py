"""A straight bevel gear pair on intersecting shafts at any shaft angle Σ (pure math: numpy; mm, rad).

Tooth form: **Tredgold's back-cone approximation, made conical.** Gear i (z_i teeth, module m at
the heel, the outer end) has pitch cone angle δ_i (tan δ_1 = sin Σ / (z_2/z_1 + cos Σ),
δ_2 = Σ − δ_1), heel pitch radius r_i = m z_i / 2 and outer cone distance R = r_i / sin δ_i (both
gears' pitch cones share their apex and R). Its back cone (the cone touching the heel pitch circle,
its generators square to the pitch cone's) develops into the plane as the *virtual spur gear* of
r_v = r / cos δ, z_v = z / cos δ teeth; the heel tooth profile is that virtual gear's involute
tooth (addendum h_a, dedendum h_f along the back cone; radial flank below the virtual base circle).
A point of the developed profile at virtual polar (r_v + u, φ_v) lies in 3-D at radius
r + u cos δ, azimuth φ_v / cos δ, u sin δ nearer the apex than the heel pitch circle. Every tooth
surface is the cone of straight lines from the common apex through the heel profile (straight
bevel teeth: every section toward the apex a similar copy, scaled about the apex); the tip and root
cones pass through the apex (addendum and dedendum angles atan(h_a / R), atan(h_f / R)).

The exact conjugate surface for intersecting axes is the spherical involute (or the octoid of a
planar crown generator); the Tredgold tooth is the standard engineering approximation of it (the
back cone for the sphere through the heel), within the backlash for the virtual tooth counts the
resolver accepts; the 3-D check measures what is left (transmission error and backlash).

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

__all__ = ["BevelPair", "BevelTooth", "bevel_pair"]


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
    def virtual_radius(self) -> float:
        """r_v = r / cos δ, the back cone's slant length to the axis."""
        return self.pitch_radius / math.cos(self.pitch_angle)

    @property
    def virtual_teeth(self) -> float:
        return self.teeth / math.cos(self.pitch_angle)

    @property
    def virtual_base_radius(self) -> float:
        return self.virtual_radius * math.cos(self.pressure_angle)

    @property
    def heel_height(self) -> float:
        """H = R cos δ: the heel pitch circle's plane, this far from the apex along the axis."""
        return self.cone_distance * math.cos(self.pitch_angle)

    @property
    def tooth_thickness(self) -> float:
        """Arc thickness at the heel pitch circle, thinning included, mm."""
        return math.pi * self.module / 2 - self.backlash

    def virtual_flank_angle(self, rho) -> np.ndarray:
        """Polar angle (rad) in the developed back cone of the upper flank at virtual radius ρ from the
        tooth's centre line (the lower: −); below the virtual base circle the flank is radial."""
        rv, rb = self.virtual_radius, self.virtual_base_radius
        a = self.pressure_angle
        psi = self.tooth_thickness / (2 * rv) + involute.inv(a)
        rho = np.maximum(np.asarray(rho, dtype=float), rb)
        t = np.sqrt(np.maximum(rho * rho - rb * rb, 0.0)) / rb
        return psi - (t - np.arctan(t))

    def to_plane(self, u, phi_v, height: float | None = None) -> np.ndarray:
        """(n, 2): the developed back-cone points at virtual radius r_v + u and angle φ_v, projected
        from the apex onto the plane square to the axis ``height`` (default H, the heel pitch plane)
        from the apex: radius (r + u cos δ) h / (H − u sin δ), azimuth φ_v / cos δ."""
        d, H = self.pitch_angle, self.heel_height
        h = H if height is None else height
        u, phi_v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(phi_v, dtype=float))
        rad = (self.pitch_radius + u * math.cos(d)) * h / (H - u * math.sin(d))
        phi = phi_v / math.cos(d)
        return np.column_stack([rad * np.cos(phi), rad * np.sin(phi)])

    def plane_radius_to_u(self, rad, height: float | None = None) -> np.ndarray:
        """The inverse of ``to_plane``'s radius: the back-cone height u of a point at radius ``rad`` in
        the plane ``height`` from the apex."""
        d, H = self.pitch_angle, self.heel_height
        q = np.asarray(rad, dtype=float) * H / (H if height is None else height)
        return H * (q - self.pitch_radius) / (H * math.cos(d) + q * math.sin(d))

    def tip_angle(self) -> float:
        """Polar half-angle (rad, developed) of the tooth at the virtual tip circle."""
        return float(self.virtual_flank_angle(self.virtual_radius + self.addendum))

    def section(self, tol: float, height: float | None = None) -> np.ndarray:
        """(n, 2) mm counter-clockwise: the gear's section by the plane square to its axis ``height``
        from the apex (default the heel pitch plane) of the conical solid through the heel profile:
        root arcs, flanks (the virtual involute, radial below its base circle), tip arcs; tooth 0 on
        +x. Points spaced so a chord sags at most ~0.8 ``tol`` at the heel. ValueError for a pointed
        tooth or one that fills its space at the root."""
        z, rv, rb = self.teeth, self.virtual_radius, self.virtual_base_radius
        ra, rr = rv + self.addendum, rv - self.dedendum
        c = math.cos(self.pitch_angle)
        psi_a = float(self.virtual_flank_angle(ra))
        lo = max(rr, rb)
        psi_r = float(self.virtual_flank_angle(lo))
        if psi_a <= 0:
            raise ValueError(f"pointed teeth: {2 * ra * psi_a:.3f} mm at the heel's tip")
        if psi_r / c >= math.pi / z:
            raise ValueError("the teeth fill their spaces at the root")
        t_lo, t_a = math.sqrt(max(lo * lo - rb * rb, 0.0)) / rb, math.sqrt(ra * ra - rb * rb) / rb
        # the involute's roll t (ρ = r_b √(1 + t²)): its radius of curvature is r_b t, so a chord over Δt sags
        # r_b t Δt² / 8; from the cusp (t = 0) the arc r_b Δt² / 2 sags r_b Δt³ / 32 — the smaller step of the two
        step_tol = 0.8 * tol
        cusp = (32 * step_tol / rb) ** (1 / 3)
        ts = [t_lo]
        while ts[-1] < t_a:
            ts.append(min(t_a, ts[-1] + 0.9 * min(math.sqrt(8 * step_tol / (rb * max(ts[-1], 1e-12))), cusp)))
        rho = rb * np.sqrt(1 + np.asarray(ts) ** 2)
        u = rho - rv
        ang = self.virtual_flank_angle(rho)
        if rr < rb:  # radial below the base circle
            u, ang = np.concatenate([[rr - rv], u]), np.concatenate([[psi_r], ang])
        upper = self.to_plane(u, ang, height)  # root → tip
        lower = upper * np.array([1.0, -1.0])

        def arc(uu: float, a0: float, a1: float) -> np.ndarray:  # developed angles a0 → a1 at height uu
            r = float(np.hypot(*self.to_plane(uu, 0.0, height)[0]))
            n = max(2, math.ceil(abs(a1 - a0) / c / (2 * math.acos(max(1 - step_tol / r, -1.0)))) + 1)
            return self.to_plane(np.full(n, uu), np.linspace(a0, a1, n), height)

        half = math.pi / z * c  # half a pitch, developed
        ua, ur = self.addendum, -self.dedendum
        tooth = np.vstack([arc(ur, -half, -psi_r)[:-1], lower, arc(ua, -psi_a, psi_a)[1:-1], upper[::-1],
                           arc(ur, psi_r, half)[1:-1]])
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

    def contact_ratio(self) -> float:
        """Transverse contact ratio of the two virtual spur gears at the heel."""
        g1, g2 = self.gears
        a = self.pressure_angle
        path = sum(math.sqrt((g.virtual_radius + g.addendum) ** 2 - g.virtual_base_radius ** 2) for g in (g1, g2))
        path -= (g1.virtual_radius + g2.virtual_radius) * math.sin(a)
        return path / (math.pi * self.module * math.cos(a))

    def interference(self) -> list[int]:
        """The gears (0, 1) whose mate's tip reaches below the involute on them (the line of action's
        end beyond the tangency point, or its contact under the root): undercut/interference."""
        bad = []
        a = self.pressure_angle
        for i in (0, 1):
            me, mate = self.gears[i], self.gears[1 - i]
            reach = math.sqrt((mate.virtual_radius + mate.addendum) ** 2 - mate.virtual_base_radius ** 2)
            L = (me.virtual_radius + mate.virtual_radius) * math.sin(a) - reach
            if L < 0 or math.hypot(me.virtual_base_radius, L) < me.virtual_radius - me.dedendum:
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
