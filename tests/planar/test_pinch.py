"""An island whose spike touches the shore at one vertex: the axis stays in the water on both sides of the spike.

Truth from shapely: the parts of every axis edge outside the polygon
(``difference``), densified, lie within ``1e-6`` of the size from its
boundary. Before the pieces at a pinch got the radii of the triangles of the
other ring's sample there, a wide triangle of the wedge between the spike
and the shore had its circumcentre in the water on the spike's other side,
and the axis edge to it crossed the spike (up to 2.9 here, five times the
tolerance; 35 m on a lake of ``benchmarks/bench_centerlines.py``).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely import affinity

import medialaxis as mx
from medialaxis.planar.axis_layer import polygon_axes


def _spiked(spike: float, length: float, angle: float) -> shapely.Polygon:
    """A lake 4000 across whose shore turns at the origin, where a triangular island's ``spike``-degree tip touches it.

    The island splits the water at the origin into a wedge between the
    spike and the shore and the rest.
    """
    tip = np.radians(spike)
    shore = [(-2000, -2000), (2000, -2000), (2000, 0), (0, 0), (-500, 2000), (-2000, 2000)]
    island = [(0, 0), (-length, length * np.tan(tip)), (-length, 0)]
    return affinity.rotate(shapely.Polygon(shore, [island]), angle, origin=(0, 0))


def _farthest_out(points: np.ndarray, edges: np.ndarray, polygon: shapely.Polygon) -> float:
    """How far the straight edges get from ``polygon`` (0 inside), their parts outside densified."""
    lines = shapely.linestrings(np.stack([points[edges[:, 0]], points[edges[:, 1]]], axis=1))
    outside = shapely.difference(lines, polygon)
    outside = outside[~shapely.is_empty(outside)]
    step = 1e-4 * np.sqrt(polygon.area)
    far = [shapely.distance(shapely.points(shapely.get_coordinates(shapely.segmentize(part, step))),
                            polygon.boundary).max() for part in outside]
    return float(max(far, default=0.0))


@pytest.mark.parametrize("angle", [0.0, 105.0, 345.0])
@pytest.mark.parametrize(("spike", "length"), [(10.0, 600.0), (15.0, 1600.0), (30.0, 600.0), (30.0, 1600.0)])
def test_the_axis_stays_in_the_water_by_an_island_spike_touching_the_shore(spike: float, length: float,
                                                                          angle: float) -> None:
    lake = _spiked(spike, length, angle)
    assert lake.is_valid and len(lake.interiors) == 1
    size = np.sqrt(lake.area)
    ma = mx.medial_axis(lake)
    assert _farthest_out(ma.points, ma.edges, lake) <= 1e-6 * size
    layer = polygon_axes([lake], detour=1.0)[0]  # the GIS route, at the layers' detour
    assert _farthest_out(layer.points, layer.edges, lake) <= 1e-6 * size
    lines = mx.centerlines([lake], show_progress=False).geometry[0]
    assert shapely.distance(shapely.points(shapely.get_coordinates(shapely.segmentize(
        shapely.difference(lines, lake), 1e-4 * size))), lake.boundary).max(initial=0.0) <= 1e-6 * size


def test_contacts_on_the_island_and_the_shore_are_as_far_apart_as_the_shore_through_the_pinch() -> None:
    """The arc of an edge whose contacts lie on two rings: along each ring to the pinch, the shorter way (shapely)."""
    from medialaxis.planar.axis import raw_axis
    from medialaxis.planar.boundary.corners import ring_arrays
    from medialaxis.planar.pipeline import planar_stages

    lake = _spiked(20.0, 900.0, 10.0)
    st = planar_stages(lake)
    smp, rings = st.samples, st.rings
    raw = raw_axis(st.triangulation, st.inside, smp, rings.region, rings.locator, ring_arrays(rings))
    across = np.flatnonzero(smp.ring[raw.contact[:, 0]] != smp.ring[raw.contact[:, 1]])
    assert len(across) > 10
    pinch = shapely.Point(0, 0)
    loops = [shapely.LineString(c) for c in rings.closed]
    for e in across:
        total = 0.0
        for sample in raw.contact[e]:
            loop = loops[smp.ring[sample]]
            along = abs(loop.project(shapely.Point(smp.points[sample])) - loop.project(pinch))
            total += min(along, loop.length - along)
        np.testing.assert_allclose(raw.contact_arc[e], total, rtol=1e-9, atol=1e-9 * loop.length)
    unjoined = raw_axis(st.triangulation, st.inside, smp, rings.region, rings.locator)
    assert np.isinf(unjoined.contact_arc[across]).all()  # rings that never meet: no arc between them


def test_the_vertices_at_one_point_are_paired_as_numpy_pairs_them() -> None:
    from medialaxis.planar.boundary.corners import ring_arrays, ring_arrays_reference
    from medialaxis.planar.boundary.sampling import simplify_rings

    rings = simplify_rings(_spiked(20.0, 900.0, 10.0), 0.0)
    got, expected = ring_arrays(rings), ring_arrays_reference(rings)
    np.testing.assert_array_equal(got.touching, expected.touching)
    pinch = np.flatnonzero(got.touching >= 0)
    assert len(pinch) == 2  # the shore's vertex at the origin and the island's tip, each the other's next
    np.testing.assert_array_equal(got.touching[pinch], pinch[::-1])
    np.testing.assert_allclose(got.xy[pinch], 0.0, atol=1e-9)
