"""The solid of a mesh whose surface cannot be cut into a closed one, contoured from its winding number.

Triangle soups (faces that do not share vertices and leave slits), shells
whose edges of three or more faces do not pair up, sheets closer than the
coordinates' accuracy: the generalized winding number still tells inside
from outside (Jacobson, Kavan, Sorkine-Hornung, "Robust inside-outside
segmentation using generalized winding numbers", ACM Transactions on
Graphics 32(4), 2013, doi:10.1145/2461912.2461916), though no surface of
the input's own faces bounds that solid. It is sampled on a grid by the fast
winding number (:mod:`medialaxis.mesh.solid._fast_winding_kernels`) and its
``1/2`` level set contoured by marching cubes (Lewiner et al. 2003, through
scikit-image): a closed surface within about a cell of the solid's, details
under a cell across lost. Where the winding number is undecided over most
of that solid (an open sheet) no solid is defined and the mesh is refused.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError, MedialAxisWarning
from medialaxis.mesh.solid.holes import UNDECIDED

__all__ = ["CELLS", "contour_solid", "contoured"]

#: Grid cells along the longest side of the mesh's bounding box.
CELLS = 128
#: Gaussian blur of the sampled winding number, in cells: beside a soup's faces, which leave slits and overlap
#: a little, it crosses 1/2 within a cell of the surface and leaves specks and tunnels of a cell (a sphere's
#: soup: 36 parts, 24 cavities, unblurred; one ball at 0.7).
BLUR = 0.7
#: The contour is refused where the winding number is undecided over more than this share of the solid.
UNDECIDED_CONTOUR = 0.25


def contour_solid(vertices: np.ndarray, faces: np.ndarray, cells: int = CELLS) -> tuple[np.ndarray, np.ndarray, float]:
    """Vertices and faces of the ``w = 1/2`` contour of the triangles' winding number, and the grid's cell size.

    Raises
    ------
    InvalidInputError
        The winding number is undecided (within ``UNDECIDED`` of 1/2) over more
        than ``UNDECIDED_CONTOUR`` of the solid, or below 1/2 everywhere.
    """
    from scipy import ndimage
    from skimage.measure import marching_cubes

    from medialaxis.mesh.solid._fast_winding_kernels import WindingTree

    vertices = np.asarray(vertices, np.float64)
    triangles = vertices[np.asarray(faces, np.int64)]
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    step = float(np.max(hi - lo)) / cells
    shape = np.ceil((hi - lo) / step).astype(np.int64) + 5  # two cells of margin each side: the contour closes
    origin = (lo + hi) / 2 - step * (shape - 1) / 2
    axes = [origin[k] + step * np.arange(shape[k]) for k in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    w = WindingTree(triangles)(grid).reshape(shape)
    decided = w[np.abs(w) >= 0.5]
    if decided.size and np.median(decided) < 0:
        w = -w  # wound inward throughout
    inside = w >= 0.5
    if not inside.any():
        raise InvalidInputError("the mesh bounds no solid: its winding number is below 1/2 everywhere")
    undecided = float(np.mean(np.abs(w[inside] - 0.5) < UNDECIDED))
    if undecided > UNDECIDED_CONTOUR:
        raise InvalidInputError(f"the mesh bounds no solid: its winding number is undecided over {100 * undecided:.0f}% "
                                "of where it is at least 1/2")
    w = ndimage.gaussian_filter(w, BLUR)  # band-limited to the grid: no specks of a cell beside a soup's slits
    points, triangles_out, _, _ = marching_cubes(w, 0.5, spacing=(step, step, step), gradient_direction="descent")
    return points + origin, triangles_out.astype(np.int64), step


def contoured(work: Any, why: str, repairs: list[str], found: dict[str, int]) -> Any:
    """``work``'s solid contoured (:func:`contour_solid`), with a warning naming ``why`` its own surface would not do."""
    try:
        points, faces, step = contour_solid(np.asarray(work.vertices), np.asarray(work.faces), CELLS)
    except InvalidInputError as error:
        raise InvalidInputError(f"{why}; {error}") from None
    solid = type(work)(points, faces, process=False)
    if solid.volume < 0:
        solid.invert()
    found["contoured"] = 1
    done = f"its solid contoured from its winding number on a grid of cells {step:.3g} across ({CELLS} along its longest side)"
    repairs.append(done)
    warnings.warn(f"{why}: {done}; details under a cell are lost", MedialAxisWarning, stacklevel=5)
    return solid
