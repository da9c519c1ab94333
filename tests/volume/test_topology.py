"""Topology of the mid-surface mesh at junctions, creases and line ends (issue 3 follow-up).

The T must come out as one contractible mesh (Euler characteristic 1) whose
three sheets share the junction edges, for every noise and sampling seed;
the member (a closed box section with a flange) as a tube with a flange
(Euler characteristic 0).
"""

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.datasets import member_phantom, t_phantom
from medialaxis.volume import _kernels
from medialaxis.volume.regions import JUNCTION, sheet_ids
from medialaxis.volume.repair import _close_boundary_triangles, _close_junction_notches, _drop_double_quads
from medialaxis.volume.validation import coverage, distance_to_rects, mesh_topology
from medialaxis.volume.voxel_table import neighbour_rows, voxel_table


def _truth(ph):
    return np.concatenate([r.sample(0.5) for r in ph.midsurface])


def _junction_edge_faces(faces, junction):
    e = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    edges, count = np.unique(e, axis=0, return_counts=True)
    return count[junction[edges[:, 0]] & junction[edges[:, 1]]]


@pytest.mark.parametrize("noise_seed", [0, 1, 2, 3])
@pytest.mark.parametrize("rng", [0, 1])
def test_t_is_contractible_with_shared_junction_edges_for_every_seed(noise_seed, rng):
    ph = t_phantom((48, 80, 70), margin=8, rng=noise_seed)
    ma = mx.medial_axis(ph.volume, method="midsurface", iso=0.5, rng=rng)
    topo = mesh_topology(ma.faces)
    assert (topo.components, topo.euler) == (1, 1), topo
    # the junction line: every edge between two junction vertices is shared
    # by the three sheets (flange halves and stem)
    shared = _junction_edge_faces(np.asarray(ma.faces), np.asarray(ma.vertex_kind) == JUNCTION)
    assert len(shared) >= 4 and np.all(shared >= 3), shared
    d = distance_to_rects(ma.points, ph.midsurface)
    assert d.max() <= 2.0 and np.percentile(d, 99) <= 1.0
    flange, stem = ph.midsurface
    zj, yj = flange.origin[0], stem.origin[1]
    near = np.hypot(ma.points[:, 0] - zj, ma.points[:, 1] - yj) <= ph.thickness
    assert d[near].max() <= 0.75  # no dent, including at the end faces
    truth = _truth(ph)
    frac, dist = coverage(truth, ma.points, ma.faces)
    assert frac >= 0.985
    near_truth = np.hypot(truth[:, 0] - zj, truth[:, 1] - yj) <= ph.thickness
    assert np.mean(dist[near_truth] <= 1.0) >= 0.97  # no slit along the junction


@pytest.mark.parametrize("noise_seed,rng", [(0, 0), (1, 0), (2, 0), (0, 5)])
def test_member_is_a_tube_with_a_flange(noise_seed, rng):
    ph = member_phantom(rng=noise_seed)
    ma = mx.medial_axis(ph.volume, method="midsurface", iso=0.5, rng=rng)
    topo = mesh_topology(ma.faces)
    assert (topo.components, topo.euler) == (1, 0), topo
    assert topo.junction_edges > 0
    d = distance_to_rects(ma.points, ph.midsurface)
    assert np.percentile(d, 99) <= 0.5  # creases sharpened by eq. (1)
    assert d.max() <= 2.0  # no extension ray across a crease
    assert coverage(_truth(ph), ma.points, ma.faces)[0] >= 0.98


def test_sheet_ids_split_a_voxel_t_at_its_junction():
    occ = np.zeros((20, 30, 12), bool)
    occ[5, 3:27, 2:10] = True  # flange
    occ[6:17, 15, 2:10] = True  # stem
    voxels = np.argwhere(occ).astype(np.int64)
    table = voxel_table(voxels, occ.shape)
    junction = (voxels[:, 0] == 5) & (voxels[:, 1] == 15)
    sheet = sheet_ids(table, voxels, junction, np.ones(3))
    assert np.all(sheet[junction] == -1)
    left = sheet[(voxels[:, 0] == 5) & (voxels[:, 1] < 15)]
    right = sheet[(voxels[:, 0] == 5) & (voxels[:, 1] > 15)]
    stem = sheet[voxels[:, 0] > 5]
    assert len(set(left)) == len(set(right)) == len(set(stem)) == 1
    assert len({left[0], right[0], stem[0]}) == 3
    # regions grown from the junction and one pick per sheet never cross sheets
    stem_row = np.flatnonzero(voxels[:, 0] == 12)
    seeds = np.r_[np.flatnonzero(junction), stem_row].astype(np.int64)
    seed_label = np.r_[np.zeros(junction.sum()), np.ones(len(stem_row))].astype(np.int64)
    labels = _kernels.sheet_labels(neighbour_rows(table, voxels), voxels, seeds, seed_label, sheet, _kernels.OFFSETS_26, np.ones(3))
    assert np.all(labels[voxels[:, 0] == 5] == 0)  # the flange has no pick of its own
    assert np.all(labels[voxels[:, 0] >= 9] == 1)


def _grid_sheets(n=6):
    """A junction line (y = 0, x = 0..n-1) with two sheets of two rows each (y > 0 and y < 0)."""
    rows = [np.array([[0.0, y, x] for x in range(n)]) for y in (0, 1, 2, -1, -2)]
    points = np.concatenate(rows)
    row = lambda k, x: k * n + x  # noqa: E731
    faces = []
    for a, b in ((0, 1), (1, 2), (0, 3), (3, 4)):
        for x in range(n - 1):
            faces += [[row(a, x), row(a, x + 1), row(b, x)], [row(a, x + 1), row(b, x + 1), row(b, x)]]
    junction = np.zeros(len(points), bool)
    junction[:n] = True
    return points, np.sort(np.array(faces), axis=1), junction, row


def test_close_junction_notches_fills_a_sheet_gap_beside_the_line():
    points, faces, junction, row = _grid_sheets()
    assert np.all(_junction_edge_faces(faces, junction) == 2)
    # the lower sheet misses its two triangles at line edge (2, 3)
    gap = [sorted([row(0, 2), row(0, 3), row(3, 2)]), sorted([row(0, 3), row(3, 3), row(3, 2)])]
    notched = np.array([f for f in faces.tolist() if f not in gap])
    assert sorted(_junction_edge_faces(notched, junction).tolist()) == [1, 2, 2, 2, 2]
    closed = _close_junction_notches(notched, junction, points)
    assert np.all(_junction_edge_faces(closed, junction) == 2)
    assert mesh_topology(closed).euler == mesh_topology(faces).euler == 1


def test_drop_double_quads_keeps_one_split():
    points = np.array([[0.0, 0, 0], [1, 0, 0], [1, 2, 0], [0, 2, 0],
                       [0.5, -1, 0], [2, 1, 0], [0.5, 3, 0], [-1, 1, 0]])
    ring = [[0, 1, 4], [1, 2, 5], [2, 3, 6], [0, 3, 7]]
    both = np.sort(np.array(ring + [[0, 1, 2], [0, 2, 3], [0, 1, 3], [1, 2, 3]]), axis=1)
    kept = _drop_double_quads(both, points)
    assert len(kept) == 6
    topo = mesh_topology(kept)
    assert topo.euler == 1 and topo.junction_edges == 0


def test_close_boundary_triangles_at_a_pinched_vertex():
    # faces around vertex 0 leaving a triangular hole (0, 2, 3) whose three
    # edges are boundary edges; 0 also lies on the outer boundary (pinched)
    faces = np.array([[0, 1, 2], [2, 3, 6], [0, 3, 4], [0, 4, 5]])
    before = mesh_topology(faces)
    closed = _close_boundary_triangles(faces)
    assert [0, 2, 3] in closed.tolist()
    after = mesh_topology(closed)
    assert after.faces == before.faces + 1 and after.boundary_edges == before.boundary_edges - 3
