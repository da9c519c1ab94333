"""The inner Delaunay tetrahedra of a surface sample: their union stands for the solid.

The medial complex of the Voronoi route is the dual of the union of the
Delaunay tetrahedra inside the solid
(:func:`~medialaxis.mesh.medial.voronoi_complex.medial_complex`), so that union must
have the solid's topology. A tetrahedron is inner when its centroid is
inside; two things made the union wrong, and are mended here:

* flat tetrahedra on the surface whose centroids are a hair inside
  (``FLAT_DEPTH``);
* a centroid signed by the faces at the tetrahedron's own samples although
  it lies nearer another part of the surface (checked against its nearest
  sample, :meth:`~medialaxis.mesh.sample.signed_distance.SignedDistance.recheck_sides`).

What is left to :func:`~medialaxis.mesh.medial.voronoi_complex.unpinch`: pinched
edges and points of the union.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.mesh.medial._voronoi_kernels import nearest_other_sample, tet_centroids
from medialaxis.mesh.sample.signed_distance import SignedDistance

__all__ = ["inner_tets", "FLAT_DEPTH"]

#: A tetrahedron is inner when its centroid is deeper than this fraction of
#: its longest edge. Surface slivers on a sphere of radius R sampled at
#: spacing s lie about s / (8 R) deep: 1e-5 keeps them up to R = 12,500 s;
#: 1e-3 leaves samples covered on the uv ellipsoid again.
FLAT_DEPTH = 1e-5


def inner_tets(dt: Any, smp: Any, sd: SignedDistance, tolerance: float) -> np.ndarray:
    """Inner tetrahedra: centroid deeper than ``tolerance`` and than ``FLAT_DEPTH`` times the longest edge.

    Flat tetrahedra lying on a face of the mesh are not inner, nor those
    lying on a nearly flat part of it: on the cap of a uv sphere, stacks of
    them with three nearly collinear samples are a hair inside, cover
    samples of the cap (every tetrahedron around such a sample is inner, its
    Voronoi cell is closed and the medial complex gains a void: 57 on a
    224 x 224 uv ellipsoid) and bring circumcentres from far away. The
    side found among the faces at a tetrahedron's samples is checked against
    the sample nearest to its centroid.

    Parameters
    ----------
    dt : Tetrahedralisation
    smp : SurfaceSample
        The samples (``face``: the face of each).
    sd : SignedDistance
    tolerance : float
        Smallest depth of an inner centroid.

    Returns
    -------
    (t,) bool ndarray
    """
    centroids = tet_centroids(dt.points, dt.simplices)
    signed, _ = sd.query(centroids, smp.face[dt.simplices])
    normals = sd.normals.face[smp.face]
    nearest = nearest_other_sample(centroids, dt.points, dt.simplices, dt.centres, dt.radii, normals, signed)
    sd.recheck_sides(centroids, signed, nearest, dt.points, smp.face)
    return signed < -np.maximum(tolerance, FLAT_DEPTH * dt.longest)
