"""The compaction's merge costs: the slab search stopped early gives the costs and moves of the full search."""

from __future__ import annotations

import numpy as np
import pytest

from medialaxis.mesh._compact_kernels import _feature_lines, _merge_cost, costs, moves, structure
from medialaxis.mesh.compact import complex_edges, sphere_quadrics
from medialaxis.mesh.voronoi import voronoi_medial_axis

trimesh = pytest.importorskip("trimesh")


def test_costs_stopped_early_and_moves_match_the_exhaustive_search():
    ma = voronoi_medial_axis(trimesh.creation.capsule(height=2.0, radius=0.5), samples=2000, compact=False)
    n = len(ma.points)
    faces = np.asarray(ma.faces, np.int64)
    edges, _ = complex_edges(faces, ma.edges, n)
    spheres = np.c_[ma.points, ma.radii]
    qa, qb, qc = sphere_quadrics(ma.points, ma.extras["contacts"])
    count = np.full(n, 4.0)
    moved = np.zeros(n)
    star = structure(n, edges, faces)
    feature = np.diff(star[3]) != 2
    src, dst, cost = costs(edges, np.arange(len(edges)), spheres, qa, qb, qc, count, moved, feature, star)
    line = _feature_lines(edges, feature, n)

    def exhaustive(j, i):  # the slab distance over the whole star, never stopped
        return _merge_cost.py_func(j, i, spheres, qa, qb, qc, count, moved, *line, star, True)

    stopped = 0
    for k in range(0, len(edges), 7):
        u, v = edges[k]
        (c_uv, _), (c_vu, _) = exhaustive(u, v), exhaustive(v, u)
        assert (src[k], dst[k], cost[k]) == ((u, v, c_uv) if c_uv <= c_vu else (v, u, c_vu))
        stopped += _merge_cost.py_func(u, v, spheres, qa, qb, qc, count, moved, *line, star, False)[1] > exhaustive(u, v)[1]
    assert stopped > 0  # the early stop ran, and left the move it returns too high ...
    rows = np.arange(0, len(edges), 7)
    expected = [exhaustive(src[k], dst[k])[1] for k in rows]
    assert np.array_equal(moves(edges, src[rows], dst[rows], spheres, qa, qb, qc, count, moved, feature, star), expected)  # ... not moves
