"""Distances of many pairs: a query against a collection, and all pairs of a collection.

Each shape's signature is computed once (and cached, :func:`~medialaxis.compare.distance.shape_signature`);
the pairs are scored by compiled kernels in blocks, on threads or on a Dask cluster.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from medialaxis.compare.distance import _options, _pack, _score_block, shape_signature
from medialaxis.compare.signature import DEFAULT_PRUNE, Signature
from medialaxis.core.parallel import check_jobs, check_scheduler, run_tasks
from medialaxis.errors import InvalidInputError

__all__ = ["distance_matrix", "query_distances"]


def _blocks(n_pairs: int, n_blocks: int) -> list[slice]:
    edges = np.linspace(0, n_pairs, n_blocks + 1).astype(np.int64)
    return [slice(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:]) if b > a]


def query_distances(
    query: Any,
    shapes: Sequence[Any],
    *,
    n_jobs: int | None = None,
    scheduler: Any = None,
    prune: float = DEFAULT_PRUNE,
    show_progress: bool | None = None,
    **options: Any,
) -> np.ndarray:
    """Distances from one shape to each of a collection (the search step).

    Parameters are those of :func:`distance_matrix`; returns ``(n,)`` float64.

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> from medialaxis.compare import query_distances
    >>> bar = np.zeros((60, 90), bool); bar[20:40, 10:80] = True
    >>> (query_distances(bar, [bar, bar.T], n_jobs=1) < 0.05).tolist()   # itself, rotated by 90 degrees
    [True, True]
    """
    params, axis_options = _options(options)
    check_jobs(n_jobs)
    check_scheduler(scheduler)
    shapes = list(shapes)
    sigs = [shape_signature(query, prune=prune, **axis_options)] + _signatures(
        shapes, prune, axis_options, n_jobs, scheduler, show_progress
    )
    if not shapes:
        return np.zeros(0)
    cols = np.arange(1, len(sigs))
    rows = np.zeros_like(cols)
    return _score_pairs(sigs, rows, cols, params, n_jobs=n_jobs, scheduler=scheduler, show_progress=show_progress)


def _signature_task(shape: Any, prune: float, axis_options: dict[str, Any]) -> Signature:
    """One shape's signature (a task of :func:`_signatures`)."""
    return shape_signature(shape, prune=prune, **axis_options)


def _signatures(
    shapes: list[Any], prune: float, axis_options: dict[str, Any], n_jobs: int | None, scheduler: Any,
    show_progress: bool | None,
) -> list[Signature]:
    """Signatures of ``shapes`` on local threads (file paths need not exist on Dask workers; the cache is here)."""
    local = "synchronous" if scheduler == "synchronous" else None
    return run_tasks(_signature_task, shapes, prune, axis_options, scheduler=local, n_jobs=n_jobs,
                     desc="signatures", show_progress=show_progress)


def _score_pairs(
    sigs: Sequence[Signature],
    rows: np.ndarray,
    cols: np.ndarray,
    params: dict[str, float],
    *,
    n_jobs: int | None,
    scheduler: Any,
    show_progress: bool | None,
) -> np.ndarray:
    """Distances of the signature pairs ``(rows[p], cols[p])``, in blocks on threads or Dask."""
    packed = _pack(sigs)
    n_pairs = len(rows)
    workers = (os.cpu_count() or 1) if n_jobs is None else int(n_jobs)
    if scheduler == "synchronous":
        workers = 1
    blocks = _blocks(n_pairs, max(1, min(n_pairs // 500 + 1, 64 * workers)))
    scores = run_tasks(_score_slice, blocks, packed, rows, cols, params, scheduler=scheduler, n_jobs=workers,
                       desc="pairs", show_progress=show_progress)
    values = np.empty(n_pairs)
    for blk, score in zip(blocks, scores):
        values[blk] = score
    return values


def _score_slice(blk: slice, packed: tuple[np.ndarray, ...], rows: np.ndarray, cols: np.ndarray,
                 params: dict[str, float]) -> np.ndarray:
    return _score_block(packed, rows[blk], cols[blk], params)

def distance_matrix(
    shapes: Sequence[Any],
    *,
    n_jobs: int | None = None,
    scheduler: Any = None,
    prune: float = DEFAULT_PRUNE,
    show_progress: bool | None = None,
    **options: Any,
) -> np.ndarray:
    """All pairwise :func:`shape_distance` values of a collection.

    Each shape's signature is computed once (and cached); the pairs are
    scored by compiled kernels in blocks, on threads or on a Dask cluster.

    Parameters
    ----------
    shapes : sequence
        Planar shapes, axes or signatures (as for :func:`shape_distance`).
    n_jobs : int, optional
        Worker threads for the local run (default: all CPUs; ``1``: serial).
    scheduler : None, "threads", "synchronous", dask Client or str
        ``None``/``"threads"``: local threads; ``"synchronous"``: one thread;
        a ``dask.distributed.Client`` or a scheduler address such as
        ``"tcp://host:8786"``: the blocks of pairs run on that cluster.
    prune, **options
        As for :func:`shape_distance` (matching parameters and options for
        :func:`medialaxis.medial_axis`).
    show_progress : bool, optional
        Progress bars on stderr (default: when stderr is a terminal).

    Returns
    -------
    (n, n) float64 ndarray
        Symmetric, zero diagonal.

    Raises
    ------
    InvalidInputError
        Fewer than one shape, mixed 2D/3D inputs, bad parameters.
    EmptyShapeError
        A shape is empty or has no axis after pruning.
    MissingDependencyError
        A Dask scheduler was asked for without ``distributed`` installed.

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> bar = np.zeros((60, 90), bool); bar[20:40, 10:80] = True
    >>> cross = bar.copy(); cross[5:55, 35:55] = True
    >>> D = mx.distance_matrix([bar, cross, bar.T], n_jobs=1)
    >>> D.shape, bool(D[0, 2] < D[0, 1])
    ((3, 3), True)
    """
    params, axis_options = _options(options)
    if isinstance(shapes, (str, os.PathLike)) or not isinstance(shapes, Sequence):
        shapes = list(shapes) if not isinstance(shapes, (str, os.PathLike)) else [shapes]
    n = len(shapes)
    if n == 0:
        raise InvalidInputError("distance_matrix needs at least one shape, got an empty collection")
    check_jobs(n_jobs)
    check_scheduler(scheduler)
    sigs = _signatures(list(shapes), prune, axis_options, n_jobs, scheduler, show_progress)
    out = np.zeros((n, n))
    if n == 1:
        return out
    rows, cols = np.triu_indices(n, 1)
    values = _score_pairs(sigs, rows, cols, params, n_jobs=n_jobs, scheduler=scheduler, show_progress=show_progress)
    out[rows, cols] = values
    out[cols, rows] = values
    return out
