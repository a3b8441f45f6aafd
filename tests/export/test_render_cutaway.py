"""The report's assembly picture: a depth buffer shows no gear teeth through a closed housing's top
(the painter's order did), and the top that hides the gears is drawn see-through and named in the
caption (decided by what hides what in the picture, not by part names). On the reducer kit."""

import io

import numpy as np
import pytest
from matplotlib.image import imread

from partgen.export.bill import bill_sections
from partgen.export.prints import printed_groups
from partgen.export.render import render_cutaway

VIEW = dict(size_px=(1100, 720), elev=35, azim=-70)


@pytest.fixture(scope="module")
def reducer(kit_of):
    built = kit_of("gear_train_reducer")
    kit = built.kit
    poses = kit.poses(0.0)
    scene = []
    for g in printed_groups(kit):
        for it in g:
            T = poses[it.part.name] @ it.local_from_print
            scene.append((it.part.name, it.part.role, g[0].mesh.vertices @ T[:3, :3].T + T[:3, 3], g[0].mesh.faces))
    return built, scene


def _pixels(png: bytes) -> np.ndarray:
    return imread(io.BytesIO(png))[:, :, :3]


def test_no_teeth_through_the_cover(reducer):
    """Cover alone in red, everything with the gears in blue: inside the cover's picture no blue pixel."""
    _, scene = reducer
    top = [s for s in scene if s[0] == "frame_top"]
    assert top
    # the cover's own picture, framed like the whole
    every = np.concatenate([v for _, _, v, _ in scene])
    alone, _ = render_cutaway([(v, f, "#ff0000") for n, _, v, f in scene if n == "frame_top"],
                              cutaway=False, frame=every, **VIEW)
    paint = lambda n, role: "#ff0000" if n == "frame_top" else "#0000ff" if n.startswith("gear") else "#00ff00"  # noqa: E731
    full, _ = render_cutaway([(v, f, paint(n, r)) for n, r, v, f in scene], cutaway=False, frame=every, **VIEW)
    cover, img = _pixels(alone), _pixels(full)
    assert cover.shape == img.shape
    in_cover = (cover[:, :, 0] > 0.2) & (cover[:, :, 1] < 0.05) & (cover[:, :, 2] < 0.05)  # the top's silhouette
    blue = (img[:, :, 2] > 0.1) & (img[:, :, 0] < 0.05) & (img[:, :, 1] < 0.05)  # the gears (shafts poke through)
    assert in_cover.sum() > 10_000
    assert blue.sum() > 500  # the gears show at the housing's open sides
    assert (blue & in_cover).sum() == 0  # nothing under the top shows through it


def test_the_cover_is_drawn_see_through_and_said(reducer):
    built, scene = reducer
    png, see = render_cutaway([(v, f, "#ff0000" if n == "frame_top" else "#0000ff") for n, _, v, f in scene], **VIEW)
    assert [scene[i][0] for i in see] == ["frame_top"]
    img = _pixels(png)
    blended = (img[:, :, 0] > 0.1) & (img[:, :, 2] > 0.1) & (img[:, :, 1] > 0.3)  # red over blue over white
    mix = (img[:, :, 0] > 0.05) & (img[:, :, 2] > 0.05) & (np.abs(img[:, :, 0] - img[:, :, 2]) < 0.9)
    assert mix.sum() > 10_000 or blended.sum() > 10_000
    mech = built.loaded.mechanism
    sections = dict(bill_sections(built.kit, mech.role_colours, [], printed_groups(built.kit)))
    assert "Cut-away: frame_top drawn see-through" in sections["Bill of parts"]
