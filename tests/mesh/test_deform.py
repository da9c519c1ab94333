"""Skeleton-driven deformation (issue 5, Du and Qin, SM '04, section 4.3)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import medialaxis as mx
from medialaxis.datasets import capsules_mesh, segment_distance, tripod_mesh, tripod_segments
from medialaxis.mesh.skeleton.deform import _minimal_rotation, node_rotations


@pytest.fixture(scope="module")
def tripod_case():
    mesh = tripod_mesh(pitch=0.1)
    return mesh, mx.medial_axis(mesh, method="flow")


def _bend_arm(sk, arm: int, degrees: float):
    segments = tripod_segments(3.0)
    junction = sk.junctions[0]
    nearest = np.argmin(np.stack([segment_distance(sk.points, segments[k : k + 1]) for k in range(3)]), axis=0)
    on_arm = (nearest == arm) & (np.arange(len(sk.points)) != junction)
    rot = Rotation.from_rotvec(np.radians(degrees) * np.array([0.0, 0.0, 1.0])).as_matrix()
    new = sk.points.copy()
    new[on_arm] = (sk.points[on_arm] - sk.points[junction]) @ rot.T + sk.points[junction]
    return new, rot, sk.points[junction]


def test_bending_an_arm_keeps_volume_and_still_parts(tripod_case):
    mesh, sk = tripod_case
    new, rot, centre = _bend_arm(sk, 0, 30.0)
    out = mx.deform(mesh, sk, new)
    assert abs(out.volume / mesh.volume - 1.0) < 0.05
    assert out.is_watertight
    v, w = np.asarray(mesh.vertices), np.asarray(out.vertices)
    segments = tripod_segments(3.0)
    arm_of = np.argmin(np.stack([segment_distance(v, segments[k : k + 1]) for k in range(3)]), axis=0)
    still = (arm_of != 0) & (np.linalg.norm(v - centre, axis=1) > 1.5)
    assert np.array_equal(w[still], v[still])  # skeleton did not move there
    # the bent arm is a capsule of the same radius around the rotated axis
    bent_axis = np.array([[centre, (segments[0, 1] - centre) @ rot.T + centre]])
    moved = (arm_of == 0) & (np.linalg.norm(v - centre, axis=1) > 1.5)
    assert np.median(np.abs(segment_distance(w[moved], bent_axis) - 0.5)) < 0.02


def test_translation_moves_the_mesh_rigidly(tripod_case):
    mesh, sk = tripod_case
    out = mx.deform(mesh, sk, sk.points + [1.0, -2.0, 0.5])
    assert np.allclose(np.asarray(out.vertices), np.asarray(mesh.vertices) + [1.0, -2.0, 0.5], atol=1e-9)


def test_no_move_changes_nothing_and_input_untouched(tripod_case):
    mesh, sk = tripod_case
    before = mesh.vertices.copy()
    out = mx.deform(mesh, sk, sk.points)
    assert np.array_equal(np.asarray(out.vertices), before)
    assert np.array_equal(mesh.vertices, before)
    assert out is not mesh


def test_capsule_rotation_keeps_its_shape():
    capsule = capsules_mesh([[[0, 0, 0], [3, 0, 0]]], 0.5, pitch=0.1)
    sk = mx.medial_axis(capsule, method="flow")
    rot = Rotation.from_euler("xyz", [0.3, -0.5, 1.1]).as_matrix()
    out = mx.deform(capsule, sk, sk.points @ rot.T)
    axis = np.array([[[0, 0, 0], [3, 0, 0]]]) @ rot.T
    d = segment_distance(np.asarray(out.vertices), axis)
    assert np.abs(d - 0.5).max() < 0.02
    assert out.volume == pytest.approx(capsule.volume, rel=0.01)


def test_bad_arguments(tripod_case):
    mesh, sk = tripod_case
    with pytest.raises(mx.InvalidInputError, match="shape"):
        mx.deform(mesh, sk, sk.points[:-1])
    with pytest.raises(mx.InvalidInputError, match="NaN"):
        mx.deform(mesh, sk, np.full(sk.points.shape, np.nan))
    other = capsules_mesh([[[0, 0, 0], [1, 0, 0]]], 0.5, pitch=0.2)
    with pytest.raises(mx.InvalidInputError, match="vertices"):
        mx.deform(other, sk, sk.points)
    with pytest.raises(mx.InvalidInputError, match="smoothing"):
        mx.deform(mesh, sk, sk.points, smoothing=-1.0)


def test_rotations_of_nodes():
    rng = np.random.default_rng(1)
    for _ in range(20):
        a, b = rng.standard_normal(3), rng.standard_normal(3)
        r = _minimal_rotation(a, b)
        assert np.allclose(r @ r.T, np.eye(3)) and np.isclose(np.linalg.det(r), 1.0)
        assert np.allclose(r @ (a / np.linalg.norm(a)), b / np.linalg.norm(b))
    r = _minimal_rotation(np.array([1.0, 0, 0]), np.array([-1.0, 0, 0]))
    assert np.allclose(r @ [1.0, 0, 0], [-1.0, 0, 0])
    # a star rotated rigidly: the junction's Kabsch rotation is that rotation
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    edges = np.array([[0, 1], [0, 2], [0, 3]])
    rot = Rotation.from_euler("xyz", [0.2, 0.4, -0.7]).as_matrix()
    assert np.allclose(node_rotations(points, points @ rot.T, edges)[0], rot)
