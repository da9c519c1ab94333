"""The compaction's merge costs: the slab search stopped early gives the costs and moves of the full search."""

from __future__ import annotations

import numpy as np
import pytest

from medialaxis.mesh.medial._compact_kernels import (
    _cheap_terms,
    _segment_distance2,
    _triangle_distance2,
    costs,
    feature_lines,
    moves,
    structure,
)
from medialaxis.mesh.medial.compact import complex_edges, sphere_quadrics
from medialaxis.mesh.voronoi import voronoi_medial_axis

trimesh = pytest.importorskip("trimesh")


def _exhaustive(j, i, spheres, terms, star):
    """Cost and move of merging ``j`` into ``i``: the slab distance over the whole star of ``j``, never stopped.

    The distances are the compiled kernels' (the interpreted ones differ in the last bit on degenerate triangles).
    """
    sqem, rest = _cheap_terms.py_func(j, i, *terms)
    ptr, idx, eid, apex_ptr, apex = star
    slab = []
    for q in range(ptr[j], ptr[j + 1]):
        k = idx[q]
        if k != i:
            slab.append(_segment_distance2(spheres, j, i, k))
            slab += [_triangle_distance2(spheres, j, i, k, a) for a in apex[apex_ptr[eid[q]]:apex_ptr[eid[q] + 1]] if a != i]
    move = max(rest, np.sqrt(min(slab)) if slab else np.linalg.norm(spheres[j] - spheres[i]))
    return max(sqem, move), move


def test_costs_stopped_early_and_moves_match_the_exhaustive_search():
    ma = voronoi_medial_axis(trimesh.creation.capsule(height=2.0, radius=0.5), samples=2000, compact=False)
    n = len(ma.points)
    faces = np.asarray(ma.faces, np.int64)
    edges, _ = complex_edges(faces, ma.edges, n)
    spheres = np.c_[ma.points, ma.radii]
    qa, qb, qc = sphere_quadrics(ma.points, ma.extras["contacts"])
    count = np.full(n, 4.0)
    moved = np.where(np.arange(n) % 3 == 0, 0.05 * ma.radii, 0.0)  # moves merged in earlier, on every third vertex
    star = structure(n, edges, faces)
    lines = feature_lines(edges, np.diff(star[3]) != 2, n)
    terms = (spheres, qa, qb, qc, count, moved, lines)
    src, dst, cost, move = costs(edges, np.arange(len(edges)), *terms, star, np.arange(n))
    rows = np.arange(0, len(edges), 7)
    for k in rows:
        u, v = edges[k]
        (c_uv, m_uv), (c_vu, m_vu) = _exhaustive(u, v, spheres, terms, star), _exhaustive(v, u, spheres, terms, star)
        assert (src[k], dst[k], cost[k]) == ((u, v, c_uv) if c_uv <= c_vu else (v, u, c_vu))
        assert np.isnan(move[k]) or move[k] == (m_uv if c_uv <= c_vu else m_vu)
    assert 0 < np.isnan(move).sum() < len(move)  # the early stop ran, and left some moves unknown ...
    expected = [_exhaustive(src[k], dst[k], spheres, terms, star)[1] for k in rows]
    assert np.array_equal(moves(src[rows], dst[rows], *terms, star), expected)  # ... which moves() gives
