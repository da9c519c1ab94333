"""Inputs and outputs of ``medialaxis compute`` over many shapes.

``compute`` takes files, glob patterns (expanded here when the shell did not)
and folders. A folder of TIFF or DICOM slices, or a Zarr store, is one volume; any other folder
stands for the shape files in it (images, polygon files, meshes, volumes and
saved results, by extension), in name order. Each input's outputs go to
``--out-dir``, one per ``--format``, named after the input.
"""

from __future__ import annotations

import glob
from collections.abc import Sequence
from pathlib import Path

from medialaxis.core.formats import ROUTED, named, suffix_of, suffixes
from medialaxis.errors import InputFileError

__all__ = ["expand_inputs", "is_slice_folder", "output_names", "SHAPE_SUFFIXES"]

#: Suffixes of the files a folder is searched for: every format an input domain reads
#: (:data:`medialaxis.core.formats.FORMATS`; ``.tif``, ``.npy``: images or volumes by content;
#: ``.json``: polygons or saved results).
SHAPE_SUFFIXES = tuple(sorted(suffixes(*ROUTED)))
#: Suffixes of slice files: a folder holding only these is one volume.
SLICE_SUFFIXES = (*named("TIFF").suffixes, *named("DICOM").suffixes, "")  # DICOM files often have none


def _files(folder: Path) -> list[Path]:
    return sorted(p for p in folder.iterdir() if p.is_file() and not p.name.startswith("."))


def is_slice_folder(folder: Path) -> bool:
    """A folder holding only TIFF or DICOM slices (``.dcm`` or no suffix): one volume."""
    files = _files(folder)
    return bool(files) and all(suffix_of(p) in SLICE_SUFFIXES for p in files)


def is_zarr_store(folder: Path) -> bool:
    """A Zarr array or group (an OME-Zarr image among them): one volume."""
    return folder.suffix.lower() == ".zarr" or any((folder / n).exists() for n in (".zarray", ".zgroup", "zarr.json"))


def expand_inputs(items: Sequence[Path]) -> list[Path]:
    """The shapes named by files, glob patterns and folders, in order, each once.

    Raises
    ------
    InputFileError
        A name that is no file, folder or matching pattern, or a folder with
        no shape file in it.
    """
    out: list[Path] = []
    for item in items:
        text = str(item)
        if not item.exists() and any(c in text for c in "*?["):
            matches = [Path(p) for p in sorted(glob.glob(text))]
            if not matches:
                raise InputFileError(f"no file matches {text!r}")
            out += [p for p in matches if p.is_file() or is_slice_folder(p)]
        elif item.is_dir() and not is_slice_folder(item) and not is_zarr_store(item):
            files = [p for p in _files(item) if suffix_of(p) in SHAPE_SUFFIXES]
            if not files:
                raise InputFileError(f"no shape file in the folder {text!r} (looked for {' '.join(SHAPE_SUFFIXES)})")
            out += files
        else:
            if not item.exists():
                raise InputFileError(f"no such file or folder: {text!r}")
            out.append(item)
    seen: set[Path] = set()
    unique = []
    for path in out:
        key = path.resolve()
        if key not in seen:
            seen.add(key)
            unique.append(path)
    return unique


def output_names(inputs: Sequence[Path], out_dir: Path, formats: Sequence[str]) -> dict[Path, list[Path]]:
    """``out_dir / <stem><format>`` for each input and format; inputs whose
    stems coincide (``a.png``, ``a.tif``) keep their whole name (``a.png.json``),
    and the same name from two folders is numbered (``a_1.json``, ``a_2.json``)."""
    stems = [p.name[: -len(suffix_of(p))] if suffix_of(p) else p.name for p in inputs]
    full = [p.name for p in inputs]
    names = []
    for k, (stem, name) in enumerate(zip(stems, full)):
        if stems.count(stem) == 1:
            names.append(stem)
        elif full.count(name) == 1:
            names.append(name)
        else:  # the same name in two folders: numbered in input order
            names.append(f"{stem}_{full[:k].count(name) + 1}")
    return {p: [out_dir / f"{n}{fmt}" for fmt in formats] for p, n in zip(inputs, names)}
