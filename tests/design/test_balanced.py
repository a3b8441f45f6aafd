"""The planar balanced butterfly linkage: its kinematics from two inputs, the similarity it keeps,
and a common centre of mass that stays at S — and visibly leaves it with 10 % extra mass."""

import cmath

import numpy as np
import pytest

from partgen.design.balanced import (Butterfly, balance_coefficients, centre_of_mass, paper_mass_equations,
                                     positions, solve_masses)

BF = Butterfly(l1a=60.0, l2=80.0, l3=70.0, l4a=90.0, s2=0.8, s3=0.6, s4=0.7)
GRID = [(q1, q4) for q1 in np.linspace(0, 2 * np.pi, 36) for q4 in np.linspace(0, 2 * np.pi, 36)]


def masses():
    rng = np.random.default_rng(0)
    m = {i: float(rng.uniform(0.5, 2)) for i in range(1, 13)}
    p = {i: float(rng.uniform(-10, 40)) for i in range(1, 13)}
    return solve_masses(BF, m, p, (3, 6, 9)), p


def collinear(pos, a, b, c):
    return abs(((pos[b] - pos[a]).conjugate() * (pos[c] - pos[a])).imag) / max(abs(pos[b] - pos[a]), 1e-9)


def test_links_keep_their_lengths_shapes_and_parallels():
    L = BF.lengths
    n = 0
    for q1, q4 in GRID:
        pos = positions(BF, q1, q4)
        if pos is None:
            continue
        n += 1
        for a, b, key in (("B2", "D2", "l2"), ("D2", "B3", "l3"), ("B8", "D1", "l5"), ("D1", "B1", "l6"),
                          ("B6", "D4", "l8"), ("D4", "B7", "l9"), ("B4", "D3", "l11"), ("D3", "B5", "l12"),
                          ("S", "B1", "l7a"), ("S", "B6", "l7b"), ("S", "B7", "l10a"), ("S", "B4", "l10b")):
            assert abs(pos[a] - pos[b]) == pytest.approx(L[key], abs=1e-9), key
        for tri in (("B5", "S", "B2"), ("B3", "S", "B8"), ("B1", "S", "B6"), ("B7", "S", "B4"),
                    ("C1", "B2", "D2"), ("D1", "B1", "C2"), ("D4", "B7", "C1"), ("C2", "B4", "D3")):
            assert collinear(pos, *tri) < 1e-9, tri
        # links 7 and 10 parallel to links 3 and 2 of the first four-bar
        assert abs(((pos["B1"] - pos["S"]).conjugate() * (pos["B3"] - pos["D2"])).imag) < 1e-6
        assert abs(((pos["B4"] - pos["S"]).conjugate() * (pos["B2"] - pos["D2"])).imag) < 1e-6
    assert n > 500


def test_common_centre_of_mass_stays_at_S():
    m, p = masses()
    assert all(v > 0 for v in m.values())  # a physical solution
    scale = sum(m.values()) * 100.0  # g·mm: the size of a mass moment here
    assert np.abs(balance_coefficients(BF, m, p)).max() < 1e-14 * scale
    worst = max(abs(centre_of_mass(pos, m, p)) for q in GRID if (pos := positions(BF, *q)) is not None)
    assert worst < 1e-11


def test_ten_percent_extra_mass_on_one_link_shows():
    m, p = masses()
    heavy = dict(m)
    heavy[5] *= 1.1
    worst = max(abs(centre_of_mass(pos, heavy, p)) for q in GRID if (pos := positions(BF, *q)) is not None)
    assert worst > 0.1  # mm


PARALLEL = Butterfly(l1a=70.0, l2=90.0, l3=70.0, l4a=90.0, s2=0.8, s3=0.6, s4=0.7)  # a, b, a, b as in a Bennett


def paper_masses(bf):
    """Links 4, 7, 9 (counterweights 40 mm beyond their reference joints) given the masses that meet
    the paper's Eq 9–11, the others random."""
    rng = np.random.default_rng(0)
    m = {i: float(rng.uniform(0.5, 2)) for i in range(1, 13)}
    p = {i: float(rng.uniform(5, 40)) for i in range(1, 13)}
    p.update({4: -40.0, 7: -40.0, 9: -40.0})
    return solve_masses(bf, m, p, (4, 7, 9), paper_mass_equations), p


def worst_com(bf, m, p):
    return max(abs(centre_of_mass(pos, m, p)) for q in GRID if (pos := positions(bf, *q)) is not None)


def _condition_rows(bf, conditions, p):
    """(3, 12) matrix of three linear mass conditions (one column per link's unit mass)."""
    return np.column_stack([conditions(bf, {k: float(k == i) for k in range(1, 13)}, p) for i in range(1, 13)])


def test_eq_9_to_11_balance_when_opposite_sides_are_equal():
    """The paper simplifies Eq 6–8 to Eq 9–11 assuming four-bar 1's opposite sides are equal (l1a = l3,
    l2 = l4a, as in every Bennett linkage). Under it, masses meeting Eq 9–11 (positive here) keep
    the centre of mass at S, and the paper's three equations span the same conditions as the three
    derived from the mass moment."""
    m, p = paper_masses(PARALLEL)
    assert all(v > 0 for v in m.values())
    assert np.abs(paper_mass_equations(PARALLEL, m, p)).max() < 1e-12 * sum(m.values()) * 100
    assert np.abs(balance_coefficients(PARALLEL, m, p)).max() < 1e-12 * sum(m.values()) * 100
    assert worst_com(PARALLEL, m, p) < 1e-12
    paper, derived = _condition_rows(PARALLEL, paper_mass_equations, p), _condition_rows(PARALLEL, balance_coefficients, p)
    assert np.linalg.matrix_rank(np.vstack([paper, derived]), tol=1e-9 * np.abs(derived).max()) == 3


@pytest.mark.parametrize("dims", [(60.0, 80.0, 70.0, 90.0), (70.0, 80.0, 70.0, 90.0), (60.0, 90.0, 70.0, 90.0)])
def test_eq_9_to_11_need_the_general_derivation_otherwise(dims):
    """Without equal opposite sides (either pair unequal) Eq 9–11 are other conditions: masses that
    meet them let the centre of mass wander (6.3 mm in the 60/80/70/90 four-bar of the other tests),
    while the conditions derived from the mass moment hold it at S."""
    bf = Butterfly(*dims, s2=0.8, s3=0.6, s4=0.7)
    m, p = paper_masses(bf)
    assert worst_com(bf, m, p) > 0.1
    derived = _condition_rows(bf, balance_coefficients, p)
    both = np.vstack([_condition_rows(bf, paper_mass_equations, p), derived])
    assert np.linalg.matrix_rank(both, tol=1e-9 * np.abs(derived).max()) > 3
    md = solve_masses(bf, m, p, (4, 7, 9))
    assert worst_com(bf, md, p) < 1e-11
    m6, p6 = masses()
    if dims == (60.0, 80.0, 70.0, 90.0):  # docs/papers.md's figure: the transcribed equations' masses in this four-bar
        rng_free = solve_masses(BF, m6, p6, (3, 6, 9), paper_mass_equations)
        assert worst_com(BF, rng_free, p6) == pytest.approx(6.29, abs=0.01)


def test_inputs_drive_link_1_and_link_4():
    pos = positions(BF, 0.4, 2.0)
    assert cmath.phase(pos["B2"]) == pytest.approx(0.4) and cmath.phase(pos["B3"]) == pytest.approx(2.0)
