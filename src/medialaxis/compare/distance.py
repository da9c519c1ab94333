"""Shape distance through medial axes: :func:`shape_distance` and :func:`distance_matrix`.

The distance has two terms, both built on the medial axis and its radius
function. The main one is Bai and Latecki's skeleton path matching: each
shape's signature (:func:`medialaxis.compare.signature`) holds the radius
function along the axis path between every pair of endpoints; endpoints are
matched one-to-one (Hungarian) with costs from order-keeping alignments of
their paths. The second, the *axis context* (:mod:`medialaxis.compare.context`),
matches samples along the two axes by where the rest of the axis's swept
area lies around them and by their radius; it separates shapes whose
endpoint paths look alike (fish and wrenches in Kimia-99) and lifts the
Kimia-99 row from 851 to 913. The sum is 0 for a shape and itself,
symmetric, and invariant under similarity transforms because the signature is.
"""

from __future__ import annotations

import os
import threading
import weakref
from collections import OrderedDict
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._progress import progress
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.compare import _kernels
from medialaxis.compare.context import N_ANGULAR
from medialaxis.compare.signature import DEFAULT_PRUNE, DEFAULT_SAMPLES, Signature, signature
from medialaxis.errors import InvalidInputError

__all__ = ["shape_distance", "distance_matrix", "query_distances", "match_endpoints", "shape_signature", "DEFAULTS"]

#: Matching parameters: weights of the path-length, chord and bend terms of
#: the path cost, cost of skipping a path in an alignment and of an unmatched
#: endpoint (both times the endpoint's weight), chosen on Kimia-99; weight of
#: the axis-context term, chosen with a class split of Kimia-99 (1.5 times the
#: ratio of the two terms' medians; 1 to 3 times give the same row, within 5);
#: with that term in, ``unmatched`` 0.8 -> 0.4 raised both halves of the split
#: (``benchmarks/bench_compare.py --variants``).
DEFAULTS = {"alpha": 0.1333, "beta": 0.0625, "gamma": 0.175, "skip": 0.2, "unmatched": 0.4, "context": 0.6}

#: Planar ``tolerance`` for vector inputs, as a fraction of sqrt(area): a
#: similarity-invariant choice, so distances do not move under rotation.
VECTOR_TOLERANCE = 1e-3

_AXIS_CACHE: weakref.WeakKeyDictionary[MedialAxis, dict[tuple[Any, ...], Signature]] = weakref.WeakKeyDictionary()
_FILE_CACHE: OrderedDict[tuple[Any, ...], Signature] = OrderedDict()
_FILE_CACHE_SIZE = 4096
_LOCK = threading.Lock()


def shape_signature(
    shape: Any, *, n_samples: int = DEFAULT_SAMPLES, prune: float = DEFAULT_PRUNE, **axis_options: Any
) -> Signature:
    """Signature of one shape, computed once and cached.

    Parameters
    ----------
    shape : Signature, MedialAxis, path, array or shapely geometry
        A signature (returned as is), a planar :class:`MedialAxis`, or
        anything :func:`medialaxis.medial_axis` takes that is planar.
    n_samples, prune : see :func:`medialaxis.compare.signature`
    **axis_options
        Passed to :func:`medialaxis.medial_axis` (``lam``, ``tolerance``...).

    Returns
    -------
    Signature

    Raises
    ------
    InvalidInputError
        A mesh, a volume or a 3D axis (comparison is planar), or bad options.
    EmptyShapeError
        An empty shape, or one with no axis left after pruning.
    """
    if isinstance(shape, Signature):
        return shape
    key = (int(n_samples), float(prune))
    if isinstance(shape, MedialAxis):
        with _LOCK:
            hit = _AXIS_CACHE.get(shape, {}).get(key)
        if hit is None:
            hit = signature(shape, n_samples=n_samples, prune=prune)
            with _LOCK:
                _AXIS_CACHE.setdefault(shape, {})[key] = hit
        return hit
    from medialaxis import _dispatch
    from medialaxis.api import medial_axis

    domain = _dispatch.classify(shape)
    if domain != "planar":
        raise InvalidInputError(
            f"shape comparison works on planar shapes; got {domain} input {_describe(shape)} (mixed 2D/3D inputs?)"
        )
    file_key = None
    if isinstance(shape, (str, os.PathLike)):
        path = Path(shape).resolve()
        stat = path.stat()
        file_key = (str(path), stat.st_mtime_ns, stat.st_size, key, repr(sorted(axis_options.items())))
        with _LOCK:
            hit = _FILE_CACHE.get(file_key)
            if hit is not None:
                _FILE_CACHE.move_to_end(file_key)
                return hit
    options = dict(axis_options)
    if "tolerance" not in options:
        area = _vector_area(shape)
        if area is not None and area > 0:
            # The planar default follows the bounding box, which rotation changes.
            options["tolerance"] = VECTOR_TOLERANCE * float(np.sqrt(area))
    sig = signature(medial_axis(shape, **options), n_samples=n_samples, prune=prune)
    if file_key is not None:
        with _LOCK:
            _FILE_CACHE[file_key] = sig
            while len(_FILE_CACHE) > _FILE_CACHE_SIZE:
                _FILE_CACHE.popitem(last=False)
    return sig


def _vector_area(shape: Any) -> float | None:
    """Area of a shapely geometry or an ``(n, 2)`` float loop; ``None`` for anything else."""
    if type(shape).__module__.startswith("shapely"):
        return float(getattr(shape, "area", 0.0))
    if isinstance(shape, (list, tuple)) and shape and all(hasattr(g, "geom_type") for g in shape):
        return float(sum(g.area for g in shape))
    if isinstance(shape, (str, os.PathLike)):
        return None
    arr = np.asarray(shape)
    if arr.ndim == 2 and arr.shape[1] == 2 and arr.dtype != bool and len(arr) >= 3 and np.isfinite(arr).all():
        x, y = arr[:, 0].astype(float), arr[:, 1].astype(float)
        return float(abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) / 2)
    return None


def _describe(shape: Any) -> str:
    if isinstance(shape, (str, os.PathLike)):
        return repr(str(shape))
    return type(shape).__name__


def _params(alpha: Any, beta: Any, gamma: Any, skip: Any, unmatched: Any, context: Any = None) -> tuple[float, ...]:
    given = {"alpha": alpha, "beta": beta, "gamma": gamma, "skip": skip, "unmatched": unmatched, "context": context}
    return tuple(check_number(DEFAULTS[k] if v is None else v, k) for k, v in given.items())


def _features(sig: Signature) -> tuple[np.ndarray, ...]:
    return sig.radii, sig.lengths, sig.chords, sig.bends, sig.weights


def _pack(sigs: Sequence[Signature]) -> tuple[_kernels.Packed, tuple[np.ndarray, ...]]:
    paths = _kernels.pack(*(list(column) for column in zip(*(_features(s) for s in sigs))))
    context = _kernels.pack_context([s.context for s in sigs], [s.context_radii for s in sigs], N_ANGULAR)
    return paths, context


def _check_samples(sigs: Sequence[Signature]) -> None:
    sizes = {s.radii.shape[2] for s in sigs}
    if len(sizes) > 1:
        raise InvalidInputError(f"signatures have different n_samples {sorted(sizes)}; compute them alike")


def shape_distance(
    a: Any,
    b: Any,
    *,
    alpha: float | None = None,
    beta: float | None = None,
    gamma: float | None = None,
    skip: float | None = None,
    unmatched: float | None = None,
    context: float | None = None,
    n_samples: int = DEFAULT_SAMPLES,
    prune: float = DEFAULT_PRUNE,
    **axis_options: Any,
) -> float:
    """Distance between two planar shapes through their medial axes.

    Skeleton path matching (Bai and Latecki): the radius function along the
    axis path between every two endpoints is compared, with the path's
    length and, added here, its chord and bend profile (+5 % on the Kimia-99
    row); endpoints are matched one-to-one (Hungarian) with costs from
    order-keeping alignments of their paths; both boundary orientations are
    tried (mirror invariance). Added to it, ``context`` times the axis-context
    distance: samples along both axes matched one-to-one by the log-polar
    layout of the axis's swept area around them and by their radius
    (:mod:`medialaxis.compare.context`).

    Parameters
    ----------
    a, b : MedialAxis, Signature, path, array or shapely geometry
        Planar shapes (anything :func:`medialaxis.medial_axis` takes) or
        their axes / signatures.
    alpha, beta, gamma : float, optional
        Weights of the path-length, chord and bend terms of the path cost
        (defaults in ``DEFAULTS``; the radius term has weight 1).
    context : float, optional
        Weight of the axis-context term (default ``DEFAULTS["context"]``;
        ``0``: the path term alone).
    skip : float, optional
        Cost of leaving a path unaligned (default ``DEFAULTS["skip"]``).
    unmatched : float, optional
        Cost of an endpoint without partner (default ``DEFAULTS["unmatched"]``).
    n_samples, prune : see :func:`medialaxis.compare.signature`
    **axis_options
        Passed to :func:`medialaxis.medial_axis` for inputs that are shapes.

    Returns
    -------
    float
        ``>= 0``; ``0`` for a shape and itself; symmetric; unchanged by
        translation, rotation, uniform scaling and mirroring of either shape.

    Raises
    ------
    InvalidInputError
        Non-planar input (mesh, volume, 3D axis), bad parameters.
    EmptyShapeError
        Empty shape or no axis after pruning.

    References
    ----------
    X. Bai and L. J. Latecki, "Path similarity skeleton graph matching",
    IEEE TPAMI 30(7), 2008; paper 000 (the axis "for comparing two shapes").

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> bar = np.zeros((60, 90), bool); bar[20:40, 10:80] = True
    >>> mx.shape_distance(bar, bar)
    0.0
    >>> mx.shape_distance(bar, bar.T) < 0.01          # rotated by 90 degrees
    True
    """
    params = _params(alpha, beta, gamma, skip, unmatched, context)
    sa = shape_signature(a, n_samples=n_samples, prune=prune, **axis_options)
    sb = shape_signature(b, n_samples=n_samples, prune=prune, **axis_options)
    if sa is sb:
        return 0.0
    _check_samples([sa, sb])
    packed = _pack([sa, sb])
    return float(_score_block(packed, np.array([0]), np.array([1]), params)[0])  # equal up to rounding; min makes it exactly symmetric


def match_endpoints(
    a: Any,
    b: Any,
    *,
    alpha: float | None = None,
    beta: float | None = None,
    gamma: float | None = None,
    skip: float | None = None,
    unmatched: float | None = None,
    context: float | None = None,
    n_samples: int = DEFAULT_SAMPLES,
    prune: float = DEFAULT_PRUNE,
    **axis_options: Any,
) -> tuple[float, list[tuple[int, int]]]:
    """The endpoint correspondence behind :func:`shape_distance`.

    Returns
    -------
    distance : float
        As :func:`shape_distance` (computed by the NumPy/SciPy reference).
    pairs : list of (int, int)
        Matched endpoints: index into ``signature(a).endpoints`` and into
        ``signature(b).endpoints``.

    Examples
    --------
    >>> import numpy as np
    >>> from medialaxis.compare import match_endpoints
    >>> bar = np.zeros((60, 90), bool); bar[20:40, 10:80] = True
    >>> match_endpoints(bar, bar)[1]
    [(0, 0), (1, 1), (2, 2), (3, 3)]
    """
    params = _params(alpha, beta, gamma, skip, unmatched, context)
    sa = shape_signature(a, n_samples=n_samples, prune=prune, **axis_options)
    sb = shape_signature(b, n_samples=n_samples, prune=prune, **axis_options)
    _check_samples([sa, sb])
    value, pairs = _kernels.reference_match(_features(sa), _features(sb), *params[:5])
    if params[5] > 0:
        value += params[5] * _kernels.context_distance_reference(
            sa.context, sa.context_radii, sb.context, sb.context_radii, N_ANGULAR
        )
    return value, pairs


# --------------------------------------------------------------- matrix
def _blocks(n_pairs: int, n_blocks: int) -> list[slice]:
    edges = np.linspace(0, n_pairs, n_blocks + 1).astype(np.int64)
    return [slice(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:]) if b > a]


def _score_block(
    packed: tuple[_kernels.Packed, tuple[np.ndarray, ...]], rows: np.ndarray, cols: np.ndarray, params: tuple[float, ...]
) -> np.ndarray:
    """Path term (exactly symmetric by a min) plus ``context`` times the axis-context term (symmetric by construction)."""
    paths, context = packed
    forward = _kernels.pair_distances(*paths, rows, cols, *params[:5])
    backward = _kernels.pair_distances(*paths, cols, rows, *params[:5])
    out = np.minimum(forward, backward)  # equal up to rounding; min makes it exactly symmetric
    if params[5] > 0:
        out += params[5] * _kernels.context_distances(*context, rows, cols)
    return out


def _check_scheduler(scheduler: Any) -> None:
    if scheduler in (None, "threads", "synchronous"):
        return
    if isinstance(scheduler, str) and "://" in scheduler:
        return
    if not isinstance(scheduler, str) and hasattr(scheduler, "submit") and hasattr(scheduler, "scatter"):
        return
    raise InvalidInputError(
        f"scheduler must be None, 'threads', 'synchronous', a dask Client or an address like "
        f"'tcp://host:8786', got {scheduler!r}"
    )


def _check_jobs(n_jobs: Any) -> None:
    if n_jobs is not None and (isinstance(n_jobs, bool) or not isinstance(n_jobs, (int, np.integer)) or n_jobs < 1):
        raise InvalidInputError(f"n_jobs must be a positive integer or None, got {n_jobs!r}")


def query_distances(
    query: Any,
    shapes: Sequence[Any],
    *,
    n_jobs: int | None = None,
    scheduler: Any = None,
    alpha: float | None = None,
    beta: float | None = None,
    gamma: float | None = None,
    skip: float | None = None,
    unmatched: float | None = None,
    context: float | None = None,
    n_samples: int = DEFAULT_SAMPLES,
    prune: float = DEFAULT_PRUNE,
    show_progress: bool | None = None,
    **axis_options: Any,
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
    params = _params(alpha, beta, gamma, skip, unmatched, context)
    _check_jobs(n_jobs)
    _check_scheduler(scheduler)
    shapes = list(shapes)
    sigs = [shape_signature(query, n_samples=n_samples, prune=prune, **axis_options)] + [
        shape_signature(s, n_samples=n_samples, prune=prune, **axis_options)
        for s in progress(shapes, desc="signatures", total=len(shapes), show=show_progress)
    ]
    _check_samples(sigs)
    if not shapes:
        return np.zeros(0)
    cols = np.arange(1, len(sigs))
    rows = np.zeros_like(cols)
    return _score_pairs(sigs, rows, cols, params, n_jobs=n_jobs, scheduler=scheduler, show_progress=show_progress)


def _dask_client(scheduler: Any) -> Any:
    from medialaxis._optional import require

    distributed = require("distributed", "medialaxis[dask]")
    if isinstance(scheduler, distributed.Client):
        return scheduler, False
    return distributed.Client(scheduler), True


def _score_pairs(
    sigs: Sequence[Signature],
    rows: np.ndarray,
    cols: np.ndarray,
    params: tuple[float, ...],
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
    blocks = _blocks(n_pairs, max(1, min(n_pairs // 2000 + 1, 64 * workers)))
    values = np.empty(n_pairs)
    if scheduler in (None, "threads", "synchronous"):
        if workers == 1:
            for blk in progress(blocks, desc="pairs", total=len(blocks), show=show_progress):
                values[blk] = _score_block(packed, rows[blk], cols[blk], params)
        else:
            with ThreadPoolExecutor(workers) as pool:
                futures = [(blk, pool.submit(_score_block, packed, rows[blk], cols[blk], params)) for blk in blocks]
                for blk, fut in progress(futures, desc="pairs", total=len(futures), show=show_progress):
                    values[blk] = fut.result()
    else:
        client, owned = _dask_client(scheduler)
        try:
            shared = client.scatter(packed, broadcast=True)
            futures = [client.submit(_score_block, shared, rows[blk], cols[blk], params, pure=False) for blk in blocks]
            for blk, fut in progress(list(zip(blocks, futures)), desc="pairs", total=len(blocks), show=show_progress):
                values[blk] = fut.result()
        finally:
            if owned:
                client.close()
    return values


def distance_matrix(
    shapes: Sequence[Any],
    *,
    n_jobs: int | None = None,
    scheduler: Any = None,
    alpha: float | None = None,
    beta: float | None = None,
    gamma: float | None = None,
    skip: float | None = None,
    unmatched: float | None = None,
    context: float | None = None,
    n_samples: int = DEFAULT_SAMPLES,
    prune: float = DEFAULT_PRUNE,
    show_progress: bool | None = None,
    **axis_options: Any,
) -> np.ndarray:
    """All pairwise :func:`shape_distance` values of a collection.

    Each shape's signature is computed once (and cached); the pairs are
    scored by a compiled kernel in blocks, on threads or on a Dask cluster.

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
    alpha, beta, gamma, skip, unmatched, context, n_samples, prune, **axis_options
        As for :func:`shape_distance`.
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
    params = _params(alpha, beta, gamma, skip, unmatched, context)
    if isinstance(shapes, (str, os.PathLike)) or not isinstance(shapes, Sequence):
        shapes = list(shapes) if not isinstance(shapes, (str, os.PathLike)) else [shapes]
    n = len(shapes)
    if n == 0:
        raise InvalidInputError("distance_matrix needs at least one shape, got an empty collection")
    _check_jobs(n_jobs)
    _check_scheduler(scheduler)
    sigs = [
        shape_signature(s, n_samples=n_samples, prune=prune, **axis_options)
        for s in progress(shapes, desc="signatures", total=n, show=show_progress)
    ]
    _check_samples(sigs)
    out = np.zeros((n, n))
    if n == 1:
        return out
    rows, cols = np.triu_indices(n, 1)
    values = _score_pairs(sigs, rows, cols, params, n_jobs=n_jobs, scheduler=scheduler, show_progress=show_progress)
    out[rows, cols] = values
    out[cols, rows] = values
    return out
