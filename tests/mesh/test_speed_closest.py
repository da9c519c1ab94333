"""The plane bound of the closest-point kernels skips only faces that could not be taken (same answers, bit for bit)."""

from __future__ import annotations

import numpy as np
import trimesh

from medialaxis.mesh.sample._closest_kernels import (
    closest_on_candidates,
    closest_point_reference,
    face_data,
    face_scale,
)


def _all_faces_ring(n_faces: int) -> tuple[np.ndarray, np.ndarray]:
    """Every face's "ring" is every face: the candidates are the whole mesh."""
    return np.arange(0, n_faces * n_faces + 1, n_faces), np.tile(np.arange(n_faces), n_faces)


def test_plane_bound_changes_no_answer_and_matches_brute_force():
    # a uv ellipsoid (fans of thin triangles at the poles, cospherical rings) plus a sliver face's worth of
    # needles: points deep inside (many faces nearly equidistant), near the surface, and outside
    mesh = trimesh.creation.uv_sphere(radius=1.0, count=[24, 24])
    mesh.apply_scale([3.0, 1.0, 1.0])
    tri = np.asarray(mesh.triangles)
    corners = tuple(np.ascontiguousarray(tri[:, k]) for k in range(3))
    fd = face_data(*corners)
    assert (np.abs(fd[:, 13:16]).sum(axis=1) > 0).any()  # normals known somewhere ...
    rng = np.random.default_rng(3)
    q = np.concatenate([rng.uniform(-1, 1, (300, 3)) * [2.5, 0.6, 0.6],  # inside
                        np.asarray(mesh.vertices)[rng.choice(len(mesh.vertices), 200)] * rng.uniform(0.95, 1.05, (200, 1)),
                        rng.normal(size=(100, 3)) * 4.0])
    ring_ptr, ring_idx = _all_faces_ring(len(tri))
    near = np.zeros((len(q), 1), np.int64)
    with_plane = closest_on_candidates(q, fd, near, ring_ptr, ring_idx, face_scale(fd))
    without = fd.copy()
    without[:, 13:16] = 0.0  # no plane bounds anything: only bounding spheres skip faces
    plain = closest_on_candidates(q, without, near, ring_ptr, ring_idx, face_scale(fd))
    for a, b in zip(with_plane, plain):
        assert np.array_equal(a, b)
    assert np.allclose(with_plane[0], closest_point_reference(q, tri), rtol=0, atol=1e-12)


def test_thin_faces_get_no_plane():
    # a needle (angle ~1e-6 at its first corner) and a proper triangle
    a = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    b = np.array([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    c = np.array([[1.0, 1e-6, 0.0], [0.0, 1.0, 0.0]])
    fd = face_data(a, b, c)
    assert np.array_equal(fd[0, 13:16], [0.0, 0.0, 0.0])
    assert np.allclose(fd[1, 13:16], [0.0, 0.0, 1.0])  # (b - a) x (c - a), unit
