"""The planar pipeline: input -> boundary sample -> Delaunay -> Voronoi axis -> pruning.

This follows paper 000 (image, boundary points, Delaunay triangulation,
axis from circumcentres, pruning of the outside parts, radius per point,
edge structure, validation by rebuilding the shape) with the
lambda-medial axis of paper 001 (Algorithm 5) and a topology-preserving
pruning (:mod:`medialaxis.planar.pruning`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any, Literal

import numpy as np
import shapely

from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import ComputationError, InvalidInputError
from medialaxis.planar._axis_kernels import merged_nodes
from medialaxis.planar._kernels import DRAWING_OVER_SPLIT, OVER_SPLIT
from medialaxis.planar.adaptive import sample_and_triangulate
from medialaxis.planar.axis import RawAxis, boundary_distance, raw_axis
from medialaxis.planar.corners import ring_arrays
from medialaxis.planar.delaunay import Triangulation
from medialaxis.planar.inputs import PlanarInput, load_planar
from medialaxis.planar.labels import merged_label_axes
from medialaxis.planar.pruning import prune_graph
from medialaxis.planar.sampling import BoundarySample, Rings, simplify_rings

__all__ = ["voronoi_medial_axis", "planar_stages", "reprune", "Stages", "DEFAULT_DETOUR"]

#: Default detour ratio of the pruning (see :mod:`medialaxis.planar.pruning`)
#: for raster inputs, whose contours carry pixel noise ...
DEFAULT_DETOUR = 0.25
#: ... and for exact vector inputs, where only branches of nearly flat
#: vertices (interior angle above about 153 degrees) are noise. The value
#: sits between the corner ratios of regular 13- and 14-gons (0.030 and
#: 0.026), away from any regular polygon's.
DEFAULT_VECTOR_DETOUR = 0.028
#: Default lambda in units of the tolerance.
LAM_PER_TOLERANCE = 8.0
#: Polygons with more vertices than this are simplified to the tolerance first.
SIMPLIFY_ABOVE = 10_000


#: Smallest ring (piece or hole), as a fraction of the shape's size, that the
#: triangulation resolves: its samples are jittered by 1e-9 of the extent.
MIN_RING_FRACTION = 1e-6


def _check_resolution(rings: Rings, size: float) -> None:
    """Refuse a ring far smaller than the shape: float64 cannot triangulate both at once."""
    extents = [float(np.ptp(v, axis=0).max()) for v in rings.vertices if len(v)]
    if extents and min(extents) < MIN_RING_FRACTION * size:
        raise InvalidInputError(
            f"the shape is {size:.3g} across but has a ring (a piece or a hole) only {min(extents):.3g} across: "
            f"details below {MIN_RING_FRACTION:g} of the size cannot be triangulated together with it; "
            "remove them or split the shape"
        )


def shape_size(region: Any) -> float:
    """Twice the largest distance from the centroid to a vertex (rotation invariant)."""
    xy = shapely.get_coordinates(region)
    centre = np.asarray(region.centroid.coords[0])
    return 2.0 * float(np.sqrt(((xy - centre) ** 2).sum(1).max()))


@dataclasses.dataclass(frozen=True)
class Stages:
    """Every intermediate of one planar run, for figures and debugging.

    Attributes
    ----------
    source : PlanarInput
    rings : Rings
        The simplified boundary.
    samples : BoundarySample
    triangulation : Triangulation
    inside : (T,) bool ndarray
        Triangles inside the shape.
    raw : MedialAxis
        The unpruned inner Voronoi axis.
    result : MedialAxis
        The pruned axis.
    """

    source: PlanarInput
    rings: Rings
    samples: BoundarySample
    triangulation: Triangulation
    inside: np.ndarray
    raw: MedialAxis
    result: MedialAxis


def _pruned(raw: MedialAxis, lam: float, detour: float) -> MedialAxis:
    """Prune ``raw`` (which carries contact data as extras) with ``lam`` and ``detour``."""
    old, edges = prune_graph(
        raw.radii,
        raw.edges,
        raw.extras["edge_contact_diameter"],
        raw.extras["edge_contact_arc"],
        raw.extras["edge_adjacent_contacts"],
        lam,
        detour,
    )
    metadata = dict(raw.metadata, lam=lam, detour=detour, pruned=True)
    # per-point extras (the label of each point of a label image) follow their points
    extras = {k: v[old] for k, v in raw.extras.items() if k.startswith("point_")}
    return MedialAxis(
        raw.points[old], raw.radii[old], edges, extras=extras, metadata=metadata, shape=raw.shape, raw=raw
    )


def _load(
    shape: Any,
    *,
    threshold: float | None,
    spacing: Any,
    tolerance: float | None,
    boundary: str,
    foreground: str,
    strokes: bool | None,
    layers: Sequence[str] | None,
    labels: bool | None,
    channel_axis: int | None,
) -> PlanarInput:
    if boundary not in ("contour", "canny"):
        raise InvalidInputError(f"boundary must be 'contour' or 'canny', got {boundary!r}")
    if tolerance is not None:
        tolerance = check_number(tolerance, "tolerance")
    if isinstance(layers, str):
        layers = [layers]
    return load_planar(
        shape, threshold=threshold, spacing=spacing, foreground=foreground, tolerance=tolerance, strokes=strokes,
        layers=layers, labels=labels, channel_axis=channel_axis,
    )


def planar_stages(
    shape: Any,
    *,
    lam: float | None = None,
    threshold: float | None = None,
    spacing: Any = None,
    tolerance: float | None = None,
    detour: float | None = None,
    boundary: Literal["contour", "canny"] = "contour",
    foreground: Literal["auto", "bright", "dark"] = "auto",
    strokes: bool | None = None,
    layers: Sequence[str] | None = None,
    labels: bool | None = None,
    channel_axis: int | None = -1,
) -> Stages:
    """Run the planar pipeline and keep every stage (see :func:`voronoi_medial_axis`)."""
    src = _load(
        shape, threshold=threshold, spacing=spacing, tolerance=tolerance, boundary=boundary, foreground=foreground,
        strokes=strokes, layers=layers, labels=labels, channel_axis=channel_axis,
    )
    if src.labels is not None:
        raise InvalidInputError(
            "the stages of a label image are not kept; draw one object's stages from its mask (image == label)"
        )
    return _stages(src, lam=lam, tolerance=tolerance, detour=detour, boundary=boundary)


def parameters(size: float, lam: float | None, tolerance: float | None, detour: float | None,
               pixel: float | None = None) -> tuple[float, float, float]:
    """The tolerance, lambda and detour in force for a shape of ``size`` (``pixel``: a raster's smallest spacing)."""
    if tolerance is None:
        tolerance = 0.25 * pixel if pixel is not None else 1e-4 * size
    tolerance = check_number(tolerance, "tolerance")
    # Below about 1e-9 of the size, float64 and the triangulation's jitter cannot tell samples apart.
    tolerance = max(tolerance, 1e-9 * size)
    lam = LAM_PER_TOLERANCE * tolerance if lam is None else check_number(lam, "lam")
    if detour is None:
        detour = DEFAULT_DETOUR if pixel is not None else DEFAULT_VECTOR_DETOUR
    return tolerance, lam, check_number(detour, "detour")


def sampled(
    src: PlanarInput, *, lam: float | None, tolerance: float | None, detour: float | None, boundary: str
) -> tuple[float, float, float, Rings, BoundarySample, Triangulation, np.ndarray]:
    """The tolerance, lambda and detour in force, the rings, the sample, its triangulation and inner triangles."""
    region = src.region
    size = shape_size(region)
    tolerance, lam, detour = parameters(size, lam, tolerance, detour,
                                        float(src.spacing.min()) if src.is_raster else None)
    if boundary == "canny":
        if not src.is_raster:
            raise InvalidInputError("boundary='canny' needs an image input")
        from medialaxis.planar.canny import canny_stages

        smp, rings, tri, inside = canny_stages(src, tolerance)
    else:
        # Small polygons keep every vertex, so the axis does not depend on
        # where a ring starts (Douglas-Peucker does) and stays exactly
        # equivariant under rotation, scaling and mirroring.
        n_vertices = len(shapely.get_coordinates(region))
        simplify = src.is_raster or n_vertices > SIMPLIFY_ABOVE
        rings = simplify_rings(region, tolerance if simplify else 0.0)
        _check_resolution(rings, size)
        min_length = max(tolerance, lam / 8.0)
        over_split = DRAWING_OVER_SPLIT if src.drawing is not None else OVER_SPLIT
        smp, tri, inside = sample_and_triangulate(rings, rings.region, tolerance, min_length, over_split)
    if not inside.any():
        raise ComputationError("no Delaunay triangle lies inside the shape; is it degenerate?")
    return tolerance, lam, detour, rings, smp, tri, inside


def _stages(
    src: PlanarInput, *, lam: float | None, tolerance: float | None, detour: float | None, boundary: str,
    prune: bool = True,
) -> Stages:
    """Every stage of the pipeline on a loaded input (``prune=False``: the result is the raw axis)."""
    tolerance, lam, detour, rings, smp, tri, inside = sampled(src, lam=lam, tolerance=tolerance, detour=detour,
                                                             boundary=boundary)
    ax: RawAxis = raw_axis(tri, inside, smp, rings.region, rings.locator, ring_arrays(rings))
    region = src.region
    # Co-circular samples give clusters of coincident Voronoi vertices (the
    # centre of a disc, the mid-line of a rectangle): one node each, at the
    # mean, where it stays inside (a member's ball: its Delaunay circle).
    loc = rings.locator
    cluster, kept, points, count = merged_nodes(ax.points, np.asarray(tri.radii, np.float64)[ax.triangle], ax.edges,
                                                tolerance, loc.segments, loc.start, loc.members, loc.y0, loc.height)
    edges = cluster[ax.edges[kept]].reshape(-1, 2)
    radii = np.bincount(cluster, ax.radii) / count
    merged = count > 1
    radii[merged] = boundary_distance(points[merged], smp)
    metadata = {
        "domain": "planar",
        "method": "voronoi",
        "boundary": boundary,
        "tolerance": tolerance,
        "lam": lam,
        "detour": detour,
        "spacing": tuple(float(s) for s in src.spacing),
        "n_samples": int(len(smp.points)),
        "n_polygons": int(len(getattr(region, "geoms", [region]))),
        "n_holes": int(sum(len(p.interiors) for p in getattr(region, "geoms", [region]))),
    }
    if src.is_raster:
        metadata["image_shape"] = tuple(int(s) for s in src.image.shape)
        metadata["threshold"] = src.threshold
        metadata["foreground"] = src.side
    if src.channels is not None:
        metadata["channels"] = src.channels
    metadata["repairs"] = [src.repaired] if src.repaired else []  # the mesh routes' name: one list of what was mended
    if src.drawing is not None:
        metadata["drawing"] = src.drawing
    raw = MedialAxis(
        points,
        radii,
        edges,
        extras={
            "edge_contact_diameter": ax.contact_diameter[kept],
            "edge_contact_arc": ax.contact_arc[kept],
            "edge_adjacent_contacts": ax.adjacent[kept],
        },
        metadata=dict(metadata, pruned=False),
        shape=region,
    )
    return Stages(src, rings, smp, tri, inside, raw, _pruned(raw, lam, detour) if prune else raw)


def voronoi_medial_axis(
    shape: Any,
    *,
    lam: float | None = None,
    threshold: float | None = None,
    spacing: Any = None,
    tolerance: float | None = None,
    detour: float | None = None,
    boundary: Literal["contour", "canny"] = "contour",
    foreground: Literal["auto", "bright", "dark"] = "auto",
    strokes: bool | None = None,
    layers: Sequence[str] | None = None,
    labels: bool | None = None,
    channel_axis: int | None = -1,
) -> MedialAxis:
    """Medial axis of a planar shape from the Voronoi diagram of boundary samples.

    Parameters
    ----------
    shape : array_like, path or shapely geometry
        2D bool mask, 2D grey image, ``(n, 2)`` boundary loop, shapely
        ``Polygon``/``MultiPolygon`` (holes allowed), or a PNG / JPEG / TIFF /
        BMP / SVG / GeoJSON / WKT file.
    lam : float, optional
        Lambda of the lambda-medial axis: the smallest contact-set diameter
        kept, in output units. Default ``8 * tolerance`` (2 pixels for
        images): contact sets of sampling noise are below it, and noise
        branches with larger contacts are removed by the ``detour`` test.
    threshold : float, optional
        Grey level of the foreground (default Otsu) for grey images.
    spacing : float or (2,) floats, optional
        Pixel size along (rows, cols) for raster inputs.
    tolerance : float, optional
        The one accuracy parameter: the boundary is simplified to within
        ``tolerance`` and sampled so that each Voronoi vertex lies within
        about ``tolerance`` of the axis of the simplified shape. Default: a
        quarter pixel for images, ``1e-4`` of the shape's size (twice the
        largest centroid-to-vertex distance) for polygons. Larger is faster
        and coarser. Polygons of more than 10,000 vertices and all image
        contours are first simplified to within ``tolerance``.
    detour : float, optional
        An edge is significant only if the boundary arc between its contacts
        exceeds their distance by ``detour`` times that distance and by
        ``2 * lam`` (scale-invariant noise test, see
        :mod:`medialaxis.planar.pruning`). Default 0.25 for images (pixel
        noise), 0.028 for polygons (drops only the branches of vertices
        flatter than about 153 degrees).
    boundary : {"contour", "canny"}
        ``"contour"``: sub-pixel iso-contour (default). ``"canny"``: the
        paper's route, Canny edge pixels as the point set with inside and
        outside taken from the filled region.
    foreground : {"auto", "bright", "dark"}
        For images: which side of the threshold is the shape. ``"bright"``
        takes the pixels above the threshold (True of a bool mask),
        ``"dark"`` those below it (a black shape on white paper).
        ``"auto"`` (default) takes the side that does not own most of the
        image border (the outermost rows and columns); a tie goes to the
        side with fewer pixels, then to the bright side. The side taken is
        ``metadata["foreground"]``. Vector inputs accept only ``"auto"``.
    strokes : bool, optional
        SVG: read strokes as the regions the pen paints (default True);
        False reads fills only.
    layers : sequence of str, optional
        DXF: the layers to read (default every layer that is on and not
        frozen).
    labels : bool, optional
        Whether an integer image is a label image (0 background, every
        other value one object, objects may touch), never thresholded: each
        label gets its own axis, and the result's points carry their label
        (``ma.point_label``; ``metadata["labels"]`` lists them). Default:
        integer arrays of 32 or 64 bits are labels (as
        :func:`skimage.measure.label` gives), 8 and 16-bit ones grey images;
        image files are labels only with ``labels=True``.
    channel_axis : int or None
        The colour axis of a 3D array (3 channels RGB or 4 RGBA; default the
        last), as scikit-image names it. RGB becomes grey as
        :func:`skimage.color.rgb2gray` does; an alpha channel that is not
        constant is the shape (what is opaque is painted).
        ``metadata["channels"]`` says which. ``None``: the array has no
        colour axis (a volume, for :func:`medialaxis.medial_axis`).

    Returns
    -------
    MedialAxis
        One connected axis per piece of the shape and one independent cycle
        per hole. For images, pieces are 4-connected: foreground pixels
        that touch only at a corner are separate pieces, as
        ``skimage.measure.label(mask, connectivity=1)`` counts them.
        ``points`` (n, 2), ``radii`` (distance to the boundary), ``edges``;
        ``metadata`` holds the parameters used; ``raw`` the unpruned axis
        (extras ``edge_contact_diameter``, ``edge_contact_arc`` and
        ``edge_adjacent_contacts``).

    Raises
    ------
    InvalidInputError, EmptyShapeError, InputFileError, ResourceLimitError

    References
    ----------
    Paper 000 (Voronoi/Delaunay medial computation from boundary points) and
    paper 001 (lambda-medial axis, Lemma 10, Algorithm 5).

    Examples
    --------
    >>> from shapely.geometry import box
    >>> ma = voronoi_medial_axis(box(0, 0, 4, 2))
    >>> len(ma.endpoints), len(ma.junctions)
    (4, 2)

    A dark rectangle with a round hole, printed on light paper:

    >>> import numpy as np
    >>> rows, cols = np.mgrid[:60, :100]
    >>> paper = np.full((60, 100), 240, np.uint8)
    >>> paper[10:50, 10:90] = 20
    >>> paper[(rows - 30) ** 2 + (cols - 50) ** 2 < 8**2] = 240
    >>> ma = voronoi_medial_axis(paper)
    >>> ma.metadata["foreground"], ma.n_components, ma.n_cycles
    ('dark', 1, 1)
    """
    src = _load(
        shape, threshold=threshold, spacing=spacing, tolerance=tolerance, boundary=boundary, foreground=foreground,
        strokes=strokes, layers=layers, labels=labels, channel_axis=channel_axis,
    )
    if src.labels is not None:
        return _label_axes(src, lam=lam, tolerance=tolerance, detour=detour, boundary=boundary)
    return _stages(src, lam=lam, tolerance=tolerance, detour=detour, boundary=boundary).result


def _label_axes(
    src: PlanarInput, *, lam: float | None, tolerance: float | None, detour: float | None, boundary: str
) -> MedialAxis:
    """One axis per label of a label image, in one result whose points carry their label."""
    if boundary != "contour":
        raise InvalidInputError(f"boundary={boundary!r} does not apply to label images (each label is a mask)")
    # each label's raw axis; all are pruned at once below
    raw = merged_label_axes(src, lambda one: _stages(one, lam=lam, tolerance=tolerance, detour=detour,
                                                     boundary=boundary, prune=False).raw)
    return _pruned(raw, float(raw.metadata["lam"]), float(raw.metadata["detour"]))


def reprune(ma: MedialAxis, *, lam: float | None = None, detour: float | None = None) -> MedialAxis:
    """Re-prune a planar result from its unpruned axis (``ma.raw``)."""
    raw = ma.raw if ma.raw is not None else ma
    lam = float(ma.metadata["lam"]) if lam is None else check_number(lam, "lam")
    detour = float(ma.metadata["detour"]) if detour is None else check_number(detour, "detour")
    return _pruned(raw, lam, detour)
