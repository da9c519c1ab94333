"""Volumes read block by block: the inputs of the chunked mid-surface route.

Each source knows its ``shape``, ``dtype`` and ``spacing`` from the file's
header and reads any box of voxels on demand (:meth:`Source.read`), never
the whole volume: ``.npy`` and raw files and the raw encoding of NRRD are
memory-mapped for the length of one read, TIFF stacks and folders are read
page by page, NIfTI through nibabel's array proxy, Zarr stores chunk by
chunk (an OME-Zarr image at one level: :mod:`~medialaxis.volume.files.ome_zarr`),
and a ``dask.array.Array`` computes only the box. Compressed NRRD
(gzip, bzip2) cannot be read at random: it is decompressed once, slab by
slab, into a temporary raw file. Sources hold paths, not open files, so they
travel to the workers of a Dask cluster (which must see the same paths).

A file that is shorter than its header says (a truncated download or copy)
is refused when it is opened, before any work.
"""

from __future__ import annotations

import inspect
import os
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._optional import require
from medialaxis.core import formats
from medialaxis.errors import InputFileError, UnsupportedFormatError
from medialaxis.volume.files.source_base import Region, Source, check_volume
from medialaxis.volume.files.source_files import TiffSource

__all__ = ["Source", "Region", "ArraySource", "ZarrSource", "DaskSource", "open_source", "is_zarr_folder"]


class ArraySource(Source):
    """An array already in memory (or any object NumPy can slice, such as an ``np.memmap``)."""

    def __init__(self, array: Any, name: str = "array") -> None:
        self.array = array
        self.name = name
        self.shape, self.dtype = check_volume(array.shape, array.dtype, name)

    def read(self, region: Region) -> np.ndarray:
        return np.array(self.array[region])


class ZarrSource(Source):
    """A 3D array in a Zarr store (a path, or an opened ``zarr.Array``)."""

    def __init__(self, store: Any) -> None:
        zarr = require("zarr", "medialaxis[dask]")
        self.store = str(store) if isinstance(store, (str, os.PathLike)) else store
        self.name = f"Zarr {str(store)!r}"
        try:
            array = zarr.open_array(self.store, mode="r") if isinstance(self.store, str) else self.store
        except Exception as exc:  # noqa: BLE001
            raise InputFileError(f"cannot open {self.name} as a Zarr array: {exc}") from exc
        self.shape, self.dtype = check_volume(array.shape, array.dtype, self.name)

    def read(self, region: Region) -> np.ndarray:
        zarr = require("zarr", "medialaxis[dask]")
        array = zarr.open_array(self.store, mode="r") if isinstance(self.store, str) else self.store
        try:
            return np.asarray(array[region])
        except Exception as exc:  # noqa: BLE001
            raise InputFileError(f"cannot read {self.name}: {exc}") from exc


class DaskSource(Source):
    """A ``dask.array.Array``: each box is computed on its own (synchronously, where the block runs)."""

    def __init__(self, array: Any) -> None:
        self.array, self.name = array, "dask array"
        self.shape, self.dtype = check_volume(array.shape, array.dtype, self.name)

    def read(self, region: Region) -> np.ndarray:
        return np.asarray(self.array[region].compute(scheduler="synchronous"))


def is_zarr_folder(path: Path) -> bool:
    return path.is_dir() and (path.suffix.lower() == ".zarr" or (path / ".zarray").exists() or (path / "zarr.json").exists())


def _call(block_reader: Any, path: Path, **options: Any) -> Source:
    """``block_reader(path, ...)`` given those of ``options`` it takes (the raw layout, ``spill``)."""
    accepted = inspect.signature(block_reader).parameters
    return block_reader(path, **{k: v for k, v in options.items() if k in accepted})  # type: ignore[no-any-return]


def open_source(volume: Any, *, raw_shape: Any = None, raw_dtype: Any = None, header_only: bool = False) -> Source:
    """A :class:`Source` for an array, a Dask or Zarr array, or a volume file or folder.

    ``header_only``: the shape and type are enough (a compressed NRRD is not decompressed).

    Raises
    ------
    InputFileError
        Missing, unreadable or truncated file.
    UnsupportedFormatError
        A file type with no block reader.
    InvalidInputError
        Not 3D, too small, not numeric; raw file without shape and dtype.
    """
    if isinstance(volume, Source):
        return volume
    if isinstance(volume, (str, os.PathLike)):
        path = Path(volume)
        if not path.exists():
            raise InputFileError(f"no such file or folder: {str(path)!r}")
        if is_zarr_folder(path):
            from medialaxis.volume.files.ome_zarr import open_ome_zarr

            return open_ome_zarr(path) or ZarrSource(path)  # an OME-Zarr image's level, or a plain array
        if path.is_dir():
            if any(formats.suffix_of(p) in formats.named("TIFF").suffixes for p in path.iterdir()):
                return TiffSource(path)
            raise UnsupportedFormatError(f"folder {str(path)!r} is not a TIFF stack or Zarr store (DICOM series are read whole)")
        fmt = formats.format_of(path)
        if fmt is None or fmt.block_reader is None:
            known = ", ".join(f.name for f in formats.FORMATS if f.block_reader)
            raise UnsupportedFormatError(f"no block reader for {str(path)!r}: use {known} or Zarr")
        return _call(formats.entry_point(fmt.block_reader), path, shape=raw_shape, dtype=raw_dtype,
                     spill=not header_only)
    module = type(volume).__module__ or ""
    if module.startswith("dask") and hasattr(volume, "chunks"):
        return DaskSource(volume)
    if module.startswith("zarr"):
        return ZarrSource(volume)
    if isinstance(volume, np.ndarray):
        return ArraySource(volume)
    return ArraySource(np.asarray(volume))
