"""The inner tetrahedra of the Voronoi route: sides checked against the nearest sample, buried samples opened, small cavities filled."""

from __future__ import annotations

import numpy as np
import trimesh
from scipy.spatial import cKDTree

import medialaxis as mx
from medialaxis.mesh.medial._voronoi_kernels import nearest_other_sample, small_cavities
from medialaxis.mesh.medial.voronoi_complex import medial_complex, open_cells
from medialaxis.mesh.medial.voronoi_diagram import tetrahedralise
from medialaxis.mesh.sample.signed_distance import SignedDistance


def _u_shape() -> trimesh.Trimesh:
    """A U of three boxes (two arms 1 apart over a base), one closed surface."""
    boxes = []
    for lo, hi in (((0, 0, 0), (3, 1.2, 1)), ((0, 1, 0), (1, 4, 1)), ((2, 1, 0), (3, 4, 1))):
        boxes.append(trimesh.creation.box(bounds=np.array([lo, hi], float)))
    return trimesh.boolean.union(boxes, engine="manifold")


def test_nearest_other_sample_is_the_kd_tree_nearest():
    rng = np.random.default_rng(3)
    points = rng.random((3000, 3))
    dt = tetrahedralise(points)
    queries = rng.dirichlet(np.ones(4) * 0.3, len(dt.simplices))  # centroid-like and near-corner points
    queries = np.einsum("tk,tkd->td", queries, points[dt.simplices])
    got = nearest_other_sample(queries, dt.points, dt.simplices, dt.centres, dt.radii)
    dist, truth = cKDTree(points).query(queries)
    own = (dt.simplices == truth[:, None]).any(1)
    np.testing.assert_array_equal(got[~own], truth[~own])
    assert (got[own] == -1).all()
    assert (~own).sum() > 100  # the walk was exercised
    # where the four tangent planes agree with the side already found there is nothing to walk for
    flat = np.zeros_like(points)
    skipped = nearest_other_sample(queries, dt.points, dt.simplices, dt.centres, dt.radii, flat, -np.ones(len(queries)))
    assert (skipped == -1).all()


def test_a_point_beside_the_wrong_faces_gets_its_side_from_the_nearest_sample():
    mesh = _u_shape()
    assert mesh.is_watertight
    sd = SignedDistance(mesh)
    # in the gap of the U (outside), but asked about the faces of the left arm's outer side (x = 0)
    query = np.array([[1.3, 2.5, 0.5], [1.5, 3.0, 0.2], [0.5, 2.5, 0.5]])
    outer_left = np.flatnonzero(np.isclose(mesh.triangles_center[:, 0], 0.0))
    near = np.tile(outer_left[:3], (len(query), 1))
    signed, _ = sd.query(query, near, rings=False)
    assert signed[0] < 0 and signed[1] < 0  # the local search alone takes the gap for the inside
    samples, faces = trimesh.sample.sample_surface_even(mesh, 4000, seed=1)
    _, nearest = cKDTree(samples).query(query)
    sd.recheck_sides(query, signed, nearest, np.asarray(samples), np.asarray(faces, np.int64))
    np.testing.assert_array_equal(signed < 0, mesh.contains(query))


def test_a_buried_sample_does_not_close_a_void():
    # a sphere's samples and its centre: every tetrahedron is inside, the centre's Voronoi cell is closed
    sphere = trimesh.creation.icosphere(3)
    points = np.vstack([sphere.vertices, [[0.0, 0.0, 0.0]]])
    dt = tetrahedralise(points)
    inner = np.ones(len(dt.simplices), bool)
    cx = medial_complex(dt, inner, lambda t: np.ones(len(t), bool), lam=1e-9)
    faces = cx.faces
    edges = np.unique(np.sort(np.r_[faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [0, 2]], cx.edges], 1), axis=0)
    n_points = len(np.unique(np.r_[faces.ravel(), cx.edges.ravel()]))
    assert n_points - len(edges) + len(faces) == 1  # a ball is contractible: no void left
    from medialaxis.mesh.medial.voronoi_diagram import edge_rings

    edge_ij, ring_ptr, ring_tets, length = edge_rings(dt, np.arange(len(dt.simplices)), 0.0)
    dropped = open_cells(dt, inner, edge_ij, np.ones(len(edge_ij), bool), length)
    assert dropped.sum() == 1 and (edge_ij[dropped] == len(points) - 1).any()


def test_a_cavity_of_one_tetrahedron_is_found_by_its_volume():
    rng = np.random.default_rng(5)
    dt = tetrahedralise(rng.random((400, 3)))
    hull = (dt.neighbors < 0).any(1)
    deep = np.flatnonzero(~hull & ~hull[dt.neighbors].any(1))[0]  # no neighbour on the hull either
    inner = np.ones(len(dt.simplices), bool)
    inner[deep] = False
    inner[np.flatnonzero(hull)[0]] = False  # an outer tetrahedron on the hull is no cavity
    share = dt.volume[deep] / dt.longest[deep] ** 3
    assert np.flatnonzero(small_cavities(dt.neighbors, inner, dt.volume, dt.longest, 1.01 * share)).tolist() == [deep]
    assert not small_cavities(dt.neighbors, inner, dt.volume, dt.longest, 0.99 * share).any()


def test_a_noisy_uv_ellipsoid_has_no_cavity():
    # a uv ellipsoid (160 x 160, 3:1:1) whose vertices moved along it by a tenth of their shortest edge:
    # sliver tetrahedra on the crowded pole caps, a hair outside and enclosed by others a hair inside,
    # were 5 cavities of the medial complex; the solid (a ball, by the mesh's own Euler characteristic) has none
    mesh = trimesh.creation.uv_sphere(radius=1.0, count=[160, 160])
    mesh.apply_scale([3.0, 1.0, 1.0])
    rng = np.random.default_rng(0)
    shortest = np.full(len(mesh.vertices), np.inf)
    for k in range(2):
        np.minimum.at(shortest, mesh.edges_unique[:, k], mesh.edges_unique_length)
    move = rng.normal(size=mesh.vertices.shape) * 0.1 * shortest[:, None]
    move -= np.einsum("ij,ij->i", move, mesh.vertex_normals)[:, None] * mesh.vertex_normals
    noisy = trimesh.Trimesh(mesh.vertices + move, mesh.faces, process=False)
    assert noisy.is_watertight and noisy.euler_number == 2
    ma = mx.medial_axis(noisy, method="voronoi", compact=False)
    # and a handle of flat tetrahedra on a pole cap was left as a loop of curves from the axis up to the
    # surface and back (through circumcentres far outside): cut, as the solid has no handle
    assert ma.betti == (1, 0, 0)
    assert ma.metadata["euler_characteristic"] == 1 and ma.metadata["n_cut_cycles"] >= 1
    # what is left is the axis: the segment |x| <= 8/3 on the x axis, up to the sampling
    x = np.clip(ma.points[:, 0], -8 / 3, 8 / 3)
    assert np.max(np.hypot(np.hypot(ma.points[:, 0] - x, ma.points[:, 1]), ma.points[:, 2])) < 0.05
