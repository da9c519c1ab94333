"""The GIS route's compiled axis (everything after the sampling in one call) against the pipeline, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import MultiPolygon, Point, Polygon, box

from medialaxis.planar._axis_kernels import pruned_graph
from medialaxis.planar.axis import axis_positions
from medialaxis.planar.axis_arrays import polygon_axis_arrays
from medialaxis.planar.pipeline import voronoi_medial_axis
from medialaxis.planar.pruning import REGROW_DETOUR, prune_graph
from tests.planar.test_incremental_sampling import SHAPES


def _lake(seed: int) -> Polygon:
    """A star-shaped polygon of 40 vertices with radii between 0.3 and 1 (arms, bays, a shore's noise)."""
    rng = np.random.default_rng(seed)
    angle = np.sort(rng.uniform(0, 2 * np.pi, 40))
    radius = rng.uniform(0.3, 1.0, 40)
    return Polygon(np.c_[radius * np.cos(angle), radius * np.sin(angle)])


CASES = {**{name: region for name, (region, _) in SHAPES.items()},
         "box": box(0, 0, 4, 2), "square": box(0, 0, 1, 1), "disc": Point(0, 0).buffer(1.0, 32),
         "triangle": Polygon([(0, 0), (1, 0), (0, 1)]),
         "two pieces, one tiny": MultiPolygon([box(0, 0, 1, 1), box(3, 0, 3.001, 0.001)]),
         **{f"lake {seed}": _lake(seed) for seed in (*range(6), 62, 98)}}  # 62, 98: circumcentres outside


@pytest.mark.parametrize("name", list(CASES))
@pytest.mark.parametrize("options", [{}, {"detour": 1.0}, {"lam": 0.05, "tolerance": 1e-3}])
def test_the_arrays_are_the_pipelines_axis(name: str, options: dict) -> None:
    ma = voronoi_medial_axis(CASES[name], **options)
    axis = polygon_axis_arrays(CASES[name], **options)
    np.testing.assert_array_equal(axis.points, ma.points)
    np.testing.assert_array_equal(axis.radii, ma.radii)
    np.testing.assert_array_equal(axis.edges, ma.edges)


def test_circumcentres_outside_the_shape_are_moved_as_the_pipeline_moves_them(monkeypatch: pytest.MonkeyPatch) -> None:
    from medialaxis.planar import axis_arrays

    calls = []

    def spy(*args):  # type: ignore[no-untyped-def]
        calls.append(1)
        return axis_positions(*args)

    monkeypatch.setattr(axis_arrays, "axis_positions", spy)
    axis, ma = polygon_axis_arrays(CASES["lake 62"]), voronoi_medial_axis(CASES["lake 62"])
    assert calls  # the compiled path handed the moves to axis_positions
    np.testing.assert_array_equal(axis.points, ma.points)
    np.testing.assert_array_equal(axis.radii, ma.radii)


def test_inputs_other_than_polygons_go_the_whole_way() -> None:
    mask = np.zeros((30, 50), bool)
    mask[5:25, 5:45] = True
    axis, ma = polygon_axis_arrays(mask), voronoi_medial_axis(mask)
    np.testing.assert_array_equal(axis.points, ma.points)
    np.testing.assert_array_equal(axis.edges, ma.edges)


@pytest.mark.parametrize("seed", range(20))
def test_the_compiled_pruning_is_prune_graph(seed: int) -> None:
    """Random graphs (trees, cycles, isolated nodes, components left without an edge) with random contact data."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 60))
    m = int(rng.integers(0, 2 * n))
    edges = rng.integers(0, n, (m, 2)).astype(np.int64)
    edges = edges[edges[:, 0] != edges[:, 1]]
    diameter = rng.uniform(0, 1, len(edges))
    arc = diameter + rng.uniform(0, 2, len(edges)) * rng.integers(0, 2, len(edges))
    adjacent = rng.integers(0, 2, len(edges)).astype(bool)
    radii = rng.integers(0, 4, n).astype(float)  # ties: the first node of largest radius stays
    lam, detour = 0.3, 0.5
    old, out = pruned_graph(radii, edges, diameter, arc, adjacent, lam, detour, REGROW_DETOUR)
    ref_old, ref_edges = prune_graph(radii, edges, diameter, arc, adjacent, lam, detour)
    np.testing.assert_array_equal(old, ref_old)
    np.testing.assert_array_equal(out, ref_edges)


@pytest.mark.parametrize("name", ["disc", "square", "two pieces, one tiny", "lake 3"])
def test_only_the_kept_nodes_are_measured_and_all_of_them_are(name: str) -> None:
    axis = polygon_axis_arrays(CASES[name], detour=1.0)
    ma = voronoi_medial_axis(CASES[name], detour=1.0)
    assert np.isfinite(axis.radii).all() and (axis.radii > 0).all()
    np.testing.assert_array_equal(axis.radii, ma.radii)
    assert len(ma.raw.points) > len(axis.points) or name in ("disc", "square")
