"""Comparing shapes through their medial axes (skeleton path matching).

>>> import medialaxis as mx
>>> d = mx.shape_distance("a.png", "b.png")        # doctest: +SKIP
"""

from __future__ import annotations

from medialaxis.compare.distance import (
    DEFAULTS,
    distance_matrix,
    match_endpoints,
    query_distances,
    shape_distance,
    shape_signature,
)
from medialaxis.compare.signature import Signature, signature

__all__ = ["shape_distance", "distance_matrix", "query_distances", "match_endpoints", "shape_signature", "signature", "Signature", "DEFAULTS"]
