"""Signatures (compared axis, endpoints, tours) on shapes with known axes."""

import dataclasses

import numpy as np
import pytest
from shapely.geometry import Point, Polygon, box

import medialaxis as mx
from medialaxis.compare import shape_signature, signature
from medialaxis.compare.signature import closed_axis
from medialaxis.core.result import MedialAxis
from medialaxis.errors import EmptyShapeError, InvalidInputError

T_SHAPE = Polygon([(0, 0), (10, 0), (10, 2), (6, 2), (6, 8), (4, 8), (4, 2), (0, 2)])


def test_t_shape_has_three_limbs_in_boundary_order():
    # Corner branches protrude 0.41 half-widths past their junction disc:
    # below prune * scale = 0.1 * 6.4 they go, leaving the three limbs.
    assert shape_signature(T_SHAPE, prune=0).n_endpoints == 6
    sig = shape_signature(T_SHAPE, prune=0.1)
    assert sig.n_endpoints == 3
    # The three limb tips, whatever the corner branches did.
    tips = {tuple(np.round(p).astype(int)) for p in sig.endpoints}
    assert tips == {(1, 1), (9, 1), (5, 7)}
    # Weights: how far each limb's discs reach past the junction disc. The junction is at
    # (5, 5/4) (as far from the bottom as from the corners (4, 2), (6, 2)), radius 5/4; a tip
    # disc has the half-width 1 as radius: |tip - J| + 1 - 5/4.
    reach = np.linalg.norm(sig.endpoints - [5.0, 1.25], axis=1) + 1.0 - 1.25
    assert np.allclose(sig.weights * sig.scale, reach, atol=0.05)
    assert np.allclose(np.sort(reach), [3.76, 3.76, 5.5], atol=0.02)


def test_arrays_read_only():
    sig = shape_signature(T_SHAPE, prune=0.1)
    for arr in (sig.weights, sig.endpoints, sig.tour, sig.tour_radii, sig.points):
        assert not arr.flags.writeable
    assert (sig.weights > 0).all()


def test_rectangle_is_a_single_path_with_corner_branches_pruned():
    sig = shape_signature(box(0, 0, 8, 2), prune=0.1)
    assert sig.n_endpoints == 2
    kept = signature(mx.medial_axis(box(0, 0, 8, 2)), prune=0)
    assert kept.n_endpoints == 4


def test_disc_has_a_point_axis():
    sig = shape_signature(Point(0, 0).buffer(3, 64))
    assert sig.n_endpoints == 2
    assert len(sig.points) == 1 and len(sig.edges) == 0
    assert np.allclose(sig.tour_radii * sig.scale, 3, rtol=0.01)


def test_keeps_largest_component():
    mask = np.zeros((60, 90), bool)
    mask[20:40, 10:70] = True
    mask[5:8, 80:83] = True  # a speck
    sig = shape_signature(mask)
    assert sig.endpoints[:, 1].max() < 75


def test_tour_versions_of_the_axis_the_raw_axis_and_the_closed_shape():
    mask = np.pad(np.ones((30, 80), bool), 10)
    ma = mx.medial_axis(mask)  # a raster rectangle: its raw axis has pixel spurs
    sig = signature(ma)
    assert sig.tour.shape == (6, 64, 60) and sig.tour_radii.shape == (6, 64) and sig.tour_points.shape == (6, 64, 2)
    assert np.allclose(sig.tour.sum(axis=2), 1.0)
    assert not np.allclose(sig.tour[:2], sig.tour[2:4])  # the raw axis is walked differently
    # Mirror versions: the same sample positions met in the other direction.
    for g in (0, 2, 4):
        assert np.allclose(np.sort(sig.tour_radii[g]), np.sort(sig.tour_radii[g + 1]))
    # A convex shape is (nearly) its own closing: the closed versions walk about the same axis.
    assert sig.closing_gain < 1e-2 and np.allclose(sig.tour_radii[4:], sig.tour_radii[:2], atol=0.02)
    # closing=0, or an axis without its shape (a bare MedialAxis): the closed versions repeat the first two.
    for bare in (signature(ma, closing=0), signature(dataclasses.replace(ma, shape=None))):
        assert np.array_equal(bare.tour[4:], bare.tour[:2]) and bare.closing_gain == 0.0
        assert np.array_equal(bare.tour[:4], sig.tour[:4])
    # Without a raw graph (e.g. a saved and reloaded axis), the second pair repeats the first.
    no_raw = signature(dataclasses.replace(ma, raw=None))
    assert np.array_equal(no_raw.tour[2:4], no_raw.tour[:2]) and np.array_equal(no_raw.tour[:2], sig.tour[:2])
    # unpruned=True walks the raw axis in the first pair (and so again in the second).
    raw = signature(ma, unpruned=True)
    assert np.array_equal(raw.tour[:2], sig.tour[2:4]) and np.array_equal(raw.tour[2:4], raw.tour[:2])


def test_closing_fills_slits_and_reports_the_area_it_added():
    """A square cut by two slits: the closed shape is the full square (area from shapely, not from us)."""
    square = np.zeros((140, 140), bool)
    square[20:120, 20:120] = True
    cut = square.copy()
    cut[40:42, 20:90] = False  # slits 2 px wide, 70 px long, from the left edge
    cut[90:92, 50:120] = False  # and from the right edge
    ma = mx.medial_axis(cut)
    closed, gain = closed_axis(ma)
    assert closed is not None and closed.shape.area == pytest.approx(100 * 100, rel=0.01)
    assert gain == pytest.approx(2 * 70 * 2 / (100 * 100 - 2 * 70 * 2), rel=0.1)
    sig = signature(ma)
    assert sig.closing_gain == pytest.approx(gain)
    # The closed axis is the square's: its radius peaks at half the side; the slits cut that disc.
    assert closed.radii.max() == pytest.approx(50, rel=0.02) and ma.radii.max() < 40
    assert not np.allclose(sig.tour_radii[4:], sig.tour_radii[:2], atol=0.05)


def test_input_axis_not_modified():
    ma = mx.medial_axis(T_SHAPE)
    before = (ma.points.copy(), ma.radii.copy(), ma.edges.copy())
    signature(ma)
    assert all(np.array_equal(x, y) for x, y in zip(before, (ma.points, ma.radii, ma.edges)))


def test_signature_cached_per_axis():
    ma = mx.medial_axis(T_SHAPE)
    assert shape_signature(ma) is shape_signature(ma)
    assert shape_signature(ma, prune=0) is not shape_signature(ma)


def test_errors():
    with pytest.raises(InvalidInputError, match="planar"):
        signature(MedialAxis(np.zeros((2, 3)), np.ones(2), [[0, 1]]))
    with pytest.raises(EmptyShapeError, match="no axis"):
        signature(MedialAxis(np.zeros((0, 2)), np.zeros(0)))
    with pytest.raises(InvalidInputError, match="MedialAxis"):
        signature(np.zeros((3, 2)))
    ma = mx.medial_axis(T_SHAPE)
    with pytest.raises(InvalidInputError, match="prune"):
        signature(ma, prune=-1)
    with pytest.raises(InvalidInputError, match="prune"):
        signature(ma, prune="much")
    with pytest.raises(EmptyShapeError):
        shape_signature(np.zeros((20, 20), bool))


def test_an_invalid_or_non_finite_shape_is_compared_by_its_axis_alone():
    """A result carrying a self-crossing or NaN outline (a hand-edited file, found by the fuzzer) still has a
    signature: the closing needs a valid outline, so the closed versions repeat the axis's own."""
    ma = mx.medial_axis(np.pad(np.ones((30, 80), bool), 10))
    bow_tie = Polygon([(0, 0), (10, 10), (10, 0), (0, 10)])
    nan = Polygon([(0, 0), (np.nan, 5), (10, 0), (10, 10)])
    for shape in (bow_tie, nan):
        sig = signature(dataclasses.replace(ma, shape=shape))
        assert sig.closing_gain == 0.0 and np.array_equal(sig.tour[4:], sig.tour[:2])
