"""Diffusion-flow curve skeletons of meshes (issue 5; Du and Qin, SM '04)."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import medialaxis as mx
from medialaxis._progress import Progress
from medialaxis.datasets import capsules_mesh, segment_distance, tripod_mesh, tripod_segments
from medialaxis.mesh.flow import FlowState, nonmanifold_vertices
from medialaxis.mesh.skeleton import _flow_operators as ops

RADIUS = 0.5
CAPSULE_AXIS = np.array([[[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]]])


@pytest.fixture(scope="module")
def tripod():
    return tripod_mesh(radius=RADIUS, arm=3.0, pitch=0.1)


@pytest.fixture(scope="module")
def tripod_skeleton(tripod):
    return mx.medial_axis(tripod, method="flow")


@pytest.fixture(scope="module")
def capsule():
    return capsules_mesh(CAPSULE_AXIS, RADIUS, pitch=0.1)


# ------------------------------------------------------------ analytic shapes
def test_tripod_skeleton_lies_on_the_three_axes(tripod_skeleton):
    d = segment_distance(tripod_skeleton.points, tripod_segments(3.0))
    assert np.percentile(d, 99) <= 0.1
    assert d.mean() <= 0.05


def test_tripod_topology(tripod_skeleton):
    assert len(tripod_skeleton.endpoints) == 3
    assert len(tripod_skeleton.junctions) == 1
    assert tripod_skeleton.n_cycles == 0
    assert tripod_skeleton.n_components == 1


def test_tripod_arms_covered_to_within_one_radius(tripod_skeleton):
    for tip in tripod_segments(3.0)[:, 1]:
        assert np.linalg.norm(tripod_skeleton.points - tip, axis=1).min() <= RADIUS
    # and every arm is covered along its length, not only at its end
    for a, b in tripod_segments(3.0):
        for t in np.linspace(0.2, 1.0, 9):
            assert np.linalg.norm(tripod_skeleton.points - (a + t * (b - a)), axis=1).min() <= RADIUS


def test_tripod_median_radius(tripod_skeleton):
    assert abs(np.median(tripod_skeleton.radii) - RADIUS) <= 0.1


def test_tripod_correspondence_and_metadata(tripod, tripod_skeleton):
    corr = tripod_skeleton.correspondence
    assert corr.shape == (len(tripod.vertices),)
    assert corr.min() >= 0 and corr.max() < len(tripod_skeleton.points)
    assert tripod_skeleton.metadata["method"] == "flow"
    assert tripod_skeleton.metadata["converged"]
    assert len(tripod_skeleton.faces) == 0
    # each vertex maps to a nearby node: within a few radii
    gap = np.linalg.norm(np.asarray(tripod.vertices) - tripod_skeleton.points[corr], axis=1)
    assert np.percentile(gap, 95) < 3 * RADIUS


def test_capsule_has_two_endpoints_and_no_junction(capsule):
    sk = mx.medial_axis(capsule, method="flow")
    assert len(sk.endpoints) == 2 and len(sk.junctions) == 0 and sk.n_cycles == 0
    assert segment_distance(sk.points, CAPSULE_AXIS).max() < 0.05
    assert abs(np.median(sk.radii) - RADIUS) < 0.05


def test_torus_gives_one_cycle():
    torus = trimesh.creation.torus(major_radius=2.0, minor_radius=0.5, major_sections=64, minor_sections=16)
    sk = mx.medial_axis(torus, method="flow")
    assert sk.n_cycles == 1 and len(sk.endpoints) == 0 and len(sk.junctions) == 0
    assert np.abs(np.hypot(sk.points[:, 0], sk.points[:, 1]) - 2.0).max() < 0.1


@pytest.mark.parametrize("sections", [(32, 32), (64, 32), (128, 48)])
def test_torus_skeleton_lies_on_its_core_circle(sections):
    """The flow's smoothing shrinks a curved tube; the nodes are put back on
    the centres of their rings (major radius 3, minor 1: 0.12-0.24 inside before)."""
    torus = trimesh.creation.torus(major_radius=3.0, minor_radius=1.0,
                                   major_sections=sections[0], minor_sections=sections[1])
    sk = mx.medial_axis(torus, method="flow")
    d = np.hypot(np.hypot(sk.points[:, 0], sk.points[:, 1]) - 3.0, sk.points[:, 2])
    assert np.percentile(d, 99) <= 0.1
    assert sk.n_cycles == 1
    assert np.allclose(np.median(sk.radii), 1.0, rtol=0.05)


def test_bent_tube_skeleton_follows_its_arc():
    """A half torus capped by spheres (a bent capsule), by marching cubes."""
    from skimage.measure import marching_cubes

    step = 0.1
    grid = np.arange(-4.6, 4.6 + step / 2, step)
    x, y, z = np.meshgrid(grid, grid, grid, indexing="ij")
    angle = np.arctan2(y, x)
    angle = np.where(angle < 0, np.where(x > 0, 0.0, np.pi), angle)  # below the arc: the nearer end
    cx, cy = 3.0 * np.cos(angle), 3.0 * np.sin(angle)
    sdf = np.sqrt((x - cx) ** 2 + (y - cy) ** 2 + z**2) - 1.0
    verts, faces, _, _ = marching_cubes(sdf, 0.0, spacing=(step,) * 3)
    sk = mx.medial_axis(trimesh.Trimesh(verts + grid[0], faces), method="flow")
    p = sk.points
    angle = np.arctan2(p[:, 1], p[:, 0])
    angle = np.where(angle < 0, np.where(p[:, 0] > 0, 0.0, np.pi), angle)
    arc = np.linalg.norm(p - np.column_stack([3.0 * np.cos(angle), 3.0 * np.sin(angle), np.zeros(len(p))]), axis=1)
    # a curve skeleton reaches the tips: the arc goes on along its tangent into each cap
    caps = segment_distance(p, np.array([[[3.0, 0.0, 0.0], [3.0, -1.0, 0.0]], [[-3.0, 0.0, 0.0], [-3.0, -1.0, 0.0]]]))
    d = np.minimum(arc, caps)
    assert np.percentile(d, 99) <= 0.1
    assert sk.n_components == 1 and sk.n_cycles == 0 and len(sk.endpoints) == 2


def test_two_components_give_two_skeletons():
    two = capsules_mesh([[[0, 0, 0], [2, 0, 0]], [[0, 3, 0], [2, 3, 0]]], RADIUS, pitch=0.12)
    sk = mx.medial_axis(two, method="flow")
    assert sk.n_components == 2
    assert len(sk.endpoints) == 4


# ------------------------------------------------------------ user control
def test_callback_sees_every_step(capsule):
    heard: list[Progress] = []
    sk = mx.medial_axis(capsule, method="flow", callback=heard.append)
    assert {(p.method, p.stage, p.total) for p in heard} == {("flow", "diffusion flow", 60)}  # the default max_steps
    assert [p.step for p in heard] == list(range(len(heard)))
    states: list[FlowState] = [p.state for p in heard]
    assert [s.step for s in states] == list(range(1, sk.metadata["steps"] + 1))
    assert states[-1].frozen.all()
    assert states[0].positions.shape == (len(states[0].frozen), 3)
    assert not states[0].positions.flags.writeable
    # frozen vertices never move again
    for before, after in zip(states, states[1:]):
        assert np.array_equal(before.positions[before.frozen], after.positions[before.frozen])


def test_callback_can_cancel(capsule):
    with pytest.raises(mx.Cancelled):
        mx.medial_axis(capsule, method="flow", callback=lambda progress: False)


def test_fixed_point_is_reached_and_connected(capsule):
    vertices = np.asarray(capsule.vertices)
    side = int(np.argmax(vertices[:, 1] - np.abs(vertices[:, 0] - 1.5)))  # on the side, mid-length
    sk = mx.medial_axis(capsule, method="flow", fixed_points=[side])
    assert np.linalg.norm(sk.points - vertices[side], axis=1).min() < 1e-9
    assert sk.n_components == 1
    node = int(np.argmin(np.linalg.norm(sk.points - vertices[side], axis=1)))
    assert sk.degree[node] == 1  # a branch ends at the chosen point
    assert len(sk.endpoints) == 3


def test_region_restricts_the_skeleton(capsule):
    box = np.array([[-1.0, -1.0, -1.0], [1.5, 1.0, 1.0]])
    sk = mx.medial_axis(capsule, method="flow", region=box)
    vertices = np.asarray(capsule.vertices)
    inside = np.all((vertices >= box[0]) & (vertices <= box[1]), axis=1)
    assert np.all(sk.correspondence[~inside] == -1)
    assert np.all(sk.correspondence[inside] >= 0)
    assert sk.points[:, 0].max() <= 1.5 + 1e-9
    assert segment_distance(sk.points, CAPSULE_AXIS).max() < 0.05
    assert sk.points[:, 0].max() > 1.2  # the axis runs up to the box
    assert sk.n_components == 1 and len(sk.endpoints) == 2


def test_curvature_threshold_lets_the_skeleton_reach_the_tips(capsule):
    plain = mx.medial_axis(capsule, method="flow")
    sharp = mx.medial_axis(capsule, method="flow", curvature_threshold=0.8 / RADIUS**2)
    tips = np.array([[-RADIUS, 0, 0], [3.0 + RADIUS, 0, 0]])
    reach_plain = [np.linalg.norm(plain.points - t, axis=1).min() for t in tips]
    reach_sharp = [np.linalg.norm(sharp.points - t, axis=1).min() for t in tips]
    assert max(reach_sharp) < 0.1 < min(reach_plain)
    assert len(sharp.endpoints) == 2 and sharp.n_components == 1
    # a threshold above every curvature of the surface changes nothing
    high = mx.medial_axis(capsule, method="flow", curvature_threshold=1e6)
    assert np.allclose(high.points, plain.points)


# ------------------------------------------------------------ bad input
def test_a_small_hole_is_capped_and_a_large_one_refused(capsule):
    open_mesh = trimesh.Trimesh(capsule.vertices, capsule.faces[5:], process=False)  # five faces of a cap
    with pytest.warns(mx.MedialAxisWarning, match="closed 1 holes"):
        assert len(mx.medial_axis(open_mesh, method="flow").endpoints) == 2
    half = capsule.triangles_center[:, 2] > 0  # the upper half gone: no solid to speak of
    with pytest.raises(mx.InvalidInputError, match=r"not watertight.*the largest .* across.*repair=True"):
        mx.medial_axis(trimesh.Trimesh(capsule.vertices, capsule.faces[~half], process=False), method="flow")


def test_nonmanifold_vertex_is_refused():
    a = trimesh.creation.icosphere(subdivisions=1)
    b = a.copy()
    b.apply_translation(a.vertices[0] - (-a.vertices[0]))  # touches a at one vertex
    both = trimesh.util.concatenate([a, b])
    merged = trimesh.Trimesh(both.vertices, both.faces, process=True)
    assert len(nonmanifold_vertices(len(merged.vertices), np.asarray(merged.faces))) == 1
    with pytest.raises(mx.InvalidInputError, match="non-manifold"):
        mx.medial_axis(merged, method="flow")


def test_degenerate_faces_are_dropped_and_reported(capsule):
    faces = np.vstack([capsule.faces, [[0, 0, 1]]])
    sk = mx.medial_axis(trimesh.Trimesh(capsule.vertices, faces, process=False), method="flow")
    assert any("degenerate" in r for r in sk.metadata["repairs"])
    assert len(sk.endpoints) == 2


@pytest.mark.parametrize(
    "options, match",
    [
        ({"dt": -1.0}, "dt"),
        ({"dt": float("nan")}, "dt"),
        ({"max_steps": 0}, "max_steps"),
        ({"region": [[0, 0, 0]]}, "region"),
        ({"region": [[1, 1, 1], [0, 0, 0]]}, "region"),
        ({"fixed_points": [10**9]}, "fixed_points"),
        ({"fixed_points": [0.5]}, "fixed_points"),
        ({"curvature_threshold": float("inf")}, "curvature_threshold"),
        ({"callback": 3}, "callback"),
        ({"colour": 1}, "colour"),
    ],
)
def test_bad_options_name_the_value(capsule, options, match):
    with pytest.raises(mx.InvalidInputError, match=match):
        mx.medial_axis(capsule, method="flow", **options)


def test_empty_region_is_an_empty_shape(capsule):
    with pytest.raises(mx.EmptyShapeError):
        mx.medial_axis(capsule, method="flow", region=[[10, 10, 10], [11, 11, 11]])


def test_diverging_flow_stops_with_a_message(capsule, monkeypatch):
    real = ops.pole_targets

    def exploding(points, normals, **kw):
        centres, radii = real(points, normals, **kw)
        return centres * 1e9, radii

    monkeypatch.setattr(ops, "pole_targets", exploding)
    with pytest.raises(mx.ComputationError, match="diverged at step 1"):
        mx.medial_axis(capsule, method="flow")


def _singular_from(monkeypatch, nth):
    """Make the ``nth`` (1-based) sparse factorisation of the flow raise as SuperLU does on a singular matrix."""
    import medialaxis.mesh.flow as flow_module

    real, calls = flow_module.splinalg.factorized, []

    def factorized(a):
        calls.append(a.shape)
        if len(calls) == nth:
            raise RuntimeError("Factor is exactly singular")
        return real(a)

    monkeypatch.setattr(flow_module.splinalg, "factorized", factorized)
    return calls


def test_singular_final_collapse_is_skipped(capsule, monkeypatch):
    """A singular operator in the optional last step: the step is skipped, so the answer is the one with it off.

    No natural input reaches this branch any more (the spiked box of the fuzz regressions once did).
    """
    without = mx.medial_axis(capsule, method="flow", final_collapse=0)
    calls = _singular_from(monkeypatch, 2)
    skipped = mx.medial_axis(capsule, method="flow")
    assert len(calls) == 2  # the flow's operator, then the last step's
    assert skipped.metadata["final_collapse_skipped"] == "its operator is singular"
    np.testing.assert_array_equal(skipped.points, without.points)
    np.testing.assert_array_equal(skipped.edges, without.edges)
    monkeypatch.undo()
    with_step = mx.medial_axis(capsule, method="flow")
    assert not np.array_equal(with_step.points, without.points)  # the step does move the nodes
    assert with_step.metadata["final_collapse_skipped"] is None


def test_singular_flow_operator_is_a_computation_error(capsule, monkeypatch):
    _singular_from(monkeypatch, 1)
    with pytest.raises(mx.ComputationError, match="operator of this mesh is singular"):
        mx.medial_axis(capsule, method="flow")


# ------------------------------------------------------------ invariants
def test_input_not_modified_and_result_read_only(capsule):
    vertices, faces = capsule.vertices.copy(), capsule.faces.copy()
    sk = mx.medial_axis(capsule, method="flow")
    assert np.array_equal(capsule.vertices, vertices) and np.array_equal(capsule.faces, faces)
    for arr in (sk.points, sk.radii, sk.edges, sk.correspondence):
        assert not arr.flags.writeable


@pytest.fixture(scope="module")
def small_capsule():
    return capsules_mesh([[[0, 0, 0], [2, 0, 0]]], 0.4, pitch=0.12)


@pytest.fixture(scope="module")
def small_capsule_skeleton(small_capsule):
    return mx.medial_axis(small_capsule, method="flow")


@settings(max_examples=8)
@given(
    angles=st.tuples(*[st.floats(-np.pi, np.pi)] * 3),
    shift=st.tuples(*[st.floats(-5, 5)] * 3),
    scale=st.floats(0.2, 5.0),
)
def test_similarity_equivariance(small_capsule, small_capsule_skeleton, angles, shift, scale):
    rot = Rotation.from_euler("xyz", angles).as_matrix()
    moved = trimesh.Trimesh(scale * np.asarray(small_capsule.vertices) @ rot.T + shift, small_capsule.faces)
    sk = mx.medial_axis(moved, method="flow")
    expected = scale * np.asarray(small_capsule_skeleton.points) @ rot.T + shift
    # same skeleton up to node placement: Hausdorff distance within one node spacing (radius / 2)
    d1 = np.min(np.linalg.norm(sk.points[:, None] - expected[None], axis=2), axis=1).max()
    d2 = np.min(np.linalg.norm(expected[:, None] - sk.points[None], axis=2), axis=1).max()
    assert max(d1, d2) < 0.5 * scale * 0.4
    assert len(sk.endpoints) == 2 and len(sk.junctions) == 0
    per_vertex = np.median(sk.radii[sk.correspondence])
    assert per_vertex == pytest.approx(scale * np.median(small_capsule_skeleton.radii[small_capsule_skeleton.correspondence]), rel=0.05)


# ------------------------------------------------------------ operators vs. references
def _reference_cotangent_laplacian(points, faces):
    n = len(points)
    dense = np.zeros((n, n))
    for f in faces:
        for c in range(3):
            o, a, b = f[c], f[(c + 1) % 3], f[(c + 2) % 3]
            u, v = points[a] - points[o], points[b] - points[o]
            cot = np.clip(np.dot(u, v) / np.linalg.norm(np.cross(u, v)), 0, ops.MAX_COT) / 2
            dense[a, b] -= cot
            dense[b, a] -= cot
    dense[np.diag_indices(n)] = -dense.sum(axis=1)
    return dense


def test_cotangent_laplacian_matches_loop_reference():
    mesh = trimesh.creation.icosphere(subdivisions=1)
    rng = np.random.default_rng(0)
    points = np.asarray(mesh.vertices) + 0.05 * rng.standard_normal(mesh.vertices.shape)
    got = ops.cotangent_laplacian(points, np.asarray(mesh.faces)).toarray()
    assert np.allclose(got, _reference_cotangent_laplacian(points, np.asarray(mesh.faces)))


def test_gaussian_curvature_obeys_gauss_bonnet():
    sphere = trimesh.creation.icosphere(subdivisions=2)
    torus = trimesh.creation.torus(major_radius=2.0, minor_radius=0.5)
    for mesh, chi in ((sphere, 2), (torus, 0)):
        p, f = np.asarray(mesh.vertices), np.asarray(mesh.faces)
        total = (ops.gaussian_curvature(p, f) * ops.vertex_areas(p, f)).sum()
        assert total == pytest.approx(2 * np.pi * chi, abs=1e-8)


def test_medial_poles_of_a_sphere_are_its_centre():
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=2.0)
    p, f = np.asarray(sphere.vertices), np.asarray(sphere.faces)
    centres, radii = ops.medial_poles(p, ops.vertex_normals(p, f), max_radius=10.0, ignore=0.5)
    assert np.median(radii) == pytest.approx(2.0, abs=0.1)
    assert np.percentile(np.linalg.norm(centres, axis=1), 90) < 0.2


def test_handle_count_is_the_genus():
    from medialaxis.mesh.skeleton.contract_graph import handle_count

    torus = trimesh.creation.torus(major_radius=2.0, minor_radius=0.5)
    sphere = trimesh.creation.icosphere(subdivisions=1)
    both = trimesh.util.concatenate([torus, sphere])
    tube = trimesh.creation.cylinder(radius=1.0, height=2.0, sections=16)
    open_tube = np.asarray(tube.faces)[np.abs(np.asarray(tube.triangles_center)[:, 2]) < 0.99]  # no caps
    assert handle_count(len(torus.vertices), np.asarray(torus.faces)) == 1
    assert handle_count(len(sphere.vertices), np.asarray(sphere.faces)) == 0
    assert handle_count(len(both.vertices), np.asarray(both.faces)) == 1
    assert handle_count(len(tube.vertices), open_tube) == 0


@pytest.mark.parametrize("pitch", [0.07, 0.12])
def test_tripod_targets_hold_at_other_resolutions(pitch):
    mesh = tripod_mesh(radius=RADIUS, arm=3.0, pitch=pitch)
    sk = mx.medial_axis(mesh, method="flow")
    d = segment_distance(sk.points, tripod_segments(3.0))
    assert np.percentile(d, 99) <= 0.1 and d.mean() <= 0.05
    assert len(sk.endpoints) == 3 and len(sk.junctions) == 1
    for tip in tripod_segments(3.0)[:, 1]:
        assert np.linalg.norm(sk.points - tip, axis=1).min() <= RADIUS
    assert abs(np.median(sk.radii) - RADIUS) <= 0.1


def test_radius_is_the_distance_to_the_surface(tripod, tripod_skeleton):
    # independent reference: trimesh's exact closest point on every triangle
    triangles = np.asarray(tripod.triangles)
    nodes = tripod_skeleton.points
    closest = trimesh.triangles.closest_point(
        np.tile(triangles, (len(nodes), 1, 1)), np.repeat(nodes, len(triangles), axis=0)
    )
    distance = np.linalg.norm(closest - np.repeat(nodes, len(triangles), axis=0), axis=1)
    distance = distance.reshape(len(nodes), len(triangles)).min(axis=1)
    arms = segment_distance(nodes, np.zeros((1, 2, 3))) > 1.0  # away from the hub
    assert np.median(np.abs(distance[arms] - tripod_skeleton.radii[arms])) < 0.05
    assert distance.min() > 0.3  # no node near the surface


def test_small_hole_is_closed_with_a_warning(capsule):
    holed = trimesh.Trimesh(capsule.vertices, capsule.faces[1:], process=False)
    with pytest.warns(mx.MedialAxisWarning, match="not watertight: closed 1 holes"):
        sk = mx.medial_axis(holed, method="flow")
    assert any("closed 1 holes" in r for r in sk.metadata["repairs"])
    assert len(sk.endpoints) == 2


def test_triangle_soup_input_maps_every_input_vertex(capsule):
    soup = trimesh.Trimesh(
        np.asarray(capsule.triangles).reshape(-1, 3), np.arange(3 * len(capsule.faces)).reshape(-1, 3), process=False
    )
    sk = mx.medial_axis(
        soup, method="flow", dt=None, fixed_points=None, region=None, curvature_threshold=None, callback=None,
        max_steps=None,
    )
    assert sk.correspondence.shape == (len(soup.vertices),)
    # copies of one point share a node
    same = np.all(np.asarray(soup.vertices)[:, None] == np.asarray(soup.vertices)[None, :60], axis=2)
    rows, cols = np.nonzero(same)
    assert np.array_equal(sk.correspondence[rows], sk.correspondence[cols])
    assert len(sk.endpoints) == 2


def test_curvature_tips_of_a_noisy_tripod(tripod):
    # marching-cubes curvature is noisy vertex to vertex; the averaged
    # curvature finds the three arm caps and the dome on top of the hub
    sk = mx.medial_axis(tripod, method="flow", curvature_threshold=0.8 / RADIUS**2)
    fixed = np.asarray(tripod.vertices)[sk.metadata["fixed_vertices"]]
    assert len(fixed) == 4
    surface_tips = [t * (1 + RADIUS / np.linalg.norm(t)) for t in tripod_segments(3.0)[:, 1]]
    for tip in surface_tips:
        assert np.linalg.norm(fixed - tip, axis=1).min() < 0.15
    assert fixed[:, 2].max() > RADIUS * 0.9  # the hub's top
    assert len(sk.endpoints) == 4 and len(sk.junctions) == 1


@pytest.mark.parametrize("make", [lambda: trimesh.creation.box(extents=(4, 1, 0.5)),
                                  lambda: trimesh.creation.torus(major_radius=2.0, minor_radius=0.5,
                                                                 major_sections=12, minor_sections=6),
                                  lambda: trimesh.creation.icosphere(subdivisions=1)])
def test_splitting_long_edges_keeps_the_surface(make):
    from medialaxis.mesh.skeleton.refine import split_long_edges

    mesh = make()
    longest = mesh.edges_unique_length.max()
    points, faces = split_long_edges(mesh.vertices, mesh.faces, 0.3 * longest)
    fine = trimesh.Trimesh(points, faces, process=False)
    assert fine.is_watertight and fine.is_winding_consistent
    assert fine.euler_number == mesh.euler_number  # same genus, computed by trimesh
    assert np.isclose(fine.volume, mesh.volume)  # midpoints of flat faces: the same solid
    assert fine.edges_unique_length.max() <= 0.3 * longest + 1e-12
    assert np.array_equal(points[: len(mesh.vertices)], mesh.vertices)  # input vertices keep their index
