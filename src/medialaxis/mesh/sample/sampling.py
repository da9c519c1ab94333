"""Epsilon-samples of a triangle mesh surface, adaptive to local feature size.

Step 1 of Algorithm 5 of Boissonnat, Wormser and Yvinec ("Curved Voronoi
diagrams", section 2.7; docs/references.md): a point set ``P`` on the surface ``S`` with
``d_H(S, P) <= epsilon``. The sample is built from the mesh itself, not only
its vertices: every vertex, points along every edge and a barycentric grid
inside every face, with a target spacing per face. The spacing follows an
estimate of the local feature size (distance to the medial axis, inner or
outer) taken from a coarse first pass, so thin parts and concave creases get
more points than flat, thick parts.

The epsilon of the result is *measured*: the largest distance from a dense
set of check points on the surface to the nearest sample.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.errors import InvalidInputError, ResourceLimitError
from medialaxis.mesh.medial.voronoi_diagram import tetrahedralise
from medialaxis.mesh.sample._rows import first_of_rows
from medialaxis.mesh.solid.crossings import vertex_shells

__all__ = [
    "SurfaceSample",
    "sample_surface",
    "pseudo_normals",
    "measure_epsilon",
    "face_spacing_for_count",
    "lfs_estimate",
    "adaptive_spacing",
    "shell_spacing",
    "local_caps",
    "sample_count",
    "degenerate",
]

#: Samples per unit area at spacing h on a triangular lattice: 2 / (sqrt(3) h^2).
_LATTICE = 2.0 / np.sqrt(3.0)
#: Most surface samples one call may make (about 1 GB of points, normals and indices).
MAX_SURFACE_SAMPLES = 20_000_000
#: Fewest samples of the Voronoi route by default, and the most accepted.
MIN_SAMPLES = 20_000
MAX_SAMPLES = 2_000_000
#: Spacing adapts to local feature size within this ratio (finest : coarsest).
ADAPTIVE_RANGE = 4.0
#: Fewest samples on each connected piece of the surface (a shell): a piece
#: smaller than the spacing (a part of a tenth of the spacing, a chip a
#: boolean left apart) is sampled at least this densely, so that the
#: Delaunay step resolves it; larger pieces have more samples already.
MIN_SHELL_SAMPLES = 50
#: A sample whose Delaunay tetrahedralisation has more tetrahedra per point than this is in
#: cospherical groups (a regular mesh's: float32 tori of 12.8k and 40k vertices 11.9 and 18.2;
#: 54 real models 6.1-6.9, the uv ellipsoid 9.3): it is taken again with its edge and face points
#: moved by up to ``JITTER`` of their spacing, at random (seeded: ``JITTER_SEED``); see :func:`_face_points`.
DEGENERATE_TETRAHEDRA = 10.0
JITTER = 0.1
JITTER_SEED = 20261128
#: Cell of the grids that thin the medial points of the local feature size
#: estimate, relative to their radius (see :func:`lfs_estimate`).
LFS_CELL = 0.05


@dataclasses.dataclass(frozen=True)
class SurfaceSample:
    """Points on a mesh surface with their outward normals.

    Attributes
    ----------
    points : (p, 3) float64 ndarray
    normals : (p, 3) float64 ndarray
        Unit outward normal (angle-weighted pseudo-normal at vertices, mean
        of the two faces on edges, the face normal inside faces).
    face : (p,) int64 ndarray
        One mesh face each sample lies on.
    """

    points: np.ndarray
    normals: np.ndarray
    face: np.ndarray


@dataclasses.dataclass(frozen=True)
class PseudoNormals:
    """Angle-weighted pseudo-normals of a closed mesh (Baerentzen and Aanaes 2005).

    Attributes
    ----------
    face : (f, 3) float64 ndarray
    vertex : (v, 3) float64 ndarray
    edge : (e, 3) float64 ndarray
        Per unique edge (``mesh.edges_unique``).
    face_edges : (f, 3) int64 ndarray
        Unique edge index of face edges ab, bc, ca.
    """

    face: np.ndarray
    vertex: np.ndarray
    edge: np.ndarray
    face_edges: np.ndarray


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-300)


def pseudo_normals(mesh: Any) -> PseudoNormals:
    """Face, angle-weighted vertex and edge pseudo-normals of ``mesh``."""
    v = np.asarray(mesh.vertices, np.float64)
    f = np.asarray(mesh.faces, np.int64)
    fn = _unit(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]))
    angles = np.asarray(mesh.face_angles, np.float64)
    vn = np.zeros_like(v)
    for k in range(3):
        np.add.at(vn, f[:, k], fn * angles[:, k : k + 1])
    # trimesh orders faces_unique_edges as (ab, bc, ca)
    fe = np.asarray(mesh.faces_unique_edges, np.int64)
    en = np.zeros((len(mesh.edges_unique), 3))
    for k in range(3):
        np.add.at(en, fe[:, k], fn)
    return PseudoNormals(fn, _unit(vn), _unit(en), fe)


def _edge_points(
    v: np.ndarray, edges: np.ndarray, counts: np.ndarray, rng: np.random.Generator | None
) -> tuple[np.ndarray, np.ndarray]:
    """Interior points splitting each edge into ``counts`` equal parts (each moved along it by up to
    ``JITTER`` of a part, given ``rng``), and their edge index."""
    inner = np.maximum(counts - 1, 0)
    owner = np.repeat(np.arange(len(edges)), inner)
    if len(owner) == 0:
        return np.empty((0, 3)), owner
    start = np.cumsum(inner) - inner
    step = np.arange(len(owner)) - start[owner] + 1.0
    if rng is not None:
        step += JITTER * rng.uniform(-1.0, 1.0, len(owner))
    t = (step / counts[owner])[:, None]
    return v[edges[owner, 0]] * (1 - t) + v[edges[owner, 1]] * t, owner


def _face_points(
    tri: np.ndarray, spacing: np.ndarray, rng: np.random.Generator | None
) -> tuple[np.ndarray, np.ndarray]:
    """Interior points of each face, as many as its area needs at ``spacing``, and their face index.

    The points of a face follow the R2 low-discrepancy sequence (Roberts
    2018) folded into the triangle, so they spread evenly whatever the
    triangle's shape. Given ``rng`` (a degenerate sample, see below), each
    is moved within its face by up to ``JITTER`` of the spacing along each
    of its two sides from the first corner (a point the move would take
    out of the face stays).

    Every face starts the sequence at the same point, and edges are split
    into equal parts, on purpose: the sample of a symmetric mesh is then
    symmetric too, and the errors of its Voronoi vertices cancel about the
    axis. A start and an edge shift that differ from face to face (tried on
    2026-11-28) broke up the uv ellipsoid's cospherical rings (2.06M -> 1.67M
    tetrahedra, 15% faster) but scattered the vertices: a capsule's axis
    up to 5.3% of its radius off its segment (3% allowed), a sphere's
    compact points up to 9.4% of its radius from its centre (6.8% allowed).
    A smaller move (tried on 2026-11-28): edge points along their edge and
    face points within their face by up to a tenth of the spacing, vertices
    kept. It breaks the cospherical fans of regular meshes (a 40k-vertex
    float32 torus: 985k -> 581k tetrahedra, a 638k -> 275k-point full
    complex, the default call 1.15 -> 0.69 GB and 7.0 -> 4.0 s) and keeps
    the axes of a capsule, a sphere and a torus within the figures above,
    but a spheroid's simplified tip ball came 0.19 from its pole (0.177
    exact, 0.005 allowed), two of its balls touched one side; a fiftieth
    still left one. On the 54 real models, whose samples are in general
    position already, it added 11% tetrahedra. So the move is made only
    where the sample is degenerate, by the count of its tetrahedra
    (``DEGENERATE_TETRAHEDRA``), which the spheroid's (6.5) is not.
    """
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    counts = np.floor(_LATTICE * area / spacing**2).astype(np.int64)
    owner = np.repeat(np.arange(len(tri)), counts)
    if len(owner) == 0:
        return np.empty((0, 3)), owner
    step = np.arange(len(owner)) - np.repeat(np.cumsum(counts) - counts, counts)
    phi = 1.324717957244746
    u = np.mod(0.5 + step / phi, 1.0)
    v = np.mod(0.5 + step / phi**2, 1.0)
    fold = u + v > 1.0
    u[fold], v[fold] = 1.0 - u[fold], 1.0 - v[fold]
    if rng is not None:  # in units of each side's length
        reach = JITTER * spacing[owner] * rng.uniform(-1.0, 1.0, (2, len(owner)))
        side = [np.maximum(np.linalg.norm(tri[owner, k] - tri[owner, 0], axis=1), 1e-300) for k in (1, 2)]
        du, dv = reach[0] / side[0], reach[1] / side[1]
        inside = (u + du > 0.0) & (v + dv > 0.0) & (u + du + v + dv < 1.0)
        u, v = np.where(inside, u + du, u), np.where(inside, v + dv, v)
    a = tri[owner, 0]
    return a + u[:, None] * (tri[owner, 1] - a) + v[:, None] * (tri[owner, 2] - a), owner


def face_spacing_for_count(areas: np.ndarray, relative: np.ndarray, count: int) -> np.ndarray:
    """Per-face spacing ``s * relative`` with ``s`` chosen so about ``count`` samples result."""
    density = (_LATTICE * areas / relative**2).sum()
    scale = np.sqrt(density / max(count, 1))
    return scale * relative


def sample_surface(
    mesh: Any, spacing: np.ndarray, normals: PseudoNormals | None = None, *, limit: int = MAX_SURFACE_SAMPLES,
    jitter: bool = False,
) -> SurfaceSample:
    """Sample a mesh with a target spacing per face.

    Parameters
    ----------
    mesh : trimesh.Trimesh
        A closed, consistently oriented mesh.
    spacing : (f,) float64 ndarray
        Target distance between neighbouring samples on each face.
    normals : PseudoNormals, optional
        Precomputed pseudo-normals.
    limit : int
        Most samples made; more is refused before any is made.
    jitter : bool
        Move the edge and face points a little, at random (seeded): for a
        sample that :func:`degenerate` found in cospherical groups.

    Returns
    -------
    SurfaceSample
        Every vertex, edge points at the finer spacing of the edge's two
        faces, and interior face points.
    """
    pn = pseudo_normals(mesh) if normals is None else normals
    v = np.asarray(mesh.vertices, np.float64)
    f = np.asarray(mesh.faces, np.int64)
    edges = np.asarray(mesh.edges_unique, np.int64)
    edge_len = np.linalg.norm(v[edges[:, 0]] - v[edges[:, 1]], axis=1)
    edge_h = np.full(len(edges), np.inf)
    edge_face = np.zeros(len(edges), np.int64)
    for k in range(3):
        np.minimum.at(edge_h, pn.face_edges[:, k], spacing)
        edge_face[pn.face_edges[:, k]] = np.arange(len(f))
    edge_counts = np.maximum(np.round(edge_len / edge_h), 1.0)
    tri = v[f]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    planned = float((edge_counts - 1.0).sum()) + float(np.floor(_LATTICE * area / spacing**2).sum()) + len(v)
    if not planned <= min(limit, MAX_SURFACE_SAMPLES):
        raise ResourceLimitError(
            f"sampling the surface at this spacing needs {planned:.3g} points (at most {min(limit, MAX_SURFACE_SAMPLES):,}): "
            "some edges are far longer than the faces are wide (a needle, a spike or a stray vertex?)"
        )
    rng = np.random.default_rng(JITTER_SEED) if jitter else None  # the same mesh and spacing, the same sample
    ep, eo = _edge_points(v, edges, edge_counts.astype(np.int64), rng)
    fp, fo = _face_points(tri, spacing, rng)
    vertex_face = np.zeros(len(v), np.int64)
    vertex_face[f.ravel()] = np.repeat(np.arange(len(f)), 3)
    points = np.concatenate([v, ep, fp])
    normal = np.concatenate([pn.vertex, pn.edge[eo], pn.face[fo]])
    face = np.concatenate([vertex_face, edge_face[eo], fo])
    # Drop coincident samples (within 1e-9 of the spacing): the Delaunay step would join them by slivers.
    grid = np.round(points / (1e-9 * float(np.min(spacing)))).astype(np.int64)
    first = first_of_rows(grid)
    return SurfaceSample(points[first], normal[first], face[first])


def degenerate(tetrahedra: int, points: int) -> bool:
    """Whether a sample's Delaunay tetrahedralisation is in cospherical fans (``DEGENERATE_TETRAHEDRA``)."""
    return tetrahedra > DEGENERATE_TETRAHEDRA * points


def random_surface_points(mesh: Any, count: int, rng: np.random.Generator) -> np.ndarray:
    """``count`` points uniformly distributed by area on the surface."""
    v = np.asarray(mesh.vertices, np.float64)
    f = np.asarray(mesh.faces, np.int64)
    area = np.asarray(mesh.area_faces, np.float64)
    face = rng.choice(len(f), size=count, p=area / area.sum())
    u = rng.random((count, 2))
    flip = u.sum(axis=1) > 1
    u[flip] = 1 - u[flip]
    a, b, c = v[f[face, 0]], v[f[face, 1]], v[f[face, 2]]
    return a + u[:, :1] * (b - a) + u[:, 1:] * (c - a)


def measure_epsilon(
    mesh: Any, points: np.ndarray, rng: np.random.Generator, count: int, lfs: Any = None
) -> tuple[float, float]:
    """Measured sampling density: ``max d(x, P)`` over ``count`` random surface points ``x``.

    Returns
    -------
    epsilon : float
        Absolute: an estimate of ``d_H(S, P)`` from below (a maximum over check points).
    epsilon_lfs : float
        The same relative to the local feature size, ``max d(x, P) / lfs(x)``,
        when ``lfs`` (a callable on points) is given, else ``nan``.
    """
    check = random_surface_points(mesh, count, rng)
    dist, _ = cKDTree(points).query(check, workers=-1)
    eps = float(dist.max()) if len(dist) else 0.0
    sub = slice(None, 20_000)  # the relative figure on a subset: lfs queries are slower
    rel = float(np.max(dist[sub] / np.maximum(lfs(check[sub]), 1e-300))) if lfs is not None else float("nan")
    return eps, rel


def lfs_estimate(mesh: Any, count: int, normals: PseudoNormals) -> cKDTree:
    """Tree of approximate medial points (inner and outer) from a coarse sample.

    The coarse sample (about ``count`` points) is the structured sample at a
    uniform spacing ``h``, thinned to one point per grid cell of size ``h``
    so that dense meshes (whose vertices are always sampled) stay cheap. The
    medial points are thinned too, keeping the smallest ball of each grid
    cell of ``LFS_CELL`` times its radius rounded down to a power of two
    times ``h`` (the radius is at least ``h``), so a distance to them grows
    by at most ``sqrt(3) LFS_CELL`` of that radius (0.09), which the
    distance from the surface is at least: they crowd on the axis of
    rounded parts, where nearest-neighbour queries from the surface, nearly
    equidistant from them all, cost a k-d tree most (3.3 s instead of
    0.25 s for the faces of a 99k-vertex uv ellipsoid). A coarser grid
    (0.1, first point of each cell) cost the simplified medial meshes of
    ``benchmarks/bench_simplify.py`` 0.2 points of median error (1.61%
    against 1.39% unthinned; 1.40% now).
    """
    area = np.asarray(mesh.area_faces, np.float64)
    h = face_spacing_for_count(area, np.ones(len(area)), count)
    # About ``count`` points are wanted; far more means needle-like faces.
    points = sample_surface(mesh, h, normals, limit=len(mesh.vertices) + 100 * count).points
    dt = tetrahedralise(points[first_of_rows(np.floor(points / h[0]).astype(np.int64))])
    diag = float(np.linalg.norm(np.ptp(np.asarray(mesh.vertices), axis=0)))
    medial = (dt.longest >= 2.0 * h[0]) & (dt.radii < diag) & (6.0 * dt.volume > 1e-6 * h[0] ** 3)
    if medial.sum() < 4:
        medial = dt.radii < diag
    by_radius = np.flatnonzero(medial)[np.argsort(dt.radii[medial], kind="stable")]
    centres, radii = dt.centres[by_radius], dt.radii[by_radius]
    level = np.floor(np.log2(np.maximum(radii, h[0]) / h[0]))
    cell = (LFS_CELL * h[0]) * 2.0**level
    key = np.c_[level, np.floor(centres / cell[:, None])].astype(np.int64)
    # the smallest ball of each cell (the nearest to the surface); a sliding-midpoint tree without
    # shrunk node boxes answers these queries from afar fastest (the torus's faces 0.54 -> 0.34 s)
    return cKDTree(centres[first_of_rows(key)], balanced_tree=False, compact_nodes=False)


def adaptive_spacing(mesh: Any, tree: cKDTree, count: int) -> np.ndarray:
    """Per-face spacing for about ``count`` samples, following the distance to the points of ``tree``.

    The local feature size at each face centroid (distance to the nearest
    medial point of :func:`lfs_estimate`) is clipped to within
    ``ADAPTIVE_RANGE`` of its area-weighted median, then scaled. A piece of
    the surface too small for ``MIN_SHELL_SAMPLES`` at that spacing gets a
    finer one (:func:`shell_spacing`).
    """
    centroids = np.asarray(mesh.triangles_center, np.float64)
    lfs, _ = tree.query(centroids, workers=-1)
    area = np.asarray(mesh.area_faces, np.float64)
    order = np.argsort(lfs)
    median = lfs[order][np.searchsorted(np.cumsum(area[order]), 0.5 * area.sum())]
    rel = np.clip(lfs, median / ADAPTIVE_RANGE, median)
    return shell_spacing(mesh, face_spacing_for_count(area, rel, count))


def shell_spacing(mesh: Any, spacing: np.ndarray) -> np.ndarray:
    """Per-face ``spacing``, finer on the pieces of the surface it would give fewer than ``MIN_SHELL_SAMPLES``.

    The local feature size of :func:`lfs_estimate` comes from a coarse sample
    that misses pieces smaller than its own spacing. Pieces are the
    components of the faces joined at their vertices; a piece's spacing is
    never finer than its edges' total length over ``MIN_SHELL_SAMPLES`` (a
    needle-thin piece gets no more points along its edges than that).
    """
    faces = np.asarray(mesh.faces, np.int64)
    n, shell = vertex_shells(len(mesh.vertices), faces)
    if n < 2:
        return spacing
    area = np.bincount(shell, np.asarray(mesh.area_faces, np.float64), n)
    tri = np.asarray(mesh.vertices, np.float64)[faces]
    half_perimeter = 0.5 * np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2).sum(axis=1)
    edge_length = np.bincount(shell, half_perimeter, n)  # each edge once on a closed piece
    wanted = np.maximum(np.sqrt(_LATTICE * area / MIN_SHELL_SAMPLES), edge_length / MIN_SHELL_SAMPLES)
    return np.minimum(spacing, wanted[shell])


def local_caps(mesh: Any, spacing: np.ndarray, centres: np.ndarray, reach: np.ndarray, caps: np.ndarray) -> np.ndarray:
    """Per-face ``spacing``, at most ``caps[i]`` on the faces within ``reach[i]`` of ``centres[i]``.

    Examples
    --------
    >>> import trimesh
    >>> box = trimesh.creation.box()
    >>> h = local_caps(box, np.ones(12), np.array([[0.5, 0.0, 0.0]]), np.array([0.1]), np.array([0.25]))
    >>> int((h == 0.25).sum()), float(h.max())
    (2, 1.0)
    """
    from trimesh.triangles import closest_point

    tri = np.asarray(mesh.triangles, np.float64)
    mid = tri.mean(axis=1)
    size = float(np.linalg.norm(tri - mid[:, None], axis=2).max(initial=0.0))
    spacing = np.array(spacing, np.float64, copy=True)
    near = cKDTree(mid).query_ball_point(np.asarray(centres, np.float64), np.asarray(reach) + size)
    for i, faces in enumerate(near):
        faces = np.asarray(faces, np.int64)
        if len(faces):
            dist = np.linalg.norm(closest_point(tri[faces], np.broadcast_to(centres[i], (len(faces), 3))) - centres[i], axis=1)
            faces = faces[dist <= reach[i]]
            spacing[faces] = np.minimum(spacing[faces], caps[i])
    return spacing


def sample_count(samples: Any, n_vertices: int) -> int:
    """The sample count asked for, checked; by default ``max(MIN_SAMPLES, n_vertices)``."""
    if samples is None:
        return int(min(max(MIN_SAMPLES, n_vertices), MAX_SAMPLES))
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)):
        raise InvalidInputError(f"samples must be an integer number of surface samples, got {samples!r}")
    if samples < 1000 or samples > MAX_SAMPLES:
        raise (ResourceLimitError if samples > MAX_SAMPLES else InvalidInputError)(
            f"samples must be between 1000 and {MAX_SAMPLES}, got {samples}"
        )
    return int(samples)
