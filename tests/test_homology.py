"""Betti numbers of complexes against exact answers."""

import numpy as np
import pytest
import trimesh

from medialaxis.core.homology import betti_numbers, void_faces

NO_EDGES = np.empty((0, 2), int)


@pytest.mark.parametrize("make,expected", [
    (lambda: trimesh.creation.icosphere(2), (1, 0, 1)),
    (lambda: trimesh.creation.torus(2.0, 0.5, major_sections=12, minor_sections=6), (1, 2, 1)),
    (lambda: trimesh.creation.box(), (1, 0, 1)),
])
def test_closed_surfaces(make, expected):
    mesh = make()
    assert betti_numbers(len(mesh.vertices), NO_EDGES, mesh.faces) == expected


def test_open_surfaces_and_pieces():
    torus = trimesh.creation.torus(2.0, 0.5, major_sections=12, minor_sections=6)
    faces = np.asarray(torus.faces)
    n = len(torus.vertices)
    assert betti_numbers(n, NO_EDGES, faces[1:]) == (1, 2, 0)  # a punctured torus
    sphere = trimesh.creation.icosphere(1)
    annulus = sphere.faces[np.abs(sphere.triangles_center[:, 2]) < 0.5]  # a band round the equator
    assert betti_numbers(len(sphere.vertices), NO_EDGES, annulus)[1:] == (1, 0)
    two = np.concatenate([faces, faces + n])
    assert betti_numbers(2 * n + 3, NO_EDGES, two) == (5, 4, 2)  # two tori and three lone points


def test_sheets_with_curves_and_junctions():
    # three triangles on one edge (a junction line), a tail, and a loop of edges
    faces = np.array([[0, 1, 2], [0, 1, 3], [0, 1, 4]])
    edges = np.array([[4, 5], [5, 6], [6, 7], [7, 8], [8, 6]])
    assert betti_numbers(9, edges, faces) == (1, 1, 0)
    # the same loop filled by a fan of triangles
    filled = np.concatenate([faces, [[6, 7, 8]]])
    assert betti_numbers(9, edges, filled) == (1, 0, 0)


def test_void_faces_open_every_void_and_keep_the_rest():
    # a torus surface (b1 = 2, b2 = 1), two spheres sharing a vertex (a wedge: b2 = 2) and a
    # triangle loop of edges (b1 = 1): truth from the pieces' own construction
    torus = trimesh.creation.torus(2.0, 0.5, major_sections=12, minor_sections=6)
    sphere = np.asarray(trimesh.creation.icosphere(1).faces)
    n_t, n_s = len(torus.vertices), int(sphere.max()) + 1
    second = sphere + n_t + n_s - 1  # its vertex 0 is the first sphere's last vertex
    faces = np.concatenate([torus.faces, sphere + n_t, second])
    start = int(faces.max()) + 1
    loop = np.array([[start, start + 1], [start + 1, start + 2], [start + 2, start]])
    n = start + 3
    assert betti_numbers(n, loop, faces) == (3, 3, 3)
    cut = void_faces(n, loop, faces)
    assert len(cut) == 3
    assert betti_numbers(n, loop, np.delete(faces, cut, axis=0)) == (3, 3, 0)
