"""Memory bounded by the mesh: the exact signed distance on a float32 torus, out-of-memory errors of the side work."""

import threading
import tracemalloc

import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")

import medialaxis as mx  # noqa: E402
import medialaxis._jit as jit  # noqa: E402
from medialaxis.mesh.sample._closest_kernels import closest_point_reference, face_tree  # noqa: E402
from medialaxis.mesh.sample.signed_distance import SignedDistance  # noqa: E402


@pytest.fixture(scope="module")
def float32_torus(tmp_path_factory):
    """A torus written to PLY by trimesh (float32 coordinates, as every STL is) and read back."""
    path = tmp_path_factory.mktemp("torus") / "torus.ply"
    trimesh.creation.torus(3, 1, major_sections=64, minor_sections=32).export(path)
    mesh = trimesh.load(path)
    assert np.array_equal(mesh.vertices, mesh.vertices.astype(np.float32))
    return mesh


def _probes(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Points of the core circle (every face of the tube's ring nearly equidistant) and far outside (most faces)."""
    angle = rng.uniform(0, 2 * np.pi, 300)
    core = np.c_[3 * np.cos(angle), 3 * np.sin(angle), np.zeros(300)]
    far = rng.normal(size=(300, 3))
    far *= rng.uniform(10, 30, (300, 1)) / np.linalg.norm(far, axis=1, keepdims=True)
    return core, far


def test_exact_distance_tests_a_bounded_number_of_faces_per_point(float32_torus):
    # the tube's faces are nearly equidistant from the core circle, and all of them nearly so from a point 30
    # radii away: the former search gathered every face within (distance found + largest reach) of each point
    # (24 GB on the 51,200-vertex torus); the tree opens only boxes nearer than the distance found
    core, far = _probes(np.random.default_rng(0))
    points = np.r_[core, far]
    sd = SignedDistance(float32_torus)
    dist, closest, face, region, tested = sd._exact(points, 32, 1_000_000)
    n_faces = len(float32_torus.faces)
    ring = 2 * 32  # faces around the tube at one angle of the core circle
    assert tested[:300].max() <= 8 * ring, tested[:300].max()  # a few rings of faces, not the tube
    assert tested[300:].max() <= n_faces // 20, tested[300:].max()
    assert np.allclose(dist, closest_point_reference(points, np.asarray(float32_torus.triangles)), rtol=0, atol=1e-12)
    signed, _ = sd.exact(points)
    assert np.array_equal(signed, np.where(float32_torus.contains(points), -dist, dist))


def test_exact_distance_memory_grows_with_the_points_not_with_the_faces_they_see(float32_torus):
    core, far = _probes(np.random.default_rng(1))
    points = np.repeat(np.r_[core, far], 40, axis=0)  # 24,000 points, each near 6 % or all of 4096 faces
    sd = SignedDistance(float32_torus)
    sd.exact(points[:10])  # the trees, built once
    tracemalloc.start()
    try:
        sd.exact(points, budget=8_000)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    # about 1 kB a point of neighbour lists and answers; the candidate lists took about 150 kB a point
    assert peak < 2_000 * len(points), peak


def test_face_tree_holds_every_face_once_in_boxes_around_them(float32_torus):
    sd = SignedDistance(float32_torus)
    order, low, high, child, start, stop = face_tree(sd.spheres[0], *sd.corners)
    assert np.array_equal(np.sort(order), np.arange(len(float32_torus.faces)))
    leaves = np.flatnonzero(child < 0)
    assert (stop[leaves] - start[leaves]).max() <= 8
    assert np.array_equal(np.sort(np.concatenate([order[start[n] : stop[n]] for n in leaves])), np.sort(order))
    for n in leaves:
        tri = np.asarray(float32_torus.triangles)[order[start[n] : stop[n]]].reshape(-1, 3)
        assert (tri >= low[n]).all() and (tri <= high[n]).all()


def _out_of_memory(*args, **kwargs):
    raise MemoryError("Unable to allocate 24.0 GiB for an array")


@pytest.mark.parametrize("concurrent", [True, False])
def test_running_out_of_memory_beside_the_delaunay_says_so(monkeypatch, concurrent):
    # the signed-distance structure is built beside the Delaunay insertion: its MemoryError reaches the
    # caller as a ResourceLimitError (a MemoryError), never as a TypeError of a value it did not return
    monkeypatch.setattr(jit, "concurrent_kernels", lambda: concurrent)
    monkeypatch.setattr(SignedDistance, "__init__", _out_of_memory)
    with pytest.raises(mx.ResourceLimitError, match="out of memory in .*Unable to allocate 24.0 GiB") as info:
        mx.medial_axis(trimesh.creation.capsule(height=2.0, radius=0.5), method="voronoi", samples=2000)
    assert isinstance(info.value, MemoryError) and isinstance(info.value.__cause__, MemoryError)


def test_beside_works_at_once_when_no_thread_can_be_started(monkeypatch):
    monkeypatch.setattr(jit, "concurrent_kernels", lambda: True)

    def refuse(self):
        raise RuntimeError("can't start new thread")

    monkeypatch.setattr(threading.Thread, "start", refuse)
    caller = threading.get_ident()
    side = jit.Beside(lambda a: (threading.get_ident(), a + 1), 41)
    assert side.result() == (caller, 42)
    with pytest.raises(mx.ResourceLimitError, match="out of memory in _out_of_memory"):
        jit.Beside(_out_of_memory).result()


def test_the_compaction_does_not_depend_on_how_many_rows_are_made_at_once(monkeypatch):
    # the reach check of each round runs CHUNK rows at a time (bounded temporaries; the sphere quadrics make none)
    import medialaxis.mesh.medial.compact_inside as compact_inside

    mesh = trimesh.creation.torus(3, 1, major_sections=24, minor_sections=12)
    results = []
    for chunk in (compact_inside.CHUNK, 97):
        monkeypatch.setattr(compact_inside, "CHUNK", chunk)
        results.append(mx.medial_axis(mesh, method="voronoi", samples=3000))
    a, b = results
    assert a.metadata["full_points"] > 20 * 97  # several chunks
    for name in ("points", "radii", "faces", "edges"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert a.betti == (1, 1, 0)
