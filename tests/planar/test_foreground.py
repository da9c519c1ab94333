"""Which side of the threshold is the shape: ``foreground="auto" | "bright" | "dark"``."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import medialaxis as mx
from medialaxis.planar.reading.inputs import shape_side


def _rect_image(dark: bool) -> np.ndarray:
    img = np.full((80, 120), 30, np.uint8)
    img[20:60, 10:110] = 220
    return 250 - img if dark else img


@pytest.mark.parametrize("dark", [False, True])
def test_auto_takes_the_side_off_the_border(dark):
    ma = mx.medial_axis(_rect_image(dark))
    assert ma.metadata["foreground"] == ("dark" if dark else "bright")
    assert len(ma.endpoints) == 4 and len(ma.junctions) == 2
    np.testing.assert_allclose(ma.radii.max(), 20, rtol=0.05)


def test_explicit_sides_and_their_inverse_agree():
    bright, dark = _rect_image(False), _rect_image(True)
    a = mx.medial_axis(bright, foreground="bright")
    b = mx.medial_axis(dark, foreground="dark")
    np.testing.assert_allclose(np.sort(a.radii), np.sort(b.radii), atol=1e-9)
    # bool masks: the False pixels are the shape on the dark side
    mask = bright > 100
    np.testing.assert_array_equal(mx.medial_axis(~mask, foreground="dark").points, mx.medial_axis(mask).points)


def test_a_shape_that_owns_most_of_the_border_needs_the_side_said():
    """A plate cut by the frame: auto takes the (small) hole side; "bright" gives the plate."""
    mask = np.ones((100, 100), bool)
    rows, cols = np.mgrid[:100, :100]
    mask[(rows - 50) ** 2 + (cols - 50) ** 2 < 15**2] = False
    assert mx.medial_axis(mask).metadata["foreground"] == "dark"
    plate = mx.medial_axis(mask, foreground="bright")
    assert plate.metadata["foreground"] == "bright" and plate.n_cycles == 1


def test_ties_go_to_the_smaller_side_then_to_bright():
    half = np.zeros((10, 10), bool)
    half[:, :5] = True  # border and pixels split evenly
    assert shape_side(half) == "bright"
    more = half.copy()
    more[4:6, 5:8] = True  # border still even, bright now the larger side
    assert shape_side(more) == "dark"
    assert shape_side(~more) == "bright"


@pytest.mark.parametrize("bad", ["black", "", None, 1, "AUTO"])
def test_bad_foreground_names_the_value(bad):
    with pytest.raises(mx.InvalidInputError, match="foreground"):
        mx.medial_axis(_rect_image(False), foreground=bad)


def test_vector_inputs_have_an_inside_already():
    square = shapely.box(0, 0, 10, 10)
    assert mx.medial_axis(square, foreground="auto").n_components == 1
    with pytest.raises(mx.InvalidInputError, match="applies to images"):
        mx.medial_axis(square, foreground="dark")


def test_one_sided_images_fail_cleanly():
    img = _rect_image(False)
    with pytest.raises(mx.EmptyShapeError, match="dark"):
        mx.medial_axis(img, foreground="dark", threshold=10)


def test_reconstruction_error_uses_the_side_of_the_axis():
    dark = _rect_image(True)
    ma = mx.medial_axis(dark)
    assert mx.reconstruction_error(ma, dark).iou > 0.95
    assert mx.reconstruction_error(ma, dark, foreground="bright").iou < 0.5
