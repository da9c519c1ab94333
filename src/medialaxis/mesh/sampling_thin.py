"""Thinning of a surface sample to its local spacing (``sample_surface(thin=)``).

The structured sample of :func:`~medialaxis.mesh.sampling.sample_surface`
(every vertex, edge points, face points) crowds where the mesh is finer
than the spacing asked for: the poles of a uv sphere, fans of slivers, and
edge points beside face points. :func:`thinned` keeps, in an order that
puts sharp features first, each sample that no sample kept before lies
nearer to than half the local spacing
(:func:`~medialaxis.mesh._sampling_kernels.thin_to_spacing`); every sample
dropped lies within that distance of a kept one. Sparse samples of this
kind (no two closer than a fraction of the spacing) are the (epsilon,
delta)-samples of Dey, "Curve and Surface Reconstruction: Algorithms with
Mathematical Analysis", Cambridge University Press, 2006.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from medialaxis.mesh._sampling_kernels import thin_to_spacing

if TYPE_CHECKING:
    from medialaxis.mesh.sampling import PseudoNormals

__all__ = ["thinned", "THIN_SPACING", "SHARP_COSINE"]

#: Samples of the Voronoi route nearer than this fraction of the local
#: spacing to one ranked before them are dropped (``sample_surface(thin=)``):
#: the 99k-vertex uv ellipsoid of ``benchmarks/bench_mesh_voronoi.py`` keeps
#: 142,077 of 221,197 samples, the 100k bumpy torus 131,220 of 138,820, both
#: with the same measured epsilon (0.6 gave the torus a 24% larger one).
THIN_SPACING = 0.5
#: A sample whose normal is farther than acos(SHARP_COSINE) (14 degrees) from
#: one of its faces' normals is sharp: it ranks first when thinning.
SHARP_COSINE = 0.97


def thinned(
    pn: PseudoNormals, f: np.ndarray, spacing: np.ndarray, edge_h: np.ndarray, eo: np.ndarray, fo: np.ndarray,
    points: np.ndarray, thin: float,
) -> np.ndarray:
    """Indices (ascending) of the samples ``[vertices, edge points, face points]`` left by thinning."""

    n_v = len(pn.vertex)
    vertex_h = np.full(n_v, np.inf)
    vertex_flat = np.ones(n_v)  # least cosine between the vertex's normal and its faces' normals
    for k in range(3):
        np.minimum.at(vertex_h, f[:, k], spacing)
        np.minimum.at(vertex_flat, f[:, k], np.einsum("ij,ij->i", pn.face, pn.vertex[f[:, k]]))
    edge_flat = np.ones(len(edge_h))
    for k in range(3):
        np.minimum.at(edge_flat, pn.face_edges[:, k], np.einsum("ij,ij->i", pn.face, pn.edge[pn.face_edges[:, k]]))
    h = np.concatenate([vertex_h, edge_h[eo], spacing[fo]])
    flat = np.concatenate([vertex_flat, edge_flat[eo], np.ones(len(fo))])
    # sharp samples first, the sharpest first; then face points (spread by their low-discrepancy
    # sequence), edge points, vertices: edge points line up in rows at the same heights along a
    # capsule's long faces (tests/mesh/test_voronoi.py's, samples=12,000), whose lens-shaped gaps
    # put Voronoi vertices off the axis: 0.0235 of the 0.5 radius with vertices first, 0.0142 so
    # (unthinned 0.0073, and 0.0073-0.014 over 8,000-20,000 samples)
    kind = np.concatenate([np.full(len(vertex_flat), 3.0), np.full(len(eo), 2.0), np.full(len(fo), 1.0)])
    order = np.argsort(np.where(flat < SHARP_COSINE, flat - 2.0, kind), kind="stable")
    group = np.concatenate([np.full(n_v + len(eo), -1), fo])  # a face's own points are spread already
    return np.flatnonzero(thin_to_spacing(points, thin * h, order, group))
