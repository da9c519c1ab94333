"""``prune(lam=)`` of mesh Voronoi results: the full complex collapsed down to a larger lambda (issue 33.1).

The truth is the route itself computed again at that lambda (Delaunay,
inside test, collapse of the facets narrower than lambda from scratch):
the re-pruned full complex must be the same triangles, and the Betti numbers
(computed apart, over GF(2)) the solid's.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import medialaxis as mx

trimesh = pytest.importorskip("trimesh")


def _triangles(ma) -> np.ndarray:
    """The triangles as sorted rows of their corners' coordinates, sorted: comparable across numberings."""
    tri = np.sort(np.round(ma.points[ma.faces], 12).reshape(len(ma.faces), -1).reshape(-1, 3, 3), axis=1)
    flat = tri.reshape(len(tri), -1)
    return flat[np.lexsort(flat.T[::-1])]


@pytest.fixture(scope="module")
def torus():
    mesh = trimesh.creation.torus(1.0, 0.35, major_sections=48, minor_sections=24)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mx.MedialAxisWarning)
        return mesh, mx.medial_axis(mesh, samples=3000)


@pytest.mark.parametrize("factor", [1.5, 2.5])
def test_repruned_full_complex_is_the_route_run_again_at_that_lambda(torus, factor):
    mesh, ma = torus
    lam = ma.metadata["lam"] * factor
    pruned = ma.prune(lam=lam)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mx.MedialAxisWarning)
        again = mx.medial_axis(mesh, samples=3000, lam=lam, compact=False)
    assert 0 < len(pruned.raw.faces) < len(ma.raw.faces)
    assert np.array_equal(_triangles(pruned.raw), _triangles(again))
    assert pruned.raw.betti == again.betti == pruned.betti == (1, 1, 0)
    assert pruned.metadata["lam"] == lam and pruned.raw.metadata["repruned_from"] == ma.metadata["lam"]
    # what stays narrower than lambda is the sheet of the tube, thinner than lambda (kept by the route too)
    narrow = pruned.raw.extras["face_contact_diameter"] < lam
    assert np.all(pruned.raw.extras["face_thin"][narrow])


def test_reprune_of_a_full_complex_and_of_a_saved_result(torus, tmp_path):
    mesh, ma = torus
    lam = 1.5 * ma.metadata["lam"]
    from_full = ma.raw.prune(lam=lam)  # compact=False results are their own full complex
    assert from_full.raw is None and np.array_equal(_triangles(from_full), _triangles(ma.prune(lam=lam).raw))
    ma.save(tmp_path / "t.npz")
    loaded = mx.load(tmp_path / "t.npz")
    assert np.array_equal(_triangles(loaded.prune(lam=lam).raw), _triangles(ma.prune(lam=lam).raw))
    assert mx.medial_axis(str(tmp_path / "t.npz"), lam=lam).betti == (1, 1, 0)  # re-pruned on load


def test_reprune_refuses_what_needs_the_voronoi_diagram_again(torus):
    _, ma = torus
    with pytest.raises(mx.InvalidInputError, match="smaller lam needs the Voronoi diagram again"):
        ma.prune(lam=0.5 * ma.metadata["lam"])
    assert ma.prune() is ma and ma.prune(lam=ma.metadata["lam"]).betti == ma.betti


def test_prune_is_absent_where_lambda_does_not_apply():
    """Mid-surfaces and voxel sets have no prune(): hasattr says so, and the error says why."""
    plate = np.zeros((16, 16, 16), bool)
    plate[3:13, 3:13, 6:10] = True
    for method in ("midsurface", "voxels"):
        ma = mx.medial_axis(plate, method=method)
        assert not hasattr(ma, "prune") and "prune" not in dir(ma)
        with pytest.raises(AttributeError, match="have no prune"):
            ma.prune(lam=1.0)
    assert hasattr(mx.medial_axis(trimesh.creation.box(extents=(2, 1, 0.5)), samples=1000), "prune")
