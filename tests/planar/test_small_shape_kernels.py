"""The compiled kernels of the small-shape speed work against their pure-Python/NumPy references."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
import shapely
from PIL import Image
from shapely.geometry import MultiPolygon, Point, box

from medialaxis.planar._inside_kernels import UNSURE, RegionLocator, locate_points, locate_points_reference
from medialaxis.planar._kernels import circumcircles_kernel
from medialaxis.planar.delaunay import circumcircles
from medialaxis.planar.reading._contour_kernels import contour_rings, mask_contours_reference

KIMIA = Path(__file__).resolve().parents[1] / "data" / "kimia99"


def _masks() -> list[np.ndarray]:
    rng = np.random.default_rng(3)
    masks = [rng.random((40, 57)) > p for p in (0.2, 0.5, 0.8) for _ in range(5)]
    masks += [np.asarray(Image.open(f)).astype(bool) for f in sorted(KIMIA.glob("*.png"))[::9]]
    rows, cols = np.mgrid[:64, :80]
    masks.append((rows - 30) ** 2 + (cols - 40) ** 2 < 20**2)
    return [np.pad(m, 1) for m in masks]


@pytest.mark.parametrize("view", ["bool", "bytes of 255"])
def test_mask_contours_are_scikit_images_point_for_point(view: str) -> None:
    for mask in _masks():
        image = mask.view(np.uint8) * np.uint8(255 if view == "bytes of 255" else 1)
        ours, theirs = contour_rings(image), mask_contours_reference(image)
        assert len(ours) == len(theirs)
        for a, b in zip(ours, theirs):
            np.testing.assert_array_equal(a, b)


def test_region_locator_gives_shapelys_answers() -> None:
    ring = Point(0, 0).buffer(1.0, 64).difference(Point(0.3, 0).buffer(0.3, 32))
    region = MultiPolygon([ring, box(2, -0.5, 3, 0.5)])
    locator = RegionLocator(region)
    rng = np.random.default_rng(0)
    xy = rng.uniform(-1.2, 3.2, (4000, 2))
    # on the boundary and at vertices: unsure, answered by GEOS
    xy = np.vstack([xy, shapely.get_coordinates(region), [[2.0, 0.0], [2.5, 0.5], [3.0, 0.1]]])
    expected = shapely.contains_xy(region, xy[:, 0], xy[:, 1])
    np.testing.assert_array_equal(locator.contains(xy[:, 0], xy[:, 1]), expected)
    reference = locate_points_reference(xy[:, 0], xy[:, 1], locator.segments)
    ours = locate_points(xy[:, 0], xy[:, 1], locator.segments, locator.start, locator.members, locator.y0,
                         locator.height)
    np.testing.assert_array_equal(ours, reference)
    assert (ours[reference != UNSURE] == expected[reference != UNSURE]).all()
    assert (reference[-3:] == UNSURE).all()


def test_circumcircles_kernel_is_the_numpy_version_bit_for_bit() -> None:
    rng = np.random.default_rng(1)
    points = rng.random((500, 2))
    points[5] = 0.5 * (points[6] + points[7])  # a collinear triangle
    simplices = rng.integers(0, 500, (3000, 3))
    simplices[0] = [5, 6, 7]
    simplices[1, 2] = simplices[1, 1]  # a repeated vertex
    for ours, ref in zip(circumcircles_kernel(points, simplices), circumcircles(points, simplices)):
        np.testing.assert_array_equal(ours, ref)


def _raw_axes() -> list[tuple[np.ndarray, np.ndarray, float]]:
    """Unpruned axes of a few shapes, with their merge tolerance."""
    from medialaxis.planar.axis import raw_axis
    from medialaxis.planar.pipeline import planar_stages

    rows, cols = np.mgrid[:80, :90]
    shapes = [box(0, 0, 4, 2), Point(0, 0).buffer(1.0, 64), (rows - 40) ** 2 + (cols - 45) ** 2 < 30**2,
              Point(0, 0).buffer(1.0).difference(Point(0.2, 0).buffer(0.3))]
    shapes += [np.asarray(Image.open(f)).astype(bool) for f in sorted(KIMIA.glob("*.png"))[::11]]
    out = []
    for shape in shapes:
        st = planar_stages(shape)
        ax = raw_axis(st.triangulation, st.inside, st.samples, st.rings.region)
        out.append((ax.points, ax.edges, float(st.raw.metadata["tolerance"])))
    return out


def test_merge_and_regrow_kernels_match_their_references() -> None:
    from medialaxis.planar.pruning import regrow_tips, regrow_tips_reference
    from tests.planar.merging import merge_close_nodes, merge_close_nodes_reference

    rng = np.random.default_rng(2)
    for points, edges, tolerance in _raw_axes():
        for scale in (1.0, 5.0, 50.0):  # more and larger clusters, some with cycles
            ours = merge_close_nodes(points, edges, scale * tolerance)
            ref = merge_close_nodes_reference(points, edges, scale * tolerance)
            for a, b in zip(ours, ref):
                np.testing.assert_array_equal(a, b)
        for _ in range(5):
            keep = rng.random(len(edges)) < 0.3
            growable = rng.random(len(edges)) < 0.7
            np.testing.assert_array_equal(regrow_tips(len(points), edges, keep, growable),
                                          regrow_tips_reference(len(points), edges, keep, growable))


def test_component_labels_group_as_scipy_does() -> None:
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    from medialaxis.planar._graph_kernels import component_labels

    rng = np.random.default_rng(4)
    n = 300
    edges = rng.integers(0, n, (200, 2))
    ours = component_labels(n, edges, np.ones(len(edges), np.bool_))
    _, theirs = connected_components(coo_matrix((np.ones(200), (edges[:, 0], edges[:, 1])), shape=(n, n)),
                                     directed=False)
    # the same partition: each label of one maps to one label of the other
    pairs = set(zip(ours.tolist(), theirs.tolist()))
    assert len(pairs) == len(set(ours.tolist())) == len(set(theirs.tolist()))


def test_refine_kernel_matches_its_reference() -> None:
    from medialaxis.planar.boundary.sampling import (
        initial_arcs,
        refine_arcs,
        refine_arcs_reference,
        sample,
        simplify_rings,
    )

    rng = np.random.default_rng(5)
    region = MultiPolygon([Point(0, 0).buffer(1.0, 16).difference(Point(0.2, 0).buffer(0.3, 8)),
                           box(2, 0, 3, 0.001)])
    rings = simplify_rings(region, 0.0)
    arcs = initial_arcs(rings, 0.05)
    arcs[0] = np.sort(np.r_[arcs[0], rng.uniform(0, arcs[0][-1], 50)])  # positions inside and at vertices
    for _ in range(3):
        ours = sample(rings, arcs)
        radius = rng.uniform(0.01, 2.0, len(ours.points))
        radius[::7] = np.inf
        conforming = rng.random(len(ours.points)) < 0.9
        new, new_ref = (f(arcs, ours, radius, conforming, 1e-3, 1e-3) for f in (refine_arcs, refine_arcs_reference))
        assert len(new) == len(new_ref)
        for a, b in zip(new, new_ref):
            np.testing.assert_array_equal(a, b)
        arcs = new
    assert refine_arcs(arcs, sample(rings, arcs), np.full(sum(map(len, arcs)), np.inf),
                       np.ones(sum(map(len, arcs)), bool), 1e-3, 1e-3) is None


def test_inner_triangles_by_the_locator_are_shapelys() -> None:
    from medialaxis.planar.axis import inner_triangles
    from medialaxis.planar.delaunay import triangulate

    region = Point(0, 0).buffer(1.0, 32).difference(Point(0.3, 0).buffer(0.3, 16))
    rng = np.random.default_rng(6)
    points = np.vstack([shapely.get_coordinates(region), rng.uniform(-1, 1, (300, 2))])
    tri = triangulate(points)
    np.testing.assert_array_equal(inner_triangles(tri, region, RegionLocator(region)), inner_triangles(tri, region))


def _bumpy_square() -> Any:
    """A square of dense edges with a bump lower than the tolerance, and a small octagonal hole in the bump."""
    from shapely.geometry import Polygon

    side = np.linspace(0, 10, 201)[:-1]
    bottom = np.c_[side, np.where(np.abs(side - 5) < 1, -0.008 * (1 - np.abs(side - 5)), 0.0)]
    outer = np.vstack([bottom, np.c_[np.full(200, 10.0), side], np.c_[10 - side, np.full(200, 10.0)],
                       np.c_[np.zeros(200), 10 - side]])
    t = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    hole = np.c_[5.0 + 0.1 * np.cos(t), -0.0035 + 0.0015 * np.sin(t)][::-1]
    return Polygon(outer, [hole])


def _wavy_annulus() -> Any:
    """A wavy ring of 900 vertices around a wavy hole of 300, far from it."""
    from shapely.geometry import Polygon

    t = np.linspace(0, 2 * np.pi, 900, endpoint=False)
    r = 1 + 0.02 * np.sin(7 * t) + 0.004 * np.sin(53 * t)
    s = t[::3] + 0.3
    return Polygon(np.c_[r * np.cos(t), r * np.sin(t)], [np.c_[0.5 * np.cos(s), 0.5 * np.sin(s)][::-1]])


@pytest.mark.parametrize("shape", ["wavy annulus", "hole in a flat bump"])
def test_plain_simplify_is_taken_only_where_it_is_the_topology_preserving_one(shape: str) -> None:
    from medialaxis.planar.boundary._simplify_kernels import flattening_is_safe, flattening_is_safe_reference
    from medialaxis.planar.boundary.sampling import _ring_arrays, topology_preserving_simplify

    region = _wavy_annulus() if shape == "wavy annulus" else _bumpy_square()
    assert region.is_valid
    tolerance = 0.01
    plain = shapely.simplify(region, tolerance, preserve_topology=False)
    before, after = _ring_arrays(region), _ring_arrays(plain)
    safe = flattening_is_safe(*before, *after, tolerance)
    assert safe == flattening_is_safe_reference(*before, *after, tolerance)
    expected = shapely.normalize(shapely.simplify(region, tolerance, preserve_topology=True))
    assert shapely.normalize(topology_preserving_simplify(region, tolerance)).equals_exact(expected, 0)
    # plain Douglas-Peucker flattens the bump across the hole: refused
    bump = shape != "wavy annulus"
    assert safe != bump
    assert shapely.normalize(plain).equals_exact(expected, 0) != bump


def test_a_flattening_across_another_ring_is_refused() -> None:
    from medialaxis.planar.boundary._simplify_kernels import flattening_is_safe, flattening_is_safe_reference
    from medialaxis.planar.boundary.sampling import _ring_arrays

    region = _bumpy_square()
    xy, start = _ring_arrays(region)
    outer, hole = xy[: start[1]], xy[start[1] :]
    # the outer ring with its bump flattened (and every 10th other vertex kept), the hole kept whole
    keep = np.flatnonzero((outer[:, 1] == 0) | (outer[:, 1] > 0))
    keep = keep[::10]
    flattened = np.vstack([outer[keep], hole])
    flat_start = np.array([0, len(keep), len(keep) + len(hole)])
    assert not flattening_is_safe(xy, start, flattened, flat_start, 0.01)
    assert not flattening_is_safe_reference(xy, start, flattened, flat_start, 0.01)
    # far from the hole, the same flattening passes
    moved = np.vstack([outer, hole + [0.0, 5.0]])
    assert flattening_is_safe(moved, start, np.vstack([outer[keep], hole + [0.0, 5.0]]), flat_start, 0.01)


def test_brio_rounds_sort_as_numpys_stable_argsort() -> None:
    from medialaxis.planar._delaunay_kernels import _stable_sort_by_key

    rng = np.random.default_rng(7)
    for n, lo, hi in ((1, 0, 1), (2, 0, 2), (37, 5, 30), (1000, 0, 1000), (1000, 100, 900)):
        key = rng.integers(0, 50, n)  # many ties
        values = rng.permutation(n)
        expected_values, expected_key = values.copy(), key.copy()
        order = np.argsort(key[lo:hi], kind="stable")
        expected_values[lo:hi], expected_key[lo:hi] = values[lo:hi][order], key[lo:hi][order]
        _stable_sort_by_key(values, key, lo, hi)
        np.testing.assert_array_equal(values, expected_values)
        np.testing.assert_array_equal(key, expected_key)


def test_nearest_samples_are_the_kd_trees() -> None:
    from scipy.spatial import cKDTree

    from medialaxis.planar._kernels import nearest_samples

    rng = np.random.default_rng(8)
    for n in (9, 10, 50, 300, 2000):
        points = rng.random((n, 2)) * [1.0, 0.1]
        query = rng.uniform(-0.2, 1.2, (400, 2))  # some outside the samples' box
        near, sure = nearest_samples(query, points, 8)
        _, expected = cKDTree(points).query(query, k=8)
        assert sure.all()
        assert all(set(a) == set(b) for a, b in zip(near.tolist(), expected.tolist()))
    grid = np.stack(np.meshgrid(np.arange(10.0), np.arange(10.0)), -1).reshape(-1, 2)
    _, sure = nearest_samples(grid + 0.5, grid, 8)  # ties at the 8th: unsure, left to the tree
    assert not sure.all()


def test_ties_with_the_kth_are_all_taken() -> None:
    from medialaxis.planar._kernels import nearest_with_ties

    grid = np.stack(np.meshgrid(np.arange(10.0), np.arange(10.0)), -1).reshape(-1, 2)
    query = np.array([[4.5, 4.5], [0.0, 0.0], [3.2, 7.9]])
    near = nearest_with_ties(query, grid, 8)
    for q, row in zip(query, near):
        d2 = ((grid - q) ** 2).sum(1)
        kth = np.sort(d2)[7]
        assert set(row.tolist()) == set(np.flatnonzero(d2 <= kth * (1 + 2e-9)).tolist())
    assert len(set(near[0].tolist())) == 12  # the 4 + 8 grid points at the two nearest distances from a cell centre


def test_dual_edges_kernel_is_the_numpy_version() -> None:
    from medialaxis.planar._graph_kernels import dual_edges
    from medialaxis.planar.axis import dual_edges_reference
    from medialaxis.planar.pipeline import planar_stages

    for mask in _masks()[::4]:
        st = planar_stages(mask)
        tri, inside, nxt = st.triangulation, st.inside, st.samples.next
        ours = dual_edges(tri.simplices, tri.neighbors, np.flatnonzero(inside), tri.points, nxt)
        for a, b in zip(ours, dual_edges_reference(tri, inside, nxt)):
            np.testing.assert_array_equal(a, b)


def test_boundary_distance_takes_the_ties_the_brute_force_takes() -> None:
    """The grid's distance is the brute-force reference's: the pieces at the k nearest and every tied sample."""
    from medialaxis.planar._distance_kernels import boundary_distance_kernel
    from medialaxis.planar._kernels import nearest_piece_distance, nearest_with_ties

    rng = np.random.default_rng(11)
    side = np.arange(12.0)
    square = np.concatenate([np.c_[side, 0 * side], np.c_[12 + 0 * side, side], np.c_[12 - side, 12 + 0 * side],
                             np.c_[0 * side, 12 - side]])  # a square ring sampled on the integer grid: many ties
    angle = np.sort(rng.uniform(0, 2 * np.pi, 300))
    wobbly = np.c_[np.cos(angle), 0.3 * np.sin(angle)] * (1 + 0.1 * np.sin(7 * angle))[:, None]
    for points, query in ((square, np.r_[rng.uniform(0, 12, (300, 2)), np.mgrid[0:12:0.5, 0:12:0.5].reshape(2, -1).T]),
                          (wobbly, rng.uniform(-1.2, 1.2, (400, 2)))):
        n = len(points)
        nxt, prv = (np.arange(n) + 1) % n, (np.arange(n) - 1) % n
        expected = nearest_piece_distance(query, points, nxt, prv, nearest_with_ties(query, points, 8))
        np.testing.assert_array_equal(boundary_distance_kernel(query, points, nxt, prv, 8), expected)
