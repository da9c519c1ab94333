"""How finely pieces too long are cut: OVER_SPLIT, and the drawings' own."""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import MultiPolygon, Point, box

from medialaxis.planar._kernels import DRAWING_OVER_SPLIT, OVER_SPLIT
from medialaxis.planar.boundary import adaptive
from medialaxis.planar.boundary.sampling import initial_arcs, refine_arcs, refine_arcs_reference, sample, simplify_rings

REGION = MultiPolygon([Point(0, 0).buffer(1.0, 16).difference(Point(0.2, 0).buffer(0.3, 8)), box(2, 0, 3, 0.4)])


@pytest.mark.parametrize("over_split", [OVER_SPLIT, DRAWING_OVER_SPLIT, 1.5])
def test_the_compiled_split_is_the_numpy_reference_for_any_over_split(over_split: float) -> None:
    rng = np.random.default_rng(7)
    rings = simplify_rings(REGION, 0.0)
    arcs = initial_arcs(rings, 0.05)
    for _ in range(3):
        smp = sample(rings, arcs)
        radius = rng.uniform(0.01, 2.0, len(smp.points))
        conforming = rng.random(len(smp.points)) < 0.9
        new, ref = (f(arcs, smp, radius, conforming, 1e-3, 1e-3, 0.5, over_split)
                    for f in (refine_arcs, refine_arcs_reference))
        for a, b in zip(new, ref):
            np.testing.assert_array_equal(a, b)
        arcs = new


def test_a_piece_is_cut_over_split_times_finer_than_the_rule_asks() -> None:
    """One straight piece of a square with a known inner radius: ``ceil(over_split * h / target)`` parts."""
    rings = simplify_rings(box(0, 0, 1, 1), 0.0)
    arcs = initial_arcs(rings, 1.0)  # the four corners: four pieces of length 1
    smp = sample(rings, arcs)
    radius = np.full(len(smp.points), 0.5)
    tolerance = 1e-3
    target = min(0.5 * 0.5, np.sqrt(16 * 0.5 * tolerance))  # the split rule's longest piece
    for over_split in (OVER_SPLIT, DRAWING_OVER_SPLIT):
        new = refine_arcs(arcs, smp, radius, np.ones(len(smp.points), bool), tolerance, 1e-4, 0.5, over_split)
        assert len(new[0]) == 4 * int(np.ceil(over_split * 1.0 / target))
        assert np.diff(new[0]).max() <= target / over_split * (1 + 1e-12)


def test_the_incremental_rounds_follow_over_split_as_the_rounds_from_scratch_do() -> None:
    rings = simplify_rings(REGION, 0.0)
    counts = {}
    for over_split in (OVER_SPLIT, DRAWING_OVER_SPLIT):
        smp, _, _ = adaptive.sample_and_triangulate(rings, rings.region, 1e-4, 1e-4, over_split)
        ref, _, _ = adaptive.rounds_from_scratch(rings, rings.region, 1e-4, 1e-4, over_split)
        np.testing.assert_array_equal(smp.points, ref.points)
        counts[over_split] = len(smp.points)
    assert counts[OVER_SPLIT] < counts[DRAWING_OVER_SPLIT]  # cut coarser, fewer samples
