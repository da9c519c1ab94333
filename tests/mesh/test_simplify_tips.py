"""The simplification's spheres at tips end the medial axis (issue 31): known axes of a box, a spheroid, a capsule.

Truth from outside the code: the medial axis of a prolate spheroid with
semi-axes ``a > b = c`` is the segment of its long axis with ``|x| <= (a^2 -
b^2) / a``, the ball at ``(x, 0, 0)`` of radius ``b sqrt(1 - x^2 / (a^2 -
b^2))``; a capsule's is the segment joining its two cap centres, every ball
of the cap's radius. A sphere is medial when trimesh's samples of the surface
within 2% of its radius span at least 90 degrees seen from its centre.
"""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from scipy.spatial import cKDTree

from medialaxis.mesh.sample.signed_distance import SignedDistance
from medialaxis.mesh.simplify.envelope import surface_sample
from medialaxis.mesh.simplify.medial_candidates import MedialCandidates, inscribed_along
from medialaxis.mesh.simplify.qmat import simplify_medial_mesh
from medialaxis.mesh.voronoi import voronoi_medial_axis

A, B = 2.0, 0.5  # the spheroid's semi-axes


def _touches_two_sides(mesh, centres, radii, band=0.02):
    """Per sphere: trimesh's surface samples within ``band`` of its radius of it span >= 90 degrees."""
    points = np.asarray(trimesh.sample.sample_surface_even(mesh, 60_000, seed=5)[0])
    tree = cKDTree(points)
    out = []
    for c, r in zip(np.atleast_2d(centres), np.atleast_1d(radii)):
        v = points[tree.query_ball_point(c, (1 + band) * r)] - c
        d = np.linalg.norm(v, axis=1)
        u = v[d >= (1 - band) * r] / d[d >= (1 - band) * r, None]
        out.append(len(u) > 1 and (u @ u.T).min() <= 0.0)
    return np.array(out)


@pytest.fixture(scope="module")
def spheroid():
    mesh = trimesh.creation.icosphere(subdivisions=4)
    mesh.apply_scale([A, B, B])
    return mesh, voronoi_medial_axis(mesh)


def _candidates(mesh, ma):
    return MedialCandidates(ma, surface_sample(mesh), SignedDistance(mesh))


def test_balls_along_a_normal_stop_at_the_medial_axis_of_a_box():
    # a 1 x 1 x 1 box: from (0.2, 0.5, 1) down, the ball reaches the side x = 0 at radius 0.2; from the top's
    # centre it reaches all six sides at 0.5, the box's centre
    box = trimesh.creation.box([1.0, 1.0, 1.0])
    box.apply_translation([0.5, 0.5, 0.5])
    points, down = np.array([[0.2, 0.5, 1.0], [0.5, 0.5, 1.0]]), np.array([[0.0, 0.0, 1.0]] * 2)
    centres, radii, other = inscribed_along(points, down, np.array([2.0, 2.0]), SignedDistance(box), slack=1e-3)
    assert radii == pytest.approx([0.2, 0.5], rel=2e-3)
    assert np.allclose(centres, [[0.2, 0.5, 0.8], [0.5, 0.5, 0.5]], atol=1e-3)
    assert other[0, 0] == pytest.approx(0.0, abs=1e-3)  # the second contact is on the side x = 0


def test_the_tip_ball_of_a_spheroid_lies_on_its_axis_and_touches_two_sides(spheroid):
    mesh, ma = spheroid
    tip = A - B * B / A  # the axis ends at the centre of the pole's osculating ball, radius b^2 / a
    for pole in (np.array([A, 0.0, 0.0]), np.array([-A, 0.0, 0.0])):
        centre, radius = _candidates(mesh, ma).tip(pole, 2.0 * B * B / A, 0.005)
        x = abs(centre[0])
        assert np.hypot(centre[1], centre[2]) <= 0.01 and x <= tip + 0.01
        assert radius == pytest.approx(B * np.sqrt(1.0 - x * x / (A * A - B * B)), rel=0.03)
        assert np.linalg.norm(pole - centre) - radius <= 0.005
        assert _touches_two_sides(mesh, centre, radius).all()


def test_the_tip_ball_of_a_capsule_is_a_ball_of_its_axis():
    mesh = trimesh.creation.capsule(height=2.0, radius=0.4, count=[32, 32])  # cap centres at z = -1, 1
    centre, radius = _candidates(mesh, voronoi_medial_axis(mesh)).tip(np.array([0.0, 0.0, 1.4]), 0.4, 0.01)
    off = np.linalg.norm(centre - [0.0, 0.0, np.clip(centre[2], -1.0, 1.0)])  # from the segment
    assert off <= 0.015
    # the smooth capsule's inscribed ball there, less the facets' sag (0.4 (1 - cos(pi / 32)) = 0.002)
    assert radius == pytest.approx(0.4 - off, abs=0.003)
    assert _touches_two_sides(mesh, centre, radius).all()


def test_the_spheroids_poles_take_medial_balls_not_patches(spheroid):
    # at 40 spheres the cover repair reached the poles with patches, balls of radius 0.063 (half the pole's
    # osculating ball) tangent at the pole vertex: 90% of the spheres touched two sides, error 0.13% of the
    # diagonal; now the ends of the axis: all of them, and the error no larger
    mesh, ma = spheroid
    s = simplify_medial_mesh(ma, 40)
    assert len(s.points) == 40
    assert _touches_two_sides(mesh, s.points, s.radii).all()
    assert (trimesh.proximity.signed_distance(mesh, s.points) >= 0.98 * s.radii).all()
    assert s.metadata["hausdorff"] / s.metadata["diagonal"] <= 0.0013


@pytest.mark.parametrize("shape", ["spheroid", "torus"])
def test_shrinking_balls_from_the_tangent_bound_are_the_largest_empty_tangent_balls(shape):
    """The largest ball tangent at ``p`` (outward normal ``n``) holding no sample is, by brute force over the
    samples ``q`` with ``(p - q).n > 0``, the least ``|p - q|^2 / (2 (p - q).n)`` (the ball through ``q``; the
    larger ones hold it). The shrinking balls started from the bound of the nearest samples reach it, and
    the bound is never below it. Exact normals: the spheroid's gradient, the torus's from its core circle."""
    from medialaxis.mesh.simplify.medial_candidates import shrinking_balls, tangent_bound

    if shape == "spheroid":
        p = np.asarray(trimesh.creation.icosphere(subdivisions=3).vertices) * [A, B, B]
        n = p / [A * A, B * B, B * B]
    else:  # R = 3, r = 1: every medial ball has radius 1 (the core circle)
        p = np.asarray(trimesh.creation.torus(3.0, 1.0, major_sections=48, minor_sections=24).vertices)
        core = p * [1.0, 1.0, 0.0]
        core *= 3.0 / np.linalg.norm(core, axis=1)[:, None]
        n = p - core
    n /= np.linalg.norm(n, axis=1)[:, None]
    v = p[:, None, :] - p[None, :, :]
    cos = np.einsum("ijk,ik->ij", v, n)
    truth = np.where(cos > 1e-9, (v * v).sum(axis=2) / (2.0 * np.where(cos > 1e-9, cos, 1.0)), np.inf).min(axis=1)
    tree = cKDTree(p)
    bound = tangent_bound(p, n, p, tree)
    assert np.all(bound >= truth * (1.0 - 1e-12))
    _, radii, _ = shrinking_balls(p, n, 100.0, p, tree)
    np.testing.assert_allclose(radii, truth, rtol=1e-6)
    if shape == "torus":
        np.testing.assert_allclose(radii, 1.0, rtol=1e-6)


def test_the_cover_repairs_gaps_are_the_envelope_gaps_of_its_result(spheroid):
    """The cover repair keeps the gaps of the mesh it grows up to date (cones added, splits); the
    simplification's error from the surface to the medial mesh is taken from them. Truth: ``envelope_gap``
    of the returned mesh from scratch at the same surface points."""
    from medialaxis.mesh.simplify.envelope import envelope_gap

    mesh, ma = spheroid
    s = simplify_medial_mesh(ma, 30)
    sample = surface_sample(mesh)
    faces = np.asarray(s.faces, np.int64).reshape(-1, 3)
    want = envelope_gap(sample.points, s.points, s.radii, s.edges, faces)
    assert s.metadata["hausdorff_surface_to_mat"] == float(np.abs(want).max())
