"""The nearest samples found along the Delaunay edges (the radii of the pruned axis) against brute force."""

from __future__ import annotations

import numpy as np

from medialaxis.planar._distance_kernels import boundary_distance_kernel, delaunay_distance, site_neighbours
from medialaxis.planar._kernels import nearest_piece_distance, nearest_with_ties
from medialaxis.planar.delaunay import triangulate


def _rings_and_queries(rng: np.random.Generator) -> list[tuple[np.ndarray, np.ndarray]]:
    side = np.arange(12.0)
    square = np.concatenate([np.c_[side, 0 * side], np.c_[12 + 0 * side, side], np.c_[12 - side, 12 + 0 * side],
                             np.c_[0 * side, 12 - side]])  # a square ring sampled on the integer grid: many ties
    angle = np.sort(rng.uniform(0, 2 * np.pi, 300))
    wobbly = np.c_[np.cos(angle), 0.3 * np.sin(angle)] * (1 + 0.1 * np.sin(7 * angle))[:, None]
    return [(square, np.r_[rng.uniform(-1, 13, (300, 2)), np.mgrid[0:12:0.5, 0:12:0.5].reshape(2, -1).T]),
            (wobbly, rng.uniform(-1.2, 1.2, (400, 2)))]


def test_the_walk_along_delaunay_edges_finds_the_samples_brute_force_finds() -> None:
    """The distance to the pieces at the k nearest samples and every one tied with the k-th: brute force's,
    bit for bit, from any seed sample (the nearest or not) and for points inside or outside the ring."""
    rng = np.random.default_rng(11)
    for points, query in _rings_and_queries(rng):
        n = len(points)
        nxt, prv = (np.arange(n) + 1) % n, (np.arange(n) - 1) % n
        expected = nearest_piece_distance(query, points, nxt, prv, nearest_with_ties(query, points, 8))
        tri = triangulate(points)
        indptr, nbrs = site_neighbours(n, tri.simplices, tri.neighbors)
        for seed in (np.zeros(len(query), np.int64), rng.integers(0, n, len(query))):
            np.testing.assert_array_equal(delaunay_distance(query, seed, points, nxt, prv, 8, indptr, nbrs), expected)
        np.testing.assert_array_equal(boundary_distance_kernel(query, points, nxt, prv, 8), expected)


def test_site_neighbours_are_the_triangulations_edges_once_each_way() -> None:
    rng = np.random.default_rng(2)
    points = rng.uniform(0, 1, (200, 2))
    tri = triangulate(points)
    indptr, nbrs = site_neighbours(len(points), tri.simplices, tri.neighbors)
    edges = {tuple(sorted((int(s[i]), int(s[(i + 1) % 3])))) for s in tri.simplices for i in range(3)}
    listed = [(i, int(j)) for i in range(len(points)) for j in nbrs[indptr[i]:indptr[i + 1]]]
    assert len(listed) == 2 * len(edges)
    assert {tuple(sorted(e)) for e in listed} == edges
