"""The socket sweep takes a ring tooth's sweep as another's turned when the (θ, ψ) grid maps their
paths onto each other: the copies are found on the numbers, and the cut is the one every dome swept
on its own would make."""

import math

import numpy as np
import pytest

from partgen.design import spherical as sph
from partgen.geometry import wrist as W
from partgen.mechanisms import load_design
from partgen.mechanisms.wrist.kit import workspace_theta_max
from partgen.mechanisms.wrist.resolve import resolve_wrist


@pytest.fixture(scope="module")
def grid():
    spec = resolve_wrist(load_design("configs/wrist_sphere.yaml"))
    I, A = spec.I, spec.A
    rows = sph.tooth_rows(I, A, spec.long_pitch, (1, 4)).rows  # a small pair: the pole and a ring of 4
    end = sph.valid_end(I)
    domes = W.dome_teeth([(r.theta, r.teeth) for r in rows], lambda a: sph.pitch_radii(np.clip(a, 0, end), I, A)[0],
                         spec.dome_radius, spec.tooth_height)
    tm = workspace_theta_max(I, spec.max_bend)
    poses = np.array([[np.linalg.inv(sph.gear2_pose(t, p, I, A)) for p in 2 * np.pi * np.arange(8) / 8]
                      for t in np.linspace(0.0, tm, 3)])
    return domes, poses, spec


def test_ring_teeth_are_found_as_turned_copies(grid):
    domes, poses, _ = grid
    centres = [np.einsum("abij,j->abi", poses[:, :, :3, :3], np.array(d.centre)) + poses[:, :, :3, 3] for d in domes]
    # ring teeth 90° apart on a 45° ψ grid: dome k is dome 1 turned by (k - 1) · 90°
    assert [W._copy_of(centres[k], centres[1], 45.0) for k in (2, 3, 4)] == pytest.approx([90.0, 180.0, 270.0])
    assert W._copy_of(centres[1], centres[0], 45.0) is None  # the pole is no ring tooth's copy
    # a grid that does not step through the teeth's spacing has no copies
    off = poses[:, [0, 1, 2, 3, 4, 5, 6]]  # 7 of 8 turns: not even
    cut = [np.einsum("abij,j->abi", off[:, :, :3, :3], np.array(d.centre)) + off[:, :, :3, 3] for d in domes]
    assert W._copy_of(cut[2], cut[1], 360.0 / 7) is None


def test_the_sweep_with_copies_is_the_sweep_without(grid, monkeypatch):
    domes, poses, spec = grid
    segs = max(24, int(round(2 * math.pi * spec.dome_radius / 0.5)))
    fast, n1 = W.socket_sweep(domes, poses, spec.clearance, 31.0, segs)
    monkeypatch.setattr(W, "_copy_of", lambda *a: None)  # every dome swept on its own
    slow, n2 = W.socket_sweep(domes, poses, spec.clearance, 31.0, segs)
    assert n1 == n2 > 0
    assert fast.volume() == pytest.approx(slow.volume(), rel=1e-4)
    assert (fast - slow).volume() < 1e-3 * fast.volume() and (slow - fast).volume() < 1e-3 * fast.volume()
