"""Results saved losslessly and read back: ``.json`` and ``.npz`` (with the unpruned axis, so
:meth:`~medialaxis.core.result.MedialAxis.prune` still works), validated on load."""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.core.outputs import atomic_write
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InputFileError, UnsupportedFormatError

__all__ = ["load", "is_result_file", "write_json", "write_npz", "jsonable", "FORMAT_VERSION", "LOSSLESS"]

#: The formats :func:`load` reads back.
LOSSLESS = (".json", ".npz")


FORMAT_VERSION = 1


def jsonable(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def _shape_wkt(ma: MedialAxis) -> str | None:
    return ma.shape.wkt if hasattr(ma.shape, "wkt") else None


def _to_dict(ma: MedialAxis) -> dict[str, Any]:
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
        "metadata": jsonable(dict(ma.metadata, dim=ma.dim)),
        "shape": _shape_wkt(ma),
        "raw": _to_dict(ma.raw) if ma.raw is not None else None,
    }


def _extra_from_json(spec: dict[str, Any]) -> np.ndarray:
    return np.asarray(spec["data"], dtype=spec["dtype"]).reshape(spec["shape"])


def _from_dict(d: dict[str, Any]) -> MedialAxis:
    if d.get("format") != "medialaxis":
        raise InputFileError("not a medialaxis result file")
    shape = None
    if d.get("shape"):
        import shapely

        shape = shapely.from_wkt(d["shape"])
    meta = d.get("metadata", {})
    for key in ("spacing", "image_shape"):
        if key in meta and isinstance(meta[key], list):
            meta[key] = tuple(meta[key])
    dim = int(meta.pop("dim", len(d["points"][0]) if d["points"] else 2))
    return MedialAxis(
        np.asarray(d["points"], np.float64).reshape(-1, dim),
        np.asarray(d["radii"], np.float64),
        np.asarray(d["edges"], np.int64).reshape(-1, 2),
        np.asarray(d["faces"], np.int64).reshape(-1, 3),
        extras={k: _extra_from_json(v) for k, v in d.get("extras", {}).items()},
        metadata=meta,
        shape=shape,
        raw=_from_dict(d["raw"]) if d.get("raw") else None,
    )


def write_json(ma: MedialAxis, path: Path) -> None:
    d = _to_dict(ma)
    with atomic_write(path, "w") as fh:
        json.dump(d, fh)


def _npz_arrays(ma: MedialAxis, prefix: str) -> dict[str, np.ndarray]:
    meta = jsonable(dict(ma.metadata))
    meta["dim"] = ma.dim
    out = {
        f"{prefix}points": ma.points,
        f"{prefix}radii": ma.radii,
        f"{prefix}edges": ma.edges,
        f"{prefix}faces": ma.faces,
        f"{prefix}metadata": np.asarray(json.dumps(meta)),
        f"{prefix}shape": np.asarray(_shape_wkt(ma) or ""),
    }
    for k, v in ma.extras.items():
        out[f"{prefix}extra__{k}"] = v
    if ma.raw is not None:
        out.update(_npz_arrays(ma.raw, prefix + "raw__"))
    return out


def write_npz(ma: MedialAxis, path: Path) -> None:
    with atomic_write(path, "wb") as fh:
        np.savez_compressed(fh, format=np.asarray("medialaxis"), version=np.asarray(FORMAT_VERSION), **_npz_arrays(ma, ""))


def _from_npz(z: Any, prefix: str) -> MedialAxis:
    meta = json.loads(str(z[f"{prefix}metadata"]))
    for key in ("spacing", "image_shape"):
        if key in meta and isinstance(meta[key], list):
            meta[key] = tuple(meta[key])
    wkt = str(z[f"{prefix}shape"])
    shape = None
    if wkt:
        import shapely

        shape = shapely.from_wkt(wkt)
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
        raw=_from_npz(z, prefix + "raw__") if has_raw else None,
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
