"""Where a closed mesh fails to bound its solid plainly: faces that cross, shells inside other shells.

Both are common in meshes as people have them (scans, CAD exports of
assemblies, parts put together without a boolean union). Neither makes the
solid undefined: :mod:`medialaxis.mesh.solid.arrangement` takes the solid where the
generalized winding number is at least 1/2 and gives its surface.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.core.arrays import unique_ints
from medialaxis.core.graph import component_labels

__all__ = [
    "candidate_pairs", "crossing_pairs", "inside_out_shells", "nested_shell", "shell_labels", "shell_volumes", "solid_betti", "unit_triangles", "vertex_shells", "winding_numbers",
]

#: Triangle-point terms of an exact winding-number call beyond which the fast winding tree answers.
EXACT_TERMS = 200_000_000
#: Vertices of a shell tested against the other shells (evenly spaced subset beyond this).
SHELL_PROBES = 500
#: Rounds of longest-edge bisection of a large face (each halves its pieces' longest side).
MAX_BISECTIONS = 40
#: Pieces of large faces made beyond 8 per face; larger faces are matched by their own spheres.
PIECE_BUDGET = 1_000_000
#: Candidate pairs of faces matched by their own spheres looked at per batch (about 100 bytes each).
SPHERE_BATCH = 2_000_000


def winding_numbers(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Generalized winding number of the triangles ``(T, 3, 3)`` at ``points`` ``(P, 3)`` (compiled, all cores)."""
    from medialaxis.mesh.solid._winding_kernels import winding_numbers as kernel

    return kernel(np.ascontiguousarray(points, np.float64), np.ascontiguousarray(triangles, np.float64))


def shell_labels(mesh: Any) -> np.ndarray:
    """Shell (connected set of faces) of each face: outer shells and cavities of a closed mesh."""
    from trimesh.graph import connected_component_labels

    return connected_component_labels(mesh.face_adjacency, node_count=len(mesh.faces))


def vertex_shells(n_vertices: int, faces: np.ndarray) -> tuple[int, np.ndarray]:
    """Pieces of a surface, its faces joined at their vertices: how many, and the piece of each face."""
    faces = np.asarray(faces, np.int64)
    n, labels = component_labels(n_vertices, faces[:, [0, 1, 1, 2]].reshape(-1, 2))
    return n, labels[faces[:, 0]]


def _six_volumes(tri: np.ndarray, shell: np.ndarray, n: int) -> np.ndarray:
    """Six times the signed volume of each of the ``n`` shells of the triangles ``tri`` (``shell``: of each)."""
    return np.bincount(shell, np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])), n)


def shell_volumes(mesh: Any) -> tuple[np.ndarray, np.ndarray]:
    """Shell of each face (:func:`shell_labels`) and six times each shell's signed volume (negative: a cavity)."""
    labels = shell_labels(mesh)
    tri = np.asarray(mesh.vertices, np.float64)[np.asarray(mesh.faces, np.int64)]
    return labels, _six_volumes(tri, labels, int(labels.max()) + 1 if len(labels) else 0)


def inside_out_shells(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Faces of the shells that face inward although no other shell encloses them ``(k,)``.

    A shell of negative signed volume bounds a cavity when the rest of the
    surface winds around it; one lying apart (a part whose faces an
    exporter turned over) has winding number 0 there and bounds nothing by
    the winding-number rule, though it was meant as a solid, as trimesh's
    ``fix_normals`` and MeshLab take it. Shells are the components of the
    faces joined at their vertices; each is tested at its first vertex,
    against the outward shells (those enclose; one winding-number call for
    all, through the fast winding tree past ``EXACT_TERMS`` terms: a porous
    part has thousands of cavities).
    """
    n, shell = vertex_shells(len(vertices), faces)
    if n < 2:
        return np.zeros(0, np.int64)
    tri = np.asarray(vertices, np.float64)[np.asarray(faces, np.int64)]
    volume = _six_volumes(tri, shell, n)
    inward = np.flatnonzero(volume < 0)
    if not len(inward):
        return np.zeros(0, np.int64)
    outward = tri[volume[shell] > 0]
    first = np.empty(n, np.int64)
    first[shell[::-1]] = np.arange(len(shell) - 1, -1, -1)  # each shell's first face
    probes = tri[first[inward], 0]
    if not len(outward):
        winding = np.zeros(len(inward))
    elif len(probes) * len(outward) > EXACT_TERMS:
        from medialaxis.mesh.solid._fast_winding_kernels import WindingTree

        winding = WindingTree(outward)(probes)
    else:
        winding = winding_numbers(probes, outward)
    free = np.zeros(n, bool)
    free[inward[np.abs(winding) < 0.5]] = True
    return np.flatnonzero(free[shell])


def solid_betti(mesh: Any) -> tuple[int, int, int]:
    """Betti numbers ``(b0, b1, b2)`` of the solid a closed, outward-oriented 2-manifold mesh bounds.

    Shells of positive signed volume are outer surfaces (``b0``), those of
    negative volume cavities (``b2``); ``b1`` follows from the solid's Euler
    characteristic, half its boundary's (a compact 3-manifold's
    ``chi(M) = chi(dM) / 2``).

    Examples
    --------
    >>> import trimesh
    >>> solid_betti(trimesh.creation.torus(3.0, 1.0))
    (1, 1, 0)
    """
    labels, volume = shell_volumes(mesh)
    b0, b2 = int((volume > 0).sum()), int((volume < 0).sum())
    faces = np.asarray(mesh.faces, np.int64)
    edges = unique_ints(np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1) @ np.array([len(mesh.vertices), 1]))
    chi = len(unique_ints(faces.ravel())) - len(edges) + len(faces)
    return b0, b0 + b2 - chi // 2, b2


def nested_shell(mesh: Any) -> int | None:
    """An outward shell lying (partly) inside another shell's solid, or ``None``.

    A closed mesh of several shells bounds a solid plainly only if each
    outward shell lies outside every other shell's solid (inward shells are
    cavities, inside their outer shell). A vertex of an outward shell where
    the other shells' winding number is about 1 lies in another shell's
    solid: the shells overlap (their faces cross) or nest (they do not
    cross, so :func:`crossing_pairs` alone misses them).
    """
    from medialaxis.mesh.solid.inputs import signed_volume

    labels = shell_labels(mesh)
    n_shells = int(labels.max()) + 1
    if n_shells < 2:
        return None
    tri = np.asarray(mesh.triangles)
    shells = [np.flatnonzero(labels == k) for k in range(n_shells)]
    lo = np.array([tri[f].reshape(-1, 3).min(axis=0) for f in shells])
    hi = np.array([tri[f].reshape(-1, 3).max(axis=0) for f in shells])
    for k, faces in enumerate(shells):
        if signed_volume(tri[faces]) <= 0:
            continue  # a cavity
        vertices = unique_ints(mesh.faces[faces])
        pick = np.linspace(0, len(vertices) - 1, min(SHELL_PROBES, len(vertices))).astype(int)
        probes = np.asarray(mesh.vertices)[vertices[pick]]
        # Only shells whose boxes meet this one's can hold its vertices; the
        # winding numbers of closed shells add up (a cavity's is -1 inside).
        winding = np.zeros(len(probes))
        for j in np.flatnonzero(np.all((lo <= hi[k]) & (hi >= lo[k]), axis=1)):
            if j == k:
                continue
            near = np.all((probes >= lo[j]) & (probes <= hi[j]), axis=1)
            if near.any():
                winding[near] += winding_numbers(probes[near], tri[shells[j]])
        if (winding > 0.75).any():
            return k
    return None


def unit_triangles(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """The triangles ``(f, 3, 3)`` in a unit box about the centre, that centre and the box's size."""
    v = np.asarray(vertices, np.float64)
    centre, size = v.mean(axis=0), float(np.ptp(v, axis=0).max()) or 1.0
    return np.ascontiguousarray(((v - centre) / size)[np.asarray(faces, np.int64)]), centre, size


def candidate_pairs(tri: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Pairs ``(i, j)`` of triangles that may cross (a superset: bounding spheres about the centroids meet).

    Pairs sharing an edge cannot cross and are left out; pairs sharing one
    vertex are kept (a face folded through a neighbour of its corner).
    Triangles up to twice the median size are binned on a grid
    (:func:`~medialaxis.mesh.solid._intersect_kernels.near_pairs`, which also
    drops the pairs with apart bounding boxes); each larger one (slivers,
    long CAD faces, caps of holes) is cut into pieces no larger by
    longest-edge bisection (:func:`_pieces`) and matched against the small
    faces whose spheres meet a piece's
    (:func:`~medialaxis.mesh.solid._broad_kernels.big_face_pairs`), and against
    the other large faces whose spheres meet its own. A long face's own sphere
    holds the whole mesh across it: the 2-unit faces along a 100k-vertex
    capsule made 60M candidates and the check took 40 s of CPU.
    """
    from medialaxis.mesh.solid._intersect_kernels import near_pairs

    centre = tri.mean(axis=1)
    radius = np.linalg.norm(tri - centre[:, None, :], axis=2).max(axis=1)
    limit = 2.0 * float(np.median(radius)) if len(radius) else 0.0
    small = radius <= limit
    idx = np.flatnonzero(small)
    pairs = []
    if len(idx) > 1:
        cell = max(2.0 * float(radius[idx].max()), 2.0**-19)  # ``tri`` lies in a unit box: at most 2^19 cells a side
        pairs.append(near_pairs(tri, faces, centre, radius, idx, cell, False))
    big = np.flatnonzero(~small)
    if len(big):
        from medialaxis.mesh.solid._broad_kernels import big_face_pairs

        small_reach = float(radius[idx].max()) if len(idx) else limit
        cut, kept = _pieces(tri, big, 2.0 * small_reach, PIECE_BUDGET + 8 * len(tri))
        piece_centre, piece_radius, piece_of = cut  # by face, as ``big`` is
        whole = np.setdiff1d(big, kept)  # too large to cut within the budget (a needle's faces)
        if len(kept):
            piece_ptr = np.searchsorted(piece_of, np.r_[kept, len(tri)]).astype(np.int64)
            pairs.append(big_face_pairs(
                tri, np.ascontiguousarray(faces, np.int64),
                np.ascontiguousarray(np.concatenate([centre[idx], piece_centre])),
                np.concatenate([radius[idx], piece_radius]), np.concatenate([idx, piece_of]).astype(np.int64),
                len(idx), kept, piece_ptr, max(small_reach + float(piece_radius.max()), 2.0**-19)))
        pairs.append(_sphere_pairs(big, big, tri, faces, centre, radius))  # large faces among themselves
        pairs.append(_sphere_pairs(whole, idx, tri, faces, centre, radius))
    return np.ascontiguousarray(np.vstack(pairs), dtype=np.int64) if pairs else np.empty((0, 2), np.int64)


def _sphere_pairs(
    query: np.ndarray, pool: np.ndarray, tri: np.ndarray, faces: np.ndarray, centre: np.ndarray, radius: np.ndarray
) -> np.ndarray:
    """Pairs ``(b, j)`` of ``query`` and ``pool`` faces, ``j`` the smaller: spheres and boxes meet, no shared edge."""
    from scipy.spatial import cKDTree

    if not len(query) or not len(pool):
        return np.empty((0, 2), np.int64)
    tree, reach = cKDTree(centre[pool]), 2.0 * radius[query]  # the smaller one's centre is within twice the larger's radius
    count = tree.query_ball_point(centre[query], reach, return_length=True)
    lo, hi = tri.min(axis=1), tri.max(axis=1)
    pairs, start = [], 0
    while start < len(query):  # a few million candidates at a time: a needle's faces reach every face
        stop = start + max(1, int(np.searchsorted(np.cumsum(count[start:]), SPHERE_BATCH)))
        near = tree.query_ball_point(centre[query[start:stop]], reach[start:stop], return_sorted=False)
        js = pool[np.concatenate([np.asarray(j, np.int64) for j in near])]
        bs = np.repeat(query[start:stop], count[start:stop])
        keep = (radius[js] < radius[bs]) | ((radius[js] == radius[bs]) & (js > bs))
        keep &= np.all((lo[js] <= hi[bs]) & (hi[js] >= lo[bs]), axis=1)
        keep &= np.linalg.norm(centre[js] - centre[bs], axis=1) <= radius[js] + radius[bs]
        keep &= (faces[bs][:, :, None] == faces[js][:, None, :]).sum(axis=(1, 2)) < 2  # not an edge apart
        pairs.append(np.column_stack([bs[keep], js[keep]]))
        start = stop
    return np.vstack(pairs)


def _pieces(
    tri: np.ndarray, which: np.ndarray, limit: float, budget: int
) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], np.ndarray]:
    """Triangles ``tri[which]`` cut by longest-edge bisection into pieces of bounding radius at most ``limit``.

    Returns each piece's centroid, the distance to its farthest corner and
    the triangle it is of, by triangle (a point of a triangle lies in one of
    its pieces), and the triangles cut: the smallest first, while their
    pieces (about ``4 area / limit^2 + 2 longest side / limit`` each) stay within ``budget``.
    """
    side = np.linalg.norm(tri[which] - np.roll(tri[which], -1, axis=1), axis=2)
    area = 0.5 * np.linalg.norm(np.cross(tri[which, 1] - tri[which, 0], tri[which, 2] - tri[which, 0]), axis=1)
    expected = 4.0 * area / limit**2 + 2.0 * side.max(axis=1) / limit + 1.0
    by_size = np.argsort(expected, kind="stable")
    kept = np.sort(which[by_size[: int(np.searchsorted(np.cumsum(expected[by_size]), budget, side="right"))]])
    done: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    pieces, of = tri[kept], kept.astype(np.int64)
    for _ in range(MAX_BISECTIONS):
        centre = pieces.mean(axis=1)
        radius = np.linalg.norm(pieces - centre[:, None, :], axis=2).max(axis=1)
        fine = radius <= limit
        done.append((centre[fine], radius[fine], of[fine]))
        pieces, of = pieces[~fine], of[~fine]
        if not len(pieces):
            break
        side = np.linalg.norm(pieces - np.roll(pieces, -1, axis=1), axis=2)  # side k: corner k to k + 1
        k = np.argmax(side, axis=1)
        rows = np.arange(len(pieces))
        a, b, c = pieces[rows, k], pieces[rows, (k + 1) % 3], pieces[rows, (k + 2) % 3]
        mid = 0.5 * (a + b)
        pieces = np.concatenate([np.stack([a, mid, c], axis=1), np.stack([mid, b, c], axis=1)])
        of = np.concatenate([of, of])
    else:  # what is left stays as it is: still a superset
        centre = pieces.mean(axis=1)
        done.append((centre, np.linalg.norm(pieces - centre[:, None, :], axis=2).max(axis=1), of))
    centre, radius, of = (np.concatenate(part) for part in zip(*done))
    by_face = np.argsort(of, kind="stable")
    return (centre[by_face], radius[by_face], of[by_face]), kept


def crossing_pairs(mesh: Any) -> np.ndarray:
    """Pairs ``(i, j)`` of faces that cross (sharing no vertex, or one): the surface passes through itself there.

    Faces that only touch (a boolean union's touching edge, coincident
    vertices) do not count.
    """
    from medialaxis.mesh.solid._intersect_kernels import crossing_mask

    f = np.ascontiguousarray(np.asarray(mesh.faces, np.int64))
    tri, _, _ = unit_triangles(mesh.vertices, f)
    # tolerance on orientation determinants (volumes), from the typical edge
    edge = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2)
    tol = 1e-9 * float(np.median(edge)) ** 3
    pairs = candidate_pairs(tri, f)
    return pairs[crossing_mask(tri, f, pairs, tol)]
