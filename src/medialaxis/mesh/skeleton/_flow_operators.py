"""Discrete differential operators on triangle meshes for the diffusion flow.

Everything here is vectorised NumPy/SciPy over the face list: the cotangent
Laplacian and lumped mass, the angle-defect Gaussian curvature of Du and Qin
(SM '04, eq. 7), area-weighted vertex normals and the inward "medial poles" found by
the shrinking-ball iteration (Ma, Bae & Choi 2012), which the flow uses as an
attraction target that scales to large meshes (aimed along fitted planes'
normals on voxel staircases, :func:`robust_poles`).
"""

from __future__ import annotations

import numpy as np
from scipy import sparse
from scipy.spatial import cKDTree

from medialaxis.core.arrays import unique_ints

__all__ = [
    "cotangent_laplacian",
    "vertex_areas",
    "gaussian_curvature",
    "vertex_normals",
    "medial_poles",
    "unique_edges",
    "unique_pairs",
    "pole_targets",
    "plane_normals",
    "robust_poles",
    "on_voxel_grid",
    "grid_frames",
]

#: Cotangent weights are clipped to ``[0, MAX_COT]``: negative weights (obtuse
#: angles) would make the system indefinite, infinite ones (needle triangles,
#: which appear as the mesh collapses) would overflow.
MAX_COT = 1.0e4
#: A vertex nearer than the shrinking ball's ``ignore`` distance still stops the
#: ball when the direction to it is within acos(OPPOSITE) of the inward normal.
OPPOSITE = 0.8
#: Neighbours of the plane fit of :func:`plane_normals` (about three edge lengths around a vertex).
PLANE_NEIGHBOURS = 32
#: Share of the vertices on grid edges that makes a surface a voxel staircase (:func:`on_voxel_grid`).
LATTICE_SHARE = 0.9
#: Most shared coordinate values whose differences are tried as grid steps, and vertices looked at.
GRID_CANDIDATES, GRID_SAMPLE = 24, 20_000
#: Median tilt (degrees) of the one-ring normals from the fitted planes' that makes a grid surface a staircase:
#: 11-22 on marching-cubes rods, spheres and tori; 0 on a thin CAD plate refined on a lattice.
STAIRCASE_TILT = 5.0
#: Pairs of mesh edges whose cross products vote for the axes of a turned grid
#: (:func:`grid_frames`), the share of the votes an axis needs, and the axes tried.
FRAME_PAIRS, FRAME_VOTES, FRAME_AXES = 4000, 0.02, 6


def unique_pairs(pairs: np.ndarray) -> np.ndarray:
    """Unique rows of a non-negative int ``(m, 2)`` array (1D keys: much faster than ``axis=0``)."""
    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    if len(pairs) == 0:
        return pairs
    base = int(pairs.max()) + 1
    keys = unique_ints(pairs[:, 0] * base + pairs[:, 1])
    return np.column_stack([keys // base, keys % base])


def unique_edges(faces: np.ndarray) -> np.ndarray:
    """Sorted unique undirected edges ``(m, 2)`` of a face list ``(k, 3)``."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    e.sort(axis=1)
    return unique_pairs(e)


def _corner_cotangents(points: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Cotangent of each face corner ``(k, 3)``; corner ``c`` is opposite edge ``(c+1, c+2)``."""
    p0, p1, p2 = points[faces[:, 0]], points[faces[:, 1]], points[faces[:, 2]]
    cots = np.empty((len(faces), 3))
    for c, (a, b, o) in enumerate(((p1, p2, p0), (p2, p0, p1), (p0, p1, p2))):
        u, v = a - o, b - o
        dot = np.einsum("ij,ij->i", u, v)
        cross = np.linalg.norm(np.cross(u, v), axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            cots[:, c] = dot / cross
    cots[~np.isfinite(cots)] = MAX_COT
    return np.clip(cots, 0.0, MAX_COT)


def cotangent_laplacian(points: np.ndarray, faces: np.ndarray) -> sparse.csr_matrix:
    """Symmetric positive semi-definite cotangent Laplacian (stiffness) matrix.

    Parameters
    ----------
    points : (n, 3) float64 ndarray
    faces : (k, 3) int64 ndarray

    Returns
    -------
    (n, n) scipy.sparse.csr_matrix
        ``L[i, j] = -(cot a + cot b) / 2`` for each edge, rows summing to zero,
        so ``-L @ p`` approximates ``2 * area * mean curvature normal``.
    """
    n = len(points)
    cots = _corner_cotangents(points, faces) * 0.5
    i = np.concatenate([faces[:, 1], faces[:, 2], faces[:, 0]])
    j = np.concatenate([faces[:, 2], faces[:, 0], faces[:, 1]])
    w = np.concatenate([cots[:, 0], cots[:, 1], cots[:, 2]])
    off = sparse.coo_matrix((-w, (i, j)), shape=(n, n))
    off = (off + off.T).tocsr()
    diag = -np.asarray(off.sum(axis=1)).ravel()
    return (off + sparse.diags(diag)).tocsr()


def face_areas(points: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Triangle areas ``(k,)``."""
    p0, p1, p2 = points[faces[:, 0]], points[faces[:, 1]], points[faces[:, 2]]
    return 0.5 * np.linalg.norm(np.cross(p1 - p0, p2 - p0), axis=1)


def vertex_areas(points: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Barycentric (lumped) vertex areas ``(n,)``: a third of the incident triangle areas."""
    a = np.repeat(face_areas(points, faces) / 3.0, 3)
    return np.bincount(faces.ravel(), weights=a, minlength=len(points))


def corner_angles(points: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Interior angle at each face corner ``(k, 3)``."""
    angles = np.empty((len(faces), 3))
    for c in range(3):
        o = points[faces[:, c]]
        u = points[faces[:, (c + 1) % 3]] - o
        v = points[faces[:, (c + 2) % 3]] - o
        angles[:, c] = np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.einsum("ij,ij->i", u, v))
    return angles


def gaussian_curvature(points: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Angle-defect Gaussian curvature per vertex ``(n,)``, eq. (7) of Du and Qin [1]_.

    ``K_i = (2 pi - sum of corner angles at i) / (area of incident triangles / 3)``
    (closed surfaces only).

    References
    ----------
    .. [1] H. Du, H. Qin, "Medial axis extraction and shape manipulation of solid objects using
           parabolic PDEs", Proc. 9th ACM Symposium on Solid Modeling and Applications (SM '04),
           2004 (DOI unconfirmed).
    """
    angle_sum = np.bincount(faces.ravel(), weights=corner_angles(points, faces).ravel(), minlength=len(points))
    area = vertex_areas(points, faces)
    with np.errstate(divide="ignore", invalid="ignore"):
        k = (2.0 * np.pi - angle_sum) / area
    return np.where(area > 0, k, 0.0)


def vertex_normals(points: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Area-weighted outward unit vertex normals ``(n, 3)`` of a consistently wound mesh."""
    p0, p1, p2 = points[faces[:, 0]], points[faces[:, 1]], points[faces[:, 2]]
    fn = np.cross(p1 - p0, p2 - p0)
    normals = np.zeros_like(points)
    for c in range(3):
        np.add.at(normals, faces[:, c], fn)
    norm = np.linalg.norm(normals, axis=1, keepdims=True)
    return normals / np.where(norm > 0, norm, 1.0)


def medial_poles(
    points: np.ndarray, normals: np.ndarray, *, max_radius: float | np.ndarray, ignore: float = 0.0, iterations: int = 30,
    k: int = 16,
) -> tuple[np.ndarray, np.ndarray]:
    """Inner medial ball of every vertex by the shrinking-ball iteration.

    For a vertex ``p`` with outward normal ``n``, the ball tangent at ``p``
    with centre ``p - r n`` is shrunk until no other vertex lies inside it:
    ``r <- |p - q|^2 / (2 (p - q) . n)`` with ``q`` the vertex nearest the
    current centre (Ma, Bae & Choi, "3D medial axis point approximation using
    nearest neighbors and the normal field", 2012).

    Parameters
    ----------
    points : (n, 3) float64 ndarray
    normals : (n, 3) float64 ndarray
        Outward unit normals.
    max_radius : float or (n,) float64 ndarray
        Starting (and largest) radius, one for all or one per vertex.
    ignore : float
        Vertices closer than this to ``p`` never shrink its ball: on a
        sampled surface they only carry noise, not the opposite side
        (unless they lie nearly straight below ``p``, within acos(OPPOSITE)
        of the inward normal: the other side of a thin plate).
    iterations : int
        Upper bound on the shrinking steps.
    k : int
        Neighbours of the centre examined for one beyond ``ignore``.

    Returns
    -------
    centres : (n, 3) float64 ndarray
    radii : (n,) float64 ndarray

    References
    ----------
    .. [1] J. Ma, S. W. Bae, S. Choi, "3D medial axis point approximation using nearest
           neighbors and the normal field", The Visual Computer 28(1):7-19, 2012.
    """
    tree = cKDTree(points)
    n = len(points)
    radius = np.broadcast_to(np.asarray(max_radius, np.float64), n).copy()
    active = np.arange(n)
    for _ in range(iterations):
        if active.size == 0:
            break
        p, nrm, r = points[active], normals[active], radius[active]
        centre = p - r[:, None] * nrm
        _dist, cand = tree.query(centre, k=range(1, min(k, n) + 1), workers=-1)  # 2D even for k = 1
        rel = p[:, None, :] - points[cand]
        gap = np.linalg.norm(rel, axis=2)
        # near vertices are noise unless they lie deep below the tangent plane:
        # the other side of a plate thinner than the ignored distance
        far = (gap > ignore) | (np.einsum("qkd,qd->qk", rel, nrm) > OPPOSITE * gap)
        first = np.argmax(far, axis=1)
        q_index = cand[np.arange(len(active)), first]
        q_index = np.where(far.any(axis=1), q_index, active)
        d = p - points[q_index]
        denom = 2.0 * np.einsum("ij,ij->i", d, nrm)
        with np.errstate(divide="ignore", invalid="ignore"):
            r_new = np.einsum("ij,ij->i", d, d) / denom
        ok = (q_index != active) & np.isfinite(r_new) & (r_new > 0) & (r_new < r * (1.0 - 1e-9))
        radius[active[ok]] = r_new[ok]
        active = active[ok]
    centres = points - radius[:, None] * normals
    return centres, radius


def pole_targets(
    points: np.ndarray,
    normals: np.ndarray,
    *,
    max_radius: float,
    ignore: float,
    max_samples: int = 20000,
    neighbours: int = 8,
) -> tuple[np.ndarray, np.ndarray]:
    """Inner-ball centre and radius for every vertex, from at most ``max_samples`` samples.

    Large meshes are thinned by a grid (one sample per cell, with the cell's
    mean normal); each vertex takes the inverse-distance weighted mean of the
    balls of its ``neighbours`` nearest samples.
    The nearest-neighbour queries of the shrinking ball cost far more than the
    flow, and the flow's smoothing does not need one ball per vertex.
    """
    n = len(points)
    if n <= max_samples:
        return medial_poles(points, normals, max_radius=max_radius, ignore=ignore)
    lo = points.min(axis=0)
    cell = max(ignore / 2.0, 1e-12)
    for _ in range(30):
        keys = np.floor((points - lo) / cell).astype(np.int64)
        dims = keys.max(axis=0) + 1
        flat = (keys[:, 0] * dims[1] + keys[:, 1]) * dims[2] + keys[:, 2]
        uniq, first, inverse = np.unique(flat, return_index=True, return_inverse=True)
        if len(uniq) <= max_samples:
            break
        cell *= 1.25
    inverse = inverse.ravel()
    k = len(uniq)
    mean_normal = np.column_stack([np.bincount(inverse, weights=normals[:, d], minlength=k) for d in range(3)])
    mean_normal /= np.maximum(np.linalg.norm(mean_normal, axis=1, keepdims=True), 1e-300)
    sample_points = points[first]
    centres, radii = medial_poles(sample_points, mean_normal, max_radius=max_radius, ignore=max(ignore, 2.0 * cell))
    # average the balls of the nearest samples: one shared ball per sample
    # would carry that sample's noise to all its vertices
    dist, nearest = cKDTree(sample_points).query(points, k=min(neighbours, k))
    weight = 1.0 / (dist + 1e-3 * cell)
    weight /= weight.sum(axis=1, keepdims=True)
    return np.einsum("nk,nkd->nd", weight, centres[nearest]), np.einsum("nk,nk->n", weight, radii[nearest])


def plane_normals(points: np.ndarray, normals: np.ndarray, k: int = PLANE_NEIGHBOURS) -> np.ndarray:
    """Unit normals of the least-squares plane of each vertex's ``k`` nearest vertices, oriented as ``normals``.

    The normal at a scale of a few edge lengths: on a voxel staircase
    (marching cubes) the one-ring normals tilt by 10-40 degrees and more from the
    surface's, the plane of 32 neighbours by a few (the tangent planes of Hoppe et
    al. [1]_).

    References
    ----------
    .. [1] Hoppe, DeRose, Duchamp, McDonald, Stuetzle, "Surface reconstruction from unorganized
           points", Proc. SIGGRAPH 92, 1992. doi:10.1145/133994.134011
    """
    _, near = cKDTree(points).query(points, k=min(k, len(points)), workers=-1)
    local = points[near] - points[near].mean(axis=1, keepdims=True)
    _, vectors = np.linalg.eigh(np.einsum("nki,nkj->nij", local, local))
    fitted = vectors[:, :, 0]
    return fitted * np.where(np.einsum("ij,ij->i", fitted, normals) < 0, -1.0, 1.0)[:, None]


def _grid_of(values: np.ndarray, top: int = GRID_CANDIDATES) -> np.ndarray:
    """Which ``values`` lie on the coarsest grid ``origin + k step`` holding at least half of them.

    Candidate steps are the differences between the ``top`` values that the
    most vertices share (grid planes hold curves of vertices; interpolated
    values repeat only by symmetry); a finer grid holds what a coarser one
    does, so the coarsest that holds half the values is taken.
    """
    distinct, counts = np.unique(values, return_counts=True)
    shared = distinct[np.argsort(-counts, kind="stable")[:top]]
    scale = max(1.0, float(np.abs(values).max()))
    best_step, best = 0.0, np.zeros(len(values), bool)
    for i, origin in enumerate(shared):
        for step in np.abs(shared[i + 1 :] - origin):
            if not step > 1e-9 * scale or step <= best_step:
                continue
            t = (values - origin) / step
            on = np.abs(t - np.round(t)) <= 1e-6 * max(1.0, float(np.abs(t).max()))
            if on.mean() >= 0.5:
                best_step, best = float(step), on
    return best


def on_voxel_grid(points: np.ndarray, share: float = LATTICE_SHARE) -> bool:
    """Whether the vertices lie on the edges of a voxel grid, as marching cubes puts them.

    A marching-cubes vertex lies on an edge of the grid: exactly two of its
    coordinates are grid coordinates (:func:`_grid_of`, per axis), the third
    is interpolated. ``share`` of the vertices must be such. A CAD part
    refined on a lattice can pass too: :func:`robust_poles` tells it by its
    normals.
    """
    points = np.asarray(points, np.float64)
    if len(points) < 100:
        return False
    sample = points[:: max(1, len(points) // GRID_SAMPLE)]
    count = np.zeros(len(sample), np.int64)
    for axis in range(3):
        count += _grid_of(sample[:, axis])
    return bool(np.mean(count == 2) >= share)


def grid_frames(points: np.ndarray, faces: np.ndarray) -> list[np.ndarray]:
    """Rotations (rows: axes) that may turn the vertices back onto the voxel grid they were meshed on.

    A marching-cubes vertex lies on a grid edge, so a mesh edge joining two
    vertices on the same grid plane is exactly perpendicular to that plane's
    axis, and the cross product of two such edges is the axis, however the
    surface was turned after meshing (a scanner's direction cosines). The
    cross products of ``FRAME_PAIRS`` random pairs of mesh edges vote; the
    ``FRAME_AXES`` directions with at least ``FRAME_VOTES`` of the votes
    (on a smooth or scanned surface, none: its products all differ) give
    the frames, orthogonal pairs first found first. The caller checks each
    with :func:`on_voxel_grid`.
    """
    edges = unique_edges(np.asarray(faces, np.int64))
    if len(edges) < 100:
        return []
    vec = points[edges[:, 1]] - points[edges[:, 0]]
    rng = np.random.default_rng(0)
    i, j = rng.integers(0, len(vec), (2, FRAME_PAIRS))
    cross = np.cross(vec[i], vec[j])
    size = np.linalg.norm(cross, axis=1)
    keep = size > 0.1 * np.linalg.norm(vec[i], axis=1) * np.linalg.norm(vec[j], axis=1)  # not nearly parallel
    axis = cross[keep] / size[keep, None]
    axis *= np.where(axis[np.arange(len(axis)), np.abs(axis).argmax(axis=1)] < 0, -1.0, 1.0)[:, None]
    _, first, votes = np.unique(np.round(axis * 1e7).astype(np.int64), axis=0, return_index=True, return_counts=True)
    top = np.argsort(-votes, kind="stable")[:FRAME_AXES]
    axes = axis[first[top[votes[top] >= FRAME_VOTES * len(axis)]]]
    frames = []
    for a in range(len(axes)):
        for b in range(a + 1, len(axes)):
            if abs(float(axes[a] @ axes[b])) < 1e-6:
                frames.append(np.stack([axes[a], axes[b], np.cross(axes[a], axes[b])]))
    return frames


def _snapped(points: np.ndarray) -> np.ndarray:
    """Coordinates rounded to 1e-9 of the largest: turned back onto a grid, equal ones differ by rounding."""
    quantum = 1e-9 * max(float(np.abs(points).max()), 1e-300)
    return np.round(points / quantum) * quantum


def robust_poles(
    points: np.ndarray, normals: np.ndarray, *, max_radius: float, edge_length: float, faces: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`pole_targets`, along :func:`plane_normals` on a voxel staircase (:func:`on_voxel_grid`).

    A ball aimed along a tilted normal meets the surface beside its vertex
    and stops small: on a marching-cubes rod of radius 5 voxels, the median
    ball along the one-ring normals had radius 2.3, 3 voxels off the axis,
    and the flow skeleton grew a spur at every step of the staircase. On
    such a surface (on a grid, its one-ring normals tilted from the fitted
    planes' by more than ``STAIRCASE_TILT`` at the median) the balls are
    aimed along the fitted planes' normals and ignore the vertices within
    twice the fit's reach (the steps); elsewhere along the vertex normals,
    ignoring two edge lengths. With ``faces``, a staircase turned after
    meshing is recognized too (:func:`grid_frames`).
    """
    grid = on_voxel_grid(points) or (
        faces is not None and any(on_voxel_grid(_snapped(points @ frame.T)) for frame in grid_frames(points, faces))
    )
    if not grid:
        return pole_targets(points, normals, max_radius=max_radius, ignore=2.0 * edge_length)
    fitted = plane_normals(points, normals)
    tilt = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", fitted, normals), -1.0, 1.0)))
    if not np.median(tilt) > STAIRCASE_TILT:  # a CAD part refined on a lattice
        return pole_targets(points, normals, max_radius=max_radius, ignore=2.0 * edge_length)
    reach = float(np.sqrt(PLANE_NEIGHBOURS / np.pi)) * edge_length
    return pole_targets(points, fitted, max_radius=max_radius, ignore=2.0 * reach)
