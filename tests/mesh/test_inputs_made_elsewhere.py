"""Meshes made by other tools: boolean unions and differences (manifold3d), marching cubes, STL soups.

The loader keeps a closed, consistently oriented 2-manifold as given
(coincident but distinct vertices included) and repairs only what needs it.
Truth comes from the input meshes themselves (their Euler characteristic and
components, computed by trimesh), not from medialaxis.
"""

from __future__ import annotations

import warnings

import networkx as nx
import numpy as np
import pytest
from mesh_balls import interpolated_balls

import medialaxis as mx
from medialaxis.mesh.solid.inputs import load_mesh

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("manifold3d")


def _genus(mesh) -> int:
    """Genus of a closed connected surface from its own Euler characteristic."""
    return (2 - int(mesh.euler_number)) // 2


def _cycles(ma) -> int:
    return len(nx.cycle_basis(ma.to_networkx()))


def test_union_touching_along_an_edge_is_taken_as_given():
    a = trimesh.creation.box(bounds=[[0, 0, 0], [1, 1, 1]])
    b = trimesh.creation.box(bounds=[[1, 1, 0], [2, 2, 1]])
    union = trimesh.boolean.union([a, b], engine="manifold")
    assert union.is_watertight
    coincident = len(union.vertices) - len(np.unique(union.vertices.round(12), axis=0))
    assert coincident > 0  # the two sides of the shared edge are kept apart
    checked = load_mesh(union)
    assert checked.repairs == () and len(checked.mesh.vertices) == len(union.vertices)
    flow = mx.medial_axis(union, method="flow")
    assert flow.n_components == 2 and len(flow.extras["correspondence"]) == len(union.vertices)
    vor = mx.medial_axis(union, method="voronoi", samples=20_000)
    assert vor.n_components == 2 and vor.metadata["repairs"] == []


def test_union_of_three_capsules_has_one_tree_skeleton():
    caps = []
    for axis in ([1, 0, 0], [0, 1, 0], [0, 0, 1]):
        cap = trimesh.creation.capsule(height=3.0, radius=0.5, count=[16, 16])
        rot = trimesh.geometry.align_vectors([0, 0, 1], axis)
        cap.apply_transform(rot)
        caps.append(cap)
    union = trimesh.boolean.union(caps, engine="manifold")
    assert union.is_watertight and union.body_count == 1
    sk = mx.medial_axis(union, method="flow")
    assert sk.n_components == 1 and _cycles(sk) == _genus(union) == 0


def _drilled_block():
    block = trimesh.creation.box(extents=(4, 4, 1.5))
    drill = trimesh.creation.cylinder(radius=0.8, height=3, sections=32)
    return trimesh.boolean.difference([block, drill], engine="manifold")


def test_difference_with_a_through_hole_is_accepted_and_keeps_its_genus_when_finely_meshed():
    part = _drilled_block()
    assert part.is_watertight and _genus(part) == 1
    assert load_mesh(part).repairs == ()
    fine = part.subdivide_to_size(0.25)  # a soup: welded by the loader
    assert _genus(trimesh.Trimesh(fine.vertices, fine.faces)) == 1
    sk = mx.medial_axis(fine, method="flow")
    assert sk.n_components == 1 and _cycles(sk) == 1


def test_flow_keeps_the_genus_of_a_coarse_cad_mesh():
    """72 vertices, long thin triangles: the surface is refined before the flow."""
    part = _drilled_block()
    sk = mx.medial_axis(part, method="flow")
    assert _cycles(sk) == 1 and sk.n_components == 1
    assert sk.metadata["refined_vertices"] > 0
    assert len(sk.extras["correspondence"]) == len(part.vertices)
    # the skeleton stays inside the block, round the hole
    assert np.all(np.abs(sk.points[:, :2]) <= 2.0) and np.all(np.abs(sk.points[:, 2]) <= 0.75)
    assert np.all(np.hypot(sk.points[:, 0], sk.points[:, 1]) >= 0.8)


def test_marching_cubes_torus():
    from skimage.measure import marching_cubes

    grid = np.linspace(-4.5, 4.5, 61)
    x, y, z = np.meshgrid(grid, grid, grid, indexing="ij")
    sdf = np.hypot(np.hypot(x, y) - 3.0, z) - 1.0
    verts, faces, _, _ = marching_cubes(sdf, 0.0, spacing=(grid[1] - grid[0],) * 3)
    mesh = trimesh.Trimesh(verts, faces, process=False)
    assert mesh.is_watertight and _genus(mesh) == 1
    sk = mx.medial_axis(mesh, method="flow")
    assert sk.n_components == 1 and _cycles(sk) == 1
    # the grid starts at the array origin: the torus's centre is at 4.5
    p = sk.points - 4.5
    d = np.hypot(np.hypot(p[:, 0], p[:, 1]) - 3.0, p[:, 2])
    assert np.percentile(d, 99) <= 0.1


def test_triangle_soup_is_welded_and_says_so(tmp_path):
    path = tmp_path / "part.stl"
    trimesh.creation.icosphere(2).export(path)  # STL: every face has its own three vertices
    checked = load_mesh(path)
    assert any("welded" in r for r in checked.repairs)
    assert checked.mesh.is_watertight and checked.mesh.euler_number == 2


def test_duplicated_vertices_of_a_closed_mesh():
    sphere = trimesh.creation.icosphere(2)
    # every vertex used by its own copy in half of the faces: closed only once welded
    n = len(sphere.vertices)
    vertices = np.vstack([sphere.vertices, sphere.vertices])
    faces = sphere.faces.copy()
    faces[::2] += n
    soup = trimesh.Trimesh(vertices, faces, process=False)
    checked = load_mesh(soup)
    assert checked.mesh.euler_number == 2 and any("welded" in r for r in checked.repairs)
    assert mx.medial_axis(soup, method="flow").n_components == 1


def test_open_meshes_bounding_no_solid_are_refused_with_counts():
    bowl = trimesh.creation.icosphere(2).slice_plane([0, 0, 0], [0, 0, -1])  # half a sphere, open at the rim
    bowl.merge_vertices()
    rim = len(trimesh.grouping.group_rows(bowl.edges_sorted, require_count=1))
    with pytest.raises(mx.InvalidInputError, match=rf"bounds no solid: its 1 holes \({rim} open edges"):
        load_mesh(bowl)


def test_solids_touching_along_an_edge_are_taken_apart_not_refused():
    # two unit boxes sharing the edge x = y = 1 by index: that edge has four faces
    a = trimesh.creation.box(bounds=[[0, 0, 0], [1, 1, 1]])
    b = trimesh.creation.box(bounds=[[1, 1, 0], [2, 2, 1]])
    both = trimesh.util.concatenate([a, b])
    both.merge_vertices()
    edges, counts = np.unique(np.sort(both.edges, axis=1), axis=0, return_counts=True)
    assert (counts == 4).sum() == 1  # the input really has one edge of four faces
    with pytest.warns(mx.MedialAxisWarning, match="edges of more than two faces"):
        solid = load_mesh(both).mesh
    assert solid.is_watertight and solid.is_winding_consistent
    assert len(solid.split(only_watertight=False)) == 2
    assert solid.volume == pytest.approx(2.0, abs=1e-12)  # exact: two unit boxes
    assert solid.euler_number == 4  # two spheres
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mx.MedialAxisWarning)
        assert mx.medial_axis(both).betti == (2, 0, 0)
        assert mx.medial_axis(both, method="flow").betti == (2, 0, 0)


def _winding_numbers(mesh, points):
    """Generalized winding number of a closed mesh at each point (Van Oosterom and Strackee solid angles)."""
    tri = np.asarray(mesh.triangles)
    out = np.zeros(len(points))
    for k in range(0, len(points), 200):
        a, b, c = (tri[None, :, i] - points[k : k + 200, None] for i in range(3))
        la, lb, lc = (np.linalg.norm(v, axis=2) for v in (a, b, c))
        det = np.einsum("pfi,pfi->pf", a, np.cross(b, c))
        den = la * lb * lc + np.einsum("pfi,pfi->pf", a, b) * lc + np.einsum("pfi,pfi->pf", b, c) * la
        den += np.einsum("pfi,pfi->pf", c, a) * lb
        out[k : k + 200] = np.arctan2(det, den).sum(axis=1) / (2 * np.pi)
    return out


def _hand():
    """A unit ball with four thin fingers, as one boolean union (co-spherical samples on every part)."""
    parts = [trimesh.creation.icosphere(subdivisions=4, radius=1.0)]
    for d in ([0, 0, 1], [1, 0, 0], [0, 1, 0], [-1, 0, 0]):
        finger = trimesh.creation.capsule(height=2.0, radius=0.1, count=[24, 24])
        finger.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], d))
        finger.apply_translation(1.7 * np.asarray(d, float))
        parts.append(finger)
    return trimesh.boolean.union(parts, engine="manifold")


@pytest.mark.slow
def test_every_medial_ball_of_a_union_lies_inside_it():
    # A faster Delaunay setting once signed a far circumcentre of a near-flat tetrahedron
    # inside: a 'medial ball' of radius 213 on this 6-unit shape.
    hand = _hand()
    compact = mx.medial_axis(hand, method="voronoi")
    ma = compact.raw  # the full complex
    assert ma.radii.max() <= 1.0 + 1e-3  # the body ball is the largest inside (truth: the construction)
    check = np.union1d(np.argsort(ma.radii)[-500:], np.random.default_rng(0).choice(len(ma.points), 1500, replace=False))
    assert (_winding_numbers(hand, ma.points[check]) > 0.5).all()  # inside, by the mesh's own solid angles
    assert (_winding_numbers(hand, compact.points) > 0.5).all()
    assert ma.betti == compact.betti == (1, _genus(hand), 0) == (1, 0, 0)
    # the balls interpolated over the compact complex stay inside too, within the sampling error
    # (trimesh's signed distance, positive inside): an edge from the body's centre straight to a
    # finger's root once made balls bulging 0.38 out of that finger
    centres, radii = interpolated_balls(compact)
    depth = trimesh.proximity.signed_distance(hand, centres)
    assert (radii - depth).max() <= 2 * compact.metadata["epsilon"]


@pytest.mark.slow
def test_fine_uv_ellipsoid_has_the_segment_axis_and_no_voids():
    # trimesh's uv sphere, scaled 3:1:1: 73k vertices, the rings near the poles nearly flat. Flat
    # tetrahedra of three nearly collinear cap samples once covered samples there: the full complex
    # had 6 voids and far circumcentres (radius 31), and the default call took minutes.
    mesh = trimesh.creation.uv_sphere(radius=1.0, count=[192, 192])
    mesh.apply_scale([3.0, 1.0, 1.0])
    compact = mx.medial_axis(mesh, method="voronoi")
    full = compact.raw
    # truth: a solid ellipsoid is contractible; its largest inscribed ball has the smallest semi-axis
    assert full.betti == compact.betti == (1, 0, 0)
    assert full.radii.max() <= 1.0 + 1e-9
    assert full.metadata["n_outside_points"] == 0
    # its medial axis is the segment |x| <= a - b^2 / a = 8/3 on the long axis, ball radii
    # sqrt(1 - x^2 / 8) (normal of the ellipse through (x, 0)); the tip of the sampled axis ends
    # where the balls get thinner than lambda
    eps = compact.metadata["epsilon"]
    x = compact.points[:, 0]
    assert np.abs(compact.points[:, 1:]).max() <= eps
    assert 8.0 / 3.0 - 3 * eps < np.abs(x).max() <= 8.0 / 3.0
    assert np.abs(compact.radii - np.sqrt(1.0 - x**2 / 8.0)).max() <= eps
