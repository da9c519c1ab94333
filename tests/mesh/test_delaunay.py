"""The compiled 3D Delaunay tetrahedralisation, checked against SciPy's Qhull and geometry.

On points in general position the tetrahedra must be SciPy's. On degenerate
inputs (lattices, spheres, grids on the faces of a box, a cylinder, a torus)
Delaunay tetrahedralisations are not unique, so the truth is geometric: the
tetrahedra tile the convex hull (volume and area of ``scipy.spatial.ConvexHull``),
are positively oriented, are glued face to face, and have empty circumspheres.
The predicates are checked against exact rational arithmetic.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import trimesh
from scipy.spatial import ConvexHull, Delaunay, cKDTree

from medialaxis.errors import ComputationError, InvalidInputError
from medialaxis.mesh.sample._predicates import GRID_BITS, _insphere, _orient
from medialaxis.mesh.sample.delaunay import JOGGLE, _delaunay, delaunay_tetrahedra

#: Vertices of the face opposite vertex k.
FACES = np.array([[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]])


def _det(points: np.ndarray, simplices: np.ndarray) -> np.ndarray:
    p = points[simplices]
    return np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))


def _longest_edge(points: np.ndarray, simplices: np.ndarray) -> np.ndarray:
    p = points[simplices]
    return np.linalg.norm(p[:, [1, 2, 3, 2, 3, 3]] - p[:, [0, 0, 0, 1, 1, 2]], axis=2).max(axis=1)


def check_tetrahedralisation(points, simplices, neighbors, hull, empty_tol=1e-7):
    """Every property of a Delaunay tetrahedralisation of ``points`` that does not depend on tie-breaking."""
    points = np.asarray(points, np.float64)
    t = len(simplices)
    assert simplices.dtype == neighbors.dtype == hull.dtype == np.int64
    assert simplices.shape == (t, 4) and neighbors.shape == (t, 4) and hull.shape[1] == 3
    assert (np.sort(simplices, axis=1)[:, 1:] != np.sort(simplices, axis=1)[:, :-1]).all()
    extent = float(np.ptp(points, axis=0).max())
    det = _det(points, simplices)
    longest = _longest_edge(points, simplices)

    # positively oriented, up to the joggle (each point moves by at most JOGGLE * extent per coordinate)
    assert (det > -20 * JOGGLE * extent * longest**2).all()

    # they tile the convex hull
    ch = ConvexHull(points)
    assert det.sum() / 6.0 == pytest.approx(ch.volume, rel=1e-9)

    # glued face to face: symmetric neighbours sharing the three vertices of the face
    i, k = np.nonzero(neighbors >= 0)
    j = neighbors[i, k]
    back = neighbors[j] == i[:, None]
    assert (back.sum(axis=1) == 1).all()
    k2 = back.argmax(axis=1)
    face_i = np.sort(simplices[i[:, None], FACES[k]], axis=1)
    face_j = np.sort(simplices[j[:, None], FACES[k2]], axis=1)
    np.testing.assert_array_equal(face_i, face_j)
    assert (simplices[i, k] != simplices[j, k2]).all()
    # every face is shared by two tetrahedra or on the hull, once
    all_faces = np.sort(simplices[:, FACES].reshape(-1, 3), axis=1)
    _, counts = np.unique(all_faces, axis=0, return_counts=True)
    assert counts.max() <= 2

    # the hull: the faces with no neighbour, outward, with ConvexHull's area
    ih, kh = np.nonzero(neighbors < 0)
    open_faces = np.sort(simplices[ih[:, None], FACES[kh]], axis=1)
    assert len(hull) == len(open_faces)
    np.testing.assert_array_equal(np.unique(np.sort(hull, axis=1), axis=0), np.unique(open_faces, axis=0))
    a, b, c = points[hull[:, 0]], points[hull[:, 1]], points[hull[:, 2]]
    normal = np.cross(b - a, c - a)
    assert 0.5 * np.linalg.norm(normal, axis=1).sum() == pytest.approx(ch.area, rel=1e-9)
    assert (np.einsum("ij,ij->i", normal, points.mean(axis=0) - a) <= 1e-9 * extent**3).all()

    # empty circumspheres (flat tetrahedra, four co-circular points, have none)
    solid = np.abs(det) > 1e-9 * longest**3
    p = points[simplices[solid]]
    rows = p[:, 1:] - p[:, :1]
    offset = np.linalg.solve(rows, 0.5 * (rows**2).sum(axis=2)[..., None])[..., 0]
    radius = np.linalg.norm(offset, axis=1)
    nearest, _ = cKDTree(points).query(p[:, 0] + offset)
    assert (nearest >= radius * (1.0 - empty_tol)).all()

    # every distinct point is a vertex, and only one of each group of duplicates
    _, first = np.unique(points, axis=0, return_index=True)
    used = np.zeros(len(points), bool)
    used[simplices.ravel()] = True
    assert used[first].all()
    assert used.sum() == len(first)
    return det


# ----------------------------------------------------------------------------
# inputs
# ----------------------------------------------------------------------------


def lattice(n: int) -> np.ndarray:
    g = np.arange(float(n))
    return np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)


def fibonacci_sphere(n: int) -> np.ndarray:
    i = np.arange(n) + 0.5
    phi = np.arccos(1.0 - 2.0 * i / n)
    theta = np.pi * (1.0 + 5.0**0.5) * i
    return np.c_[np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)]


def box_surface_grid(k: int) -> np.ndarray:
    """A k x k grid on each face of the unit cube: the edges and corners are repeated (duplicates)."""
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(0.0, 1.0, k), np.linspace(0.0, 1.0, k)))
    faces = []
    for axis in range(3):
        for value in (0.0, 1.0):
            f = np.empty((len(u), 3))
            f[:, axis], f[:, (axis + 1) % 3], f[:, (axis + 2) % 3] = value, u, v
            faces.append(f)
    return np.concatenate(faces)


def cylinder_grid(sections: int, rings: int) -> np.ndarray:
    theta, z = np.meshgrid(np.linspace(0.0, 2 * np.pi, sections, endpoint=False), np.linspace(0.0, 1.0, rings))
    return np.c_[np.cos(theta.ravel()), np.sin(theta.ravel()), z.ravel()]


def torus_grid(major: int, minor: int) -> np.ndarray:
    theta, phi = np.meshgrid(
        np.linspace(0.0, 2 * np.pi, major, endpoint=False), np.linspace(0.0, 2 * np.pi, minor, endpoint=False)
    )
    ring = 1.0 + 0.35 * np.cos(phi.ravel())
    return np.c_[ring * np.cos(theta.ravel()), ring * np.sin(theta.ravel()), 0.35 * np.sin(phi.ravel())]


DEGENERATE = {
    "lattice 12^3": lambda: lattice(12),
    "uv sphere": lambda: np.asarray(trimesh.creation.uv_sphere(count=[32, 32]).vertices),
    "fibonacci sphere": lambda: fibonacci_sphere(2000),
    "box surface grid": lambda: box_surface_grid(15),
    "cylinder grid": lambda: cylinder_grid(40, 20),
    "torus grid": lambda: torus_grid(48, 24),
    "box surface samples": lambda: np.asarray(trimesh.creation.box().sample(3000, seed=0)),
}


# ----------------------------------------------------------------------------
# tests
# ----------------------------------------------------------------------------


def _adjacency(simplices, neighbors):
    key = [tuple(s) for s in np.sort(simplices, axis=1)]
    return {(key[i], simplices[i, k], key[n] if n >= 0 else None) for (i, k), n in np.ndenumerate(neighbors)}


def test_random_points_give_scipys_tetrahedra():
    points = np.random.default_rng(0).random((2000, 3))
    simplices, neighbors, hull = delaunay_tetrahedra(points)
    ref = Delaunay(points)
    ours = {tuple(s) for s in np.sort(simplices, axis=1)}
    assert ours == {tuple(s) for s in np.sort(ref.simplices, axis=1)}
    # the same neighbours: (tetrahedron, vertex, tetrahedron across the face opposite that vertex)
    assert _adjacency(simplices, neighbors) == _adjacency(ref.simplices, ref.neighbors)
    det = check_tetrahedralisation(points, simplices, neighbors, hull, empty_tol=1e-12)
    assert (det > 0).all()
    assert len(hull) == len(ConvexHull(points).simplices)


@pytest.mark.parametrize("name", sorted(DEGENERATE))
def test_degenerate_inputs_give_a_delaunay_tiling_of_the_hull(name):
    points = DEGENERATE[name]()
    simplices, neighbors, hull = delaunay_tetrahedra(points)
    check_tetrahedralisation(points, simplices, neighbors, hull)


@pytest.mark.parametrize("name", ["lattice 12^3", "box surface grid"])
def test_flat_tetrahedra_are_positive_on_the_joggled_points(name):
    # flat on the input (four co-planar points), but exactly positively oriented on the points triangulated
    simplices, _, _, info = _delaunay(DEGENERATE[name]())
    joggled = info["joggled"]
    flat = simplices[_det(joggled, simplices) < 1e-12]
    assert len(flat) > 100
    assert all(_exact_orient(joggled[s]) == 1 for s in flat)


def test_no_point_is_moved_or_left_out_of_a_cavity_with_the_joggle():
    # the fallbacks exist for exact ties; with the joggle and exact predicates they are never needed
    for name in ("torus grid", "lattice 12^3", "box surface grid"):
        info = _delaunay(DEGENERATE[name]())[3]
        assert (info["moved"], info["shrunk"], info["retries"]) == (0, 0, 0), name


@pytest.mark.parametrize("name", ["lattice 12^3", "uv sphere", "box surface grid", "torus grid"])
def test_without_joggle_the_fallbacks_keep_a_valid_tiling(name):
    # exact ties everywhere: points are moved and cavities shrunk, the tiling must stay valid
    points = DEGENERATE[name]()
    simplices, neighbors, hull, info = _delaunay(points, joggle=0.0)
    assert info["moved"] + info["shrunk"] > 0
    check_tetrahedralisation(points, simplices, neighbors, hull, empty_tol=np.inf)


def test_duplicates_keep_the_first_point():
    rng = np.random.default_rng(1)
    base = rng.random((300, 3))
    base[0] = (0.0, 0.5, 0.5)
    points = np.concatenate([base, base[:50], [(-0.0, 0.5, 0.5)]])
    simplices, neighbors, hull = delaunay_tetrahedra(points)
    used = np.unique(simplices)
    np.testing.assert_array_equal(used, np.arange(300))
    reference, *_ = delaunay_tetrahedra(base)
    assert {tuple(s) for s in np.sort(simplices, axis=1)} == {tuple(s) for s in np.sort(reference, axis=1)}


def test_growing_the_arrays_changes_nothing(monkeypatch):
    import medialaxis.mesh.sample.delaunay as kernels

    points = np.asarray(trimesh.creation.uv_sphere(count=[24, 24]).vertices)
    expected = delaunay_tetrahedra(points)
    monkeypatch.setattr(kernels, "_SLOTS_PER_POINT", 0.1)
    monkeypatch.setattr(kernels, "_BUFFER", 2)
    monkeypatch.setattr(kernels, "_HASH", 4)
    simplices, neighbors, hull = delaunay_tetrahedra(points)
    # the same tetrahedra (found from other places of the walk, so in another order)
    assert _adjacency(simplices, neighbors) == _adjacency(*expected[:2])
    assert {tuple(f) for f in np.sort(hull, axis=1)} == {tuple(f) for f in np.sort(expected[2], axis=1)}


def test_results_are_deterministic():
    points = box_surface_grid(9)
    first = delaunay_tetrahedra(points)
    second = delaunay_tetrahedra(points.copy())
    for a, b in zip(first, second):
        np.testing.assert_array_equal(a, b)


def test_scale_and_offset_do_not_change_the_tetrahedra():
    points = np.random.default_rng(2).random((500, 3))
    simplices, *_ = delaunay_tetrahedra(points)
    moved, *_ = delaunay_tetrahedra(points * 1e-3 + 10.0)
    assert {tuple(s) for s in np.sort(simplices, axis=1)} == {tuple(s) for s in np.sort(moved, axis=1)}


@pytest.mark.parametrize(
    "points, error",
    [
        (np.random.default_rng(0).random((4, 3)), ComputationError),
        (np.repeat(np.random.default_rng(0).random((4, 3)), 3, axis=0), ComputationError),
        (np.c_[np.random.default_rng(0).random((50, 2)), np.zeros(50)], ComputationError),
        (np.c_[box_surface_grid(5)[:, :2], np.full(150, 0.5)], ComputationError),
        (np.outer(np.linspace(0.0, 1.0, 20), [1.0, 2.0, 3.0]), ComputationError),
        (np.where(np.arange(30)[:, None] == 7, np.nan, np.random.default_rng(0).random((30, 3))), InvalidInputError),
        (np.where(np.arange(30)[:, None] == 7, np.inf, np.random.default_rng(0).random((30, 3))), InvalidInputError),
        (np.random.default_rng(0).random((30, 2)), InvalidInputError),
        (np.random.default_rng(0).random(30), InvalidInputError),
    ],
    ids=["4 points", "4 distinct points", "coplanar", "coplanar grid", "collinear", "nan", "inf", "2d", "1d"],
)
def test_bad_input_is_refused(points, error):
    with pytest.raises(error):
        delaunay_tetrahedra(points)


# ----------------------------------------------------------------------------
# predicates against exact rational arithmetic
# ----------------------------------------------------------------------------


def _exact_orient(p):
    a, b, c, d = ([Fraction(float(v)) for v in row] for row in p)
    u, v, w = ([q[i] - a[i] for i in range(3)] for q in (b, c, d))
    det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])
    return (det > 0) - (det < 0)


def _exact_insphere(p):
    """+1 if p[4] is inside the circumsphere of the positively oriented p[0:4], -1 outside, 0 on it."""
    q = [[Fraction(float(v)) for v in row] for row in p]
    rows = [[r[i] - q[4][i] for i in range(3)] for r in q[:4]]
    rows = [r + [sum(x * x for x in r)] for r in rows]

    def det(m):
        if len(m) == 1:
            return m[0][0]
        return sum((-1) ** j * m[0][j] * det([r[:j] + r[j + 1 :] for r in m[1:]]) for j in range(len(m)))

    d = det(rows)
    return -((d > 0) - (d < 0))


def _grid(x):
    scale = 2.0**GRID_BITS
    return np.rint(x * scale) / scale


def test_predicates_are_exact_on_ties_and_near_ties():
    rng = np.random.default_rng(3)
    cases = []
    for trial in range(300):
        kind = trial % 3
        if kind == 0:  # general position
            p = rng.uniform(-0.5, 0.5, (5, 3))
        elif kind == 1:  # on a sphere, or on a circle (co-planar and co-spherical), within 1e-13
            p = rng.normal(size=(5, 3))
            p = 0.3 * p / np.linalg.norm(p, axis=1)[:, None]
            if trial % 2:
                p[:, 2] = 0.1
            p += rng.uniform(-1e-13, 1e-13, (5, 3))
        else:  # exact ties on a small lattice
            p = rng.integers(-3, 4, (5, 3)) / 8.0
        cases.append(_grid(p))
    for p in cases:
        o = _exact_orient(p[:4])
        assert _orient(p, 0, 1, 2, 3) == o
        if o != 0:
            order = (0, 1, 2, 3, 4) if o > 0 else (1, 0, 2, 3, 4)
            assert _insphere(p, *order) == _exact_insphere(p[list(order)])
