"""The compiled 2D Delaunay kernel against its reference, SciPy's Qhull."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import Delaunay

from medialaxis.planar import delaunay
from medialaxis.planar._delaunay_kernels import delaunay_2d, insertion_order
from medialaxis.planar.delaunay import FAR_CORNERS, triangulate


def _unit(points: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """``points`` scaled into the unit square and jittered as :func:`triangulate` does."""
    work = (points - points.min(0)) / np.ptp(points, axis=0).max()
    return work + rng.uniform(-1e-9, 1e-9, points.shape)


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _triangle_set(simplices: np.ndarray) -> set[tuple[int, ...]]:
    return set(map(tuple, np.sort(simplices, axis=1).tolist()))


def _qhull_triangles(work: np.ndarray) -> np.ndarray:
    s = Delaunay(np.vstack([work, FAR_CORNERS])).simplices
    return s[(s < len(work)).all(axis=1)]


def _ring(n: int, rng: np.random.Generator) -> np.ndarray:
    th = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 1 + 0.3 * np.cos(5 * th)
    return np.c_[r * np.cos(th), r * np.sin(th)]


@pytest.mark.parametrize("n", [3, 4, 10, 150, 1500])
@pytest.mark.parametrize("kind", ["random", "ring"])
def test_same_triangles_as_qhull(n: int, kind: str) -> None:
    rng = np.random.default_rng(n)
    points = rng.uniform(0, 1, (n, 2)) if kind == "random" else _ring(n, rng)
    work = _unit(points, rng)
    found = delaunay_2d(np.vstack([work, FAR_CORNERS]))
    assert found is not None
    simplices, neighbors = found
    assert _triangle_set(simplices) == _triangle_set(_qhull_triangles(work))
    # counter-clockwise triangles; neighbours share the edge opposite each vertex
    a, b, c = (work[simplices[:, k]] for k in range(3))
    assert (_cross(b - a, c - a) > 0).all()
    for t, k in zip(*np.nonzero(neighbors >= 0)):
        edge = set(simplices[t]) - {simplices[t, k]}
        assert edge <= set(simplices[neighbors[t, k]])
        assert t in neighbors[neighbors[t, k]]


def test_grid_is_delaunay() -> None:
    """On a jittered grid (co-circular fours) every inner edge is locally Delaunay."""
    rng = np.random.default_rng(0)
    work = _unit(np.argwhere(np.ones((20, 20))).astype(float), rng)
    simplices, neighbors = delaunay_2d(np.vstack([work, FAR_CORNERS]))
    for t, k in zip(*np.nonzero(neighbors >= 0)):
        u = neighbors[t, k]
        far_vertex = (set(simplices[u]) - set(simplices[t])).pop()
        a, b, c = (work[i] - work[far_vertex] for i in simplices[t])
        det = (a @ a) * _cross(b, c) + (b @ b) * _cross(c, a) + (c @ c) * _cross(a, b)
        assert det <= 1e-20


def test_insertion_order_is_a_permutation() -> None:
    rng = np.random.default_rng(1)
    xy = rng.uniform(0, 1, (1000, 2))
    order = insertion_order(xy[:, 0], xy[:, 1])
    assert sorted(order.tolist()) == list(range(1000))
    assert (insertion_order(xy[:, 0], xy[:, 1]) == order).all()  # deterministic


def test_gives_up_on_coincident_points_and_qhull_takes_over(monkeypatch: pytest.MonkeyPatch) -> None:
    work = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [0.5, 1.0]])
    assert delaunay_2d(np.vstack([work, FAR_CORNERS])) is None
    calls = []
    monkeypatch.setattr(delaunay, "delaunay_2d", lambda w: calls.append(len(w)))
    tri = triangulate(np.random.default_rng(2).uniform(0, 1, (50, 2)))
    assert calls == [54]
    assert len(tri.simplices) > 0 and (tri.neighbors < len(tri.simplices)).all()


def test_boundary_distance_kernel_matches_its_reference() -> None:
    from medialaxis.planar._kernels import nearest_piece_distance, nearest_piece_distance_reference

    rng = np.random.default_rng(3)
    points = _ring(300, rng)
    nxt = (np.arange(300) + 1) % 300
    prv = (np.arange(300) - 1) % 300
    query = rng.uniform(-1, 1, (500, 2))
    near = rng.integers(0, 300, (500, 8))
    expected = nearest_piece_distance_reference(query, points, nxt, prv, near)
    assert np.allclose(nearest_piece_distance(query, points, nxt, prv, near), expected, rtol=1e-12, atol=1e-15)


def test_round_kernels_match_their_references() -> None:
    from shapely.geometry import Polygon

    from medialaxis.planar._kernels import piece_state, piece_state_reference, triangle_centroids
    from medialaxis.planar.axis import inner_triangles, proper_triangles

    rng = np.random.default_rng(4)
    points = _ring(200, rng)
    points = np.vstack([points, points[:20] * 0.5 + points[20:40] * 0.5])  # collinear triples: slivers
    tri = triangulate(points)
    extent = float(np.ptp(points, axis=0).max())
    proper, centroids = triangle_centroids(tri.points, tri.simplices, 1e-7 * extent)
    assert (proper == proper_triangles(tri)).all()
    assert np.allclose(centroids, tri.points[tri.simplices[proper]].mean(axis=1), rtol=0, atol=1e-15)
    inside = inner_triangles(tri, Polygon(points[:200]))
    nxt = (np.arange(len(points)) + 1) % len(points)
    got = piece_state(tri.simplices, inside, tri.radii, nxt)
    expected = piece_state_reference(tri.simplices, inside, tri.radii, nxt)
    assert (got[0] == expected[0]).all() and (got[1] == expected[1]).all()
    assert got[0].any() and np.isfinite(got[1]).any() and not got[0].all()
