"""The file formats medialaxis reads and writes: one record per format.

Every list of suffixes in the package is read from :data:`FORMATS` (as
meshio's ``register_format`` puts its formats in one table): the dispatcher
routes an input by its suffix's domains, the batch CLI and ``search`` look
for these suffixes in folders, each domain reads its own formats through the
reader named here, :func:`medialaxis.save` writes through the writer named
here, and ``--help`` lists them. Readers and writers are ``"module:function"``
strings imported on first use, since ``core`` imports none of the domains.

A format read by several domains (``.tif``: an image or a stack of slices;
``.npy``: an image or a volume; ``.json``: GeoJSON or a saved result) is
resolved by the dispatcher from the file's content.
"""

from __future__ import annotations

import dataclasses
import importlib
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from medialaxis.core.outputs import KINDS

__all__ = ["Format", "FORMATS", "ROUTED", "register_format", "named", "format_of", "suffix_of", "suffixes", "reader_suffixes",
           "writer_suffixes",
           "entry_point", "writer_missing", "limits_text", "needs_text"]

#: The domains the dispatcher routes an input to (``"raster"``: GeoTIFF masks of :mod:`medialaxis.gis`, not routed).
ROUTED = ("planar", "mesh", "volume", "result")


@dataclasses.dataclass(frozen=True)
class Format:
    """One file format.

    Attributes
    ----------
    name : str
        What the format is called (``"NIfTI"``).
    suffixes : tuple of str
        Lower-case suffixes with their dot; compound ones (``".nii.gz"``) allowed.
    readers : mapping of str to str
        Per domain (``"planar"``, ``"mesh"``, ``"volume"``, ``"result"``, ``"raster"``) that reads
        the format, its reader as ``"module:function"``; empty for an output-only format.
    block_reader : str or None
        The volume's block reader (:func:`medialaxis.volume.files.sources.open_source`), if it has one.
    writer : str or None
        The function ``writer(result, path)`` that writes a :class:`~medialaxis.MedialAxis` in it.
    holds : tuple of (str, frozenset of str) or None
        What a written file holds, and the kinds of result (:data:`~medialaxis.core.outputs.KINDS`) that fit.
    writer_needs : tuple of (str, str) or None
        The optional module the writer imports and the requirement that installs it.
    """

    name: str
    suffixes: tuple[str, ...]
    readers: Mapping[str, str] = dataclasses.field(default_factory=dict)
    block_reader: str | None = None
    writer: str | None = None
    holds: tuple[str, frozenset[str]] | None = None
    writer_needs: tuple[str, str] | None = None

    @property
    def domains(self) -> tuple[str, ...]:
        """The domains that read the format, in :data:`ROUTED` order (``"raster"`` left out)."""
        return tuple(d for d in ROUTED if d in self.readers)


#: Every format, in the order help texts list them.
FORMATS: list[Format] = []
_BY_SUFFIX: dict[str, Format] = {}


def register_format(fmt: Format) -> Format:
    """Add ``fmt`` to :data:`FORMATS`; a suffix belongs to one format only.

    Raises
    ------
    ValueError
        A suffix already registered, or not lower case with a leading dot.
    """
    for s in fmt.suffixes:
        if s in _BY_SUFFIX or not s.startswith(".") or s != s.lower():
            raise ValueError(f"suffix {s!r} of {fmt.name} is taken or malformed")
    FORMATS.append(fmt)
    _BY_SUFFIX.update(dict.fromkeys(fmt.suffixes, fmt))
    return fmt


def suffix_of(path: str | os.PathLike[str]) -> str:
    """The lower-case suffix of ``path`` that picks its format: a registered compound suffix
    (``.nii.gz``) when the name ends with one, else the last one (``""`` for none).

    >>> suffix_of("scan.NII.GZ"), suffix_of("a.b.png"), suffix_of("folder")
    ('.nii.gz', '.png', '')
    """
    name = Path(path).name.lower()
    for s in _BY_SUFFIX:
        if s.count(".") > 1 and name.endswith(s) and len(name) > len(s):
            return s
    return Path(name).suffix


def named(name: str) -> Format:
    """The registered format called ``name``.

    >>> named("NIfTI").suffixes
    ('.nii', '.nii.gz')
    """
    for fmt in FORMATS:
        if fmt.name == name:
            return fmt
    raise KeyError(f"no format called {name!r}")


def format_of(path: str | os.PathLike[str]) -> Format | None:
    """The registered format of ``path``'s suffix, or None."""
    return _BY_SUFFIX.get(suffix_of(path))


def suffixes(*domains: str) -> tuple[str, ...]:
    """The suffixes of the formats read by any of ``domains``, in registry order.

    >>> suffixes("mesh")
    ('.ply', '.obj', '.off', '.stl', '.glb', '.gltf')
    """
    return tuple(s for f in FORMATS if any(d in f.readers for d in domains) for s in f.suffixes)


def reader_suffixes(domain: str, reader: str) -> tuple[str, ...]:
    """The suffixes that ``domain`` reads with ``reader`` (``"module:function"``)."""
    return tuple(s for f in FORMATS if f.readers.get(domain) == reader for s in f.suffixes)


def writer_suffixes() -> tuple[str, ...]:
    """The suffixes :func:`medialaxis.save` writes, in registry order."""
    return tuple(s for f in FORMATS if f.writer for s in f.suffixes)


def limits_text() -> str:
    """The formats that hold only some kinds of result, for help texts.

    >>> limits_text()
    'GeoJSON: lines and points; SVG: planar axes; SWC: curve skeletons'
    """
    return "; ".join(f"{f.name}: {f.holds[0]}" for f in FORMATS if f.holds and f.holds[1] != frozenset(KINDS))


def needs_text() -> str:
    """The outputs that need an optional package, for help texts.

    >>> needs_text()
    'VTK, VTU need medialaxis[meshio]'
    """
    needs: dict[str, list[str]] = {}
    for f in FORMATS:
        if f.writer_needs:
            needs.setdefault(f.writer_needs[1], []).append(f.name)
    return "; ".join(f"{', '.join(names)} need {requirement}" for requirement, names in needs.items())


def entry_point(entry: str) -> Callable[..., Any]:
    """The function named by a ``"module:function"`` string, its module imported now."""
    module, _, name = entry.partition(":")
    return getattr(importlib.import_module(module), name)  # type: ignore[no-any-return]


def writer_missing(suffix: str) -> str | None:
    """What to install to write ``suffix`` when its writer's optional module is missing; None otherwise."""
    fmt = _BY_SUFFIX.get(suffix)
    if fmt is None or fmt.writer_needs is None:
        return None
    module, requirement = fmt.writer_needs
    try:
        importlib.import_module(module)
    except ImportError:
        return f"writing {suffix} needs {module!r}; install it with `pip install {requirement}`"
    return None


# ------------------------------------------------------------ the table
_IMAGE = "medialaxis.planar.reading.images:read_image"
_DRAWING = "medialaxis.planar.reading.inputs:read_drawing"
_VECTOR = "medialaxis.planar.reading.vectors:read_vector"
_MESH = "medialaxis.mesh.solid.inputs:load_mesh"
_RESULT = "medialaxis.core.lossless:load"
_RASTER = "medialaxis.gis.rasters:read_mask"
_VOLUME = "medialaxis.volume.files.readers:"
_BLOCKS = "medialaxis.volume.files.source_files:"
_WRITE = "medialaxis.core.io:"
_ANY = ("any result", frozenset(KINDS))
_LINES = ("lines and points", frozenset({"planar curves", "space curves", "voxel sets"}))
_CURVES = ("curve skeletons", frozenset({"planar curves", "space curves"}))
_MESHIO = ("meshio", "medialaxis[meshio]")

for _fmt in (
    Format("JSON", (".json",), {"planar": _VECTOR, "result": _RESULT}, writer="medialaxis.core.lossless:write_json",
           holds=_ANY),
    Format("NumPy archive", (".npz",), {"result": _RESULT}, writer="medialaxis.core.lossless:write_npz", holds=_ANY),
    Format("GraphML", (".graphml",), writer=_WRITE + "write_graphml", holds=_ANY),
    Format("GeoJSON", (".geojson",), {"planar": _VECTOR}, writer=_WRITE + "write_geojson", holds=_LINES),
    Format("SVG", (".svg",), {"planar": _DRAWING}, writer=_WRITE + "write_svg",
           holds=("planar axes", frozenset({"planar curves"}))),
    Format("PNG", (".png",), {"planar": _IMAGE}, writer=_WRITE + "write_png", holds=_ANY),
    Format("PLY", (".ply",), {"mesh": _MESH}, writer=_WRITE + "write_ply", holds=_ANY),
    Format("OBJ", (".obj",), {"mesh": _MESH}, writer=_WRITE + "write_obj", holds=_ANY),
    Format("VTK", (".vtk",), writer=_WRITE + "write_vtk", holds=_ANY, writer_needs=_MESHIO),
    Format("VTU", (".vtu",), writer=_WRITE + "write_vtu", holds=_ANY, writer_needs=_MESHIO),
    Format("SWC", (".swc",), writer=_WRITE + "write_swc", holds=_CURVES),
    Format("HTML", (".html",), writer=_WRITE + "write_html", holds=_ANY),
    Format("JPEG", (".jpg", ".jpeg"), {"planar": _IMAGE}),
    Format("BMP", (".bmp",), {"planar": _IMAGE}),
    Format("GIF", (".gif",), {"planar": _IMAGE}),
    Format("TIFF", (".tif", ".tiff"), {"planar": _IMAGE, "volume": _VOLUME + "read_tiff", "raster": _RASTER},
           block_reader=_BLOCKS + "TiffSource"),
    Format("DXF", (".dxf",), {"planar": _DRAWING}),
    Format("WKT", (".wkt",), {"planar": _VECTOR}),
    Format("NumPy array", (".npy",), {"planar": "numpy:load", "volume": _VOLUME + "read_npy"},
           block_reader=_BLOCKS + "npy_source"),
    Format("OFF", (".off",), {"mesh": _MESH}),
    Format("STL", (".stl",), {"mesh": _MESH}),
    Format("glTF", (".glb", ".gltf"), {"mesh": _MESH}),
    Format("NRRD", (".nrrd", ".nhdr"), {"volume": _VOLUME + "read_nrrd"}, block_reader=_BLOCKS + "nrrd_source"),
    Format("NIfTI", (".nii", ".nii.gz"), {"volume": _VOLUME + "read_nifti"}, block_reader=_BLOCKS + "NiftiSource"),
    Format("raw", (".raw",), {"volume": _VOLUME + "read_raw"}, block_reader=_BLOCKS + "raw_source"),
    Format("DICOM", (".dcm",), {"volume": _VOLUME + "read_dicom"}),
    Format("GDAL virtual raster", (".vrt",), {"raster": _RASTER}),
):
    register_format(_fmt)
