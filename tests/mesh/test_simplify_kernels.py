"""The compiled simplification loops against plain references: scipy's k-d tree, the Python heap loop.

The reference collapse is the loop ``qmat`` ran before it was compiled
(``heapq`` of ``(cost, i, j, version i, version j)`` tuples, neighbour and
triangle sets), written again here; both share the merge cost
(:func:`~medialaxis.mesh.simplify._simplify_kernels.optimum`), so the spheres, the
triangles and the curve must agree exactly.
"""

from __future__ import annotations

import heapq

import numpy as np
import pytest
import trimesh
from scipy.spatial import cKDTree

from medialaxis.mesh.simplify._simplify_kernels import (
    PENDING,
    collapse,
    kd_build,
    kd_knn,
    optimum,
    pair_costs,
    snap_many,
)
from medialaxis.mesh.simplify.qmat import _collapsed_mesh, _initial_quadrics
from medialaxis.mesh.voronoi import voronoi_medial_axis


@pytest.mark.parametrize("k", [1, 16, 64])
def test_nearest_candidates_are_scipys(k):
    rng = np.random.default_rng(5)
    points = rng.normal(size=(3000, 4)) * [1.0, 2.0, 0.5, 0.1]
    tree = kd_build(points)
    queries = rng.normal(size=(200, 4))
    expected = cKDTree(points).query(queries, k=k)[1].reshape(len(queries), -1)
    for q, row in zip(queries, expected):
        assert np.array_equal(kd_knn(q, k, points, *tree), row)


def test_snaps_take_the_cheapest_of_the_nearest_not_known_outside():
    rng = np.random.default_rng(7)
    cand = rng.normal(size=(500, 4))
    state = np.where(rng.random(500) < 0.3, -1, 0).astype(np.int8)
    spheres = rng.normal(size=(50, 4))
    m = rng.normal(size=(50, 4, 4))
    qa, qb = m @ m.transpose(0, 2, 1), rng.normal(size=(50, 4))
    got = snap_many(spheres, qa, qb, cand, state.copy(), kd_build(cand), 16)
    tree = cKDTree(cand)
    for s, a, b, g in zip(spheres, qa, qb, got):
        near = tree.query(s, k=16)[1]
        near = near[state[near] != -1]
        cost = np.einsum("ki,ij,kj->k", cand[near], a, cand[near]) - 2.0 * cand[near] @ b
        assert g == near[np.argmin(cost)]


def test_taken_candidates_not_yet_asked_are_marked_pending():
    cand = np.eye(4)
    state = np.array([0, -1, 1, 0], np.int8)
    got = snap_many(np.array([[1.0, 0, 0, 0], [0, 0, 1.0, 0]]), np.tile(np.eye(4), (2, 1, 1)), np.zeros((2, 4)),
                    cand, state, kd_build(cand), 1)
    assert got.tolist() == [0, 2] and state.tolist() == [PENDING, -1, 1, 0]


def _reference(spheres, qa, qb, qc, reg, faces, edges, target):
    """The collapse loop as qmat ran it in Python (sets and heapq)."""
    spheres, qa, qb, qc = spheres.copy(), qa.copy(), qb.copy(), qc.copy()
    n = len(spheres)
    tri = {k: tuple(f) for k, f in enumerate(faces.tolist())}
    at = [set() for _ in range(n)]
    for k, f in tri.items():
        for v in f:
            at[v].add(k)
    nbr = [set() for _ in range(n)]
    for a, b in edges.tolist():
        if a != b:
            nbr[a].add(b)
            nbr[b].add(a)
    version, alive, heap = np.zeros(n, np.int64), np.ones(n, bool), []

    def push(pairs):
        ends = np.array(pairs, np.int64).reshape(-1, 2)
        for (i, j), c in zip(pairs, pair_costs(qa, qb, qc, spheres, reg, ends).tolist()):
            heapq.heappush(heap, (c, i, j, int(version[i]), int(version[j])))

    push([(i, j) for i in range(n) for j in nbr[i] if i < j])
    left = n
    while left > target and heap:
        _, i, j, vi, vj = heapq.heappop(heap)
        if not (alive[i] and alive[j]) or version[i] != vi or version[j] != vj:
            continue
        spheres[i] = optimum(qa[i] + qa[j], qb[i] + qb[j], qc[i] + qc[j], spheres[i], spheres[j], reg)[0]
        qa[i], qb[i], qc[i] = qa[i] + qa[j], qb[i] + qb[j], qc[i] + qc[j]
        alive[j], left = False, left - 1
        for k in at[j]:
            f = tri[k]
            if i in f:
                del tri[k]
                for v in f:
                    if v != j:
                        at[v].discard(k)
            else:
                tri[k] = tuple(i if v == j else v for v in f)
                at[i].add(k)
        for k in nbr[j]:
            nbr[k].discard(j)
            if k != i:
                nbr[k].add(i)
                nbr[i].add(k)
        nbr[i].discard(j)
        nbr[j] = set()
        version[i] += 1
        push([(min(i, k), max(i, k)) for k in nbr[i]])
    keep = np.flatnonzero(alive)
    new = np.full(n, -1, np.int64)
    new[keep] = np.arange(len(keep))
    out = np.unique(np.sort(new[np.array(list(tri.values()), np.int64).reshape(-1, 3)], axis=1), axis=0)
    sides = {tuple(sorted(e)) for f in out.tolist() for e in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
    curve = sorted({(min(new[i], new[j]), max(new[i], new[j])) for i in keep for j in nbr[i]} - sides)
    return spheres[keep], out, np.array(curve, np.int64).reshape(-1, 2)


@pytest.mark.parametrize("target", [40, 400])
def test_compiled_collapses_are_the_python_loops(target):
    box = trimesh.creation.box(extents=(2, 1, 0.5))
    ma = voronoi_medial_axis(box, samples=3000).raw  # the full complex: 4,000 spheres, a curve and sheets
    spheres = np.c_[ma.points, ma.radii]
    qa, qb, qc = _initial_quadrics(ma)
    reg = 1e-3 * float(np.mean(np.trace(qa, axis1=1, axis2=2)))
    edges = np.concatenate([ma.edges, ma.faces[:, [0, 1]], ma.faces[:, [1, 2]], ma.faces[:, [2, 0]]]).astype(np.int64)
    none = np.zeros((0, 4))
    out, into = collapse(spheres, qa, qb, qc, reg, edges, target, np.inf, False, none, np.zeros(0, np.int8),
                         kd_build(none), 16)
    keep, faces, curve = _collapsed_mesh(into, ma.faces, edges)
    ref_spheres, ref_faces, ref_curve = _reference(spheres, qa, qb, qc, reg, ma.faces, edges, target)
    assert len(keep) == target and len(faces)
    assert np.array_equal(out[keep], ref_spheres)
    assert np.array_equal(faces, ref_faces) and np.array_equal(curve, ref_curve)
