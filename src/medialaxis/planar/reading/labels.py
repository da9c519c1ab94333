"""Label images: every labelled object is a shape of its own, never thresholded.

A label image (as :func:`skimage.measure.label`, :func:`scipy.ndimage.label`
or a cell segmentation gives) holds an integer per pixel: 0 is background,
each other value one object. Objects may touch: the border between two
labels bounds both. Each object is contoured on its own bounding box (plus
one pixel), as a binary mask is (sub-pixel 0.5 contour, smoothed along its
length by one pixel), in index order scaled by ``spacing``.
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import shapely

from medialaxis._progress import progress
from medialaxis.core.result import MedialAxis
from medialaxis.errors import ComputationError, EmptyShapeError, InvalidInputError, MedialAxisWarning
from medialaxis.planar.reading.images import BINARY_SMOOTHING, contour_region

__all__ = ["is_label_image", "label_regions", "merged_label_axes"]


def is_label_image(image: np.ndarray, labels: bool | None) -> bool:
    """Whether an array is read as labels.

    ``labels=None`` (default) takes integer arrays of 32 or 64 bits as
    labels (the dtypes of :func:`skimage.measure.label` and
    :func:`scipy.ndimage.label`) and 8 and 16-bit ones as grey images (the
    dtypes of photographs and scans). ``labels=True`` reads any integer
    array as labels (a uint16 segmentation), ``labels=False`` none.
    """
    if labels is None:
        return image.ndim == 2 and image.dtype.kind in "iu" and image.dtype.itemsize >= 4
    if labels and (image.ndim != 2 or image.dtype.kind not in "iu"):
        raise InvalidInputError(
            f"labels=True needs a 2D integer image, got an array of shape {image.shape} and dtype {image.dtype}"
        )
    return bool(labels)


def label_regions(image: np.ndarray, spacing: np.ndarray) -> list[tuple[int, Any]]:
    """The region of every label (> 0) of a label image, in index order scaled by ``spacing``.

    Parameters
    ----------
    image : (rows, cols) integer ndarray
        0 is background; negative values are refused.
    spacing : (2,) float ndarray

    Returns
    -------
    list of (int, shapely Polygon or MultiPolygon)
        In increasing label order.

    Raises
    ------
    InvalidInputError
        A negative label.
    EmptyShapeError
        No label other than 0.

    Examples
    --------
    >>> image = np.zeros((10, 20), np.int32); image[2:8, 2:9] = 1; image[2:8, 9:18] = 2
    >>> [(label, round(region.area)) for label, region in label_regions(image, np.ones(2))]
    [(1, 39), (2, 51)]
    """
    from scipy import ndimage

    if image.size and image.min() < 0:
        raise InvalidInputError(f"labels must be >= 0 (0 is background), got {int(image.min())}")
    values, dense = np.unique(image, return_inverse=True)
    dense = dense.reshape(image.shape)
    if values[0] != 0:  # no background: label k is at index k - 1, make it k
        dense += 1
        values = np.r_[0, values]
    if len(values) < 2:
        raise EmptyShapeError("the label image has no label other than 0 (background)")
    out = []
    for index, box in enumerate(ndimage.find_objects(dense), start=1):
        if box is None:
            continue
        rows = slice(max(box[0].start - 1, 0), box[0].stop + 1)
        cols = slice(max(box[1].start - 1, 0), box[1].stop + 1)
        mask = dense[rows, cols] == index
        region = contour_region(mask, 0.5, spacing, smoothing=BINARY_SMOOTHING)
        region = shapely.affinity.translate(region, rows.start * spacing[0], cols.start * spacing[1])
        out.append((int(values[index]), region))
    return out


def merged_label_axes(src: Any, axis_of: Callable[[Any], MedialAxis]) -> MedialAxis:
    """The unpruned axes of every label of a loaded label image, in one result.

    Parameters
    ----------
    src : PlanarInput
        A loaded label image (``src.labels`` holds each label and its region).
    axis_of : callable
        The unpruned axis (with its contact extras) of a loaded input: called
        with ``src`` restricted to one label's region.

    Returns
    -------
    MedialAxis
        Points, radii and edges of every label's axis, with the per-point
        extra ``point_label``; ``metadata["labels"]`` lists the labels.
        Labels without an axis (degenerate objects) are left out with a
        :class:`~medialaxis.MedialAxisWarning` and listed in
        ``metadata["labels_without_axis"]``.
    """
    raws = []
    failed = {}
    for label, region in progress(src.labels, desc="labels"):
        try:
            raws.append((label, axis_of(dataclasses.replace(src, region=region, labels=None))))
        except (EmptyShapeError, ComputationError) as exc:
            failed[label] = str(exc)
    if not raws:
        raise EmptyShapeError(f"no label of the image has a medial axis: {next(iter(failed.values()), '')}")
    if failed:
        shown = ", ".join(f"{label} ({reason})" for label, reason in list(failed.items())[:3])
        warnings.warn(f"{len(failed)} labels have no medial axis: {shown}", MedialAxisWarning, stacklevel=4)
    counts = np.array([len(raw.points) for _, raw in raws])
    offsets = np.r_[0, np.cumsum(counts)[:-1]]
    metadata = {
        **{k: v for k, v in raws[0][1].metadata.items() if k not in ("threshold", "foreground")},
        "image_shape": tuple(int(n) for n in src.image.shape),
        "foreground": "labels",
        "labels": [label for label, _ in raws],
        "n_samples": int(sum(raw.metadata["n_samples"] for _, raw in raws)),
        "n_polygons": int(sum(raw.metadata["n_polygons"] for _, raw in raws)),
        "n_holes": int(sum(raw.metadata["n_holes"] for _, raw in raws)),
    }
    if failed:
        metadata["labels_without_axis"] = sorted(failed)
    return MedialAxis(
        np.concatenate([r.points for _, r in raws]),
        np.concatenate([r.radii for _, r in raws]),
        np.concatenate([r.edges + o for (_, r), o in zip(raws, offsets)]),
        extras={
            **{key: np.concatenate([r.extras[key] for _, r in raws]) for key in raws[0][1].extras},
            "point_label": np.repeat(np.array([label for label, _ in raws], dtype=np.int64), counts),
        },
        metadata=metadata,
        shape=src.region,
    )
