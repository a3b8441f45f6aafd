"""A printer's measured biases in the tolerance study: the mean deviation each printed feature is
drawn around (``design.tolerance.with_means``).

A feature of kind hole, pin, tooth or outline on a part prints off by its kind's bias (hole, pin,
outline, outline) unless ``build`` compensates that part for it (``export.kit.compensated``): then
its model already carries the opposite offset and the mean is 0. Positions and heights have no
measured bias (0)."""

from __future__ import annotations

import numpy as np

from ..design.tolerance import MarginModel, with_means
from .kit import compensated

__all__ = ["feature_means", "biased_model"]


def feature_means(model: MarginModel, kit) -> np.ndarray:
    """(F,) mm: each feature's mean deviation on this printer, as printed from this kit."""
    pr = kit.printer
    by_kind = {"hole": pr.hole_bias, "pin": pr.pin_bias, "tooth": pr.outline_bias, "outline": pr.outline_bias}
    if not any(by_kind.values()):
        return np.zeros(len(model.features))
    parts = {p.name: p for p in kit.parts}
    out = np.zeros(len(model.features))
    for i, f in enumerate(model.features):
        b = by_kind.get(f.kind, 0.0)
        part = parts.get(f.part)
        if b and not (part is not None and part.printed and compensated(part, pr)[1]):
            out[i] = b
    return out


def biased_model(model: MarginModel, kit) -> MarginModel:
    """``model`` with the printer's residual biases (what ``build`` did not compensate) as means."""
    mean = feature_means(model, kit)
    return with_means(model, mean, "biases as means: " + ", ".join(
        f"{f.name} {m:+.3f} mm" for f, m in zip(model.features, mean) if m)[:500])
