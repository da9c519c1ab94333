"""The chunked volume route: the same medial voxels and mesh as the in-memory route, block by block.

Truth is the in-memory route on the same array (itself tested against the
phantoms' exact mid-planes) and the files other programs wrote: tifffile,
pynrrd, nibabel, zarr, NumPy.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.errors import Cancelled, EmptyShapeError, InputFileError, InvalidInputError
from medialaxis.volume import chunked
from medialaxis.volume.phantoms import ribbed_panel, ribbed_panel_slab, ribbed_panel_truth, t_phantom
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


def _same_voxels(a, b):
    assert a.points.shape == b.points.shape
    assert np.array_equal(a.points, b.points)
    for key in ("radii", "position", "normal", "voxel_kind"):
        assert np.array_equal(np.asarray(getattr(a, key)), np.asarray(getattr(b, key))), key


def test_the_borders_cut_junctions_and_free_edges():
    truth = ribbed_panel_truth(PANEL, margin=MARGIN)
    assert truth[0].origin[0] == BORDERS[0] - 0.5  # base mid-plane
    assert truth[1].origin[1] == BORDERS[1] - 0.5  # first web
    assert truth[4].origin[2] == BORDERS[2] - 0.5  # rib
    assert truth[1].origin[0] + truth[1].u[0] == 4 * BORDERS[0] - 0.5  # web tops


@pytest.mark.parametrize("chunks", [BORDERS, (24, 40, 40), 64])
def test_medial_voxels_and_mesh_do_not_depend_on_the_chunking(panel16, reference, chunks):
    voxels, mesh = reference
    got = mx.medial_axis(panel16, method="voxels", chunks=chunks, n_jobs=2)
    _same_voxels(voxels, got)
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


def test_plates_of_two_thicknesses_label_themselves_per_block():
    # a 4-voxel rib on an 8-voxel flange: the route that reads each block twice
    ph = t_phantom((60, 80, 80), thickness=8, stem_thickness=4, margin=8)
    whole = mx.medial_axis(ph.volume, method="voxels", chunks=0)
    for chunks in [(20, 32, 24), 40]:
        _same_voxels(whole, mx.medial_axis(ph.volume, method="voxels", chunks=chunks, n_jobs=2))


def test_a_float_scan_gets_the_same_voxels():
    vol = ribbed_panel((64, 96, 80), margin=6).volume  # float32, ISO-50 from a histogram and class sums
    whole = mx.medial_axis(vol, method="voxels", chunks=0)
    got = mx.medial_axis(vol, method="voxels", chunks=32, scheduler="synchronous")
    assert got.metadata["iso"] == pytest.approx(whole.metadata["iso"], rel=1e-9)
    _same_voxels(whole, got)


@pytest.fixture(scope="module")
def small16():
    return (t_phantom((40, 64, 56), margin=6).volume * 2000 + 1000).astype(np.uint16)


@pytest.fixture(scope="module")
def small_reference(small16):
    return mx.medial_axis(small16, method="voxels", chunks=0)


def _writers():
    def npy(path, a):
        np.save(path / "scan.npy", a)
        return path / "scan.npy", {}

    def raw(path, a):
        a.tofile(path / "scan.raw")
        return path / "scan.raw", {"raw_shape": a.shape, "raw_dtype": "uint16"}

    def tiff_stack(path, a):
        tifffile = pytest.importorskip("tifffile")
        tifffile.imwrite(path / "scan.tif", a)
        return path / "scan.tif", {}

    def tiff_folder(path, a):
        tifffile = pytest.importorskip("tifffile")
        (path / "slices").mkdir()
        for k, plane in enumerate(a):
            tifffile.imwrite(path / "slices" / f"s{k:04d}.tif", plane)
        return path / "slices", {}

    def nrrd_raw(path, a):
        nrrd = pytest.importorskip("nrrd")
        nrrd.write(str(path / "scan.nrrd"), a, {"encoding": "raw", "spacings": [1.0, 1.0, 1.0]}, index_order="C")
        return path / "scan.nrrd", {}

    def nrrd_gzip(path, a):
        nrrd = pytest.importorskip("nrrd")
        nrrd.write(str(path / "scan.nrrd"), a, {"encoding": "gzip"}, index_order="C")
        return path / "scan.nrrd", {}

    def nifti(path, a):
        nib = pytest.importorskip("nibabel")
        nib.save(nib.Nifti1Image(a, np.eye(4)), str(path / "scan.nii"))
        return path / "scan.nii", {}

    def nifti_gzip(path, a):
        nib = pytest.importorskip("nibabel")
        nib.save(nib.Nifti1Image(a, np.eye(4)), str(path / "scan.nii.gz"))
        return path / "scan.nii.gz", {}

    def zarr_store(path, a):
        zarr = pytest.importorskip("zarr")
        z = zarr.open_array(str(path / "scan.zarr"), mode="w", shape=a.shape, dtype=a.dtype, chunks=(16, 32, 32))
        z[:] = a
        return path / "scan.zarr", {}

    return [npy, raw, tiff_stack, tiff_folder, nrrd_raw, nrrd_gzip, nifti, nifti_gzip, zarr_store]


@pytest.mark.parametrize("write", _writers(), ids=lambda f: f.__name__)
def test_files_written_by_other_programs_are_read_by_blocks(tmp_path, small16, small_reference, write):
    import tempfile
    from pathlib import Path

    path, options = write(tmp_path, small16)
    before = set(Path(tempfile.gettempdir()).glob("medialaxis-inflated-*"))
    blocks = mx.medial_axis(path, method="voxels", chunks=24, n_jobs=2, **options)
    _same_voxels(small_reference, blocks)
    # a compressed file is decompressed once, to a temporary file, not once per block
    compressed = write.__name__.endswith("gzip")
    assert (blocks.metadata["decompressed"] is not None) == compressed
    assert not compressed or blocks.metadata["decompressed"] >= small16.nbytes
    _same_voxels(small_reference, mx.medial_axis(path, method="voxels", **options))  # small: read whole
    assert set(Path(tempfile.gettempdir()).glob("medialaxis-inflated-*")) == before  # the decompressed copy is gone


def test_a_dask_array_takes_the_chunked_route(small16, small_reference):
    da = pytest.importorskip("dask.array")
    lazy = da.from_array(small16, chunks=(20, 32, 28))
    got = mx.medial_axis(lazy, method="voxels", n_jobs=2)
    assert got.metadata["chunks"] == [40, 64, 56]  # default 256, cut to the volume
    _same_voxels(small_reference, got)


def test_large_inputs_take_the_chunked_route_by_themselves(tmp_path, small16, monkeypatch):
    np.save(tmp_path / "scan.npy", small16)
    monkeypatch.setattr(chunked, "CHUNKED_VOXELS", small16.size - 1)
    assert chunked.use_chunks(str(tmp_path / "scan.npy"), None, None) == (256, 256, 256)
    assert chunked.use_chunks(small16, None, None) == (256, 256, 256)
    assert chunked.use_chunks(small16, 0, None) is None
    monkeypatch.setattr(chunked, "CHUNKED_VOXELS", small16.size)
    assert chunked.use_chunks(small16, None, None) is None
    assert "chunks" not in mx.medial_axis(small16, method="voxels").metadata


def test_the_blocks_run_on_a_cluster_of_worker_processes(tmp_path, small16, small_reference):
    distributed = pytest.importorskip("distributed")
    np.save(tmp_path / "scan.npy", small16)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            _same_voxels(small_reference, mx.medial_axis(tmp_path / "scan.npy", method="voxels", chunks=24,
                                                         scheduler=client))
            mesh = mx.medial_axis(tmp_path / "scan.npy", chunks=24, scheduler=cluster.scheduler_address)
    assert mesh.n_components == 1


def test_a_callback_cancels_between_blocks(small16):
    seen = []

    def stop(stage):
        seen.append(stage)
        return len(seen) < 3

    with pytest.raises(Cancelled):
        mx.medial_axis(small16, chunks=16, n_jobs=1, callback=stop)
    assert len(seen) == 3


def test_bad_inputs_get_a_clear_error(tmp_path, small16):
    small16.tofile(tmp_path / "scan.raw")
    with pytest.raises(InputFileError, match="expected"):
        mx.medial_axis(tmp_path / "scan.raw", chunks=24, raw_shape=(40, 64, 57), raw_dtype="uint16")
    nrrd = pytest.importorskip("nrrd")
    for encoding in ("raw", "gzip"):
        path = tmp_path / f"cut_{encoding}.nrrd"
        nrrd.write(str(path), small16, {"encoding": encoding}, index_order="C")
        data = path.read_bytes()
        path.write_bytes(data[: len(data) - 5000])
        with pytest.raises(InputFileError, match="truncated"):
            mx.medial_axis(path, chunks=24)
    tifffile = pytest.importorskip("tifffile")
    tifffile.imwrite(tmp_path / "cut.tif", small16)
    data = (tmp_path / "cut.tif").read_bytes()
    (tmp_path / "cut.tif").write_bytes(data[: len(data) // 2])
    with pytest.raises(InputFileError):
        mx.medial_axis(tmp_path / "cut.tif", method="midsurface", chunks=24)
    with pytest.raises(InvalidInputError, match="halo"):
        mx.medial_axis(small16, chunks=16, thickness=30)
    with pytest.raises(InvalidInputError, match="chunks"):
        mx.medial_axis(small16, chunks=8)
    nan = small16.astype(np.float32)
    nan[30, 40, 40] = np.nan
    with pytest.raises(InvalidInputError, match="NaN"):
        mx.medial_axis(nan, chunks=24, iso=1500)
    with pytest.raises(EmptyShapeError):
        mx.medial_axis(np.zeros((40, 40, 40), np.uint16), chunks=24, iso=5)


def test_cli_runs_the_chunked_route_and_writes_nothing_on_failure(tmp_path, small16):
    np.save(tmp_path / "scan.npy", small16)
    run = [sys.executable, "-m", "medialaxis", "compute"]
    ok = subprocess.run(run + [str(tmp_path / "scan.npy"), "--method", "midsurface", "--chunks", "24", "--jobs", "2",
                               "-o", str(tmp_path / "mid.ply")], capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    assert (tmp_path / "mid.ply").stat().st_size > 1000
    small16.tofile(tmp_path / "scan.raw")
    bad = subprocess.run(run + [str(tmp_path / "scan.raw"), "--raw-shape", "40", "64", "50", "--raw-dtype", "uint16",
                                "--chunks", "24", "-o", str(tmp_path / "bad.ply")], capture_output=True, text=True)
    assert bad.returncode == 1 and "expected" in bad.stderr and "Traceback" not in bad.stderr
    assert not (tmp_path / "bad.ply").exists() and len(list(tmp_path.iterdir())) == 3
    usage = subprocess.run(run + [str(tmp_path / "scan.npy"), "--chunks", "1", "2"], capture_output=True, text=True)
    assert usage.returncode == 2


def test_ctrl_c_between_blocks_stops_cleanly_and_writes_nothing(tmp_path):
    import signal
    import time

    np.save(tmp_path / "scan.npy", ribbed_panel_slab((96, 192, 192), 0, 96, levels=(1000, 3000), dtype=np.uint16))
    out = tmp_path / "mid.ply"
    proc = subprocess.Popen([sys.executable, "-m", "medialaxis", "compute", str(tmp_path / "scan.npy"), "--chunks", "16",
                             "--jobs", "2", "-o", str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(4.0)  # imported, reading blocks (the run takes far longer with blocks this small)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert err == "medialaxis: interrupted\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scan.npy"]


def test_anisotropic_voxels_give_the_same_voxels(small16):
    spacing = (2.0, 1.0, 0.75)  # slices twice as far apart as the pixels, as CT scans often are
    whole = mx.medial_axis(small16, method="voxels", chunks=0, spacing=spacing)
    _same_voxels(whole, mx.medial_axis(small16, method="voxels", chunks=(16, 40, 40), spacing=spacing, n_jobs=2))


def test_a_lazy_array_is_not_read_whole_to_find_its_domain():
    da = pytest.importorskip("dask.array")
    from medialaxis._dispatch import classify

    def refuse(block):
        raise AssertionError("read")

    lazy = da.zeros((64, 64, 64), chunks=32, dtype=np.uint16).map_blocks(refuse, dtype=np.uint16)
    assert classify(lazy) == "volume"


@pytest.mark.parametrize("thickness", [6.0, (4.0, 12.0)])
def test_a_given_thickness_gives_the_same_voxels(small16, thickness):
    # a number: the blocks mark their voxels in one pass; a range: the first pass's pairs finish them
    whole = mx.medial_axis(small16, method="voxels", chunks=0, thickness=thickness)
    _same_voxels(whole, mx.medial_axis(small16, method="voxels", chunks=24, thickness=thickness, n_jobs=2))


def test_a_progress_bar_counts_the_blocks(small16, capsys):
    mx.medial_axis(small16, method="voxels", chunks=24, n_jobs=2, show_progress=True)
    err = capsys.readouterr().err
    assert "medial voxels" in err and "/18 " in err  # 40 x 64 x 56 in blocks of 24: 2 x 3 x 3 blocks
