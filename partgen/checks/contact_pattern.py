"""Contact along the face of a gear pair on any axes, measured exactly in 3-D: where along the face
the loaded flanks come within a small gap of each other — the marking-compound test of a gear
shop (the "contact pattern"), done on the solids.

At each phase the driven gear is first turned to where its loaded flank touches the driver (its
``ahead`` angle from ``checks.contact3d.contact_angles``), then a further ``gap_rad`` — the stated
gap along its pitch circle (``CONTACT_GAP_MM``) over that circle's radius. The exact intersection
of the two posed solids (manifold3d) is then the set of points where the flanks were within that
gap of each other; each connected piece of it, its points mapped to a coordinate along the face
(the mechanism's: the cone distance from toe to heel, a gear's axis), is one stretch of contact.
The stretches at one phase are the contact's length then; over the phases (a tooth pitch of the
driver: the mesh repeats) they make the pattern a run leaves on the teeth, reported from its first
point to its last along the face — the contact moves continuously between the sampled phases, so
the gaps the sampling leaves between them are not gaps of the pattern (the union of the sampled
stretches alone is reported too) — as a fraction of the face width, with where it sits (its middle
against the face's).

A mechanism gives ``near(theta) -> (a, Ta, b, Tb)`` as for ``checks.contact3d`` and one or more
``Face`` (a coordinate along a gear's face, mm, from the points and the poses; the face's ends in
it; the names of the two ends). Nothing here knows a mechanism.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..core.findings import Finding
from ..geometry.solid import mesh_arrays
from .contact3d import VOLUME_EPS, turned

__all__ = ["CONTACT_GAP_MM", "CENTRED_WITHIN", "REQUIRED_FRACTION", "Face", "contact_pattern", "pattern_text",
           "pattern_finding"]

CONTACT_GAP_MM = 0.02  # the flanks count as in contact where within this of each other, along the driven gear's
# pitch circle (the backlash's measure): the film a layer of marking compound leaves, a tenth of the backlash
CENTRED_WITHIN = 0.1  # the pattern is "centred" when its middle is within this fraction of the face of the middle
REQUIRED_FRACTION = 0.5  # a pattern shorter than this fraction of the face is a warning (info at or above it)


@dataclass(frozen=True)
class Face:
    """A coordinate along one gear's face: ``coord(points (n, 3) world, Ta, Tb) -> (n,)`` mm (Ta the
    driver's pose, Tb the driven gear's as turned), the face from ``lo`` to ``hi`` in it, and the
    names of those two ends (``ends``); ``what``: the face in words, for the text."""

    coord: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]
    lo: float
    hi: float
    ends: tuple[str, str]
    what: str

    @property
    def width(self) -> float:
        return self.hi - self.lo


def _merge(intervals: list[tuple[float, float]], tol: float = 1e-6) -> list[tuple[float, float]]:
    """The union of closed intervals, sorted, overlapping (or within ``tol``) ones joined."""
    out: list[list[float]] = []
    for a, b in sorted(intervals):
        if out and a <= out[-1][1] + tol:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append([a, b])
    return [(a, b) for a, b in out]


def _length(intervals) -> float:
    return float(sum(b - a for a, b in intervals))


def contact_pattern(near: Callable, thetas, ahead, overlap, gap_rad: float, faces: list[Face],
                    reach: float = np.inf) -> list[dict]:
    """Per face in ``faces``: where along it the loaded flanks are within the gap (see the module).
    ``thetas`` the driver's turns (rad) and, at each, ``ahead`` the driven gear's touching angle and
    ``overlap`` the overlap at its nominal angle (mm³; a phase that already overlaps, or whose flank
    is ``reach`` or more away, has no loaded flank and is left out); ``gap_rad``: the gap as a turn
    of the driven gear.

    Returns one dict per face: ``fraction`` (the pattern's length, first to last point in contact,
    over the face width), ``from`` and ``to`` (its ends, 0 at ``lo`` … 1 at ``hi``), ``centre`` (its
    middle, same scale), ``sits`` ("centred" or "toward <end>"), ``sampled_fraction`` and
    ``stretches`` (the union of the sampled stretches: its length, its pieces as (from, to)),
    ``instantaneous`` (min, mean and max over the phases of the contact's length at one phase, as
    fractions), ``phases`` (used) and ``face_width_mm``. With no usable phase, ``fraction`` is None."""
    thetas = np.atleast_1d(np.asarray(thetas, dtype=float))
    per_phase: list[list[list[tuple[float, float]]]] = [[] for _ in faces]
    for k, t in enumerate(thetas):
        if overlap[k] > VOLUME_EPS or ahead[k] >= reach * (1 - 1e-9):
            continue
        a, Ta, b, Tb = near(float(t))
        Tt = turned(Tb, float(ahead[k]) + gap_rad)
        common = a.transform(Ta[:3, :]) ^ b.transform(Tt[:3, :])
        pieces = [c for c in common.decompose() if c.volume() > VOLUME_EPS] if common.volume() > VOLUME_EPS else []
        points = [mesh_arrays(c)[0] for c in pieces]
        for i, face in enumerate(faces):
            spans = []
            for v in points:
                s = face.coord(np.asarray(v, dtype=float), Ta, Tt)
                lo, hi = max(float(s.min()), face.lo), min(float(s.max()), face.hi)
                if hi > lo:
                    spans.append((lo, hi))
            per_phase[i].append(_merge(spans))
    out = []
    for face, phases in zip(faces, per_phase):
        w = face.width
        if not phases:
            out.append({"fraction": None, "phases": 0, "face_width_mm": w, "what": face.what})
            continue
        union = _merge([s for p in phases for s in p])
        length = _length(union)
        inst = np.array([_length(p) / w for p in phases])
        frac = lambda x: float(round((x - face.lo) / w, 4))  # noqa: E731
        if length > 0:
            first, last = union[0][0], union[-1][1]
            c = ((first + last) / 2 - face.lo) / w
            sits = "centred" if abs(c - 0.5) <= CENTRED_WITHIN else f"toward {face.ends[0] if c < 0.5 else face.ends[1]}"
            ends, extent = (frac(first), frac(last)), (last - first) / w
        else:
            c, sits, ends, extent = None, "nowhere", (None, None), 0.0
        out.append({"fraction": float(round(extent, 4)), "from": ends[0], "to": ends[1],
                    "centre": None if c is None else float(round(c, 4)), "sits": sits,
                    "sampled_fraction": float(round(length / w, 4)), "stretches": [[frac(a), frac(b)] for a, b in union],
                    "instantaneous": {"min": float(round(inst.min(), 4)), "mean": float(round(inst.mean(), 4)),
                                      "max": float(round(inst.max(), 4))},
                    "phases": len(phases), "face_width_mm": float(round(w, 6)), "ends": list(face.ends),
                    "what": face.what})
    return out


def pattern_text(p: dict, gap_mm: float = CONTACT_GAP_MM) -> str:
    """One line: the pattern ``p`` (from ``contact_pattern``) in words."""
    if p["fraction"] is None:
        return f"contact along {p['what']}: not measured (no phase with a loaded flank clear of interference)"
    i = p["instantaneous"]
    return (f"contact along {p['what']}: {100 * p['fraction']:.0f} % of its {p['face_width_mm']:g} mm over "
            f"{p['phases']} phases ({100 * p['from']:.0f}–{100 * p['to']:.0f} % from {p['ends'][0]} to "
            f"{p['ends'][1]}), {p['sits']}; at one phase {100 * i['min']:.0f}–{100 * i['max']:.0f} % "
            f"(flanks within {gap_mm:g} mm)" if p["from"] is not None else
            f"contact along {p['what']}: none within {gap_mm:g} mm")


def pattern_finding(p: dict, parts: tuple[str, ...], key: str, required: float = REQUIRED_FRACTION,
                    hint: str = ""):
    """The pattern ``p`` as a Finding: info when it covers at least ``required`` of the face, a warning
    below (``hint``: what to do, appended)."""
    if p["fraction"] is None:
        return Finding("contact", "warn", pattern_text(p), parts, key=key, rule="contact-pattern")
    ok = p["fraction"] >= required
    message = pattern_text(p) + ("" if ok else f"; under {100 * required:.0f} % of the face" + (f": {hint}" if hint else ""))
    return Finding("contact", "info" if ok else "warn", message, parts, value=p["fraction"], unit="fraction of the face",
                   key=key, rule="contact-pattern")
