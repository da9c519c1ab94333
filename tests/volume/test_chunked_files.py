"""The chunked volume route reads the files other programs wrote, block by block, and refuses bad ones.

Truth is the in-memory route on the same array and the files written by
tifffile, pynrrd, nibabel, zarr and NumPy; the command line runs in a child process.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.errors import EmptyShapeError, InputFileError, InvalidInputError


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
def test_files_written_by_other_programs_are_read_by_blocks(tmp_path, small16, small_reference, write, same_voxels):
    import tempfile
    from pathlib import Path

    path, options = write(tmp_path, small16)
    before = set(Path(tempfile.gettempdir()).glob("medialaxis-inflated-*"))
    blocks = mx.medial_axis(path, method="voxels", chunks=24, n_jobs=2, **options)
    same_voxels(small_reference, blocks)
    # a compressed file is decompressed once, to a temporary file, not once per block
    compressed = write.__name__.endswith("gzip")
    assert (blocks.metadata["decompressed"] is not None) == compressed
    assert not compressed or blocks.metadata["decompressed"] >= small16.nbytes
    same_voxels(small_reference, mx.medial_axis(path, method="voxels", **options))  # small: read whole
    assert set(Path(tempfile.gettempdir()).glob("medialaxis-inflated-*")) == before  # the decompressed copy is gone


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
