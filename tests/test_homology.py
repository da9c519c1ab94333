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


def _dense_betti(n_points, edges, faces):
    """Ranks of the full boundary matrices over GF(2) by dense elimination: an independent count."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    spans = [tuple(sorted(e)) for e in np.asarray(edges).reshape(-1, 2).tolist()]
    spans += [tuple(sorted((f[i], f[(i + 1) % 3]))) for f in np.asarray(faces).reshape(-1, 3).tolist() for i in range(3)]
    all_edges = sorted({e for e in spans if e[0] != e[1]})  # a triangle with a point twice is an edge
    faces = [f for f in np.asarray(faces).tolist() if len(set(f)) == 3]
    index = {e: i for i, e in enumerate(all_edges)}
    matrix = np.zeros((len(faces), len(all_edges)), np.uint8)
    for row, f in enumerate(faces):
        for i in range(3):
            matrix[row, index[tuple(sorted((f[i], f[(i + 1) % 3])))]] ^= 1
    rank, m = 0, matrix.copy()
    for col in range(m.shape[1]):
        hit = np.flatnonzero(m[rank:, col]) + rank
        if not len(hit):
            continue
        m[[rank, hit[0]]] = m[[hit[0], rank]]
        below = np.flatnonzero(m[:, col])
        m[below[below != rank]] ^= m[rank]
        rank += 1
    e = np.array(all_edges, int).reshape(-1, 2)
    b0 = connected_components(coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n_points, n_points)))[0]
    return int(b0), len(all_edges) - n_points + int(b0) - rank, len(faces) - rank


@pytest.mark.parametrize("seed", range(12))
def test_betti_numbers_match_dense_elimination(seed):
    """Closed surfaces glued along junction edges, pieces of them, stray triangles (some with a point
    repeated), duplicates and loose edges: the same numbers as the full boundary matrix's ranks."""
    rng = np.random.default_rng(seed)
    sphere = np.asarray(trimesh.creation.icosphere(1).faces)
    torus = np.asarray(trimesh.creation.torus(2.0, 0.5, major_sections=8, minor_sections=5).faces)
    parts, n = [], 0
    for _ in range(rng.integers(2, 5)):
        piece = sphere if rng.random() < 0.5 else torus
        piece = piece[rng.random(len(piece)) < 0.97] if rng.random() < 0.4 else piece  # a few holes
        shift = n - rng.integers(0, 4) if n else 0  # share up to 3 points with the part before
        parts.append(piece + shift)
        n = max(n, int(piece.max()) + shift + 1)
    stray = rng.integers(0, n + 5, size=(rng.integers(0, 30), 3))  # junctions, flat triangles
    faces = np.concatenate(parts + [stray, parts[0][:rng.integers(0, 3)]])
    n += 5
    edges = rng.integers(0, n, size=(rng.integers(0, 20), 2))
    assert betti_numbers(n, edges, faces) == _dense_betti(n, edges, faces)
    cut = void_faces(n, edges, faces)
    b0, b1, b2 = _dense_betti(n, edges, faces)
    assert len(cut) == b2
    assert betti_numbers(n, edges, np.delete(faces, cut, axis=0)) == (b0, b1, 0)


def test_betti_numbers_of_a_complex_with_large_closed_sheets_stay_small_in_memory():
    """Nested closed sheets of 20,000 faces each under a sheet with edge indices in the millions: the
    elimination on faces kept one integer per row as wide as the highest edge index (gigabytes)."""
    import tracemalloc

    sphere = trimesh.creation.icosphere(6)  # 81,920 faces
    faces = np.asarray(sphere.faces)
    n = len(sphere.vertices)
    shells = np.concatenate([faces + k * n for k in range(3)])
    tracemalloc.start()
    assert betti_numbers(3 * n, NO_EDGES, shells) == (3, 0, 3)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak < 200e6
