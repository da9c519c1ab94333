"""Merged clusters of Voronoi nodes stay inside the shape (a cluster's mean can lie outside a thin bent part)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString

from medialaxis.planar.axis import raw_axis
from medialaxis.planar.axis_arrays import polygon_axis_arrays
from medialaxis.planar.axis_layer import polygon_axes
from medialaxis.planar.pipeline import sampled, voronoi_medial_axis
from medialaxis.planar.reading.inputs import load_planar
from tests.planar.merging import merge_close_nodes

#: Tolerances from a fifth of the narrower strip's width to above it: clusters of short edges along the bend.
TOLERANCES = (0.01, 0.013, 0.018, 0.024, 0.033, 0.044, 0.06)


def _vee(angle: float, width: float) -> shapely.Polygon:
    """A strip ``width`` wide bent by ``angle`` degrees at its apex, arms 1 long."""
    half = np.radians(angle) / 2
    arm = LineString([(-np.sin(half), np.cos(half)), (0, 0), (np.sin(half), np.cos(half))])
    return arm.buffer(width / 2, join_style="mitre", cap_style="flat")


def _lines(points: np.ndarray, edges: np.ndarray) -> shapely.Geometry:
    return shapely.multilinestrings(np.stack([points[edges[:, 0]], points[edges[:, 1]]], axis=1))


def _unchecked_mean_outside(shape: shapely.Polygon, tolerance: float, lam: float) -> bool:
    """Whether contracting every cluster of short edges to its mean would put a node outside ``shape``."""
    tolerance, _, _, rings, smp, tri, inside = sampled(load_planar(shape), lam=lam, tolerance=tolerance, detour=None,
                                                       boundary="contour")
    ax = raw_axis(tri, inside, smp, rings.region, rings.locator)
    assert shape.covers(shapely.points(ax.points)).all()  # the Voronoi nodes themselves are inside
    cluster, _, _ = merge_close_nodes(ax.points, ax.edges, tolerance)
    count = np.bincount(cluster)
    means = np.stack([np.bincount(cluster, ax.points[:, k]) / count for k in range(2)], axis=1)
    return not shape.covers(shapely.points(means[count > 1])).all()


@pytest.mark.parametrize(("angle", "width"), [(90.0, 0.05), (60.0, 0.1), (120.0, 0.05)])
def test_the_axis_of_a_bent_strip_stays_inside_it(angle: float, width: float) -> None:
    shape, lam = _vee(angle, width), width / 4  # lambda below the width: the arms are kept
    half = np.radians(angle) / 2
    ends = np.array([[-np.sin(half), np.cos(half)], [np.sin(half), np.cos(half)]])
    outside = []
    for tolerance in TOLERANCES:
        outside.append(_unchecked_mean_outside(shape, tolerance, lam))
        ma = voronoi_medial_axis(shape, tolerance=tolerance, lam=lam)
        arrays = polygon_axis_arrays(shape, tolerance=tolerance, lam=lam)
        (layer,) = polygon_axes([shape], tolerance=tolerance, lam=lam)
        assert all(np.array_equal(a, b) for a, b in zip(arrays, (ma.points, ma.radii, ma.edges)))
        assert all(np.array_equal(a, b) for a, b in zip(arrays, layer))
        assert len(ma.edges) > 0
        assert shape.covers(_lines(ma.points, ma.edges)), tolerance
        # the pruned axis still runs along both arms, to near their ends
        assert (np.min(np.linalg.norm(ma.points[:, None] - ends[None], axis=2), axis=0) < 0.2).all(), tolerance
    assert any(outside)  # the merge this guards against happens on this strip
