"""Meshes that cross themselves or whose shells overlap or nest: the solid where the winding number is >= 1/2.

Truth comes from outside the code under test: manifold3d's boolean union of
the same parts (volume, Euler characteristic), trimesh's signed distance to
that union (radii), and the mesh's own Euler characteristic.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import medialaxis as mx

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("manifold3d")

from medialaxis.mesh.solid._winding_kernels import winding_numbers, winding_numbers_reference  # noqa: E402
from medialaxis.mesh.solid.arrangement import solid_surface  # noqa: E402
from medialaxis.mesh.solid.inputs import load_mesh  # noqa: E402


def _parts(name: str) -> list:
    if name == "boxes":  # overlapping, no face in a common plane
        a, b = trimesh.creation.box(), trimesh.creation.box()
        b.apply_translation([0.5, 0.3, 0.2])
        return [a, b]
    if name == "cross":  # top and bottom faces in common planes, crossing edges meet exactly
        return [trimesh.creation.box(extents=(2, 1, 1)), trimesh.creation.box(extents=(1, 2, 1))]
    if name == "spheres":  # vertices of one lie exactly on the other
        a, b = trimesh.creation.icosphere(3), trimesh.creation.icosphere(3)
        b.apply_translation([1.0, 0, 0])
        return [a, b]
    if name == "capsules":  # three crossing cylinders, long CAD faces
        caps = [trimesh.creation.capsule(height=2, radius=0.4, count=[16, 8]) for _ in range(3)]
        caps[1].apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [1, 0, 0]))
        caps[2].apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
        return caps
    if name == "nested":  # a sphere inside a sphere, both outward: the inner one is inside the solid
        return [trimesh.creation.icosphere(3, 1.0), trimesh.creation.icosphere(2, 0.5)]
    if name == "ring":  # a box through a torus's hole, touching nothing: two shells, one tunnel
        torus = trimesh.creation.torus(1.0, 0.3, major_sections=32, minor_sections=12)
        return [torus, trimesh.creation.box(extents=(0.5, 0.5, 1.5))]
    if name == "three_boxes":  # on one grid: curves of the cut meet at points of edges and diagonals; two touch face to face
        return [_box([0, 0, 0], [2, 2, 2]), _box([1, 1, 1], [3, 3, 3]), _box([1, -1, 1], [3, 1, 3])]
    if name == "stacked":  # crossing boxes with coincident faces in two planes
        return [_box([0, 0, 0], [3, 1, 1]), _box([1, 0, 0], [2, 1, 3]), _box([1, -1, 0], [2, 2, 1])]
    if name == "diamond":  # a box's vertical edges lie in a thin diamond's side faces: cuts end where edges cross
        square = np.array([[2, 0, 0], [0, 2, 0], [-2, 0, 0], [0, -2, 0]], float)
        diamond = trimesh.convex.convex_hull(np.vstack([square - [0, 0, 0.5], square + [0, 0, 0.5]]))
        return [_box([-1, -1, -1], [1, 1, 1]), diamond]
    if name == "through_vertex":  # a tetrahedron's faces pass exactly through a box's vertices
        tet = trimesh.Trimesh([[1.5, 1.5, 1.5], [-2.5, 1.5, 1.5], [1.5, -2.5, 1.5], [1.5, 1.5, -2.5]],
                              [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
        tet.fix_normals()
        return [_box([-1, -1, -1], [1, 1, 1]), tet]
    if name == "touching":  # a box on another's face: the wall between them is left out
        return [_box([0, 0, 0], [1, 1, 1]), _box([1, 0.25, 0.25], [2, 0.75, 0.75])]
    if name == "tilted":  # the same box turned by 1e-3: sheets cross at a small angle
        a, b = _box([-1, -1, -1], [1, 1, 1]), _box([-1, -1, -1], [1, 1, 1])
        b.apply_transform(trimesh.transformations.rotation_matrix(1e-3, [1, 0, 0]))
        b.apply_translation([0.5, 0, 0])
        return [a, b]
    raise KeyError(name)


def _box(lo: list, hi: list):
    return trimesh.creation.box(bounds=np.array([lo, hi], float))


def test_winding_kernel_matches_its_reference():
    rng = np.random.default_rng(3)
    sphere = trimesh.creation.icosphere(2)
    tri = np.ascontiguousarray(sphere.triangles)
    points = rng.uniform(-1.5, 1.5, size=(300, 3))
    fast, slow = winding_numbers(points, tri), winding_numbers_reference(points, tri)
    assert np.allclose(fast, slow, atol=1e-12)
    inside = sphere.contains(points)  # trimesh's ray test: an outside truth
    assert np.array_equal(fast > 0.5, inside)
    assert np.allclose(fast[inside], 1.0, atol=1e-9) and np.allclose(fast[~inside], 0.0, atol=1e-9)


@pytest.mark.parametrize("name", ["boxes", "cross", "spheres", "capsules", "nested", "ring", "three_boxes", "stacked",
                                  "diamond", "through_vertex", "touching", "tilted"])
def test_the_solid_surface_is_the_union_manifold3d_computes(name):
    parts = _parts(name)
    soup = trimesh.util.concatenate(parts)
    union = trimesh.boolean.union(parts, engine="manifold")
    s = solid_surface(soup.vertices, soup.faces)
    solid = trimesh.Trimesh(s.vertices, s.faces, process=False)
    assert solid.is_watertight and solid.is_winding_consistent
    assert solid.volume == pytest.approx(union.volume, rel=1e-6)  # manifold3d computes in float32
    assert solid.euler_number == union.euler_number
    assert len(solid.split(only_watertight=False)) == len(union.split(only_watertight=False))
    # the solid's surface lies on the union's surface
    assert np.abs(trimesh.proximity.signed_distance(union, solid.vertices)).max() < 1e-6


@pytest.mark.parametrize("name", ["spheres", "capsules", "nested", "ring", "tilted"])
def test_the_fast_winding_tree_gives_the_same_solid(name, monkeypatch):
    # many patches on a large mesh are judged through the tree (arrangement.EXACT_TERMS); forced here
    import medialaxis.mesh.solid.arrangement as arrangement

    parts = _parts(name)
    soup = trimesh.util.concatenate(parts)
    exact = solid_surface(soup.vertices, soup.faces)
    monkeypatch.setattr(arrangement, "EXACT_TERMS", 0)
    s = solid_surface(soup.vertices, soup.faces)
    assert np.array_equal(s.faces, exact.faces) and np.array_equal(s.vertices, exact.vertices)
    union = trimesh.boolean.union(parts, engine="manifold")
    assert trimesh.Trimesh(s.vertices, s.faces).volume == pytest.approx(union.volume, rel=1e-6)


def test_both_methods_take_the_solid_of_overlapping_parts_and_say_so():
    parts = _parts("cross")
    soup = trimesh.util.concatenate(parts)
    union = trimesh.boolean.union(parts, engine="manifold")
    for method in ("voronoi", "flow"):
        with pytest.warns(mx.MedialAxisWarning, match=r"passes through itself \(12 pairs of faces cross\).*winding number"):
            ma = mx.medial_axis(soup, method=method)
        assert ma.betti == (1, 0, 0)
        assert any("solid by winding number" in r for r in ma.metadata["repairs"])
        inside = trimesh.proximity.signed_distance(union, ma.points)
        assert inside.min() > 0  # every node inside the union
        if method == "voronoi":
            assert ma.metadata["defects"]["crossing_face_pairs"] == 12
            # radii are distances to the union's surface, not to the faces inside it
            assert np.abs(inside - ma.radii).max() < 1e-6
            assert ma.radii.max() == pytest.approx(0.5, abs=0.01)  # the centre of the cross: half the height


def test_the_voronoi_result_of_crossing_capsules_matches_that_of_their_union():
    from scipy.spatial import cKDTree

    parts = _parts("capsules")
    soup = trimesh.util.concatenate(parts)
    union = trimesh.boolean.union(parts, engine="manifold")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mx.MedialAxisWarning)
        ma = mx.medial_axis(soup, samples=20_000, compact=False)
    ref = mx.medial_axis(union, samples=20_000, compact=False)
    assert ma.betti == ref.betti == (1, 0, 0)
    # the full complex's closest-point search may stop at a face a hair farther (module docstring):
    # 1.3e-4 at most here, against a tenth or more for a ball reaching a face inside the union
    assert np.abs(trimesh.proximity.signed_distance(union, ma.points) - ma.radii).max() < 5e-4
    assert ma.radii.max() == pytest.approx(ref.radii.max(), rel=0.02)
    # the same medial surface, up to the sampling (each from its own triangulation of the surface):
    # 99% of either's Voronoi vertices within an eighth of the capsules' radius (0.4) of the other's
    assert np.percentile(cKDTree(ref.points).query(ma.points)[0], 99) < 0.05
    assert np.percentile(cKDTree(ma.points).query(ref.points)[0], 99) < 0.05


def test_a_sphere_pulled_through_itself_gets_the_solid_its_winding_number_defines():
    sphere = trimesh.creation.icosphere(2)
    vertices = sphere.vertices.copy()
    vertices[np.argmax(vertices[:, 2])] = [0.05, 0.03, -1.5]  # the top pulled out through the bottom
    folded = trimesh.Trimesh(vertices, sphere.faces, process=False)
    assert folded.is_watertight and folded.is_winding_consistent  # only the geometry is wrong
    s = solid_surface(folded.vertices, folded.faces)
    solid = trimesh.Trimesh(s.vertices, s.faces, process=False)
    assert solid.is_watertight and solid.euler_number == 0  # the cone drilled a tunnel: genus 1
    # the volume is the measure of {w >= 1/2}: checked on a grid with the reference winding number
    g = np.linspace(-1.6, 1.1, 28)
    grid = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    w = winding_numbers_reference(grid, np.asarray(folded.triangles))
    assert solid.contains(grid[np.abs(w - 0.5) > 0.2]).tolist() == (w[np.abs(w - 0.5) > 0.2] > 0.5).tolist()
    for method in ("voronoi", "flow"):
        with pytest.warns(mx.MedialAxisWarning, match="passes through itself"):
            ma = mx.medial_axis(folded, method=method)
        assert ma.betti[:2] == (1, 1)


def test_the_same_result_with_or_without_a_second_thread(monkeypatch):
    from medialaxis import _jit as jit

    soup = trimesh.util.concatenate(_parts("boxes"))
    results = []
    for concurrent in (jit.concurrent_kernels(), False):
        monkeypatch.setattr(jit, "concurrent_kernels", lambda c=concurrent: c)
        with pytest.warns(mx.MedialAxisWarning, match="winding number"):
            results.append(mx.medial_axis(soup, method="voronoi", samples=5000))
    assert np.array_equal(results[0].points, results[1].points)
    assert results[0].betti == (1, 0, 0)


def test_a_triangle_soup_with_a_hole_is_welded_before_its_hole_is_capped():
    sphere = trimesh.creation.icosphere(3)
    keep = np.arange(1, len(sphere.faces))  # one face missing
    soup = trimesh.Trimesh(sphere.triangles[keep].reshape(-1, 3), np.arange(3 * len(keep)).reshape(-1, 3), process=False)
    with pytest.warns(mx.MedialAxisWarning, match="closed 1 holes"):
        ma = mx.medial_axis(soup, method="flow")
    assert ma.betti[:2] == (1, 0)
    assert any("welded" in r for r in ma.metadata["repairs"])


def test_solids_touching_along_an_edge_are_kept_apart_as_manifold3d_keeps_them():
    from medialaxis.mesh.solid.inputs import load_mesh

    parts = [_box([0, 0, 0], [1, 1, 1]), _box([1, 1, 0], [2, 2, 1])]
    mesh = trimesh.util.concatenate(parts)
    mesh.merge_vertices()  # one edge of four faces
    union = trimesh.boolean.union(parts, engine="manifold")
    with pytest.warns(mx.MedialAxisWarning, match="1 edges of more than two faces"):
        solid = load_mesh(mesh).mesh
    assert solid.is_watertight and solid.is_winding_consistent
    assert solid.volume == pytest.approx(union.volume, rel=1e-9)
    assert solid.euler_number == union.euler_number == 4
    assert len(solid.split(only_watertight=False)) == len(union.split(only_watertight=False)) == 2


def test_holes_touching_at_a_vertex_are_capped_each_on_its_own():
    from medialaxis.mesh.solid.inputs import load_mesh

    sphere = trimesh.creation.icosphere(3)
    v = sphere.faces[0, 0]
    around = np.flatnonzero((sphere.faces == v).any(axis=1))
    # two faces at v that share no edge: two one-face holes meeting at v
    second = next(g for g in around[1:] if len(set(sphere.faces[g]) & set(sphere.faces[around[0]])) == 1)
    gone = [around[0], second]
    holed = trimesh.Trimesh(sphere.vertices, np.delete(sphere.faces, gone, axis=0), process=False)
    with pytest.warns(mx.MedialAxisWarning, match="closed 2 holes"):
        solid = load_mesh(holed).mesh
    assert solid.is_watertight and solid.is_winding_consistent and solid.euler_number == 2
    assert solid.volume == pytest.approx(sphere.volume, rel=1e-12)


def test_a_flat_shell_bounds_no_solid_and_is_refused_with_the_reason():
    from medialaxis.errors import InvalidInputError

    tri = trimesh.creation.box().triangles[:1].reshape(-1, 3)
    flat = trimesh.Trimesh(np.vstack([tri, tri]), [[0, 1, 2], [3, 5, 4]], process=False)  # a face and its reverse
    with pytest.raises(InvalidInputError, match="bounds no solid"):
        solid_surface(flat.vertices, flat.faces)


def _open_end(part, top: bool):
    """``part`` without the faces of its top (or bottom) disc: a rim left open there."""
    z = part.triangles_center[:, 2]
    end = np.isclose(z, z.max() if top else z.min()) & np.isclose(np.abs(part.face_normals[:, 2]), 1.0)
    return trimesh.Trimesh(part.vertices, part.faces[~end])


@pytest.mark.parametrize("stl", [False, True])
def test_a_lid_set_in_a_pots_opening_closes_it_as_manifold3d_unites_them(stl, tmp_path):
    # as the Utah teapot: the pot open at the top, the lid open at the bottom, both rims in one plane and
    # the lid's inside the pot's; their caps would overlap in that plane with opposite orientations
    pot = trimesh.creation.cylinder(radius=1.0, height=2.0, sections=32)  # z from -1 to 1
    lid = trimesh.creation.cylinder(radius=0.8, height=0.5, sections=24)
    lid.apply_translation([0, 0, 1.25])  # z from 1 to 1.5
    union = trimesh.boolean.union([pot, lid], engine="manifold")
    both = trimesh.util.concatenate([_open_end(pot, top=True), _open_end(lid, top=False)])
    if stl:  # turned, in float32 coordinates as every STL has: the rims coplanar to float32's accuracy only
        turn = trimesh.transformations.rotation_matrix(0.7, [1, 2, 0])
        for part in (pot, lid, both):
            part.apply_transform(turn)
        both.export(tmp_path / "pot.stl")
        both = trimesh.load(tmp_path / "pot.stl")
        union = trimesh.boolean.union([pot, lid], engine="manifold")
    assert not both.is_watertight
    with pytest.warns(mx.MedialAxisWarning, match="not watertight: closed 2 holes"):
        solid = load_mesh(both).mesh
    assert solid.is_watertight and solid.is_winding_consistent
    assert solid.volume == pytest.approx(union.volume, rel=1e-6)
    assert solid.euler_number == union.euler_number == 2
    assert np.abs(trimesh.proximity.signed_distance(union, solid.vertices)).max() < 1e-6
    if stl:
        return
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mx.MedialAxisWarning)
        assert mx.medial_axis(both, samples=8000).betti == (1, 0, 0)
