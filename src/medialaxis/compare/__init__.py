"""Comparing shapes through their medial axes.

"A Qualitative Approach for Medial Computation" builds the medial axis "for
comparing two shapes" (docs/references.md); this layer does it by walking
around the axis. The walk (the axis's Euler tour) meets the axis's parts in
the order the boundary does; samples along it are medial
points, each described by its radius and by a log-polar histogram of where
the axis's swept area lies around it, seen from the walk direction
(:mod:`medialaxis.compare.tour`). Two shapes are compared by aligning their
walks cyclically, keeping the order and paying for skipped samples (dynamic
programming), for the shape and its mirror image, and for the shape closed
(slits and cracks filled, charged for the area that changed), keeping the best.

Why this: it was measured against the alternatives on Kimia-99
(``benchmarks/bench_compare.py``). Bai and Latecki's path similarity with
Hungarian endpoint matching (TPAMI 2008) reaches 853 there (their paper: 939
with hand-tuned DCE pruning); adding an unordered axis context, 912; the
ordered tour, 960 (shock graphs: 956; MPEG-7 dev classes: 88.66%, and 90.87% with
the closed shapes, which need the shape as well as its axis). Those two terms and DCE pruning now
live in ``benchmarks/research/``: they did not add to the tour on Kimia-99
nor on MPEG-7, a set they were not tuned on. The tour needs only the axis
and its radius function (what :class:`~medialaxis.MedialAxis` holds), tolerates missing or spurious
branches (their samples are skipped at a cost proportional to their
length), is exactly invariant under similarities (one axis-derived scale,
angles from the walk, both orientations tried), and its pairwise step is a
compiled kernel (0.4-0.8 ms a pair on one core, six tour versions), so collections of
thousands of shapes are practical. Shock-graph edit distance was not built:
its matching is a search over edits of the graph structure, far slower per
pair, and the tour already matches its figures.

>>> import medialaxis as mx
>>> d = mx.shape_distance("a.png", "b.png")        # doctest: +SKIP
>>> D = mx.distance_matrix(list_of_shapes)         # doctest: +SKIP
"""

from __future__ import annotations

from medialaxis.compare.distance import DEFAULTS, match_tour, shape_distance, shape_signature
from medialaxis.compare.matrix import distance_matrix, query_distances
from medialaxis.compare.retrieval import diffusion_rerank, retrieval_row
from medialaxis.compare.signature import Signature, signature

__all__ = [
    "shape_distance",
    "distance_matrix",
    "query_distances",
    "match_tour",
    "shape_signature",
    "signature",
    "Signature",
    "DEFAULTS",
    "retrieval_row",
    "diffusion_rerank",
]
