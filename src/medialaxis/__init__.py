"""medialaxis: the medial axis transform of images, polygons, meshes and volumes.

>>> import medialaxis as mx
>>> ma = mx.medial_axis("shape.png")        # doctest: +SKIP
>>> ma.points, ma.radii, ma.edges, ma.faces  # doctest: +SKIP
"""

from __future__ import annotations

from medialaxis._version import __version__
from medialaxis.api import medial_axis
from medialaxis.core.io import load
from medialaxis.mesh.deform import deform
from medialaxis.metrics import reconstruction_error
from medialaxis.core.result import Branch, MedialAxis
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
