"""The mid-surface meshed block by block on the workers is the whole sheet's mesh, bit for bit.

Truth: the in-memory route on the same array (the whole sheet polygonized,
dented and extended at once); the greedy sub-sampling of the whole sheet for
the certainty of a window's picks; trimesh's PLY reader for the streamed file.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import medialaxis as mx
from medialaxis.datasets import ribbed_panel_slab, ribbed_panel_truth
from medialaxis.volume import _kernels as K
from medialaxis.volume.validation import distance_to_rects, mesh_topology
from medialaxis.volume.voxel_table import voxel_table

#: A panel wide enough that the blocks' windows (core plus mesh halo) do not hold the whole sheet.
WIDE = (40, 160, 160)
CHUNK = 48


#: A smaller panel for the outputs (T and X junctions, free edges; windows hold most of its sheet).
SMALL = (40, 96, 96)


@pytest.fixture(scope="module")
def wide():
    return ribbed_panel_slab(WIDE, 0, WIDE[0], thickness=4, margin=8, levels=(1000, 3000), dtype=np.uint16)


@pytest.fixture(scope="module")
def small():
    """The small panel and its mid-surface by the whole route."""
    grey = ribbed_panel_slab(SMALL, 0, SMALL[0], thickness=4, margin=8, levels=(1000, 3000), dtype=np.uint16)
    return grey, mx.medial_axis(grey, method="midsurface", chunks=0)


def _same_mesh(points, faces, radii, whole):
    """The same vertices and radii (bit for bit, in any order) and the same triangles over them."""
    order, ref = np.lexsort(points.T), np.lexsort(whole.points.T)
    assert np.array_equal(points[order], whole.points[ref]) and np.array_equal(radii[order], whole.radii[ref])
    rank, ref_rank = np.empty(len(order), np.int64), np.empty(len(ref), np.int64)
    rank[order], ref_rank[ref] = np.arange(len(order)), np.arange(len(ref))
    got = np.unique(np.sort(rank[faces], axis=1), axis=0)
    assert len(got) == len(faces) == len(whole.faces)
    assert np.array_equal(got, np.unique(np.sort(ref_rank[whole.faces], axis=1), axis=0))
    return order, ref


def test_blocks_mesh_windows_and_the_stitched_mesh_is_the_whole_one(wide):
    whole = mx.medial_axis(wide, method="midsurface", chunks=0)
    blocks = mx.medial_axis(wide, method="midsurface", chunks=CHUNK, n_jobs=2)
    # the windows are smaller than the sheet: the seams are real
    assert CHUNK + 2 * blocks.metadata["mesh_halo"] < max(WIDE)
    assert np.array_equal(blocks.points, whole.points)
    assert np.array_equal(blocks.faces, whole.faces)
    assert np.array_equal(blocks.radii, whole.radii) and np.array_equal(blocks.vertex_kind, whole.vertex_kind)
    a, b = mesh_topology(whole.faces), mesh_topology(blocks.faces)
    assert (b.components, b.euler, b.boundary_edges) == (a.components, a.euler, a.boundary_edges) == (1, a.euler, a.boundary_edges)
    truth = ribbed_panel_truth(WIDE, thickness=4, margin=8)
    assert np.percentile(distance_to_rects(blocks.points, truth), 99) <= 1.0


def test_the_mesh_streams_to_a_ply_file(tmp_path, small):
    trimesh = pytest.importorskip("trimesh")
    grey, whole = small
    out = tmp_path / "mid.ply"
    np.save(tmp_path / "scan.npy", grey)
    written = mx.medial_axis(tmp_path / "scan.npy", method="midsurface", chunks=CHUNK, n_jobs=2, out=out)
    assert written.metadata["written"] == str(out) and len(written.points) == 0
    assert (written.metadata["vertices"], written.metadata["faces"]) == (len(whole.points), len(whole.faces))
    got = trimesh.load(out, process=False)  # read back by trimesh
    radius = np.asarray(got.metadata["_ply_raw"]["vertex"]["data"]["radius"])
    _same_mesh(np.asarray(got.vertices), np.asarray(got.faces), radius, whole)


def test_the_mesh_streams_to_a_zarr_group(tmp_path, small):
    zarr = pytest.importorskip("zarr")
    grey, whole = small
    out = tmp_path / "mid.zarr"
    written = mx.medial_axis(grey, method="midsurface", chunks=CHUNK, n_jobs=2, out=out)
    assert written.metadata["written"] == str(out) and len(written.points) == 0
    assert not (tmp_path / "mid.zarr.part").exists()
    group = zarr.open_group(str(out), mode="r")  # read back by zarr itself
    points, faces = np.asarray(group["vertices"]), np.asarray(group["faces"])
    assert (len(points), len(faces)) == (written.metadata["vertices"], written.metadata["faces"])
    order, ref = _same_mesh(points, faces, np.asarray(group["radii"]), whole)
    assert np.array_equal(np.asarray(group["vertex_kind"])[order], whole.vertex_kind[ref])
    # written again over the old group: the in-memory route writes the same arrays in its own order
    mx.medial_axis(grey, method="midsurface", chunks=0, out=out)
    group = zarr.open_group(str(out), mode="r")
    for key, value in (("vertices", whole.points), ("faces", whole.faces), ("radii", whole.radii),
                       ("vertex_kind", whole.vertex_kind)):
        assert np.array_equal(np.asarray(group[key]), value), key


def test_out_refuses_other_formats(tmp_path, wide):
    with pytest.raises(mx.MedialAxisError, match=".ply"):
        mx.medial_axis(wide[:, :64, :64], method="midsurface", chunks=CHUNK, out=tmp_path / "mid.obj")
    assert not (tmp_path / "mid.obj").exists()


def _sheet(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    occ = np.zeros((6, 40, 40), bool)
    occ[2] = rng.random((40, 40)) < 0.9
    occ[3] = rng.random((40, 40)) < 0.2
    return np.argwhere(occ)


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 10_000), st.integers(8, 30), st.floats(1.0, 3.5))
def test_certain_picks_of_a_window_are_the_whole_sheets(seed, cut, reach):
    voxels = _sheet(seed)
    rng = np.random.default_rng(seed)
    radius = rng.uniform(1.0, reach, len(voxels))
    order = rng.permutation(len(voxels))
    spacing = np.ones(3)
    table = voxel_table(voxels, (6, 40, 40))
    picked = np.zeros(len(voxels), bool)
    picked[K.greedy_subsample(*table, voxels, order, radius, spacing)] = True
    # the window: the voxels with x < cut, in the whole sheet's relative order
    inside = voxels[:, 2] < cut
    rows = np.flatnonzero(inside)
    local = np.full(len(voxels), -1)
    local[rows] = np.arange(len(rows))
    w_order = local[order[inside[order]]]
    w_vox, w_radius = voxels[rows], radius[rows]
    band = w_vox[:, 2] >= cut - int(np.ceil(reach)) - 1
    near_band = w_vox[:, 2] >= cut - 2 * int(np.ceil(reach)) - 2
    w_table = voxel_table(w_vox, (6, 40, 40))
    w_picked = np.zeros(len(rows), bool)
    w_picked[K.greedy_subsample(*w_table, w_vox, w_order, w_radius, spacing)] = True
    certain = K.subsample_certainty(*w_table, w_vox, w_order, w_radius, spacing, band, near_band)
    assert np.array_equal(w_picked[certain], picked[rows][certain])
    assert certain[w_vox[:, 2] < cut - 4 * reach - 2].mean() > 0.5 if (w_vox[:, 2] < cut - 4 * reach - 2).any() else True
    assert np.array_equal(certain, K.subsample_certainty_reference(w_vox, w_order, w_radius, spacing, band, near_band))


def test_a_block_without_free_edge_rays_marches_none():
    # a block whose sheet has no free-edge vertex asks for chords along no ray (it raised on 1024^3 panels)
    from medialaxis.volume.blockwise.blocks import BlockSampler
    from medialaxis.volume.files.sources import ArraySource
    from medialaxis.volume.sheet.extension import centre_on_chords, march_to_iso

    grey = np.full((8, 8, 8), 3000.0)
    none = np.zeros((0, 3))
    for sampled in (grey, BlockSampler(ArraySource(grey), (4, 4, 4), 1000.0)):
        assert march_to_iso(sampled, 2000.0, np.ones(3), none, none, 4.0, 0.25).shape == (0,)
        assert centre_on_chords(sampled, 2000.0, np.ones(3), none, none, np.zeros(0), np.zeros(0)).shape == (0,)
