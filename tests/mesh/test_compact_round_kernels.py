"""The compaction's bookkeeping kernels against the NumPy expressions they replace."""

from __future__ import annotations

import numpy as np

from medialaxis.mesh.medial._compact_kernels import lattice
from medialaxis.mesh.medial._compact_round_kernels import (
    changed_prims,
    merge_into,
    morton_codes,
    quadrics,
    remap_faces,
    ties_by_source,
)
from medialaxis.mesh.medial.compact import complex_edges


def test_ties_by_source_is_the_lexsort_by_cost_then_source_then_edge():
    rng = np.random.default_rng(1)
    n = 300
    keys = np.unique(rng.integers(0, n * n, 6000))
    edges = np.c_[keys // n, keys % n]
    edges = np.sort(edges[edges[:, 0] != edges[:, 1]], axis=1)
    edges = edges[np.unique(edges[:, 0] * n + edges[:, 1], return_index=True)[1]]  # sorted, distinct
    cost = rng.integers(0, 40, len(edges)) / 7.0  # many ties
    src = edges[np.arange(len(edges)), rng.integers(0, 2, len(edges))]
    rows = np.flatnonzero(cost < 5.0)
    expected = rows[np.lexsort((src[rows], cost[rows]))]
    for kind in ("quicksort", "stable", "heapsort"):
        got = ties_by_source(rows[np.argsort(cost[rows], kind=kind)], cost, src, edges, np.arange(n))
        assert np.array_equal(got, expected)
    # the same complex with its vertices renamed: the order follows the names given, not the labels used
    perm = rng.permutation(n)
    label = np.empty(n, np.int64)
    label[perm] = np.arange(n)
    got = ties_by_source(rows[np.argsort(cost[rows], kind="quicksort")], cost, label[src], label[edges], perm)
    assert np.array_equal(got, expected)


def test_morton_codes_interleave_the_grid_coordinates():
    points = np.array([[x, y, z] for z in range(4) for y in range(4) for x in range(4)], float)[::-1] * 0.5 + 2.0
    q = ((points - 2.0) / 1.5 * 2097151.0).astype(np.int64)  # the 2^21 grid over the box (side 1.5)
    expected = [sum(((int(c) >> b) & 1) << (3 * b + k) for b in range(21) for k, c in enumerate(row)) for row in q]
    assert morton_codes(points).tolist() == expected
    assert not morton_codes(np.array([[0.0, np.nan, 1.0], [1.0, 2.0, 3.0]])).any()  # no box: no order


def test_quadrics_are_the_tangent_planes_squared_distances():
    rng = np.random.default_rng(2)
    points = rng.normal(size=(50, 3))
    contacts = points[:, None, :] + rng.normal(size=(50, 4, 3))
    qa, qb, qc = quadrics(points, contacts)
    sphere = np.c_[rng.normal(size=(50, 3)), rng.uniform(0.1, 1.0, 50)]
    normal = contacts - points[:, None, :]
    normal /= np.linalg.norm(normal, axis=2, keepdims=True)
    # the signed distance of sphere (x, r) to the plane through p with normal n is n.(p - x) - r
    planes = ((normal * (contacts - sphere[:, None, :3])).sum(axis=2) - sphere[:, None, 3]) ** 2
    quadric = np.einsum("ij,ijk,ik->i", sphere, qa, sphere) - 2 * (qb * sphere).sum(axis=1) + qc
    assert np.allclose(quadric, planes.sum(axis=1), rtol=1e-9, atol=1e-9)
    einsum = np.einsum("ijk,ijk->ij", normal, contacts)  # the NumPy sums of the version before, to the bit
    assert np.array_equal(qc, (einsum * einsum).sum(axis=1))


def _star_of_a_strip():
    """A strip of 12 triangles over 14 vertices, its edges, and a map merging vertices 3 -> 2 and 9 -> 10."""
    top, bottom = np.arange(0, 7), np.arange(7, 14)
    faces = np.concatenate([np.c_[top[:-1], bottom[:-1], top[1:]], np.c_[top[1:], bottom[:-1], bottom[1:]]])
    edges = complex_edges(faces, np.empty((0, 2), np.int64), 14)[0]
    to = np.arange(14)
    to[[3, 9]] = [2, 10]
    return faces, edges, to


def test_remap_faces_drops_the_squeezed_triangles():
    faces, _, to = _star_of_a_strip()
    out, origin, corners = remap_faces(faces, np.arange(len(faces)) + 100, to)
    mapped = to[faces]
    kept = (mapped[:, 0] != mapped[:, 1]) & (mapped[:, 1] != mapped[:, 2]) & (mapped[:, 2] != mapped[:, 0])
    assert kept.sum() < len(faces)
    assert np.array_equal(out, mapped[kept]) and np.array_equal(origin, np.flatnonzero(kept) + 100)
    assert np.array_equal(corners, np.sort(mapped[kept], axis=1))


def test_changed_prims_are_those_the_map_moves_and_does_not_squeeze():
    faces, edges, to = _star_of_a_strip()
    spheres = np.c_[np.arange(14) % 7, np.arange(14) // 7, np.zeros(14), np.ones(14)].astype(float)
    prims = np.concatenate([faces, edges[:, [0, 1, 1]]])
    after = to[prims]
    flat = (after[:, 0] == after[:, 1]) | (after[:, 2] == after[:, 0]) | ((after[:, 1] == after[:, 2]) & (prims[:, 1] != prims[:, 2]))
    changed = (after != prims).any(axis=1) & ~flat
    for spacing in (0.4, 5.0):  # every changed primitive carries lattice samples, none does
        got_after, got_before, touched = changed_prims(faces, edges, to, spheres, spacing)
        assert np.array_equal(np.flatnonzero(touched), np.unique(after[changed]))
        sampled = [len(lattice(spheres, after[[p]], np.c_[after, prims][[p]], spacing, -1.0)[0]) > 0 for p in range(len(prims))]
        assert np.array_equal(got_before, prims[changed & sampled]) and np.array_equal(got_after, after[changed & sampled])
        assert (len(got_after) > 0) == (spacing < 1.0)


def test_merge_into_adds_rows():
    rng = np.random.default_rng(3)
    qa, qb, qc, count = rng.normal(size=(9, 4, 4)), rng.normal(size=(9, 4)), rng.normal(size=9), np.full(9, 4.0)
    expected = [x.copy() for x in (qa, qb, qc, count)]
    j, i = np.array([0, 5, 7]), np.array([1, 4, 8])
    for x in expected:
        x[i] += x[j]
    merge_into(j, i, qa, qb, qc, count)
    assert all(np.array_equal(x, y) for x, y in zip((qa, qb, qc, count), expected))


def test_complex_edges_counts_the_triangles_on_each_edge():
    faces, _, _ = _star_of_a_strip()
    curve = np.array([[20, 3], [0, 1], [5, 5]])  # a curve piece, a triangle side listed again, a loop (dropped)
    edges, count = complex_edges(faces, curve, 21)
    sides = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]], [[3, 20]]]), axis=1)
    expected, times = np.unique(sides, axis=0, return_counts=True)
    assert np.array_equal(edges, expected)
    assert np.array_equal(count, times - (expected == [3, 20]).all(axis=1))


def test_small_rounds_run_on_one_thread():
    import numba

    from medialaxis.mesh.medial.compact import PARALLEL_ROWS, threads_for

    before = numba.get_num_threads()
    with threads_for(PARALLEL_ROWS - 1):
        assert numba.get_num_threads() == 1
    assert numba.get_num_threads() == before
    with threads_for(PARALLEL_ROWS):
        assert numba.get_num_threads() == before
