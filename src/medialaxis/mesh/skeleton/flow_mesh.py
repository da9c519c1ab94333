"""The surface a curve-skeleton flow starts from: checked, repaired, refined; and the curvature that marks its tips."""

from __future__ import annotations

import dataclasses
import os
import warnings
from pathlib import Path
from typing import Any

import numpy as np
from scipy import sparse
from scipy.spatial import cKDTree

from medialaxis.core import graph as _graph
from medialaxis.core.arrays import unique_ints
from medialaxis.errors import InvalidInputError, MedialAxisWarning
from medialaxis.mesh.skeleton import _flow_operators as ops
from medialaxis.mesh.solid.crossings import shell_volumes
from medialaxis.mesh.solid.inputs import _read, load_mesh

__all__ = ["FlowState", "nonmanifold_vertices", "prepare_flow_mesh", "smoothed_gaussian_curvature", "curvature_tips",
           "MIN_TIP_CURVATURE", "readonly"]


#: Smallest total Gaussian curvature (sum of angle defects, radians) of a
#: patch above ``curvature_threshold`` that counts as a tip: an eighth of a
#: cube corner's pi/2; a hemispherical cap has 2 pi.
MIN_TIP_CURVATURE = np.pi / 16


@dataclasses.dataclass(frozen=True)
class FlowState:
    """What the flow's ``callback`` receives after every step, as ``Progress.state``.

    Attributes
    ----------
    step : int
        1 for the first step.
    positions : (n, 3) float64 ndarray, read-only
        Current positions of the cleaned mesh's vertices.
    frozen : (n,) bool ndarray, read-only
        Vertices that are skeletal points (frozen) so far.
    faces : (k, 3) int64 ndarray, read-only
        Faces of the cleaned mesh (constant).
    time : float
        Flow time reached (in units of the squared median thickness).
    """

    step: int
    positions: np.ndarray
    frozen: np.ndarray
    faces: np.ndarray
    time: float


def readonly(a: np.ndarray) -> np.ndarray:
    a = np.array(a, copy=True)
    a.setflags(write=False)
    return a


def nonmanifold_vertices(n_vertices: int, faces: np.ndarray) -> np.ndarray:
    """Vertices whose incident faces form more than one fan (a "bow-tie") ``(b,)``."""
    # nodes: directed (vertex, neighbour) pairs; each face corner links its two neighbours
    corner = np.concatenate([faces, np.roll(faces, -1, axis=1), np.roll(faces, -2, axis=1)], axis=0)
    v, a, b = corner[:, 0], corner[:, 1], corner[:, 2]
    pairs = np.concatenate([np.column_stack([v, a]), np.column_stack([v, b])])
    keys = pairs[:, 0] * n_vertices + pairs[:, 1]
    ukeys, inv = np.unique(keys, return_inverse=True)
    inv = inv.ravel()
    uniq = np.column_stack([ukeys // n_vertices, ukeys % n_vertices])
    k = len(v)
    _, label = _graph.component_labels(len(uniq), np.column_stack([inv[:k], inv[k:]]))
    fans = ops.unique_pairs(np.column_stack([uniq[:, 0], label]))
    count = np.bincount(fans[:, 0], minlength=n_vertices)
    return np.flatnonzero(count > 1)


def prepare_flow_mesh(mesh: Any, *, repair: bool = False) -> tuple[Any, np.ndarray, tuple[str, ...]]:
    """Validate a closed mesh for the flow.

    Returns
    -------
    clean : trimesh.Trimesh
        Cleaned watertight copy (see :func:`medialaxis.mesh.solid.inputs.load_mesh`).
    vertex_map : (n_input,) int64 ndarray
        Vertex of ``clean`` for each input vertex (merged duplicates share one).
    repairs : tuple of str

    Raises
    ------
    InvalidInputError
        Open, non-manifold (edges or vertices) or self-intersecting meshes,
        non-finite coordinates.
    EmptyShapeError, InputFileError
        See :func:`medialaxis.mesh.solid.inputs.load_mesh`.
    """
    raw = _read(Path(mesh)) if isinstance(mesh, (str, os.PathLike)) else mesh
    checked = load_mesh(raw, watertight=True, repair=repair)
    clean = checked.mesh
    faces = np.asarray(clean.faces, dtype=np.int64)
    bad = nonmanifold_vertices(len(clean.vertices), faces)
    if len(bad):
        raise InvalidInputError(
            f"the mesh has {len(bad)} non-manifold vertices (e.g. vertex {int(bad[0])} joins separate "
            "fans of faces); split them first"
        )
    raw_vertices = np.asarray(raw.vertices, dtype=np.float64)
    clean_vertices = np.asarray(clean.vertices)
    if raw_vertices.shape == clean_vertices.shape and np.array_equal(raw_vertices, clean_vertices):
        vertex_map = np.arange(len(raw_vertices))
    else:
        _, vertex_map = cKDTree(clean_vertices).query(raw_vertices, k=1)
    vertex_map = np.asarray(vertex_map, dtype=np.int64)
    clean, kept, note = _without_cavities(clean)
    if note:
        warnings.warn(note, MedialAxisWarning, stacklevel=3)
        vertex_map = kept[vertex_map]
    return clean, vertex_map, tuple(checked.repairs) + ((note.split(":")[0],) if note else ())


def _without_cavities(mesh: Any) -> tuple[Any, np.ndarray, str]:
    """``mesh`` without the shells that bound cavities (negative signed volume), the new index of each
    vertex (``-1``: dropped) and a warning, empty when there is none.

    A curve skeleton has no room for a void, and the flow would contract a
    cavity's surface to a curve inside the cavity, apart from the rest (a
    hollow ball gave two components): the skeleton is that of the solid with
    its cavities filled.
    """
    labels, volume = shell_volumes(mesh)
    faces = np.asarray(mesh.faces, np.int64)
    cavity = volume < 0
    n_vertices = len(mesh.vertices)
    if not cavity.any():
        return mesh, np.arange(n_vertices), ""
    keep = ~cavity[labels]
    used = unique_ints(faces[keep].ravel())
    new_index = np.full(n_vertices + 1, -1, np.int64)  # the last entry: dropped vertices stay -1
    new_index[used] = np.arange(len(used))
    import trimesh

    filled = trimesh.Trimesh(np.asarray(mesh.vertices)[used], new_index[faces[keep]], process=False)
    k = int(cavity.sum())
    note = (f"filled {k} cavit{'y' if k == 1 else 'ies'} of the solid: a curve skeleton has no room for a void "
            "(method='voronoi' keeps them)")
    return filled, new_index, note


def smoothed_gaussian_curvature(points: np.ndarray, faces: np.ndarray, edges: np.ndarray, radius: float) -> np.ndarray:
    """Angle-defect Gaussian curvature (eq. 7) averaged over about ``radius`` of surface ``(n,)``.

    The discrete curvature of a sampled surface is noisy vertex to vertex
    (marching-cubes meshes especially); the total curvature and area are
    summed over ``radius / mean edge length`` rings before dividing.
    """
    area = ops.vertex_areas(points, faces)
    defect = ops.gaussian_curvature(points, faces) * area
    length = float(np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1).mean())
    rings = int(np.clip(np.ceil(radius / max(length, 1e-300)), 0, 50))
    n = len(points)
    spread = sparse.coo_matrix((np.ones(2 * len(edges)), (edges.ravel(), edges[:, ::-1].ravel())), shape=(n, n))
    spread = (spread + sparse.identity(n)).tocsr()
    for _ in range(rings):
        defect = spread @ defect
        area = spread @ area
    return defect / np.maximum(area, 1e-300)


def curvature_tips(
    points: np.ndarray, faces: np.ndarray, edges: np.ndarray, threshold: float, radius: float
) -> np.ndarray:
    """The deepest vertex of each edge-connected patch where the Gaussian curvature is ``>= threshold``.

    "Deepest" is farthest (along mesh edges) from the patch's rim, so a
    rounded tip gives its apex rather than a noisy curvature maximum. Patches
    whose total curvature (sum of angle defects) is below
    :data:`MIN_TIP_CURVATURE` are noise, not tips, and are skipped.
    """
    from scipy.sparse import csgraph

    k = smoothed_gaussian_curvature(points, faces, edges, radius)
    hot = k >= threshold
    if not hot.any():
        return np.zeros(0, dtype=np.int64)
    inner = edges[hot[edges[:, 0]] & hot[edges[:, 1]]]
    _, label = _graph.component_labels(len(points), inner)
    rim_edges = edges[hot[edges[:, 0]] != hot[edges[:, 1]]]
    rim = unique_ints(rim_edges[hot[rim_edges]]) if len(rim_edges) else np.zeros(0, dtype=np.int64)
    length = np.linalg.norm(points[inner[:, 0]] - points[inner[:, 1]], axis=1) + 1e-300
    adj = sparse.coo_matrix((length, (inner[:, 0], inner[:, 1])), shape=(len(points),) * 2).tocsr()
    depth = csgraph.dijkstra(adj, directed=False, indices=rim, min_only=True) if len(rim) else np.zeros(len(points))
    depth = np.where(np.isfinite(depth), depth, np.inf)  # a closed patch without rim: any vertex
    # a tip must carry some total curvature: lone noisy vertices do not count
    defect = ops.gaussian_curvature(points, faces) * ops.vertex_areas(points, faces)
    total = np.bincount(label[hot], weights=defect[hot], minlength=len(points))
    idx = np.flatnonzero(hot & (total[label] >= MIN_TIP_CURVATURE))
    if idx.size == 0:
        return np.zeros(0, dtype=np.int64)
    order = idx[np.lexsort((-np.where(np.isinf(depth[idx]), 0.0, depth[idx]), label[idx]))]
    first = np.unique(label[order], return_index=True)[1]
    return np.sort(order[first])
