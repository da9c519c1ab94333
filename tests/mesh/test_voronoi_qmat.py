"""Q-MAT-style simplification of Voronoi medial meshes."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from medialaxis.errors import InvalidInputError
from medialaxis.mesh.qmat import _initial_quadrics, simplify_medial_mesh
from medialaxis.mesh.voronoi import voronoi_medial_axis


@pytest.fixture(scope="module")
def box_mesh():
    return trimesh.creation.box(extents=(2.0, 1.0, 0.5))


@pytest.fixture(scope="module")
def box_ma(box_mesh):
    return voronoi_medial_axis(box_mesh, samples=1500)


def test_initial_quadrics_vanish_on_the_medial_spheres(box_ma):
    qa, qb, qc = _initial_quadrics(box_ma)
    s = np.c_[box_ma.points, box_ma.radii]
    err = np.einsum("ni,nij,nj->n", s, qa, s) - 2 * np.einsum("ni,ni->n", qb, s) + qc
    # each contact lies on its sphere up to the radius polish (sample vs. mesh distance)
    assert np.sqrt(np.abs(err).max()) <= 2 * box_ma.metadata["epsilon"]


def test_simplify_to_n_spheres_reports_hausdorff(box_ma, box_mesh):
    few = simplify_medial_mesh(box_ma, 30, surface=box_mesh)
    more = simplify_medial_mesh(box_ma, 200, surface=box_mesh)
    assert len(few.points) == 30 and len(more.points) == 200
    assert few.raw is box_ma and few.metadata["n_spheres"] == 30
    for s in (few, more):
        h = s.metadata["hausdorff"]
        assert h == max(s.metadata["hausdorff_surface_to_mat"], s.metadata["hausdorff_mat_to_surface"])
        assert 0 < h < 0.25 * s.metadata["diagonal"]
        assert np.all(s.radii > 0)
    assert more.metadata["hausdorff"] <= few.metadata["hausdorff"] + 1e-9
    # spheres stay inside the box, near the medial sheets
    half = np.array([1.0, 0.5, 0.25])
    assert np.all(np.abs(few.points) <= half)


def test_simplify_by_error_bound_and_through_the_pipeline(box_mesh):
    ma = voronoi_medial_axis(box_mesh, samples=1500, simplify=0.02)
    assert ma.metadata["simplified"] and 1 <= len(ma.points) < len(ma.raw.points)
    assert ma.raw.metadata.get("simplified") is None


@pytest.mark.parametrize("bad", [0, -3, 1.5, 0.0, True, "ten"])
def test_rejects_bad_simplify(bad, box_ma):
    with pytest.raises(InvalidInputError):
        simplify_medial_mesh(box_ma, bad)
