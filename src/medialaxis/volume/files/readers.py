"""Volume file readers: NRRD, NIfTI, TIFF stacks, DICOM series, ``.npy`` and raw.

Every reader returns ``(array, spacing)`` with the array in index order
``(axis0, axis1, axis2)`` as stored and ``spacing`` per array axis (``None``
when the file does not say). Missing, unreadable or truncated files raise
:class:`~medialaxis.errors.InputFileError`.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._optional import require
from medialaxis.core import formats
from medialaxis.core.validate import memory_budget
from medialaxis.errors import InputFileError, InvalidInputError, ResourceLimitError, UnsupportedFormatError
from medialaxis.volume.files.source_files import check_raw_size, nrrd_spacing, raw_layout

__all__ = ["read_volume", "VOLUME_SUFFIXES", "read_dicom", "read_nifti", "read_npy", "read_nrrd", "read_raw", "read_tiff"]

#: Suffixes handled by :func:`read_volume` (a folder is a TIFF or DICOM series), each with its reader in
#: :data:`medialaxis.core.formats.FORMATS`.
VOLUME_SUFFIXES = formats.suffixes("volume")

#: Bytes of working memory per voxel of the in-memory pipeline (distance and
#: feature transforms, labels, masks), used to refuse a volume before reading it.
BYTES_PER_VOXEL = 32


def check_voxels(shape: Any, what: str) -> None:
    """Refuse, before reading, a volume whose declared ``shape`` needs more memory than allowed."""
    try:
        sizes = [int(s) for s in shape]
    except (TypeError, ValueError, OverflowError):
        raise InputFileError(f"{what} declares a bad shape {shape!r}") from None
    if any(s < 0 for s in sizes):
        raise InputFileError(f"{what} declares a negative size in its shape {tuple(sizes)}")
    voxels = 1
    for s in sizes:
        voxels *= s
    limit = memory_budget() // BYTES_PER_VOXEL
    if voxels > limit:
        raise ResourceLimitError(
            f"{what} has {voxels:,} voxels (shape {tuple(sizes)}); at most {limit:,} fit in memory here "
            f"(about {BYTES_PER_VOXEL} bytes per voxel are needed)"
        )



def read_nrrd(path: Path) -> tuple[np.ndarray, Any]:
    nrrd = require("nrrd", "pynrrd")
    check_voxels(nrrd.read_header(str(path)).get("sizes", ()), f"NRRD {str(path)!r}")
    data, header = nrrd.read(str(path), index_order="C")
    return data, (nrrd_spacing(header) if data.ndim == 3 else None)


def read_nifti(path: Path) -> tuple[np.ndarray, Any]:
    nib = require("nibabel", "nibabel")
    img = nib.load(str(path))
    check_voxels(img.shape, f"NIfTI {str(path)!r}")
    data = np.asanyarray(img.dataobj)
    zooms = tuple(float(z) for z in img.header.get_zooms()[: data.ndim])
    return data, zooms if len(zooms) == 3 else None


def read_tiff(path: Path) -> tuple[np.ndarray, Any]:
    tifffile = require("tifffile", "tifffile")
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if formats.suffix_of(p) in formats.named("TIFF").suffixes)
        if not files:
            raise InputFileError(f"folder {str(path)!r} holds no .tif/.tiff slices or .dcm files")
        with tifffile.TiffFile(str(files[0])) as tf:
            check_voxels((len(files), *tf.series[0].shape), f"TIFF series {str(path)!r}")
        data = tifffile.imread([str(f) for f in files])
    else:
        # Page by page: the pages of a stack are its slices. (tifffile's
        # series detection can walk a corrupt file's tags for minutes.)
        with tifffile.TiffFile(str(path)) as tf:
            pages = [tf.pages[i] for i in range(len(tf.pages))]
            shapes = {tuple(page.shape) for page in pages}
            if len(shapes) != 1:
                raise InputFileError(f"the pages of TIFF {str(path)!r} differ in size: {sorted(shapes)}")
            shape = shapes.pop()
            check_voxels((len(pages), *shape) if len(pages) > 1 else shape, f"TIFF {str(path)!r}")
            data = np.stack([page.asarray() for page in pages]) if len(pages) > 1 else pages[0].asarray()
    return data, None


def read_dicom(path: Path) -> tuple[np.ndarray, Any]:
    pydicom = require("pydicom", "pydicom")
    names = (*formats.named("DICOM").suffixes, "")  # DICOM files often have no suffix
    files = sorted(p for p in path.iterdir() if p.is_file() and formats.suffix_of(p) in names) if path.is_dir() else [path]
    slices = []
    for f in files:
        try:
            ds = pydicom.dcmread(str(f))
            slices.append((ds, ds.pixel_array))
        except Exception as exc:  # noqa: BLE001 - any decoder failure is a bad file
            raise InputFileError(f"cannot read DICOM file {str(f)!r}: {exc}") from exc
    if not slices:
        raise InputFileError(f"folder {str(path)!r} holds no DICOM files")

    def position(item: Any) -> float:
        ds = item[0]
        ipp = getattr(ds, "ImagePositionPatient", None)
        return float(ipp[2]) if ipp is not None else float(getattr(ds, "InstanceNumber", 0))

    slices.sort(key=position)
    arrays = [a for _, a in slices]
    if len({a.shape for a in arrays}) != 1:
        raise InputFileError(f"DICOM slices in {str(path)!r} have different sizes")
    data = np.stack(arrays) if arrays[0].ndim == 2 else arrays[0]
    ds0 = slices[0][0]
    pixel = [float(s) for s in getattr(ds0, "PixelSpacing", [1.0, 1.0])]
    if len(slices) > 1:
        dz = abs(position(slices[1]) - position(slices[0])) or float(getattr(ds0, "SliceThickness", 1.0))
    else:
        dz = float(getattr(ds0, "SliceThickness", 1.0))
    return data, (dz, pixel[0], pixel[1])


def read_npy(path: Path) -> tuple[np.ndarray, Any]:
    check_voxels(np.load(path, mmap_mode="r", allow_pickle=False).shape, f"{str(path)!r}")
    return np.load(path, allow_pickle=False), None


def read_raw(path: Path, shape: Any, dtype: Any) -> tuple[np.ndarray, Any]:
    shape, dt = raw_layout(path, shape, dtype)
    check_voxels(shape, f"raw file {str(path)!r}")
    check_raw_size(path, shape, dt)
    return np.fromfile(path, dtype=dt).reshape(shape), None


def read_volume(path: str | os.PathLike[str], *, shape: Any = None, dtype: Any = None) -> tuple[np.ndarray, Any]:
    """Read a 3D volume file or a folder of slices.

    Parameters
    ----------
    path : str or path
        ``.nrrd``/``.nhdr``, ``.nii``/``.nii.gz``, multi-page ``.tif``, a folder
        of TIFF slices or DICOM files, a ``.dcm`` file, ``.npy`` or ``.raw``.
    shape, dtype : optional
        Required for ``.raw``: the array shape ``(Z, Y, X)`` and NumPy dtype.

    Returns
    -------
    array : (Z, Y, X) ndarray
    spacing : tuple of 3 float or None
        Voxel size per array axis when the file records it.

    Raises
    ------
    InputFileError
        Missing, unreadable, truncated or not 3D.
    UnsupportedFormatError
        An extension no reader handles.
    MissingDependencyError
        The reader's optional package is not installed.

    Examples
    --------
    >>> import numpy as np, tempfile, os
    >>> d = tempfile.mkdtemp(); p = os.path.join(d, "v.npy")
    >>> np.save(p, np.zeros((4, 5, 6), np.uint8))
    >>> read_volume(p)[0].shape
    (4, 5, 6)
    """
    p = Path(path)
    if not p.exists():
        raise InputFileError(f"no such file or folder: {str(p)!r}")
    if p.is_dir():
        tiff = formats.named("TIFF").suffixes
        reader = read_tiff if any(formats.suffix_of(q) in tiff for q in p.iterdir() if q.is_file()) else read_dicom
    else:
        fmt = formats.format_of(p)
        if fmt is None or "volume" not in fmt.readers:
            ext = formats.suffix_of(p) or "(none)"
            raise UnsupportedFormatError(f"unsupported volume file type {ext!r} for {str(p)!r}")
        reader = formats.entry_point(fmt.readers["volume"])
        if reader is read_raw:  # the one reader told the layout
            return _check3d(read_raw(p, shape, dtype), p)
    try:
        result = reader(p)
    except (InputFileError, InvalidInputError, ImportError, ResourceLimitError):
        raise
    except MemoryError as exc:
        raise ResourceLimitError(f"reading {str(p)!r} needs more memory than is free: {exc}") from exc
    except Exception as exc:  # noqa: BLE001 - decoder errors of any kind mean a bad file
        raise InputFileError(f"cannot read volume {str(p)!r}: {type(exc).__name__}: {exc}") from exc
    return _check3d(result, p)


def _check3d(result: tuple[np.ndarray, Any], path: Path) -> tuple[np.ndarray, Any]:
    data, spacing = result
    data = np.asarray(data)
    data = np.squeeze(data) if data.ndim > 3 else data
    if data.ndim != 3:
        raise InputFileError(f"{str(path)!r} holds a {data.ndim}D array of shape {data.shape}, expected a 3D volume")
    return data, spacing
