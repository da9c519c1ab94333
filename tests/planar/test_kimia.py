"""Real silhouettes: the Kimia-99 set (99 binary 128 x 128 shapes)."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image
from skimage.transform import rotate

import medialaxis as mx


def _load(path) -> np.ndarray:
    return np.asarray(Image.open(path)).astype(bool)


def _rotated(mask: np.ndarray, angle: float) -> np.ndarray:
    return rotate(mask.astype(float), angle, resize=True, order=1) > 0.5


@pytest.fixture(scope="module")
def kimia_axes(kimia_dir):
    files = sorted(kimia_dir.glob("*.png"))
    assert len(files) == 99
    out = []
    for f in files:
        mask = _load(f)
        out.append((f.name, mx.medial_axis(mask), mx.medial_axis(_rotated(mask, 30))))
    return out


def test_one_connected_axis_per_shape_and_cycles_equal_holes(kimia_axes):
    for name, ma, rot in kimia_axes:
        for axis in (ma, rot):
            assert axis.n_components == axis.metadata["n_polygons"], name
            assert axis.n_cycles == axis.metadata["n_holes"], name
            region = axis.shape
            import shapely

            assert shapely.contains_xy(region, axis.points[:, 0], axis.points[:, 1]).all(), name


def test_endpoint_count_survives_30_degree_rotation(kimia_axes):
    same = sum(len(ma.endpoints) == len(rot.endpoints) for _, ma, rot in kimia_axes)
    assert same >= 0.9 * len(kimia_axes), f"only {same}/99 shapes keep their endpoint count"


def test_thin_necks_narrower_than_lambda_stay_connected():
    # two discs joined by a one-pixel-wide bridge
    mask = np.zeros((80, 160), bool)
    rr, cc = np.mgrid[:80, :160]
    mask |= (rr - 40) ** 2 + (cc - 40) ** 2 < 30**2
    mask |= (rr - 40) ** 2 + (cc - 120) ** 2 < 30**2
    mask[40, 60:101] = True
    ma = mx.medial_axis(mask, lam=8.0)
    assert ma.n_components == 1
    assert ma.n_cycles == 0


def test_reconstruction_iou_on_silhouettes(kimia_axes):
    ious = [mx.reconstruction_error(ma).iou for _, ma, _ in kimia_axes[::9]]
    assert min(ious) > 0.93
    assert np.mean(ious) > 0.95
