"""The top-level :func:`medial_axis` dispatcher."""

from __future__ import annotations

from typing import Any

from medialaxis import _dispatch
from medialaxis.core.result import MedialAxis

__all__ = ["medial_axis"]


def medial_axis(
    shape: Any,
    *,
    method: str | None = None,
    lam: float | None = None,
    threshold: float | None = None,
    spacing: Any = None,
    **options: Any,
) -> MedialAxis:
    """Medial axis transform of a 2D shape, a 3D mesh or a 3D volume.

    Parameters
    ----------
    shape : array_like, path, shapely geometry or mesh
        A 2D bool mask or grey image, an ``(n, 2)`` closed boundary loop
        (non-bool dtype), a shapely ``Polygon``/``MultiPolygon``, an image /
        SVG / GeoJSON / WKT file; a mesh (``trimesh.Trimesh`` or mesh file);
        or a 3D volume (array or volume file). The input is never modified.
        A result saved by :meth:`MedialAxis.save` (``.json``, ``.npz``) is
        returned as loaded (re-pruned if ``lam`` or ``detour`` is given).
    method : str, optional
        Method within the input's domain. Planar: ``"voronoi"`` (default).
        Other domains list theirs in their error message.
    lam : float, optional
        Lambda of the lambda-medial axis: the smallest diameter of the
        contact set kept, in output units. ``None`` picks the method's
        documented default.
    threshold : float, optional
        Grey level separating foreground from background for grey images
        (default: Otsu's threshold). Which side is the shape is the planar
        option ``foreground`` (``"auto"``: the side that does not own most
        of the image border; ``"bright"``; ``"dark"``).
    spacing : float or sequence of float, optional
        Physical size of a pixel/voxel along each array axis (default 1).
        A ``(rows, cols, 3 | 4)`` array is a colour image (RGB or RGBA, as
        ``skimage.io.imread`` gives it); the option ``channel_axis`` names
        another colour axis, or ``None`` for a volume whose last axis has 3
        or 4 entries. Integer arrays of 32 or 64 bits are label images (one
        axis per label; option ``labels``).
    **options
        The method's options, as keywords or as one frozen dataclass
        ``options=`` (:class:`~medialaxis.PlanarOptions`,
        :class:`~medialaxis.MeshVoronoiOptions`, :class:`~medialaxis.FlowOptions`,
        :class:`~medialaxis.MidsurfaceOptions`, :class:`~medialaxis.VoxelOptions`),
        documented by the method and listed in ``docs/options.md``; and the
        progress ``callback`` (:class:`~medialaxis._progress.Progress`).

    Returns
    -------
    MedialAxis

    Raises
    ------
    InvalidInputError
        Bad array shape or dtype, NaN coordinates, empty shape, unknown
        method or option.
    InputFileError
        A file that is missing, unreadable or corrupt.
    ResourceLimitError
        An input too large to process in the memory allowed.

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> mask = np.zeros((40, 80), bool); mask[10:30, 10:70] = True
    >>> ma = mx.medial_axis(mask)
    >>> len(ma.endpoints), len(ma.junctions)
    (4, 2)
    """
    domain = _dispatch.classify(shape, method, options)
    given = {"lam": lam, "threshold": threshold, "spacing": spacing}
    kwargs = {k: v for k, v in given.items() if v is not None}
    kwargs.update(options)
    if domain != "planar" and "channel_axis" in kwargs and kwargs["channel_axis"] is None:
        del kwargs["channel_axis"]  # "no colour axis" said of a volume: nothing for its method to do
    if domain == _dispatch.RESULT:
        return _dispatch.load_result(shape, method, kwargs)
    name, fn = _dispatch.resolve(domain, method)
    _dispatch.announce_compiling(domain, name)
    return _dispatch.call_checked(fn, shape, kwargs)
