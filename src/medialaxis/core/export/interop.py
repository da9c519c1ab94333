"""Results as the objects of other libraries: pyvista, napari, shapely, trimesh.

pyvista and trimesh are loaded on first use (``pip install pyvista``,
``pip install trimesh``); napari is never imported: :func:`to_napari` returns
napari's layer-data tuples, which ``viewer._add_layer_from_data(*t)`` or a
napari reader plugin turns into layers. The pixel skeleton of image results
(skimage's and skan's kind) is :func:`medialaxis.core.export.skeleton_image.to_image`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from medialaxis import _optional
from medialaxis.core.export.mesh_files import curve_edges, point_fields, points_3d
from medialaxis.errors import InvalidInputError

if TYPE_CHECKING:  # pragma: no cover
    from medialaxis.core.result import MedialAxis

__all__ = ["to_napari", "to_pyvista", "to_shapely", "to_trimesh"]


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


def to_shapely(ma: MedialAxis) -> Any:
    """The branches of a planar curve axis as a :class:`shapely.MultiLineString`.

    One LineString per branch (:meth:`MedialAxis.branches`, in that order),
    in the result's coordinates: ``(row, col) * spacing`` for image inputs
    (x is the row), the input's own x, y for vector inputs. A point without
    edges (the centre of a disc) is in no branch: ``shapely.MultiPoint(
    ma.points[ma.degree == 0])`` gives those. The radius is not carried.

    Raises
    ------
    InvalidInputError
        The result is 3D or has faces (use :func:`to_trimesh`).

    Examples
    --------
    >>> import shapely, medialaxis as mx
    >>> lines = mx.medial_axis(shapely.box(0, 0, 100, 10)).to_shapely()
    >>> lines.geom_type, len(lines.geoms)
    ('MultiLineString', 5)
    """
    shapely = _optional.require("shapely", "shapely")
    if ma.dim != 2 or len(ma.faces):
        kind = "a 3D" if ma.dim != 2 else "a surface"
        raise InvalidInputError(f"to_shapely() takes planar curve axes; this is {kind} axis: use to_trimesh()")
    return shapely.MultiLineString([branch.points for branch in ma.branches()])


def to_trimesh(ma: MedialAxis) -> Any:
    """The result as a trimesh object, by its kind.

    * with faces (medial surfaces): a :class:`trimesh.Trimesh` of the
      triangles; every point is a vertex, in the result's order (so
      ``ma.edges`` index it too), nothing merged or dropped
      (``process=False``), and ``vertex_attributes["radius"]``. Curve
      edges of a mixed result are not in the mesh (``to_pyvista`` has both).
    * curves only: a :class:`trimesh.path.Path3D` (``Path2D`` for planar
      axes) with one ``Line`` entity per branch through its points, and
      ``vertex_attributes["radius"]``.
    * points only: a :class:`trimesh.PointCloud`, the radii in
      ``metadata["radius"]`` (point clouds have no vertex attributes).

    Raises
    ------
    MissingDependencyError
        trimesh is not installed.

    Examples
    --------
    >>> import trimesh, medialaxis as mx
    >>> path = mx.medial_axis(trimesh.creation.torus(2.0, 0.5), method="flow").to_trimesh()
    >>> type(path).__name__, len(path.entities), round(path.length / (2 * 3.14159), 1)
    ('Path3D', 1, 2.0)
    """
    trimesh = _optional.require("trimesh", "trimesh")
    points = np.asarray(ma.points, np.float64)
    radius = {"radius": np.array(ma.radii, np.float64)}
    if len(ma.faces):
        return trimesh.Trimesh(vertices=points.copy(), faces=np.array(ma.faces, np.int64), process=False,
                               validate=False, vertex_attributes=radius)
    if len(ma.edges):
        path_module = _optional.require("trimesh.path", "trimesh")
        from trimesh.path.entities import Line

        entities = [Line(np.array(branch.indices, np.int64)) for branch in ma.branches()]
        cls = path_module.Path2D if ma.dim == 2 else path_module.Path3D
        path = cls(entities=entities, vertices=points.copy(), process=False)
        path.vertex_attributes.update(radius)
        return path
    return trimesh.PointCloud(points.copy(), metadata=radius)
