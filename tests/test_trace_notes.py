"""The chain's trace figure: its notes (the largest deviation, which way is up) do not cover its
legend, measured on the drawn figure's text boxes (matplotlib's renderer)."""

from pathlib import Path

import matplotlib.pyplot as plt
import pytest
from matplotlib.text import Text

from partgen import pipeline
from partgen.mechanisms.gear_chain.trace_plots import trace_fig

ROOT = Path(__file__).parent.parent


def _overlap(a, b) -> float:
    w, h = min(a.x1, b.x1) - max(a.x0, b.x0), min(a.y1, b.y1) - max(a.y0, b.y0)
    return max(w, 0.0) * max(h, 0.0)


@pytest.mark.parametrize("name", ["star"])
def test_trace_notes_clear_of_the_legend(name):
    loaded = pipeline.load(ROOT / "configs" / f"{name}.yaml")
    tr = loaded.mechanism.trace(loaded.spec, None, 720, None)  # stats only
    head = {k: v for k, v in tr.stats.items() if k.endswith("_mm")}
    head["worst_theta_rad"] = tr.stats["worst_theta_rad"]
    fig = trace_fig(loaded.spec.mechanism, head, name)
    try:
        r = fig.canvas.get_renderer()
        ax = fig.axes[0]
        legend = ax.get_legend().get_window_extent(r)
        notes = [Text.get_window_extent(t, r) for t in ax.texts]  # annotations are the axes' texts
        assert any("largest deviation" in t.get_text() for t in ax.texts)
        assert len(notes) == 2
        for b in notes:
            assert _overlap(b, legend) == 0.0, (b, legend)
            assert fig.bbox.x0 <= b.x0 and b.x1 <= fig.bbox.x1 and fig.bbox.y0 <= b.y0 and b.y1 <= fig.bbox.y1
        assert _overlap(notes[0], notes[1]) == 0.0
    finally:
        plt.close(fig)
