"""The axis of an image result drawn back on the image's grid: the pixel skeleton of skimage and skan.

scikit-image's ``medial_axis(image, return_distance=True)`` gives a boolean
skeleton and a distance map; skan measures such a skeleton. :func:`to_image`
gives the same pair for a result of ours, so code written for them takes it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from medialaxis.core import graph
from medialaxis.errors import InvalidInputError

if TYPE_CHECKING:  # pragma: no cover
    from medialaxis.core.result import MedialAxis

__all__ = ["SkeletonImage", "to_image"]

#: Triangle samples per pixel along an edge when surfaces are drawn.
SAMPLES_PER_PIXEL = 3


class SkeletonImage(NamedTuple):
    """A pixel (voxel) skeleton on the input's grid.

    Attributes
    ----------
    skeleton : (rows, cols[, planes]) bool ndarray
        Pixels the axis passes through.
    distance : (rows, cols[, planes]) float64 ndarray
        The radius (physical units) at the skeleton's pixels, interpolated
        along the edges; 0 elsewhere. This is skimage's ``skeleton *
        distance``, the image skan's ``Skeleton`` reads values from.
    """

    skeleton: np.ndarray
    distance: np.ndarray


def _draw_segments(index: np.ndarray, radii: np.ndarray, edges: np.ndarray,
                   distance: np.ndarray, drawn: np.ndarray) -> None:
    """Mark the pixels of each edge (skimage's ``line_nd``) with the radius interpolated along it."""
    from skimage.draw import line_nd

    upper = np.asarray(drawn.shape) - 1
    for a, b in edges:
        pixels = np.asarray(line_nd(index[a], index[b], endpoint=True))
        count = pixels.shape[1]
        t = np.arange(count) / max(count - 1, 1)
        values = radii[a] + t * (radii[b] - radii[a])
        at = tuple(np.clip(pixels, 0, upper[:, None]))
        np.maximum.at(distance, at, values)
        drawn[at] = True


def _draw_triangles(coords: np.ndarray, radii: np.ndarray, faces: np.ndarray,
                    distance: np.ndarray, drawn: np.ndarray) -> None:
    """Mark the voxels of each triangle by barycentric samples finer than a voxel."""
    upper = np.asarray(drawn.shape) - 1
    tri = coords[faces]
    longest = np.max(np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2), axis=1)
    splits = np.maximum(1, np.ceil(longest * SAMPLES_PER_PIXEL)).astype(np.int64)
    splits = 2 ** np.ceil(np.log2(splits)).astype(np.int64)  # few groups, each drawn at once
    for n in np.unique(splits):
        group = np.flatnonzero(splits == n)
        i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
        keep = i + j <= n
        weights = np.stack([n - i[keep] - j[keep], i[keep], j[keep]], axis=1) / n  # (k, 3)
        samples = np.einsum("kv,fvd->fkd", weights, tri[group]).reshape(-1, coords.shape[1])
        values = np.einsum("kv,fv->fk", weights, radii[faces[group]]).reshape(-1)
        pixels = tuple(np.clip(np.rint(samples).astype(np.int64), 0, upper).T)
        np.maximum.at(distance, pixels, values)
        drawn[pixels] = True


def _restore_tips(thin: np.ndarray, index: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """``thin`` with the pixel of each end of the axis put back where thinning took it off a branch's tip.

    Thinning may drop an end pixel that a staircase step left beside two
    others; the branch then ends a pixel short, and skan reads it shorter
    and with a larger mean radius. The pixel goes back only where exactly
    one skeleton pixel touches it, so no junction or loop is made.
    """
    degree = graph.degree(len(index), edges)
    out = thin.copy()
    upper = np.asarray(thin.shape)
    for tip in index[degree == 1]:
        if out[tuple(tip)]:
            continue
        lo, hi = np.maximum(tip - 1, 0), np.minimum(tip + 2, upper)
        window = out[tuple(slice(a, b) for a, b in zip(lo, hi))]
        if window.sum() == 1:
            out[tuple(tip)] = True
    return out


def to_image(ma: MedialAxis) -> SkeletonImage:
    """The axis drawn on the grid of the image (or volume) it was computed from.

    Edges are drawn between the pixels of their ends with
    :func:`skimage.draw.line_nd` (a point's pixel is ``round(point /
    spacing)``); a curve axis is then thinned to one pixel with
    :func:`skimage.morphology.skeletonize`, so that pixel-skeleton tools
    (skan) find the result's branches and no clumps where edges run close
    together. Triangles of a medial surface are filled by samples a third
    of a voxel apart (not thinned); points without edges mark their pixel.

    Parameters
    ----------
    ma : MedialAxis
        A result of an image or volume input: its metadata holds
        ``image_shape`` and ``spacing``.

    Returns
    -------
    SkeletonImage
        ``(skeleton, distance)``, both of shape ``image_shape``.

    Raises
    ------
    InvalidInputError
        The result has no pixel grid (a vector input: polygon, mesh,
        drawing).

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> image = np.zeros((40, 80), bool); image[10:31, 10:70] = True
    >>> skeleton, distance = mx.medial_axis(image).to_image()
    >>> bool(skeleton[20, 40]), bool(skeleton[15, 40]), round(float(distance[20, 40]))
    (True, False, 10)
    """
    if ma.frame != "image":
        method = ma.metadata.get("method", "?")
        raise InvalidInputError(
            f"to_image() draws the axis on the input's pixel grid, and this {method!r} result came from an input "
            "without one (a polygon, a drawing, a mesh); to_shapely() or to_trimesh() give its geometry"
        )
    shape = tuple(int(s) for s in ma.metadata["image_shape"])
    if len(shape) != ma.dim:
        raise InvalidInputError(f"image_shape {shape} does not match {ma.dim}D points")
    spacing = np.broadcast_to(np.asarray(ma.metadata.get("spacing", 1.0), np.float64), (ma.dim,))
    coords = np.asarray(ma.points, np.float64) / spacing
    radii = np.asarray(ma.radii, np.float64)
    index = np.clip(np.rint(coords).astype(np.int64), 0, np.asarray(shape) - 1)
    distance = np.zeros(shape, np.float64)
    drawn = np.zeros(shape, bool)
    used = np.zeros(len(coords), bool)
    used[np.asarray(ma.edges).ravel()] = True
    used[np.asarray(ma.faces).ravel()] = True
    lone = np.flatnonzero(~used)
    if len(ma.faces):
        _draw_triangles(coords, radii, np.asarray(ma.faces, np.int64), distance, drawn)
    _draw_segments(index, radii, np.asarray(ma.edges, np.int64), distance, drawn)
    np.maximum.at(distance, tuple(index[lone].T), radii[lone])
    drawn[tuple(index[lone].T)] = True
    if not len(ma.faces) and len(ma.edges):
        from skimage.morphology import skeletonize

        drawn = _restore_tips(skeletonize(drawn), index, np.asarray(ma.edges, np.int64))
    distance[~drawn] = 0.0
    return SkeletonImage(drawn.astype(bool), distance)
