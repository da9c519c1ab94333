"""Shape distance through medial axes: :func:`shape_distance` (many pairs: :mod:`medialaxis.compare.matrix`).

The *axis tour* (:mod:`medialaxis.compare.tour`): samples along the walk
around the axis, each described by where the axis's swept area lies around
it and by its radius, aligned cyclically in order with a cost ``gap`` per
skipped sample, for the axis as pruned, for the axis before the method's own
pruning and for the axis of the shape closed (slits and cracks filled;
charged for the area the closing changed), keeping the best.

Two more terms were options here: Bai and Latecki's skeleton path matching
(Kimia-99 853 alone; with the axis context 912, the default before the tour)
and an unordered axis context (889 alone). Neither raised the tour on
Kimia-99 nor on MPEG-7 (a set they were not tuned on: +0.06 and -0.17
points), so both moved to ``benchmarks/research/`` (issue 17), where
``bench_compare.py`` still computes them as the "previous default" row.
The distance is 0 for a shape and itself, symmetric, and invariant under
similarity transforms because the signature is.
"""

from __future__ import annotations

import os
import threading
import weakref
from collections import OrderedDict
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.compare import _kernels
from medialaxis.compare.signature import DEFAULT_PRUNE, Signature, signature
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import InvalidInputError

__all__ = ["shape_distance", "match_tour", "shape_signature", "DEFAULTS"]

#: Matching parameters. ``gap``: cost of a tour sample left unaligned; the
#: tour distance is a mean cost per sample, on Kimia-99 a median 0.23
#: between shapes of one class and 0.44 between classes (10-90%: 0.13-0.32
#: and 0.38-0.53). There 0.2 gives the row 953, 0.25 960, 0.3 960, 0.35 958,
#: 0.4 959 (``benchmarks/bench_compare.py --variants``, one pruning level).
DEFAULTS = {"gap": 0.3}

#: Planar ``tolerance`` for vector inputs, as a fraction of sqrt(area): a
#: similarity-invariant choice, so distances do not move under rotation.
VECTOR_TOLERANCE = 1e-3

_AXIS_CACHE: weakref.WeakKeyDictionary[MedialAxis, dict[tuple[Any, ...], Signature]] = weakref.WeakKeyDictionary()
_FILE_CACHE: OrderedDict[tuple[Any, ...], Signature] = OrderedDict()
_FILE_CACHE_SIZE = 4096
_LOCK = threading.Lock()


def shape_signature(shape: Any, *, prune: float = DEFAULT_PRUNE, **axis_options: Any) -> Signature:
    """Signature of one shape, computed once and cached.

    Parameters
    ----------
    shape : Signature, MedialAxis, path, array or shapely geometry
        A signature (returned as is), a planar :class:`MedialAxis` or a
        saved one (``.json``, ``.npz``), or anything
        :func:`medialaxis.medial_axis` takes that is planar.
    prune : see :func:`medialaxis.compare.signature`
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
    key = (float(prune),)
    if isinstance(shape, MedialAxis):
        with _LOCK:
            hit = _AXIS_CACHE.get(shape, {}).get(key)
        if hit is None:
            hit = signature(shape, prune=prune)
            with _LOCK:
                _AXIS_CACHE.setdefault(shape, {})[key] = hit
        return hit
    from medialaxis import _dispatch
    from medialaxis.api import medial_axis

    domain = _dispatch.classify(shape)
    if domain not in ("planar", _dispatch.RESULT):
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
    if domain == _dispatch.RESULT:
        # A saved axis is compared as the axis it was when saved.
        ma = _dispatch.load_result(shape, None, options)
        if ma.dim != 2:
            raise InvalidInputError(f"shape comparison works on planar shapes; {_describe(shape)} holds a 3D axis")
    else:
        if "tolerance" not in options:
            area = _vector_area(shape)
            if area is not None and area > 0:
                # The planar default follows the bounding box, which rotation changes.
                options["tolerance"] = VECTOR_TOLERANCE * float(np.sqrt(area))
        ma = medial_axis(shape, **options)
    sig = signature(ma, prune=prune)
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


def _params(options: dict[str, Any]) -> dict[str, float]:
    """Matching parameters from keyword options (``None``: the default); checked to be numbers >= 0."""
    return {k: check_number(DEFAULTS[k] if options.get(k) is None else options[k], k) for k in DEFAULTS}


def _options(options: dict[str, Any]) -> tuple[dict[str, float], dict[str, Any]]:
    """Checked matching parameters and the options left for :func:`medialaxis.medial_axis`."""
    axis_options = dict(options)
    matching = {k: axis_options.pop(k) for k in list(axis_options) if k in DEFAULTS}
    return _params(matching), axis_options


def _signature_pair(a: Any, b: Any, prune: float, options: dict[str, Any]) -> tuple[Signature, Signature, dict[str, float]]:
    """Signatures of ``a`` and ``b`` and the matching parameters, from a public function's keywords."""
    params, axis_options = _options(options)
    return shape_signature(a, prune=prune, **axis_options), shape_signature(b, prune=prune, **axis_options), params


def _pack(sigs: Sequence[Signature]) -> tuple[np.ndarray, ...]:
    """Pack the signatures' tours for the compiled kernel."""
    return _kernels.pack_tour([s.tour for s in sigs], [s.tour_radii for s in sigs], [s.closing_gain for s in sigs])


def shape_distance(a: Any, b: Any, *, prune: float = DEFAULT_PRUNE, **options: Any) -> float:
    """Distance between two planar shapes through their medial axes.

    The main term walks around each axis (the order in which the boundary
    meets its parts) and aligns the two walks cyclically, keeping the order:
    each sample is an axis point with its radius and a log-polar histogram of
    where the axis's swept area lies around it (:mod:`medialaxis.compare.tour`);
    it is computed for the axis as pruned, for the axis before the method's
    own pruning and for the shapes closed (slits, cracks and narrow gaps
    filled), charged for the area the closing changed; the least is kept. Both orientations (mirror images) are
    tried.

    Parameters
    ----------
    a, b : MedialAxis, Signature, path, array or shapely geometry
        Planar shapes (anything :func:`medialaxis.medial_axis` takes) or
        their axes / signatures.
    prune : see :func:`medialaxis.compare.signature`
    **options
        ``gap`` (cost of a tour sample left unaligned, >= 0; default in
        ``DEFAULTS``); any other keyword goes to :func:`medialaxis.medial_axis`
        for inputs that are shapes.

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
    .. [1] "A Qualitative Approach for Medial Computation" (Voronoi/Delaunay medial axis of a 2D
           image; authors, venue and year unconfirmed: docs/references.md): the axis "for comparing
           two shapes".
    .. [2] S. Belongie, J. Malik, J. Puzicha, "Shape matching and object recognition using shape
           contexts", IEEE Transactions on Pattern Analysis and Machine Intelligence
           24(4):509-522, 2002. doi:10.1109/34.993558 (the histograms, here of medial mass).

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> bar = np.zeros((60, 90), bool); bar[20:40, 10:80] = True
    >>> mx.shape_distance(bar, bar)
    0.0
    >>> mx.shape_distance(bar, bar[::-1]) == 0.0      # mirrored: the same axis, reflected
    True
    >>> mx.shape_distance(bar, bar.T) < 0.05          # transposed: equal up to pixel noise
    True
    """
    sa, sb, params = _signature_pair(a, b, prune, options)
    if sa is sb:
        return 0.0
    return float(_score_block(_pack([sa, sb]), np.array([0]), np.array([1]), params)[0])


def match_tour(a: Any, b: Any, *, prune: float = DEFAULT_PRUNE, **options: Any) -> tuple[float, np.ndarray, np.ndarray]:
    """The tour alignment behind the main term of :func:`shape_distance`.

    Parameters are those of :func:`shape_distance`.

    Returns
    -------
    distance : float
        The tour term (NumPy reference computation).
    points_a, points_b : (p, 2) float64 ndarray
        Aligned tour samples: ``points_a[i]`` on ``a``'s axis matched
        ``points_b[i]`` on ``b``'s, in walk order (input units); on the axes
        of the closed shapes when that comparison was the better.

    Examples
    --------
    >>> import numpy as np
    >>> from medialaxis.compare import match_tour
    >>> bar = np.zeros((60, 90), bool); bar[20:40, 10:80] = True
    >>> d, pa, pb = match_tour(bar, bar)
    >>> d, len(pa), bool(np.array_equal(pa, pb))
    (0.0, 64, True)
    """
    sa, sb, params = _signature_pair(a, b, prune, options)
    value, va, vb, pairs = _kernels.tour_match_reference(
        sa.tour, sa.tour_radii, sb.tour, sb.tour_radii, params["gap"], sa.closing_gain, sb.closing_gain
    )
    index = np.asarray(pairs, np.int64).reshape(-1, 2)
    return value, sa.tour_points[va][index[:, 0]], sb.tour_points[vb][index[:, 1]]


# --------------------------------------------------------------- matrix


def _score_block(packed: tuple[np.ndarray, ...], rows: np.ndarray, cols: np.ndarray, params: dict[str, float]) -> np.ndarray:
    """Distances of the pairs ``(rows[p], cols[p])``; exactly symmetric."""
    return _kernels.tour_distances(*packed, rows, cols, params["gap"])
