"""Arrays as scikit-image users have them: colour images from io.imread, label images from measure.label."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from skimage import color, draw, io, measure
from skimage.util import img_as_float

import medialaxis as mx
from medialaxis import _dispatch


@pytest.fixture
def scan(tmp_path):
    """A dark ellipse on white paper, as an RGB PNG."""
    img = np.full((200, 300, 3), 255, np.uint8)
    rr, cc = draw.ellipse(100, 150, 60, 110)
    img[rr, cc] = (30, 40, 50)
    path = tmp_path / "scan.png"
    io.imsave(path, img, check_contrast=False)
    return path


def test_rgb_array_is_a_colour_image_not_a_volume(scan):
    rgb = io.imread(scan)
    assert rgb.shape == (200, 300, 3)
    ma = mx.medial_axis(rgb)
    assert ma.metadata["domain"] == "planar" and ma.metadata["channels"] == "rgb"
    assert ma.metadata["foreground"] == "dark"
    # the same as skimage's own grey conversion, and the same as the file
    np.testing.assert_array_equal(ma.points, mx.medial_axis(color.rgb2gray(rgb)).points)
    np.testing.assert_array_equal(ma.points, mx.medial_axis(scan).points)
    # an ellipse's axis: one segment along the major axis
    assert len(ma.endpoints) == 2 and ma.n_cycles == 0
    np.testing.assert_allclose(ma.points[:, 0], 100, atol=1.0)


def test_channel_axis(scan):
    rgb = io.imread(scan)
    first = np.moveaxis(rgb, -1, 0)  # (3, rows, cols)
    np.testing.assert_array_equal(mx.medial_axis(first, channel_axis=0).points, mx.medial_axis(rgb).points)
    with pytest.raises(mx.InvalidInputError, match="channel_axis"):
        mx.medial_axis(rgb, channel_axis=0)
    # channel_axis=None: a volume whose last axis happens to have 3 entries
    assert _dispatch.classify(rgb, None, {"channel_axis": None}) == "volume"
    assert _dispatch.classify(rgb, "midsurface") == "volume"
    assert _dispatch.classify(np.zeros((20, 20, 5))) == "volume"


def test_alpha_is_the_shape_when_it_varies():
    # a white shape on a transparent background: only the alpha tells where it is
    rgba = np.zeros((100, 120, 4), np.uint8)
    rgba[..., :3] = 255
    rgba[20:80, 10:110, 3] = 255
    ma = mx.medial_axis(rgba)
    assert ma.metadata["channels"] == "alpha"
    np.testing.assert_array_equal(ma.points, mx.medial_axis(img_as_float(rgba[..., 3])).points)
    assert len(ma.endpoints) == 4 and len(ma.junctions) == 2
    # an opaque alpha is ignored: the colours give the shape
    rgba[..., 3] = 255
    rgba[20:80, 10:110, :3] = 0
    assert mx.medial_axis(rgba).metadata["channels"] == "rgb"


def _two_objects():
    mask = np.zeros((120, 240), bool)
    mask[20:100, 20:100] = True
    rr, cc = draw.disk((60, 170), 35)
    mask[rr, cc] = True
    return mask


def test_label_image_of_skimage_label_keeps_every_label():
    labels = measure.label(_two_objects())
    assert labels.max() == 2
    ma = mx.medial_axis(labels)
    assert ma.metadata["labels"] == [1, 2] and ma.metadata["foreground"] == "labels"
    assert ma.n_components == 2
    # each label's axis is the axis of that object alone
    for label in (1, 2):
        alone = mx.medial_axis(labels == label)
        mine = ma.points[ma.point_label == label]
        assert len(mine) == len(alone.points)
        distance = shapely.hausdorff_distance(shapely.MultiPoint(mine), shapely.MultiPoint(alone.points))
        assert distance < 1e-6
    # the same int32 array as the issue saw it (Otsu kept only one object)
    assert mx.medial_axis(labels.astype(np.int32)).n_components == 2


def test_touching_labels_each_get_their_axis():
    labels = np.zeros((100, 200), np.int32)
    labels[20:80, 20:100] = 4
    labels[20:80, 100:180] = 9  # shares the column border with label 4
    ma = mx.medial_axis(labels)
    assert ma.metadata["labels"] == [4, 9] and ma.n_components == 2
    # every point lies in its own object, at its distance from that object's boundary
    for label in (4, 9):
        points = ma.points[ma.point_label == label]
        rows, cols = np.nonzero(labels == label)
        assert rows.min() - 0.5 <= points[:, 0].min() and points[:, 0].max() <= rows.max() + 0.5
        assert cols.min() - 0.5 <= points[:, 1].min() and points[:, 1].max() <= cols.max() + 0.5
    # a 60 x 80 rectangle each: the longest axis segment at radius about 30
    assert ma.radii.max() == pytest.approx(30, abs=1.0)
    pruned = ma.prune(lam=10.0)
    assert set(np.unique(pruned.point_label)) == {4, 9}


def test_label_results_save_and_load(tmp_path):
    labels = measure.label(_two_objects())
    ma = mx.medial_axis(labels)
    for name in ("l.json", "l.npz"):
        ma.save(tmp_path / name)
        back = mx.load(tmp_path / name)
        np.testing.assert_array_equal(back.point_label, ma.point_label)


def test_which_integer_images_are_labels(tmp_path):
    grey = np.zeros((60, 80), np.uint8)
    grey[10:50, 10:70] = 200
    grey[20:40, 20:40] = 100  # a grey level inside: Otsu takes the bright rectangle
    assert "labels" not in mx.medial_axis(grey).metadata
    assert mx.medial_axis(grey, labels=True).metadata["labels"] == [100, 200]
    assert "labels" not in mx.medial_axis(grey.astype(np.int64), labels=False).metadata
    with pytest.raises(mx.InvalidInputError, match="label image is not thresholded"):
        mx.medial_axis(grey.astype(np.int32), threshold=50)
    with pytest.raises(mx.InvalidInputError, match=">= 0"):
        mx.medial_axis(-grey.astype(np.int32))
    with pytest.raises(mx.EmptyShapeError):
        mx.medial_axis(np.zeros((10, 10), np.int32))
    # a label file (32-bit TIFF, as segmentation tools write them) is read as labels when asked
    tifffile = pytest.importorskip("tifffile")
    path = tmp_path / "labels.tif"
    tifffile.imwrite(path, measure.label(_two_objects()).astype(np.int32))
    assert mx.medial_axis(path, labels=True).metadata["labels"] == [1, 2]


def test_a_volume_of_tubes_names_the_route_that_works():
    z, y, x = np.mgrid[:30, :30, :60]
    rod = ((z - 15) ** 2 + (y - 15) ** 2 <= 25) & (x > 5) & (x < 55)
    with pytest.raises(mx.EmptyShapeError, match="marching_cubes.*method='flow'"):
        mx.medial_axis(rod)


def test_a_grey_image_in_int64_is_flagged_when_read_as_labels():
    rng = np.random.default_rng(0)
    grey = (rng.integers(0, 4, (40, 60)) * 60).astype(np.int64)  # a noisy grey picture after an upcast
    with pytest.warns(mx.MedialAxisWarning, match="labels=False"):
        mx.medial_axis(grey)
    labels = measure.label(_two_objects())
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", mx.MedialAxisWarning)
        mx.medial_axis(labels)  # real labels: no warning
