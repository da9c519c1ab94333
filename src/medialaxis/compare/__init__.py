"""Comparing shapes through their medial axes (skeleton path matching).

>>> import medialaxis as mx
>>> d = mx.shape_distance("a.png", "b.png")        # doctest: +SKIP
"""

from __future__ import annotations

from medialaxis.compare.signature import Signature, signature

__all__ = ["Signature", "signature"]
