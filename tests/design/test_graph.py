"""design.graph.components against scipy's connected components on random graphs."""

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from partgen.design.graph import components


@pytest.mark.parametrize("seed", range(5))
def test_components_match_scipy(seed):
    rng = np.random.default_rng(seed)
    n = 2000
    k = int(rng.integers(200, 2500))
    a, b = rng.integers(0, n, k), rng.integers(0, n, k)
    got = components(n, a, b)
    count, ref = connected_components(coo_matrix((np.ones(k), (a, b)), shape=(n, n)), directed=False)
    assert len(np.unique(got)) == count
    # the same partition: each of ours maps to one of scipy's and back
    pairs = np.unique(np.stack([got, ref], axis=1), axis=0)
    assert len(pairs) == count
    smallest = np.full(n, n)
    np.minimum.at(smallest, got, np.arange(n))
    assert (got == smallest[got]).all()  # each label is its component's smallest node


def test_no_pairs_is_every_node_alone():
    assert (components(4, np.zeros(0, int), np.zeros(0, int)) == np.arange(4)).all()
