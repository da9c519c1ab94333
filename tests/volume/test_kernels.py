"""The compiled kernels agree with their pure-Python references."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from medialaxis.volume import _kernels as K
from medialaxis.volume.voxel_table import neighbour_rows, voxel_table


def _random_sheet(seed: int, shape=(9, 10, 11), p=0.35) -> np.ndarray:
    rng = np.random.default_rng(seed)
    occ = rng.random(shape) < p
    occ[0], occ[-1], occ[:, 0], occ[:, -1], occ[:, :, 0], occ[:, :, -1] = (False,) * 6
    return occ


@given(st.integers(0, 10_000), st.floats(0.1, 0.8))
def test_topology_class_matches_reference(seed, p):
    occ = _random_sheet(seed, p=p)
    vox = np.argwhere(occ)
    fast = K.topology_class(neighbour_rows(voxel_table(np.argwhere(occ), occ.shape), vox), K.N26_ADJ)
    assert np.array_equal(fast, K.topology_class_reference(occ, vox))


def test_topology_class_of_plane_edge_and_junction():
    occ = np.zeros((7, 9, 7), bool)
    occ[2, 1:8, 1:6] = True  # a sheet normal to axis 0
    occ[3:6, 4, 1:6] = True  # a sheet hanging from its middle: a T
    vox = np.array([[2, 2, 3], [2, 1, 3], [2, 4, 3], [4, 4, 3]])
    got = K.topology_class(neighbour_rows(voxel_table(np.argwhere(occ), occ.shape), vox), K.N26_ADJ).tolist()
    assert got == [2, 1, 3, 2]  # surface, free edge, junction, surface


@given(st.integers(0, 10_000), st.floats(0.8, 3.5))
def test_greedy_subsample_matches_reference(seed, r):
    occ = _random_sheet(seed, p=0.5)
    vox = np.argwhere(occ)
    table = voxel_table(vox, occ.shape)
    rng = np.random.default_rng(seed)
    order = rng.permutation(len(vox))
    radius = rng.uniform(0.5, r, len(vox))
    spacing = np.array([1.0, 1.5, 0.75])
    fast = K.greedy_subsample(*table, vox, order, radius, spacing)
    ref = K.greedy_subsample_reference(vox, order, radius, spacing)
    assert np.array_equal(fast, ref)
    # picks are farther apart than the radius of the earlier pick
    phys = vox[fast] * spacing
    for k in range(len(fast)):
        d = np.linalg.norm(phys[k + 1 :] - phys[k], axis=1)
        assert np.all(d > radius[fast[k]])


@given(st.integers(0, 10_000), st.integers(1, 6))
def test_single_sheet_labels_are_plain_geodesic_voronoi(seed, nseeds):
    occ = _random_sheet(seed, p=0.6)
    vox = np.argwhere(occ)
    table = voxel_table(vox, occ.shape)
    seeds = np.random.default_rng(seed).choice(len(vox), size=min(nseeds, len(vox)), replace=False)
    spacing = np.array([1.0, 1.0, 2.0])
    labels = np.arange(len(seeds), dtype=np.int64)
    sheet = np.zeros(len(vox), np.int64)
    fast = K.sheet_labels(neighbour_rows(table, vox), vox, seeds, labels, sheet, K.OFFSETS_26, spacing)
    assert np.array_equal(fast, K.sheet_labels_reference(vox, seeds, labels, sheet, spacing))
    assert np.array_equal(fast[seeds], np.arange(len(seeds)))


@given(st.integers(0, 10_000), st.integers(1, 6))
def test_sheet_labels_match_reference(seed, nseeds):
    occ = _random_sheet(seed, p=0.6)
    vox = np.argwhere(occ)
    table = voxel_table(vox, occ.shape)
    rng = np.random.default_rng(seed)
    sheet = rng.integers(-1, 3, len(vox))  # -1: junction voxels (all seeds), else 3 sheets
    junction = np.flatnonzero(sheet < 0)
    others = rng.choice(np.flatnonzero(sheet >= 0), size=min(nseeds, int((sheet >= 0).sum())), replace=False)
    seeds = np.concatenate([junction, others]).astype(np.int64)
    seed_label = np.concatenate([rng.integers(0, 2, len(junction)), 2 + np.arange(len(others))]).astype(np.int64)
    spacing = np.array([1.0, 1.0, 2.0])
    fast = K.sheet_labels(neighbour_rows(table, vox), vox, seeds, seed_label, sheet, K.OFFSETS_26, spacing)
    assert np.array_equal(fast, K.sheet_labels_reference(vox, seeds, seed_label, sheet, spacing))
    assert np.array_equal(fast[seeds], seed_label)
    # a region never holds voxels of two sheets
    for lab in np.unique(fast[fast >= 2]):
        assert len(np.unique(sheet[fast == lab])) == 1


@given(st.integers(0, 10_000), st.floats(0.2, 0.8), st.booleans())
def test_block_labels_match_reference(seed, p, sheets):
    from medialaxis.volume.sheet.triangles import _block_labels, block_labels_reference

    occ = _random_sheet(seed, p=p)
    vox = np.argwhere(occ)
    table = voxel_table(vox, occ.shape)
    rng = np.random.default_rng(seed)
    label = rng.integers(-1, 12, len(vox))
    sheet = rng.integers(-1, 3, len(vox)) if sheets else None
    fast = _block_labels(table, vox, label, sheet)
    ref = block_labels_reference(table, vox, label, sheet)
    # the same rows (the compiled walk visits each block once, in another order)
    assert len(fast) == len(ref) and np.array_equal(np.unique(fast, axis=0), np.unique(ref, axis=0))


@given(st.integers(0, 10_000), st.floats(0.0, 4.0))
def test_pair_gaps_match_reference(seed, shortest):
    from medialaxis.volume.distance import feature_transform
    from medialaxis.volume.inputs import load_volume
    from medialaxis.volume.plates import pair_gaps, pair_gaps_reference

    occ = _random_sheet(seed, shape=(12, 13, 14), p=0.6)
    features = feature_transform(load_volume(occ), workers=1)
    for fast, ref in zip(pair_gaps(features, shortest), pair_gaps_reference(features, shortest)):
        for a, b in zip(fast, ref):
            assert np.array_equal(a, b)  # the same pairs in the same order, the same gaps bit for bit
