"""Invariants that hold for every shape (hypothesis)."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, note
from hypothesis import strategies as st
from shapely import affinity

import medialaxis as mx


@st.composite
def star_polygons(draw):
    n = draw(st.integers(5, 24))
    radii = np.array(draw(st.lists(st.floats(0.4, 1.5), min_size=n, max_size=n)))
    jitter = np.array(draw(st.lists(st.floats(-0.3, 0.3), min_size=n, max_size=n)))
    theta = (np.arange(n) + jitter) * 2 * np.pi / n
    poly = shapely.Polygon(np.c_[radii * np.cos(theta), radii * np.sin(theta)])
    if draw(st.booleans()):
        hole = shapely.Point(0, 0).buffer(0.15, quad_segs=16)
        if poly.buffer(-0.05).contains(hole):
            poly = poly.difference(hole)
    return shapely.make_valid(poly) if not poly.is_valid else poly


def _polygonal(g):
    parts = [p for p in shapely.get_parts(g) if p.geom_type == "Polygon" and p.area > 1e-3]
    return max(parts, key=lambda p: p.area) if parts else None


@given(star_polygons())
def test_points_inside_radius_is_distance_and_balls_rebuild_the_shape(poly):
    poly = _polygonal(poly)
    if poly is None:
        return
    note(f"polygon: {poly.wkt}")
    ma = mx.medial_axis(poly)
    tol = ma.metadata["tolerance"]
    # inside (up to the simplification tolerance)
    assert shapely.contains_xy(poly.buffer(tol), ma.points[:, 0], ma.points[:, 1]).all()
    # radius = distance to the boundary
    d = shapely.distance(shapely.points(ma.points), poly.boundary)
    np.testing.assert_allclose(ma.radii, d, atol=2 * tol)
    # the union of balls rebuilds the shape
    assert mx.reconstruction_error(ma).iou >= 0.98
    # topology of the shape
    assert ma.n_components == 1
    assert ma.n_cycles == len(poly.interiors)


@given(
    star_polygons(),
    st.floats(0, 360),
    st.floats(0.01, 100.0),
    st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3)),
)
def test_equivariant_under_rotation_scale_translation(poly, angle, scale, shift):
    poly = _polygonal(poly)
    if poly is None:
        return

    def move(g):
        g = affinity.rotate(g, angle, origin=(0, 0))
        g = affinity.scale(g, scale, scale, origin=(0, 0))
        return affinity.translate(g, *shift)

    note(f"polygon: {poly.wkt}")
    a = mx.medial_axis(poly)
    b = mx.medial_axis(move(poly))
    np.testing.assert_allclose(b.radii.max(), scale * a.radii.max(), rtol=1e-3)
    moved = move(a.reconstruct())
    rebuilt = b.reconstruct()
    iou = moved.intersection(rebuilt).area / moved.union(rebuilt).area
    assert iou >= 0.99
    # every point of the moved shape's axis lies near the moved axis
    moved_axis = move(shapely.MultiLineString([a.points[e] for e in a.edges]) if len(a.edges) else shapely.MultiPoint(a.points))
    gap = shapely.distance(shapely.points(b.points), moved_axis)
    diag = np.hypot(*np.ptp(np.asarray(move(poly).exterior.coords), axis=0))
    assert np.percentile(gap, 90) <= 1e-2 * diag


@given(star_polygons())
def test_input_is_not_modified_and_results_are_read_only(poly):
    poly = _polygonal(poly)
    if poly is None:
        return
    before = poly.wkb
    ma = mx.medial_axis(poly)
    assert poly.wkb == before
    for arr in (ma.points, ma.radii, ma.edges, ma.faces):
        assert not arr.flags.writeable


def test_mask_input_is_not_modified():
    mask = np.zeros((30, 40), bool)
    mask[5:25, 5:35] = True
    copy = mask.copy()
    mx.medial_axis(mask)
    np.testing.assert_array_equal(mask, copy)
    grey = mask.astype(np.float32) * 200
    gcopy = grey.copy()
    mx.medial_axis(grey)
    np.testing.assert_array_equal(grey, gcopy)
