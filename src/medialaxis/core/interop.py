"""Results as the objects of 3D viewers: a pyvista mesh and napari layer data.

pyvista is loaded on first use (``pip install pyvista``); napari is never
imported: :func:`to_napari` returns napari's layer-data tuples, which
``viewer._add_layer_from_data(*t)`` or a napari reader plugin turns into layers.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from medialaxis import _optional
from medialaxis.core.mesh_files import curve_edges, point_fields, points_3d

if TYPE_CHECKING:  # pragma: no cover
    from medialaxis.core.result import MedialAxis

__all__ = ["to_napari", "to_pyvista"]


def to_pyvista(ma: MedialAxis) -> Any:
    """A :class:`pyvista.PolyData`: the points (``z = 0`` in 2D), triangles,
    curve edges as lines, and ``radius``, ``thickness`` and every per-point
    extra as point data.

    Raises
    ------
    MissingDependencyError
        pyvista is not installed.
    """
    pv = _optional.require("pyvista", "pyvista")
    faces = np.asarray(ma.faces, np.int64).reshape(-1, 3)
    lines = curve_edges(ma)
    mesh = pv.PolyData(
        points_3d(ma),
        faces=np.c_[np.full(len(faces), 3), faces].ravel() if len(faces) else None,
        lines=np.c_[np.full(len(lines), 2), lines].ravel() if len(lines) else None,
    )
    for name, values in point_fields(ma).items():
        mesh.point_data[name] = values
    return mesh


def to_napari(ma: MedialAxis) -> list[tuple[Any, dict[str, Any], str]]:
    """napari layer-data tuples ``(data, kwargs, layer_type)``.

    A ``"surface"`` layer for the triangles (vertices, faces, radius as
    values), a ``"shapes"`` layer of paths for the curve edges, and a
    ``"points"`` layer with the radius as each point's size (diameter).
    Coordinates stay in the result's order (image index order for arrays),
    as napari expects.
    """
    layers: list[tuple[Any, dict[str, Any], str]] = []
    points = np.asarray(ma.points, np.float64)
    radii = np.asarray(ma.radii, np.float64)
    if len(ma.faces):
        layers.append(((points, np.asarray(ma.faces, np.int64), radii),
                       {"name": "medial surface", "colormap": "viridis"}, "surface"))
    lines = curve_edges(ma)
    if len(lines):
        layers.append(([points[e] for e in lines], {"name": "medial axis", "shape_type": "path",
                                                     "edge_color": "yellow"}, "shapes"))
    layers.append((points, {"name": "medial balls", "size": 2.0 * radii, "properties": {"radius": radii},
                            "face_color": "transparent"}, "points"))
    return layers
