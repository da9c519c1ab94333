"""Convex corners sampled in mirrored pairs: which triangles are exempt, and what the axis keeps."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely import affinity

from medialaxis.planar._kernels import piece_state
from medialaxis.planar.boundary._corner_kernels import corner_piece_state, corner_triangle, sample_edges
from medialaxis.planar.boundary.corners import ring_arrays
from medialaxis.planar.boundary.sampling import simplify_rings
from medialaxis.planar.pipeline import planar_stages

# A right-angled corner at (0, 0): the ring runs clockwise (the region on its right), (0, 4) -> (0, 0) -> (6, 0).
SQUARE = shapely.Polygon([(0, 0), (0, 4), (6, 4), (6, 0)])


def _corner_case(offsets: list[float]):
    """Samples at ``offsets`` along the ring from the corner at (0, 0) (negative: before it)."""
    rings = simplify_rings(SQUARE, 0.0)
    closed = ring_arrays(rings)
    v = rings.vertices[0]
    corner = int(np.flatnonzero(np.all(v == 0, axis=1))[0])
    s = closed.s[: len(v) + 1]
    arc = np.mod(s[corner] + np.asarray(offsets, float), s[-1])
    ring = np.zeros(len(arc), np.int64)
    edge, at_vertex = sample_edges(arc, ring, 0, closed.s, closed.start)
    points = np.c_[np.interp(arc, s, np.r_[v[:, 0], v[0, 0]]), np.interp(arc, s, np.r_[v[:, 1], v[0, 1]])]
    assert closed.convex[corner]
    return closed, ring, edge, at_vertex, points


def _circumcentre(p: np.ndarray) -> np.ndarray:
    (ax, ay), (bx, by), (cx, cy) = p
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    ux = ((ax**2 + ay**2) * (by - cy) + (bx**2 + by**2) * (cy - ay) + (cx**2 + cy**2) * (ay - by)) / d
    uy = ((ax**2 + ay**2) * (cx - bx) + (bx**2 + by**2) * (ax - cx) + (cx**2 + cy**2) * (bx - ax)) / d
    return np.array([ux, uy])


def test_the_vertex_and_a_mirrored_pair_make_a_corner_triangle_an_unmirrored_pair_does_not() -> None:
    closed, ring, edge, at_vertex, points = _corner_case([0.0, 0.5, 0.7, -0.5, -0.7, 1.0])

    def exempt(a: int, b: int, c: int, tolerance: float = 1e-3) -> bool:
        centre = _circumcentre(points[[a, b, c]])
        return bool(corner_triangle(a, b, c, centre[0], centre[1], edge, at_vertex, ring, closed.xy, closed.start,
                                    closed.convex, tolerance))

    assert exempt(0, 1, 3)  # the vertex and the pair at 0.5: isosceles, centre on the bisector
    assert exempt(1, 2, 3) and exempt(2, 3, 4)  # the trapezoid of the pairs at 0.5 and 0.7, either diagonal
    assert not exempt(0, 1, 4)  # 0.5 and 0.7: centre off the bisector by far more than the tolerance
    assert exempt(0, 1, 4, tolerance=1.0)  # ... but within a tolerance that large
    assert exempt(1, 5, 3)  # 0.5, 1.0 against 0.5: the lone sample mirrors one of the pair, centre on the bisector
    assert not exempt(1, 5, 4)  # 0.5, 1.0 against 0.7: it mirrors neither


def test_without_convex_vertices_the_state_is_piece_states() -> None:
    st = planar_stages(affinity.rotate(SQUARE, 20))
    smp, tri = st.samples, st.triangulation
    closed = ring_arrays(st.rings)
    none = np.zeros_like(closed.convex)
    got = corner_piece_state(tri.simplices, st.inside, tri.radii, tri.centers, smp.next, smp.arc, smp.ring, 0,
                             closed.s, closed.xy, closed.start, none, closed.touching, 1e-3)
    for a, b in zip(got, piece_state(tri.simplices, st.inside, tri.radii, smp.next)):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("angle", [0, 25])
@pytest.mark.parametrize("corner", [30.0, 60.0, 90.0, 120.0])
def test_a_corner_is_sampled_in_mirrored_pairs_and_its_axis_is_the_bisector_up_to_lam(corner: float,
                                                                                       angle: float) -> None:
    """A kite with a convex corner of ``corner`` degrees at the origin: samples mirrored, axis on the bisector."""
    half = np.radians(corner / 2)
    kite = shapely.Polygon([(0, 0), (3 * np.cos(half), 3 * np.sin(half)), (2.2, 0), (3 * np.cos(half),
                                                                                    -3 * np.sin(half))])
    kite = affinity.rotate(kite, angle, origin=(0, 0))
    st = planar_stages(kite)
    ma, tol, lam = st.result, st.result.metadata["tolerance"], st.result.metadata["lam"]
    direction = np.array([np.cos(np.radians(angle)), np.sin(np.radians(angle))])
    p = st.samples.points
    near = np.linalg.norm(p, axis=1)
    side = np.sign(p @ np.array([-direction[1], direction[0]]))
    close = (near > 0) & (near < 0.5)
    upper, lower = np.sort(near[close & (side > 0)]), np.sort(near[close & (side < 0)])
    np.testing.assert_allclose(upper, lower, rtol=0, atol=1e-9)  # the samples near the corner, mirrored
    assert len(upper) <= 12  # a few pairs, not a refinement down to min_length
    along = ma.points @ direction
    across = np.abs(ma.points @ np.array([-direction[1], direction[0]]))
    on_bisector = along < 0.5
    assert (across[on_bisector] <= 0.25 * tol).all()  # the axis near the corner is the bisector
    # ... and it reaches into the corner until its contacts are about lam apart, as dense samples did
    tip = along[on_bisector].min()
    assert tip <= lam / (2 * np.sin(half)) / np.cos(half)  # the bisector point whose feet are lam apart


T_SHAPE = shapely.Polygon([(0, 0), (10, 0), (10, 2), (6, 2), (6, 8), (4, 8), (4, 2), (0, 2)])
CROSS = shapely.box(0, 0, 10, 3).union(shapely.box(3, 0, 5, 9))


@pytest.mark.parametrize("shape", [T_SHAPE, CROSS, SQUARE])
@pytest.mark.parametrize("angle", [1.0, 30.0, 137.0])
def test_co_circular_samples_give_the_same_sampling_turned_or_mirrored(shape: shapely.Polygon, angle: float) -> None:
    """Strips and square arm ends sampled regularly have co-circular samples, whose Delaunay diagonal turns on
    rounding: the corner exemption is decided per circle, so a turned (and mirrored) copy is sampled alike."""
    base = planar_stages(shape)
    for mirror in (1, -1):
        def motion(geom, mirror=mirror):  # type: ignore[no-untyped-def]
            return affinity.scale(affinity.rotate(geom, angle, origin=(0, 0)), mirror, 1, origin=(0, 0))

        moved = planar_stages(motion(shape))
        assert len(moved.samples.points) == len(base.samples.points)
        assert len(moved.result.points) == len(base.result.points)
        expected = shapely.get_coordinates(motion(shapely.MultiPoint(base.result.points)))
        gap = np.linalg.norm(moved.result.points[:, None, :] - expected[None, :, :], axis=2)
        assert max(gap.min(0).max(), gap.min(1).max()) < 1e-8  # the same axis, moved (shapes 10 across)


def test_the_corner_tests_kept_between_rounds_give_the_state_tested_anew() -> None:
    from medialaxis.planar.boundary._corner_kernels import corner_piece_state_memo

    st = planar_stages(shapely.Polygon([(0, 0), (0, 4), (3, 4), (3, 7), (9, 7), (9, 0)]))
    smp, tri = st.samples, st.triangulation
    closed = ring_arrays(st.rings)
    args = (tri.simplices, st.inside, tri.radii, tri.centers, smp.next, smp.arc, smp.ring, 0, closed.s, closed.xy,
            closed.start, closed.convex, closed.touching, 1e-4 * 11.4)
    fresh = corner_piece_state(*args)
    memo = np.full((len(tri.simplices), 4), -1, np.int64)
    memo[::3, :3] = np.roll(tri.simplices[::3], 1, axis=1)  # stale rows: other triangles (the same vertices turned)
    memo[::3, 3] = 1
    for _ in range(2):  # the first call tests and keeps, the second reads what it kept
        got = corner_piece_state_memo(*args, memo)
        np.testing.assert_array_equal(got[0], fresh[0])
        np.testing.assert_array_equal(got[1], fresh[1])
    np.testing.assert_array_equal(memo[:, :3], tri.simplices)
    assert memo[:, 3].any()  # the L shape's convex corners have corner triangles


@pytest.mark.parametrize("seed", range(12))
def test_the_fast_whole_circles_are_the_sorted_scans(seed: int) -> None:
    """Circles repeated exactly, within the scan's 1e-9 and just beyond it, equal x of different circles, not finite."""
    from medialaxis.planar.boundary._circle_kernels import _whole_circles, whole_circles

    rng = np.random.default_rng(seed)
    n = 400
    centres = rng.uniform(-50, 50, (n, 2)) * rng.choice([1e-3, 1.0, 1e3])
    radii = rng.uniform(0.1, 5, n)
    for _ in range(60):  # copies of a circle: exact, near (the scan's eps is 1e-9 of r + |x| + |y|), or only x kept
        a, b = rng.integers(0, n, 2)
        scale = 1e-9 * (radii[a] + np.abs(centres[a]).sum())
        kind = rng.integers(0, 3)
        nudge = 0.0 if kind == 0 else rng.choice([0.3, 0.9, 1.1, 3.0]) * scale * rng.choice([-1, 1], 3)
        centres[b] = centres[a] + (nudge[:2] if kind else 0.0)
        radii[b] = radii[a] + (nudge[2] if kind else 0.0)
        if kind == 2:
            centres[b, 1] += rng.uniform(0, 1)  # the same x only
    if seed == 0:
        centres[5, 0] = np.nan
    inside = rng.random(n) < 0.9
    corner = inside & (rng.random(n) < 0.3)
    np.testing.assert_array_equal(whole_circles(corner, inside, centres, radii),
                                  _whole_circles(corner, inside, centres, radii))


@pytest.mark.parametrize("share", [0.0, 0.003, 0.05, 0.9])
def test_the_whole_circles_buckets_find_what_the_sorted_scan_finds(share: float) -> None:
    """One corner triangle, corners all at one x, few or most triangles corners: the bucketed search's answer."""
    from medialaxis.planar.boundary._circle_kernels import _whole_circles, whole_circles

    rng = np.random.default_rng(int(share * 1000))
    n = 300
    centres = rng.uniform(-5, 5, (n, 2))
    radii = rng.uniform(0.1, 5, n)
    inside = rng.random(n) < 0.95
    corner = inside & (rng.random(n) < share)
    twins = rng.integers(0, n, (80, 2))
    centres[twins[:, 1]], radii[twins[:, 1]] = centres[twins[:, 0]], radii[twins[:, 0]]  # shared circles
    c, u = np.flatnonzero(inside)[:2]  # a corner triangle whose circle an inside triangle shares: not a corner's
    corner[c], corner[u] = True, False
    centres[u], radii[u] = centres[c], radii[c]
    for same_x in (False, True):
        if same_x:
            centres[corner, 0] = centres[corner][0, 0]
        np.testing.assert_array_equal(whole_circles(corner, inside, centres, radii),
                                      _whole_circles(corner, inside, centres, radii))
        assert not whole_circles(corner, inside, centres, radii)[c]
