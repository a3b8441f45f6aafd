"""The report's build plates: one picture per plate at the width the page shows it (not one wide
picture shrunk), and plate labels whose text boxes, measured with matplotlib's renderer in the drawn
figure, do not overlap."""

import itertools
import re

import pytest
from matplotlib.text import Text

from partgen.core.findings import Result
from partgen.export import plates as P
from partgen.export import report as R
from partgen.export.prints import plan_plates, plate_pngs
from partgen.export.report_page import plates_section, png_size

# the page's column: body max-width less its padding (1em = 16 px each side)
COLUMN_PX = int(re.search(r"max-width:(\d+)px", R.CSS).group(1)) - 2 * 16


@pytest.fixture(scope="module")
def desktop(kit_of):
    """The desktop kit (three plates on the Prusa MK4)."""
    return kit_of("butterfly_desktop")


def _margin(built):
    return built.loaded.mechanism.plate_margin(built.loaded.spec)


def test_each_plate_is_its_own_picture_at_the_size_the_page_shows(desktop):
    result = Result()
    pngs = plate_pngs(desktop.kit, _margin(desktop), result)
    assert result.figures["plates"] >= 2 and len(pngs) == result.figures["plates"]
    title, html = plates_section(pngs, result)
    imgs = re.findall(r'<img src="data:image/png;base64,([^"]+)" alt="[^"]*" width="(\d+)"', html)
    assert len(imgs) == len(pngs) == html.count("<img")
    import base64

    for b64, width in imgs:
        w, h = png_size(base64.b64decode(b64))
        shown = min(int(width), COLUMN_PX)
        assert w >= shown, (w, shown)  # never enlarged
        assert int(width) <= COLUMN_PX  # never shrunk by the column either
        assert shown >= 900  # a plate fills most of the column: legible


def _label_overlaps(fig) -> tuple[int, float, list]:
    """(labels, summed pairwise overlap of their text boxes in px², boxes outside the axes)."""
    r = fig.canvas.get_renderer()
    ax = fig.axes[0]
    boxes = [Text.get_window_extent(t, r) for t in ax.texts]
    area = 0.0
    for a, b in itertools.combinations(boxes, 2):
        w, h = min(a.x1, b.x1) - max(a.x0, b.x0), min(a.y1, b.y1) - max(a.y0, b.y0)
        area += max(w, 0) * max(h, 0)
    frame = ax.get_window_extent(r)
    out = [b for b in boxes if b.x0 < frame.x0 - 0.5 or b.x1 > frame.x1 + 0.5 or b.y0 < frame.y0 - 0.5
           or b.y1 > frame.y1 + 0.5]
    return len(boxes), area, out


@pytest.mark.parametrize("name", ["butterfly_desktop", "gear_train_planetary"])
def test_plate_labels_do_not_overlap(kit_of, name):
    """Every copy labelled once, no two label boxes overlapping, all on the axes, none below 6 pt
    (the planetary's shaft_in#1 and shaft_out#1 stand side by side on the plate)."""
    built = kit_of(name)
    margin = _margin(built)
    lay, meshes, _ = plan_plates(built.kit, margin, Result())
    fps = {n: P.footprint(m, margin) for n, m in meshes.items()}
    for i, plate in enumerate(lay.plates):
        fig = P.plate_figure(lay, i, fps, name)
        n, area, out = _label_overlaps(fig)
        assert n == len(plate), (i, n, len(plate))
        assert sorted(t.get_text() for t in fig.axes[0].texts) == sorted(P.instance_name(p) for p in plate)
        assert area == 0.0, (i, area)
        assert not out, (i, out)
        assert min(t.get_fontsize() for t in fig.axes[0].texts) >= 6.0
