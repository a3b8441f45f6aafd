"""Curve → links: the links trace ρ(θ) itself, the pruned set is the paper's Table 2, the chain
order and initial angles are Table 3's."""

from pathlib import Path

import numpy as np
import pytest
import yaml

from partgen.design.curve import from_cartesian, from_polar
from partgen.design.synthesis import Chain, chain_order, links_from_curve, prune, trace

DATA = Path(__file__).resolve().parents[1] / "data"
SIN = {1: -1.0, 3: 2.3, 5: 2.5, 7: -2.0, 9: -0.4}
COS = {2: 4.0, 4: -2.5}


def rho(theta):
    """The paper's Eq 5, written out independently of partgen."""
    t = theta
    return (7 - np.sin(t) + 2.3 * np.sin(3 * t) + 2.5 * np.sin(5 * t) - 2 * np.sin(7 * t) - 0.4 * np.sin(9 * t)
            + 4 * np.cos(2 * t) - 2.5 * np.cos(4 * t))


def table(name):
    return yaml.safe_load((DATA / f"liu2017_{name}.yaml").read_text())


@pytest.fixture(scope="module")
def butterfly():
    return from_polar(7.0, SIN, COS)


def test_links_trace_rho_itself(butterfly):
    offset, links = links_from_curve(butterfly, 1.0)
    theta = np.linspace(0, 2 * np.pi, 200_001)
    p = trace(Chain(links, offset), theta)
    target = rho(theta) * np.exp(1j * theta)
    assert np.abs(p - target).max() < 1e-9
    assert len(links) == 14  # Table 1: 14 non-zero links


def test_trace_is_the_right_way_up(butterfly):
    """The butterfly's wings open upward: ρ(π/2) = 7 - 1 - 2.3 + 2.5 + 2 - 0.4 - 4 - 2.5 = 1.3 is its
    small 'body' end and ρ(3π/2) = 7 + 1 + 2.3 - 2.5 - 2 + 0.4 - 4 - 2.5 = -0.3 … measure both
    extreme points of the traced path against the polar formula's, not just |P|."""
    offset, links = links_from_curve(butterfly, 1.0)
    theta = np.linspace(0, 2 * np.pi, 20_001)
    p = trace(Chain(links, offset), theta)
    t = rho(theta) * np.exp(1j * theta)
    for f in (np.argmax, np.argmin):
        assert abs(p.imag[f(p.imag)] - t.imag[f(t.imag)]) < 1e-9
        assert abs(p.real[f(p.real)] - t.real[f(t.real)]) < 1e-9
    # a mirrored (upside-down) chain would put the top where the bottom is
    mirrored = np.conj(p)
    assert np.abs(mirrored - t).max() > 1.0


def test_paper_eq2_sign_convention_is_the_slip(butterfly):
    """Table 1's phases used in Eq 2 as printed (L e^{i(kθ - ψ)}) do not give the curve; used as
    arg of the coefficient (e^{i(kθ + ψ)}) they do. This is the sign slip docs/papers.md reports."""
    rows = table("table1_full")["rows"]
    theta = np.linspace(0, 2 * np.pi, 4001)
    target = rho(theta) * np.exp(1j * theta)
    as_printed = sum(L * np.exp(1j * (k * theta - psi)) + M * np.exp(-1j * (k * theta + eta))
                     for k, L, psi, M, eta in rows)
    as_args = sum(L * np.exp(1j * (k * theta + psi)) + M * np.exp(-1j * (k * theta - eta))
                  for k, L, psi, M, eta in rows)
    assert np.abs(as_args - target).max() < 1e-6  # the table's 8-digit phases
    assert np.abs(as_printed - target).max() > 1.0


def test_links_match_table1(butterfly):
    offset, links = links_from_curve(butterfly, 1.0)
    got = {l.name: l for l in links}
    for k, L, psi, M, eta in table("table1_full")["rows"]:
        if k == 0:
            assert abs(offset - (L * np.exp(1j * psi) + M * np.exp(1j * eta))) < 1e-7  # 8-digit phases
            continue
        for name, length, phase in ((f"L{k}", L, psi), (f"M{k}", M, eta)):
            if length == 0:
                assert name not in got
                continue
            assert got[name].length == pytest.approx(length, abs=1e-12)
            assert np.exp(1j * got[name].phase) == pytest.approx(np.exp(1j * phase), abs=1e-7)


def test_pruned_set_matches_table2(butterfly):
    _, links = links_from_curve(butterfly, 1.0)
    kept = {l.name: l.length for l in prune(links, ["L2", "L10", "M8"])}
    expected = {}
    for k, L, _, M, _ in table("table2_reduced")["rows"]:
        if k:
            expected.update({f"L{k}": L, f"M{k}": M})
    expected = {n: v for n, v in expected.items() if v}
    assert set(kept) == set(expected)
    for n, v in expected.items():
        assert kept[n] == pytest.approx(v, abs=1e-12)


def test_chain_order_and_initial_angles_match_table3(butterfly):
    _, links = links_from_curve(butterfly, 30.0)
    chain = chain_order(prune(links, ["L2", "L10", "M8"]))
    rows = table("table3_manufacturing")["rows"]
    assert [l.name for l in chain] == [r[2] for r in rows]
    for link, (j, k, name, S, delta, *_rest) in zip(chain, rows):
        assert link.speed == k
        assert link.length == pytest.approx(S, abs=1e-9)
        assert np.exp(1j * link.phase) == pytest.approx(np.exp(1j * delta), abs=1e-6)


def test_cartesian_and_polar_forms_agree(butterfly):
    """The same curve given as Eq 1's a, b, c, d gives the same links (Eq 3's L_k, M_k)."""
    theta = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    p = butterfly.evaluate(theta)
    K = 10
    a = [p.real.mean()] + [2 * np.mean(p.real * np.cos(k * theta)) for k in range(1, K + 1)]
    b = [0.0] + [2 * np.mean(p.real * np.sin(k * theta)) for k in range(1, K + 1)]
    c = [p.imag.mean()] + [2 * np.mean(p.imag * np.cos(k * theta)) for k in range(1, K + 1)]
    d = [0.0] + [2 * np.mean(p.imag * np.sin(k * theta)) for k in range(1, K + 1)]
    cart = from_cartesian(a, b, c, d)
    dense = np.linspace(0, 2 * np.pi, 5001)
    assert np.abs(cart.evaluate(dense) - butterfly.evaluate(dense)).max() < 1e-12
    for k in range(1, K + 1):  # Eq 3
        L = 0.5 * np.hypot(a[k] + d[k], c[k] - b[k])
        M = 0.5 * np.hypot(a[k] - d[k], c[k] + b[k])
        assert abs(cart.coefficient(k)) == pytest.approx(L, abs=1e-12)
        assert abs(cart.coefficient(-k)) == pytest.approx(M, abs=1e-12)


def test_chain_order_alternates_and_sorts():
    from partgen.design.synthesis import Link
    links = [Link("L1", 1, 5, 0), Link("M1", -1, 9, 0), Link("L2", 2, 7, 0), Link("M3", -3, 1, 0), Link("L4", 4, 7, 0)]
    order = chain_order(links)
    assert [l.name for l in order] == ["L2", "M1", "L4", "M3", "L1"]


def test_prune_rejects_unknown_names(butterfly):
    _, links = links_from_curve(butterfly, 1.0)
    with pytest.raises(KeyError, match="L7"):
        prune(links, ["L7"])
