"""Extension of the mid-surface to the part's free edges.

The medial surface stops about half a thickness short of a free edge: near
the end face the nearest boundary point is on that face, so no voxel pair
straddles the sheet. Kumar et al. find where the extended sheet meets the
isosurface by region growing on boundary voxels, add balls there and
recompute the medial voxels (1,190 s on their T). Here each vertex on the
mesh's free boundary is moved outward in the plane of its boundary
triangles, along a ray, to the iso-crossing of the grey values (trilinear
interpolation), and a strip of triangles joins the old boundary to the new
vertices. The cost is one short ray per boundary vertex.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import ndimage

__all__ = ["boundary_edges", "outward_directions", "march_to_iso", "extend_mesh", "sample_grey"]


def boundary_edges(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Edges used by exactly one face and the third vertex of that face.

    Returns
    -------
    edges : (b, 2) int64 ndarray
    opposite : (b,) int64 ndarray
    """
    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    opp = np.concatenate([faces[:, 2], faces[:, 0], faces[:, 1]])
    key = np.sort(e, axis=1)
    _, inverse, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    single = count[inverse.ravel()] == 1
    return key[single], opp[single]


def outward_directions(points: np.ndarray, edges: np.ndarray, opposite: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit outward direction at every vertex of the free boundary.

    For a boundary edge ``(a, b)`` of face ``(a, b, c)`` the outward
    direction is the part of ``(a + b) / 2 - c`` orthogonal to ``b - a`` (in
    the face's plane, away from it); a vertex takes the normalised sum over
    its boundary edges (several at a junction's end).

    Returns
    -------
    vertices : (k,) int64 ndarray
    directions : (k, 3) float64 ndarray
    """
    a, b = points[edges[:, 0]], points[edges[:, 1]]
    t = b - a
    t /= np.maximum(np.linalg.norm(t, axis=1, keepdims=True), 1e-12)
    w = 0.5 * (a + b) - points[opposite]
    w -= np.einsum("ij,ij->i", w, t)[:, None] * t
    w /= np.maximum(np.linalg.norm(w, axis=1, keepdims=True), 1e-12)
    vertices, inv = np.unique(edges.ravel(), return_inverse=True)
    acc = np.zeros((len(vertices), 3))
    np.add.at(acc, inv.reshape(-1, 2)[:, 0], w)
    np.add.at(acc, inv.reshape(-1, 2)[:, 1], w)
    norm = np.linalg.norm(acc, axis=1, keepdims=True)
    return vertices, np.divide(acc, norm, out=np.zeros_like(acc), where=norm > 1e-9)


def _minimum(grey: Any) -> float:
    if hasattr(grey, "sample"):
        return float(grey.minimum)
    return float(np.min(grey)) if grey.size else 0.0


def sample_grey(grey: Any, coords: np.ndarray, cval: float) -> np.ndarray:
    """Trilinear grey values at ``coords`` ((3, k) index coordinates), ``cval`` outside.

    ``grey`` is an array, or an object with ``sample(coords, cval)`` and
    ``minimum`` (a volume read block by block).
    """
    if hasattr(grey, "sample"):
        return np.asarray(grey.sample(coords, cval))
    return ndimage.map_coordinates(grey, coords, order=1, mode="constant", cval=cval)


def march_to_iso(grey: np.ndarray, iso: float, spacing: np.ndarray, start: np.ndarray, direction: np.ndarray,
                 max_length: float, step: float) -> np.ndarray:
    """Distance along each ray to the first iso-crossing (NaN when none).

    Parameters
    ----------
    grey : (Z, Y, X) ndarray
        Grey values (foreground above ``iso``); outside the array counts as background.
    start, direction : (k, 3) float64 ndarray
        Ray origins (physical units) and unit directions.
    max_length, step : float
        Longest ray and sampling step (physical units).

    Returns
    -------
    (k,) float64 ndarray
    """
    if len(start) == 0:  # a block without such rays (its samples cannot be reshaped per ray)
        return np.zeros(0)
    ts = np.arange(0.0, max_length + step, step)
    pts = start[:, None, :] + ts[None, :, None] * direction[:, None, :]
    idx = (pts / spacing).reshape(-1, 3).T
    vals = sample_grey(grey, idx, min(_minimum(grey), iso - 1.0)).reshape(len(start), -1)
    inside = vals > iso
    out = np.full(len(start), np.nan)
    first_out = np.argmax(~inside, axis=1)
    ok = inside[:, 0] & (~inside).any(axis=1)
    k = first_out[ok]
    rows = np.flatnonzero(ok)
    v0, v1 = vals[rows, k - 1], vals[rows, k]
    frac = np.clip((v0 - iso) / np.maximum(v0 - v1, 1e-12), 0, 1)
    out[rows] = ts[k - 1] + frac * step
    return out


#: A chord across the plate is trusted when its length is within this share of the plate's thickness.
CHORD_TOLERANCE = 0.4


def centre_on_chords(grey: Any, iso: float, spacing: np.ndarray, centres: np.ndarray, normals: np.ndarray,
                     reach: np.ndarray, thickness: np.ndarray) -> np.ndarray:
    """Offsets along ``normals`` that put ``centres`` on the mid-points of their chords across the plate.

    From each centre the first iso-crossings along ``+normal`` and
    ``-normal`` (within ``reach``) bound a chord of the part; its mid-point
    lies on the mid-plane of a flat plate for any direction that crosses both
    faces, so an error in the normal does not move it. An offset is 0 where a
    crossing is missing or the chord's length is not the plate's ``thickness``
    within :data:`CHORD_TOLERANCE` (a chord into a crease or another plate).

    Returns
    -------
    (k,) float64 ndarray
    """
    step = 0.25 * float(spacing.min())
    longest = float(reach.max(initial=0.0))
    both = march_to_iso(grey, iso, spacing, np.concatenate([centres, centres]), np.concatenate([normals, -normals]),
                        longest, step)
    up, down = both[:len(centres)], both[len(centres):]
    ok = np.isfinite(up) & np.isfinite(down) & (up <= reach) & (down <= reach)
    ok &= np.abs(np.nan_to_num(up + down) - thickness) <= CHORD_TOLERANCE * thickness
    return np.where(ok, 0.5 * (np.nan_to_num(up) - np.nan_to_num(down)), 0.0)


def _centred_ends(points: np.ndarray, new_points: np.ndarray, vertices: np.ndarray, directions: np.ndarray,
                  length: np.ndarray, eigen: np.ndarray, is_normal: np.ndarray, grey: Any, iso: float,
                  spacing: np.ndarray, reach: np.ndarray, thickness: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The extended vertices of one sheet and their new vertices moved onto their chords' mid-points.

    A free edge's vertex mixes in points of the end face and its faces tilt
    near it: the ray's end, several voxels out, would leave the mid-plane by
    the tilt. The new vertex takes the offset of the chord one voxel inside
    the end face (at the end face itself the chord vanishes).
    """
    one = is_normal.sum(axis=1) == 1
    rows = np.flatnonzero(one)
    normal = np.einsum("kij,kj->ki", eigen[rows], is_normal[rows].astype(np.float64))
    v = vertices[rows]
    inside = np.maximum(length[rows] - float(spacing.max()), 0.5 * length[rows])
    centres = np.concatenate([points[v], points[v] + inside[:, None] * directions[rows]])
    offsets = centre_on_chords(grey, iso, spacing, centres, np.concatenate([normal, normal]),
                               np.concatenate([reach[v], reach[v]]), np.concatenate([thickness[v], thickness[v]]))
    points = points.copy()
    new_points = new_points.copy()
    points[v] += offsets[:len(v)][:, None] * normal
    new_points[rows] += offsets[len(v):][:, None] * normal  # the chord was measured on the ray before the move
    return points, new_points


#: Largest |cos| between an extension ray and the normal of a face at its vertex.
MAX_NORMAL_COMPONENT = 0.35


def _max_normal_component(points: np.ndarray, faces: np.ndarray, vertices: np.ndarray, directions: np.ndarray,
                          plane_normals: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    from medialaxis.volume.sheet.dents import face_normals

    normals = face_normals(points, faces)
    slot = np.full(len(points), -1, np.int64)
    slot[vertices] = np.arange(len(vertices))
    out = np.zeros(len(vertices))
    for corner in range(3):
        s = slot[faces[:, corner]]
        has = s >= 0
        cos = np.abs(np.einsum("ij,ij->i", normals[has], directions[s[has]]))
        np.maximum.at(out, s[has], cos)
    if plane_normals is not None:
        owner, normal = plane_normals
        s = slot[owner]
        has = s >= 0
        cos = np.abs(np.einsum("ij,ij->i", normal[has], directions[s[has]]))
        np.maximum.at(out, s[has], cos)
    return out


#: Eigen-directions of the face-normal scatter at a vertex holding more than
#: this share of it are normals of a sheet through the vertex.
SHEET_NORMAL_SHARE = 0.15


def _in_sheet_planes(points: np.ndarray, faces: np.ndarray, vertices: np.ndarray,
                     directions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Directions with their components along the vertices' sheet normals removed.

    The normals are the main eigen-directions of the scatter ``sum n n^T`` of
    the unit normals of the faces at each vertex: one on a sheet, two where
    sheets meet (leaving only the junction line's direction). Returned
    vectors are not renormalised: a short one was mostly out of the sheets.
    """
    from medialaxis.volume.sheet.dents import face_normals

    normals = face_normals(points, faces)
    slot = np.full(len(points), -1, np.int64)
    slot[vertices] = np.arange(len(vertices))
    scatter = np.zeros((len(vertices), 3, 3))
    nnT = normals[:, :, None] * normals[:, None, :]
    for corner in range(3):
        s = slot[faces[:, corner]]
        has = s >= 0
        np.add.at(scatter, s[has], nnT[has])
    value, vector = np.linalg.eigh(scatter)
    total = np.maximum(value.sum(axis=1, keepdims=True), 1e-12)
    keep = value / total <= SHEET_NORMAL_SHARE  # (k, 3): eigen-directions in the sheets' planes
    coef = np.einsum("kij,ki->kj", vector, directions) * keep
    return np.einsum("kij,kj->ki", vector, coef), vector, ~keep & (value > 0)


#: A junction line's direction replaces a vertex's outward direction unless
#: they point this much apart (cosine below minus this).
LINE_AGREEMENT = 0.3


def _along_junction_lines(points: np.ndarray, faces: np.ndarray, junction: np.ndarray, vertices: np.ndarray,
                          directions: np.ndarray, tolerance: float = 0.0, reach: float | np.ndarray = 0.0,
                          outward: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Directions of junction-line ends: away from their one junction neighbour.

    The faces at a line's end belong to several sheets, and the outward
    directions of their boundary edges do not agree; the line's own direction
    does. Free-boundary vertices on the line beyond its end (within
    ``tolerance`` of it and ``reach`` of the end, one value or the end's own
    longest extension: the corners of the sheets
    there) take the line's direction too, instead of a diagonal into the
    other sheet. With ``outward`` (the boundary edges' own directions), a
    vertex keeps its direction where the line's points back into the mesh
    (a short junction piece along a crease).

    Returns
    -------
    directions : (k, 3) float64 ndarray
    on_line : (k,) bool ndarray
        Vertices that took a line's direction.
    """
    e = np.unique(np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1), axis=0)
    e = e[junction[e[:, 0]] & junction[e[:, 1]]]
    ends = np.concatenate([e, e[:, ::-1]])  # (vertex, junction neighbour)
    degree = np.bincount(ends[:, 0], minlength=len(points))
    out = directions.copy()
    taken = np.zeros(len(vertices), bool)
    slot = np.full(len(points), -1, np.int64)
    slot[vertices] = np.arange(len(vertices))
    one = ends[(degree[ends[:, 0]] == 1)]
    d = points[one[:, 0]] - points[one[:, 1]]
    d /= np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-12)
    if tolerance > 0 and len(one):
        candidates = vertices[~junction[vertices]]
        reach = np.broadcast_to(np.asarray(reach, np.float64), (len(points),))
        for end, t in zip(one[:, 0], d):
            rel = points[candidates] - points[end]
            along = rel @ t
            across = np.linalg.norm(rel - along[:, None] * t, axis=1)
            on_line = slot[candidates[(along > -tolerance) & (along <= reach[end]) & (across <= tolerance)]]
            if outward is not None:
                on_line = on_line[outward[on_line] @ t > -LINE_AGREEMENT]
            out[on_line] = t
            taken[on_line] = True
    rows = slot[one[:, 0]]
    has = rows >= 0
    if outward is not None:
        has[has] = np.einsum("ij,ij->i", outward[rows[has]], d[has]) > -LINE_AGREEMENT
    out[rows[has]] = d[has]
    taken[rows[has]] = True
    return out, taken


def extend_mesh(points: np.ndarray, faces: np.ndarray, grey: np.ndarray, iso: float, spacing: np.ndarray,
                max_length: float | np.ndarray, plane_normals: tuple[np.ndarray, np.ndarray] | None = None,
                free: np.ndarray | None = None, junction: np.ndarray | None = None,
                probe: float | np.ndarray = 0.0, chord: float | np.ndarray = 0.0,
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Extend the free boundary of a mid-surface mesh to the isosurface.

    Parameters
    ----------
    points : (v, 3) float64 ndarray
        Physical coordinates (index order times ``spacing``).
    faces : (f, 3) int64 ndarray
    grey : (Z, Y, X) ndarray
    iso : float
    spacing : (3,) float64 ndarray
    max_length : float or (v,) float64 ndarray
        Longest extension (physical units), one value or one per vertex; rays
        that do not leave the part within it are not extended.
    plane_normals : (owner (p,) int, normal (p, 3)) arrays, optional
        Sheet normals known at each vertex (e.g. of the medial voxels in its
        Voronoi region); like the normals of its faces, a ray must be nearly
        orthogonal to all of them.
    free : (v,) bool ndarray, optional
        Vertices on a free edge of the part (medial voxels classified as
        boundary). When given, only they, and vertices joined to them by a
        boundary edges (the ends of junction lines), are extended; the edges
        of small holes in the mesh are not free edges of the part.
    junction : (v,) bool ndarray, optional
        Junction vertices. A junction vertex with one junction neighbour ends
        a junction line and is extended along that line.
    probe : float or (v,) float64 ndarray, optional
        When > 0 (one value or one per vertex): a ray is kept only if, half-way to its hit and one voxel
        before it, the grey values ``probe`` away along each sheet normal at
        the vertex are background (the part ends beside the sheet there; it does not where
        a ray runs along a sheet into a crease or another plate). Rays along
        junction lines are not probed.
    chord : float or (v,) float64 ndarray, optional
        When > 0 and with ``probe``: the plate's thickness at each vertex. The
        extended vertices (of one sheet, not along a junction line) and their
        new vertices are put on the mid-point of the chord across the plate
        along the sheet normal (:func:`centre_on_chords`; at a new vertex the
        chord one voxel inside the end face).

    Returns
    -------
    points : (v + k, 3) float64 ndarray
        The input points (the extended ones centred with ``chord``) followed by the new vertices.
    faces : (f + m, 3) int64 ndarray
    source : (k,) int64 ndarray
        The boundary vertex each new vertex extends.

    References
    ----------
    .. [1] V. Kumar, T. Michikawa, H. Suzuki, "Improving medial surfaces for reverse
           engineering" (venue, year and DOI unconfirmed: docs/references.md).
    """
    edges, opposite = boundary_edges(faces)
    if len(edges) == 0:
        return points, faces, np.empty(0, np.int64)
    limit = np.broadcast_to(np.asarray(max_length, np.float64), (len(points),))
    probes = np.broadcast_to(np.asarray(probe, np.float64), (len(points),))
    vertices, outward = outward_directions(points, edges, opposite)
    directions, eigen, is_normal = _in_sheet_planes(points, faces, vertices, outward)
    in_plane = np.linalg.norm(directions, axis=1)
    directions = np.divide(directions, in_plane[:, None], out=np.zeros_like(directions), where=in_plane[:, None] > 0.5)
    along_line = np.zeros(len(vertices), bool)
    if junction is not None:
        directions, along_line = _along_junction_lines(points, faces, np.asarray(junction, bool), vertices, directions,
                                           tolerance=1.5 * float(spacing.max()), reach=limit, outward=outward)
    good = np.linalg.norm(directions, axis=1) > 0.5
    if free is not None:
        free = np.asarray(free, bool)
        reach = free.copy()
        reach[edges[free[edges[:, 1]], 0]] = True
        reach[edges[free[edges[:, 0]], 1]] = True
        good &= reach[vertices]
    # only rays in the plane of every face at the vertex: boundary edges of
    # small holes (or folds) would otherwise shoot across the plate; the small
    # faces at a junction line's end tilt, and its direction is trusted there
    tilt = _max_normal_component(points, faces, vertices, directions, plane_normals)
    good &= along_line | (tilt < MAX_NORMAL_COMPONENT)
    vertices, directions = vertices[good], directions[good]
    step = 0.25 * float(spacing.min())
    length = march_to_iso(grey, iso, spacing, points[vertices], directions, float(limit[vertices].max(initial=0.0)), step)
    grow = np.isfinite(length) & (length > 0.25 * step) & (length <= limit[vertices])
    if probes.max(initial=0.0) > 0:
        # the part must end on both sides of the sheet, half-way to the hit
        # and just before it: a ray along a sheet into a crease or another
        # plate exits through that plate's face, where the part goes on
        # beside the sheet
        along_line = along_line[good]
        reach = np.nan_to_num(length)
        # every probe point in one call (a volume read by blocks reads each block once)
        probe_points = [(inner + sign * probes[vertices][:, None] * eigen[good][:, :, k]) / spacing
                        for inner in (points[vertices] + 0.5 * reach[:, None] * directions,
                                      points[vertices] + np.maximum(reach - float(spacing.max()), 0)[:, None] * directions)
                        for k in range(3) for sign in (1.0, -1.0)]
        values = sample_grey(grey, np.concatenate(probe_points).T, iso - 1.0).reshape(len(probe_points), -1)
        for row in range(len(probe_points)):
            k = (row // 2) % 3
            if row % 2 == 0:
                use = is_normal[good][:, k] & grow & ~along_line & (probes[vertices] > 0)
            grow &= ~(use & (values[row] > iso))
    vertices, directions, length = vertices[grow], directions[grow], length[grow]
    new_points = points[vertices] + length[:, None] * directions
    chords = np.broadcast_to(np.asarray(chord, np.float64), (len(points),))
    if probes.max(initial=0.0) > 0 and chords.max(initial=0.0) > 0:
        points, new_points = _centred_ends(points, new_points, vertices, directions, length,
                                           eigen[good][grow], is_normal[good][grow] & ~along_line[grow][:, None],
                                           grey, iso, spacing, probes, chords)
    new_index = np.full(len(points), -1, np.int64)
    new_index[vertices] = len(points) + np.arange(len(vertices))
    a, b = edges[:, 0], edges[:, 1]
    a2, b2 = new_index[a], new_index[b]
    both = (a2 >= 0) & (b2 >= 0)
    all_points = np.concatenate([points, new_points])
    # split each quad (a, b, b2, a2) across its shorter diagonal
    d_ab2 = np.linalg.norm(all_points[a[both]] - all_points[b2[both]], axis=1)
    d_ba2 = np.linalg.norm(all_points[b[both]] - all_points[a2[both]], axis=1)
    use = d_ab2 <= d_ba2
    qa, qb, qa2, qb2 = a[both], b[both], a2[both], b2[both]
    tri = [
        np.stack([qa, qb, qb2], 1)[use], np.stack([qa, qb2, qa2], 1)[use],
        np.stack([qa, qb, qa2], 1)[~use], np.stack([qb, qb2, qa2], 1)[~use],
    ]
    only_a = (a2 >= 0) & (b2 < 0)
    only_b = (b2 >= 0) & (a2 < 0)
    tri += [np.stack([a[only_a], b[only_a], a2[only_a]], 1), np.stack([a[only_b], b[only_b], b2[only_b]], 1)]
    return all_points, np.concatenate([faces, *tri]).astype(np.int64), vertices
