"""medialaxis: the medial axis transform of images, polygons, meshes and volumes.

>>> import medialaxis as mx
>>> ma = mx.medial_axis("shape.png")        # doctest: +SKIP
>>> ma.points, ma.radii, ma.edges, ma.faces  # doctest: +SKIP
"""

from __future__ import annotations

from medialaxis._version import __version__
from medialaxis.api import medial_axis
from medialaxis.core.io import load
from medialaxis.core.result import Branch, MedialAxis
from medialaxis.metrics import reconstruction_error
from medialaxis.errors import (
    Cancelled,
    ComputationError,
    EmptyShapeError,
    InputFileError,
    InvalidInputError,
    MedialAxisError,
    MissingDependencyError,
    ResourceLimitError,
    UnsupportedFormatError,
)

__all__ = [
    "__version__",
    "medial_axis",
    "shape_distance",
    "distance_matrix",
    "deform",
    "load",
    "reconstruction_error",
    "MedialAxis",
    "Branch",
    "MedialAxisError",
    "InvalidInputError",
    "EmptyShapeError",
    "InputFileError",
    "UnsupportedFormatError",
    "ResourceLimitError",
    "MissingDependencyError",
    "ComputationError",
    "Cancelled",
]


# Entry points of heavier layers load on first use, so ``import medialaxis``
# stays light (no numba compilation, no trimesh).
_LAZY = {
    "shape_distance": "medialaxis.compare",
    "distance_matrix": "medialaxis.compare",
    "deform": "medialaxis.mesh.deform",
}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'medialaxis' has no attribute {name!r}")
