"""The raw (unpruned) inner Voronoi axis of a boundary sample.

Nodes are the Delaunay triangles inside the region, placed at their
circumcentres (the Voronoi vertices); two nodes are joined when their
triangles share an edge (the Voronoi edge dual to that Delaunay edge). For a
conforming sample this graph is the dual of a triangulation of the region,
so it has one component per polygon and one independent cycle per hole.

Every edge records the two sample points of its dual Delaunay edge, i.e. its
contact set: its diameter (for the lambda-medial axis) and the boundary arc
between the two contacts (for the detour test of :mod:`.pruning`).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import shapely
from scipy.spatial import cKDTree

from medialaxis.planar._distance_kernels import boundary_distance_kernel
from medialaxis.planar._graph_kernels import dual_edges
from medialaxis.planar._inside_kernels import RegionLocator
from medialaxis.planar._kernels import nearest_piece_distance, triangle_centroids
from medialaxis.planar.boundary._pinch_kernels import pinch_arcs
from medialaxis.planar.boundary.corners import RingArrays
from medialaxis.planar.boundary.sampling import BoundarySample
from medialaxis.planar.delaunay import Triangulation

__all__ = ["RawAxis", "proper_triangles", "inner_triangles", "axis_positions", "raw_axis", "boundary_distance", "dual_edges_reference"]


@dataclasses.dataclass(frozen=True)
class RawAxis:
    """Inner Voronoi graph with contact data per edge.

    Attributes
    ----------
    points : (n, 2) float ndarray
    radii : (n,) float ndarray
        Distance from each point to the sampled boundary.
    edges : (m, 2) int ndarray
    contact : (m, 2) int ndarray
        Sample indices of the contact points of each edge.
    contact_diameter : (m,) float ndarray
        Distance between the two contacts.
    contact_arc : (m,) float ndarray
        Boundary arc length between the two contacts (inf across rings).
    adjacent : (m,) bool ndarray
        The contacts are consecutive samples: the edge is dual to a boundary
        piece and runs towards the boundary, never along the medial axis.
    triangle : (n,) int ndarray
        Delaunay triangle of each node.
    """

    points: np.ndarray
    radii: np.ndarray
    edges: np.ndarray
    contact: np.ndarray
    contact_diameter: np.ndarray
    contact_arc: np.ndarray
    adjacent: np.ndarray
    triangle: np.ndarray


def proper_triangles(tri: Triangulation) -> np.ndarray:
    """(T,) bool: triangles that are not jitter slivers.

    Triangles thinner than ``1e-7`` of the extent are the slivers the
    triangulation's jitter makes of collinear samples; they lie on the
    boundary and belong to neither side.
    """
    pts = tri.points[tri.simplices]
    u = pts[:, 1] - pts[:, 0]
    v = pts[:, 2] - pts[:, 0]
    twice_area = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
    longest = np.sqrt(np.max([(u**2).sum(1), (v**2).sum(1), ((u - v) ** 2).sum(1)], axis=0))
    extent = float(np.ptp(tri.points, axis=0).max())
    return twice_area > 1e-7 * extent * longest


def inner_triangles(tri: Triangulation, region: Any, locator: RegionLocator | None = None) -> np.ndarray:
    """(T,) bool: proper triangles whose centroid lies inside ``region`` (``locator``: its compiled test)."""
    if locator is not None:
        return locator.inner_triangles(tri.points, tri.simplices, 1e-7)
    extent = float((tri.points.max(0) - tri.points.min(0)).max())
    proper, centroid = triangle_centroids(tri.points, tri.simplices, 1e-7 * extent)
    inside = np.zeros(len(proper), bool)
    inside[proper] = _contains(region, locator, centroid)
    return inside


def _contains(region: Any, locator: RegionLocator | None, xy: np.ndarray) -> np.ndarray:
    """``shapely.contains_xy(region, *xy.T)``, by ``locator`` when there is one."""
    if locator is not None:
        return locator.contains(xy[:, 0], xy[:, 1])
    shapely.prepare(region)
    return shapely.contains_xy(region, xy[:, 0], xy[:, 1])


def boundary_distance(query: np.ndarray, smp: BoundarySample, tree: cKDTree | None = None, k: int = 8) -> np.ndarray:
    """Distance from ``query`` points to the sampled boundary polyline.

    The nearest boundary point lies on a segment next to one of the ``k``
    nearest samples whenever the sampling is finer than the distance, which
    the adaptive sampling ensures; the value never exceeds the distance to the
    nearest sample.
    """
    if len(query) == 0:
        return np.empty(0)
    query = np.ascontiguousarray(query, dtype=np.float64)
    k = min(k, len(smp.points))
    if tree is None and k < len(smp.points):  # the compiled grid, every sample tied with the k-th taken
        return boundary_distance_kernel(query, np.ascontiguousarray(smp.points, dtype=np.float64),
                                        np.asarray(smp.next, np.int64), np.asarray(smp.prev, np.int64), k)
    _, idx = (smp.tree if tree is None else tree).query(query, k=k)
    near = np.ascontiguousarray(idx.reshape(len(query), k), dtype=np.int64)
    return nearest_piece_distance(query, smp.points, smp.next, smp.prev, near)


def _enclosing_centre(tri_pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centre and diameter of the smallest circle enclosing each triangle."""
    sides = np.stack([tri_pts[:, 1] - tri_pts[:, 2], tri_pts[:, 2] - tri_pts[:, 0], tri_pts[:, 0] - tri_pts[:, 1]], 1)
    sq = (sides**2).sum(2)
    k = np.argmax(sq, axis=1)
    rows = np.arange(len(k))
    longest = sq[rows, k]
    others = sq.sum(1) - longest
    obtuse = longest >= others
    mid = 0.5 * (tri_pts[rows, (k + 1) % 3] + tri_pts[rows, (k + 2) % 3])
    return mid, np.sqrt(longest), obtuse


def axis_positions(
    tri: Triangulation, inside: np.ndarray, region: Any, locator: RegionLocator | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """The inner triangles (ascending) and their Voronoi vertices, each one in the shape.

    Voronoi vertices outside the region (obtuse triangles at sparse spots)
    are moved to the centre of the triangle's smallest enclosing circle, or
    its centroid, so every axis point lies in the shape.
    """
    t_in = np.flatnonzero(inside)
    pos = tri.centers[t_in].copy()
    outside = ~_contains(region, locator, pos)
    if outside.any():
        tri_pts = tri.points[tri.simplices[t_in[outside]]]
        mid, _, _ = _enclosing_centre(tri_pts)
        ok = _contains(region, locator, mid)
        pos[outside] = np.where(ok[:, None], mid, tri_pts.mean(1))
    return t_in, pos


def raw_axis(
    tri: Triangulation, inside: np.ndarray, smp: BoundarySample, region: Any, locator: RegionLocator | None = None,
    closed: RingArrays | None = None,
) -> RawAxis:
    """Build the inner Voronoi graph (see module docstring); ``locator``: the compiled inside test of ``region``;
    ``closed``: the sampled rings, whose pinches join the arcs of contacts on two rings
    (:func:`medialaxis.planar.boundary._pinch_kernels.pinch_arcs`)."""
    t_in, pos = axis_positions(tri, inside, region, locator)
    # Dual edges between inner triangles (compiled; dual_edges_reference is the NumPy version)
    edges, contact, diameter, adjacent = dual_edges(tri.simplices, tri.neighbors, t_in.astype(np.int64),
                                                    np.ascontiguousarray(tri.points, dtype=np.float64),
                                                    np.asarray(smp.next, np.int64))
    arc = smp.arc_between(contact[:, 0], contact[:, 1])
    if closed is not None and len(closed.start) - 1 == len(smp.ring_length):
        pinch_arcs(arc, contact, np.asarray(smp.arc, np.float64), np.asarray(smp.ring, np.int64),
                   np.asarray(smp.ring_length, np.float64), closed.s, closed.start, closed.touching)
    radii = boundary_distance(pos, smp)
    return RawAxis(pos, radii, edges, contact, diameter, arc, adjacent, t_in)


def dual_edges_reference(
    tri: Triangulation, inside: np.ndarray, nxt: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """NumPy version of :func:`medialaxis.planar._kernels.dual_edges` (for the tests)."""
    t_in = np.flatnonzero(inside)
    node_of = np.full(len(tri.simplices), -1, np.int64)
    node_of[t_in] = np.arange(len(t_in))
    nb = tri.neighbors[t_in]
    t_rep = np.repeat(t_in, 3)
    k_rep = np.tile(np.arange(3), len(t_in))
    n_rep = nb.ravel()
    valid = n_rep >= 0
    valid[valid] &= inside[n_rep[valid]]
    valid &= t_rep < np.where(n_rep < 0, -1, n_rep)
    t_rep, k_rep, n_rep = t_rep[valid], k_rep[valid], n_rep[valid]
    s = tri.simplices[t_rep]
    rows = np.arange(len(t_rep))
    ca = s[rows, (k_rep + 1) % 3]
    cb = s[rows, (k_rep + 2) % 3]
    diameter = np.linalg.norm(tri.points[ca] - tri.points[cb], axis=1)
    return np.c_[node_of[t_rep], node_of[n_rep]], np.c_[ca, cb], diameter, (nxt[ca] == cb) | (nxt[cb] == ca)
