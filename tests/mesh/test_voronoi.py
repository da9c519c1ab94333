"""Voronoi lambda-medial surfaces of meshes: analytic shapes, certificate, topology, inputs."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from mesh_balls import interpolated_balls

import medialaxis as mx
from medialaxis.errors import EmptyShapeError, InvalidInputError, MedialAxisWarning
from medialaxis.mesh.medial._collapse_kernels import collapse_facets, collapse_free_sides
from medialaxis.mesh.sample._closest_kernels import (
    closest_on_candidates,
    closest_point_reference,
    face_data,
    face_scale,
)
from medialaxis.mesh.voronoi import euler_characteristic, voronoi_medial_axis


def winding_number(mesh: trimesh.Trimesh, query: np.ndarray) -> np.ndarray:
    """Generalised winding number (Jacobson et al. 2013), brute force: independent inside test."""
    tri = np.asarray(mesh.triangles)[None]
    out = []
    for chunk in np.array_split(query, max(1, len(query) // 200)):
        a, b, c = (tri[:, :, k] - chunk[:, None] for k in range(3))
        la, lb, lc = (np.linalg.norm(x, axis=-1) for x in (a, b, c))
        det = np.einsum("qfk,qfk->qf", a, np.cross(b, c))
        den = la * lb * lc + np.einsum("qfk,qfk->qf", a, b) * lc + np.einsum("qfk,qfk->qf", b, c) * la
        den += np.einsum("qfk,qfk->qf", c, a) * lb
        out.append(np.arctan2(det, den).sum(axis=1) / (2 * np.pi))
    return np.concatenate(out)


@pytest.fixture(scope="module")
def capsule_mesh():
    # Fine enough that the faceted caps' own medial sheets stay below 3 % of the radius
    # (with count=[24, 24] the mesh's axis runs 6 % past the segment's ends).
    return trimesh.creation.capsule(height=2.0, radius=0.5, count=[64, 64])


@pytest.fixture(scope="module")
def capsule(capsule_mesh):
    return voronoi_medial_axis(capsule_mesh, samples=12_000)


@pytest.fixture(scope="module")
def box_mesh():
    return trimesh.creation.box(extents=(2.0, 1.0, 0.5))


@pytest.fixture(scope="module")
def box(box_mesh):
    return voronoi_medial_axis(box_mesh, samples=15_000)


@pytest.fixture(scope="module")
def torus_mesh():
    return trimesh.creation.torus(major_radius=1.0, minor_radius=0.3, major_sections=48, minor_sections=16)


@pytest.fixture(scope="module")
def torus(torus_mesh):
    return voronoi_medial_axis(torus_mesh, samples=15_000)


# ------------------------------------------------------------ known answers
@pytest.mark.parametrize("full", [False, True], ids=["compact", "full"])
def test_capsule_axis_is_its_segment(capsule, full):
    ma = capsule.raw if full else capsule
    p = ma.points
    z = np.clip(p[:, 2], -1.0, 1.0)
    to_segment = np.sqrt(p[:, 0] ** 2 + p[:, 1] ** 2 + (p[:, 2] - z) ** 2)
    assert to_segment.max() <= 0.03 * 0.5
    assert np.abs(ma.radii - 0.5).max() <= 0.03 * 0.5
    # the whole segment is covered, not only its middle
    assert p[:, 2].min() < -0.9 and p[:, 2].max() > 0.9
    if full:
        assert len(p) > 100 and len(ma.faces) > 1000  # the sampling noise: a fan of narrow sheets
    else:
        # compact: a polyline with radii (a stray sliver at most), its ends near the cap centres
        assert len(p) <= 12 and len(ma.faces) <= 2 and ma.metadata["n_curve_edges"] >= 1
        assert ma.betti == (1, 0, 0)


@pytest.mark.parametrize("name", ["capsule", "box", "torus"])
def test_compact_complex_is_smaller_with_the_same_topology(name, request):
    ma = request.getfixturevalue(name)
    mesh = request.getfixturevalue(name + "_mesh")
    full = ma.raw
    assert full is not None and not full.metadata.get("compact")
    assert ma.metadata["full_faces"] == len(full.faces) and ma.metadata["full_points"] == len(full.points)
    # the solid's topology from its own surface: one piece, genus g = 1 - chi(surface) / 2
    genus = 1 - mesh.euler_number // 2
    assert ma.betti == full.betti == (1, genus, 0)
    assert len(ma.faces) <= 0.01 * len(full.faces) and len(ma.points) <= 0.02 * len(full.points)
    # kept spheres are spheres of the full complex, with their extras; their radius is the exact
    # distance to the mesh (brute force), which the full complex's local search may overshoot
    index = {tuple(p): k for k, p in enumerate(full.points.tolist())}
    rows = np.array([index[tuple(p)] for p in ma.points.tolist()])
    assert np.array_equal(ma.contacts, full.contacts[rows])
    with pytest.raises(InvalidInputError, match="compact"):
        voronoi_medial_axis(mesh, samples=2000, compact="no")
    assert np.all(ma.radii <= full.radii[rows])
    assert np.allclose(ma.radii, closest_point_reference(ma.points, mesh.triangles), rtol=1e-9, atol=1e-12)


def test_box_medial_surface_is_its_planar_pieces(box):
    half = np.array([1.0, 0.5, 0.25])
    d = np.sort(np.concatenate([half - box.points, half + box.points], axis=1), axis=1)
    # within the linear region, the distance to the bisector of the two nearest
    # faces is at most (d2 - d1) / sqrt(2) (perpendicular) or / 2 (parallel)
    assert ((d[:, 1] - d[:, 0]) / np.sqrt(2)).max() <= 0.01
    # the central sheet z = 0 is there, over most of its extent
    sheet = np.abs(box.points[:, 2]) < 0.01
    assert np.ptp(box.points[sheet, 0]) > 1.2 and np.ptp(box.points[sheet, 1]) > 0.2
    assert np.allclose(box.radii, d[:, 0], atol=1e-9)


def test_torus_gives_its_core_circle(torus):
    p = torus.points
    to_circle = np.hypot(np.hypot(p[:, 0], p[:, 1]) - 1.0, p[:, 2])
    assert to_circle.max() <= 0.05 * 0.3
    assert torus.n_components == 1
    assert euler_characteristic(len(p), torus.faces, torus.edges) == 0  # one cycle: b1 = 1
    along, _ = interpolated_balls(torus)  # the complex's points, edges and faces, not only its vertices
    angle = np.arctan2(along[:, 1], along[:, 0])
    assert np.histogram(angle, bins=36, range=(-np.pi, np.pi))[0].min() > 0  # all the way round


@pytest.mark.parametrize("seed", [3, 4])
def test_flat_tetrahedra_do_not_reach_out_to_a_faceted_sphere(seed):
    # Four co-circular samples near the surface of a faceted sphere make a flat tetrahedron whose
    # circumcentre (the circle's centre) lies near the surface: its Voronoi ball pokes far out
    # of the mesh. Rotated this way, the release before kept a sheet out to 1.95 from the centre
    # of this radius-2 icosphere (a ball of radius 0.05 at the surface). Truth: the medial axis
    # of a sphere is its centre; the facets add only sheets thinner than lambda.
    from scipy.spatial.transform import Rotation

    sphere = trimesh.creation.icosphere(subdivisions=3, radius=2.0)
    sphere.apply_transform(np.r_[np.c_[Rotation.random(random_state=seed).as_matrix(), np.zeros(3)], [[0, 0, 0, 1]]])
    full = voronoi_medial_axis(sphere, samples=3000, compact=False)
    assert np.linalg.norm(full.points, axis=1).max() < 0.25
    assert full.radii.min() > 1.75


def test_sphere_gives_its_centre():
    # A ball's medial axis is its centre: the compact complex shrinks to a few spheres there, with
    # nothing left to sample between them (the reach check of the collapses then has no work).
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=2.0)
    ma = voronoi_medial_axis(sphere, samples=3000)
    # How many are left depends on ties among the co-spherical samples: 7 or 11 from the same
    # complex with circumcentres differing in the last bits; the positions below do not.
    assert len(ma.points) <= 12 and ma.betti == (1, 0, 0)
    # within the compaction tolerance of the centre (4.7% of the radius here; the facets lie 0.6% inside)
    assert np.linalg.norm(ma.points, axis=1).max() <= ma.metadata["compact_tolerance"] + 0.012 * 2.0
    assert np.abs(ma.radii - 2.0).max() <= ma.metadata["compact_tolerance"] + 0.012 * 2.0


# ---------------------------------------------------------------- certificate
@pytest.mark.parametrize("name", ["capsule", "box", "torus"])
def test_medial_certificate(name, request):
    ma = request.getfixturevalue(name)
    mesh = request.getfixturevalue(name + "_mesh")
    lam = ma.metadata["lam"]
    rng = np.random.default_rng(1)
    pick = rng.choice(len(ma.points), size=min(300, len(ma.points)), replace=False)
    q = ma.points[pick]
    # inside (independent winding number), radius = distance to the surface (brute force)
    assert np.all(winding_number(mesh, q) > 0.5)
    # radius = distance to the mesh found by local search from the contacts: never below the
    # true distance, and within 0.5 % of it (0.2 % measured on the faceted torus)
    true = closest_point_reference(q, mesh.triangles)
    assert np.all(ma.radii[pick] >= true - 1e-12)
    assert np.allclose(ma.radii[pick], true, rtol=5e-3, atol=0)
    assert ma.metadata["n_filling_faces"] == 0 and ma.metadata["n_outside_points"] == 0
    # each ball touches the surface (its four contacts) at points at least lam apart
    contacts = ma.contacts[pick]
    on_ball = np.linalg.norm(contacts - q[:, None], axis=2) - ma.radii[pick, None]
    assert np.abs(on_ball).max() <= ma.metadata["epsilon"]
    assert np.all(ma.contact_diameter >= lam)
    gap = np.linalg.norm(contacts[:, :, None] - contacts[:, None, :], axis=3).max(axis=(1, 2))
    assert np.all(gap >= lam)
    assert np.all(ma.face_contact_diameter >= lam)
    # the union of the balls interpolated over the (compact) complex covers the solid up to the
    # sampling error: every point deeper than epsilon (brute-force distance to the mesh), and
    # about 95 % of all of it (the compact torus, a 17-gon of epsilon = 10 % of its tube
    # radius, covers 95.0 %, measured on 200k points; its full complex 98.7 %)
    lo, hi = mesh.bounds
    x = rng.uniform(lo, hi, size=(5000, 3))
    x = x[winding_number(mesh, x) > 0.5]
    centres, radii = interpolated_balls(ma)
    covered = np.zeros(len(x), bool)
    for chunk in np.array_split(np.arange(len(centres)), max(1, len(centres) // 2000)):
        d = np.linalg.norm(x[:, None] - centres[None, chunk], axis=2)
        covered |= (d <= radii[chunk]).any(axis=1)
    missed = x[~covered]
    missed_deep = closest_point_reference(missed, mesh.triangles) > ma.metadata["epsilon"]
    assert missed_deep.sum() <= 0.005 * len(x)
    assert covered.mean() >= 0.93


# ------------------------------------------------------------------ topology
@pytest.mark.parametrize("name", ["capsule", "box", "torus"])
def test_topology_matches_the_solid(name, request):
    ma = request.getfixturevalue(name)
    mesh = request.getfixturevalue(name + "_mesh")
    chi = euler_characteristic(len(ma.points), ma.faces, ma.edges)
    assert chi == ma.metadata["euler_characteristic"] == mesh.euler_number // 2
    assert ma.n_components == 1
    # b1 = b0 + b2 - chi, with b2 = 0 for a solid without cavities
    assert 1 - chi == (1 - mesh.euler_number // 2)


def test_genus_two_solid_topology():
    # two tori side by side, overlapping in a bridge: a genus-2 solid built by a voxel union
    from skimage.measure import marching_cubes

    g = np.linspace(-2.2, 2.2, 70)
    x, y, z = np.meshgrid(g, g, g, indexing="ij")

    def tube(cx):
        return (np.hypot(x - cx, y) - 0.8) ** 2 + z**2 < 0.35**2

    solid = tube(-0.9) | tube(0.9)
    v, f, _, _ = marching_cubes(np.pad(solid, 1).astype(float), 0.5, spacing=(g[1] - g[0],) * 3)
    mesh = trimesh.Trimesh(v, f, process=True)
    mesh.fix_normals()
    assert mesh.is_watertight and mesh.euler_number == -2
    ma = voronoi_medial_axis(mesh, samples=15_000)
    assert ma.n_components == 1
    assert euler_characteristic(len(ma.points), ma.faces, ma.edges) == -1  # b1 = 2


def test_lambda_mode_is_algorithm_5_literally(capsule_mesh):
    ma = voronoi_medial_axis(capsule_mesh, samples=8_000, topology="lambda")
    assert np.all(ma.face_contact_diameter >= ma.metadata["lam"])
    assert np.all(ma.face_certified)


# ------------------------------------------------------------------ sampling
def test_sampling_metadata_and_adaptivity():
    flat = trimesh.creation.icosphere(subdivisions=3)
    flat.apply_scale((1.0, 1.0, 0.25))
    ma = voronoi_medial_axis(flat, samples=10_000)
    md = ma.metadata
    assert md["n_samples"] > len(flat.vertices)
    assert 0 < md["epsilon"] < md["lam"] < md["lam_bound"]
    assert 0 < md["epsilon_lfs"] < 1
    from medialaxis.mesh.sample.sampling import adaptive_spacing, lfs_estimate, pseudo_normals

    spacing = adaptive_spacing(flat, lfs_estimate(flat, 2000, pseudo_normals(flat)), 10_000)
    rim = np.abs(flat.triangles_center[:, 2]) < 0.05
    assert np.median(spacing[rim]) < 0.6 * np.median(spacing[~rim])


# -------------------------------------------------------------------- kernels
def test_closest_point_kernel_matches_brute_force():
    mesh = trimesh.creation.icosphere(subdivisions=1)
    rng = np.random.default_rng(0)
    q = rng.normal(size=(200, 3)) * 0.8
    tri = np.asarray(mesh.triangles)
    corners = tuple(np.ascontiguousarray(tri[:, k]) for k in range(3))
    # true rings (faces sharing a vertex), starting from one far face: the walk must find the closest
    nf = len(tri)
    f = mesh.faces
    shares = (f[:, None, :, None] == f[None, :, None, :]).any(axis=(2, 3))
    ring_ptr = np.r_[0, np.cumsum(shares.sum(axis=1))].astype(np.int64)
    ring_idx = np.nonzero(shares)[1].astype(np.int64)
    near = np.zeros((len(q), 1), np.int64)
    fd = face_data(*corners)
    dist, point, face, _ = closest_on_candidates(q, fd, near, ring_ptr, ring_idx, face_scale(fd))
    assert nf == 80
    assert np.allclose(dist, closest_point_reference(q, tri), atol=1e-12)
    assert np.allclose(np.linalg.norm(q - point, axis=1), dist)


def test_exact_signed_distance_matches_brute_force_where_many_faces_are_nearly_equidistant():
    # points on the axis of a faceted surface of revolution (whole rings of faces nearly equidistant),
    # deep inside it and outside: distance against a brute force over every face, sign against
    # trimesh's own containment test
    from medialaxis.mesh.sample.signed_distance import SignedDistance

    mesh = trimesh.creation.uv_sphere(radius=1.0, count=[64, 64])
    mesh.apply_scale([3, 1, 1])
    rng = np.random.default_rng(1)
    on_axis = np.c_[rng.uniform(-2.5, 2.5, 200), np.zeros((200, 2))]
    inside = rng.uniform(-0.9, 0.9, (200, 3)) * [3, 1, 1]
    outside = rng.normal(size=(200, 3)) * 2.0
    points = np.r_[on_axis, inside, outside]
    signed, closest = SignedDistance(mesh).exact(points, budget=5_000)  # small batches: the padding path runs
    assert np.allclose(np.abs(signed), closest_point_reference(points, np.asarray(mesh.triangles)), atol=1e-12)
    assert np.allclose(np.linalg.norm(points - closest, axis=1), np.abs(signed), atol=1e-12)
    assert np.array_equal(signed < 0, mesh.contains(points))


def test_collapse_kernels_match_python_and_keep_euler():
    # a 3x3 grid of squares (a disc) with one protected square: collapses to it
    ptr, sides, ends = [0], [], {}

    def side(a, b):
        return ends.setdefault((min(a, b), max(a, b)), len(ends))

    for i in range(3):
        for j in range(3):
            v = [i * 4 + j, i * 4 + j + 1, (i + 1) * 4 + j + 1, (i + 1) * 4 + j]
            sides += [side(v[k], v[(k + 1) % 4]) for k in range(4)]
            ptr.append(len(sides))
    ptr, sides = np.array(ptr), np.array(sides)
    length = np.arange(9, dtype=float)
    protected = np.zeros(9, bool)
    protected[4] = True
    out = collapse_facets(ptr, sides, len(ends), length, protected)
    ref = collapse_facets.py_func(ptr, sides, len(ends), length, protected)
    assert all(np.array_equal(a, b) for a, b in zip(out, ref))
    assert out[0].sum() == 1 and out[0][4]
    # priorities not in ascending order (the kernel sorts them; ascending ones it takes as they come)
    shuffled = np.random.default_rng(0).permutation(9).astype(float)
    mixed = collapse_facets(ptr, sides, len(ends), shuffled, protected)
    assert all(np.array_equal(a, b) for a, b in zip(mixed, collapse_facets.py_func(ptr, sides, len(ends), shuffled, protected)))
    end_arr = np.array(sorted(ends, key=ends.get))
    used = np.zeros(len(ends), bool)
    used[sides[4 * 4 : 5 * 4]] = True
    alive = collapse_free_sides(out[1], used, end_arr, 16)
    assert np.array_equal(alive, collapse_free_sides.py_func(out[1], used, end_arr, 16))
    assert np.array_equal(alive, used)  # every dangling side went



def _collapse_by_definition(ptr, sides, n_sides, length, protected):
    """Elementary collapses by their definition, slowly: the present unprotected facet of least (length, index)
    with a free side (one no other present facet uses) goes, with the first such side, until none is left."""
    alive, side_alive = np.ones(len(ptr) - 1, bool), np.ones(n_sides, bool)
    while True:
        count = np.bincount(np.concatenate([sides[ptr[f]:ptr[f + 1]] for f in np.flatnonzero(alive)] or [[]]).astype(int),
                            minlength=n_sides)
        best = None
        for f in np.flatnonzero(alive & ~protected):
            free = [s for s in sides[ptr[f]:ptr[f + 1]] if side_alive[s] and count[s] == 1]
            if free and (best is None or (length[f], f) < (length[best[0]], best[0])):
                best = (f, free[0])
        if best is None:
            return alive, side_alive
        alive[best[0]], side_alive[best[1]] = False, False


def test_collapse_facets_is_the_collapse_by_its_definition():
    # the rings of a random Delaunay's inner edges (facets are polygons, sides the triangles between tetrahedra)
    from scipy.spatial import Delaunay

    from medialaxis.mesh.medial._ring_kernels import all_edge_rings, flagged_sides, ring_side_slots

    rng = np.random.default_rng(4)
    for trial in range(4):
        points = rng.normal(size=(60, 3))
        dt = Delaunay(points)
        simplices, neighbors = dt.simplices.astype(np.int64), dt.neighbors.astype(np.int64)
        _, ptr, ring, length = all_edge_rings(simplices, neighbors, points, np.zeros(0, np.int64), True, 0.0)
        slot, ends = flagged_sides(neighbors, np.ones(len(simplices), bool))
        sides = ring_side_slots(ptr, ring, neighbors, slot)
        length = np.round(length, 1)  # ties, broken by index
        protected = rng.random(len(length)) < 0.05 * trial
        got = collapse_facets(ptr, sides, len(ends), length, protected)
        want = _collapse_by_definition(ptr, sides, len(ends), length, protected)
        np.testing.assert_array_equal(got[0], want[0])
        np.testing.assert_array_equal(got[1], want[1])

def test_reach_lattice_of_the_compaction():
    # the spheres the compaction's reach check samples over a triangle and an edge (corners left out)
    from medialaxis.mesh.medial._compact_kernels import lattice

    spheres = np.array([[0.0, 0, 0, 1.0], [1.0, 0, 0, 1.0], [0.0, 1.0, 0, 2.0]])
    prims = np.array([[0, 1, 2], [0, 1, 1]])
    out, owner = lattice(spheres, prims, prims, 0.25, -np.inf)  # nothing bounded away
    steps = (int(np.ceil(np.sqrt(3.0) / 0.25)), 4)  # longest side in (centre, radius): sqrt(3) and 1
    assert np.bincount(owner).tolist() == [(steps[0] + 1) * (steps[0] + 2) // 2 - 3, steps[1] - 1]
    # each sample is the interpolation of the corners at barycentric coordinates k / steps
    w = np.linalg.lstsq(spheres[[0, 1, 2]].T, out[owner == 0].T, rcond=None)[0].T
    assert np.allclose(w.sum(axis=1), 1.0) and w.min() >= -1e-12
    assert np.allclose(w * steps[0], np.round(w * steps[0]), atol=1e-9)
    assert not np.isclose(w, 1.0).any()  # no corner
    edge = out[owner == 1]
    assert np.allclose(edge[:, 1:], [0.0, 0.0, 1.0]) and np.allclose(np.sort(edge[:, 0]), [0.25, 0.5, 0.75])
    # a sphere within the tolerance of reaching out, by its corners' balls, is not sampled
    assert len(lattice(spheres, prims, prims, 0.25, 0.5)[0]) < len(out)
    assert len(lattice(spheres, prims, prims, 0.25, 2.0)[0]) == 0  # none can reach 2.0 out: r <= 2.0


# ---------------------------------------------------------- inputs and API
def test_dispatch_file_input_and_outputs(tmp_path, capsule_mesh):
    path = tmp_path / "capsule.ply"
    capsule_mesh.export(path)
    ma = mx.medial_axis(str(path), method="voronoi", samples=6000)
    assert ma.metadata["domain"] == "mesh" and ma.dim == 3 and len(ma.edges) and len(ma.raw.faces)
    for ext in (".ply", ".obj", ".npz", ".json"):
        ma.save(tmp_path / f"out{ext}")
        assert (tmp_path / f"out{ext}").stat().st_size > 0
    back = mx.load(tmp_path / "out.npz")
    assert np.array_equal(back.points, ma.points) and np.array_equal(back.faces, ma.faces)


def test_input_not_modified_and_result_read_only(capsule_mesh):
    mesh = capsule_mesh.copy()
    before = mesh.vertices.copy()
    ma = voronoi_medial_axis(mesh, samples=5000)
    assert np.array_equal(mesh.vertices, before)
    with pytest.raises(ValueError):
        ma.points[0, 0] = 1.0


def test_scale_and_rigid_motion_equivariance(capsule_mesh):
    a = voronoi_medial_axis(capsule_mesh, samples=6000)
    moved = capsule_mesh.copy()
    rot = trimesh.transformations.rotation_matrix(0.7, [1, 2, 3])
    moved.apply_transform(rot)
    moved.apply_scale(3.0)
    moved.apply_translation([5.0, -2.0, 1.0])
    b = voronoi_medial_axis(moved, samples=6000)
    # lam follows the measured epsilon; the coarse LFS pass thins on an axis-aligned grid,
    # so the sample (and epsilon) is only approximately invariant under rotation
    assert b.metadata["lam"] == pytest.approx(3.0 * a.metadata["lam"], rel=0.25)
    assert b.radii.max() == pytest.approx(3.0 * a.radii.max(), rel=0.02)
    back = (b.points - [5.0, -2.0, 1.0]) / 3.0 @ rot[:3, :3]
    # mapped back, b's axis is as close to the capsule's axis as a's (coarse sample: a few %)
    off_a = np.hypot(a.points[:, 0], a.points[:, 1]).max()
    off_b = np.hypot(back[:, 0], back[:, 1]).max()
    assert off_a <= 0.1 * 0.5 and off_b <= 0.1 * 0.5


def test_a_large_hole_is_capped_where_the_winding_number_decides_the_solid(box_mesh):
    # half a side missing: a hole across most of the box, but the rest of the surface still decides
    # inside and outside (Jacobson et al. 2013), as libigl's winding-number segmentation would
    open_mesh = trimesh.Trimesh(box_mesh.vertices, box_mesh.faces[1:], process=False)
    with pytest.warns(MedialAxisWarning, match=r"closed 1 holes .*undecided over \d"):
        ma = voronoi_medial_axis(open_mesh, samples=5000)
    assert any("closed 1 holes" in r for r in ma.metadata["repairs"])
    assert ma.metadata["mesh_volume"] == pytest.approx(box_mesh.volume, rel=1e-12)  # the missing face, exactly
    assert ma.betti == (1, 0, 0)


def test_an_open_bowl_bounds_no_solid_and_is_capped_on_request():
    bowl = trimesh.creation.icosphere(3).slice_plane([0, 0, 0], [0, 0, -1])  # open along the equator
    with pytest.raises(InvalidInputError, match=r"bounds no solid: its 1 holes .*undecided over \d+%.*repair=True"):
        voronoi_medial_axis(bowl)
    with pytest.warns(MedialAxisWarning, match="closed 1 holes"):
        ma = voronoi_medial_axis(bowl, repair=True, samples=5000)
    assert ma.metadata["mesh_volume"] == pytest.approx(bowl.convex_hull.volume, rel=1e-9)  # capped by its rim's plane


def test_a_scan_with_small_holes_gets_the_solid_its_winding_number_defines():
    sphere = trimesh.creation.icosphere(4)
    rng = np.random.default_rng(0)
    gone = rng.choice(len(sphere.faces), 6, replace=False)  # six one-face holes, far apart
    holed = trimesh.Trimesh(sphere.vertices, np.delete(sphere.faces, gone, axis=0), process=False)
    assert not holed.is_watertight
    with pytest.warns(MedialAxisWarning, match="not watertight: closed 6 holes"):
        ma = voronoi_medial_axis(holed, samples=5000)
    assert ma.betti == (1, 0, 0)
    assert ma.metadata["mesh_volume"] == pytest.approx(sphere.volume, rel=1e-12)
    assert ma.radii.max() == pytest.approx(1.0, abs=0.02)


def test_signed_volume_is_exact_far_from_the_origin_and_load_mesh_turns_an_inward_mesh_out():
    from medialaxis.mesh.solid.inputs import load_mesh, signed_volume

    box = trimesh.creation.box(extents=(2.0, 3.0, 4.0))
    box.apply_translation([1e6, -2e6, 3e6])
    assert signed_volume(box.triangles) == pytest.approx(24.0, rel=1e-9)  # truth: 2 x 3 x 4
    inward = box.copy()
    inward.invert()
    assert signed_volume(inward.triangles) == pytest.approx(-24.0, rel=1e-9)
    loaded = load_mesh(inward)
    assert loaded.volume == pytest.approx(24.0, rel=1e-9)
    assert any("flipped" in r for r in loaded.repairs)
    assert signed_volume(loaded.mesh.triangles) > 0


@pytest.mark.parametrize(
    "options",
    [{"lam": -1.0}, {"lam": float("nan")}, {"samples": 10}, {"samples": 2.5}, {"topology": "none"}],
)
def test_rejects_bad_options(options, box_mesh):
    with pytest.raises(InvalidInputError):
        voronoi_medial_axis(box_mesh, **options)


def test_rejects_empty_and_flat_meshes():
    with pytest.raises(EmptyShapeError):
        voronoi_medial_axis(trimesh.Trimesh(np.zeros((0, 3)), np.zeros((0, 3), int)))
    with pytest.raises((EmptyShapeError, InvalidInputError)):
        voronoi_medial_axis(trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], [[0, 1, 2], [1, 3, 2]]))


def test_html_view_is_self_contained(tmp_path, box):
    out = tmp_path / "box.html"
    box.save(out)
    text = out.read_text()
    library = sorted(tmp_path.glob("plotly-*.min.js"))
    assert len(library) == 1 and f'<script src="{library[0].name}"></script>' in text  # beside the page, not remote
    assert '<script src="http' not in text
    assert "medial surface" in text and "input surface" in text


def test_slab_distance_kernels_against_a_dense_grid():
    # distance in (x, y, z, r) from a sphere to a segment / triangle of spheres, against the
    # minimum over a dense barycentric grid (the exact value lies at most a grid step below)
    from medialaxis.mesh.medial._compact_kernels import _segment_distance2, _triangle_distance2

    rng = np.random.default_rng(3)
    n = 60
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    keep = i + j <= n
    u, w = i[keep] / n, j[keep] / n
    for _ in range(50):
        s = rng.normal(size=(4, 4))
        tri = s[1] + u[:, None] * (s[2] - s[1]) + w[:, None] * (s[3] - s[1])
        grid = np.sqrt(((tri - s[0]) ** 2).sum(axis=1).min())
        exact = np.sqrt(_triangle_distance2(s, 0, 1, 2, 3))
        assert exact <= grid + 1e-12
        assert exact >= grid - 2.0 * np.abs(s[1:] - s[1]).sum(axis=1).max() / n
        seg = s[1] + np.linspace(0, 1, 2001)[:, None] * (s[2] - s[1])
        grid = np.sqrt(((seg - s[0]) ** 2).sum(axis=1).min())
        exact = np.sqrt(_segment_distance2(s, 0, 1, 2))
        assert grid - np.linalg.norm(s[2] - s[1]) / 2000 <= exact <= grid + 1e-12


def test_collapse_free_sides_peels_every_dangling_side_by_its_definition():
    # a random graph: sides a facet uses stay; any other side with an end of degree one goes, until none
    rng = np.random.default_rng(5)
    for _ in range(20):
        n = int(rng.integers(2, 40))
        ends = rng.integers(0, n, (int(rng.integers(1, 60)), 2))
        ends = ends[ends[:, 0] != ends[:, 1]].astype(np.int32)
        alive, used = rng.random(len(ends)) < 0.9, rng.random(len(ends)) < 0.3
        want = alive.copy()
        while True:
            degree = np.bincount(ends[want].ravel(), minlength=n)
            leaf = np.flatnonzero(want & ~used & ((degree[ends[:, 0]] == 1) | (degree[ends[:, 1]] == 1)))
            if not len(leaf):
                break
            want[leaf[0]] = False
        np.testing.assert_array_equal(collapse_free_sides(alive, used, ends, n), want)
