"""Samples of a regular mesh in cospherical groups are moved a little (``sampling.JITTER``), others not.

A float32 torus, as a PLY or STL file holds it, sampled at its lattice: large
groups of samples lie on common spheres, and the Delaunay tetrahedralisation
of such a group is a fan of slivers, each an inner Voronoi vertex. The truths
here come from outside the sampler: SciPy's Delaunay of the samples, the
barycentric coordinates trimesh computes, the torus's own geometry.
"""

from pathlib import Path

import numpy as np
import pytest
import trimesh
from scipy.spatial import Delaunay, cKDTree

from medialaxis.mesh.sample import sampling
from medialaxis.mesh.sample.sampling import JITTER, degenerate, face_spacing_for_count, sample_surface
from medialaxis.mesh.voronoi import voronoi_medial_axis

DATA = Path(__file__).resolve().parents[1] / "data" / "meshes"


def _float32_torus(minor: int) -> trimesh.Trimesh:
    mesh = trimesh.creation.torus(3.0, 1.0, major_sections=2 * minor, minor_sections=minor)
    return trimesh.Trimesh(np.asarray(mesh.vertices, np.float32).astype(np.float64), mesh.faces)


@pytest.fixture(scope="module")
def torus_samples():
    mesh = _float32_torus(60)
    spacing = face_spacing_for_count(np.asarray(mesh.area_faces), np.ones(len(mesh.faces)), 10_000)
    return mesh, spacing, sample_surface(mesh, spacing), sample_surface(mesh, spacing, jitter=True)


def test_the_jittered_sample_lies_on_its_faces_and_keeps_the_vertices(torus_samples):
    mesh, spacing, plain, moved = torus_samples
    n = len(mesh.vertices)
    np.testing.assert_array_equal(moved.points[:n], mesh.vertices)  # every vertex, unmoved
    # (the lattice sample has points that coincide, dropped as one; moved apart, both stay)
    assert len(plain.points) <= len(moved.points) <= 1.1 * len(plain.points)
    bary = trimesh.triangles.points_to_barycentric(mesh.triangles[moved.face], moved.points)
    assert bary.min() > -1e-9 and bary.max() < 1 + 1e-9  # in its face (the plane: the barycentric fit)
    back = np.einsum("ij,ijk->ik", bary, mesh.triangles[moved.face])
    assert np.abs(back - moved.points).max() < 1e-9
    shift = cKDTree(plain.points).query(moved.points)[0]  # from the nearest lattice point
    assert shift.max() <= 2 * JITTER * spacing.max()
    assert np.median(shift[n:]) > 0.1 * JITTER * spacing.min()  # the edge and face points did move
    again = sample_surface(mesh, spacing, jitter=True)
    np.testing.assert_array_equal(again.points, moved.points)  # seeded: the same sample each call


def test_scipy_finds_the_lattice_sample_degenerate_and_the_jittered_one_not(torus_samples):
    _, _, plain, moved = torus_samples
    before, after = (len(Delaunay(s.points).simplices) for s in (plain, moved))
    assert degenerate(before, len(plain.points)) and not degenerate(after, len(moved.points))
    assert after < 0.75 * before


def test_a_scanned_models_sample_is_not_degenerate():
    # a scan (tests/data/meshes: the kitten) is in general position: its sample stays as it is (the 57 real
    # models of benchmarks/bench_mesh_routes.py: the same points, faces and Betti numbers as before)
    mesh = trimesh.load(DATA / "kitten.off", process=False)
    spacing = face_spacing_for_count(np.asarray(mesh.area_faces), np.ones(len(mesh.faces)), 20_000)
    points = sample_surface(mesh, spacing).points
    assert not degenerate(len(Delaunay(points).simplices), len(points))
    assert not voronoi_medial_axis(mesh, compact=False).metadata["sample_jittered"]


def test_a_degenerate_torus_gets_a_smaller_full_complex_and_the_same_axis(monkeypatch):
    mesh = _float32_torus(80)
    ma, default = voronoi_medial_axis(mesh, compact=False), voronoi_medial_axis(mesh)
    monkeypatch.setattr(sampling, "DEGENERATE_TETRAHEDRA", np.inf)  # as before: the lattice sample kept
    lattice = voronoi_medial_axis(mesh, compact=False)
    assert ma.betti == lattice.betti == (1, 1, 0)
    assert len(ma.points) < 0.6 * len(lattice.points)
    assert ma.metadata["sample_jittered"] and not lattice.metadata["sample_jittered"]
    for result in (ma, default):  # the full complex and the default call
        core = np.hypot(np.hypot(result.points[:, 0], result.points[:, 1]) - 3.0, result.points[:, 2])
        assert np.percentile(core, 99) < 0.02 and core.max() < 0.05  # of the minor radius 1
        assert np.percentile(np.abs(result.radii - 1.0), 99) < 0.02
