"""Dense meshes: a coarse spacing is allowed, and the Delaunay does not depend on the order of the samples."""

import numpy as np
import pytest
import trimesh

from medialaxis.mesh.medial.voronoi_diagram import tetrahedralise
from medialaxis.mesh.sample.sampling import sample_surface


def _dense_plate(thickness=0.02, size=1.0, subdivisions=5):
    plate = trimesh.creation.box(extents=(size, size, thickness))
    for _ in range(subdivisions):
        plate = plate.subdivide()
    return plate


def test_sampling_a_dense_mesh_coarsely_is_allowed():
    # the planned count counted one point per edge where an edge gets none (a false 'needle' error)
    plate = _dense_plate(thickness=0.2, subdivisions=6)
    smp = sample_surface(plate, np.full(len(plate.faces), 0.2), limit=len(plate.vertices) + 1000)
    assert len(smp.points) >= len(plate.vertices)


def test_delaunay_does_not_depend_on_the_sample_order():
    rng = np.random.default_rng(1)
    points = trimesh.creation.icosphere(4).vertices * 2.0  # co-spherical: the degenerate case
    a = tetrahedralise(points)
    perm = rng.permutation(len(points))
    b = tetrahedralise(points[perm])

    def volume(dt):
        return np.abs(np.linalg.det(dt.points[dt.simplices[:, 1:]] - dt.points[dt.simplices[:, :1]])).sum() / 6

    assert volume(a) == pytest.approx(volume(b), rel=1e-9)
    assert volume(a) == pytest.approx(trimesh.convex.convex_hull(points).volume, rel=1e-9)
