"""The edge counts of the Voronoi route's complexes, against Python sets of the same edges."""

from __future__ import annotations

import numpy as np
import pytest

from medialaxis.mesh.medial.compact import _relabelled
from medialaxis.mesh.medial.voronoi_complex import euler_characteristic


def _edge_set(faces, edges):
    out = {tuple(sorted((int(a), int(b)))) for f in faces for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
    return out | {tuple(sorted((int(a), int(b)))) for a, b in edges}


@pytest.mark.parametrize("seed", range(6))
def test_euler_characteristic_counts_each_edge_once(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 40))
    faces = rng.integers(0, n, (int(rng.integers(0, 80)), 3))
    edges = rng.integers(0, n, (int(rng.integers(0, 30)), 2))
    assert euler_characteristic(n, faces, edges) == n - len(_edge_set(faces, edges)) + len(faces)
    assert euler_characteristic(n, faces) == n - len(_edge_set(faces, [])) + len(faces)


def test_euler_characteristic_of_a_tetrahedron_surface_and_an_octahedron():
    tet = np.array([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])
    octa = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    assert euler_characteristic(4, tet) == 2
    assert euler_characteristic(6, octa) == 2
    assert euler_characteristic(6, octa, np.array([[0, 1]])) == 1  # a chord: one cycle more


@pytest.mark.parametrize("seed", range(8))
def test_relabelled_edges_are_the_distinct_merged_pairs(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 50))
    pairs = {tuple(sorted(p)) for p in rng.integers(0, n, (int(rng.integers(0, 150)), 2)).tolist() if p[0] != p[1]}
    edges = np.array(sorted(pairs), np.int64).reshape(-1, 2)
    to = np.arange(n)
    merged = rng.choice(n, int(rng.integers(0, n // 2 + 1)), replace=False)
    to[merged] = rng.integers(0, n, len(merged))
    want = sorted({tuple(sorted((int(to[a]), int(to[b])))) for a, b in edges if to[a] != to[b]})
    assert _relabelled(edges, to, n).tolist() == [list(p) for p in want]
