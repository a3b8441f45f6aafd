"""What play costs at a gear train's output, the part every sub-slice shares (docs/tolerance.md, "What
play costs"): the lost motion as a sum of *shares*, its worst case and the figure 95 % of prints stay
under, and the transmission-error band.

A sub-slice (``stages/play.py``, ``planetary/play.py``, ``rack/play.py``) writes its output's lost
motion (the input held, how far the output moves freely) as ``Σ_k gain_k · q_k``: each ``q_k`` one
mesh's circumferential backlash on its operating pitch circle or one bore's radial play (mm), its gain
what a millimetre of it moves the output by (arc-minutes, or mm of a rack's travel), and each ``q_k``
a linear function of the printed features' deviations — the tolerance model's features with its
distributions (``design.tolerance``: a gear's outline, a bore, a pin, a feature's position; normal,
σ = A/3 for the printer's ± A xy accuracy, A/(3√2) per coordinate of a position):

* **nominal**: every feature as designed (every share at its nominal value);
* **worst case**: every feature at ± A (3σ) in the sense that adds lost motion (a linear stack:
  ``nominal + Σ_f 3σ_f |Σ_k gain_k ∂q_k/∂δ_f|``; a share never credited below 0);
* **95 % of prints** (``p95``, and the median ``p50``): ``PRINTS`` prints drawn from those
  distributions (seed 0), each share clipped at 0, the 95th percentile of their lost motion;
* **transmission-error band**: the drive- and coast-flank transmission error measured on the printed
  outlines (every body centred in its bore) widened on each side by half the bores' share (the play
  lets the output sit anywhere between; a sub-slice whose play opens its output's two limits unevenly
  — the stages' compound gears — gives the split); for the worst-case print and the 95 % print widened further
  by half the lost motion's excess over nominal on each side (a print's extra backlash and play open
  both flanks alike).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ....design.tolerance import Margin, ModelBuilder
from .trace import ARCMIN

__all__ = ["ARCMIN", "PRINTS", "Share", "lost_motion", "te_band"]

PRINTS = 4000  # prints the 95 % figure is drawn from (its sampling error: well under 1 % of it)


@dataclass(frozen=True)
class Share:
    """One term of a lost motion: ``mm`` (a mesh's circumferential backlash or a bore's radial play,
    nominal) times ``gain`` (the output's unit per mm); ``terms``: its change per mm of each printed
    feature's deviation, keyed as ``design.tolerance.ModelBuilder.add`` takes them; ``label``: the row
    it is shown in (like shares of several planets in one), ``kind``: "backlash" or "bores"."""

    name: str
    label: str
    kind: str
    mm: float
    gain: float
    terms: dict = field(default_factory=dict)


def te_band(te_drive: np.ndarray, te_coast: np.ndarray, bores: float, extra: dict | None = None,
            sides: tuple[float, float] = (0.5, 0.5)) -> dict:
    """The transmission-error band (the output's place about its nominal, in the unit of the transmission
    errors): from the least to the most of the measured drive- and coast-flank errors (either may be the
    lower: an output turning negative lags upwards), widened by ``sides`` (low, high) of the ``bores``
    share (half each unless a sub-slice's model splits it otherwise); ``extra``: {name: lost motion
    beyond nominal} -> that band's width, widened by it."""
    both = np.concatenate([np.ravel(te_drive), np.ravel(te_coast)])
    lo = float(np.min(both)) - bores * sides[0]
    hi = float(np.max(both)) + bores * sides[1]
    out = {"low": round(lo, 4), "high": round(hi, 4), "width": round(hi - lo, 4)}
    for k, v in (extra or {}).items():
        out[f"{k}_width"] = round(hi - lo + max(v, 0.0), 4)
    return out


def lost_motion(shares: list[Share], accuracy_mm: float, unit: str, te_drive=None, te_coast=None,
                prints: int = PRINTS, seed: int = 0, sides: tuple[float, float] = (0.5, 0.5)) -> dict:
    """The lost motion of ``shares`` (in their gains' unit): nominal (``total``, its ``backlash`` and
    ``bores`` parts), ``worst_case``, ``p95`` and ``p50`` over prints at ± ``accuracy_mm``, a row per
    label; with the measured transmission errors (same unit), the band about nominal
    (``transmission_error_band_<unit>``; ``sides``: the bores' share below and above, ``te_band``)."""
    b = ModelBuilder()
    for s in shares:
        b.add(Margin(s.name, "mesh" if s.kind == "backlash" else "joint", s.kind, float(s.mm)), s.terms)
    model = b.model(accuracy_mm, "lost motion")
    gain = np.array([s.gain for s in shares], dtype=float)
    nominal_q = np.maximum(model.nominal, 0.0)
    nominal = float(nominal_q @ gain)
    # worst case: each feature at ± 3σ in the sense that adds lost motion
    worst = nominal + float(np.abs(model.coeff @ gain) @ (3.0 * model.sigma))
    rng = np.random.default_rng(seed)
    z = rng.standard_normal((prints, len(model.features)))
    q = np.maximum(model.nominal[None, :] + z @ (model.coeff * model.sigma[:, None]), 0.0)
    got = q @ gain
    p95, p50 = float(np.percentile(got, 95)), float(np.percentile(got, 50))
    lash = float(sum(max(s.mm, 0.0) * s.gain for s in shares if s.kind == "backlash"))
    bores = nominal - lash
    rows: dict[str, dict] = {}
    for s in shares:
        r = rows.setdefault(s.label, {"share": s.label, "kind": s.kind, "count": 0, "mm": round(s.mm, 6), "at_output": 0.0})
        r["count"] += 1
        r["at_output"] += max(s.mm, 0.0) * s.gain
    for r in rows.values():
        r["at_output"] = round(r["at_output"], 4)
    out = {"total": round(nominal, 4), "backlash": round(lash, 4), "bores": round(bores, 4),
           "worst_case": round(worst, 4), "p95": round(p95, 4), "p50": round(p50, 4), "prints": prints,
           "accuracy_mm": float(accuracy_mm), "shares": list(rows.values())}
    if te_drive is not None and te_coast is not None:
        out[f"transmission_error_band_{unit}"] = te_band(te_drive, te_coast, bores,
                                                 {"worst_case": worst - nominal, "p95": p95 - nominal}, sides)
    return out
