"""The planar pipeline: input -> boundary sample -> Delaunay -> Voronoi axis -> pruning.

This follows "A Qualitative Approach for Medial Computation" (image, boundary
points, Delaunay triangulation, axis from circumcentres, pruning of the
outside parts, radius per point, edge structure, validation by rebuilding the
shape) with the lambda-medial axis of Boissonnat, Wormser and Yvinec, "Curved
Voronoi diagrams", section 2.7 (Algorithm 5), and a topology-preserving
pruning (:mod:`medialaxis.planar.pruning`); the works are in
docs/references.md.
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Callable
from typing import Any

import numpy as np
import shapely

from medialaxis._progress import Progress, check_cancel
from medialaxis.core.options import make_options, takes_options
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import ComputationError, InvalidInputError
from medialaxis.planar._axis_kernels import merged_nodes
from medialaxis.planar._kernels import DRAWING_OVER_SPLIT, OVER_SPLIT
from medialaxis.planar.axis import RawAxis, boundary_distance, raw_axis
from medialaxis.planar.boundary.adaptive import sample_and_triangulate
from medialaxis.planar.boundary.corners import ring_arrays
from medialaxis.planar.boundary.sampling import BoundarySample, Rings, simplify_rings
from medialaxis.planar.delaunay import Triangulation
from medialaxis.planar.options import PlanarOptions
from medialaxis.planar.pruning import prune_graph
from medialaxis.planar.reading.inputs import PlanarInput, load_planar
from medialaxis.planar.reading.labels import merged_label_axes

__all__ = ["voronoi_medial_axis", "planar_stages", "reprune", "Stages", "DEFAULT_DETOUR", "STAGES"]

#: The stages the callback hears of, in order.
STAGES = ("load", "sample", "axis", "prune")

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


def _load(shape: Any, opts: PlanarOptions) -> PlanarInput:
    tolerance = None if opts.tolerance is None else check_number(opts.tolerance, "tolerance")
    layers = [opts.layers] if isinstance(opts.layers, str) else opts.layers
    return load_planar(
        shape, threshold=opts.threshold, spacing=opts.spacing, foreground=opts.foreground, tolerance=tolerance,
        strokes=opts.strokes, layers=layers, labels=opts.labels, channel_axis=opts.channel_axis,
    )


@takes_options(PlanarOptions)
def planar_stages(shape: Any, options: PlanarOptions | None = None, **kwargs: Any) -> Stages:
    """Run the planar pipeline and keep every stage (see :func:`voronoi_medial_axis`).

    Parameters
    ----------
    shape : array_like, path or shapely geometry
        As :func:`voronoi_medial_axis` takes it.
    {options}
    """
    opts = make_options(PlanarOptions, options, kwargs, "planar_stages")
    src = _load(shape, opts)
    if src.labels is not None:
        raise InvalidInputError(
            "the stages of a label image are not kept; draw one object's stages from its mask (image == label)"
        )
    return _stages(src, lam=opts.lam, tolerance=opts.tolerance, detour=opts.detour, boundary=opts.boundary)


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
        from medialaxis.planar.boundary.canny import canny_stages

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
    prune: bool = True, callback: Callable[[Progress], Any] | None = None,
) -> Stages:
    """Every stage of the pipeline on a loaded input (``prune=False``: the result is the raw axis)."""
    check_cancel(callback, Progress("voronoi", STAGES[1], 1, len(STAGES)))
    tolerance, lam, detour, rings, smp, tri, inside = sampled(src, lam=lam, tolerance=tolerance, detour=detour,
                                                             boundary=boundary)
    check_cancel(callback, Progress("voronoi", STAGES[2], 2, len(STAGES)))
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
    if src.is_raster and src.image is not None:
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
    if prune:
        check_cancel(callback, Progress("voronoi", STAGES[3], 3, len(STAGES)))
    return Stages(src, rings, smp, tri, inside, raw, _pruned(raw, lam, detour) if prune else raw)


@takes_options(PlanarOptions)
def voronoi_medial_axis(
    shape: Any, options: PlanarOptions | None = None, *, callback: Callable[[Progress], Any] | None = None,
    **kwargs: Any,
) -> MedialAxis:
    """Medial axis of a planar shape from the Voronoi diagram of boundary samples.

    Parameters
    ----------
    shape : array_like, path or shapely geometry
        2D bool mask, 2D grey image, ``(n, 2)`` boundary loop, shapely
        ``Polygon``/``MultiPolygon`` (holes allowed), or a PNG / JPEG / TIFF /
        BMP / SVG / GeoJSON / WKT file.
    callback : callable, optional
        ``callback(Progress)`` before each stage (``"load"``, ``"sample"``,
        ``"axis"``, ``"prune"``; a label image's ``"label axes"`` once per
        label); returning ``False`` cancels.
    {options}

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
    .. [1] "A Qualitative Approach for Medial Computation" (Voronoi/Delaunay medial axis of a
           2D image; authors, venue and year unconfirmed: docs/references.md).
    .. [2] J.-D. Boissonnat, C. Wormser, M. Yvinec, "Curved Voronoi diagrams", in J.-D.
           Boissonnat, M. Teillaud (eds.), Effective Computational Geometry for Curves and
           Surfaces, Springer, 67-116, 2006, section 2.7 (the lambda-medial axis, Lemma 10,
           Algorithm 5). https://hal.archives-ouvertes.fr/hal-00488446

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
    opts = make_options(PlanarOptions, options, kwargs, "voronoi_medial_axis")
    check_cancel(callback, Progress("voronoi", "load", 0, len(STAGES)))
    src = _load(shape, opts)
    if src.labels is not None:
        return _label_axes(src, opts, callback)
    return _stages(src, lam=opts.lam, tolerance=opts.tolerance, detour=opts.detour, boundary=opts.boundary,
                   callback=callback).result


def _label_axes(src: PlanarInput, opts: PlanarOptions, callback: Callable[[Progress], Any] | None) -> MedialAxis:
    """One axis per label of a label image, in one result whose points carry their label."""
    if opts.boundary != "contour":
        raise InvalidInputError(f"boundary={opts.boundary!r} does not apply to label images (each label is a mask)")
    done = itertools.count()

    def axis_of(one: PlanarInput) -> MedialAxis:  # each label's raw axis; all are pruned at once below
        check_cancel(callback, Progress("voronoi", "label axes", next(done), len(src.labels or ())))
        return _stages(one, lam=opts.lam, tolerance=opts.tolerance, detour=opts.detour, boundary=opts.boundary,
                       prune=False).raw

    raw = merged_label_axes(src, axis_of)
    return _pruned(raw, float(raw.metadata["lam"]), float(raw.metadata["detour"]))


def reprune(ma: MedialAxis, *, lam: float | None = None, detour: float | None = None) -> MedialAxis:
    """Re-prune a planar result from its unpruned axis (``ma.raw``)."""
    raw = ma.raw if ma.raw is not None else ma
    lam = float(ma.metadata["lam"]) if lam is None else check_number(lam, "lam")
    detour = float(ma.metadata["detour"]) if detour is None else check_number(detour, "detour")
    return _pruned(raw, lam, detour)
