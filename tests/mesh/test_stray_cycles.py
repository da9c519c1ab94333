"""Cycles of the medial complex through points outside the solid are cut only where the solid lacks them.

The complexes are built by hand, so their Betti numbers are known from the
construction: a disc (a fan of triangles) is contractible, each curve loop
hung on it adds one cycle.
"""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

import medialaxis as mx
import medialaxis.mesh.voronoi as voronoi
from medialaxis.core.homology import betti_numbers
from medialaxis.mesh.medial.stray_cycles import complement_voids, cut_stray_cycles, without_stray_cycles

RIM = 8  # a disc: centre 0, rim points 1..8


def _disc_with_loops(loops: list[int]) -> tuple[int, np.ndarray, np.ndarray, int]:
    """A fan disc with, for each entry, a curve loop of that many new points from rim point 1 to rim point 5."""
    faces = np.array([[0, 1 + k, 1 + (k + 1) % RIM] for k in range(RIM)])
    border = np.array([[1 + k, 1 + (k + 1) % RIM] for k in range(RIM)])
    curve, n = [], RIM + 1
    for length in loops:
        chain = [1, *range(n, n + length), 5]
        curve += [[a, b] for a, b in zip(chain[:-1], chain[1:])]
        n += length
    return n, faces, np.concatenate([np.array(curve).reshape(-1, 2), border]), len(curve)


def test_a_loop_through_stray_points_is_cut_and_pulled_back_to_the_disc():
    n, faces, edges, n_curve = _disc_with_loops([4])
    assert betti_numbers(n, edges, faces) == (1, 1, 0)
    stray = np.zeros(n, bool)
    stray[[11, 12]] = True  # two points far out on the loop
    kept, n_kept, keep, n_cut = cut_stray_cycles(n, faces, edges, n_curve, stray, excess=1)
    assert n_cut == 1 and n_kept == 0
    assert keep.tolist() == [True] * (RIM + 1) + [False] * 4  # the loop's points all go
    np.testing.assert_array_equal(kept, edges[n_curve:])  # the disc's border is left, untouched
    assert betti_numbers(n, kept, faces)[1:] == (0, 0)


@pytest.mark.parametrize("length", [3, 4, 5])
def test_a_loop_alone_collapses_to_a_point_not_to_nothing(length):
    # a component that is a loop of curve edges only, beside the disc: cut, it is a point, still a
    # component (the path left collapses from both ends and meets at a point or at an edge)
    n, faces, edges, n_curve = _disc_with_loops([])
    loop = np.c_[np.arange(n, n + length), np.roll(np.arange(n, n + length), -1)]
    edges = np.concatenate([loop, edges])
    stray = np.ones(n + length, bool)
    assert betti_numbers(n + length, edges, faces) == (2, 1, 0)
    kept, n_kept, keep, n_cut = cut_stray_cycles(n + length, faces, edges, length, stray, excess=1)
    assert n_cut == 1 and n_kept == 0 and keep.sum() == n + 1
    new_index = np.cumsum(keep) - 1
    assert betti_numbers(int(keep.sum()), new_index[kept], new_index[faces]) == (2, 0, 0)


def test_a_loop_of_medial_points_is_never_cut():
    n, faces, edges, n_curve = _disc_with_loops([4])
    kept, n_kept, keep, n_cut = cut_stray_cycles(n, faces, edges, n_curve, np.zeros(n, bool), excess=1)
    assert n_cut == 0 and n_kept == n_curve and keep.all()
    np.testing.assert_array_equal(kept, edges)


def test_no_more_cycles_are_cut_than_the_solid_lacks():
    n, faces, edges, n_curve = _disc_with_loops([3, 3, 2])
    assert betti_numbers(n, edges, faces) == (1, 3, 0)
    stray = np.zeros(n, bool)
    stray[RIM + 1 :] = True
    kept, n_kept, keep, n_cut = cut_stray_cycles(n, faces, edges, n_curve, stray, excess=2)
    assert n_cut == 2
    new_index = np.cumsum(keep) - 1
    assert betti_numbers(int(keep.sum()), new_index[kept], new_index[faces]) == (1, 1, 0)
    # the loop left is whole: a chain of k points has k + 1 edges
    assert n_kept in (3, 4) and keep.sum() == RIM + 1 + n_kept - 1


def test_the_complex_is_renumbered_and_left_alone_when_its_euler_characteristic_is_the_solids():
    n, faces, edges, n_curve = _disc_with_loops([4, 2])
    used = np.arange(100, 100 + n)  # tetrahedra of the points
    stray = np.zeros(n, bool)
    stray[RIM + 1 :] = True
    chi = 1 - 2 + 0  # the disc and two loops
    same = without_stray_cycles(used, faces, edges, n_curve, stray, (1, 2, 0), lambda: 0, chi)  # a solid of genus 2
    assert same[4] == 0 and same[1] is faces and same[2] is edges
    used2, faces2, edges2, n_curve2, n_cut = without_stray_cycles(used, faces, edges, n_curve, stray, (1, 0, 0), lambda: 0, chi)
    assert n_cut == 2 and n_curve2 == 0
    np.testing.assert_array_equal(used2, used[: RIM + 1])
    np.testing.assert_array_equal(faces2, faces)
    assert betti_numbers(len(used2), edges2, faces2) == (1, 0, 0)


def test_the_voids_by_the_complement_are_those_of_the_homology(monkeypatch):
    # a hollow ball and a ball with two cavities: b2 of the full complex by GF(2) elimination
    # (core.homology, checked against exact answers) and by the components of its complement
    seen = []
    real = voronoi.medial_complex

    def spy(dt, *args, **kwargs):
        cx = real(dt, *args, **kwargs)
        seen.append((dt, cx))
        return cx

    monkeypatch.setattr(voronoi, "medial_complex", spy)
    outer = trimesh.creation.icosphere(4, radius=2.0)
    holes = [trimesh.creation.icosphere(3, radius=0.5).apply_translation(c) for c in ((0.9, 0, 0), (-0.9, 0, 0))]
    for n_holes in (1, 2):
        parts = [outer] + [h.copy() for h in holes[:n_holes]]
        for part in parts[1:]:
            part.invert()
        mesh = trimesh.util.concatenate(parts)
        mx.medial_axis(mesh, method="voronoi", compact=False)
        dt, cx = seen[-1]
        assert betti_numbers(len(cx.tets), cx.edges, cx.faces)[2] == n_holes
        assert complement_voids(dt.simplices, dt.neighbors, cx.facet_ij) == n_holes


def _voids_by_graph(simplices: np.ndarray, neighbors: np.ndarray, facet_ij: np.ndarray) -> int:
    """The complement's bounded components by SciPy: every tetrahedron's six edges as a sparse graph."""
    from scipy import sparse
    from scipy.sparse import csgraph

    n = int(simplices.max()) + 1
    pairs = np.sort(simplices[:, [0, 0, 0, 1, 1, 2, 1, 2, 3, 2, 3, 3]].reshape(-1, 2, 6).transpose(0, 2, 1).reshape(-1, 2),
                    axis=1)
    kept = {(int(a), int(b)) for a, b in np.sort(facet_ij, axis=1)}
    free = np.array([(int(a), int(b)) not in kept for a, b in pairs], bool)
    hull = np.unique(np.concatenate([np.delete(simplices[neighbors[:, k] < 0], k, axis=1).ravel() for k in range(4)]))
    rows = np.concatenate([pairs[free, 0], hull])
    cols = np.concatenate([pairs[free, 1], np.full(len(hull), n)])
    graph = sparse.coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n + 1, n + 1))
    label = csgraph.connected_components(graph, directed=False)[1]
    present = np.zeros(n + 1, bool)
    present[simplices.ravel()] = True
    present[n] = True
    return len(np.unique(label[present])) - 1


@pytest.mark.parametrize("seed", range(6))
def test_the_compiled_complement_counts_as_a_sparse_graph_does(seed):
    # random points, the cells of a few inner samples closed (all their edges kept: a void each, unless two
    # touch) and a random share of the other edges kept (0-90%: from 3 voids to 112, isolated samples)
    from medialaxis.mesh.medial.voronoi_diagram import tetrahedralise

    rng = np.random.default_rng(seed)
    dt = tetrahedralise(rng.random((400, 3)))
    lo = np.minimum(dt.simplices[:, [0, 0, 0, 1, 1, 2]], dt.simplices[:, [1, 2, 3, 2, 3, 3]]).ravel()
    hi = np.maximum(dt.simplices[:, [0, 0, 0, 1, 1, 2]], dt.simplices[:, [1, 2, 3, 2, 3, 3]]).ravel()
    edges = np.unique(np.c_[lo, hi], axis=0)
    inner = np.flatnonzero(np.linalg.norm(dt.points - 0.5, axis=1) < 0.3)
    closed = rng.choice(inner, size=3 + seed, replace=False)
    around = np.isin(edges, closed).any(axis=1)
    kept = edges[around | (rng.random(len(edges)) < 0.18 * seed)]
    expected = _voids_by_graph(dt.simplices, dt.neighbors, kept)
    assert complement_voids(dt.simplices, dt.neighbors, kept) == expected
    assert complement_voids(dt.simplices, dt.neighbors, kept[:, ::-1]) == expected  # either end first
    if seed == 0:
        assert expected >= 1  # closed cells apart are voids
