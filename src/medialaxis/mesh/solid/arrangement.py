"""The surface of the solid a self-intersecting or multi-shell mesh bounds, by generalized winding number.

A closed mesh whose faces cross, or whose shells overlap or nest, still
defines a solid: the points where its winding number is at least 1/2
(Jacobson et al. 2013). Its surface is made of pieces of the mesh: each face
that meets another is cut along the intersection segments (the mesh
arrangement of Zhou et al. 2016, in exact rational arithmetic as theirs:
:mod:`medialaxis.mesh.solid._exact_cut`, so that a point found from several pairs
of faces is one point and the pieces close up), and each piece is kept when
the winding number is at least 1/2 behind it and below 1/2 in front of it
(turned over when it is the other way round), or dropped (faces inside the
solid or outside it). Pieces of coplanar faces that overlap with the same
orientation are kept once, coincident faces of opposite orientation (parts
touching face to face) cancel. Faces no other face meets keep their
vertices; pieces that round to zero area are flipped or collapsed away
(:mod:`medialaxis.mesh.solid.degenerate`).

References
----------
.. [1] Jacobson, Kavan, Sorkine-Hornung, "Robust inside-outside segmentation using
       generalized winding numbers", ACM Transactions on Graphics 32(4):33:1-33:12 (Proc.
       SIGGRAPH), 2013. doi:10.1145/2461912.2461916
.. [2] Zhou, Grinspun, Zorin, Jacobson, "Mesh arrangements for solid geometry", ACM
       Transactions on Graphics 35(4):39:1-39:15 (Proc. SIGGRAPH), 2016.
       doi:10.1145/2897824.2925901
"""

from __future__ import annotations

import dataclasses

import numpy as np
import shapely
from scipy import sparse
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from medialaxis.errors import InvalidInputError
from medialaxis.mesh.solid._exact_cut import ExactCut
from medialaxis.mesh.solid.crossings import candidate_pairs, unit_triangles, winding_numbers
from medialaxis.mesh.solid.degenerate import coordinate_accuracy, remove_degenerate_faces

__all__ = ["SolidSurface", "solid_surface"]

#: Vertices closer than this (in units of the mesh's size, raised to the
#: accuracy of its coordinates) are one vertex before the exact cut.
TOLERANCE = 1e-9
#: Where the winding number on a piece is ambiguous (a coplanar face over
#: it), it is taken this fraction of the piece's inradius in front and behind.
OFFSET = 0.05
#: Solid-angle terms (patches times faces) summed one by one at most; beyond, the
#: patches' winding numbers come through the fast winding tree (Barill et al. 2018):
#: 70 s -> 2 s on a uv ellipsoid of 198,912 faces crossing in 20,704 pairs at its poles.
EXACT_TERMS = 200_000_000


@dataclasses.dataclass(frozen=True)
class SolidSurface:
    """The closed surface of the solid ``{winding number >= 1/2}`` of a mesh.

    Attributes
    ----------
    vertices : (n, 3) float64 ndarray
    faces : (m, 3) int64 ndarray
        Outward.
    cut_faces : int
        Faces of the input cut along where other faces meet them.
    dropped_faces, flipped_faces : int
        Input faces (or all their pieces) left out as lying inside or
        outside the solid, and turned over.
    """

    vertices: np.ndarray
    faces: np.ndarray
    cut_faces: int
    dropped_faces: int
    flipped_faces: int


def _unit_normal(t: np.ndarray) -> np.ndarray:
    n = np.cross(t[1] - t[0], t[2] - t[0])
    return n / (np.linalg.norm(n) or 1.0)


def _frame(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Origin and (2, 3) axes of the plane of ``t``, right-handed with its normal."""
    u = t[1] - t[0]
    u = u / np.linalg.norm(u)
    v = np.cross(_unit_normal(t), u)
    return t[0], np.stack([u, v])


def _weld(points: np.ndarray, first_new: int, tol: float) -> np.ndarray:
    """Map of each point to the one it merges with: new points within ``tol`` of another (the lowest id stays)."""
    label = np.arange(len(points))
    pairs = cKDTree(points).query_pairs(tol, output_type="ndarray")
    pairs = pairs[pairs.max(axis=1) >= first_new]  # the mesh's own coincident vertices stay apart
    if len(pairs):
        graph = sparse.coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(points),) * 2)
        _, comp = connected_components(graph, directed=False)
        lowest = np.full(comp.max() + 1, len(points))
        np.minimum.at(lowest, comp, np.arange(len(points)))
        label = lowest[comp]
    return label


def _sides(tri: np.ndarray, parent: np.ndarray, all_tri: np.ndarray, beside: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Winding numbers just behind and in front of each triangle (a piece of input face ``parent``).

    At the centroid itself, the other faces' winding number is their mean
    over both sides, a half-integer where the mesh is closed: behind is
    half more, in front half less, however close another sheet passes (a
    fold through a neighbour at a small angle). Where it is not a
    half-integer (a coplanar face over the piece, a gap), the winding
    number is taken a fraction of the inradius behind and in front.
    """
    from medialaxis.mesh.solid._fast_winding_kernels import WindingTree
    from medialaxis.mesh.solid._winding_kernels import own_terms, winding_numbers_without

    c = tri.mean(axis=1)
    all_tri, parent = np.ascontiguousarray(all_tri, np.float64), np.ascontiguousarray(parent, np.int64)
    if len(c) * len(all_tri) <= EXACT_TERMS:
        mean = winding_numbers_without(c, all_tri, parent)
    else:  # the tree's leaves sum the same terms exactly near each centroid, its own face's among them
        mean = WindingTree(all_tri)(c) - own_terms(c, all_tri, parent)
    behind, front = mean + 0.5, mean - 0.5
    off = (np.abs(mean - np.floor(mean) - 0.5) > 0.25) | beside
    if off.any():
        t = tri[off]
        e = np.linalg.norm(t - np.roll(t, 1, axis=1), axis=2)
        n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        twice_area = np.linalg.norm(n, axis=1)
        n = n / np.maximum(twice_area, 1e-300)[:, None]
        step = OFFSET * twice_area / e.sum(axis=1)  # a fraction of the inradius
        w = winding_numbers(np.vstack([c[off] - step[:, None] * n, c[off] + step[:, None] * n]), all_tri)
        behind[off], front[off] = w[: len(t)], w[len(t) :]
    return behind, front


def solid_surface(vertices: np.ndarray, faces: np.ndarray, accuracy: float = 0.0) -> SolidSurface:
    """The outward closed surface of ``{winding number >= 1/2}`` of a closed mesh.

    Parameters
    ----------
    vertices : (n, 3) float ndarray
    faces : (m, 3) int ndarray
    accuracy : float
        Accuracy of the coordinates (the tolerance of the cut is at least this).

    Raises
    ------
    InvalidInputError
        No solid (the winding number is below 1/2 everywhere).
    """
    tri, centre, size = unit_triangles(vertices, faces)
    unit_vertices = (np.asarray(vertices, np.float64) - centre) / size
    tol = max(TOLERANCE, 4.0 * accuracy / size)
    # coincident vertices are one point of the solid's surface (where the curve of a crossing meets them)
    faces = np.ascontiguousarray(_weld(unit_vertices, 0, tol)[np.asarray(faces, np.int64)])
    pairs = candidate_pairs(tri, faces)
    if len(pairs):
        from medialaxis.mesh.solid._intersect_kernels import may_meet

        pairs = pairs[may_meet(tri, faces, pairs, 1e-12)]
    involved = np.unique(pairs)
    cuts = ExactCut(np.asarray(vertices, np.float64), faces, np.unique(faces[involved]))
    for i, j in pairs:
        cuts.cut_pair(int(i), int(j))
    touched = {f for f, s in cuts.segments.items() if s}
    if cuts.on_edge:  # the faces on each side of an edge with points of the cut on it
        n = len(unit_vertices)
        edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
        split = np.array([u * n + v for u, v in cuts.on_edge], np.int64)
        touched.update((np.flatnonzero(np.isin(edges[:, 0] * n + edges[:, 1], split)) % len(faces)).tolist())
    pieces, parent = [], []
    for f in sorted(touched):
        cut = cuts.triangulate(f)
        pieces += cut
        parent += [f] * len(cut)
    n_vertices = len(unit_vertices)
    found = np.array([cuts.coordinates(p) for p in range(n_vertices, cuts.next_id)]).reshape(-1, 3)
    points = np.vstack([unit_vertices, (found - centre) / size])
    kept_whole = np.setdiff1d(np.arange(len(faces)), np.array(sorted(touched), np.int64))
    new_faces = np.vstack([faces[kept_whole], np.array(pieces, np.int64).reshape(-1, 3)])
    origin = np.concatenate([kept_whole, np.array(parent, np.int64)])
    new_faces, keep_flip, dropped = _select(points, new_faces, origin, cuts.covered, cuts.coplanar, tri)
    if not len(new_faces):
        if dropped:
            raise InvalidInputError("the mesh bounds no solid: its winding number is below 1/2 everywhere")
        raise InvalidInputError(f"the mesh's faces vanish at the accuracy of its size ({size:.3g} across): its details "
                                "are too small beside its extent to cut it where it passes through itself")
    out = points * size + centre
    out[:n_vertices] = np.asarray(vertices, np.float64)  # the mesh's own vertices exactly, not rescaled
    # points of the cut apart by less than the coordinates' resolution (where curves of the cut
    # nearly meet) make faces of zero area once rounded: flipped or collapsed away, the surface closed
    new_faces, _, _, _ = remove_degenerate_faces(out, new_faces, coordinate_accuracy(out))
    used, inverse = np.unique(new_faces, return_inverse=True)
    new_faces = inverse.reshape(-1, 3).astype(np.int64)
    out, new_faces = _split_pinched(out[used], new_faces)
    return SolidSurface(out, new_faces, len(touched), dropped, keep_flip)


def _split_pinched(points: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where the solid touches itself (at a vertex, along an edge) its surface made a 2-manifold.

    Each directed edge is paired with a reverse one (:func:`_twins`); the
    faces around a vertex that follow each other across paired edges are one
    fan, and a vertex of several fans becomes one vertex per fan, as a
    boolean union leaves the two sides of a touching edge apart. Faces whose
    edges do not pair up are left as they are.
    """
    twin = _twins(points, faces)
    if twin is None:
        return points, faces
    n = len(faces)
    start = faces.ravel()  # corner 3 f + k, at vertex faces[f, k], starts the edge to faces[f, k + 1]
    # corner (f, k) and the corner at the same vertex in the face across its outgoing edge
    across = (twin // 3) * 3 + (twin % 3 + 1) % 3
    graph = sparse.coo_matrix((np.ones(3 * n), (np.arange(3 * n), across)), shape=(3 * n, 3 * n))
    _, fan = connected_components(graph, directed=False)
    fans_of = np.unique(np.column_stack([start, fan]), axis=0)
    first = np.unique(fans_of[:, 0], return_index=True)[1]
    extra = np.setdiff1d(np.arange(len(fans_of)), first)  # a second, third ... fan at a vertex
    if not len(extra):
        return points, faces
    new_id = np.full(fan.max() + 1, -1)
    new_id[fans_of[extra, 1]] = len(points) + np.arange(len(extra))
    corners = new_id[fan]
    out = np.where(corners >= 0, corners, start)
    return np.vstack([points, points[fans_of[extra, 0]]]), out.reshape(-1, 3)


def _twins(points: np.ndarray, faces: np.ndarray) -> np.ndarray | None:
    """For each directed edge (corner ``3 f + k``), the reverse edge across which the solid continues.

    An edge of two faces pairs them; around an edge of more faces (solids
    touching along it), each face is paired with the reverse one next to it
    on its inner side, by the angle of the faces about the edge. ``None``
    where edges do not pair up so.
    """
    start = faces.ravel()
    end = np.roll(faces, -1, axis=1).ravel()
    m = len(points)
    key, back = start * m + end, end * m + start
    order = np.argsort(key, kind="stable")
    lo, hi = np.searchsorted(key[order], back, "left"), np.searchsorted(key[order], back, "right")
    if np.any(hi - lo != np.searchsorted(key[order], key, "right") - np.searchsorted(key[order], key, "left")):
        return None  # as many faces one way along each edge as the other
    twin = order[np.minimum(lo, len(key) - 1)]
    for e in np.flatnonzero(hi - lo > 1):
        if start[e] > end[e]:
            continue  # each edge once, from its lower vertex
        forward = order[np.searchsorted(key[order], key[e]):np.searchsorted(key[order], key[e], "right")]
        reverse = order[lo[e]:hi[e]]
        u, v = points[start[e]], points[end[e]]
        axis = (v - u) / np.linalg.norm(v - u)
        ref = None
        angles = []
        for c in np.concatenate([forward, reverse]):
            w = points[faces[c // 3, (c % 3 + 2) % 3]] - u
            w = w - axis * float(w @ axis)
            ref = w if ref is None else ref
            angles.append(np.arctan2(float(np.cross(ref, w) @ axis), float(ref @ w)))
        ring = np.concatenate([forward, reverse])[np.argsort(angles)]
        is_forward = np.isin(ring, forward)
        if np.any(is_forward == np.roll(is_forward, 1)):
            return None  # not alternating: no solid on one side of each face
        # a face u -> v has its solid on the side of smaller angle, a face v -> u on the larger
        for k in np.flatnonzero(is_forward):
            other = ring[k - 1]
            twin[ring[k]], twin[other] = other, ring[k]
    return twin


def _select(points: np.ndarray, faces: np.ndarray, origin: np.ndarray, covered: dict[int, list[int]],
            coplanar: set[int], all_tri: np.ndarray) -> tuple[np.ndarray, int, int]:
    """The faces on the solid's boundary, outward; how many input faces were turned over and left out.

    Faces are judged by patch: faces joined by an edge of exactly two faces
    have the same sides (the curves where sheets meet have edges of four
    faces, or three where a sheet ends on another).
    """
    valid = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
    faces, origin = faces[valid], origin[valid]
    if not len(faces):  # every face welded flat (coordinates far apart in scale)
        return faces, 0, len(np.unique(origin))
    parents = np.unique(origin)
    faces, origin, doubled = _coincident(faces, origin)
    n = len(faces)
    if not n:  # every face cancelled by a coincident opposite one (flat shells: a triangle soup capped face by face)
        return faces, 0, len(parents)
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    owner = np.tile(np.arange(n), 3)
    _, inverse, counts = np.unique(edges, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    order = np.argsort(inverse, kind="stable")
    two = counts[inverse[order]] == 2
    first = order[two][0::2]
    second = order[two][1::2]
    a, b = owner[first], owner[second]
    graph = sparse.coo_matrix((np.ones(len(a)), (a, b)), shape=(n, n))
    _, patch = connected_components(graph, directed=False)
    tri = points[faces]
    area = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    # each patch judged at its largest face
    order = np.lexsort((-area, patch))
    heads = order[np.r_[True, patch[order][1:] != patch[order][:-1]]]
    beside = doubled[heads] | np.isin(origin[heads], np.array(sorted(coplanar), np.int64))
    behind, front = _sides(tri[heads], origin[heads], all_tri, beside)
    status = np.zeros(patch.max() + 1, np.int8)  # 1 keep, -1 turn over, 0 leave out
    status[patch[heads]] = np.where((behind >= 0.5) & (front < 0.5), 1, np.where((front >= 0.5) & (behind < 0.5), -1, 0))
    state = status[patch]
    for f, lower in covered.items():
        state[(origin == f) & (state != 0) & _inside_any(tri, origin, f, lower, all_tri)] = 0
    out = np.where((state == -1)[:, None], faces[:, ::-1], faces)[state != 0]
    kept = np.unique(origin[state != 0])
    flipped = len(np.unique(origin[state == -1]))
    return out, flipped, len(parents) - len(kept)


def _coincident(faces: np.ndarray, origin: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Faces on the same three points (parts touching face to face) counted once: opposite ones cancel.

    Returns the faces left, their input faces, and which of them stood for
    several (the others' winding numbers are ambiguous on them).
    """
    _, group, size = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True, return_counts=True)
    group = group.ravel()
    doubled = size[group] > 1
    if not doubled.any():
        return faces, origin, doubled
    a, b, c = faces.T
    sign = np.where((a < b).astype(int) + (b < c) + (c < a) == 2, 1, -1)  # a rotation of the sorted order, or not
    net = np.zeros(len(size), np.int64)
    np.add.at(net, group, sign)
    candidate = np.flatnonzero(doubled & (sign == np.sign(net[group])))
    _, first = np.unique(group[candidate], return_index=True)
    keep = ~doubled
    keep[candidate[first]] = True
    return faces[keep], origin[keep], doubled[keep]


def _inside_any(tri: np.ndarray, origin: np.ndarray, f: int, lower: list[int], all_tri: np.ndarray) -> np.ndarray:
    """Whether each face's centroid lies in one of the (coplanar) input faces ``lower`` (only pieces of ``f`` asked)."""
    out = np.zeros(len(tri), bool)
    mine = np.flatnonzero(origin == f)
    c = tri[mine].mean(axis=1)
    for g in lower:
        origin_g, axes = _frame(all_tri[g])
        poly = shapely.Polygon((all_tri[g] - origin_g) @ axes.T)
        out[mine] |= shapely.contains_xy(poly, *((c - origin_g) @ axes.T).T)
    return out
