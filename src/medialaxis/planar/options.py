"""Options of the planar method (:func:`medialaxis.planar.voronoi_medial_axis`)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

from medialaxis.core.options import LAM_FLAG, SPACING_FLAG, THRESHOLD_FLAG, Flag, Options, option

__all__ = ["PlanarOptions"]


@dataclass(frozen=True)
class PlanarOptions(Options):
    """Options of the planar Voronoi method; each is documented in :func:`~medialaxis.planar.voronoi_medial_axis`.

    >>> PlanarOptions(tolerance=0.01).changed()
    {'tolerance': 0.01}
    """

    lam: float | None = option(None, """
        Lambda of the lambda-medial axis: the smallest contact-set diameter
        kept, in output units. Default ``8 * tolerance`` (2 pixels for
        images): contact sets of sampling noise are below it, and noise
        branches with larger contacts are removed by the ``detour`` test.""", flag=LAM_FLAG)
    threshold: float | None = option(None, """
        Grey level of the foreground (default Otsu) for grey images.""", flag=THRESHOLD_FLAG)
    spacing: Any = option(None, """
        Pixel size along (rows, cols) for raster inputs.""", flag=SPACING_FLAG, kind="float or (2,) floats, optional")
    tolerance: float | None = option(None, """
        The one accuracy parameter: the boundary is simplified to within
        ``tolerance`` and sampled so that each Voronoi vertex lies within
        about ``tolerance`` of the axis of the simplified shape. Default: a
        quarter pixel for images, ``1e-4`` of the shape's size (twice the
        largest centroid-to-vertex distance) for polygons. Larger is faster
        and coarser. Polygons of more than 10,000 vertices and all image
        contours are first simplified to within ``tolerance``.""", flag=Flag("accuracy (output units)"))
    detour: float | None = option(None, """
        An edge is significant only if the boundary arc between its contacts
        exceeds their distance by ``detour`` times that distance and by
        ``2 * lam`` (scale-invariant noise test, see
        :mod:`medialaxis.planar.pruning`). Default 0.25 for images (pixel
        noise), 0.028 for polygons (drops only the branches of vertices
        flatter than about 153 degrees).""", flag=Flag("pruning detour ratio"))
    boundary: Literal["contour", "canny"] = option("contour", """
        ``"contour"``: sub-pixel iso-contour (default). ``"canny"``: the
        paper's route, Canny edge pixels as the point set with inside and
        outside taken from the filled region.""", flag=Flag("boundary extraction of images"))
    foreground: Literal["auto", "bright", "dark"] = option("auto", """
        For images: which side of the threshold is the shape. ``"bright"``
        takes the pixels above the threshold (True of a bool mask),
        ``"dark"`` those below it (a black shape on white paper).
        ``"auto"`` (default) takes the side that does not own most of the
        image border (the outermost rows and columns); a tie goes to the
        side with fewer pixels, then to the bright side. The side taken is
        ``metadata["foreground"]``. Vector inputs accept only ``"auto"``.""",
        flag=Flag("images: which side of the threshold is the shape; auto (the default) takes the side that does "
                  "not own most of the image border, so a dark shape on light paper works"))
    strokes: bool | None = option(None, """
        SVG: read strokes as the regions the pen paints (default True);
        False reads fills only.""", flag=Flag("SVG drawings: read fills only, not strokes", name="--fills-only",
                                              const=False))
    layers: Sequence[str] | None = option(None, """
        DXF: the layers to read (default every layer that is on and not
        frozen).""", flag=Flag("DXF drawings: the layers to read (default: every layer that is on and not frozen)",
                               nargs="+", metavar="LAYER", type=str), kind="sequence of str, optional")
    labels: bool | None = option(None, """
        Whether an integer image is a label image (0 background, every
        other value one object, objects may touch), never thresholded: each
        label gets its own axis, and the result's points carry their label
        (``ma.point_label``; ``metadata["labels"]`` lists them). Default:
        integer arrays of 32 or 64 bits are labels (as
        :func:`skimage.measure.label` gives), 8 and 16-bit ones grey images;
        image files are labels only with ``labels=True``.""",
        flag=Flag("images: an integer image is a label image, one axis per label", const=True))
    channel_axis: int | None = option(-1, """
        The colour axis of a 3D array (3 channels RGB or 4 RGBA; default the
        last), as scikit-image names it. RGB becomes grey as
        :func:`skimage.color.rgb2gray` does; an alpha channel that is not
        constant is the shape (what is opaque is painted).
        ``metadata["channels"]`` says which. ``None``: the array has no
        colour axis (a volume, for :func:`medialaxis.medial_axis`).""", kind="int or None")
