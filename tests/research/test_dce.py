"""Discrete Curve Evolution and the skeleton pruning it drives."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from shapely import affinity
from shapely.geometry import Polygon, box

import medialaxis as mx
from medialaxis.compare.distance import VECTOR_TOLERANCE
from medialaxis.core import graph
from medialaxis.errors import InvalidInputError
from research.dce import convex_dce_vertices, dce, dce_prune, relevance
from research.path_similarity import path_signature, previous_default, term_matrices


def _reference_dce(v, threshold, min_vertices=3):
    """Plain DCE: recompute every relevance after each removal of the least relevant (ties together)."""
    alive = np.arange(len(v))
    perimeter = np.linalg.norm(v - np.roll(v, 1, axis=0), axis=1).sum()
    while len(alive) > min_vertices:
        rel = relevance(v[alive], perimeter)
        low = rel.min()
        if low >= threshold:
            break
        drop = rel <= low * (1 + 1e-6) + 1e-15
        if len(alive) - drop.sum() < min_vertices:
            drop = np.arange(len(alive)) == np.flatnonzero(drop)[0]
        alive = alive[~drop]
    return alive


def _blob(rng, n=60, noise=0.05):
    """A star-shaped polygon with lobes and boundary noise."""
    t = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 1 + 0.4 * np.cos(3 * t + rng.uniform(0, 6)) + noise * rng.standard_normal(n)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


def test_relevance_of_a_square_and_of_collinear_vertices():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    assert relevance(square) == pytest.approx(np.full(4, np.pi / 2 * (1 / 16) / (1 / 2)))
    line = np.array([[0, 0], [1, 0], [2, 0], [2, 1]], float)
    assert relevance(line)[1] == 0.0


@given(seed=st.integers(0, 2**32 - 1), threshold=st.floats(0.0, 0.05), keep=st.integers(3, 12))
def test_dce_matches_the_plain_reference(seed, threshold, keep):
    v = _blob(np.random.default_rng(seed))
    assert dce(v, threshold, min_vertices=keep).tolist() == _reference_dce(v, threshold, keep).tolist()


def _similar(v, angle, factor, mirror):
    """Rotate by ``angle`` degrees, scale by ``factor``, mirror x if asked."""
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    out = v @ np.array([[c, s], [-s, c]]) * factor
    return out * [-1, 1] if mirror else out


@given(
    seed=st.integers(0, 2**32 - 1),
    angle=st.floats(-180, 180),
    factor=st.floats(0.05, 20),
    mirror=st.booleans(),
)
def test_dce_invariant_under_similarities(seed, angle, factor, mirror):
    v = _blob(np.random.default_rng(seed))
    moved = _similar(v, angle, factor, mirror) + [3.0, -7.0]
    for threshold in (0.002, 0.01, 0.03):
        assert dce(moved, threshold).tolist() == dce(v, threshold).tolist()
    got = convex_dce_vertices(moved, 0.01)
    want = _similar(convex_dce_vertices(v, 0.01), angle, factor, mirror) + [3.0, -7.0]
    assert np.allclose(got, want, atol=1e-9 * factor)


def test_dce_keeps_the_corners_of_a_noisy_rectangle():
    rng = np.random.default_rng(1)
    side = np.linspace(0, 1, 30, endpoint=False)
    outline = np.vstack([np.column_stack([4 * side, 0 * side]), np.column_stack([4 + 0 * side, side]),
                         np.column_stack([4 - 4 * side, 1 + 0 * side]), np.column_stack([0 * side, 1 - side])])
    outline = outline + 0.003 * rng.standard_normal(outline.shape)
    corners = convex_dce_vertices(outline, 0.02)
    assert len(corners) == 4
    assert np.allclose(np.sort(np.round(corners)[:, 0]), [0, 0, 4, 4])


def test_dce_errors():
    with pytest.raises(InvalidInputError, match="shape"):
        dce(np.zeros((2, 2)), 0.1)
    with pytest.raises(InvalidInputError, match="NaN"):
        dce(np.array([[0, 0], [1, 0], [np.nan, 1]]), 0.1)
    with pytest.raises(InvalidInputError, match="threshold"):
        dce(np.eye(3)[:, :2], -1.0)
    with pytest.raises(InvalidInputError, match="min_vertices"):
        dce(np.eye(3)[:, :2], 0.1, min_vertices=2)


@pytest.mark.parametrize("seed", range(4))
def test_dce_prune_keeps_the_axis_connected_and_ends_claimed(seed):
    outline = _blob(np.random.default_rng(seed), n=120, noise=0.02)
    ma = mx.medial_axis(Polygon(outline)).raw
    points, radii, edges = np.asarray(ma.points), np.asarray(ma.radii), np.asarray(ma.edges)
    convex = convex_dce_vertices(outline, 0.01)
    kept = dce_prune(points, radii, edges, convex)
    assert set(map(tuple, kept.tolist())) <= set(map(tuple, edges.tolist()))
    nodes, sub = graph.compact(len(points), kept)
    assert graph.component_labels(len(nodes), sub)[0] == graph.component_labels(len(points), edges)[0] == 1
    ends = np.flatnonzero(graph.degree(len(points), kept) == 1)
    before = int((graph.degree(len(points), edges) == 1).sum())
    assert 2 <= len(ends) <= before
    gap = np.linalg.norm(convex[:, None] - points[ends][None], axis=2) - radii[ends][None]
    claimed = (gap <= gap.min(axis=1, keepdims=True) + 1e-6 * (1 + np.abs(gap.min(axis=1, keepdims=True)))).any(0)
    assert claimed.all() or len(ends) == 2


def test_path_signature_with_dce_is_a_similarity_invariant():
    a = Polygon(_blob(np.random.default_rng(3), n=120, noise=0.02))
    b = box(0, 0, 10, 3).union(box(3, 0, 5, 9))

    def sig(geom):
        ma = mx.medial_axis(geom, tolerance=VECTOR_TOLERANCE * np.sqrt(geom.area))
        return path_signature(ma, dce=1.0, dce_vertices=16, unpruned=True)

    moved = [affinity.translate(affinity.scale(affinity.rotate(a, angle, origin=(0, 0)), -f if mirror else f, f,
                                               origin=(0, 0)), 7, -3)
             for angle, f, mirror in ((33.0, 2.5, False), (-120.0, 0.3, True))]
    D = previous_default(term_matrices([sig(g) for g in (a, b, a, *moved)], n_jobs=1))
    assert D[0, 2] == 0.0 and D[0, 1] > 0.05
    assert D[1, 3:] == pytest.approx([D[0, 1]] * 2, rel=1e-6, abs=1e-9)
