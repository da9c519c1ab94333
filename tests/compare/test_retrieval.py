"""Kimia-99 retrieval with the standard protocol (the figures are in benchmarks/bench_compare.py)."""

import numpy as np

from medialaxis.compare.retrieval import diffusion_rerank, retrieval_row


def test_retrieval_row_protocol_on_a_toy_matrix():
    labels = np.array([0, 0, 1, 1])
    D = np.array([[0, 1, 2, 3], [1, 0, 0.5, 3], [2, 0.5, 0, 1], [3, 3, 1, 0]], float)
    # Query 0: same class at rank 1; query 1: rank 2; query 2: rank 2 (1 is closer); query 3: rank 1.
    assert retrieval_row(D, labels, ranks=3).tolist() == [2, 2, 0]


def test_kimia99_retrieval(kimia_matrix, kimia_labels):
    row = retrieval_row(kimia_matrix, kimia_labels)
    assert row.shape == (10,)
    # Regression floor under the measured row (960, see the benchmark); chance is about 10 per rank.
    # The path and unordered-context terms stay at 912 or below (bench --variants): the floor checks
    # that the ordered tour term is in.
    assert row[0] >= 97 and row[:5].sum() >= 485 and row.sum() >= 940
    reranked = retrieval_row(diffusion_rerank(kimia_matrix), kimia_labels)
    assert reranked.sum() >= row.sum()  # collection-level re-ranking lifts the late ranks (980 measured)
