"""Zero-area faces never open a closed mesh (issue 31, point 2).

A manifold3d union of capsules and a float32 STL with a T-junction closed by a
flat triangle are closed surfaces (every edge shared by two faces) with
zero-area faces; before, the loader dropped those faces and refused the mesh
as open ("3 open edges"), or welded what the union keeps apart and found
crossing faces.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.errors import MedialAxisWarning
from medialaxis.mesh.solid.degenerate import coordinate_accuracy, degenerate_faces, remove_degenerate_faces
from medialaxis.mesh.solid.inputs import load_mesh

trimesh = pytest.importorskip("trimesh")
manifold3d = pytest.importorskip("manifold3d")

X, Z = [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]


def _capsule_union(specs, count) -> trimesh.Trimesh:
    """Union (manifold3d) of ``trimesh.creation.capsule``s, each ``(axis, angle, position)``."""
    union = None
    for axis, angle, position in specs:
        capsule = trimesh.creation.capsule(height=1.0, radius=0.25, count=count)
        move = trimesh.transformations.rotation_matrix(angle, axis)
        move[:3, 3] = position
        capsule.apply_transform(move)
        solid = manifold3d.Manifold(manifold3d.Mesh(vert_properties=np.asarray(capsule.vertices, np.float32),
                                                    tri_verts=np.asarray(capsule.faces, np.uint32)))
        union = solid if union is None else union + solid
    out = union.to_mesh()
    return trimesh.Trimesh(np.asarray(out.vert_properties)[:, :3], np.asarray(out.tri_verts), process=False)


def _small_union() -> trimesh.Trimesh:
    """448 faces, one of zero area (refused before as "3 open edges")."""
    return _capsule_union([(X, 0.0, (0, 0, 0)), (X, 0.0, (0.3, 0, 0.25)), (Z, 0.0, (0.15, 0.3, -0.25))], [8, 8])


def _fine_union() -> trimesh.Trimesh:
    """4984 faces, six of zero area (refused before as crossing itself)."""
    return _capsule_union([(X, 0.0, (0, 0, 0)), (X, 0.0, (0.25, 0, 0.5)), (Z, 0.0, (0.125, 0.25, -0.5))], [32, 32])


def _closed_with_zero_area(mesh: trimesh.Trimesh) -> None:
    edge_use = np.bincount(mesh.edges_unique_inverse, minlength=len(mesh.edges_unique))
    assert (edge_use == 2).all()  # every edge shared by two faces: closed
    assert (mesh.area_faces == 0).any()


@pytest.mark.parametrize("make, zero", [(_small_union, 1), (_fine_union, 6)])
def test_a_capsule_union_with_zero_area_faces_loads_closed(make, zero):
    mesh = make()
    _closed_with_zero_area(mesh)
    assert int((mesh.area_faces == 0).sum()) == zero
    for repair in (False, True):
        with pytest.warns(MedialAxisWarning, match="zero-area faces"):
            loaded = load_mesh(mesh, repair=repair)
        assert loaded.mesh.is_watertight and loaded.mesh.is_winding_consistent
        assert any("zero-area faces" in r and "collapsed" in r for r in loaded.repairs)
        assert abs(loaded.volume - mesh.volume) <= 1e-6 * mesh.volume  # the same solid
        assert not len(degenerate_faces(loaded.mesh.vertices, loaded.mesh.faces, coordinate_accuracy(mesh.vertices)))


def test_the_medial_surface_of_a_capsule_union_has_its_topology_and_radii():
    mesh = _small_union()
    with pytest.warns(MedialAxisWarning):
        ma = mx.medial_axis(mesh)
    assert ma.betti == (1, 0, 0)  # one component, no tunnel, no void: a ball's
    assert any("zero-area" in r for r in ma.metadata["repairs"])
    # radii are distances to the surface (trimesh, on the input less its zero-area faces, which add no point)
    surface = trimesh.Trimesh(mesh.vertices, mesh.faces[mesh.area_faces > 0], process=False)
    _, distance, _ = trimesh.proximity.closest_point(surface, ma.points)
    assert np.abs(distance - ma.radii).max() < 1e-6
    assert mesh.contains(ma.points).all()


@pytest.mark.parametrize("make", [_small_union, _fine_union])
def test_the_flow_skeleton_of_a_capsule_union_is_one_tree(make):
    mesh = make()
    for repair in (False, True):
        with pytest.warns(MedialAxisWarning):
            sk = mx.medial_axis(mesh, method="flow", repair=repair)
        assert sk.betti == (1, 0, 0)
        assert len(sk.edges) == len(sk.points) - 1  # connected and no cycle: a tree
    if make is _small_union:
        assert (np.bincount(sk.edges.ravel()) == 1).sum() == 3  # three arms


def _box_with_t_junction() -> trimesh.Trimesh:
    """A box one of whose edges is split on one side only, the T-junction closed by a flat triangle."""
    box = trimesh.creation.box(extents=(1.0, 2.0, 0.5))
    faces = [tuple(int(x) for x in f) for f in box.faces]
    vertices = np.asarray(box.vertices, np.float64)
    # the first side of a face along an axis (a box edge, not a face diagonal)
    i, k = next((n, k) for n, f in enumerate(faces) for k in range(3)
                if np.count_nonzero(vertices[f[k]] != vertices[f[(k + 1) % 3]]) == 1)
    a, b, c = faces[i][k], faces[i][(k + 1) % 3], faces[i][(k + 2) % 3]
    m = len(vertices)
    vertices = np.vstack([vertices, 0.5 * (vertices[a] + vertices[b])])  # exact: coordinates are +-0.5, 1, 0.25
    faces[i] = (a, m, c)
    faces += [(m, b, c), (a, b, m)]
    return trimesh.Trimesh(vertices, np.array(faces), process=False)


def test_a_float32_stl_with_one_zero_area_face_loads_closed(tmp_path):
    mesh = _box_with_t_junction()
    _closed_with_zero_area(mesh)
    path = tmp_path / "t_junction.stl"
    mesh.export(path)  # binary STL: a float32 triangle soup
    with pytest.warns(MedialAxisWarning, match="1 zero-area faces"):
        loaded = load_mesh(path)
    assert loaded.mesh.is_watertight
    assert "zero-area faces: 1 flipped away" in loaded.repairs
    assert loaded.volume == pytest.approx(1.0 * 2.0 * 0.5, rel=1e-9)
    with pytest.warns(MedialAxisWarning):
        sk = mx.medial_axis(path, method="flow")
    assert sk.betti == (1, 0, 0)


def test_flips_and_collapses_keep_the_surface_closed():
    mesh = _fine_union()
    vertices = np.asarray(mesh.vertices)
    faces, flipped, collapsed, kept = remove_degenerate_faces(vertices, np.asarray(mesh.faces),
                                                              coordinate_accuracy(vertices))
    assert (flipped, collapsed, kept) == (0, 7, 0)  # six of zero area, one more within the float32 accuracy
    out = trimesh.Trimesh(vertices, faces, process=False)
    out.remove_unreferenced_vertices()
    assert out.is_watertight and out.is_winding_consistent
    assert out.euler_number == mesh.euler_number == 2
    assert out.volume == pytest.approx(mesh.volume, rel=1e-9)


def test_a_mesh_without_degenerate_faces_is_left_as_it_is():
    sphere = trimesh.creation.icosphere(subdivisions=2)
    with warnings.catch_warnings():
        warnings.simplefilter("error", MedialAxisWarning)
        loaded = load_mesh(sphere)
    assert loaded.repairs == ()
    assert np.array_equal(loaded.mesh.faces, sphere.faces)


def test_many_caps_are_each_flipped_away():
    # 40 T-junctions on an icosphere, each closed by a flat cap: every cap flipped, the surface as it was
    sphere = trimesh.creation.icosphere(subdivisions=3)
    vertices, faces = [*np.asarray(sphere.vertices)], [tuple(int(x) for x in f) for f in sphere.faces]
    rng, used, caps = np.random.default_rng(3), set(), 0
    for i in rng.permutation(len(faces)):
        a, b, c = faces[i]
        j = next(n for n, f in enumerate(faces) if (b, a) in {(f[0], f[1]), (f[1], f[2]), (f[2], f[0])})
        if {i, j} & used:
            continue
        used |= {i, j}
        m = len(vertices)
        vertices.append(0.5 * (vertices[a] + vertices[b]))
        faces[i] = (a, m, c)
        faces += [(m, b, c), (a, b, m)]  # the cap: zero area, its third vertex on its longest edge
        caps += 1
        if caps == 40:
            break
    v = np.array(vertices)
    mesh = trimesh.Trimesh(v, np.array(faces), process=False)
    _closed_with_zero_area(mesh)
    out, flipped, collapsed, kept = remove_degenerate_faces(v, np.array(faces), coordinate_accuracy(v))
    assert (flipped, collapsed, kept) == (40, 0, 0)
    assert len(degenerate_faces(v, out, coordinate_accuracy(v))) == 0
    result = trimesh.Trimesh(v, out, process=False)
    assert result.is_watertight and result.is_winding_consistent and result.euler_number == 2
    assert result.volume == pytest.approx(sphere.volume, rel=1e-12)
