"""Shapes whose exact medial axis is known."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely import affinity

import medialaxis as mx
from medialaxis.datasets import (
    annulus,
    capsule,
    ellipse,
    ellipse_axis,
    in_image,
    rectangle_axis,
    render,
    rotation,
)
from medialaxis.datasets import segment_distance as distance_to_segments

ANGLES = [0, 10, 30, 45]


def _bbox_diag(segments) -> float:
    pts = np.array([p for s in segments for p in s], float)
    return float(np.linalg.norm(np.ptp(pts, axis=0)))


@pytest.mark.parametrize("angle", ANGLES)
def test_rectangle_polygon_axis_is_exact_and_clean(angle):
    geom = affinity.rotate(shapely.box(-2, -1, 2, 1), angle, origin=(0, 0))
    ma = mx.medial_axis(geom)
    back = ma.points @ rotation(angle)  # undo the rotation
    segs = rectangle_axis(4, 2)
    assert distance_to_segments(back, segs).max() <= 2e-3 * _bbox_diag(segs)
    assert len(ma.endpoints) == 4 and len(ma.junctions) == 2
    assert ma.n_components == 1 and ma.n_cycles == 0
    # the branches reach the corners up to the lambda cut
    tips = back[ma.endpoints]
    corner_dist = np.min(np.linalg.norm(tips[:, None] - np.array([[2, 1], [2, -1], [-2, 1], [-2, -1]]), axis=2), axis=1)
    assert corner_dist.max() < 0.05


@pytest.mark.parametrize("angle", [0, 30])
def test_ellipse_polygon_axis(angle):
    geom = affinity.rotate(ellipse(), angle, origin=(0, 0))
    ma = mx.medial_axis(geom)
    back = ma.points @ rotation(angle)
    segs = ellipse_axis()
    assert distance_to_segments(back, segs).max() <= 2e-3 * _bbox_diag(segs)
    assert len(ma.endpoints) == 2 and len(ma.junctions) == 0
    # covers the exact axis (from centre of curvature to centre of curvature)
    assert back[:, 0].min() < -1.45 and back[:, 0].max() > 1.45


def test_annulus_axis_is_the_mid_circle():
    ma = mx.medial_axis(annulus())
    r = np.linalg.norm(ma.points, axis=1)
    assert np.abs(r - 1.5).max() <= 2e-3 * 3 * np.sqrt(2)
    assert ma.n_cycles == 1 and len(ma.endpoints) == 0 and ma.n_components == 1
    np.testing.assert_allclose(ma.radii, 0.5, atol=2e-3)


def test_capsule_axis_is_its_segment():
    ma = mx.medial_axis(capsule(4.0, 0.5))
    d = distance_to_segments(ma.points, [((-2, 0), (2, 0))])
    assert d.max() <= 2e-3 * 4
    assert len(ma.endpoints) == 2 and len(ma.junctions) == 0
    inner = np.abs(ma.points[:, 0]) < 1.9
    np.testing.assert_allclose(ma.radii[inner], 0.5, atol=2e-3)


def test_disc_axis_is_its_centre():
    ma = mx.medial_axis(shapely.Point(1, 2).buffer(3, quad_segs=64))
    assert np.linalg.norm(ma.points - [1, 2], axis=1).max() < 0.05
    assert ma.n_components == 1 and len(ma.edges) <= 2
    np.testing.assert_allclose(ma.radii.max(), 3, rtol=1e-3)


def test_holes_give_cycles_and_pieces_give_components():
    plate = shapely.box(0, 0, 10, 4)
    for k in range(3):
        plate = plate.difference(shapely.Point(2 + 3 * k, 2).buffer(0.8))
    two = shapely.MultiPolygon([plate, shapely.box(20, 0, 24, 2)])
    ma = mx.medial_axis(two)
    assert ma.n_cycles == 3
    assert ma.n_components == 2


def test_radii_equal_distance_to_boundary():
    geom = shapely.box(0, 0, 6, 3).union(shapely.box(4, 0, 6, 8))
    ma = mx.medial_axis(geom)
    d = shapely.distance(shapely.points(ma.points), geom.boundary)
    np.testing.assert_allclose(ma.radii, d, atol=1e-9)
    assert shapely.contains_xy(geom, ma.points[:, 0], ma.points[:, 1]).all()


def _image_errors(geom_xy, segs_xy, angle, binary):
    """p99 distance (pixels) from the image axis to the exact axis."""
    g = in_image(geom_xy, angle)
    img = render(g)
    image = img > 0.5 if binary else img
    ma = mx.medial_axis(image)
    # points are (row, col); exact axis in (x, y) = (col, row)
    rot = rotation(angle)
    segs = [((rot @ a)[::-1] + 256, (rot @ b)[::-1] + 256) for a, b in ((np.array(a), np.array(b)) for a, b in segs_xy)]
    d = distance_to_segments(ma.points, segs)
    return float(np.percentile(d, 99)), ma


IMAGE_SHAPES = {
    "rectangle": (shapely.box(-180, -90, 180, 90), rectangle_axis(360, 180), 4, 2),
    "ellipse": (ellipse(200, 100), ellipse_axis(200, 100), 2, 0),
}


@pytest.mark.parametrize("binary", [False, True], ids=["antialiased", "binary"])
@pytest.mark.parametrize("name", sorted(IMAGE_SHAPES))
@pytest.mark.parametrize("angle", [0, 10, 30, 45])
def test_image_axis_p99_error(name, binary, angle):
    """512 x 512 images: p99 error <= 1 px (anti-aliased), <= 1.5 px (binary), clean structure."""
    geom, segs, n_end, n_junction = IMAGE_SHAPES[name]
    p99, ma = _image_errors(geom, segs, angle, binary=binary)
    assert p99 <= (1.5 if binary else 1.0)
    assert len(ma.endpoints) == n_end and len(ma.junctions) == n_junction


def test_spacing_scales_index_coordinates():
    mask = np.zeros((40, 80), bool)
    mask[10:30, 10:70] = True
    a = mx.medial_axis(mask)
    b = mx.medial_axis(mask, spacing=(0.5, 1.0))
    c = mx.medial_axis(mask, spacing=2.0)
    assert len(a.endpoints) == len(b.endpoints) == len(c.endpoints) == 4
    # the central segment runs along row 19.5 (row spacing 0.5 -> 9.75)
    np.testing.assert_allclose(a.points[a.junctions][:, 0], 19.5, atol=0.3)
    np.testing.assert_allclose(b.points[b.junctions][:, 0], 19.5 * 0.5, atol=0.3)
    # isotropic spacing scales everything
    np.testing.assert_allclose(np.sort(c.radii), np.sort(2 * a.radii), rtol=1e-9, atol=1e-9)
    assert b.metadata["spacing"] == [0.5, 1.0]


def test_canny_route_gives_the_same_structure():
    mask = np.zeros((60, 100), bool)
    mask[10:50, 10:90] = True
    ma = mx.medial_axis(mask, boundary="canny")
    assert len(ma.endpoints) == 4 and len(ma.junctions) == 2 and ma.n_components == 1
    assert ma.metadata["boundary"] == "canny"
