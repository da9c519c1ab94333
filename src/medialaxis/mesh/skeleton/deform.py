"""Skeleton-driven deformation of a mesh (Du and Qin, SM '04, section 4.3).

Move the nodes of a curve skeleton computed by ``method="flow"`` and the
surface follows: every vertex is carried by the rigid frame (rotation plus
translation) of its skeletal point, blended linearly with the frame of the
next node along the branch it lies beside, so the surface bends smoothly
along branches and around junctions; then, as in the paper, a diffusion step
(implicit heat flow of the displacement field on the input surface, cotangent
Laplacian) smooths the seams. Vertices whose skeletal points did not move
(position and frame) stay exactly where they are. The diffusion step acts
only on the vertices of junction nodes and their neighbours (where branch
frames meet), with the blended displacement as boundary condition, so
rigid motions of whole branches stay rigid.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import sparse
from scipy.sparse import linalg as splinalg

from medialaxis._optional import require
from medialaxis.core import graph as _graph
from medialaxis.errors import InvalidInputError
from medialaxis.mesh.skeleton import _flow_operators as ops

__all__ = ["deform", "node_rotations"]


def _minimal_rotation(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Rotation ``(3, 3)`` turning direction ``a`` into direction ``b`` about ``a x b``."""
    na, nb = np.linalg.norm(a), np.linalg.norm(b)
    if na == 0 or nb == 0:
        return np.eye(3)
    a, b = a / na, b / nb
    v = np.cross(a, b)
    c = float(a @ b)
    if c < -1.0 + 1e-12:  # half turn about any axis perpendicular to a
        axis = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
        axis /= np.linalg.norm(axis)
        return 2.0 * np.outer(axis, axis) - np.eye(3)
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + vx + vx @ vx / (1.0 + c)


def node_rotations(points: np.ndarray, new_points: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Rotation ``(s, 3, 3)`` of each skeleton node's frame.

    Junctions take the best rotation of their edge vectors (Kabsch); chain
    nodes and endpoints the smallest rotation of their tangent, so branches
    do not twist.
    """
    n = len(points)
    rot = np.tile(np.eye(3), (n, 1, 1))
    adj = _graph.adjacency(n, edges)
    for i in range(n):
        nbrs = adj.indices[adj.indptr[i] : adj.indptr[i + 1]]
        if len(nbrs) == 0:
            continue
        old = points[nbrs] - points[i]
        new = new_points[nbrs] - new_points[i]
        if len(nbrs) >= 3:
            u, sv, vt = np.linalg.svd(old.T @ new)
            if sv[1] > 1e-9 * sv[0]:
                d = np.sign(np.linalg.det(vt.T @ u.T)) or 1.0
                rot[i] = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
                continue
        if len(nbrs) == 1:
            rot[i] = _minimal_rotation(old[0], new[0])
        else:
            tangent_old = points[nbrs[-1]] - points[nbrs[0]]
            tangent_new = new_points[nbrs[-1]] - new_points[nbrs[0]]
            rot[i] = _minimal_rotation(tangent_old, tangent_new)
    return rot


def deform(mesh: Any, skeleton: Any, new_points: Any, *, smoothing: float = 0.5) -> Any:
    """Deform a mesh by moving the nodes of its curve skeleton.

    Parameters
    ----------
    mesh : trimesh.Trimesh
        The mesh the skeleton was computed from (same vertices, same order).
    skeleton : MedialAxis
        A result of ``medial_axis(mesh, method="flow")``: it carries
        ``correspondence`` (one node per input vertex, ``-1`` for none).
    new_points : (s, 3) array_like
        New positions of the skeleton's nodes.
    smoothing : float
        Duration of the diffusion step, in units of the squared median
        skeleton radius (0 skips it).

    Returns
    -------
    trimesh.Trimesh
        A new mesh with the input's faces and moved vertices; the input is
        not modified.

    Raises
    ------
    InvalidInputError
        Mismatched vertex count or node count, non-finite positions, a
        skeleton without ``correspondence``, negative smoothing.

    References
    ----------
    .. [1] H. Du, H. Qin, "Medial axis extraction and shape manipulation of solid objects using
           parabolic PDEs", Proc. 9th ACM Symposium on Solid Modeling and Applications (SM '04),
           2004 (DOI unconfirmed), section 4.3 (skeleton-based shape sculpting).

    Examples
    --------
    >>> import medialaxis as mx
    >>> from medialaxis.datasets import capsules_mesh
    >>> capsule = capsules_mesh([[[0, 0, 0], [3, 0, 0]]], 0.5, pitch=0.1)
    >>> sk = mx.medial_axis(capsule, method="flow")
    >>> moved = mx.deform(capsule, sk, sk.points + [0.0, 0.0, 1.0])
    >>> bool(abs(moved.vertices[:, 2].mean() - capsule.vertices[:, 2].mean() - 1.0) < 1e-9)
    True
    """
    trimesh = require("trimesh", "medialaxis[mesh]")
    if not (hasattr(mesh, "vertices") and hasattr(mesh, "faces")):
        raise InvalidInputError(f"expected a trimesh.Trimesh, got {type(mesh).__name__}")
    vertices = np.array(mesh.vertices, dtype=np.float64, copy=True)
    faces = np.array(mesh.faces, dtype=np.int64, copy=True)
    corr = getattr(skeleton, "extras", {}).get("correspondence") if hasattr(skeleton, "extras") else None
    if corr is None:
        raise InvalidInputError("the skeleton has no correspondence; compute it with medial_axis(mesh, method='flow')")
    corr = np.asarray(corr, dtype=np.int64)
    if len(corr) != len(vertices):
        raise InvalidInputError(
            f"the skeleton was computed for a mesh of {len(corr)} vertices, this mesh has {len(vertices)}"
        )
    old = np.asarray(skeleton.points, dtype=np.float64)
    new = np.array(new_points, dtype=np.float64, copy=True)
    if new.shape != old.shape:
        raise InvalidInputError(f"new_points must have shape {old.shape}, got {new.shape}")
    if not np.all(np.isfinite(new)):
        raise InvalidInputError("new_points contain NaN or infinite values")
    if not (np.isfinite(smoothing) and smoothing >= 0):
        raise InvalidInputError(f"smoothing must be a non-negative number, got {smoothing!r}")
    edges = np.asarray(skeleton.edges, dtype=np.int64)
    rot = node_rotations(old, new, edges)
    moved_node = (np.linalg.norm(new - old, axis=1) > 0) | (np.abs(rot - np.eye(3)).max(axis=(1, 2)) > 1e-12)

    mapped = np.flatnonzero(corr >= 0)
    c = corr[mapped]
    v = vertices[mapped]
    # blend partner: the neighbour node the vertex lies furthest towards
    adj = _graph.adjacency(len(old), edges)
    partner = c.copy()
    t_best = np.zeros(len(c))
    degree = np.diff(adj.indptr)
    for k in range(int(degree.max()) if len(degree) else 0):
        has = degree[c] > k
        nb = np.where(has, adj.indices[np.minimum(adj.indptr[c] + k, len(adj.indices) - 1)], c)
        seg = old[nb] - old[c]
        length2 = np.einsum("ij,ij->i", seg, seg)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(has & (length2 > 0), np.einsum("ij,ij->i", v - old[c], seg) / length2, 0.0)
        better = t > t_best
        partner = np.where(better, nb, partner)
        t_best = np.where(better, t, t_best)
    w_partner = np.minimum(t_best, 0.5)[:, None]
    own = new[c] + np.einsum("nij,nj->ni", rot[c], v - old[c])
    other = new[partner] + np.einsum("nij,nj->ni", rot[partner], v - old[partner])
    displacement = np.zeros_like(vertices)
    displacement[mapped] = (1.0 - w_partner) * own + w_partner * other - v
    moving = np.zeros(len(vertices), dtype=bool)
    moving[mapped] = moved_node[c] | moved_node[partner]
    displacement[~moving] = 0.0

    if smoothing > 0 and moving.any() and (degree >= 3).any():
        radius = float(np.median(skeleton.radii)) if len(skeleton.radii) else 1.0
        tau = smoothing * radius * radius
        lap = ops.cotangent_laplacian(vertices, faces)
        area = ops.vertex_areas(vertices, faces)
        mass = np.maximum(area, 1e-12 * max(float(area.mean()), 1e-300))
        a = (sparse.diags(mass) + tau * lap).tocsr()
        # only around junctions, where branch frames meet, is the blend not
        # smooth; elsewhere smoothing a rotation's displacement would shrink it
        near_junction = degree >= 3
        if len(edges):
            near_junction[edges[near_junction[edges[:, 1]], 0]] = True
            near_junction[edges[near_junction[edges[:, 0]], 1]] = True
        seam = np.zeros(len(vertices), dtype=bool)
        seam[mapped] = near_junction[c] | near_junction[partner]
        free = np.flatnonzero(moving & seam)
        fixed = np.flatnonzero(~(moving & seam))
        a_ff = a[free][:, free].tocsc()
        solve = splinalg.factorized(a_ff)
        rhs = mass[free, None] * displacement[free] - a[free][:, fixed] @ displacement[fixed]
        displacement[free] = np.column_stack([solve(rhs[:, d]) for d in range(3)])
    return trimesh.Trimesh(vertices + displacement, faces, process=False)
