"""The work on the mesh alone (crossing faces, signed distance) is done once per mesh, beside the sampling.

:func:`~medialaxis.mesh.sample.sample_delaunay.surface_structures` starts before
the sampling; every sample of the same mesh uses its answer: the larger sample
a thin part asks for and the finer second sample where thick air was filled
each used to check the crossings and build the closest-point structures again
(0.9 s of CPU on a 200k-face mesh).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import medialaxis as mx
import medialaxis.mesh.sample.sample_delaunay as sample_delaunay

trimesh = pytest.importorskip("trimesh")


@pytest.fixture
def counted(monkeypatch: pytest.MonkeyPatch) -> dict[str, list[int]]:
    """Calls of the crossing check and of the signed distance (faces of their mesh), and Delaunay insertions (points)."""
    calls: dict[str, list[int]] = {"crossing": [], "signed": [], "delaunay": []}
    crossing, signed, tetra = (sample_delaunay.crossing_pairs, sample_delaunay.SignedDistance,
                               sample_delaunay.tetrahedralise)

    def crossing_pairs(mesh):  # type: ignore[no-untyped-def]
        calls["crossing"].append(len(mesh.faces))
        return crossing(mesh)

    def signed_distance(mesh, normals=None):  # type: ignore[no-untyped-def]
        calls["signed"].append(len(mesh.faces))
        return signed(mesh, normals)

    def tetrahedralise(points):  # type: ignore[no-untyped-def]
        calls["delaunay"].append(len(points))
        return tetra(points)

    monkeypatch.setattr(sample_delaunay, "crossing_pairs", crossing_pairs)
    monkeypatch.setattr(sample_delaunay, "SignedDistance", signed_distance)
    monkeypatch.setattr(sample_delaunay, "tetrahedralise", tetrahedralise)
    return calls


def test_a_thin_plate_is_sampled_twice_and_checked_once(counted: dict[str, list[int]]) -> None:
    """A 10 x 10 x 0.2 plate (8 vertices, as CAD writes it): the thin-part check asks for a larger sample."""
    plate = trimesh.creation.box(extents=(10.0, 10.0, 0.2))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ma = mx.medial_axis(plate, method="voronoi", compact=False)
    assert len(counted["delaunay"]) == 2 and counted["delaunay"][1] > counted["delaunay"][0]
    assert counted["crossing"] == [12] and counted["signed"] == [12]
    # the answer is the plate's mid-sheet: within a tenth of the thickness of z = 0 away from the rim, each
    # ball touching the nearer face (radius 0.1 - |z|: the Voronoi vertices of the two faces' samples)
    middle = (np.abs(ma.points[:, :2]) < 4.0).all(axis=1)
    assert middle.sum() > 1000
    z = np.abs(ma.points[middle, 2])
    assert z.max() < 0.02
    np.testing.assert_allclose(ma.radii[middle], 0.1 - z, atol=1e-9)
    assert ma.betti == (1, 0, 0)


def test_a_crossing_surface_is_checked_again_as_its_solid(counted: dict[str, list[int]]) -> None:
    """Two boxes through each other: the check finds the crossing, and runs again on the solid made of it."""
    a = trimesh.creation.box(extents=(2.0, 1.0, 1.0))
    b = trimesh.creation.box(extents=(1.0, 2.0, 1.0))
    b.apply_translation((0.3, 0.2, 0.1))
    both = trimesh.util.concatenate([a, b])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ma = mx.medial_axis(both, method="voronoi", compact=False, samples=4000)
    assert any("passes through itself" in str(w.message) for w in caught)
    assert len(counted["crossing"]) == 2 and counted["crossing"][0] == 24 and counted["crossing"][1] != 24
    assert counted["signed"] == counted["crossing"][1:]  # none for the surface that crosses itself
    assert ma.betti == (1, 0, 0)


def test_the_finer_second_sample_reuses_the_mesh_work(counted: dict[str, list[int]]) -> None:
    """The cavity under a pinch of ``test_refine_pockets``: sampled twice, the mesh checked once."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from test_pinch_half_ball import _input

    mesh, _ = _input(2.0, 0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ma = mx.medial_axis(mesh, method="voronoi")
    assert "refine" in ma.metadata["timings"]
    assert len(counted["delaunay"]) >= 2
    assert len(counted["crossing"]) == 1 and len(counted["signed"]) == 1


def test_thin_plates_through_each_other_measure_epsilon_once(counted, monkeypatch):
    """Two crossing plates by default: the crossing is found first, the larger sample is taken of the solid only.

    Epsilon draws from the route's random generator: it is measured for the
    sample the complex is built on and for no other, as before the mesh's own
    work moved ahead of the sampling.
    """
    draws = []
    measure = sample_delaunay.measure_epsilon

    def measure_epsilon(mesh, points, *args):  # type: ignore[no-untyped-def]
        draws.append(len(points))
        return measure(mesh, points, *args)

    monkeypatch.setattr(sample_delaunay, "measure_epsilon", measure_epsilon)
    a = trimesh.creation.box(extents=(6.0, 6.0, 0.3))
    b = trimesh.creation.box(extents=(0.3, 6.0, 6.0))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ma = mx.medial_axis(trimesh.util.concatenate([a, b]), method="voronoi", compact=False)
    assert any("passes through itself" in str(w.message) for w in caught)
    assert len(counted["crossing"]) == 2 and counted["crossing"][0] == 24  # the mesh, then its solid
    # the crossing mesh is not sampled again at the larger count its thin check asks (that was a third insertion,
    # thrown away): the solid is sampled at it at once
    assert len(counted["delaunay"]) == 2 and counted["delaunay"][1] > counted["delaunay"][0]
    assert draws == counted["delaunay"][-1:]  # once, on the sample inserted last
    assert ma.betti == (1, 0, 0)
