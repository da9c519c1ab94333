"""Volume files read by blocks: raw arrays (``.npy``, ``.raw``, NRRD) memory-mapped, TIFF, NIfTI.

A file that is shorter than its header says (a truncated download or copy)
is refused when it is opened, before any work. Compressed NRRD (gzip,
bzip2) and NIfTI (``.nii.gz``) cannot be read at random: they are decompressed
once, slab by slab, into a temporary file (``source.cleanup`` names its folder).
"""

from __future__ import annotations

import bz2
import gzip
import os
import shutil
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._optional import require
from medialaxis.core.formats import named, suffix_of
from medialaxis.errors import InputFileError, InvalidInputError
from medialaxis.volume.files.source_base import Region, Source, check_volume

__all__ = ["MappedSource", "TiffSource", "NiftiSource", "HeaderOnly", "npy_source", "raw_source", "nrrd_source",
           "nrrd_spacing", "raw_layout", "check_raw_size"]


class MappedSource(Source):
    """A raw C-order array at ``offset`` bytes into a file (``.npy``, ``.raw``, raw NRRD)."""

    def __init__(self, path: Path, shape: Any, dtype: Any, offset: int, name: str, spacing: Any = None) -> None:
        self.path, self.offset, self.name, self.spacing = str(path), int(offset), name, spacing
        self.shape, self.dtype = check_volume(shape, dtype, name)
        expected = self.offset + self.nbytes
        size = os.path.getsize(self.path)
        if size < expected:
            raise InputFileError(
                f"{name} has {size} bytes, expected {expected} for shape {self.shape} and dtype {self.dtype} (truncated)"
            )

    def read(self, region: Region) -> np.ndarray:
        mapped = np.memmap(self.path, dtype=self.dtype, mode="r", offset=self.offset, shape=self.shape)
        try:
            return np.array(mapped[region])
        finally:
            del mapped  # unmapped: the pages leave this process's resident memory


def npy_source(path: Path) -> MappedSource:
    try:
        with open(path, "rb") as fh:
            version = np.lib.format.read_magic(fh)
            read_header = np.lib.format.read_array_header_1_0 if version == (1, 0) else np.lib.format.read_array_header_2_0
            shape, fortran, dtype = read_header(fh)
            offset = fh.tell()
    except (ValueError, OSError, SyntaxError) as exc:
        raise InputFileError(f"cannot read .npy header of {str(path)!r}: {exc}") from exc
    if fortran:
        raise InputFileError(f"{str(path)!r} is stored in Fortran order; save it C-ordered (np.save(np.ascontiguousarray(a)))")
    if dtype.hasobject:
        raise InputFileError(f"{str(path)!r} holds Python objects, not voxels")
    return MappedSource(path, shape, dtype, offset, repr(str(path)))


def raw_layout(path: Path, shape: Any, dtype: Any) -> tuple[tuple[int, int, int], np.dtype]:
    """The ``raw_shape`` and ``raw_dtype`` of a raw file, checked (3 positive sizes, a NumPy dtype)."""
    if shape is None or dtype is None:
        raise InvalidInputError(f"reading raw file {str(path)!r} needs the raw_shape=(Z, Y, X) and raw_dtype options")
    try:
        shape = tuple(int(s) for s in shape)
        dt = np.dtype(dtype)
    except (TypeError, ValueError) as exc:
        raise InvalidInputError(f"bad raw shape {shape!r} or dtype {dtype!r}: {exc}") from None
    if len(shape) != 3 or min(shape) < 1:
        raise InvalidInputError(f"raw shape must be 3 positive sizes, got {shape}")
    return shape, dt  # type: ignore[return-value]


def check_raw_size(path: Path, shape: tuple[int, ...], dt: np.dtype) -> None:
    """Refuse a raw file whose size is not ``shape`` times the item size (truncated or the wrong layout)."""
    expected = int(np.prod(shape, dtype=np.int64)) * dt.itemsize
    size = path.stat().st_size
    if size != expected:
        raise InputFileError(
            f"raw file {str(path)!r} has {size} bytes, expected {expected} for shape {shape} and dtype {dt}"
            + (" (truncated)" if size < expected else "")
        )


def raw_source(path: Path, shape: Any, dtype: Any) -> MappedSource:
    shape, dt = raw_layout(path, shape, dtype)
    check_raw_size(path, shape, dt)
    return MappedSource(path, shape, dt, 0, f"raw file {str(path)!r}")


#: NRRD type names (the header's ``type`` field) and their NumPy kinds.
_NRRD_TYPES = {
    "i1": ("signed char", "int8", "int8_t"),
    "u1": ("uchar", "unsigned char", "uint8", "uint8_t"),
    "i2": ("short", "short int", "signed short", "signed short int", "int16", "int16_t"),
    "u2": ("ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"),
    "i4": ("int", "signed int", "int32", "int32_t"),
    "u4": ("uint", "unsigned int", "uint32", "uint32_t"),
    "i8": ("longlong", "long long", "long long int", "signed long long", "signed long long int", "int64", "int64_t"),
    "u8": ("ulonglong", "unsigned long long", "unsigned long long int", "uint64", "uint64_t"),
    "f4": ("float",),
    "f8": ("double",),
}


def nrrd_spacing(header: dict[str, Any]) -> tuple[float, float, float] | None:
    """Spacing per array axis (C order) from an NRRD header, or None."""
    spacing = None
    if "spacings" in header:
        spacing = tuple(float(s) for s in header["spacings"])
    elif "space directions" in header:
        dirs = np.asarray(header["space directions"], dtype=float)
        if dirs.ndim == 2 and np.all(np.isfinite(dirs)):
            spacing = tuple(float(s) for s in np.linalg.norm(dirs, axis=1))
    if spacing is None or len(spacing) != 3:
        return None
    return spacing[::-1]  # type: ignore[return-value]  # the header lists the fastest axis first


class HeaderOnly(Source):
    """The shape and type of a volume file whose data is not opened (a compressed NRRD before decompression)."""

    def __init__(self, shape: Any, dtype: Any, name: str, spacing: Any = None) -> None:
        self.name, self.spacing = name, spacing
        self.shape, self.dtype = check_volume(shape, dtype, name)

    def read(self, region: Region) -> np.ndarray:
        raise RuntimeError(f"{self.name} was opened for its header only")


def nrrd_source(path: Path, spill: bool = True) -> Source:
    nrrd = require("nrrd", "pynrrd")
    name = f"NRRD {str(path)!r}"
    try:
        with open(path, "rb") as fh:
            header = nrrd.read_header(fh)
            offset = fh.tell()
    except Exception as exc:  # noqa: BLE001 - any header error is a bad file
        raise InputFileError(f"cannot read the header of {name}: {exc}") from exc
    kind = next((k for k, names in _NRRD_TYPES.items() if str(header.get("type", "")).lower() in names), None)
    if kind is None:
        raise InputFileError(f"{name} has an unsupported voxel type {header.get('type')!r}")
    dtype = np.dtype(kind).newbyteorder("<" if header.get("endian", "little") == "little" else ">")
    shape = tuple(int(s) for s in header.get("sizes", ()))[::-1]
    data = path
    if "data file" in header or "datafile" in header:
        data = path.parent / str(header.get("data file", header.get("datafile")))
        offset = 0
        if not data.exists():
            raise InputFileError(f"{name} names a data file {str(data)!r} that does not exist")
    skip = int(header.get("byte skip", 0))
    if skip < 0:
        raise InputFileError(f"{name}: 'byte skip: -1' is not supported by the chunked reader")
    offset += skip
    encoding = str(header.get("encoding", "raw")).lower()
    spacing = nrrd_spacing(header)
    if encoding == "raw":
        return MappedSource(data, shape, dtype, offset, name, spacing)
    if encoding in ("gzip", "gz", "bzip2", "bz2"):
        if not spill:
            return HeaderOnly(shape, dtype, name, spacing)
        return _spill(data, offset, encoding, shape, dtype, name, spacing)
    raise InputFileError(f"{name} uses the {encoding!r} encoding; the chunked reader takes raw, gzip and bzip2")


def _inflate(path: Any, offset: int, opener: Any, expected: int, name: str, suffix: str) -> tuple[str, Path, int]:
    """The compressed stream at ``offset`` bytes into ``path`` (``opener``: ``gzip.open`` or ``bz2.open``)
    decompressed once in slabs into a new temporary folder: ``(folder, file, bytes)``; at least
    ``expected`` bytes, or :class:`InputFileError` (the folder removed)."""
    folder = tempfile.mkdtemp(prefix="medialaxis-inflated-")
    target = Path(folder) / f"volume{suffix}"
    written = 0
    try:
        with open(path, "rb") as raw:
            raw.seek(offset)
            with opener(raw, "rb") as stream, open(target, "wb") as out:
                while block := stream.read(64 << 20):
                    out.write(block)
                    written += len(block)
    except (OSError, EOFError, ValueError) as exc:
        shutil.rmtree(folder, ignore_errors=True)
        raise InputFileError(f"cannot decompress {name}: {exc} (truncated or corrupt)") from exc
    if written < expected:
        shutil.rmtree(folder, ignore_errors=True)
        raise InputFileError(f"{name} holds {written} bytes, expected {expected} (truncated)")
    return folder, target, written


def _spill(path: Path, offset: int, encoding: str, shape: Any, dtype: np.dtype, name: str, spacing: Any) -> Source:
    """Decompress a compressed data section once, in slabs, into a temporary raw file."""
    shape, dtype = check_volume(shape, dtype, name)
    expected = int(np.prod(shape, dtype=np.int64)) * dtype.itemsize
    opener = gzip.open if encoding in ("gzip", "gz") else bz2.open
    folder, target, written = _inflate(path, offset, opener, expected, name, ".raw")
    source = MappedSource(target, shape, dtype, 0, name, spacing)
    source.cleanup, source.decompressed = folder, written  # type: ignore[attr-defined]
    return source


class TiffSource(Source):
    """A multi-page TIFF (pages are slices) or a folder of single-page TIFF slices."""

    def __init__(self, path: Path) -> None:
        tifffile = require("tifffile", "tifffile")
        self.name = f"TIFF {str(path)!r}"
        self.files = [str(p) for p in sorted(path.iterdir()) if suffix_of(p) in named("TIFF").suffixes] if path.is_dir() \
            else [str(path)]
        if not self.files:
            raise InputFileError(f"folder {str(path)!r} holds no .tif/.tiff slices")
        self.paged = not path.is_dir()
        shapes, dtypes, pages = set(), set(), 0
        try:
            for f in self.files:
                size = os.path.getsize(f)
                with tifffile.TiffFile(f) as tf:
                    declared = _declared_pages(tf)
                    if declared > len(tf.pages):
                        raise InputFileError(f"{self.name}: {f!r} declares {declared} pages and holds {len(tf.pages)} (truncated)")
                    for page in tf.pages:
                        ends = [int(o) + int(n) for o, n in zip(page.dataoffsets, page.databytecounts)]
                        if max(ends, default=0) > size:
                            raise InputFileError(f"{self.name}: page {pages} of {f!r} ends past the end of the file (truncated)")
                        shapes.add(tuple(page.shape))
                        dtypes.add(np.dtype(page.dtype))
                        pages += 1
        except InputFileError:
            raise
        except Exception as exc:  # noqa: BLE001 - any decoder error is a bad file
            raise InputFileError(f"cannot read {self.name}: {type(exc).__name__}: {exc}") from exc
        if len(shapes) != 1 or len(dtypes) != 1:
            raise InputFileError(f"the slices of {self.name} differ in size or type: {sorted(shapes)}")
        if not self.paged and pages != len(self.files):
            raise InputFileError(f"{self.name}: a folder of slices needs one page per file ({pages} pages in {len(self.files)} files)")
        (plane,), (dtype,) = shapes, dtypes
        if len(plane) != 2:
            raise InputFileError(f"{self.name}: pages of shape {plane} are not 2D slices")
        self.shape, self.dtype = check_volume((pages, *plane), dtype, self.name)

    def read(self, region: Region) -> np.ndarray:
        tifffile = require("tifffile", "tifffile")
        z, y, x = region
        out = np.empty((z.stop - z.start, y.stop - y.start, x.stop - x.start), self.dtype)
        try:
            if self.paged:
                with tifffile.TiffFile(self.files[0]) as tf:
                    for k in range(z.start, z.stop):
                        out[k - z.start] = tf.pages[k].asarray()[y, x]
            else:
                for k in range(z.start, z.stop):
                    out[k - z.start] = tifffile.imread(self.files[k])[y, x]
        except Exception as exc:  # noqa: BLE001
            raise InputFileError(f"cannot read slices {z.start}..{z.stop - 1} of {self.name}: {exc}") from exc
        return out


def _declared_pages(tf: Any) -> int:
    """Pages a TIFF says it has (tifffile's shape or ImageJ's image count), 0 when it does not say."""
    try:
        if tf.is_shaped and tf.shaped_metadata:
            shape = tf.shaped_metadata[0].get("shape", ())
            return int(np.prod(shape)) // max(1, int(np.prod(tf.pages[0].shape)))
        if tf.is_imagej and tf.imagej_metadata:
            return int(tf.imagej_metadata.get("images", 0))
    except (TypeError, ValueError, AttributeError):
        pass
    return 0


class NiftiSource(Source):
    """A NIfTI file read through nibabel's array proxy (scaled by the header's slope and intercept).

    A gzip-compressed file (``.nii.gz``) cannot be read at random (each
    block would decompress the stream from its start): with ``spill`` it is
    decompressed once into a temporary ``.nii`` file (``source.cleanup``
    names its folder, ``source.decompressed`` its size in bytes), which the
    proxy then reads block by block.
    """

    def __init__(self, path: Path, spill: bool = False) -> None:
        nib = require("nibabel", "nibabel")
        self.path, self.name = str(path), f"NIfTI {str(path)!r}"
        try:
            img = nib.load(self.path)
            shape = tuple(int(s) for s in img.shape)
            dtype = img.get_data_dtype()
            slope, inter = img.dataobj.slope, img.dataobj.inter
            zooms = tuple(float(v) for v in img.header.get_zooms()[:3])
            offset = int(img.dataobj.offset)
        except Exception as exc:  # noqa: BLE001
            raise InputFileError(f"cannot read {self.name}: {exc}") from exc
        while len(shape) > 3 and shape[-1] == 1:
            shape = shape[:-1]
        if not (slope in (None, 1.0) and inter in (None, 0.0)) or np.isnan(slope if slope is not None else 0.0):
            dtype = np.dtype(np.float64)
        self.shape, self.dtype = check_volume(shape, dtype, self.name)
        self.spacing = zooms if len(zooms) == 3 else None
        expected = offset + int(np.prod(self.shape, dtype=np.int64)) * img.get_data_dtype().itemsize
        if self.path.lower().endswith(".gz") and spill:
            self.path = self._decompress(expected)
        if not self.path.lower().endswith(".gz") and os.path.getsize(self.path) < expected:
            raise InputFileError(f"{self.name} is shorter than its header says ({expected} bytes): truncated")

    def _decompress(self, expected: int) -> str:
        """The file decompressed once into a temporary ``.nii`` (its path); ``expected`` bytes at least."""
        self.cleanup, target, self.decompressed = _inflate(self.path, 0, gzip.open, expected, self.name, ".nii")
        return str(target)

    def read(self, region: Region) -> np.ndarray:
        nib = require("nibabel", "nibabel")
        proxy = nib.load(self.path).dataobj
        try:
            block = np.asarray(proxy[region] if proxy.ndim == 3 else proxy[(*region,) + (0,) * (proxy.ndim - 3)])
        except Exception as exc:  # noqa: BLE001
            raise InputFileError(f"cannot read {self.name}: {exc}") from exc
        return block.astype(self.dtype, copy=False)
