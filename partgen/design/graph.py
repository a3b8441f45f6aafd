"""Connected components of a graph given as arrays of node pairs (pure numpy): the mesh checks'
shells, the GLB's smooth patches."""

from __future__ import annotations

import numpy as np

__all__ = ["components"]


def components(n: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(n,) the component label (its smallest node) of each of ``n`` nodes joined by the pairs
    ``(a[i], b[i])`` (int arrays of one length): union-find by hooking each pair's roots onto the
    smaller, then jumping pointers to the roots, until no pair spans two components."""
    parent = np.arange(n)
    a, b = np.asarray(a, dtype=np.int64), np.asarray(b, dtype=np.int64)
    while True:
        pa, pb = parent[a], parent[b]
        split = pa != pb
        if not split.any():
            return parent
        np.minimum.at(parent, np.maximum(pa, pb)[split], np.minimum(pa, pb)[split])
        while True:
            pp = parent[parent]
            if np.array_equal(pp, parent):
                break
            parent = pp
