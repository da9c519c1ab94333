"""The chunked volume route: the same medial voxels and mesh as the in-memory route, block by block.

Truth is the in-memory route on the same array (itself tested against the
phantoms' exact mid-planes). The files other programs wrote are in
``test_chunked_files.py``, worker processes and Ctrl-C in ``test_chunked_processes.py``.
"""

from __future__ import annotations

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.datasets import ribbed_panel, ribbed_panel_slab, ribbed_panel_truth, t_phantom
from medialaxis.errors import Cancelled
from medialaxis.volume.blockwise import chunked
from medialaxis.volume.shell import shell_of_source
from medialaxis.volume.validation import distance_to_rects, mesh_topology

#: Panel whose chunk borders (16, 34, 48) pass through its junctions and free edges: the
#: base's mid-plane (z = 15.5) meets the webs at the z = 16 border, the first web's mid-plane
#: (y = 33.5) is cut by y = 34, the rib's (x = 47.5) by x = 48, and the webs end at z = 64.
PANEL = (76, 112, 96)
MARGIN = 12
BORDERS = (16, 34, 48)


@pytest.fixture(scope="module")
def panel16():
    """The panel as a 16-bit scan (grey 1000 / 3000), as a CT scanner writes it."""
    return ribbed_panel_slab(PANEL, 0, PANEL[0], margin=MARGIN, levels=(1000, 3000), dtype=np.uint16)


@pytest.fixture(scope="module")
def reference(panel16):
    """The in-memory route's voxels and mid-surface."""
    return (mx.medial_axis(panel16, method="voxels", chunks=0),
            mx.medial_axis(panel16, method="midsurface", chunks=0))


def test_the_borders_cut_junctions_and_free_edges():
    truth = ribbed_panel_truth(PANEL, margin=MARGIN)
    assert truth[0].origin[0] == BORDERS[0] - 0.5  # base mid-plane
    assert truth[1].origin[1] == BORDERS[1] - 0.5  # first web
    assert truth[4].origin[2] == BORDERS[2] - 0.5  # rib
    assert truth[1].origin[0] + truth[1].u[0] == 4 * BORDERS[0] - 0.5  # web tops


@pytest.mark.parametrize("chunks", [BORDERS, (24, 40, 40), 64])
def test_medial_voxels_and_mesh_do_not_depend_on_the_chunking(panel16, reference, chunks, same_voxels):
    voxels, mesh = reference
    got = mx.medial_axis(panel16, method="voxels", chunks=chunks, n_jobs=2)
    same_voxels(voxels, got)
    assert got.metadata["iso"] == voxels.metadata["iso"]  # ISO-50 from value counts, block by block
    surface = mx.medial_axis(panel16, method="midsurface", chunks=chunks, n_jobs=2)
    a, b = mesh_topology(mesh.faces), mesh_topology(surface.faces)
    assert (b.components, b.euler, b.boundary_edges) == (a.components, a.euler, a.boundary_edges) and b.components == 1
    assert np.array_equal(surface.faces, mesh.faces) and np.array_equal(surface.points, mesh.points)
    # one mesh across the seams: no vertex twice, no face twice
    assert len(np.unique(surface.points, axis=0)) == len(surface.points)
    assert len(np.unique(np.sort(surface.faces, axis=1), axis=0)) == len(surface.faces)
    # and on the exact mid-planes, extended to the plate ends
    truth = ribbed_panel_truth(PANEL, margin=MARGIN)
    assert np.percentile(distance_to_rects(surface.points, truth), 99) <= 1.0
    assert surface.metadata["chunks"] == list(np.broadcast_to(chunks, 3))


def test_plates_of_two_thicknesses_label_themselves_per_block(same_voxels):
    # a 4-voxel rib on an 8-voxel flange: the route that reads each block twice
    ph = t_phantom((60, 80, 80), thickness=8, stem_thickness=4, margin=8)
    whole = mx.medial_axis(ph.volume, method="voxels", chunks=0)
    for chunks in [(20, 32, 24), 40]:
        same_voxels(whole, mx.medial_axis(ph.volume, method="voxels", chunks=chunks, n_jobs=2))


def test_a_float_scan_gets_the_same_voxels(same_voxels):
    vol = ribbed_panel((64, 96, 80), margin=6).volume  # float32, ISO-50 from a histogram and class sums
    whole = mx.medial_axis(vol, method="voxels", chunks=0)
    got = mx.medial_axis(vol, method="voxels", chunks=32, scheduler="synchronous")
    assert got.metadata["iso"] == pytest.approx(whole.metadata["iso"], rel=1e-9)
    same_voxels(whole, got)


def test_a_dask_array_takes_the_chunked_route(small16, small_reference, same_voxels):
    da = pytest.importorskip("dask.array")
    lazy = da.from_array(small16, chunks=(20, 32, 28))
    got = mx.medial_axis(lazy, method="voxels", n_jobs=2)
    assert got.metadata["chunks"] == [40, 64, 56]  # default 256, cut to the volume
    same_voxels(small_reference, got)


def test_large_inputs_take_the_chunked_route_by_themselves(tmp_path, small16, monkeypatch):
    np.save(tmp_path / "scan.npy", small16)
    monkeypatch.setattr(chunked, "CHUNKED_VOXELS", small16.size - 1)
    assert chunked.use_chunks(str(tmp_path / "scan.npy"), None, None) == (256, 256, 256)
    assert chunked.use_chunks(small16, None, None) == (256, 256, 256)
    assert chunked.use_chunks(small16, 0, None) is None
    monkeypatch.setattr(chunked, "CHUNKED_VOXELS", small16.size)
    assert chunked.use_chunks(small16, None, None) is None
    assert "chunks" not in mx.medial_axis(small16, method="voxels").metadata


def test_a_callback_cancels_between_blocks(small16):
    seen = []

    def stop(stage):
        seen.append(stage)
        return len(seen) < 3

    with pytest.raises(Cancelled):
        mx.medial_axis(small16, chunks=16, n_jobs=1, callback=stop)
    assert len(seen) == 3 and [(p.method, p.step) for p in seen] == [("midsurface", k) for k in range(3)]
    seen.clear()
    with pytest.raises(Cancelled):
        mx.medial_axis(small16, method="voxels", chunks=16, n_jobs=1, callback=stop)
    assert [(p.method, p.step) for p in seen] == [("voxels", k) for k in range(3)]


def test_anisotropic_voxels_give_the_same_voxels(small16, same_voxels):
    spacing = (2.0, 1.0, 0.75)  # slices twice as far apart as the pixels, as CT scans often are
    whole = mx.medial_axis(small16, method="voxels", chunks=0, spacing=spacing)
    same_voxels(whole, mx.medial_axis(small16, method="voxels", chunks=(16, 40, 40), spacing=spacing, n_jobs=2))


def test_a_lazy_array_is_not_read_whole_to_find_its_domain():
    da = pytest.importorskip("dask.array")
    from medialaxis._dispatch import classify

    def refuse(block):
        raise AssertionError("read")

    lazy = da.zeros((64, 64, 64), chunks=32, dtype=np.uint16).map_blocks(refuse, dtype=np.uint16)
    assert classify(lazy) == "volume"


@pytest.mark.parametrize("thickness", [6.0, (4.0, 12.0)])
def test_a_given_thickness_gives_the_same_voxels(small16, thickness, same_voxels):
    # a number: the blocks mark their voxels in one pass; a range: the first pass's pairs finish them
    whole = mx.medial_axis(small16, method="voxels", chunks=0, thickness=thickness)
    same_voxels(whole, mx.medial_axis(small16, method="voxels", chunks=24, thickness=thickness, n_jobs=2))


def test_a_progress_bar_counts_the_blocks(small16, capsys):
    mx.medial_axis(small16, method="voxels", chunks=24, n_jobs=2, show_progress=True)
    err = capsys.readouterr().err
    assert "medial voxels" in err and "/18 " in err  # 40 x 64 x 56 in blocks of 24: 2 x 3 x 3 blocks


def test_the_shell_keeps_only_every_steps_voxels_of_the_planes_it_reads():
    import tracemalloc

    from medialaxis.volume.files.sources import ArraySource

    volume = np.zeros((128, 1024, 1024), np.uint8)  # pages never written cost nothing
    volume[40:80, 300:700, 300:700] = 200
    tracemalloc.start()
    try:
        shell = shell_of_source(ArraySource(volume), 100.0, np.ones(3))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    lo, hi = shell.vertices.min(axis=0), shell.vertices.max(axis=0)
    assert np.all(np.abs(lo - (40, 300, 300)) <= 8) and np.all(np.abs(hi - (80, 700, 700)) <= 8)  # one step: 8
    # 16 planes read (every 8th), each kept as 128 x 128 floats: 1 MiB; whole planes would hold 64 MiB
    assert peak < 16 * 2**20, peak / 2**20
