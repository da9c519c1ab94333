"""Real silhouettes: the Kimia-99 set (99 binary 128 x 128 shapes)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from PIL import Image
from scipy.spatial import cKDTree
from skimage.transform import rotate

import medialaxis as mx
from medialaxis.datasets import raster_counts as truth_counts


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
        rotated = _rotated(mask, 30)
        out.append((f.name, (mask, mx.medial_axis(mask)), (rotated, mx.medial_axis(rotated))))
    return out


def test_one_connected_axis_per_piece_and_one_cycle_per_hole(kimia_axes):
    """Pieces and holes are counted by scikit-image on the mask, not read from our metadata."""
    for name, *versions in kimia_axes:
        for mask, axis in versions:
            pieces, holes = truth_counts(mask)
            assert axis.n_components == pieces, name
            assert axis.n_cycles == holes, name
            assert shapely.contains_xy(axis.shape, axis.points[:, 0], axis.points[:, 1]).all(), name


@pytest.mark.parametrize("name", ["kimia_class1_01.png", "kimia_class3_05.png", "kimia_class5_03.png", "kimia_class8_05.png"])
def test_dark_and_light_versions_of_the_bundled_shapes_give_one_axis(name, tmp_path):
    """Each bundled silhouette and its negative (saved by PIL) have the same axis."""
    from importlib.resources import files

    light = np.asarray(Image.open(files("medialaxis") / "data" / name).convert("L"))
    dark_path = tmp_path / "negative.png"
    Image.fromarray(255 - light).save(dark_path)
    a = mx.medial_axis(light)
    b = mx.medial_axis(dark_path)
    assert (a.metadata["foreground"], b.metadata["foreground"]) == ("bright", "dark")
    assert a.n_components == b.n_components == 1
    assert (len(a.endpoints), len(a.junctions), a.n_cycles) == (len(b.endpoints), len(b.junctions), b.n_cycles)
    gap = cKDTree(a.points).query(b.points)[0].max(), cKDTree(b.points).query(a.points)[0].max()
    assert max(gap) < 0.5
    # Forcing the wrong side gives the background's axis, outside the shape.
    wrong = mx.medial_axis(dark_path, foreground="bright")
    assert wrong.metadata["foreground"] == "bright"
    assert shapely.contains_xy(a.shape, wrong.points[:, 0], wrong.points[:, 1]).mean() < 0.05


def test_endpoint_count_survives_30_degree_rotation(kimia_axes):
    same = sum(len(ma.endpoints) == len(rot.endpoints) for _, (_, ma), (_, rot) in kimia_axes)
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
    ious = [mx.reconstruction_error(ma).iou for _, (_, ma), _ in kimia_axes[::9]]
    assert min(ious) > 0.93
    assert np.mean(ious) > 0.95
