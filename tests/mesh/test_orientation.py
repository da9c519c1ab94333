"""Consistent face winding (:func:`~medialaxis.mesh.solid.orientation.fix_winding`).

Faces of known surfaces are turned at random; the answer is known: each
component back as it was when fewer than half its faces were turned, all of
it the other way round otherwise. trimesh's ``fix_winding`` is the peer: the
same faces up to turning a whole component (it keeps the way its walk's
first face runs).
"""

from __future__ import annotations

import numpy as np
import pytest

from medialaxis.mesh.solid.orientation import fix_winding

trimesh = pytest.importorskip("trimesh")


def _turned(faces: np.ndarray, share: float, seed: int) -> tuple[np.ndarray, np.ndarray]:
    which = np.random.default_rng(seed).random(len(faces)) < share
    out = faces.copy()
    out[which] = faces[which][:, ::-1]
    return out, which


@pytest.mark.parametrize("share", [0.05, 0.3, 0.45])
def test_a_sphere_with_some_faces_turned_comes_back_as_it_was(share):
    sphere = trimesh.creation.icosphere(3)
    faces, which = _turned(np.asarray(sphere.faces), share, 1)
    mesh = trimesh.Trimesh(sphere.vertices, faces, process=False)
    assert fix_winding(mesh) == which.sum()
    np.testing.assert_array_equal(mesh.faces, sphere.faces)
    assert mesh.is_winding_consistent and mesh.volume > 0


def test_each_component_keeps_the_way_most_of_its_faces_run():
    sphere = trimesh.creation.icosphere(2)
    torus = trimesh.creation.torus(2.0, 0.5, major_sections=24, minor_sections=12).apply_translation((6.0, 0, 0))
    both = trimesh.util.concatenate([sphere, torus])
    faces, _ = _turned(np.asarray(both.faces), 0.2, 2)
    k = len(sphere.faces)
    faces[:k] = faces[:k, ::-1]  # the sphere: 80% of its faces now run the other way
    mesh = trimesh.Trimesh(both.vertices, faces, process=False)
    fix_winding(mesh)
    np.testing.assert_array_equal(mesh.faces[:k], np.asarray(both.faces)[:k, ::-1])  # all of it inward
    np.testing.assert_array_equal(mesh.faces[k:], np.asarray(both.faces)[k:])
    assert mesh.is_winding_consistent


def test_the_same_as_trimesh_up_to_whole_components():
    torus = trimesh.creation.torus(2.0, 0.5, major_sections=32, minor_sections=16)
    open_torus = np.asarray(torus.faces)[np.random.default_rng(4).random(len(torus.faces)) > 0.02]  # holes
    faces, _ = _turned(open_torus, 0.35, 3)
    ours = trimesh.Trimesh(torus.vertices, faces, process=False)
    peer = ours.copy()
    fix_winding(ours)
    trimesh.repair.fix_winding(peer)
    assert ours.is_winding_consistent and peer.is_winding_consistent
    same, reversed_ = (np.array_equal(ours.faces, peer.faces),
                       np.array_equal(np.asarray(ours.faces), np.asarray(peer.faces)[:, ::-1]))
    assert same or reversed_


def test_a_moebius_band_is_walked_and_left_with_one_seam():
    # not orientable: whatever the walk, some pair of neighbours disagrees; the rest agree
    angles, across = np.linspace(0, 2 * np.pi, 41)[:-1], (-0.3, 0.0, 0.3)
    points = np.array([[(1 + s * np.cos(a / 2)) * np.cos(a), (1 + s * np.cos(a / 2)) * np.sin(a), s * np.sin(a / 2)]
                       for a in angles for s in across])
    faces = []
    for i in range(40):
        for j in range(2):
            a0, a1 = 3 * i + j, 3 * i + j + 1
            b0, b1 = (3 * (i + 1) + j, 3 * (i + 1) + j + 1) if i < 39 else (2 - j, 1 - j)  # the half twist
            faces += [[a0, b0, a1], [a1, b0, b1]]
    mesh = trimesh.Trimesh(points, _turned(np.array(faces), 0.4, 5)[0], process=False)
    fix_winding(mesh)
    f = np.asarray(mesh.faces)

    def directed(t):
        return {(int(t[k]), int(t[(k + 1) % 3])) for k in range(3)}

    disagree = sum(bool(directed(f[a]) & directed(f[b])) for a, b in np.asarray(mesh.face_adjacency))  # same way
    assert not mesh.is_winding_consistent
    assert 1 <= disagree <= 2  # one seam across the band


def test_faces_over_the_same_corners_are_left_to_trimesh():
    # a pillow of two faces over three corners, both given the same way: which edge they share is not defined
    mesh = trimesh.Trimesh(np.eye(3), np.array([[0, 1, 2], [0, 1, 2]]), process=False)
    assert len(mesh.face_adjacency) and not mesh.is_winding_consistent
    assert fix_winding(mesh) == 1
    assert mesh.is_winding_consistent
