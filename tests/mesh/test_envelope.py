"""The exact envelope of a medial mesh's interpolated spheres, against closed forms and dense sampling."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from medialaxis.mesh.simplify.envelope import envelope_gap, envelope_samples, primitives, two_sided_distance


def _dense_gap(points, centres, radii, pairs, faces, steps=400, grid=120):
    """min |x - c| - r over spheres interpolated at ``1/steps`` along edges and a ``1/grid`` lattice on triangles."""
    s = np.c_[centres, radii]
    t = np.linspace(0.0, 1.0, steps + 1)[:, None]
    parts = [s] + [(1 - t) * s[a] + t * s[b] for a, b in pairs]
    uv = np.array([(i / grid, j / grid) for i in range(grid + 1) for j in range(grid + 1 - i)])
    parts += [(1 - uv.sum(1))[:, None] * s[a] + uv[:, :1] * s[b] + uv[:, 1:] * s[c] for a, b, c in faces]
    dense = np.concatenate(parts)
    return np.array([(np.linalg.norm(dense[:, :3] - p, axis=1) - dense[:, 3]).min() for p in points])


def test_gap_of_equal_radii_is_the_distance_to_the_segment_or_triangle_less_the_radius():
    rng = np.random.default_rng(3)
    x = rng.normal(size=(2000, 3))
    seg = np.array([[-0.5, 0.1, 0.0], [0.7, -0.2, 0.3]])
    t = np.clip(((x - seg[0]) @ (seg[1] - seg[0])) / np.sum((seg[1] - seg[0]) ** 2), 0, 1)
    exact = np.linalg.norm(x - seg[0] - t[:, None] * (seg[1] - seg[0]), axis=1) - 0.3
    got = envelope_gap(x, seg, [0.3, 0.3], [[0, 1]], np.zeros((0, 3), int))
    np.testing.assert_allclose(got, exact, atol=1e-12)
    tri = np.array([[0.0, 0.0, 0.0], [1.0, 0.2, 0.0], [0.3, 0.9, 0.4]])
    closest = trimesh.triangles.closest_point(np.repeat(tri[None], len(x), axis=0), x)
    exact = np.linalg.norm(x - closest, axis=1) - 0.25
    got = envelope_gap(x, tri, [0.25, 0.25, 0.25], np.zeros((0, 2), int), [[0, 1, 2]])
    np.testing.assert_allclose(got, exact, atol=1e-12)


def test_gap_with_varying_radii_matches_dense_interpolation_from_below():
    rng = np.random.default_rng(1)
    c = rng.random((6, 3))
    r = 0.05 + 0.2 * rng.random(6)
    edges, faces = np.array([[0, 1], [4, 5]]), np.array([[1, 2, 3], [2, 3, 4]])
    x = rng.random((1500, 3)) * 1.6 - 0.3
    got = envelope_gap(x, c, r, edges, faces)
    pairs = [(0, 1), (4, 5), (1, 2), (2, 3), (1, 3), (2, 4), (3, 4)]
    dense = _dense_gap(x, c, r, pairs, faces)
    # the exact minimum is below every sampled one, and near it (lattice steps of 1/120 on triangles)
    assert np.all(got <= dense + 1e-12)
    assert np.max(dense - got) < 5e-4


def test_a_sphere_inside_its_neighbour_adds_nothing():
    c = np.array([[0.0, 0.0, 0.0], [0.1, 0.0, 0.0]])
    x = np.random.default_rng(0).normal(size=(500, 3))
    got = envelope_gap(x, c, [1.0, 0.2], [[0, 1]], np.zeros((0, 3), int))
    np.testing.assert_allclose(got, np.linalg.norm(x, axis=1) - 1.0, atol=1e-12)


def test_envelope_samples_lie_on_the_union_or_inside_it():
    rng = np.random.default_rng(2)
    c, r = rng.random((5, 3)), 0.1 + 0.1 * rng.random(5)
    faces, edges = np.array([[0, 1, 2]]), np.array([[2, 3], [3, 4]])
    spheres = np.c_[c, r]
    y = envelope_samples(spheres, primitives(5, edges, faces), budget=5000)
    g = envelope_gap(y, c, r, edges, faces)
    assert len(y) >= 4000 and np.all(g <= 1e-12)
    assert np.mean(g > -1e-9) > 0.2  # many are on the boundary itself


@pytest.mark.parametrize("radius", [0.3, 1.0])
def test_a_capsule_mesh_is_its_two_sphere_medial_mesh(radius):
    # trimesh's capsule: the envelope of two spheres of the same radius, half its height apart
    capsule = trimesh.creation.capsule(height=2.0, radius=radius, count=[64, 64])
    centres = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])
    to_mat, from_mat = two_sided_distance(centres, [radius, radius], [[0, 1]], np.zeros((0, 3), int), capsule)
    # the polygonal mesh's own distance from the round capsule, from a dense sample and the closed form
    x, _ = trimesh.sample.sample_surface_even(capsule, 200_000, seed=0)
    depth = np.abs(np.linalg.norm(x - np.c_[0 * x[:, :2], np.clip(x[:, 2], -1, 1)], axis=1) - radius).max()
    assert 0.85 * depth < to_mat < 1.05 * depth
    assert 0.5 * depth < from_mat < 1.05 * depth
    # one sphere alone: the far cap is the height (2.0) away from it
    to_mat, from_mat = two_sided_distance(centres[:1], [radius], np.zeros((0, 2), int), np.zeros((0, 3), int), capsule)
    assert abs(to_mat - 2.0) < 0.02


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), scale=st.floats(0.01, 100.0))
def test_gap_moves_with_rotation_translation_and_scale(seed, scale):
    rng = np.random.default_rng(seed)
    c, r = rng.random((5, 3)), 0.05 + 0.3 * rng.random(5)
    edges, faces = np.array([[3, 4]]), np.array([[0, 1, 2], [1, 2, 3]])
    x = rng.normal(size=(200, 3))
    rotation = trimesh.transformations.random_rotation_matrix(rng.random(3))[:3, :3]
    shift = rng.normal(size=3) * 10
    moved = envelope_gap(scale * x @ rotation.T + shift, scale * c @ rotation.T + shift, scale * r, edges, faces)
    np.testing.assert_allclose(moved, scale * envelope_gap(x, c, r, edges, faces), atol=1e-9 * scale, rtol=1e-9)


def test_degenerate_primitives_give_finite_gaps():
    # coincident centres, a zero-length edge, collinear and repeated triangle corners, a sphere inside another
    c = np.array([[0.0, 0, 0], [0.0, 0, 0], [1.0, 0, 0], [2.0, 0, 0], [0.5, 0, 0]])
    r = np.array([0.2, 0.1, 0.2, 0.3, 0.0])
    edges, faces = np.array([[0, 1], [1, 2]]), np.array([[0, 2, 3], [0, 0, 2], [2, 3, 4]])
    x = np.random.default_rng(0).normal(size=(300, 3))
    got = envelope_gap(x, c, r, edges, faces)
    assert np.all(np.isfinite(got))
    dense = _dense_gap(x, c, r, [(0, 1), (1, 2), (0, 2), (2, 3), (0, 3), (3, 4), (2, 4)], [(0, 2, 3), (2, 3, 4)])
    assert np.all(got <= dense + 1e-12) and np.max(dense - got) < 1e-3
    y = envelope_samples(np.c_[c, r], primitives(5, edges, faces), budget=2000)
    assert len(y) and np.all(np.isfinite(y))


def test_two_overlapping_spheres_against_their_capsule():
    # two unit spheres 1 apart, no edge between them: their union's crease circle (radius sqrt(3)/2)
    # lies 1 - sqrt(3)/2 inside the capsule's waist; the waist is sqrt(5)/2 - 1 from the union
    capsule = trimesh.creation.capsule(height=1.0, radius=1.0, count=[128, 128])
    centres = np.array([[0.0, 0.0, -0.5], [0.0, 0.0, 0.5]])
    to_mat, from_mat = two_sided_distance(centres, [1.0, 1.0], np.zeros((0, 2), int), np.zeros((0, 3), int), capsule)
    assert abs(from_mat - (1 - np.sqrt(3) / 2)) < 1e-3
    assert abs(to_mat - (np.sqrt(5) / 2 - 1)) < 1e-3


def test_the_exhaustive_check_ends_where_every_local_distance_overstates():
    """A triangle soup's local closest-point search finds no near face for most points: every local distance
    overstates. The exact search must then reach the true largest distance, in few batches (it took over
    40 minutes 64 points at a time, the whole array sorted each round)."""
    from medialaxis.mesh.sample.signed_distance import SignedDistance

    sphere = trimesh.creation.icosphere(subdivisions=4)
    exact = SignedDistance(sphere)
    calls = []

    class Overstating:
        def query(self, z, faces):
            return np.full(len(z), 10.0), None  # no near face found: far too far

        def exact(self, z):
            calls.append(len(z))
            return exact.exact(z)

    centres, radii = np.zeros((1, 3)), [0.8]
    _, from_mat = two_sided_distance(centres, radii, np.zeros((0, 2), int), np.zeros((0, 3), int), sphere,
                                     signed=Overstating())
    _, truth = two_sided_distance(centres, radii, np.zeros((0, 2), int), np.zeros((0, 3), int), sphere)
    assert from_mat == pytest.approx(truth, rel=1e-4) and from_mat == pytest.approx(0.2, abs=0.01)
    assert len(calls) <= int(np.log2(sum(calls) / 64 + 1)) + 1  # batches doubling from 64
