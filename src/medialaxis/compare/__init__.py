"""Comparing shapes through their medial axes (skeleton path matching).

Paper 000 builds the medial axis "for comparing two shapes"; this layer does
it with Bai and Latecki's path similarity (TPAMI 2008): a shape is the set of
axis paths between its endpoints, each described by the radius function
along it (plus its length, chord and bend profile); endpoints are matched
one-to-one by the Hungarian algorithm, with costs from order-keeping
alignments of the paths leaving them.

Why this and not shock-graph edit distance: it needs only the axis and its
radius function (what :class:`~medialaxis.MedialAxis` holds), tolerates
missing or spurious branches through skip and unmatched costs weighted by
how much of the shape a branch carries, is exactly invariant under
similarities (everything is divided by one axis-derived scale and both
boundary orientations are tried), and its pairwise step is a small compiled
kernel (tens of microseconds a pair), so collections of thousands of shapes
are practical. Measured figures: ``benchmarks/bench_compare.py``.

>>> import medialaxis as mx
>>> d = mx.shape_distance("a.png", "b.png")        # doctest: +SKIP
>>> D = mx.distance_matrix(list_of_shapes)         # doctest: +SKIP
"""

from __future__ import annotations

from medialaxis.compare.distance import (
    DEFAULTS,
    distance_matrix,
    match_endpoints,
    match_tour,
    query_distances,
    shape_distance,
    shape_signature,
)
from medialaxis.compare.retrieval import diffusion_rerank, retrieval_row
from medialaxis.compare.signature import Signature, signature

__all__ = [
    "shape_distance",
    "distance_matrix",
    "query_distances",
    "match_tour",
    "match_endpoints",
    "shape_signature",
    "signature",
    "Signature",
    "DEFAULTS",
    "retrieval_row",
    "diffusion_rerank",
]
