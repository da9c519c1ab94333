"""Thinning of the surface sample: the compiled kernel against its reference, and what the sample keeps."""

import numpy as np
import pytest
import trimesh
from scipy.spatial import cKDTree

from medialaxis.mesh._sampling_kernels import thin_to_spacing, thin_to_spacing_reference
from medialaxis.mesh.sampling import face_spacing_for_count, sample_surface
from medialaxis.mesh.sampling_thin import THIN_SPACING


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_kernel_keeps_what_the_reference_keeps(seed):
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(3000, 3))
    points[:500] = points[:1] + 1e-3 * rng.normal(size=(500, 3))  # a crowd
    points[500:510] = points[600]  # coincident points
    radius = rng.uniform(0.05, 0.4, len(points))
    order = rng.permutation(len(points))
    group = np.where(rng.random(len(points)) < 0.5, rng.integers(0, 20, len(points)), -1)
    keep = thin_to_spacing(points, radius, order, group)
    assert np.array_equal(keep, thin_to_spacing_reference(points, radius, order, group))
    assert np.array_equal(thin_to_spacing(points, radius, order, np.full(len(points), -1)),
                          thin_to_spacing_reference(points, radius, order, np.full(len(points), -1)))
    group = np.full(len(points), -1)
    keep = thin_to_spacing(points, radius, order, group)
    # nothing kept lies within the smaller radius of another kept point; all dropped lie within their own
    kept = np.flatnonzero(keep)
    pairs = cKDTree(points[kept]).query_pairs(radius.max(), output_type="ndarray")
    gap = np.linalg.norm(points[kept[pairs[:, 0]]] - points[kept[pairs[:, 1]]], axis=1)
    assert np.all(gap >= np.minimum(radius[kept[pairs[:, 0]]], radius[kept[pairs[:, 1]]]))
    dist, _ = cKDTree(points[kept]).query(points[~keep])
    assert np.all(dist < radius[~keep])


def _uv_ellipsoid(count=64):
    mesh = trimesh.creation.uv_sphere(radius=1.0, count=[count, count])
    mesh.apply_scale([3.0, 1.0, 1.0])
    return mesh


def test_crowded_poles_add_no_samples_and_keep_the_cover():
    # a uv sphere crowds its vertices at the poles: thinned, the sample follows the spacing asked for
    mesh = _uv_ellipsoid()
    spacing = face_spacing_for_count(mesh.area_faces, np.ones(len(mesh.faces)), 4000)
    full = sample_surface(mesh, spacing)
    thin = sample_surface(mesh, spacing, thin=THIN_SPACING)
    assert len(thin.points) < 0.75 * len(full.points)
    nearest, _ = cKDTree(thin.points).query(thin.points, k=2)
    assert nearest[:, 1].min() >= THIN_SPACING * spacing.min() * (1 - 1e-12)
    # every point of the full sample lies within the thinning radius of a kept one
    dist, _ = cKDTree(thin.points).query(full.points)
    assert dist.max() <= THIN_SPACING * spacing.max()
    # kept samples are samples of the full set, with their normals and faces
    index = cKDTree(full.points).query(thin.points)[1]
    assert np.allclose(full.points[index], thin.points, atol=0)
    assert np.array_equal(full.face[index], thin.face)
    assert np.array_equal(full.normals[index], thin.normals)


def test_box_corners_are_kept():
    box = trimesh.creation.box(extents=(2.0, 1.0, 0.5)).subdivide().subdivide()
    spacing = np.full(len(box.faces), 0.3)
    smp = sample_surface(box, spacing, thin=THIN_SPACING)
    corners = trimesh.creation.box(extents=(2.0, 1.0, 0.5)).vertices
    assert cKDTree(smp.points).query(corners)[0].max() == 0.0


def test_only_pole_like_circumcentres_stand_for_medial_points():
    from types import SimpleNamespace

    from medialaxis.mesh.sampling import _pole_like

    rng = np.random.default_rng(0)
    on_sphere = rng.normal(size=(4, 3))
    on_sphere /= np.linalg.norm(on_sphere, axis=1)[:, None]  # centre 0: each normal points away from it
    angle = np.array([0.1, 1.7, 3.3, 4.9])
    flat = np.c_[np.cos(angle), np.sin(angle), 1e-3 * np.array([1.0, -1.0, 1.0, -1.0])]  # a flat patch
    up = np.tile([0.0, 0.0, 1.0], (4, 1))
    dt = SimpleNamespace(points=np.r_[on_sphere, flat], simplices=np.array([[0, 1, 2, 3], [4, 5, 6, 7]]),
                         centres=np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]))
    assert list(_pole_like(dt, np.array([0, 1]), np.r_[on_sphere, up])) == [True, False]
