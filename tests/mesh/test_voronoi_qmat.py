"""Q-MAT-style simplification of Voronoi medial meshes."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import trimesh

import medialaxis as mx
from medialaxis.errors import InvalidInputError
from medialaxis.mesh.simplify.qmat import _initial_quadrics, simplify_medial_mesh
from medialaxis.mesh.voronoi import voronoi_medial_axis

DATA = Path(__file__).resolve().parents[1] / "data" / "meshes"


@pytest.fixture(scope="module")
def box_mesh():
    return trimesh.creation.box(extents=(2.0, 1.0, 0.5))


@pytest.fixture(scope="module")
def box_ma(box_mesh):
    return voronoi_medial_axis(box_mesh, samples=1500, compact=False)  # simplify starts from the full complex


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
    ma = voronoi_medial_axis(box_mesh, samples=1500, simplify=0.05)
    assert ma.metadata["simplified"] and ma.metadata["target_met"]
    assert ma.metadata["hausdorff"] <= 0.05 * ma.metadata["diagonal"]
    assert ma.raw.metadata.get("simplified") is None
    with pytest.raises(InvalidInputError, match="not both"):
        voronoi_medial_axis(box_mesh, samples=1500, simplify=10, simplify_error=0.05)
    for bad in (2, 1.5, 0.0, float("nan"), "1%"):
        with pytest.raises(InvalidInputError, match="simplify_error"):
            voronoi_medial_axis(box_mesh, samples=1500, simplify_error=bad)


def _torus_distance(p, major=1.0, minor=0.3):
    """Signed distance to the round torus (negative inside)."""
    return np.hypot(np.hypot(p[:, 0], p[:, 1]) - major, p[:, 2]) - minor


def test_simplify_error_meets_the_bound_measured_apart():
    torus = trimesh.creation.torus(major_radius=1.0, minor_radius=0.3, major_sections=64, minor_sections=32)
    diag = np.linalg.norm(np.ptp(torus.vertices, axis=0))
    samples, _ = trimesh.sample.sample_surface_even(torus, 3000, seed=0)
    found = {}
    for bound in (0.03, 0.015):
        s = mx.medial_axis(torus, method="voronoi", simplify_error=bound)
        assert s.metadata["target_met"] and s.metadata["hausdorff"] <= bound * diag
        assert s.betti == (1, 1, 0)  # the torus's own: one tunnel
        # apart from the package: the surface to the densely interpolated balls, and how far the
        # balls poke out of the round torus (the mesh's faces lie at most 0.2% of the diagonal inside it)
        assert np.abs(_surface_gap(samples, s, steps=64)).max() <= 1.02 * bound * diag
        c, r = _dense_balls(s, steps=64)
        assert np.max(r + _torus_distance(c)) <= 1.02 * bound * diag
        found[bound] = len(s.points)
    assert found[0.03] < found[0.015]


@pytest.mark.parametrize("bad", [0, -3, 1.5, 0.0, True, "ten"])
def test_rejects_bad_simplify(bad, box_ma):
    with pytest.raises(InvalidInputError):
        simplify_medial_mesh(box_ma, bad)


def _dense_balls(s, steps=8, interiors=False):
    """The simplified mesh's spheres and those interpolated at ``1/steps`` along its edges and its
    triangles' edges (and over a lattice of that step inside its triangles, with ``interiors``)."""
    c, r = s.points, s.radii
    parts = [(c, r)]
    for a, b in np.concatenate([s.edges, s.faces[:, [0, 1]], s.faces[:, [1, 2]], s.faces[:, [2, 0]]]):
        t = np.linspace(0, 1, steps + 1)[1:-1, None]
        parts.append(((1 - t) * c[a] + t * c[b], (1 - t[:, 0]) * r[a] + t[:, 0] * r[b]))
    if interiors:
        uv = np.array([(i, j) for i in range(1, steps) for j in range(1, steps - i)], float) / steps
        w = np.c_[1 - uv.sum(axis=1), uv]
        for f in s.faces:
            parts.append((w @ c[f], w @ r[f]))
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


def _surface_gap(points, s, steps=8, interiors=False):
    """Distance from surface points to the union of the simplified mesh's spheres (vertices and
    interpolations, see :func:`_dense_balls`), computed here by brute force."""
    cc, rr = _dense_balls(s, steps, interiors)
    return np.array([(np.linalg.norm(cc - p, axis=1) - rr).min() for p in points])


def test_every_finger_keeps_a_sphere_near_its_tip():
    # a ball with four thin fingers, made by manifold3d's boolean union (another tool's mesh)
    pytest.importorskip("manifold3d")
    parts = [trimesh.creation.icosphere(subdivisions=4, radius=1.0)]
    directions = np.array([[0, 0, 1], [1, 0, 0], [0, 1, 0], [-1, 0, 0]], float)
    for d in directions:
        finger = trimesh.creation.capsule(height=2.0, radius=0.1, count=[24, 24])
        finger.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], d))
        finger.apply_translation(1.7 * d)
        parts.append(finger)
    hand = trimesh.boolean.union(parts, engine="manifold")
    s = mx.medial_axis(hand, method="voronoi", simplify=20)
    assert len(s.points) == 20 and s.betti == (1, 0, 0)
    tips = directions * (1.7 + 1.0 + 0.1)  # the far ends of the fingers, on the surface
    diag = np.linalg.norm(np.ptp(hand.vertices, axis=0))
    # without the spheres added at the farthest surface points, one tip was 1.8% of the diagonal away
    assert np.abs(_surface_gap(tips, s)).max() < 0.012 * diag
    samples, _ = trimesh.sample.sample_surface_even(hand, 3000, seed=0)
    assert np.abs(_surface_gap(samples, s)).max() < 0.03 * diag


def test_own_surface_figure_on_a_scanned_model_agrees_with_a_brute_force_measure():
    # the scanned kitten (AIM@SHAPE, tests/data/meshes): the package's surface->medial figure against
    # trimesh's even surface sample and densely interpolated balls (edges and triangle interiors)
    kitten = trimesh.load(DATA / "kitten.off", force="mesh", process=False)
    s = mx.medial_axis(kitten, method="voronoi", simplify=60)
    diag = s.metadata["diagonal"]
    samples, _ = trimesh.sample.sample_surface_even(kitten, 4000, seed=1)
    to_mat = np.abs(_surface_gap(samples, s, steps=16, interiors=True)).max()
    # both sample the surface (20,000 points and the vertices against 4,000): they differ by the spacing
    assert abs(s.metadata["hausdorff_surface_to_mat"] - to_mat) < 0.003 * diag
