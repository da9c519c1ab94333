"""Input validation, file readers and clear errors."""

import os

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.errors import EmptyShapeError, InputFileError, InvalidInputError, UnsupportedFormatError
from medialaxis.volume.files.readers import read_volume
from medialaxis.volume.inputs import load_volume


@pytest.fixture
def grey():
    rng = np.random.default_rng(1)
    vol = np.zeros((16, 24, 22), np.uint16)
    vol[5:11, 3:21, 3:19] = 1000
    return vol + rng.integers(0, 50, vol.shape).astype(np.uint16)


def test_bad_arrays():
    with pytest.raises(InvalidInputError, match="3D"):
        load_volume(np.zeros((10, 10, 2, 2), bool))
    with pytest.raises(EmptyShapeError, match="empty"):
        load_volume(np.zeros((8, 8, 8), bool))
    with pytest.raises(EmptyShapeError, match="full"):
        load_volume(np.ones((8, 8, 8), bool))
    nan = np.ones((8, 8, 8))
    nan[0, 0, 0] = np.nan
    with pytest.raises(InvalidInputError, match="NaN"):
        load_volume(nan)
    with pytest.raises(InvalidInputError, match="dtype"):
        load_volume(np.full((8, 8, 8), "a"))
    with pytest.raises(InvalidInputError, match="spacing"):
        load_volume(np.eye(8)[None].repeat(8, 0).astype(bool), spacing=(1, -1, 1))
    with pytest.raises(InvalidInputError, match="iso"):
        load_volume(np.eye(8)[None].repeat(8, 0), iso="x")


def test_two_d_array_goes_to_planar_and_method_is_checked():
    with pytest.raises(InvalidInputError, match="does not apply to planar"):
        mx.medial_axis(np.zeros((10, 10), bool), method="midsurface")
    with pytest.raises(InvalidInputError, match="unknown option"):
        mx.medial_axis(np.ones((9, 9, 9), bool), method="midsurface", wrong=1)


def test_thickness_that_does_not_fit(flat_plate):
    with pytest.raises(InvalidInputError, match="does not fit"):
        mx.medial_axis(flat_plate, method="midsurface", thickness=40)
    with pytest.raises(InvalidInputError, match="under 2 voxels"):
        mx.medial_axis(flat_plate, method="midsurface", thickness=1)
    with pytest.raises(InvalidInputError, match="thickness"):
        mx.medial_axis(flat_plate, method="midsurface", thickness=-3)
    with pytest.raises(EmptyShapeError, match="lam"):
        mx.medial_axis(flat_plate, method="midsurface", lam=50.0)


def test_grey_otsu_and_iso_threshold_aliases(grey):
    a = mx.medial_axis(grey, method="midsurface")
    b = mx.medial_axis(grey, method="midsurface", threshold=500)
    c = mx.medial_axis(grey, method="midsurface", iso=500)
    assert 450 < a.metadata["iso"] < 600  # half-way between the air (~25) and material (~1025) levels
    assert np.percentile(np.abs(a.points[:, 0] - 7.5), 99) < 0.5  # the plate's mid-plane
    assert np.allclose(b.points, c.points)
    with pytest.raises(InvalidInputError, match="disagree"):
        mx.medial_axis(grey, method="midsurface", threshold=500, iso=400)


def _same(path, vol, **kw):
    got, spacing = read_volume(path, **kw)
    assert np.array_equal(got, vol)
    return spacing


def test_readers_round_trip(tmp_path, grey):
    import nibabel as nib
    import nrrd
    import tifffile

    np.save(tmp_path / "v.npy", grey)
    assert _same(tmp_path / "v.npy", grey) is None
    grey.tofile(tmp_path / "v.raw")
    assert _same(tmp_path / "v.raw", grey, shape=grey.shape, dtype="uint16") is None
    nrrd.write(str(tmp_path / "v.nrrd"), grey, {"spacings": [0.5, 0.25, 2.0]}, index_order="C")
    assert _same(tmp_path / "v.nrrd", grey) == (2.0, 0.25, 0.5)  # header lists the fastest axis first
    nib.save(nib.Nifti1Image(grey, np.diag([0.7, 0.8, 0.9, 1])), str(tmp_path / "v.nii.gz"))
    assert np.allclose(_same(tmp_path / "v.nii.gz", grey), (0.7, 0.8, 0.9))
    tifffile.imwrite(tmp_path / "v.tif", grey)
    _same(tmp_path / "v.tif", grey)
    (tmp_path / "slices").mkdir()
    for k, sl in enumerate(grey):
        tifffile.imwrite(tmp_path / "slices" / f"s{k:03d}.tif", sl)
    _same(tmp_path / "slices", grey)


def _write_dicom_series(folder, vol, spacing):
    from pydicom.dataset import Dataset, FileMetaDataset
    from pydicom.uid import ExplicitVRLittleEndian, generate_uid

    for k, sl in enumerate(vol):
        meta = FileMetaDataset()
        meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2"
        meta.MediaStorageSOPInstanceUID = generate_uid()
        meta.TransferSyntaxUID = ExplicitVRLittleEndian
        ds = Dataset()
        ds.file_meta = meta
        ds.SOPClassUID, ds.SOPInstanceUID = meta.MediaStorageSOPClassUID, meta.MediaStorageSOPInstanceUID
        ds.Rows, ds.Columns = sl.shape
        ds.SamplesPerPixel, ds.PhotometricInterpretation = 1, "MONOCHROME2"
        ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 16, 16, 15, 0
        ds.PixelSpacing = [spacing[1], spacing[2]]
        ds.ImagePositionPatient = [0, 0, spacing[0] * k]
        ds.InstanceNumber = k
        ds.PixelData = np.ascontiguousarray(sl, np.uint16).tobytes()
        # write slices in reverse order of names: the reader sorts by position
        ds.save_as(str(folder / f"im{len(vol) - k:03d}.dcm"), enforce_file_format=True)


def test_dicom_series(tmp_path, grey):
    (tmp_path / "dcm").mkdir()
    _write_dicom_series(tmp_path / "dcm", grey, (0.5, 1.0, 1.0))
    assert np.allclose(_same(tmp_path / "dcm", grey), (0.5, 1.0, 1.0))
    ma = mx.medial_axis(str(tmp_path / "dcm"), method="midsurface")
    assert ma.metadata["spacing"] == [0.5, 1.0, 1.0]
    assert np.median(2 * ma.radii) == pytest.approx(6 * 0.5, rel=0.1)


def test_file_errors(tmp_path, grey):
    with pytest.raises(InputFileError, match="no such file"):
        read_volume(tmp_path / "missing.nrrd")
    grey.tofile(tmp_path / "v.raw")
    with pytest.raises(InputFileError, match="truncated"):
        read_volume(tmp_path / "v.raw", shape=(17, 24, 22), dtype="uint16")
    with pytest.raises(InvalidInputError, match="shape"):
        read_volume(tmp_path / "v.raw")
    (tmp_path / "bad.nrrd").write_bytes(b"NRRD0004\ntype: garbage\n\n")
    with pytest.raises(InputFileError, match="cannot read"):
        read_volume(tmp_path / "bad.nrrd")
    (tmp_path / "bad.nii").write_bytes(b"\0" * 100)
    with pytest.raises(InputFileError):
        read_volume(tmp_path / "bad.nii")
    np.save(tmp_path / "flat.npy", np.zeros((4, 4)))
    with pytest.raises(InputFileError, match="2D"):
        read_volume(tmp_path / "flat.npy")
    (tmp_path / "x.xyz").write_text("?")
    with pytest.raises(UnsupportedFormatError):
        read_volume(tmp_path / "x.xyz")
    (tmp_path / "empty").mkdir()
    with pytest.raises(InputFileError, match="no DICOM"):
        read_volume(tmp_path / "empty")
    with open(tmp_path / "cut.tif", "wb") as fh:
        import tifffile

        tifffile.imwrite(tmp_path / "whole.tif", grey)
        fh.write((tmp_path / "whole.tif").read_bytes()[:500])
    with pytest.raises(InputFileError):
        read_volume(tmp_path / "cut.tif")


def test_raw_through_dispatcher(tmp_path, flat_plate):
    path = tmp_path / "plate.raw"
    flat_plate.astype(np.uint8).tofile(path)
    ma = mx.medial_axis(str(path), method="midsurface", raw_shape=flat_plate.shape, raw_dtype="uint8", iso=0.5,
                        spacing=0.5)
    assert np.allclose(ma.points[:, 0], 9.5 * 0.5)
    assert os.path.exists(path)
