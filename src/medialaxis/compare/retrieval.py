"""Retrieval protocol (Kimia-99 style) and an optional collection-level re-ranking."""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["retrieval_row", "diffusion_rerank"]


def _check_square(D: Any) -> np.ndarray:
    D = np.asarray(D, dtype=np.float64)
    if D.ndim != 2 or D.shape[0] != D.shape[1]:
        raise InvalidInputError(f"expected a square distance matrix, got shape {D.shape}")
    if np.isnan(D).any():
        raise InvalidInputError("the distance matrix contains NaN")
    return D


def retrieval_row(D: Any, labels: Any, *, ranks: int = 10) -> np.ndarray:
    """For ranks 1..``ranks``, how many queries have a same-class shape at that rank.

    Each shape queries all the others (itself excluded); ties are broken by
    index, which never favours a class.

    Parameters
    ----------
    D : (n, n) array_like
        Distances (smaller is more similar).
    labels : (n,) array_like
        Class of each shape.
    ranks : int
        Number of ranks counted.

    Returns
    -------
    (ranks,) int64 ndarray
        Kimia-99 reports these for ranks 1 to 10 (best: 99 each).

    Raises
    ------
    InvalidInputError
        Non-square matrix, NaN, label count mismatch, ``ranks`` out of range.

    Examples
    --------
    >>> retrieval_row([[0, 1, 5], [1, 0, 5], [5, 5, 0]], [0, 0, 1], ranks=2).tolist()
    [2, 0]
    """
    D = _check_square(D).copy()
    labels = np.asarray(labels)
    n = len(D)
    if labels.shape != (n,):
        raise InvalidInputError(f"labels must have shape ({n},), got {labels.shape}")
    if not 1 <= ranks < n:
        raise InvalidInputError(f"ranks must be between 1 and {n - 1}, got {ranks}")
    np.fill_diagonal(D, np.inf)
    order = np.argsort(D, axis=1, kind="stable")[:, :ranks]
    return (labels[order] == labels[:, None]).sum(axis=0).astype(np.int64)


def diffusion_rerank(D: Any, *, neighbours: int = 7, iterations: int = 2) -> np.ndarray:
    """Collection-level re-ranking: diffuse similarities over the k-nearest-neighbour graph.

    Not a pairwise distance: the value for two shapes depends on the whole
    collection. Affinities ``W = exp(-D**2 / (s_i s_j))`` (``s_i`` the
    distance to the ``neighbours``-th neighbour) are restricted to each
    shape's nearest neighbours, row-normalised into ``P``, and diffused as
    ``A <- P A P^T`` (locally constrained diffusion, Yang, Koknar-Tezel and
    Latecki, CVPR 2009). Returns a dissimilarity: ``-(A + A^T)``, with the
    original distances added at scale 1e-9 so ties fall back to them.

    Parameters
    ----------
    D : (n, n) array_like
        Distances, e.g. from :func:`medialaxis.distance_matrix`.
    neighbours : int
        Size of the neighbourhoods.
    iterations : int
        Diffusion steps.

    Returns
    -------
    (n, n) float64 ndarray
        Symmetric dissimilarity for ranking.

    References
    ----------
    .. [1] Yang, Koknar-Tezel, Latecki, locally constrained diffusion process for shape
           retrieval, CVPR 2009 (title, pages and DOI unconfirmed).

    Examples
    --------
    >>> D = [[0, 1, 5, 6], [1, 0, 5, 6], [5, 5, 0, 1], [6, 6, 1, 0]]
    >>> R = diffusion_rerank(D, neighbours=1, iterations=1)
    >>> bool(R[0, 1] < R[0, 2])
    True
    """
    D = _check_square(D)
    n = len(D)
    if not 1 <= neighbours < n:
        raise InvalidInputError(f"neighbours must be between 1 and {n - 1}, got {neighbours}")
    if iterations < 0:
        raise InvalidInputError(f"iterations must be >= 0, got {iterations}")
    sigma = np.sort(D, axis=1)[:, neighbours]
    W = np.exp(-(D**2) / (sigma[:, None] * sigma[None, :] + 1e-300))
    near = np.argsort(D, axis=1, kind="stable")[:, : neighbours + 1]
    P = np.zeros_like(W)
    rows = np.arange(n)[:, None]
    P[rows, near] = W[rows, near]
    P /= P.sum(axis=1, keepdims=True)
    A = P.copy()
    for _ in range(iterations):
        A = P @ A @ P.T
    return -(A + A.T) + 1e-9 * D / max(float(D.max()), 1e-300)
