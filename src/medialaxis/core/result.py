"""The :class:`MedialAxis` result type shared by every method."""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Mapping
from functools import cached_property
from types import MappingProxyType
from typing import Any, Literal

import numpy as np

from medialaxis.core import graph as _graph
from medialaxis.core.branch import Branch
from medialaxis.core.export import interop
from medialaxis.core.homology import betti_numbers
from medialaxis.core.metadata import frozen_metadata
from medialaxis.core.summary import branch_table
from medialaxis.errors import InvalidInputError

__all__ = ["MedialAxis", "Branch"]


def _frozen(array: Any, dtype: Any, width: int | None, name: str) -> np.ndarray:
    """Copy ``array`` to a read-only C-contiguous array of ``dtype``."""
    out = np.array(array, dtype=dtype, copy=True)
    if width is not None:
        if out.size == 0:
            out = out.reshape(0, width)
        if out.ndim != 2 or out.shape[1] != width:
            raise InvalidInputError(f"{name} must have shape (n, {width}), got {out.shape}")
    out = np.ascontiguousarray(out)
    out.setflags(write=False)
    return out


def _rebuild(*fields: Any) -> MedialAxis:
    return MedialAxis(*fields)


@dataclasses.dataclass(frozen=True, eq=False)
class MedialAxis:
    """The medial axis transform of a shape: axis geometry plus radius function.

    Every method of :func:`medialaxis.medial_axis` returns this type. Arrays are
    read-only copies; derived quantities are computed once and cached.

    Attributes
    ----------
    points : (n, d) float64 ndarray
        Axis points. For array inputs, array index order times ``spacing``
        (row, col[, plane]); for vector inputs, the input's own coordinates.
    radii : (n,) float64 ndarray
        Radius of the medial ball at each point (distance to the boundary).
    edges : (m, 2) int64 ndarray
        The axis as a graph over ``points`` (curve pieces and face boundaries).
    faces : (k, 3) int64 ndarray
        Triangles of medial surface pieces; empty for curve skeletons.
    extras : mapping of str to ndarray
        Documented per-method extra arrays, also reachable as attributes
        (``ma.correspondence``). The planar methods store
        ``edge_contact_diameter`` (m,) here.
    metadata : mapping
        Method name, parameters actually used (``lam``, ``tolerance``...),
        ``spacing`` and, for raster inputs, ``image_shape``; wall-clock
        seconds per stage under ``timings`` (left out of saved files unless
        asked for). Read-only and JSON-like: text keys, lists, plain Python
        numbers (:func:`~medialaxis.core.metadata.frozen_metadata`), so that
        a saved result reads back equal.
    shape : object, optional
        The input region the axis belongs to, when the method keeps it: a
        shapely geometry for planar inputs, the input mesh (trimesh) for the
        mesh methods, the isosurface (:class:`~medialaxis.core.export.scene3d.Surface`)
        for the volume methods. Used by :meth:`reconstruct` and the pictures;
        saved with the result (a surface as its vertices and faces).
    raw : MedialAxis, optional
        What the result was made from without recomputing (:meth:`prune` starts there): the planar unpruned
        axis; a mesh Voronoi result's full complex; a simplified medial mesh's compact complex.
    """

    points: np.ndarray
    radii: np.ndarray
    edges: np.ndarray = dataclasses.field(default_factory=lambda: np.empty((0, 2), np.int64))
    faces: np.ndarray = dataclasses.field(default_factory=lambda: np.empty((0, 3), np.int64))
    extras: Mapping[str, np.ndarray] = dataclasses.field(default_factory=dict)
    metadata: Mapping[str, Any] = dataclasses.field(default_factory=dict)
    shape: Any = None
    raw: MedialAxis | None = dataclasses.field(default=None, repr=False)

    def __post_init__(self) -> None:
        points = np.asarray(self.points, dtype=np.float64)
        dim = points.shape[1] if points.ndim == 2 else None
        if dim not in (2, 3):
            raise InvalidInputError(f"points must have shape (n, 2) or (n, 3), got {points.shape}")
        set_ = object.__setattr__
        set_(self, "points", _frozen(points, np.float64, dim, "points"))
        n = len(self.points)
        radii = _frozen(self.radii, np.float64, None, "radii").reshape(-1)
        if radii.shape != (n,):
            raise InvalidInputError(f"radii must have shape ({n},), got {radii.shape}")
        set_(self, "radii", radii)
        for name, width in (("edges", 2), ("faces", 3)):
            arr = _frozen(self.__dict__[name], np.int64, width, name)
            if arr.size and (arr.min() < 0 or arr.max() >= n):
                raise InvalidInputError(f"{name} index out of range for {n} points")
            set_(self, name, arr)
        extras = {}
        for key, value in dict(self.extras).items():
            arr = np.array(value, copy=True)
            arr.setflags(write=False)
            extras[key] = arr
        set_(self, "extras", MappingProxyType(extras))
        set_(self, "metadata", frozen_metadata(self.metadata))

    def __reduce__(self) -> tuple[Any, ...]:
        # Read-only mappings do not pickle; rebuild from plain dicts (for
        # multiprocessing and Dask workers).
        return (
            _rebuild,
            (self.points, self.radii, self.edges, self.faces, dict(self.extras), dict(self.metadata), self.shape, self.raw),
        )

    def __getattr__(self, name: str) -> Any:
        # Only called when normal lookup fails: expose documented extras; say why an operation is absent.
        extras = self.__dict__.get("extras", {})
        if name in extras:
            return extras[name]
        why = self._no_prune() if name == "prune" else None
        raise AttributeError(why or f"{type(self).__name__!s} has no attribute {name!r}")

    def __repr__(self) -> str:
        method = self.metadata.get("method", "?")
        return (
            f"MedialAxis(method={method!r}, dim={self.dim}, points={len(self.points)}, "
            f"edges={len(self.edges)}, faces={len(self.faces)})"
        )

    # ------------------------------------------------------------------ kind
    @property
    def domain(self) -> str | None:
        """The input domain that made the result: ``"planar"``, ``"mesh"`` or ``"volume"`` (None if built by hand)."""
        return self.metadata.get("domain")

    @property
    def method(self) -> str | None:
        """The method that made the result (``"voronoi"``, ``"flow"``, ``"midsurface"``, ``"voxels"``), or None."""
        return self.metadata.get("method")

    @property
    def frame(self) -> Literal["image", "world"]:
        """``"image"``: array index order (row first) times ``spacing``; ``"world"``: the input's own coordinates."""
        return "image" if "image_shape" in self.metadata else "world"

    @property
    def kind(self) -> str:
        """``"planar curves"``, ``"space curves"``, ``"surfaces"`` or ``"voxel sets"`` (``outputs.result_kind``)."""
        from medialaxis.core.outputs import result_kind

        return result_kind(self)

    # ------------------------------------------------------------------ graph
    @property
    def dim(self) -> int:
        """Spatial dimension of the points (2 or 3)."""
        return int(self.points.shape[1])

    @cached_property
    def degree(self) -> np.ndarray:
        """(n,) int64: number of axis edges at each point."""
        out = _graph.degree(len(self.points), self.edges)
        out.setflags(write=False)
        return out

    @cached_property
    def junctions(self) -> np.ndarray:
        """Indices of points where three or more branches meet."""
        out = np.flatnonzero(self.degree >= 3)
        out.setflags(write=False)
        return out

    @cached_property
    def endpoints(self) -> np.ndarray:
        """Indices of points where a branch ends (degree 1)."""
        out = np.flatnonzero(self.degree == 1)
        out.setflags(write=False)
        return out

    @cached_property
    def n_components(self) -> int:
        """Number of connected components of the axis (points, edges and faces)."""
        return _graph.n_components(len(self.points), self._all_edges)

    @cached_property
    def n_cycles(self) -> int:
        """First Betti number of the edge graph (independent cycles), curves only."""
        return _graph.cycle_rank(len(self.points), self.edges)

    @cached_property
    def betti(self) -> tuple[int, int, int]:
        """Betti numbers ``(b0, b1, b2)`` of the whole complex (points, edges and faces), over GF(2).

        For a medial axis with the solid's homotopy type: the solid's
        components, its genus (summed over components) and 0. See
        :func:`medialaxis.core.homology.betti_numbers`.
        """
        return betti_numbers(len(self.points), self.edges, self.faces)

    @cached_property
    def _all_edges(self) -> np.ndarray:
        if len(self.faces) == 0:
            return self.edges
        f = self.faces
        return np.concatenate([self.edges, f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])

    def branches(self) -> list[Branch]:
        """Chains of the edge graph between junctions and endpoints.

        Returns
        -------
        list of Branch
            Every edge belongs to exactly one branch. A component that is a
            single loop comes back as one closed branch.
        """
        chains = _graph.branches(len(self.points), self.edges)
        return [Branch(c, self.points[c], self.radii[c]) for c in chains]

    def summary(self, *, style: str = "medialaxis") -> Any:
        """A table of the result (a pandas DataFrame): what a row is follows :attr:`kind`.

        Curves (``"planar curves"``, ``"space curves"``): one row per branch,
        below. Surfaces: one row per sheet, with its area, thickness
        min/mean/max and free and junction edge lengths
        (:func:`medialaxis.core.summary.sheet_table`). Voxel sets: one row
        per class of voxel, with counts and radii
        (:func:`medialaxis.core.summary.voxel_count_table`). ``style="skan"``
        is for curves only.

        Parameters
        ----------
        style : {"medialaxis", "skan"}
            ``"medialaxis"``: ends, kind, length, Euclidean distance, radius
            min/mean/max. ``"skan"``: the columns and branch-type codes of
            ``skan.summarize(skeleton, separator="_")`` (``skeleton_id``,
            ``node_id_src``, ``branch_distance``, ``branch_type``,
            ``mean_pixel_value``, ``coord_src_0``, ``euclidean_distance``
            ...), the radius as the pixel value. See
            :func:`medialaxis.core.summary.branch_table`.

        Returns
        -------
        pandas.DataFrame
        """
        kind = self.kind
        if kind in ("surfaces", "voxel sets"):
            if style != "medialaxis":
                raise InvalidInputError(f"style={style!r} is for curve skeletons; this result holds {kind}")
            from medialaxis.core.summary import sheet_table, voxel_count_table

            return sheet_table(self) if kind == "surfaces" else voxel_count_table(self)
        return branch_table(self, style=style)

    # ------------------------------------------------------------- notebook
    def plot(self, ax: Any = None, *, shape: bool = True, color_by_radius: bool = True, nodes: bool = True,
             colorbar: bool = True, title: bool = True) -> Any:
        """Draw the axis with matplotlib and return the axes.

        Planar results are drawn over their shape (images the right way
        up: row downwards); 3D results on 3D axes inside a translucent
        input shell, with one scale on all axes.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (3D axes for a 3D result:
            ``fig.add_subplot(projection="3d")``). Default: new axes on a new
            pyplot figure.
        shape : bool
            Draw the input region (2D) or shell (3D) when the result keeps it.
        color_by_radius : bool
            Colour the axis by radius (viridis), else one colour.
        nodes : bool
            Mark junctions (black) and endpoints (green).
        colorbar, title : bool
            Add a radius colour bar; a title with the method and counts.

        Returns
        -------
        matplotlib.axes.Axes

        Raises
        ------
        InvalidInputError
            ``ax`` is 2D for a 3D result, or 3D for a planar one.

        Examples
        --------
        >>> import matplotlib; matplotlib.use("Agg")
        >>> import numpy as np, medialaxis as mx
        >>> image = np.zeros((60, 90), bool); image[15:45, 10:80] = True
        >>> ax = mx.medial_axis(image).plot()
        >>> ax.get_title().endswith("5 branches"), bool(ax.yaxis_inverted())  # an image: row downwards
        (True, True)
        >>> import matplotlib.pyplot as plt; plt.close(ax.figure)
        """
        from medialaxis.core.export.plot import plot

        return plot(self, ax, shape=shape, color_by_radius=color_by_radius, nodes=nodes, colorbar=colorbar,
                    title=title)

    def _repr_png_(self) -> bytes:
        """The picture of :meth:`plot`, for Jupyter (drawn off pyplot, so nothing else is shown)."""
        from medialaxis.core.export.plot import png_bytes

        return png_bytes(self)

    # -------------------------------------------------------------- interop
    def to_shapely(self) -> Any:
        """The branches of a planar curve axis as a shapely MultiLineString,
        in the result's coordinates (see :func:`medialaxis.core.export.interop.to_shapely`)."""
        return interop.to_shapely(self)

    def to_trimesh(self) -> Any:
        """A :class:`trimesh.Trimesh` of the faces (surfaces) or a ``Path3D`` /
        ``Path2D`` of the branches (curves), with ``vertex_attributes["radius"]``;
        a ``PointCloud`` for points only (see :func:`medialaxis.core.export.interop.to_trimesh`)."""
        return interop.to_trimesh(self)

    def to_image(self) -> Any:
        """``(skeleton, distance)`` images on the input's pixel grid, as
        skimage's ``medial_axis(return_distance=True)`` (the distance only on
        the skeleton); image and volume results only (see
        :func:`medialaxis.core.export.skeleton_image.to_image`)."""
        from medialaxis.core.export.skeleton_image import to_image

        return to_image(self)

    def to_pyvista(self) -> Any:
        """The result as a :class:`pyvista.PolyData` (see :func:`medialaxis.core.export.interop.to_pyvista`)."""
        return interop.to_pyvista(self)

    def to_napari(self) -> list[tuple[Any, dict[str, Any], str]]:
        """napari layer-data tuples (see :func:`medialaxis.core.export.interop.to_napari`)."""
        return interop.to_napari(self)

    def to_networkx(self) -> Any:
        """The axis as a :class:`networkx.Graph`.

        Nodes carry ``pos`` (tuple) and ``radius``; edges carry ``length``.
        """
        return _graph.to_networkx(self.points, self.radii, self._all_edges)

    # ------------------------------------------------------------- derived
    @property
    def prune(self) -> Callable[..., MedialAxis]:
        """``prune(lam=None, **options)``: the axis re-pruned with another ``lam``, without recomputing it.

        Present where lambda means something and the result keeps what it was
        pruned from; absent elsewhere (``hasattr(ma, "prune")`` is False:
        mid-surfaces and voxel sets). Planar results re-prune their unpruned
        axis (any ``lam`` and ``detour``); mesh Voronoi results collapse their
        full complex down to the facets at least ``lam`` wide, homotopy kept
        (``lam`` at least the one computed with;
        :func:`medialaxis.mesh.medial.reprune.reprune`); flow skeletons drop the
        terminal branches narrower than ``lam``
        (:func:`medialaxis.mesh.skeleton.branch_prune.reprune`). ``lam=None``: the value used.
        """
        from medialaxis._dispatch import repruner

        why = self._no_prune()
        if why:
            raise AttributeError(why)
        return functools.partial(repruner(self.metadata), self)

    def _no_prune(self) -> str | None:
        """Why this result has no ``prune``, or None."""
        from medialaxis._dispatch import REPRUNERS

        if (self.domain, self.method) not in REPRUNERS:
            return f"{self.method!r} results ({self.kind}) have no prune(): lambda does not apply once computed"
        if self.raw is None and self.method == "voronoi" and "face_contact_diameter" not in self.extras:
            return f"this {self.method!r} result keeps no unpruned axis to re-prune"  # a mesh's full complex is its own
        return None

    def __dir__(self) -> list[str]:
        return [n for n in super().__dir__() if n != "prune" or not self._no_prune()]

    def reconstruct(self, *, raster: bool = False, resolution: int = 64) -> Any:
        """Union of the medial balls.

        Parameters
        ----------
        raster : bool
            For image inputs, return a boolean image of the input's shape
            (pixels whose centre lies in a disc) instead of a geometry.
        resolution : int
            Segments per quarter circle of each disc (geometry output).

        Returns
        -------
        shapely geometry or (rows, cols) bool ndarray
        """
        from medialaxis.core.reconstruct import reconstruct

        return reconstruct(self, raster=raster, resolution=resolution)

    def save(self, path: Any, *, timings: bool = False) -> None:
        """Write the result; the format follows the extension.

        ``.json`` and ``.npz`` are lossless (read back equal with
        :func:`medialaxis.load`: arrays, metadata, the input shape and the
        unpruned axis); ``.graphml``, ``.geojson`` export the graph;
        ``.svg`` draws the axis over the shape; ``.png`` plots it coloured by
        radius. The file is written to a temporary name, then renamed.
        ``timings=True`` keeps the wall-clock ``metadata["timings"]`` in the
        file (left out by default: the same result gives the same file).
        """
        from medialaxis.core.io import save

        save(self, path, timings=timings)
