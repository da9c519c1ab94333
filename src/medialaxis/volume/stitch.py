"""The blocks' mesh pieces joined by their vertex names: in memory, or streamed to a PLY file.

Each piece (:func:`~medialaxis.volume.tiles.mesh_block`) lists the vertices
its block owns, named by their voxel's volume index and sorted by name, and
the faces it owns as triples of names. A vertex has one owner, so joining is
a lookup: :func:`join_pieces` gathers them in the whole route's order (the
pick order of :mod:`~medialaxis.volume.polygonize`), :func:`stream_ply`
writes them block by block, each face's names found in the pieces of the
blocks that own them (never more than a few pieces in memory).
"""

from __future__ import annotations

import os
from collections import OrderedDict
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError
from medialaxis.volume.tiles import name_voxels

__all__ = ["join_pieces", "stream_ply", "STREAMED_SUFFIXES"]

#: Output files the mesh can be streamed to.
STREAMED_SUFFIXES = (".ply",)


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


def stream_ply(folder: str, counts: list[dict[str, Any]], chunks: tuple[int, int, int], out: str | os.PathLike) -> tuple[int, int]:
    """Write the pieces to a binary PLY file (the fields of :func:`~medialaxis.core.mesh_files.write_ply`)
    block by block, atomically; returns the numbers of vertices and faces."""
    out = Path(out)
    if out.suffix.lower() not in STREAMED_SUFFIXES:
        raise InvalidInputError(f"out= streams the mesh to {', '.join(STREAMED_SUFFIXES)} files, got {str(out)!r}")
    pieces = [c for c in counts if c["vertices"] or c["faces"]]
    offsets: dict[tuple[int, int, int], int] = {}
    total = 0
    for c in pieces:
        offsets[tuple(c["index"])] = total  # type: ignore[index]
        total += c["vertices"]
    n_faces = sum(c["faces"] for c in pieces)
    header = ["ply", "format binary_little_endian 1.0", "comment medialaxis result (streamed by blocks)",
              f"element vertex {total}", *(f"property double {n}" for n in ("x", "y", "z", "radius", "thickness",
                                                                            "vertex_kind")),
              f"element face {n_faces}", "property list uchar int vertex_indices", "end_header"]
    lookup = _Names(folder, chunks, offsets)
    tmp = out.with_name(out.name + ".part")
    try:
        with open(tmp, "wb") as fh:
            fh.write(("\n".join(header) + "\n").encode("ascii"))
            for c in pieces:
                p = _load(folder, c["index"])
                vert = np.empty(len(p["names"]), [(n, "<f8") for n in ("x", "y", "z", "radius", "thickness", "vertex_kind")])
                for j, axis in enumerate("xyz"):
                    vert[axis] = p["points"][:, j]
                vert["radius"], vert["thickness"], vert["vertex_kind"] = p["radii"], 2.0 * p["radii"], p["kind"]
                fh.write(vert.tobytes())
            for c in pieces:
                faces = _load(folder, c["index"])["faces"]
                rows = np.empty(len(faces), [("k", "u1"), ("v", "<i4", (3,))])
                rows["k"], rows["v"] = 3, lookup.numbers(faces)
                fh.write(rows.tobytes())
        os.replace(tmp, out)
    finally:
        if tmp.exists():
            tmp.unlink()
    return total, n_faces
