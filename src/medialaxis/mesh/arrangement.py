"""The surface of the solid a self-intersecting or multi-shell mesh bounds, by generalized winding number.

A closed mesh whose faces cross, or whose shells overlap or nest, still
defines a solid: the points where its winding number is at least 1/2
(Jacobson et al. 2013). Its surface is made of pieces of the mesh: each face
that meets another is cut along the intersection segments (the mesh
arrangement of Zhou et al. 2016, in floating point with a tolerance), and
each piece is kept when the winding number is at least 1/2 behind it and
below 1/2 in front of it (turned over when it is the other way round), or
dropped (faces inside the solid or outside it). Pieces of coplanar faces
that overlap with the same orientation are kept once. The pieces are welded
into one closed surface; faces no other face meets keep their vertices.

References
----------
Jacobson, Kavan, Sorkine-Hornung. Robust inside-outside segmentation using
generalized winding numbers. ACM Transactions on Graphics 32(4) (Proc.
SIGGRAPH), 33:1-33:12, 2013. doi:10.1145/2461912.2461916

Zhou, Grinspun, Zorin, Jacobson. Mesh arrangements for solid geometry. ACM
Transactions on Graphics 35(4) (Proc. SIGGRAPH), 39:1-39:15, 2016.
doi:10.1145/2897824.2925901
"""

from __future__ import annotations

import dataclasses
from collections import defaultdict

import numpy as np
import shapely
from scipy import sparse
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from medialaxis.errors import InvalidInputError
from medialaxis.mesh.crossings import candidate_pairs, unit_triangles, winding_numbers

__all__ = ["SolidSurface", "solid_surface"]

#: Tolerance of the cut (points merged, points on edges, coplanarity), in
#: units of the mesh's size; raised to the accuracy of its coordinates.
TOLERANCE = 1e-9
#: The winding number is taken this fraction of a piece's inradius in front
#: of and behind its centroid.
OFFSET = 0.05


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


class _Cuts:
    """Points, edge insertions and constraint segments of the cut, in the unit box."""

    def __init__(self, tri: np.ndarray, faces: np.ndarray, points: np.ndarray, tol: float) -> None:
        self.tri, self.faces, self.tol = tri, faces, tol
        self.points = [p for p in points]  # vertices first (their ids are the mesh's)
        self.n_vertices = len(points)
        self.segments: dict[int, list[tuple[int, int]]] = defaultdict(list)
        self.on_edge: dict[tuple[int, int], set[int]] = defaultdict(set)
        self.covered: dict[int, list[int]] = defaultdict(list)

    def point(self, x: np.ndarray, faces: tuple[int, ...]) -> int:
        """Id of point ``x`` lying on ``faces``: a corner of theirs if it is one, noted on the edges it lies on."""
        for f in faces:
            for k in range(3):
                if np.linalg.norm(self.tri[f, k] - x) <= self.tol:
                    return int(self.faces[f, k])
        pid = len(self.points)
        self.points.append(np.asarray(x, np.float64))
        for f in faces:
            for k in range(3):
                a, b = self.tri[f, k], self.tri[f, (k + 1) % 3]
                d = b - a
                t = float(np.dot(x - a, d) / np.dot(d, d))
                if 0.0 < t < 1.0 and np.linalg.norm(a + t * d - x) <= self.tol:
                    u, v = int(self.faces[f, k]), int(self.faces[f, (k + 1) % 3])
                    self.on_edge[(min(u, v), max(u, v))].add(pid)
        return pid

    def segment(self, p: np.ndarray, q: np.ndarray, into: tuple[int, ...], on: tuple[int, ...]) -> None:
        """A constraint from ``p`` to ``q`` in each face of ``into``; both points lie on the faces ``on``."""
        if np.linalg.norm(p - q) <= self.tol:
            return
        a, b = self.point(p, on), self.point(q, on)
        if a != b:
            for f in into:
                self.segments[f].append((a, b))


def _plane_section(t: np.ndarray, origin: np.ndarray, normal: np.ndarray, tol: float) -> np.ndarray:
    """Points of triangle ``t`` on the plane (its corners on it, its edges across it): 0 to 2 of them."""
    s = (t - origin) @ normal
    s[np.abs(s) <= tol] = 0.0
    out = [t[k] for k in range(3) if s[k] == 0.0]
    for k in range(3):
        m = (k + 1) % 3
        if s[k] * s[m] < 0.0:
            out.append(t[k] + (t[m] - t[k]) * (s[k] / (s[k] - s[m])))
    return np.array(out).reshape(-1, 3)


def _unit_normal(t: np.ndarray) -> np.ndarray:
    n = np.cross(t[1] - t[0], t[2] - t[0])
    return n / (np.linalg.norm(n) or 1.0)


def _frame(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Origin and (2, 3) axes of the plane of ``t``, right-handed with its normal."""
    u = t[1] - t[0]
    u = u / np.linalg.norm(u)
    v = np.cross(_unit_normal(t), u)
    return t[0], np.stack([u, v])


def _cut_pair(cuts: _Cuts, i: int, j: int) -> None:
    """Record where faces ``i`` and ``j`` meet: a segment, or for coplanar faces each one's edges within the other."""
    ti, tj = cuts.tri[i], cuts.tri[j]
    ni, nj = _unit_normal(ti), _unit_normal(tj)
    tol = cuts.tol
    if np.all(np.abs((tj - ti[0]) @ ni) <= tol) and np.all(np.abs((ti - tj[0]) @ nj) <= tol):
        _cut_coplanar(cuts, i, j)
        return
    si, sj = _plane_section(ti, tj[0], nj, tol), _plane_section(tj, ti[0], ni, tol)
    if len(si) < 2 or len(sj) < 2:
        return
    line = np.cross(ni, nj)
    line /= np.linalg.norm(line)
    pi, pj = si @ line, sj @ line
    lo = max(pi.min(), pj.min())
    hi = min(pi.max(), pj.max())
    if hi - lo <= tol:
        return
    ends = np.vstack([si, sj])
    params = np.concatenate([pi, pj])
    p, q = ends[np.argmin(np.abs(params - lo))], ends[np.argmin(np.abs(params - hi))]
    cuts.segment(p, q, (i, j), (i, j))


def _cut_coplanar(cuts: _Cuts, i: int, j: int) -> None:
    ti, tj = cuts.tri[i], cuts.tri[j]
    origin, axes = _frame(ti)
    flat_i, flat_j = shapely.Polygon((ti - origin) @ axes.T), shapely.Polygon((tj - origin) @ axes.T)
    if flat_i.intersection(flat_j).area <= cuts.tol * max(flat_i.length, flat_j.length):
        return  # they touch only
    for own, other, f in ((tj, flat_i, i), (ti, flat_j, j)):
        for k in range(3):
            a, b = own[k], own[(k + 1) % 3]
            flat = shapely.LineString([(a - origin) @ axes.T, (b - origin) @ axes.T])
            inside = flat.intersection(other)
            for piece in getattr(inside, "geoms", [inside]):
                if not isinstance(piece, shapely.LineString) or piece.length <= cuts.tol:
                    continue
                ends = np.asarray(piece.coords)[[0, -1]]
                d = (b - a) @ axes.T
                t = (ends - (a - origin) @ axes.T) @ d / float(d @ d)
                p, q = a + np.clip(t[0], 0, 1) * (b - a), a + np.clip(t[1], 0, 1) * (b - a)
                cuts.segment(p, q, (f,), (i, j))
    if float(np.dot(_unit_normal(ti), _unit_normal(tj))) > 0:
        cuts.covered[max(i, j)].append(min(i, j))  # the same surface twice: the lower face's pieces stay


def _triangulate(cuts: _Cuts, f: int, points: np.ndarray) -> list[tuple[int, int, int]]:
    """Face ``f`` cut along its constraints: triangles of point ids, oriented as the face."""
    corners = [int(x) for x in cuts.faces[f]]
    t = points[corners]
    origin, axes = _frame(t)
    ring: list[int] = []
    for k in range(3):
        u, v = corners[k], corners[(k + 1) % 3]
        extra = sorted(cuts.on_edge.get((min(u, v), max(u, v)), ()),
                       key=lambda p: float(np.dot(points[p] - points[u], points[v] - points[u])))
        ring += [u] + extra
    ids = list(dict.fromkeys(ring + [p for s in cuts.segments.get(f, ()) for p in s]))
    flat = {p: tuple((points[p] - origin) @ axes.T) for p in ids}
    lines = [shapely.LineString([flat[p] for p in ring + ring[:1]])]
    lines += [shapely.LineString([flat[a], flat[b]]) for a, b in cuts.segments.get(f, ())]
    noded = shapely.node(shapely.MultiLineString(lines))
    lookup = cKDTree(np.array([flat[p] for p in ids]))
    out = []
    for poly in shapely.get_parts(shapely.polygonize(shapely.get_parts(noded))):
        for tri in shapely.get_parts(shapely.constrained_delaunay_triangles(poly)):
            xy = np.asarray(tri.exterior.coords)[:3]
            tri_ids = []
            for pt in xy:
                dist, k = lookup.query(pt)
                if dist <= cuts.tol:
                    tri_ids.append(ids[k])
                else:  # two constraints cross inside the face (three faces meet there)
                    tri_ids.append(len(cuts.points))
                    cuts.points.append(origin + pt @ axes)
            area = (xy[1, 0] - xy[0, 0]) * (xy[2, 1] - xy[0, 1]) - (xy[1, 1] - xy[0, 1]) * (xy[2, 0] - xy[0, 0])
            if area < 0:
                tri_ids.reverse()
            out.append(tuple(tri_ids))
    return out


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


def _sides(tri: np.ndarray, all_tri: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Winding numbers just behind and in front of each triangle's centroid."""
    e = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2)
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    twice_area = np.linalg.norm(n, axis=1)
    n = n / np.maximum(twice_area, 1e-300)[:, None]
    step = OFFSET * twice_area / e.sum(axis=1)  # a fraction of the inradius
    c = tri.mean(axis=1)
    w = winding_numbers(np.vstack([c - step[:, None] * n, c + step[:, None] * n]), all_tri)
    return w[: len(tri)], w[len(tri) :]


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
        No solid (the winding number is below 1/2 everywhere), or the cut
        pieces do not close up (crossings too degenerate for a floating-point
        cut).
    """
    tri, centre, size = unit_triangles(vertices, faces)
    unit_vertices = (np.asarray(vertices, np.float64) - centre) / size
    tol = max(TOLERANCE, 4.0 * accuracy / size)
    # coincident vertices are one point of the solid's surface (where the curve of a crossing meets them)
    faces = np.ascontiguousarray(_weld(unit_vertices, 0, tol)[np.asarray(faces, np.int64)])
    pairs = candidate_pairs(tri, faces)
    if len(pairs):
        from medialaxis.mesh._intersect_kernels import planes_meet

        pairs = pairs[planes_meet(tri, faces, pairs, tol)]
    cuts = _Cuts(tri, faces, unit_vertices, tol)
    for i, j in pairs:
        _cut_pair(cuts, int(i), int(j))
    # points found twice (from two pairs) become one before the faces are cut
    points = np.array(cuts.points)
    label = _weld(points, cuts.n_vertices, tol)
    cuts.segments = defaultdict(list, {f: [(int(label[a]), int(label[b])) for a, b in s if label[a] != label[b]]
                                       for f, s in cuts.segments.items()})
    cuts.on_edge = defaultdict(set, {e: {int(label[p]) for p in s} for e, s in cuts.on_edge.items()})
    touched = set(cuts.segments)
    edge_faces = defaultdict(list)
    for f, (a, b, c) in enumerate(faces):
        for u, v in ((a, b), (b, c), (c, a)):
            edge_faces[(min(u, v), max(u, v))].append(f)
    for e in cuts.on_edge:
        touched.update(edge_faces.get(e, ()))
    pieces, parent = [], []
    for f in sorted(touched):  # reads only points found so far; appends where constraints cross inside a face
        cut = _triangulate(cuts, f, points)
        pieces += cut
        parent += [f] * len(cut)
    points = np.array(cuts.points)
    kept_whole = np.setdiff1d(np.arange(len(faces)), np.array(sorted(touched), np.int64))
    new_faces = np.vstack([faces[kept_whole], np.array(pieces, np.int64).reshape(-1, 3)])
    origin = np.concatenate([kept_whole, np.array(parent, np.int64)])
    label = _weld(points, cuts.n_vertices, tol)
    new_faces = label[new_faces]
    new_faces, keep_flip, dropped = _select(points, new_faces, origin, cuts.covered, tri)
    if not len(new_faces):
        if dropped:
            raise InvalidInputError("the mesh bounds no solid: its winding number is below 1/2 everywhere")
        raise InvalidInputError(f"the mesh's faces vanish at the accuracy of its size ({size:.3g} across): its details "
                                "are too small beside its extent to cut it where it passes through itself")
    used, inverse = np.unique(new_faces, return_inverse=True)
    out = points[used] * size + centre
    given = used < cuts.n_vertices
    out[given] = np.asarray(vertices, np.float64)[used[given]]  # the mesh's own vertices exactly, not rescaled
    return SolidSurface(out, inverse.reshape(-1, 3).astype(np.int64), len(touched), dropped, keep_flip)


def _select(points: np.ndarray, faces: np.ndarray, origin: np.ndarray,
            covered: dict[int, list[int]], all_tri: np.ndarray) -> tuple[np.ndarray, int, int]:
    """The faces on the solid's boundary, outward; how many input faces were turned over and left out.

    Faces are judged by patch: faces joined by an edge of exactly two faces
    have the same sides (the curves where sheets meet have edges of four
    faces, or three where a sheet ends on another).
    """
    valid = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
    faces, origin = faces[valid], origin[valid]
    n = len(faces)
    if not n:  # every face welded flat (coordinates far apart in scale)
        return faces, 0, len(np.unique(origin))
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
    behind, front = _sides(tri[heads], all_tri)
    status = np.zeros(patch.max() + 1, np.int8)  # 1 keep, -1 turn over, 0 leave out
    status[patch[heads]] = np.where((behind >= 0.5) & (front < 0.5), 1, np.where((front >= 0.5) & (behind < 0.5), -1, 0))
    state = status[patch]
    for f, lower in covered.items():
        state[(origin == f) & (state != 0) & _inside_any(tri, origin, f, lower, all_tri)] = 0
    out = np.where((state == -1)[:, None], faces[:, ::-1], faces)[state != 0]
    parents = np.unique(origin)
    kept = np.unique(origin[state != 0])
    flipped = len(np.unique(origin[state == -1]))
    return out, flipped, len(parents) - len(kept)


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
