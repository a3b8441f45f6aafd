"""Involute spur-gear geometry and the exact outline a rack cutter generates (pure math).

Units: millimetres and radians everywhere.  Only numpy and the standard library.

Generation model (the one ``gear_outline`` implements exactly)
---------------------------------------------------------------
The basic rack (ISO 53 style) has straight flanks at the pressure angle ``alpha``, a flat
tip ``hf*m`` below its reference line and tip fillets of radius ``rho*m`` tangent to flank
and tip line.  Rack coordinates are ``(u, w)``: ``u`` along the pitch line, ``w`` the
distance outward from the gear's reference pitch circle ``r_p = m*z/2`` (the rolling
line).  The rack's reference line sits at ``w = x*m`` (profile shift) and the cutter tooth
is ``thinning`` wider than nominal (tangential shift of ``thinning/2`` per side), so the
gear's flanks stay true involutes while its tooth gets ``thinning`` thinner at ``r_p``.
Seen from the gear, a rack point ``(u, w)`` in contact at instantaneous centre
``(u_I, 0)`` lies at ``R(u_I / r_p) @ (r_p + w, u - u_I)``.  A cutter point with outward
normal angle ``theta`` is in contact when its normal passes through the pitch point, i.e.
``u_I = u - w*cot(theta)``; for the fillet arc (``alpha - pi <= theta <= -pi/2``) this gives
the root trochoid (the envelope of the fillet circle) directly as a function of ``theta``.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass

import numpy as np

__all__ = [
    "GearOutline",
    "max_tip_fillet_coeff",
    "inv",
    "reference_tooth_thickness",
    "tip_diameter",
    "root_diameter",
    "base_diameter",
    "tooth_thickness_at",
    "undercut_limit",
    "min_profile_shift",
    "auto_profile_shift",
    "repeat_tooth",
    "is_undercut",
    "working_pressure_angle",
    "inv_inverse",
    "centre_distance",
    "contact_ratio",
    "circumferential_backlash",
    "gear_outline",
]


class OutlineError(ValueError):
    """The rack cannot generate this outline; ``field`` names the ``ToothSystem`` field to change
    ("cutter_tip_coeff", "addendum_coeff", "profile_shift")."""

    def __init__(self, problem: str, field: str):
        super().__init__(problem)
        self.field = field

_MAX_CHORD = 0.5  # mm, longest chord of any sampled curve
_DENSE = 1024  # dense evaluations per curve piece for the adaptive sampler
_SAFETY = 0.9  # sampler aims at this fraction of the chord tolerance
_DUP = 1e-9  # mm, consecutive points closer than this are merged


# ----------------------------------------------------------------------------- validation
def _int_teeth(z, name="z"):
    try:
        zi = operator.index(z)
    except TypeError:
        raise ValueError(f"{name} must be an integer tooth count, got {z!r}") from None
    if isinstance(z, bool) or zi < 4:
        raise ValueError(f"{name} must be an integer >= 4, got {z!r}")
    return int(zi)


def _finite(v, name):
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {v!r}") from None
    if not math.isfinite(f):
        raise ValueError(f"{name} must be finite, got {v!r}")
    return f


def _positive(v, name):
    f = _finite(v, name)
    if f <= 0.0:
        raise ValueError(f"{name} must be > 0, got {v!r}")
    return f


def _pressure_angle(alpha, name="alpha"):
    a = _finite(alpha, name)
    if not 0.0 < a < math.pi / 4:
        raise ValueError(f"{name} (pressure angle) must lie in (0, 45 deg) in radians, got {alpha!r}")
    return a


# ----------------------------------------------------------------------------- basic relations
def inv(a):
    """Involute function ``tan(a) - a``.

    a : float or array, rad.  Returns the same shape (float for a scalar).
    """
    arr = np.asarray(a, dtype=float)
    out = np.tan(arr) - arr
    return float(out) if out.ndim == 0 else out


def _inv_at_radius(r, rb):
    """inv(arccos(rb/r)) computed as t - atan(t), t = sqrt(r^2 - rb^2)/rb (accurate near rb)."""
    r = np.asarray(r, dtype=float)
    t = np.sqrt(np.maximum((r - rb) * (r + rb), 0.0)) / rb
    return t - np.arctan(t)


def reference_tooth_thickness(z, m, alpha, x=0.0, thinning=0.0) -> float:
    """Arc tooth thickness at the reference pitch circle ``r_p = m*z/2``, mm.

    ``m*(pi/2 + 2*x*tan(alpha)) - thinning``; ``thinning`` (mm) is this gear's backlash allowance.
    """
    _int_teeth(z)
    m = _positive(m, "m")
    alpha = _pressure_angle(alpha)
    x = _finite(x, "x")
    thinning = _finite(thinning, "thinning")
    return m * (math.pi / 2 + 2.0 * x * math.tan(alpha)) - thinning


def tip_diameter(z, m, x=0.0, ha=1.0) -> float:
    """Tip (outside) diameter ``m*(z + 2*ha + 2*x)``, mm."""
    z = _int_teeth(z)
    m = _positive(m, "m")
    d = m * (z + 2.0 * _positive(ha, "ha") + 2.0 * _finite(x, "x"))
    if d <= 0.0:
        raise ValueError(f"x = {x!r} gives a non-positive tip diameter")
    return d


def root_diameter(z, m, x=0.0, hf=1.25) -> float:
    """Root diameter ``m*(z - 2*hf + 2*x)``, mm (the generating rack's tip line)."""
    z = _int_teeth(z)
    m = _positive(m, "m")
    d = m * (z - 2.0 * _positive(hf, "hf") + 2.0 * _finite(x, "x"))
    if d <= 0.0:
        raise ValueError(f"hf = {hf!r} (with x = {x!r}) gives a non-positive root diameter")
    return d


def base_diameter(z, m, alpha) -> float:
    """Base circle diameter ``m*z*cos(alpha)``, mm."""
    return _int_teeth(z) * _positive(m, "m") * math.cos(_pressure_angle(alpha))


def tooth_thickness_at(r, z, m, alpha, x=0.0, thinning=0.0) -> float:
    """Arc thickness of the involute tooth at radius ``r`` (mm, ``r >= base radius``), mm.

    ``2*r*(s/(2*r_p) + inv(alpha) - inv(arccos(r_b/r)))`` with ``s = reference_tooth_thickness``.
    Negative means the flanks have already crossed (pointed tooth).  ``r`` may be an array.
    """
    s = reference_tooth_thickness(z, m, alpha, x, thinning)
    rp = m * z / 2.0
    rb = rp * math.cos(alpha)
    rr = np.asarray(r, dtype=float)
    if not np.all(np.isfinite(rr)) or np.any(rr < rb * (1.0 - 1e-12)):
        raise ValueError(f"r must be >= the base radius {rb!r} mm, got {r!r}")
    out = 2.0 * rr * (s / (2.0 * rp) + inv(alpha) - _inv_at_radius(rr, rb))
    return float(out) if out.ndim == 0 else out


def undercut_limit(alpha, ha=1.0) -> float:
    """Smallest tooth count (real number) cut without undercut at ``x = 0``: ``2*ha/sin(alpha)**2``."""
    alpha = _pressure_angle(alpha)
    return 2.0 * _positive(ha, "ha") / math.sin(alpha) ** 2


def min_profile_shift(z, alpha, ha=1.0) -> float:
    """Smallest profile shift coefficient without generation undercut: ``ha - z*sin(alpha)**2/2``."""
    z = _int_teeth(z)
    alpha = _pressure_angle(alpha)
    return _positive(ha, "ha") - z * math.sin(alpha) ** 2 / 2.0


def auto_profile_shift(z, alpha, ha=1.0) -> float:
    """Automatic profile shift coefficient, like BOSL2's ``profile_shift="auto"``.

    0 when ``z >= undercut_limit(alpha, ha)``; otherwise the smallest shift that avoids
    undercut, ``min_profile_shift(z, alpha, ha)``.  That is ``max(0, ha - z*sin(alpha)**2/2)``.
    The rule assumes the rack's straight flank ends ``ha*m`` below its reference line; with
    the ISO 53 profile (hf 1.25, rho 0.38, 20 deg) it actually ends 0.99997*m below it.
    """
    return max(0.0, min_profile_shift(z, alpha, ha))


def is_undercut(z, alpha, x=0.0, ha=1.0) -> bool:
    """True when generation undercuts the flank: ``x < min_profile_shift(z, alpha, ha)`` (1e-12 slack)."""
    return bool(_finite(x, "x") < min_profile_shift(z, alpha, ha) - 1e-12)


def repeat_tooth(tooth: np.ndarray, z: int) -> np.ndarray:
    """A whole gear's outline from one tooth: ``tooth`` (n, 2) mm, counter-clockwise from -π/z to
    π/z, turned to each of the ``z`` teeth; points closer than ``_DUP`` to the one before (and a last
    point on the first) merged. Returns (m, 2) mm."""
    rot = 2.0 * math.pi * np.arange(z) / z
    cr, sr = np.cos(rot)[:, None], np.sin(rot)[:, None]
    pts = np.stack([cr * tooth[:, 0] - sr * tooth[:, 1], sr * tooth[:, 0] + cr * tooth[:, 1]], axis=-1)
    pts = pts.reshape(-1, 2)
    keep = np.ones(len(pts), dtype=bool)
    keep[1:] = np.hypot(*np.diff(pts, axis=0).T) >= _DUP
    pts = pts[keep]
    if np.hypot(*(pts[-1] - pts[0])) < _DUP:
        pts = pts[:-1]
    return pts


# ----------------------------------------------------------------------------- pair relations
def working_pressure_angle(z1, z2, alpha, x1, x2) -> float:
    """Operating pressure angle ``a_w`` of a zero-backlash-geometry mesh, rad.

    Solves ``inv(a_w) = inv(alpha) + 2*tan(alpha)*(x1 + x2)/(z1 + z2)`` by Newton's method.
    """
    z1, z2 = _int_teeth(z1, "z1"), _int_teeth(z2, "z2")
    alpha = _pressure_angle(alpha)
    xs = _finite(x1, "x1") + _finite(x2, "x2")
    if xs == 0.0:
        return alpha
    y = math.tan(alpha) - alpha + 2.0 * math.tan(alpha) * xs / (z1 + z2)
    if y <= 0.0:
        raise ValueError(f"x1 + x2 = {xs!r} is too negative: no working pressure angle exists")
    if y > math.tan(1.5) - 1.5:
        raise ValueError(f"x1 + x2 = {xs!r} is too large: working pressure angle above 86 deg")
    return inv_inverse(y)


def inv_inverse(y: float) -> float:
    """The angle a (rad) with ``inv(a) = tan(a) - a = y`` for 0 < y ≤ inv(1.5), by Newton's method
    (``inv(a) >= a**3/3``, so it starts right of the root and converges monotonically).

    At most 100 steps, stopping at a step under 1e-16 a. Most roots never take so small a step: the
    last ulps cycle through a few values. An iterate seen before repeats its successors, so the
    100th step is read off the cycle instead of iterated to (the same number, a quarter the time)."""
    a = min((3.0 * y) ** (1.0 / 3.0), 1.5)
    seen: dict[float, int] = {}  # each iterate -> the step that made it
    after: list[float] = []  # the iterate after each step
    for n in range(100):
        ta = math.tan(a)
        step = (ta - a - y) / (ta * ta)
        a -= step
        if abs(step) <= 1e-16 * a:
            break
        k = seen.get(a)
        if k is not None:  # steps k … n − 1 repeat for ever: step 99 lands where the cycle puts it
            return after[k + (99 - k) % (n - k)]
        seen[a] = n
        after.append(a)
    return a


def centre_distance(z1, z2, m, alpha, x1=0.0, x2=0.0) -> float:
    """Operating centre distance of the unthinned pair meshing without backlash, mm.

    ``m*(z1 + z2)/2 * cos(alpha)/cos(a_w)`` with ``a_w = working_pressure_angle(...)``.
    """
    aw = working_pressure_angle(z1, z2, alpha, x1, x2)
    return _positive(m, "m") * (z1 + z2) / 2.0 * math.cos(alpha) / math.cos(aw)


def _operating_angle(z1, z2, m, alpha, a):
    z1, z2 = _int_teeth(z1, "z1"), _int_teeth(z2, "z2")
    m = _positive(m, "m")
    alpha = _pressure_angle(alpha)
    a = _positive(a, "a")
    rb_sum = m * (z1 + z2) / 2.0 * math.cos(alpha)
    if a <= rb_sum:
        raise ValueError(f"a = {a!r} mm must exceed the sum of base radii {rb_sum!r} mm")
    return z1, z2, m, alpha, a, math.acos(rb_sum / a)


def contact_ratio(z1, z2, m, alpha, x1, x2, a, ha=1.0) -> float:
    """Transverse contact ratio of the pair at centre distance ``a`` (mm).

    ``(sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a*sin(a_a)) / (pi*m*cos(alpha))`` with tip
    radii ``m*(z/2 + ha + x)``, base radii ``m*z*cos(alpha)/2``, ``cos(a_a) = (rb1 + rb2)/a``.
    No tip shortening; the fillets are assumed not to interfere.
    """
    z1, z2, m, alpha, a, aa = _operating_angle(z1, z2, m, alpha, a)
    ha = _positive(ha, "ha")
    total = -a * math.sin(aa)
    for z, x, name in ((z1, x1, "x1"), (z2, x2, "x2")):
        ra = m * (z / 2.0 + ha + _finite(x, name))
        rb = m * z / 2.0 * math.cos(alpha)
        if ra <= rb:
            raise ValueError(f"{name} = {x!r}: tip radius {ra!r} mm not above base radius {rb!r} mm")
        total += math.sqrt((ra - rb) * (ra + rb))
    return total / (math.pi * m * math.cos(alpha))


def circumferential_backlash(z1, z2, m, alpha, x1, x2, thinning1, thinning2, a) -> float:
    """Circumferential backlash on the operating pitch circle when the pair runs at ``a``, mm.

    ``j = p_w - s_w1 - s_w2`` with operating pitch radii ``r_wi = a*z_i/(z1 + z2)``, pitch
    ``p_w = 2*pi*a/(z1 + z2)`` and thicknesses ``s_wi = 2*r_wi*(s_i/(2*r_i) + inv(alpha) -
    inv(a_a))``, ``cos(a_a) = (rb1 + rb2)/a``.  At ``a = centre_distance(...)`` this is
    ``(thinning1 + thinning2) * a/(m*(z1 + z2)/2)`` (= thinning_i * r_wi/r_i summed); it
    grows by about ``2*tan(a_a)*da`` with the centre distance.  Negative means interference.
    """
    z1, z2, m, alpha, a, aa = _operating_angle(z1, z2, m, alpha, a)
    j = 2.0 * math.pi * a / (z1 + z2)
    for z, x, th in ((z1, x1, thinning1), (z2, x2, thinning2)):
        s = reference_tooth_thickness(z, m, alpha, x, th)
        r, rw = m * z / 2.0, a * z / (z1 + z2)
        j -= 2.0 * rw * (s / (2.0 * r) + inv(alpha) - inv(aa))
    return j


# ----------------------------------------------------------------------------- outline
@dataclass(frozen=True, eq=False)
class GearOutline:
    """A generated spur-gear outline.

    points : (n, 2) float, mm; closed (first point not repeated), counter-clockwise, centred
        at the origin, tooth 0 centred on the +x axis.  Read-only.
    undercut : the root trochoid cuts into the involute flank.
    form_radius : mm, radius where the true involute flank starts (fillet join or undercut crossing).
    z, m, alpha, x, thinning, ha, hf, rho, tol : the parameters used (mm, rad).
    pitch_radius, base_radius, tip_radius, root_radius : mm.
    """

    points: np.ndarray
    undercut: bool
    form_radius: float
    z: int
    m: float
    alpha: float
    x: float
    thinning: float
    ha: float
    hf: float
    rho: float
    tol: float
    pitch_radius: float
    base_radius: float
    tip_radius: float
    root_radius: float


def max_tip_fillet_coeff(alpha: float, hf: float, thinning_over_m: float = 0.0) -> float:
    """The largest tip fillet radius (x module) a basic rack of pressure angle ``alpha`` (rad) and
    dedendum ``hf`` (x module) can have before the fillets of one cutter tooth overlap, with the
    tooth thinned by ``thinning_over_m`` (arc at the pitch line / module; see ``_cutter``):
    rho <= (pi/4 + t/2m - hf tan a) / (1/cos a - tan a)."""
    ta = math.tan(alpha)
    return (math.pi / 4.0 + thinning_over_m / 2.0 - hf * ta) / (1.0 / math.cos(alpha) - ta)


def _cutter(z, m, alpha, x, thinning, hf, rho):
    """Left tip-fillet of the generating rack tooth that cuts the space above tooth 0.

    Returns ``(rp, w_c, u_c, rf, c)``: pitch radius, fillet centre ``(u_c, w_c)`` in rack
    coordinates (mm), fillet radius ``rf = rho*m`` and the rack tooth's centre line ``u = c``.
    """
    rp = m * z / 2.0
    rf = rho * m
    w_c = (x - hf + rho) * m
    # left cutter flank: u = m*pi/4 - thinning/2 - (w - x*m)*tan(alpha); centre is rf inside it
    u_c = m * math.pi / 4.0 - thinning / 2.0 + (hf - rho) * m * math.tan(alpha) + rf / math.cos(alpha)
    return rp, w_c, u_c, rf, m * math.pi / 2.0


def _fillet_points(theta, rp, w_c, u_c, rf):
    """Envelope (root trochoid) of the cutter's tip fillet.

    theta : (k,) float, rad, outward normal angle of the fillet arc, in [alpha - pi, -pi/2].
    Returns (k, 2) float, mm, gear-frame points of the upper side of the space after tooth 0.
    """
    ct, st = np.cos(theta), np.sin(theta)
    w = w_c + rf * st
    wcot = w * ct / st  # u - u_I at contact
    g = (u_c + rf * ct - wcot) / rp  # rotation of the gear frame at contact
    cg, sg = np.cos(g), np.sin(g)
    X = rp + w
    return np.stack([cg * X - sg * wcot, sg * X + cg * wcot], axis=-1)


def _flank_points(t, rb, psi_b):
    """Upper involute flank of tooth 0 at roll angles ``t`` (k,) rad -> (k, 2) mm."""
    r = rb * np.sqrt(1.0 + t * t)
    ang = psi_b - (t - np.arctan(t))
    return np.stack([r * np.cos(ang), r * np.sin(ang)], axis=-1)


def _adaptive(param, pts, tol):
    """Parameters of a sampling whose chords keep sagitta <= tol and length <= _MAX_CHORD.

    param : (k,) dense parameter grid; pts : (k, 2) the curve there.  Uses the discrete
    turning angle: a chord of length L turning by dtheta has sagitta ~ L*dtheta/8.
    """
    d = np.diff(pts, axis=0)
    seg = np.hypot(d[:, 0], d[:, 1])
    head = np.arctan2(d[:, 1], d[:, 0])
    turn = np.abs((np.diff(head) + np.pi) % (2.0 * np.pi) - np.pi)
    tv = np.concatenate([turn[:1], turn, turn[-1:]]) if turn.size else np.zeros(2)
    tseg = 0.5 * (tv[:-1] + tv[1:])
    dens = np.maximum(seg / _MAX_CHORD, np.sqrt(seg * tseg / (8.0 * tol * _SAFETY)))
    cum = np.concatenate([[0.0], np.cumsum(dens)])
    n = max(int(math.ceil(cum[-1])), 2)
    if cum[-1] <= 0.0:
        return np.linspace(param[0], param[-1], n + 1)
    out = np.interp(np.linspace(0.0, cum[-1], n + 1), cum, param)
    out[0], out[-1] = param[0], param[-1]
    return out


def _arc_steps(radius, span, tol):
    """Number of chords for an arc of ``radius`` (mm) spanning ``span`` (rad)."""
    dphi = 2.0 * math.acos(max(1.0 - tol * _SAFETY / radius, -1.0))
    dphi = min(dphi, 2.0 * math.asin(min(_MAX_CHORD / (2.0 * radius), 1.0)))
    return max(1, int(math.ceil(span / dphi - 1e-9)))


def _crossing(th0, th1, rp, w_c, u_c, rf, rb, psi_b):
    """Fillet parameter where the trochoid enters the involute flank (undercut), or None."""
    th = np.linspace(th0, th1, _DENSE + 1)

    def f(theta):
        p = _fillet_points(np.asarray(theta, dtype=float), rp, w_c, u_c, rf)
        r = np.hypot(p[..., 0], p[..., 1])
        val = np.arctan2(p[..., 1], p[..., 0]) - (psi_b - _inv_at_radius(r, rb))
        return np.where(r >= rb, val, np.nan)

    fv = f(th)
    if not fv[0] > 0.0:
        return th0
    pos = fv > 0.0  # NaN (below the base circle) counts as crossed
    change = np.nonzero(pos[:-1] & ~pos[1:])[0]
    if change.size == 0:
        return None
    lo, hi = th[change[0]], th[change[0] + 1]
    for _ in range(200):  # bisection to the last bit
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if f(mid) > 0.0:
            lo = mid
        else:
            hi = mid
    return hi


def gear_outline(z, m, alpha, x=0.0, thinning=0.0, ha=1.0, hf=1.25, rho=0.38, tol=0.001) -> GearOutline:
    """Exact outline of an external involute spur gear generated by a rack cutter.

    z : teeth (int >= 4); m : module, mm; alpha : pressure angle, rad in (0, pi/4);
    x : profile shift coefficient; thinning : reduction of the arc thickness at the reference
    pitch circle, mm (tangential rack shift); ha, hf : addendum / dedendum coefficients;
    rho : cutter tip radius / m; tol : chord sagitta tolerance, mm.
    Flanks are sampled involutes (a vertex at the reference pitch circle), the tip is an arc
    of the tip circle, the root is the cutter's tip-fillet trochoid plus the root-circle arc
    its flat tip leaves; with undercut the trochoid is cut exactly where it meets the involute.
    Returns a GearOutline whose ``points`` are (n, 2) float, mm, counter-clockwise.
    """
    z = _int_teeth(z)
    m = _positive(m, "m")
    alpha = _pressure_angle(alpha)
    x = _finite(x, "x")
    thinning = _finite(thinning, "thinning")
    ha = _positive(ha, "ha")
    hf = _positive(hf, "hf")
    rho = _finite(rho, "rho")
    if rho < 0.0:
        raise OutlineError(f"rho must be >= 0, got {rho!r}", "cutter_tip_coeff")
    tol = _positive(tol, "tol")

    rp, w_c, u_c, rf, c = _cutter(z, m, alpha, x, thinning, hf, rho)
    rb = rp * math.cos(alpha)
    ra = tip_diameter(z, m, x, ha) / 2.0
    rr = root_diameter(z, m, x, hf) / 2.0
    if c - u_c < -1e-12 * m:
        raise OutlineError(
            f"rho = {rho!r} is too large for hf = {hf!r}, alpha and thinning = {thinning!r}: "
            f"the cutter's tip fillets overlap (at most {max_tip_fillet_coeff(alpha, hf, thinning / m):.4f})",
            "cutter_tip_coeff")
    u_c = min(u_c, c)
    s = reference_tooth_thickness(z, m, alpha, x, thinning)
    psi_b = s / (2.0 * rp) + inv(alpha)  # half angle of the tooth at the base circle
    if ra <= rb:
        raise OutlineError(f"ha = {ha!r} with x = {x!r}: tip radius {ra!r} mm is not above the base radius",
                           "addendum_coeff")
    psi_a = psi_b - float(_inv_at_radius(ra, rb))
    if psi_a <= 0.0:
        raise OutlineError(
            f"pointed tooth: tip thickness {2 * ra * psi_a:.6g} mm <= 0 "
            f"(reduce ha = {ha!r}, x = {x!r} or thinning = {thinning!r})", "profile_shift")

    sa = math.sin(alpha)
    w_t = w_c - rf * sa  # where the cutter's straight flank meets its fillet
    q = rp * sa + w_t / sa  # signed distance of that contact from the base tangent point
    th0, th1 = alpha - math.pi, -math.pi / 2.0
    undercut = q < 0.0
    if undercut:
        ths = _crossing(th0, th1, rp, w_c, u_c, rf, rb, psi_b)
        if ths is None:
            raise ValueError(f"z = {z}, x = {x!r}: the undercut trochoid does not meet the involute flank")
        p_form = _fillet_points(np.array([ths]), rp, w_c, u_c, rf)[0]
        form = float(np.hypot(p_form[0], p_form[1]))
        t_form = math.sqrt(max((form - rb) * (form + rb), 0.0)) / rb
    else:
        ths = th0
        t_form = q / rb
        form = rb * math.sqrt(1.0 + t_form * t_form)
        p_form = None
    if form >= ra:
        raise ValueError(
            f"no involute flank: form radius {form:.6g} mm >= tip radius {ra:.6g} mm (ha = {ha!r}, z = {z})")

    # flank, from the form radius up to the tip, with vertices on the pitch and tip circles
    t_a = math.sqrt((ra - rb) * (ra + rb)) / rb
    t_p = math.tan(alpha)
    knots = [t_form, t_p, t_a] if t_form + 1e-9 < t_p < t_a - 1e-9 else [t_form, t_a]
    ts = []
    for k0, k1 in zip(knots[:-1], knots[1:]):
        dense = np.linspace(k0, k1, _DENSE // 2 + 1)
        ts.append(_adaptive(dense, _flank_points(dense, rb, psi_b), tol)[:-1])
    ts = np.concatenate(ts + [[t_a]])
    if ts.size < 5:
        ts = np.linspace(t_form, t_a, 5)
    flank = _flank_points(ts, rb, psi_b)
    flank[-1] = (ra * math.cos(psi_a), ra * math.sin(psi_a))
    if len(knots) == 3:
        i = int(np.argmin(np.abs(ts - t_p)))
        flank[i] = (rp * math.cos(s / (2 * rp)), rp * math.sin(s / (2 * rp)))
    if p_form is not None:
        flank[0] = p_form

    # root trochoid from the form point down to the root circle, then the root-circle arc
    dense = np.linspace(ths, th1, _DENSE + 1)
    troch = _fillet_points(_adaptive(dense, _fillet_points(dense, rp, w_c, u_c, rf), tol), rp, w_c, u_c, rf)
    g_end = math.atan2(troch[-1, 1], troch[-1, 0])
    span = math.pi / z - g_end
    if span > 1e-12:
        ang = np.linspace(g_end, math.pi / z, _arc_steps(rr, span, tol) + 1)
        root = np.stack([rr * np.cos(ang), rr * np.sin(ang)], axis=-1)
    else:
        root = np.empty((0, 2))

    upper = np.concatenate([flank[::-1], troch, root])
    lower = upper[::-1] * np.array([1.0, -1.0])
    ang = np.linspace(-psi_a, psi_a, _arc_steps(ra, 2.0 * psi_a, tol) + 1)
    tip = np.stack([ra * np.cos(ang), ra * np.sin(ang)], axis=-1)
    tooth = np.concatenate([lower, tip, upper])

    pts = np.ascontiguousarray(repeat_tooth(tooth, z))
    pts.setflags(write=False)
    return GearOutline(
        points=pts, undercut=bool(undercut), form_radius=float(form), z=z, m=m, alpha=alpha, x=x,
        thinning=thinning, ha=ha, hf=hf, rho=rho, tol=tol, pitch_radius=rp, base_radius=rb,
        tip_radius=ra, root_radius=rr)
