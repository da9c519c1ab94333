"""The ring kernels of the medial complex against SciPy's Delaunay and sparse matrices (the truth from outside).

The ring entries are int32 (the largest arrays of a medial complex: about six
per tetrahedron); these tests pin that the narrower type changes no answer.
"""

from __future__ import annotations

import numpy as np
from scipy import sparse
from scipy.spatial import Delaunay

from medialaxis.mesh.medial._ring_kernels import (
    all_edge_rings,
    csr_transpose,
    flagged_sides,
    ring_side_ids,
    ring_side_slots,
)


def _delaunay(n=300, seed=0):
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(n, 3))
    dt = Delaunay(points)
    return points, dt.simplices.astype(np.int64), dt.neighbors.astype(np.int64)


def test_every_interior_edge_has_its_ring_of_scipys_tetrahedra_in_cyclic_order():
    points, simplices, neighbors = _delaunay()
    edge_ij, ptr, ring, length = all_edge_rings(simplices, neighbors, points, np.arange(len(simplices)), False, 0.0)
    assert ring.dtype == np.int32 and len(ptr) == len(edge_ij) + 1
    # the truth: the tetrahedra holding both ends, by brute force; hull edges (open rings) are left out
    hull = {tuple(sorted(e)) for f in Delaunay(points).convex_hull for e in ((f[0], f[1]), (f[1], f[2]), (f[0], f[2]))}
    holding: dict[tuple[int, int], set[int]] = {}
    for t, tet in enumerate(simplices):
        for a in range(4):
            for b in range(a + 1, 4):
                holding.setdefault(tuple(sorted((int(tet[a]), int(tet[b])))), set()).add(t)
    interior = {e for e in holding if e not in hull}
    assert {tuple(map(int, e)) for e in edge_ij} == interior
    assert (np.diff(edge_ij[:, 0]) >= 0).all()  # ascending
    for k, (i, j) in enumerate(edge_ij):
        tets = ring[ptr[k]:ptr[k + 1]]
        assert set(tets.tolist()) == holding[(int(i), int(j))] and len(set(tets.tolist())) == len(tets)
        for a, b in zip(tets, np.roll(tets, -1)):  # each shares a triangle with the next
            assert len(set(simplices[a]) & set(simplices[b])) == 3
        assert np.isclose(length[k], np.linalg.norm(points[i] - points[j]))
    # every=True reads no index array: the same rings
    for got, want in zip(all_edge_rings(simplices, neighbors, points, np.zeros(0, np.int64), True, 0.0),
                         (edge_ij, ptr, ring, length)):
        np.testing.assert_array_equal(got, want)


def test_side_slots_are_the_slots_of_the_side_ids():
    points, simplices, neighbors = _delaunay(seed=1)
    _, ptr, ring, _ = all_edge_rings(simplices, neighbors, points, np.arange(len(simplices)), False, 0.0)
    flag = np.random.default_rng(2).random(len(simplices)) < 0.7
    slot, ends = flagged_sides(neighbors, flag)
    ids = ring_side_ids(ptr, ring, neighbors)
    assert ids.dtype == np.int32 and slot.dtype == np.int32 and ends.dtype == np.int32
    np.testing.assert_array_equal(ring_side_slots(ptr, ring, neighbors, slot), np.where(ids >= 0, slot[ids], -1))
    # each side id names the triangle after each entry: neighbors[lo, k] is the other tetrahedron
    for r in range(len(ptr) - 1):
        tets = ring[ptr[r]:ptr[r + 1]]
        for q, (a, b) in enumerate(zip(tets, np.roll(tets, -1))):
            lo, k = divmod(int(ids[ptr[r] + q]), 4)
            assert lo == min(a, b) and neighbors[lo, k] == max(a, b)
    # sides: the triangles between two flagged tetrahedra (the truth: SciPy's neighbours), numbered in slot
    pairs = {(t, int(u)) for t in range(len(neighbors)) for u in neighbors[t] if u > t and flag[t] and flag[u]}
    assert {tuple(map(int, e)) for e in ends} == pairs and len(ends) == len(pairs)
    for s, (a, b) in enumerate(ends):
        assert slot[4 * a + list(neighbors[a]).index(b)] == s
    assert (slot >= 0).sum() == len(ends)


def test_transpose_in_int32_is_scipys():
    rng = np.random.default_rng(3)
    counts = rng.integers(0, 6, 400)
    ptr = np.r_[0, np.cumsum(counts)].astype(np.int64)
    idx = rng.integers(0, 150, ptr[-1]).astype(np.int32)
    tptr, rows = csr_transpose(ptr, idx, 150)
    assert rows.dtype == np.int32
    truth = sparse.csr_matrix((np.ones(len(idx)), idx, ptr), shape=(400, 150)).T.tocsr()
    truth.sort_indices()
    np.testing.assert_array_equal(tptr, truth.indptr)
    # the rows of each column ascending, a row twice where it names the column twice (as SciPy keeps them)
    np.testing.assert_array_equal(rows, truth.indices)
    np.testing.assert_array_equal(rows, csr_transpose(ptr, idx.astype(np.int64), 150)[1])
