"""medialaxis: the medial axis transform of images, polygons, meshes and volumes.

>>> import medialaxis as mx
>>> ma = mx.medial_axis("shape.png")        # doctest: +SKIP
>>> ma.points, ma.radii, ma.edges, ma.faces  # doctest: +SKIP
"""

from __future__ import annotations

from medialaxis._version import __version__
from medialaxis.errors import (
    Cancelled,
    ComputationError,
    EmptyShapeError,
    InputFileError,
    InvalidInputError,
    MedialAxisError,
    MedialAxisWarning,
    MissingDependencyError,
    ResourceLimitError,
    UnsupportedFormatError,
)

# typing.TYPE_CHECKING without importing typing: the console script's
# start-up, before its Ctrl-C handler, stays as short as it can be
TYPE_CHECKING = False

__all__ = [
    "__version__",
    "medial_axis",
    "shape_distance",
    "distance_matrix",
    "deform",
    "centerlines",
    "load",
    "reconstruction_error",
    "MedialAxis",
    "Branch",
    "PlanarOptions",
    "MeshVoronoiOptions",
    "FlowOptions",
    "MidsurfaceOptions",
    "VoxelOptions",
    "MedialAxisError",
    "InvalidInputError",
    "EmptyShapeError",
    "InputFileError",
    "UnsupportedFormatError",
    "ResourceLimitError",
    "MissingDependencyError",
    "ComputationError",
    "Cancelled",
    "MedialAxisWarning",
]


if TYPE_CHECKING:  # pragma: no cover
    from medialaxis.api import medial_axis
    from medialaxis.compare import distance_matrix, shape_distance
    from medialaxis.core.io import load
    from medialaxis.core.result import Branch, MedialAxis
    from medialaxis.gis import centerlines
    from medialaxis.mesh.options import FlowOptions, MeshVoronoiOptions
    from medialaxis.mesh.skeleton.deform import deform
    from medialaxis.metrics import reconstruction_error
    from medialaxis.planar.options import PlanarOptions
    from medialaxis.volume.options import MidsurfaceOptions, VoxelOptions

# Everything but the errors loads on first use, so ``import medialaxis`` is
# light (no NumPy, no numba, no trimesh) and the command line can report a
# Ctrl-C during start-up as an interruption.
_LAZY = {
    "medial_axis": "medialaxis.api",
    "load": "medialaxis.core.io",
    "MedialAxis": "medialaxis.core.result",
    "Branch": "medialaxis.core.result",
    "reconstruction_error": "medialaxis.metrics",
    "shape_distance": "medialaxis.compare",
    "distance_matrix": "medialaxis.compare",
    "deform": "medialaxis.mesh.skeleton.deform",
    "centerlines": "medialaxis.gis",
    "PlanarOptions": "medialaxis.planar.options",
    "MeshVoronoiOptions": "medialaxis.mesh.options",
    "FlowOptions": "medialaxis.mesh.options",
    "MidsurfaceOptions": "medialaxis.volume.options",
    "VoxelOptions": "medialaxis.volume.options",
}
_SUBMODULES = ("datasets",)  # mx.datasets without importing it first


def __getattr__(name: str):
    if name in _SUBMODULES:
        import importlib

        return importlib.import_module(f"medialaxis.{name}")
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'medialaxis' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
