"""Moved to :mod:`medialaxis.datasets.phantoms`; kept for ``volume/validation.py``'s import of ``Rect``
until that import names :mod:`medialaxis.datasets` (then delete this module)."""

from medialaxis.datasets.phantoms import Rect

__all__ = ["Rect"]
