"""A drawn curve → the fewest links within a deviation budget (partgen.design.drawing): the fit,
the two parametrisations, the measured Hausdorff distance and the rescue when nothing fits."""

import numpy as np
import pytest

from partgen.design import drawing as D
from partgen.design.synthesis import Chain, chain_order, trace


def heart(n=400, scale=5.0):
    """x = 16 sin³t, y = 13 cos t − 5 cos 2t − 2 cos 3t − cos 4t, uniform in t, mm."""
    t = 2 * np.pi * np.arange(n) / n
    return scale * (16 * np.sin(t) ** 3 + 1j * (13 * np.cos(t) - 5 * np.cos(2 * t) - 2 * np.cos(3 * t) - np.cos(4 * t)))


def lissajous(n=600, size=50.0):
    t = 2 * np.pi * np.arange(n) / n
    return size * (np.sin(3 * t) + 1j * np.sin(2 * t))


def drawing(z, param):
    fc, off, links, theta = D.fit(z, param)
    return off, links, D.Drawing(z, theta, param)


def brute_hausdorff(p, q, per=40):
    """Independent check: both closed polylines densified (per points per segment), point sets."""
    def dense(z):
        a, b = z, np.roll(z, -1)
        s = np.linspace(0, 1, per, endpoint=False)
        return (a[:, None] + s[None, :] * (b - a)[:, None]).ravel()
    P, Q = dense(p), dense(q)
    pq, qp = 0.0, np.full(len(Q), np.inf)
    for i in range(0, len(P), 500):
        d = np.abs(P[i:i + 500, None] - Q[None, :])
        pq = max(pq, d.min(axis=1).max())
        qp = np.minimum(qp, d.min(axis=0))
    return max(pq, qp.max())


def test_heart_is_eight_links_and_its_chain_lies_on_it():
    # 16 sin³t = 12 sin t − 4 sin 3t, so P = x + iy has harmonics ±1..±4: C_k = ((a+d) + i(c−b))/2,
    # C_−k = ((a−d) + i(c+b))/2 give, in heart units, M1 12.5, M3 3, L2 2.5, M2 2.5, L3 1,
    # L1 0.5, L4 0.5, M4 0.5: eight links, no offset.
    off, links, d = drawing(heart(scale=5.0), "samples")
    expected = sorted([12.5, 3, 2.5, 2.5, 1, 0.5, 0.5, 0.5], reverse=True)
    assert [round(l.length / 5.0, 9) for l in links] == expected
    assert abs(off) < 1e-9
    choice = D.choose(off, links, d, max_deviation_mm=0.05, max_links=12, min_link_mm=2.0)
    assert choice.chosen is not None and choice.chosen.links == 8
    assert len(choice.chain.links) == 8
    # fewer links are measured outside the budget: the choice is the fewest
    assert all(r.hausdorff_mm > 0.05 for r in choice.rows[:7])
    # the measure is the distance to the samples (chords of the input), checked independently
    theta, path = D.chain_path(choice.chain, 4096)
    assert D.polyline_hausdorff(d.samples, path) <= 0.05
    # a coarser budget takes fewer links, and their measured distance is within it
    loose = D.choose(off, links, d, max_deviation_mm=8.0, max_links=12, min_link_mm=2.0)
    assert loose.chosen.links < 8 and loose.chosen.hausdorff_mm <= 8.0
    h = D.polyline_hausdorff(d.samples, D.chain_path(loose.chain, 4096)[1])
    assert h == pytest.approx(loose.chosen.hausdorff_mm, rel=1e-9) and h > 0.05
    coarse = D.chain_path(loose.chain, 4096)[1][::8]
    exact = D.polyline_hausdorff(d.samples, coarse)
    assert exact <= brute_hausdorff(d.samples, coarse, per=16) + 1e-9 <= exact + 0.05


def test_measured_hausdorff_matches_brute_force_for_a_poor_fit():
    off, links, d = drawing(heart(n=200, scale=3.0), "samples")
    chain = Chain(chain_order(links[:3]), off)
    _, path = D.chain_path(chain, 800)
    assert D.polyline_hausdorff(d.samples, path, d.theta, 2 * np.pi * np.arange(800) / 800) == pytest.approx(
        brute_hausdorff(d.samples, path, per=20), abs=0.05)


def test_short_links_are_dropped_and_the_rescue_names_the_scale():
    off, links, d = drawing(heart(scale=5.0), "samples")
    # the printer's smallest link is 3 mm: the three 2.5 mm links cannot be printed
    choice = D.choose(off, links, d, max_deviation_mm=0.05, max_links=12, min_link_mm=3.0)
    assert choice.chosen is None
    assert all(l.length >= 3.0 for l in choice.chain.links) and len(choice.chain.links) == 5
    r = D.rescue(off, links, d, 0.05, 12, 3.0)
    assert r.up == pytest.approx(3.0 / 2.5) and r.up_links == 8 and r.links is None
    # the rescue holds: at that scale the budget is met (deviation scales with the drawing)
    off2, links2, d2 = drawing(heart(scale=5.0 * r.up), "samples")
    again = D.choose(off2, links2, d2, 0.05 * 1.0, 12, 3.0 - 1e-9)
    assert again.chosen is not None and again.chosen.links == 8
    # both ways: 100 e^{iθ} + 30 e^{-2iθ} + 5 e^{4iθ} mm, 20 mm smallest link, 4 mm budget: the two long
    # links miss by the 5 mm term (measured H), so shrinking to 4/H keeps them within budget while
    # the 30 mm link stays over 20 mm; or enlarging 4× makes the 5 mm link printable (three links)
    t = 2 * np.pi * np.arange(500) / 500
    z = 100 * np.exp(1j * t) + 30 * np.exp(-2j * t) + 5 * np.exp(4j * t)
    off3, links3, d3 = drawing(z, "samples")
    r3 = D.rescue(off3, links3, d3, 4.0, 3, 20.0)
    h2 = D.tradeoff(off3, links3, d3, 2)[1].hausdorff_mm
    assert 3.0 < h2 <= 5.0 + 1e-9
    assert r3.down == pytest.approx(4.0 / h2) and r3.down_links == 2 and r3.down * 30 >= 20
    assert r3.up == pytest.approx(4.0) and r3.up_links == 3
    # too few links allowed: the rescue names the count
    r2 = D.rescue(off, links, d, 0.05, 4, 2.0)
    assert r2.links == 8


def test_lissajous_is_four_links_by_samples_and_many_by_arc_length():
    z = lissajous()
    budget = 1.0  # mm on a 100 x 100 mm figure
    off, links, d = drawing(z, "samples")
    c = D.choose(off, links, d, budget, 64, 1.0)
    assert c.chosen.links == 4
    assert sorted(abs(l.speed) for l in c.chain.links) == [2, 2, 3, 3]
    off, links, d = drawing(z, "arc_length")
    c = D.choose(off, links, d, budget, 64, 0.05)
    assert c.chosen is not None and c.chosen.links > 20  # 38 measured
    assert c.chosen.hausdorff_mm <= budget


def test_arc_length_angles_follow_the_distance_along_the_curve():
    # a square traced with uneven sample spacing: θ is proportional to the distance walked
    side = np.concatenate([np.linspace(0, 1, 5, endpoint=False), np.linspace(0, 1, 20, endpoint=False)])
    z = np.concatenate([side[:5] * 10, 10 + 10j * side[5:], ])
    z = np.concatenate([z, (10 - 10 * side[:5]) + 10j, 10j * (1 - side[5:])])
    theta = D.crank_angles(z, "arc_length")
    walked = np.concatenate([[0], np.cumsum(np.abs(np.diff(z)))])
    assert np.allclose(theta, 2 * np.pi * walked / 40.0)
    assert np.allclose(D.crank_angles(z, "samples"), 2 * np.pi * np.arange(len(z)) / len(z))


def test_every_chain_is_ordered_so_gears_can_couple_it():
    # Eq 11: (ω_{j+1} − ω_j)/(ω_{j−1} − ω_j) > 0 for every stage (ω_0 = 0). The heart's four longest
    # links are M1, M3, L2, M2: three turning backwards, so +/− alternation alone cannot order them.
    from partgen.design.drivetrain import eq11_ratios

    off, links, d = drawing(heart(scale=9.0), "samples")
    for n in range(1, len(links) + 1):
        order = D.drawable_order(links[:n])
        assert sorted(l.name for l in order) == sorted(l.name for l in links[:n])
        assert all(r > 0 for r in eq11_ratios([l.speed for l in order]))
    assert [l.name for l in D.drawable_order(links[:4])][0] in ("L2", "M1", "M3")
    rng = np.random.default_rng(1)
    for _ in range(50):
        speeds = rng.choice([s for s in range(-12, 13) if s], size=rng.integers(1, 12), replace=False)
        fake = tuple(D.Link(f"x{s}", int(s), float(rng.uniform(1, 9)), 0.0) for s in speeds)
        assert all(r > 0 for r in eq11_ratios([l.speed for l in D.drawable_order(fake, budget=50)]))
