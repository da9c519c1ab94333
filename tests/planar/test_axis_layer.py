"""Many polygons' axes with their shapely work vectorised (planar.axis_layer) against one polygon at a time, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, Point, Polygon, box

from medialaxis.errors import EmptyShapeError, InvalidInputError
from medialaxis.planar import axis_layer
from medialaxis.planar.axis_arrays import polygon_axis_arrays
from medialaxis.planar.axis_layer import polygon_axes
from tests.planar.test_axis_arrays import CASES


def _same(one, other) -> bool:  # type: ignore[no-untyped-def]
    return all(np.array_equal(a, b) for a, b in zip(one, other))


@pytest.mark.parametrize("options", [{}, {"detour": 1.0}, {"lam": 0.05, "tolerance": 1e-3}])
def test_the_layers_axes_are_each_polygons_axis(options: dict) -> None:
    shapes = list(CASES.values())
    axes = polygon_axes(shapes, **options)
    assert len(axes) == len(shapes)
    for shape, axis in zip(shapes, axes):
        reference = polygon_axis_arrays(shape, **options)
        assert _same(axis, reference) and len(axis.points)


def test_polygons_the_batch_does_not_take_as_they_are_go_one_by_one(monkeypatch: pytest.MonkeyPatch) -> None:
    bow_tie = Polygon([(0, 0), (2, 2), (2, 0), (0, 2)])  # invalid: repaired
    doubled = Polygon([(0, 0), (4, 0), (4, 0), (4, 1), (0, 1)])  # a repeated vertex: removed in the batch too
    tiny_ring = MultiPolygon([box(0, 0, 1, 1), box(3, 0, 3 + 1e-8, 1e-8)])  # refused: too small a ring
    alone = []

    def spy(shape, **options):  # type: ignore[no-untyped-def]
        alone.append(shape)
        return polygon_axis_arrays(shape, **options)

    monkeypatch.setattr(axis_layer, "polygon_axis_arrays", spy)
    shapes = [box(0, 0, 4, 2), bow_tie, doubled, Point(0, 0).buffer(1.0, 16)]
    axes = polygon_axes(shapes, detour=1.0)
    assert alone == [bow_tie]  # only the invalid one left the batch
    for shape, axis in zip(shapes, axes):
        assert _same(axis, polygon_axis_arrays(shape, detour=1.0))
    with pytest.raises(InvalidInputError, match="ring"):
        polygon_axes([box(0, 0, 1, 1), tiny_ring])
    with pytest.raises(EmptyShapeError):
        polygon_axes([box(0, 0, 1, 1), Polygon()])
    with pytest.raises(InvalidInputError, match="finite"):
        polygon_axes([box(0, 0, 1, 1)], tolerance=-1.0)


def test_random_lakes_with_islands_as_one_layer() -> None:
    rng = np.random.default_rng(34)
    shapes = []
    for k in range(12):
        angle = np.sort(rng.uniform(0, 2 * np.pi, 30))
        radius = rng.uniform(0.4, 1.0, 30)
        lake = Polygon(np.c_[radius * np.cos(angle), radius * np.sin(angle)] * 10 ** rng.uniform(-2, 5)
                       + rng.uniform(-1e5, 1e5, 2))
        if k % 3 == 0:  # an island
            lake = lake.difference(shapely.centroid(lake).buffer(0.1 * np.sqrt(lake.area), 8))
        shapes.append(lake)
    for axis, shape in zip(polygon_axes(shapes, detour=1.0), shapes):
        assert _same(axis, polygon_axis_arrays(shape, detour=1.0))
