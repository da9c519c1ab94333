"""Results saved losslessly and read back equal: ``.json`` and ``.npz``, validated on load.

A result reads back with the same arrays, the same metadata (value for value:
:func:`~medialaxis.core.metadata.frozen_metadata` keeps it JSON-like), its input
shape (a planar geometry as WKT; a mesh or an isosurface as vertices and
faces, a mesh read back as a ``trimesh.Trimesh`` when trimesh is installed)
and its unpruned axis, so :meth:`~medialaxis.core.result.MedialAxis.prune`
still works. The wall-clock ``metadata["timings"]`` is written only when
asked for (``timings=True``).
"""

from __future__ import annotations

import base64
import json
import os
import re
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.core.export.scene3d import Surface
from medialaxis.core.metadata import jsonable
from medialaxis.core.outputs import atomic_write
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InputFileError, UnsupportedFormatError

__all__ = ["load", "is_result_file", "write_json", "write_npz", "jsonable", "FORMAT_VERSION", "LOSSLESS"]

#: The formats :func:`load` reads back.
LOSSLESS = (".json", ".npz")


#: 2: the input shape of every method (a mesh's or an isosurface's vertices and faces, not only a planar
#: geometry's WKT), metadata without the wall-clock ``timings`` unless asked for. Version 1 files still load.
FORMAT_VERSION = 2


def _metadata(ma: MedialAxis, timings: bool) -> dict[str, Any]:
    meta = jsonable(ma.metadata)
    if not timings:
        meta.pop("timings", None)
    meta["dim"] = ma.dim
    return meta


def _shape_parts(shape: Any, parent: Any) -> dict[str, Any] | None:
    """What is saved of an input shape: a planar geometry as WKT, a surface as its vertices and faces.

    ``"parent"``: the unpruned axis's shape is its pruned result's (saved once). Anything else
    (an object none of the methods keeps) is not saved.
    """
    if shape is None:
        return None
    if parent is not None and shape is parent:
        return {"type": "parent"}
    if hasattr(shape, "wkt"):
        return {"type": "geometry", "wkt": shape.wkt}
    if hasattr(shape, "vertices") and hasattr(shape, "faces"):
        kind = "surface" if isinstance(shape, Surface) else "mesh"
        return {"type": kind, "vertices": np.asarray(shape.vertices, np.float64).reshape(-1, 3),
                "faces": np.asarray(shape.faces, np.int64).reshape(-1, 3)}
    return None


def _shape_from(parts: dict[str, Any] | str | None, parent: Any) -> Any:
    """The shape saved by :func:`_shape_parts` (or a version 1 file's WKT text)."""
    if not parts:
        return None
    if isinstance(parts, str):
        parts = {"type": "geometry", "wkt": parts}
    kind = parts["type"]
    if kind == "parent":
        return parent
    if kind == "geometry":
        import shapely

        return shapely.from_wkt(parts["wkt"])
    vertices = np.asarray(_array(parts["vertices"]), np.float64).reshape(-1, 3)
    faces = np.asarray(_array(parts["faces"]), np.int64).reshape(-1, 3)
    if kind == "mesh":
        try:
            import trimesh
        except ImportError:  # the mesh extra is not installed: the surface still draws and compares
            return Surface(vertices, faces)
        return trimesh.Trimesh(vertices, faces, process=False)
    if kind == "surface":
        return Surface(vertices, faces)
    raise InputFileError(f"unknown shape type {kind!r}")


def _packed(array: np.ndarray) -> dict[str, Any]:
    """An array as JSON text in little-endian bytes, base64: a meshed shape of 10^5 vertices as digits took
    seconds to write."""
    array = np.ascontiguousarray(array, array.dtype.newbyteorder("<"))
    return {"dtype": array.dtype.str, "shape": list(array.shape), "base64": base64.b64encode(array.tobytes()).decode()}


def _array(value: Any) -> np.ndarray:
    """:func:`_packed`'s array back, or a plain list's."""
    if isinstance(value, dict):
        return np.frombuffer(base64.b64decode(value["base64"]), np.dtype(value["dtype"])).reshape(value["shape"])
    return np.asarray(value)


def _to_dict(ma: MedialAxis, timings: bool = False, parent: Any = None) -> dict[str, Any]:
    shape = _shape_parts(ma.shape, parent)
    if shape is not None and "vertices" in shape:
        shape = dict(shape, vertices=_packed(shape["vertices"]), faces=_packed(shape["faces"]))
    return {
        "format": "medialaxis",
        "version": FORMAT_VERSION,
        "points": ma.points.tolist(),
        "radii": ma.radii.tolist(),
        "edges": ma.edges.tolist(),
        "faces": ma.faces.tolist(),
        # Infinite values (contacts on different rings) are kept as JSON
        # ``Infinity``, which Python's json module reads back.
        "extras": {k: {"dtype": str(v.dtype), "shape": list(v.shape), "data": v.tolist()} for k, v in ma.extras.items()},
        "metadata": _metadata(ma, timings),
        "shape": jsonable(shape),
        "raw": _to_dict(ma.raw, timings, ma.shape) if ma.raw is not None else None,
    }


def _extra_from_json(spec: dict[str, Any]) -> np.ndarray:
    return np.asarray(spec["data"], dtype=spec["dtype"]).reshape(spec["shape"])


def _from_dict(d: dict[str, Any], parent: Any = None) -> MedialAxis:
    if d.get("format") != "medialaxis":
        raise InputFileError("not a medialaxis result file")
    shape = _shape_from(d.get("shape"), parent)
    meta = d.get("metadata", {})
    dim = int(meta.pop("dim", len(d["points"][0]) if d["points"] else 2))
    return MedialAxis(
        np.asarray(d["points"], np.float64).reshape(-1, dim),
        np.asarray(d["radii"], np.float64),
        np.asarray(d["edges"], np.int64).reshape(-1, 2),
        np.asarray(d["faces"], np.int64).reshape(-1, 3),
        extras={k: _extra_from_json(v) for k, v in d.get("extras", {}).items()},
        metadata=meta,
        shape=shape,
        raw=_from_dict(d["raw"], shape) if d.get("raw") else None,
    )


def write_json(ma: MedialAxis, path: Path, timings: bool = False) -> None:
    d = _to_dict(ma, timings)
    with atomic_write(path, "w") as fh:
        json.dump(d, fh)


def _npz_arrays(ma: MedialAxis, prefix: str, timings: bool, parent: Any = None) -> dict[str, np.ndarray]:
    shape = _shape_parts(ma.shape, parent) or {"type": ""}
    out = {
        f"{prefix}points": ma.points,
        f"{prefix}radii": ma.radii,
        f"{prefix}edges": ma.edges,
        f"{prefix}faces": ma.faces,
        f"{prefix}metadata": np.asarray(json.dumps(_metadata(ma, timings))),
        f"{prefix}shape": np.asarray(shape.get("wkt", "")),  # version 1 readers see a planar shape
        f"{prefix}shape_type": np.asarray(shape["type"]),
    }
    if "vertices" in shape:
        out[f"{prefix}shape_vertices"], out[f"{prefix}shape_faces"] = shape["vertices"], shape["faces"]
    for k, v in ma.extras.items():
        out[f"{prefix}extra__{k}"] = v
    if ma.raw is not None:
        out.update(_npz_arrays(ma.raw, prefix + "raw__", timings, ma.shape))
    return out


def write_npz(ma: MedialAxis, path: Path, timings: bool = False) -> None:
    with atomic_write(path, "wb") as fh:
        arrays = {"format": np.asarray("medialaxis"), "version": np.asarray(FORMAT_VERSION),
                  **_npz_arrays(ma, "", timings)}
        np.savez_compressed(fh, **arrays)  # type: ignore[arg-type]  # numpy's stub reads ** as allow_pickle


def _from_npz(z: Any, prefix: str, parent: Any = None) -> MedialAxis:
    meta = json.loads(str(z[f"{prefix}metadata"]))
    kind = str(z[f"{prefix}shape_type"]) if f"{prefix}shape_type" in z.files else "geometry"
    parts: dict[str, Any] | None = {"type": kind, "wkt": str(z[f"{prefix}shape"])} if kind else None
    if kind in ("mesh", "surface"):
        parts = {"type": kind, "vertices": z[f"{prefix}shape_vertices"], "faces": z[f"{prefix}shape_faces"]}
    elif kind == "geometry" and not parts["wkt"]:  # type: ignore[index]
        parts = None
    shape = _shape_from(parts, parent)
    extras = {k[len(prefix) + 7 :]: z[k] for k in z.files if k.startswith(f"{prefix}extra__")}
    has_raw = f"{prefix}raw__points" in z.files
    dim = int(meta.pop("dim", 2))
    return MedialAxis(
        z[f"{prefix}points"].reshape(-1, dim),
        z[f"{prefix}radii"],
        z[f"{prefix}edges"],
        z[f"{prefix}faces"],
        extras=extras,
        metadata=meta,
        shape=shape,
        raw=_from_npz(z, prefix + "raw__", shape) if has_raw else None,
    )


#: A ``.json`` file larger than this is sniffed, not parsed, by :func:`is_result_file`.
_PARSE_JSON_BELOW = 64 << 20


_FORMAT_TAG = re.compile(rb'^\s*\{\s*"format"\s*:\s*"medialaxis"')


def is_result_file(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` is a result saved by :meth:`MedialAxis.save` (``.json`` or ``.npz``).

    A ``.npz`` is one if it holds a ``format`` array equal to
    ``"medialaxis"``; a ``.json`` if its top-level object has
    ``"format": "medialaxis"`` (GeoJSON and other JSON are not). Files that
    cannot be read are not results (their reader reports why).
    """
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in LOSSLESS or not path.is_file():
        return False
    try:
        if ext == ".npz":
            with np.load(path, allow_pickle=False) as z:
                return "format" in z.files and str(z["format"]) == "medialaxis"
        if path.stat().st_size > _PARSE_JSON_BELOW:
            with open(path, "rb") as fh:  # :func:`save` writes the tag first
                return bool(_FORMAT_TAG.match(fh.read(256)))
        with open(path, "rb") as fh:
            doc = json.load(fh)
        return isinstance(doc, dict) and doc.get("format") == "medialaxis"
    except Exception:  # noqa: BLE001 - unreadable or corrupt: not a result
        return False


def _check_loaded(ma: MedialAxis, what: str) -> None:
    """Refuse a loaded result whose numbers no computation could have produced."""
    from medialaxis.core.validate import MAX_COORDINATE

    for name, values in (("points", ma.points), ("radii", ma.radii)):
        bad = ~np.isfinite(values) | (np.abs(values) > MAX_COORDINATE)
        if name == "radii":
            bad |= values < 0
        if bad.any():
            kinds = "negative, infinite or overflowing" if name == "radii" else "infinite or overflowing"
            raise InputFileError(f"{what} is corrupt: its {name} hold {kinds} values")
    for key, value in ma.extras.items():
        if value.dtype.kind not in "biuf":
            raise InputFileError(f"{what} is corrupt: its extra {key!r} holds {value.dtype} values, not numbers")
    if hasattr(ma.shape, "vertices") and hasattr(ma.shape, "faces"):
        vertices, faces = np.asarray(ma.shape.vertices), np.asarray(ma.shape.faces)
        if not np.isfinite(vertices).all() or (faces.size and (faces.min() < 0 or faces.max() >= len(vertices))):
            raise InputFileError(f"{what} is corrupt: its shape's vertices are not finite or its faces name no vertex")
    if ma.raw is not None:
        _check_loaded(ma.raw, what + " (unpruned axis)")


def load(path: str | os.PathLike[str]) -> MedialAxis:
    """Read a result written by :meth:`MedialAxis.save` as ``.json`` or ``.npz``.

    Raises
    ------
    InputFileError
        Missing, unreadable or corrupt file.
    UnsupportedFormatError
        Any other extension.
    """
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in LOSSLESS:
        raise UnsupportedFormatError(f"cannot load {ext!r}; lossless formats are {', '.join(LOSSLESS)}")
    if not path.is_file():
        raise InputFileError(f"no such file: {str(path)!r}")
    try:
        if ext == ".json":
            with open(path) as fh:
                ma = _from_dict(json.load(fh))
        else:
            with np.load(path, allow_pickle=False) as z:
                if "format" not in z.files or str(z["format"]) != "medialaxis":
                    raise InputFileError(f"{str(path)!r} is not a medialaxis result file")
                ma = _from_npz(z, "")
    except InputFileError:
        raise
    except Exception as exc:  # noqa: BLE001 - corrupt files raise many types
        raise InputFileError(f"cannot read {str(path)!r}: {type(exc).__name__}: {exc}") from exc
    _check_loaded(ma, repr(str(path)))
    return ma
