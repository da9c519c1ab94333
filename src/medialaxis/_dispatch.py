"""Route an input to its domain (planar, mesh, volume) and method.

The domains never import one another; this module only knows where their
entry points live (``"module:function"`` strings, imported on first use).
"""

from __future__ import annotations

import functools
import importlib
import inspect
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.core.formats import format_of, suffix_of
from medialaxis.core.io import is_result_file, load
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import is_geometry_text
from medialaxis.errors import InputFileError, InvalidInputError, UnsupportedFormatError

__all__ = ["METHODS", "DEFAULT_METHOD", "OPTIONS", "RESULT", "classify", "resolve", "option_types", "repruner", "load_result"]

#: Entry points per domain and method name.
METHODS: dict[str, dict[str, str]] = {
    "planar": {
        "voronoi": "medialaxis.planar.pipeline:voronoi_medial_axis",
    },
    "mesh": {
        "flow": "medialaxis.mesh.flow:flow_skeleton",
        "voronoi": "medialaxis.mesh.voronoi:voronoi_medial_axis",
    },
    "volume": {
        "midsurface": "medialaxis.volume.pipeline:midsurface_medial_axis",
        "voxels": "medialaxis.volume.voxel_axis:medial_voxel_axis",
    },
}

#: The options dataclass of each method (:mod:`medialaxis.core.options`), keyed by (domain, method).
OPTIONS: dict[tuple[str, str], str] = {
    ("planar", "voronoi"): "medialaxis.planar.options:PlanarOptions",
    ("mesh", "flow"): "medialaxis.mesh.options:FlowOptions",
    ("mesh", "voronoi"): "medialaxis.mesh.options:MeshVoronoiOptions",
    ("volume", "midsurface"): "medialaxis.volume.options:MidsurfaceOptions",
    ("volume", "voxels"): "medialaxis.volume.options:VoxelOptions",
}

#: Default method per domain.
DEFAULT_METHOD = {"planar": "voronoi", "mesh": "voronoi", "volume": "midsurface"}

#: The pseudo-domain of results saved by :meth:`MedialAxis.save` (``.json``, ``.npz``).
RESULT = "result"

#: Options a saved result accepts: they re-prune it (see :meth:`MedialAxis.prune`).
PRUNING_OPTIONS = ("lam", "detour")

#: Re-pruning entry points, keyed by (domain, method): where lambda means something and the result keeps what
#: it was selected from (the planar unpruned axis, the mesh Voronoi method's full complex, a skeleton's branches).
REPRUNERS: dict[tuple[str, str], str] = {
    ("planar", "voronoi"): "medialaxis.planar.pipeline:reprune",
    ("mesh", "voronoi"): "medialaxis.mesh.medial.reprune:reprune",
    ("mesh", "flow"): "medialaxis.mesh.skeleton.branch_prune:reprune",
}

#: A compiled kernel that every call of each method runs, keyed by (domain, method): while it is not compiled
#: yet (the first call after an install, unless ``medialaxis warmup`` ran), the call says on a terminal that it
#: compiles (:func:`medialaxis._jit.announce_compiling`).
FIRST_KERNELS: dict[tuple[str, str], str] = {
    ("planar", "voronoi"): "medialaxis.planar.boundary._rounds_kernels:incremental_rounds",
    ("mesh", "voronoi"): "medialaxis.mesh.sample._delaunay_kernels:_insert",
    ("mesh", "flow"): "medialaxis.mesh.solid._intersect_kernels:near_pairs",
    ("volume", "midsurface"): "medialaxis.volume._kernels:adjacent_gaps",
    ("volume", "voxels"): "medialaxis.volume._kernels:adjacent_gaps",
}

#: The default colour axis of a 3D array (scikit-image's ``channel_axis``).
CHANNEL_AXIS = -1


def _classify_path(path: Path, method: str | None, channel_axis: Any = CHANNEL_AXIS) -> str:
    try:
        exists = path.exists()
    except OSError as exc:  # a name too long, say
        raise InputFileError(f"not a file name: {str(path)[:60]!r}...: {exc.strerror}") from exc
    if not exists:
        raise InputFileError(f"no such file or folder: {str(path)!r}")
    if path.is_dir():
        return "volume"  # TIFF slices or a DICOM series
    fmt = format_of(path)
    domains = fmt.domains if fmt is not None else ()
    if not domains:  # unknown, or written but not read (.vtk, .swc, ...)
        raise UnsupportedFormatError(f"unsupported file type {suffix_of(path) or '(none)'!r} for {str(path)!r}")
    if RESULT in domains and (len(domains) == 1 or is_result_file(path)):
        return RESULT
    domains = tuple(d for d in domains if d != RESULT)
    if len(domains) == 1:
        return domains[0]
    return _PEEK[fmt.name](path, method, channel_axis)  # type: ignore[union-attr]


def _tiff_domain(path: Path, method: str | None, channel_axis: Any) -> str:
    """A multi-page TIFF is a volume, a single page an image; a volume method makes it a volume."""
    if method in METHODS["volume"]:
        return "volume"
    try:
        from medialaxis.core.images import open_image

        with open_image(path, None) as im:  # the page count only: nothing is decoded
            return "volume" if getattr(im, "n_frames", 1) > 1 else "planar"
    except Exception as exc:  # noqa: BLE001 - any decoder failure is a bad file
        raise InputFileError(f"cannot read TIFF {str(path)!r}: {exc}") from exc


def _npy_domain(path: Path, method: str | None, channel_axis: Any) -> str:
    """A ``.npy`` array by its dimensions (:func:`_classify_ndim`); a volume method makes it a volume."""
    try:
        arr = np.load(path, mmap_mode="r", allow_pickle=False)
    except Exception as exc:  # noqa: BLE001
        raise InputFileError(f"cannot read {str(path)!r}: {exc}") from exc
    if method in METHODS["volume"]:
        return "volume"
    return _classify_ndim(arr.ndim, arr.shape, arr.dtype, channel_axis)


#: How the formats that two domains read are told apart: by their content (:attr:`Format.domains`).
_PEEK = {"TIFF": _tiff_domain, "NumPy array": _npy_domain}


def _classify_ndim(ndim: int, shape: tuple[int, ...], dtype: np.dtype, channel_axis: Any = CHANNEL_AXIS) -> str:
    if ndim == 2:
        return "planar"
    if ndim == 3:
        # an (rows, cols, 3 | 4) array is a colour image (skimage.io.imread's), unless channel_axis=None
        if isinstance(channel_axis, (int, np.integer)) and not isinstance(channel_axis, bool):
            if -3 <= int(channel_axis) < 3 and shape[int(channel_axis)] in (3, 4):
                return "planar"
        return "volume"
    raise InvalidInputError(f"expected a 2D image, an (n, 2) boundary loop or a 3D volume, got an array of shape {shape}")


def classify(shape: Any, method: str | None = None, options: Mapping[str, Any] | None = None) -> str:
    """Return the domain (``"planar"``, ``"mesh"``, ``"volume"``) of an input, or :data:`RESULT`.

    A 3D array whose ``channel_axis`` (option, default the last axis) has 3
    or 4 entries is a colour image, planar; ``channel_axis=None`` or a
    volume method makes it a volume.
    """
    channel_axis = (options or {}).get("channel_axis", CHANNEL_AXIS)
    if is_geometry_text(shape):  # WKT or GeoJSON text, not a file name
        return "planar"
    if isinstance(shape, (str, os.PathLike)):
        return _classify_path(Path(shape), method, channel_axis)
    module = type(shape).__module__ or ""
    if module.startswith("shapely"):
        return "planar"
    if hasattr(shape, "vertices") and hasattr(shape, "faces"):
        return "mesh"
    if isinstance(shape, (list, tuple)) and shape and all(hasattr(s, "geom_type") for s in shape):
        return "planar"
    if module.startswith(("dask", "zarr")) and hasattr(shape, "ndim") and hasattr(shape, "dtype"):
        return _classify_ndim(shape.ndim, tuple(shape.shape), shape.dtype, None)  # lazy arrays: volumes
    try:
        arr = np.asarray(shape)
    except Exception as exc:  # noqa: BLE001
        raise InvalidInputError(f"cannot interpret input of type {type(shape).__name__}") from exc
    if arr.dtype == object:
        raise InvalidInputError(f"cannot interpret input of type {type(shape).__name__} as a shape")
    if method in METHODS["volume"]:
        return "volume" if arr.ndim == 3 else _classify_ndim(arr.ndim, arr.shape, arr.dtype, None)
    return _classify_ndim(arr.ndim, arr.shape, arr.dtype, channel_axis)


def _load(entry: str) -> Callable[..., Any]:
    module, _, name = entry.partition(":")
    return getattr(importlib.import_module(module), name)


def option_types() -> dict[tuple[str, str], Any]:
    """The options dataclass of every method, keyed by (domain, method)."""
    return {key: _load(entry) for key, entry in OPTIONS.items()}


def resolve(domain: str, method: str | None) -> tuple[str, Callable[..., Any]]:
    """Entry point of ``method`` (or the domain's default) for ``domain``."""
    name = DEFAULT_METHOD[domain] if method is None else method
    available = METHODS[domain]
    if name not in available:
        known = ", ".join(sorted(available)) or "none yet"
        raise InvalidInputError(f"method {name!r} does not apply to {domain} input (available: {known})")
    return name, _load(available[name])


def announce_compiling(domain: str, method: str) -> bool:
    """Say on a terminal that this call compiles the method's kernels, when it will (see :data:`FIRST_KERNELS`)."""
    from medialaxis import _jit

    return _jit.announce_compiling(_load(FIRST_KERNELS[domain, method]), f"{domain} {method}")


@functools.lru_cache(maxsize=64)
def _signature(fn: Callable[..., Any]) -> inspect.Signature:
    return inspect.signature(fn)  # 0.1-0.2 ms a call: 3-4% of a small shape's axis


def call_checked(fn: Callable[..., Any], shape: Any, options: Mapping[str, Any]) -> Any:
    """Call ``fn(shape, **options)`` after checking the option names."""
    sig = _signature(fn)
    try:
        sig.bind(shape, **options)
    except TypeError as exc:
        accepted = [p for p in sig.parameters if p != next(iter(sig.parameters))]
        bad = [k for k in options if k not in sig.parameters]
        detail = f"unknown option(s) {', '.join(map(repr, bad))}" if bad else str(exc)
        raise InvalidInputError(f"{detail}; {fn.__name__} accepts {', '.join(accepted)}") from None
    return fn(shape, **options)


def repruner(metadata: Mapping[str, Any]) -> Callable[..., Any]:
    """The re-pruning function of the domain that produced ``metadata``."""
    key = (metadata.get("domain"), metadata.get("method"))
    if key not in REPRUNERS:
        raise InvalidInputError(f"results of the {key[0]!r} domain's {key[1]!r} method cannot be re-pruned")
    return _load(REPRUNERS[key])  # type: ignore[index]


def load_result(path: str | os.PathLike[str], method: str | None, options: Mapping[str, Any]) -> MedialAxis:
    """A saved result, as loaded, or re-pruned when ``lam`` or ``detour`` is given.

    Raises
    ------
    InvalidInputError
        ``method`` differs from the saved one, or an option other than the
        pruning options is given (the axis is computed already).
    InputFileError
        The file cannot be read.
    """
    ma = load(path)
    saved = ma.metadata.get("method")
    if method is not None and method != saved:
        raise InvalidInputError(f"{str(path)!r} is a saved {saved!r} result; method {method!r} does not apply to it")
    bad = [k for k, v in options.items() if v is not None and k not in PRUNING_OPTIONS]
    if bad:
        raise InvalidInputError(
            f"{str(path)!r} is a saved result, returned as loaded; option(s) {', '.join(map(repr, bad))} "
            f"apply when computing an axis (only {', '.join(PRUNING_OPTIONS)} re-prune a saved one)"
        )
    pruning = {k: v for k, v in options.items() if v is not None}
    if pruning and not hasattr(ma, "prune"):
        raise InvalidInputError(f"{str(path)!r}: {ma._no_prune()}")
    return ma.prune(**pruning) if pruning else ma
