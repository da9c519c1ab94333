"""The compiled kernels of the small-shape speed work against their pure-Python/NumPy references."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from medialaxis.planar._contour_kernels import contour_rings, mask_contours_reference


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
