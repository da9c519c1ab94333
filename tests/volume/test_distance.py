"""Sub-voxel feature transform against SciPy's exact EDT."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy import ndimage

from medialaxis.volume.distance import feature_transform
from medialaxis.volume.inputs import load_volume


@given(st.integers(0, 10_000), st.sampled_from([(1.0, 1.0, 1.0), (2.0, 1.0, 0.5)]))
def test_distance_brackets_scipy_edt(seed, spacing):
    rng = np.random.default_rng(seed)
    vol = ndimage.binary_dilation(rng.random((14, 15, 16)) < 0.02, iterations=3)
    vol[0] = False
    if not vol.any() or vol.all():
        vol[5:9, 5:9, 5:9] = True
    f = feature_transform(load_volume(vol, spacing=spacing))
    edt = ndimage.distance_transform_edt(np.pad(vol, 1), sampling=spacing)[1:-1, 1:-1, 1:-1]
    ours = f.distance
    ref = edt[tuple((f.voxels + f.offset).T)]
    # boundary points sit half a voxel from background voxel centres
    assert np.all(ours <= ref + 1e-9)
    assert np.all(ours >= ref - 0.5 * max(spacing) - 1e-9)
    # the feature points are on the boundary sample and at that distance
    phys = (f.voxels + f.offset) * np.asarray(spacing)
    assert np.allclose(np.linalg.norm(f.feature - phys, axis=1), ours)


def test_grey_crossings_are_sub_voxel():
    # a plate whose faces sit at fractional positions through partial-volume grey values
    vol = np.zeros((12, 10, 10), np.float32)
    vol[4:8] = 1.0
    vol[3] = 0.25  # face at 3.75 -> crossing between 3 and 4 at t = (1 - .5) / (1 - .25)
    f = feature_transform(load_volume(vol, iso=0.5))
    z = f.boundary[:, 0]
    assert np.isclose(z.min(), 4 - 0.5 / 0.75)
    assert np.isclose(z.max(), 7.5)


def test_input_not_modified_and_border_touching():
    vol = np.zeros((6, 6, 6), bool)
    vol[:3] = True  # touches the array border
    before = vol.copy()
    f = feature_transform(load_volume(vol))
    assert np.array_equal(vol, before)
    assert np.isclose(f.distance.max(), 1.5)  # half a voxel beyond the border counts as background
