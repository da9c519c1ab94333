"""The incremental adaptive sampling against triangulating every round anew, and the Delaunay property by Qhull."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image
from scipy.spatial import Delaunay, cKDTree
from shapely.geometry import MultiPolygon, Point, box

from medialaxis.planar.boundary import adaptive
from medialaxis.planar.boundary._refine_kernels import first_sample as adaptive_first_sample
from medialaxis.planar.boundary._rounds_kernels import FAILED
from medialaxis.planar.boundary.sampling import simplify_rings
from medialaxis.planar.delaunay import circumcircles, jitter
from medialaxis.planar.pipeline import planar_stages

KIMIA = Path(__file__).resolve().parents[1] / "data" / "kimia99"


def _shapes() -> dict[str, tuple[Any, float]]:
    """Regions with their tolerance: Kimia contours as the pipeline simplifies them (a quarter pixel), polygons."""
    out = {}
    for f in sorted(KIMIA.glob("*.png"))[::11]:
        out[f.stem] = (planar_stages(np.asarray(Image.open(f)).astype(bool)).rings.region, 0.25)
    disc_with_holes = Point(0, 0).buffer(1.0, 64).difference(Point(0.4, 0).buffer(0.2, 16)).difference(
        box(-0.6, -0.1, -0.3, 0.1))
    out["disc with holes"] = (disc_with_holes, 1e-4)
    out["two pieces"] = (MultiPolygon([box(0, 0, 4, 1), Point(6, 0).buffer(1.0, 5)]), 1e-4)
    return out


SHAPES = _shapes()


def _triangles(simplices: np.ndarray) -> set[tuple[int, ...]]:
    return set(map(tuple, np.sort(simplices, axis=1).tolist()))


@pytest.mark.parametrize("name", list(SHAPES))
def test_incremental_rounds_give_the_sample_and_triangles_of_rounds_from_scratch(name: str) -> None:
    region, tolerance = SHAPES[name]
    rings = simplify_rings(region, 0.0)
    smp, tri, inside = adaptive.sample_and_triangulate(rings, rings.region, tolerance, tolerance)
    ref_smp, ref_tri, ref_inside = adaptive.rounds_from_scratch(rings, rings.region, tolerance, tolerance)
    for field in ("points", "ring", "arc", "next"):
        np.testing.assert_array_equal(getattr(smp, field), getattr(ref_smp, field))
    # Co-circular samples (a box, a regular polygon, and every convex corner, whose samples are mirrored:
    # an isosceles trapezoid is cyclic): the jitter picks either diagonal, with the same circumcentres;
    # collinear samples' slivers lie on the boundary, outside both.
    ours, theirs = (np.c_[t.centers[i], t.radii[i]] for t, i in ((tri, inside), (ref_tri, ref_inside)))
    for a, b in ((ours, theirs), (theirs, ours)):
        assert cKDTree(b).query(a)[0].max() < 1e-9 * np.ptp(smp.points)


@pytest.mark.parametrize("name", list(SHAPES)[:3])
def test_incremental_triangulation_is_qhulls(name: str) -> None:
    """Qhull triangulates the final sample into as many triangles with the same circumcircles; neighbours agree.

    Where four samples are co-circular (mirrored corners), either diagonal is Delaunay: both give the same circle.
    """
    region, tolerance = SHAPES[name]
    rings = simplify_rings(region, 0.0)
    smp, tri, _ = adaptive.sample_and_triangulate(rings, rings.region, tolerance, tolerance)
    work = (smp.points - smp.points.min(0)) / np.ptp(smp.points, axis=0).max()
    qhull = Delaunay(np.vstack([work, adaptive.FAR_CORNERS])).simplices
    qhull = qhull[(qhull < len(work)).all(axis=1)]
    assert len(qhull) == len(tri.simplices)
    ours, theirs = (np.c_[circumcircles(smp.points, t)[0], circumcircles(smp.points, t)[1]] for t in (tri.simplices, qhull))
    ours, theirs = ours[np.isfinite(ours).all(1)], theirs[np.isfinite(theirs).all(1)]
    for a, b in ((ours, theirs), (theirs, ours)):
        assert cKDTree(b).query(a)[0].max() < 1e-7 * np.ptp(smp.points)
    for t, k in zip(*np.nonzero(tri.neighbors >= 0)):
        assert set(tri.simplices[t]) - {tri.simplices[t, k]} <= set(tri.simplices[tri.neighbors[t, k]])


def test_a_failed_insertion_falls_back_to_rounds_from_scratch(monkeypatch: pytest.MonkeyPatch) -> None:
    region, tolerance = SHAPES["disc with holes"]
    rings = simplify_rings(region, 0.0)
    ref = adaptive.rounds_from_scratch(rings, rings.region, tolerance, tolerance)
    calls = []

    def failing(round_, *args):  # type: ignore[no-untyped-def]
        calls.append(round_)
        return (FAILED, round_, False) + (None,) * 19  # the status, the round, settled, the state

    monkeypatch.setattr(adaptive, "incremental_rounds", failing)
    smp, tri, inside = adaptive.sample_and_triangulate(rings, rings.region, tolerance, tolerance)
    assert calls
    np.testing.assert_array_equal(smp.points, ref[0].points)
    assert _triangles(tri.simplices[inside]) == _triangles(ref[1].simplices[ref[2]])


def test_interp_is_numpys_bit_for_bit() -> None:
    from medialaxis.planar.boundary._refine_kernels import interp

    rng = np.random.default_rng(7)
    xp = np.concatenate([[0.0], np.cumsum(rng.exponential(1.0, 40))])
    fp = rng.normal(0, 3, len(xp))
    x = np.concatenate([rng.uniform(-1, xp[-1] + 1, 500), xp, [xp[-1]]])
    ours = [interp(v, xp, fp, 0)[0] for v in x]
    np.testing.assert_array_equal(ours, np.interp(x, xp, fp))


@pytest.mark.parametrize("name", list(SHAPES))
def test_the_compiled_first_sample_is_sample_of_the_start_arcs(name: str) -> None:
    from medialaxis.planar.boundary._refine_kernels import first_sample
    from medialaxis.planar.boundary.corners import ring_arrays
    from medialaxis.planar.boundary.sampling import sample

    region, tolerance = SHAPES[name]
    rings = simplify_rings(region, 0.0)
    closed = ring_arrays(rings)
    for min_length in (tolerance, 40 * tolerance):  # the corners mirrored down to it, or not at all
        ref = sample(rings, adaptive._start_arcs(rings, closed, rings.region, tolerance, min_length))
        got = first_sample(closed.xy, closed.s, closed.start, adaptive._start_length(rings.region, min_length),
                           float(tolerance), float(min_length), adaptive.RATIO)
        for value, field in zip(got, ("points", "arc", "ring", "next")):
            np.testing.assert_array_equal(value, getattr(ref, field))


def _assembled_reference(points, arc, ring, n_rings, tv, tn, count, centre, radius, where):  # type: ignore[no-untyped-def]
    """NumPy version of :func:`medialaxis.planar.boundary._refine_kernels.assembled` (its code before it was compiled)."""
    from medialaxis.planar._delaunay_kernels import drop_corners
    from medialaxis.planar.boundary._refine_kernels import CORNERS

    order = np.lexsort((arc, ring))
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    simplices, neighbors, row = drop_corners(tv, tn, count, CORNERS, CORNERS + len(points))
    kept = np.flatnonzero(row >= 0)
    ring = ring[order]
    size = np.bincount(ring, minlength=n_rings)
    start = np.repeat(np.cumsum(size) - size, size)
    following = np.arange(len(ring)) + 1
    nxt = np.where(following - start >= size[ring], start, following)
    return (points[order], ring, arc[order], nxt, rank[simplices], neighbors, centre[kept], radius[kept],
            where[kept] == 1)


@pytest.mark.parametrize("name", ["disc with holes", "two pieces"])
def test_the_compiled_assembly_is_its_numpy_reference(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    region, tolerance = SHAPES[name]
    rings = simplify_rings(region, 0.0)
    calls = []

    def recording(*args: Any) -> Any:
        calls.append(tuple(np.copy(a) if isinstance(a, np.ndarray) else a for a in args))
        return assembled(*args)

    from medialaxis.planar.boundary._refine_kernels import assembled

    monkeypatch.setattr(adaptive, "assembled", recording)
    adaptive.sample_and_triangulate(rings, rings.region, tolerance, tolerance)
    assert len(calls) == 1
    for got, expected in zip(assembled(*calls[0]), _assembled_reference(*calls[0])):
        np.testing.assert_array_equal(got, expected)


@pytest.mark.parametrize("name", list(SHAPES))
def test_the_compiled_ring_arrays_are_their_numpy_reference(name: str) -> None:
    from medialaxis.planar.boundary.corners import ring_arrays, ring_arrays_reference

    rings = simplify_rings(SHAPES[name][0], 0.0)
    got, expected = ring_arrays(rings), ring_arrays_reference(rings)
    for field in ("xy", "s", "start", "convex", "touching"):
        np.testing.assert_array_equal(getattr(got, field), getattr(expected, field))
    assert expected.convex.any()


@pytest.mark.parametrize("name", ["disc with holes", "two pieces"])
def test_the_rounds_resumed_from_python_give_the_same_sample(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """Back in Python after every round (a large shape) or for a longer jitter table: the same sample and triangles."""
    region, tolerance = SHAPES[name]
    rings = simplify_rings(region, 0.0)
    smp, tri, inside = adaptive.sample_and_triangulate(rings, rings.region, tolerance, tolerance)
    monkeypatch.setattr(adaptive, "ONE_ROUND_ABOVE", 0)
    lengths, first = [], []

    def first_sample(*args):  # type: ignore[no-untyped-def]
        out = adaptive_first_sample(*args)
        first.append(len(out[0]))
        return out

    def short_table(n: int) -> np.ndarray:  # the first table just holds the first sample
        lengths.append(n)
        return jitter(n)[: first[0]] if len(lengths) == 1 else jitter(n)

    monkeypatch.setattr(adaptive, "first_sample", first_sample)
    monkeypatch.setattr(adaptive, "jitter", short_table)
    again, tri_again, inside_again = adaptive.sample_and_triangulate(rings, rings.region, tolerance, tolerance)
    assert len(lengths) > 1  # the table was made longer
    np.testing.assert_array_equal(again.points, smp.points)
    np.testing.assert_array_equal(tri_again.simplices[inside_again], tri.simplices[inside])
