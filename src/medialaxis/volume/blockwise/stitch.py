"""The blocks' mesh pieces joined by their vertex names: in memory, or streamed to a PLY file or a Zarr group.

Each piece (:func:`~medialaxis.volume.blockwise.tiles.mesh_block`) lists the vertices
its block owns, named by their voxel's volume index and sorted by name, and
the faces it owns as triples of names. A vertex has one owner, so joining is
a lookup: :func:`join_pieces` gathers them in the whole route's order (the
pick order of :mod:`~medialaxis.volume.sheet.polygonize`), :func:`stream_mesh`
writes them block by block (to PLY, or to a Zarr group of arrays), each face's names found in the pieces of the
blocks that own them (never more than a few pieces in memory).
"""

from __future__ import annotations

import os
import shutil
from collections import OrderedDict
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError
from medialaxis.volume.blockwise.tiles import name_voxels

__all__ = ["join_pieces", "stream_mesh", "write_zarr_mesh", "check_streamed", "STREAMED_SUFFIXES"]

#: Outputs the mesh can be streamed to: a binary PLY file, a Zarr group (a folder).
STREAMED_SUFFIXES = (".ply", ".zarr")


def _piece_path(folder: str, index: tuple[int, ...]) -> Path:
    return Path(folder) / ("mesh_{}_{}_{}.npz".format(*index))


def _load(folder: str, index: tuple[int, ...]) -> dict[str, np.ndarray]:
    with np.load(_piece_path(folder, index)) as data:
        return {key: data[key] for key in data.files}


def join_pieces(folder: str, indices: list[tuple[int, int, int]]) -> tuple[np.ndarray, ...]:
    """``(points, radii, kind, faces)`` of the whole mesh, vertices in pick order (as the whole sheet gives them)."""
    pieces = [_load(folder, i) for i in indices]
    if not pieces:
        return np.zeros((0, 3)), np.zeros(0), np.zeros(0, np.int8), np.zeros((0, 3), np.int64)
    cat = {key: np.concatenate([p[key] for p in pieces]) for key in pieces[0]}
    names, order = cat["names"], cat["order"]
    # extension vertices after all picks, each group in pick order, ties by voxel
    rank = np.lexsort((names >> 1, order[:, 1], order[:, 0], names & 1))
    position = np.empty(len(names), np.int64)
    position[rank] = np.arange(len(names))
    sorted_names = np.argsort(names)
    where = np.searchsorted(names, cat["faces"], sorter=sorted_names)
    faces = position[sorted_names[where]]
    return cat["points"][rank], cat["radii"][rank], cat["kind"][rank], faces


class _Names:
    """Global vertex numbers of names, from the pieces of the blocks that own them (a few kept at a time)."""

    def __init__(self, folder: str, chunks: tuple[int, int, int], offsets: dict[tuple[int, int, int], int],
                 keep: int = 64) -> None:
        self.folder, self.chunks, self.offsets, self.keep = folder, np.asarray(chunks), offsets, keep
        self.cache: OrderedDict[tuple[int, int, int], np.ndarray] = OrderedDict()

    def _names(self, index: tuple[int, int, int]) -> np.ndarray:
        if index not in self.cache:
            self.cache[index] = _load(self.folder, index)["names"]
            if len(self.cache) > self.keep:
                self.cache.popitem(last=False)
        self.cache.move_to_end(index)
        return self.cache[index]

    def numbers(self, names: np.ndarray) -> np.ndarray:
        flat = names.ravel()
        owner = name_voxels(flat) // self.chunks
        out = np.empty(len(flat), np.int64)
        keys, inverse = np.unique(owner, axis=0, return_inverse=True)
        for k, key in enumerate(map(tuple, keys.tolist())):
            rows = np.flatnonzero(inverse.ravel() == k)
            listed = self._names(key)
            out[rows] = self.offsets[key] + np.searchsorted(listed, flat[rows])
        return out.reshape(names.shape)


def _layout(counts: list[dict[str, Any]]) -> tuple[list[dict[str, Any]], dict[tuple[int, int, int], int], int, int]:
    """The pieces with a vertex or a face, the first vertex number of each, and the numbers of vertices and faces."""
    pieces = [c for c in counts if c["vertices"] or c["faces"]]
    offsets: dict[tuple[int, int, int], int] = {}
    total = 0
    for c in pieces:
        offsets[tuple(c["index"])] = total  # type: ignore[index]
        total += c["vertices"]
    return pieces, offsets, total, sum(c["faces"] for c in pieces)


def _part(out: Path) -> Path:
    return out.with_name(out.name + ".part")


def _ply(folder: str, pieces: list[dict[str, Any]], lookup: _Names, tmp: Path, total: int, n_faces: int) -> None:
    names = ("x", "y", "z", "radius", "thickness", "vertex_kind")
    header = ["ply", "format binary_little_endian 1.0", "comment medialaxis result (streamed by blocks)",
              f"element vertex {total}", *(f"property double {n}" for n in names),
              f"element face {n_faces}", "property list uchar int vertex_indices", "end_header"]
    with open(tmp, "wb") as fh:
        fh.write(("\n".join(header) + "\n").encode("ascii"))
        for c in pieces:
            p = _load(folder, c["index"])
            vert = np.empty(len(p["names"]), [(n, "<f8") for n in names])
            for j, axis in enumerate("xyz"):
                vert[axis] = p["points"][:, j]
            vert["radius"], vert["thickness"], vert["vertex_kind"] = p["radii"], 2.0 * p["radii"], p["kind"]
            fh.write(vert.tobytes())
        for c in pieces:
            faces = _load(folder, c["index"])["faces"]
            rows = np.empty(len(faces), [("k", "u1"), ("v", "<i4", (3,))])
            rows["k"], rows["v"] = 3, lookup.numbers(faces)
            fh.write(rows.tobytes())


#: Rows per chunk of the arrays of a Zarr mesh.
ZARR_ROWS = 1 << 18


def _zarr_group(path: Path, total: int, n_faces: int, zarr_format: int = 3) -> dict[str, Any]:
    """An empty Zarr group at ``path`` with the mesh's arrays (``vertices``, ``faces``, ``radii``, ``vertex_kind``)."""
    from medialaxis._optional import require

    zarr = require("zarr", "medialaxis[dask]")
    group = zarr.open_group(str(path), mode="w", zarr_format=zarr_format)
    group.attrs.update({"medialaxis": "mid-surface mesh", "n_vertices": int(total), "n_faces": int(n_faces),
                        "radii": "half the local thickness", "vertex_kind": "0 surface, 1 free edge, 2 junction, 3 extension"})
    rows = max(1, min(ZARR_ROWS, max(total, n_faces)))
    return {"vertices": group.create_array("vertices", shape=(total, 3), dtype="<f8", chunks=(rows, 3)),
            "faces": group.create_array("faces", shape=(n_faces, 3), dtype="<i8", chunks=(rows, 3)),
            "radii": group.create_array("radii", shape=(total,), dtype="<f8", chunks=(rows,)),
            "vertex_kind": group.create_array("vertex_kind", shape=(total,), dtype="i1", chunks=(rows,))}


def _zarr(folder: str, pieces: list[dict[str, Any]], lookup: _Names, tmp: Path, total: int, n_faces: int,
          zarr_format: int = 3) -> None:
    arrays = _zarr_group(tmp, total, n_faces, zarr_format)
    start = first_face = 0
    for c in pieces:
        p = _load(folder, c["index"])
        stop = start + len(p["names"])
        arrays["vertices"][start:stop] = p["points"]
        arrays["radii"][start:stop] = p["radii"]
        arrays["vertex_kind"][start:stop] = p["kind"]
        start = stop
        faces = lookup.numbers(p["faces"])
        arrays["faces"][first_face:first_face + len(faces)] = faces
        first_face += len(faces)


def write_zarr_mesh(out: str | os.PathLike, points: np.ndarray, radii: np.ndarray, kind: np.ndarray,
                    faces: np.ndarray, zarr_format: int = 3) -> None:
    """A mesh in memory written as the Zarr group :func:`stream_mesh` streams (atomically)."""
    out = Path(out)
    tmp = _part(out)
    try:
        arrays = _zarr_group(tmp, len(points), len(faces), zarr_format)
        arrays["vertices"][:], arrays["radii"][:], arrays["vertex_kind"][:] = points, radii, kind
        arrays["faces"][:] = faces
        _replace(tmp, out)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _replace(tmp: Path, out: Path) -> None:
    """``tmp`` (a file or a Zarr folder) moved to ``out``, an older output there removed."""
    if out.is_dir() and tmp.is_dir():
        old = out.with_name(out.name + ".old")
        shutil.rmtree(old, ignore_errors=True)
        os.replace(out, old)
        os.replace(tmp, out)
        shutil.rmtree(old, ignore_errors=True)
    else:
        os.replace(tmp, out)


def check_streamed(out: Any) -> Path:
    """``out`` as a path with a suffix the mesh streams to (:data:`STREAMED_SUFFIXES`)."""
    path = Path(out)
    if path.suffix.lower() not in STREAMED_SUFFIXES:
        raise InvalidInputError(f"out= writes the mesh to a {' or '.join(STREAMED_SUFFIXES)} file, got {str(out)!r}")
    return path


def stream_mesh(folder: str, counts: list[dict[str, Any]], chunks: tuple[int, int, int], out: str | os.PathLike,
                zarr_format: int | None = None) -> tuple[int, int]:
    """Write the pieces block by block, atomically, to a binary PLY file (the fields of
    :func:`~medialaxis.core.export.mesh_files.write_ply`) or a Zarr group (``vertices (n, 3)``,
    ``faces (k, 3)`` int64, ``radii (n,)``, ``vertex_kind (n,)`` int8); returns the numbers of
    vertices and faces. Vertices come block by block, each block's sorted by name.
    ``zarr_format``: a Zarr group of that format whatever ``out``'s suffix (2 inside an OME-Zarr image)."""
    out = Path(out) if zarr_format else check_streamed(out)
    pieces, offsets, total, n_faces = _layout(counts)
    lookup = _Names(folder, chunks, offsets)
    tmp = _part(out)
    try:
        if zarr_format or out.suffix.lower() == ".zarr":
            _zarr(folder, pieces, lookup, tmp, total, n_faces, zarr_format or 3)
        else:
            _ply(folder, pieces, lookup, tmp, total, n_faces)
        _replace(tmp, out)
    finally:
        if tmp.is_dir():
            shutil.rmtree(tmp, ignore_errors=True)
        elif tmp.exists():
            tmp.unlink()
    return total, n_faces
