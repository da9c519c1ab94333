"""One exception hierarchy for every public entry point.

Every error raised on purpose by :mod:`medialaxis` derives from
:class:`MedialAxisError`, so ``except mx.MedialAxisError`` catches them all.
The subclasses also derive from the matching builtin (``ValueError``,
``OSError``, ``ImportError``, ``MemoryError``) so generic handlers keep working.
"""

from __future__ import annotations

__all__ = [
    "MedialAxisError",
    "InvalidInputError",
    "EmptyShapeError",
    "InputFileError",
    "UnsupportedFormatError",
    "UnsupportedFeatureError",
    "ResourceLimitError",
    "MissingDependencyError",
    "ComputationError",
    "Cancelled",
    "MedialAxisWarning",
]


class MedialAxisError(Exception):
    """Base class of every error raised by medialaxis."""


class InvalidInputError(MedialAxisError, ValueError):
    """An argument has the wrong type, shape, value or dimension."""


class EmptyShapeError(InvalidInputError):
    """The shape has no interior (empty mask, all-foreground mask, zero area)."""


class InputFileError(MedialAxisError, OSError):
    """A file cannot be read: missing, unreadable, truncated or corrupt."""


class UnsupportedFormatError(InvalidInputError):
    """A file extension or object type that no reader or writer handles."""


class UnsupportedFeatureError(UnsupportedFormatError):
    """A file of a supported format uses a feature no reader handles (an SVG mask, a DXF proxy entity)."""


class ResourceLimitError(MedialAxisError, MemoryError):
    """The work would need more memory than allowed; refused before allocating."""


class MissingDependencyError(MedialAxisError, ImportError):
    """An optional dependency is not installed; the message says what to install."""


class ComputationError(MedialAxisError, RuntimeError):
    """A numerical step failed (degenerate geometry, divergence)."""


class Cancelled(MedialAxisError):
    """The computation was cancelled by the user (Ctrl-C or a callback)."""


class MedialAxisWarning(UserWarning):
    """Something was left out or changed on the way to a result (the result is still valid)."""
