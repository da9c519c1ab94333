"""Mesh and curve files that other tools open: PLY, legacy VTK, VTU, SWC.

Each file holds the result's points with ``radius`` (and every per-point
extra) as point data, its triangles, and its curve edges (edges on no
triangle) as line cells where the format has them:

========  ==========================================  =====================================
format    cells                                       read by (tested)
========  ==========================================  =====================================
``.ply``  triangles; a curve result's edges as        meshio, trimesh, pyvista (triangles);
          two-point faces (meshio's convention)       meshio (lines)
``.vtk``  legacy ``UNSTRUCTURED_GRID``: triangles     meshio, pyvista, trimesh (triangles)
          and lines
``.vtu``  XML ``UnstructuredGrid``: the same          meshio, pyvista, trimesh (triangles)
``.swc``  curve results: one tree per component       any SWC reader (neuron morphology);
          (edges closing cycles as comment lines)     parsed back in the tests
========  ==========================================  =====================================

2D results are written with ``z = 0``. VTK and VTU are written by meshio
(the ``medialaxis[meshio]`` extra). PLY and SWC are written here, because no
library writes what they must hold: meshio's PLY writer has no ``edge``
element (the curve pieces of a complex of triangles and curves) and stamps
the time into the file, so the same result would not give the same bytes;
SWC has no writer in meshio, trimesh or pyvista.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, TextIO

import numpy as np
from scipy import sparse
from scipy.sparse import csgraph

from medialaxis._optional import require
from medialaxis.errors import UnsupportedFormatError

if TYPE_CHECKING:  # pragma: no cover
    from medialaxis.core.result import MedialAxis

__all__ = ["curve_edges", "point_fields", "points_3d", "write_ply", "write_swc", "write_vtk", "write_vtu"]

def points_3d(ma: MedialAxis) -> np.ndarray:
    """(n, 3) points of ``ma``; a 2D result gets ``z = 0``."""
    n, d = ma.points.shape
    return np.asarray(ma.points, np.float64) if d == 3 else np.c_[ma.points, np.zeros(n)]


def curve_edges(ma: MedialAxis) -> np.ndarray:
    """(c, 2) edges of ``ma`` that are not an edge of any of its faces."""
    edges = np.sort(np.asarray(ma.edges, np.int64).reshape(-1, 2), axis=1)
    if len(ma.faces) == 0 or len(edges) == 0:
        return edges
    f = np.asarray(ma.faces, np.int64)
    n = len(ma.points)
    on_face = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    return edges[~np.isin(edges[:, 0] * n + edges[:, 1], on_face[:, 0] * n + on_face[:, 1])]


def point_fields(ma: MedialAxis) -> dict[str, np.ndarray]:
    """Per-point scalars to write: ``radius``, ``thickness`` (twice it) and every per-point extra."""
    n = len(ma.points)
    fields = {"radius": np.asarray(ma.radii, np.float64), "thickness": 2.0 * np.asarray(ma.radii, np.float64)}
    for key, value in ma.extras.items():
        value = np.asarray(value)
        if value.shape == (n,) and key not in fields and np.issubdtype(value.dtype, np.number):
            fields[key] = value.astype(np.float64)
    return fields


def _cell_blocks(ma: MedialAxis) -> list[tuple[str, np.ndarray]]:
    """meshio cell blocks: triangles, then curve lines; lone points (``vertex``) when neither."""
    tri = np.asarray(ma.faces, np.int64).reshape(-1, 3)
    lines = curve_edges(ma)
    if len(tri) == 0 and len(lines) == 0:
        return [("vertex", np.arange(len(ma.points), dtype=np.int64)[:, None])]
    return [(kind, block) for kind, block in (("triangle", tri), ("line", lines)) if len(block)]


def _meshio_mesh(ma: MedialAxis) -> Any:
    """``ma`` as a ``meshio.Mesh``: 3D points, cell blocks and the point fields."""
    meshio = require("meshio", "medialaxis[meshio]")
    return meshio, meshio.Mesh(points_3d(ma), _cell_blocks(ma), point_data=point_fields(ma))


def write_ply(ma: MedialAxis, fh: object) -> None:
    """Binary PLY: ``vertex`` (x, y, z and the point fields), ``face`` (the
    triangles, or a curve result's edges as two-point faces) and, for a
    complex of triangles and curve pieces, the pieces as the standard ``edge``
    element (``vertex1``, ``vertex2``). trimesh keeps them
    (``metadata["_ply_raw"]["edge"]``) and VTK reads the triangles; meshio's
    PLY reader knows no ``edge`` element: use .vtu or .vtk there."""
    fields = point_fields(ma)
    xyz = points_3d(ma)
    faces = np.asarray(ma.faces, np.int64).reshape(-1, 3)
    curves = curve_edges(ma)
    polys = faces if len(faces) or not len(curves) else curves  # triangles, else the curve as two-point faces
    extra = curves if len(faces) else curves[:0]
    header = ["ply", "format binary_little_endian 1.0", "comment medialaxis result", f"element vertex {len(xyz)}",
              "property double x", "property double y", "property double z"]
    header += [f"property double {name}" for name in fields]
    header += [f"element face {len(polys)}", "property list uchar int vertex_indices"]
    if len(extra):
        header += [f"element edge {len(extra)}", "property int vertex1", "property int vertex2"]
    header.append("end_header")
    vert = np.empty(len(xyz), dtype=[(name, "<f8") for name in ("x", "y", "z", *fields)])
    for j, axis in enumerate("xyz"):
        vert[axis] = xyz[:, j]
    for name, values in fields.items():
        vert[name] = values
    fh.write(("\n".join(header) + "\n").encode("ascii"))  # type: ignore[attr-defined]
    fh.write(vert.tobytes())  # type: ignore[attr-defined]
    k = polys.shape[1]
    face = np.empty(len(polys), dtype=[("k", "u1"), ("v", "<i4", (k,))])
    face["k"], face["v"] = k, polys
    fh.write(face.tobytes())  # type: ignore[attr-defined]
    if len(extra):
        fh.write(np.ascontiguousarray(extra, "<i4").tobytes())  # type: ignore[attr-defined]


def write_vtk(ma: MedialAxis, path: str) -> None:
    """Legacy binary VTK ``UNSTRUCTURED_GRID``, file version 4.2 (read by meshio, pyvista, ParaView; VTK
    before 9 cannot read meshio's default 5.1), written by meshio."""
    meshio, mesh = _meshio_mesh(ma)
    meshio.vtk.write(path, mesh, fmt_version="4.2", binary=True)


def write_vtu(ma: MedialAxis, path: str) -> None:
    """XML VTK ``UnstructuredGrid`` (binary, zlib-compressed arrays), written by meshio."""
    meshio, mesh = _meshio_mesh(ma)
    meshio.vtu.write(path, mesh, binary=True, compression="zlib")


def write_swc(ma: MedialAxis, fh: TextIO) -> None:
    """SWC (id, type, x, y, z, radius, parent) of a curve result: each component
    is a tree rooted at its widest point, parents found breadth first; edges
    that close a cycle are listed as ``# cycle a b`` comment lines."""
    if len(ma.faces):
        raise UnsupportedFormatError(f"SWC holds curve skeletons; this result has {len(ma.faces)} faces "
                                     "(write .ply, .vtk or .vtu)")
    n = len(ma.points)
    xyz = points_3d(ma)
    edges = np.asarray(ma.edges, np.int64).reshape(-1, 2)
    edges = np.unique(np.sort(edges[edges[:, 0] != edges[:, 1]], axis=1), axis=0)
    graph = sparse.coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n)).tocsr()
    _, component = csgraph.connected_components(graph, directed=False)
    radii = np.asarray(ma.radii, np.float64)
    parent = np.full(n, -1, np.int64)
    order: list[np.ndarray] = []
    for c in np.unique(component):
        members = np.flatnonzero(component == c)
        root = int(members[np.argmax(radii[members])])
        visit, pred = csgraph.breadth_first_order(graph, root, directed=False, return_predecessors=True)
        order.append(visit)
        parent[visit[1:]] = pred[visit[1:]]
    sequence = np.concatenate(order) if order else np.empty(0, np.int64)
    new_id = np.empty(n, np.int64)
    new_id[sequence] = np.arange(1, n + 1)
    tree = {(min(a, b), max(a, b)) for a, b in zip(range(n), parent.tolist()) if b >= 0}
    fh.write(f"# medialaxis curve skeleton: {n} points, {len(edges)} edges\n"
             "# id type x y z radius parent\n")
    for a, b in edges.tolist():
        if (a, b) not in tree:
            fh.write(f"# cycle {new_id[a]} {new_id[b]}\n")
    rows = np.c_[new_id[sequence], np.zeros(n, np.int64)[: len(sequence)], xyz[sequence], radii[sequence],
                 np.where(parent[sequence] >= 0, new_id[np.maximum(parent[sequence], 0)], -1)]
    np.savetxt(fh, rows, fmt=["%d", "%d", "%.10g", "%.10g", "%.10g", "%.10g", "%d"])
