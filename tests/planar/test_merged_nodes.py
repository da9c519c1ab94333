"""Merged clusters of Voronoi nodes stay inside the shape (a cluster's mean can lie outside a thin bent part)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString

from medialaxis.planar.axis import raw_axis
from medialaxis.planar.axis_arrays import polygon_axis_arrays
from medialaxis.planar.axis_layer import polygon_axes
from medialaxis.planar.inputs import load_planar
from medialaxis.planar.pipeline import sampled, voronoi_medial_axis
from medialaxis.planar.pruning import merge_close_nodes


def _vee(angle: float, width: float) -> shapely.Polygon:
    """A strip ``width`` wide bent by ``angle`` degrees at its apex, arms 1 long."""
    half = np.radians(angle) / 2
    arm = LineString([(-np.sin(half), np.cos(half)), (0, 0), (np.sin(half), np.cos(half))])
    return arm.buffer(width / 2, join_style="mitre", cap_style="flat")


VEES = [(90.0, 0.1, 0.012), (30.0, 0.05, 0.034), (120.0, 0.05, 0.034)]


def _lines(points: np.ndarray, edges: np.ndarray) -> shapely.Geometry:
    if not len(edges):
        return shapely.multipoints(points)
    return shapely.multilinestrings(np.stack([points[edges[:, 0]], points[edges[:, 1]]], axis=1))


@pytest.mark.parametrize(("angle", "width", "tolerance"), VEES)
def test_an_unchecked_merge_would_leave_the_strip(angle: float, width: float, tolerance: float) -> None:
    """The premise: contracting every cluster of short edges to its mean puts a node outside the strip."""
    shape = _vee(angle, width)
    tolerance, _, _, rings, smp, tri, inside = sampled(load_planar(shape), lam=width / 4, tolerance=tolerance,
                                                       detour=None, boundary="contour")
    ax = raw_axis(tri, inside, smp, rings.region, rings.locator)
    assert shape.covers(shapely.points(ax.points)).all()  # the Voronoi nodes themselves are inside
    cluster, _, _ = merge_close_nodes(ax.points, ax.edges, tolerance)
    count = np.bincount(cluster)
    means = np.stack([np.bincount(cluster, ax.points[:, k]) / count for k in range(2)], axis=1)
    assert not shape.covers(shapely.points(means[count > 1])).all()


@pytest.mark.parametrize(("angle", "width", "tolerance"), VEES)
def test_the_axis_of_a_bent_strip_stays_inside_it(angle: float, width: float, tolerance: float) -> None:
    shape, lam = _vee(angle, width), width / 4  # lambda below the width: the arms are kept
    ma = voronoi_medial_axis(shape, tolerance=tolerance, lam=lam)
    arrays = polygon_axis_arrays(shape, tolerance=tolerance, lam=lam)
    (layer,) = polygon_axes([shape], tolerance=tolerance, lam=lam)
    for points, edges in ((ma.points, ma.edges), arrays[::2], layer[::2]):
        assert len(edges) > 0
        assert shape.covers(_lines(points, edges))
    assert all(np.array_equal(a, b) for a, b in zip(arrays, (ma.points, ma.radii, ma.edges)))
    # the pruned axis still runs along both arms, to near their ends
    half = np.radians(angle) / 2
    ends = np.array([[-np.sin(half), np.cos(half)], [np.sin(half), np.cos(half)]])
    reach = np.min(np.linalg.norm(ma.points[:, None] - ends[None], axis=2), axis=0)
    assert (reach < 0.2).all()
