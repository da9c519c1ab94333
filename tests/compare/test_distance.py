"""shape_distance / distance_matrix: a distance, invariant, robust, and fast to batch."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from PIL import Image
from shapely import affinity
from shapely.geometry import MultiPoint, Point, Polygon, box
from skimage import transform

import medialaxis as mx
from medialaxis.compare import match_tour, query_distances, shape_signature, signature
from medialaxis.compare.signature import CLOSING
from medialaxis.errors import EmptyShapeError, InvalidInputError

T_SHAPE = Polygon([(0, 0), (10, 0), (10, 2), (6, 2), (6, 8), (4, 8), (4, 2), (0, 2)])
L_SHAPE = Polygon([(0, 0), (9, 0), (9, 2), (2, 2), (2, 6), (0, 6)])
CROSS = box(0, 0, 10, 3).union(box(3, 0, 5, 9))
POLYGONS = [T_SHAPE, L_SHAPE, CROSS]


def _similarity(geom, angle, factor, dx, dy, mirror):
    g = affinity.rotate(geom, angle, origin=(0, 0))
    g = affinity.scale(g, -factor if mirror else factor, factor, origin=(0, 0))
    return affinity.translate(g, dx, dy)


def test_zero_for_itself_and_symmetric():
    for a in POLYGONS:
        assert mx.shape_distance(a, a) == 0.0
    d_ab, d_ba = mx.shape_distance(T_SHAPE, CROSS), mx.shape_distance(CROSS, T_SHAPE)
    assert d_ab > 0 and d_ab == d_ba


def test_zero_for_a_copy_of_itself():
    assert mx.shape_distance(T_SHAPE, Polygon(T_SHAPE.exterior.coords)) == 0.0


@given(
    which=st.integers(0, 2),
    other=st.integers(0, 2),
    angle=st.floats(-180, 180),
    factor=st.floats(0.05, 20),
    dx=st.floats(-100, 100),
    dy=st.floats(-100, 100),
    mirror=st.booleans(),
)
def test_polygon_distance_invariant_under_similarities(which, other, angle, factor, dx, dy, mirror):
    a, b = POLYGONS[which], POLYGONS[other]
    moved = _similarity(a, angle, factor, dx, dy, mirror)
    base = mx.shape_distance(a, b)
    got = mx.shape_distance(moved, b)
    assert got == pytest.approx(base, rel=1e-6, abs=1e-9)
    assert mx.shape_distance(b, moved) == got


def test_a_disc_has_a_finite_distance_to_other_shapes():
    """A disc's axis is one point (a one-sample tour): it is compared with the others, not at infinity.

    Its samples (all the mass at the centre) match no sample of an axis of some
    length, so the distance is the cap, every sample of both left out: 2 * gap.
    """
    disc, ellipse = Point(0, 0).buffer(10), affinity.scale(Point(0, 0).buffer(10), 1.3, 1.0)
    for other in (ellipse, T_SHAPE):
        assert mx.shape_distance(disc, other) == pytest.approx(2 * 0.3)
        assert mx.shape_distance(disc, other, gap=0.2) == pytest.approx(2 * 0.2)
    assert mx.shape_distance(disc, affinity.scale(disc, 3.0, 3.0)) < 1e-9


def test_slits_do_not_hide_a_shape():
    """A pentagon cut by three slits (as MPEG-7's device classes are) is nearest to the pentagon.

    The truth is the construction: the cut shape is the pentagon minus thin
    rectangles. Without the closed versions (``closing=0``) a star comes first.
    """
    angles = np.pi / 2 + 2 * np.pi * np.arange(5) / 5
    pentagon = Polygon(np.c_[np.cos(angles), np.sin(angles)] * 10)
    cut = pentagon
    for angle in (36, 180, 324):
        cut = cut.difference(affinity.rotate(box(-0.15, 2, 0.15, 12), angle, origin=(0, 0)))
    star_angles = np.pi / 2 + np.pi * np.arange(10) / 5
    star = Polygon(np.c_[np.cos(star_angles), np.sin(star_angles)] * np.where(np.arange(10) % 2, 4, 10)[:, None])
    others = [pentagon, star, box(0, 0, 10, 10), Polygon([(0, 0), (10, 0), (5, 8.7)]), T_SHAPE]
    for closing, nearest in ((CLOSING, 0), (0.0, 1)):
        def sig(g, closing=closing):
            return signature(mx.medial_axis(g, tolerance=1e-3 * np.sqrt(g.area)), closing=closing)

        query = sig(cut)
        assert (query.closing_gain > 0.01) == (closing > 0)
        assert int(np.argmin([mx.shape_distance(query, sig(g)) for g in others])) == nearest


def test_distance_separates_shapes():
    d_same = mx.shape_distance(T_SHAPE, _similarity(T_SHAPE, 17, 3, 1, 2, True))
    assert d_same < 1e-9
    assert mx.shape_distance(T_SHAPE, L_SHAPE) > 0.01
    assert mx.shape_distance(T_SHAPE, CROSS) > 0.01


def _load(path):
    return np.asarray(Image.open(path).convert("L")) > 127


def _nearest_other_class(query_sig, signatures, labels, label):
    d = query_distances(query_sig, [s for s, other in zip(signatures, labels) if other != label], n_jobs=1)
    return d.min()


@pytest.mark.parametrize("name", ["class1_01", "class3_05", "class7_03", "class8_05", "class9_02"])
@pytest.mark.parametrize("kind", ["rotate", "rescale", "noise", "bump", "scratch"])
def test_raster_changes_stay_within_class(name, kind, kimia_dir, kimia_files, kimia_signatures, kimia_labels):
    mask = _load(kimia_dir / f"{name}.png")
    rng = np.random.default_rng(0)
    if kind == "rotate":
        moved = transform.rotate(mask.astype(float), 37, resize=True, order=1) > 0.5
    elif kind == "rescale":
        moved = transform.rescale(mask.astype(float), 1.6, order=1) > 0.5
    elif kind == "noise":
        # Flip about a third of the boundary pixels: noise of a pixel.
        from scipy import ndimage

        edge = mask ^ ndimage.binary_erosion(mask)
        moved = mask.copy()
        flip = edge & (rng.random(mask.shape) < 0.33)
        moved[flip] = False
        out = ndimage.binary_dilation(mask) & ~mask & (rng.random(mask.shape) < 0.33)
        moved[out] = True
    elif kind == "scratch":
        # A dark scratch 2 pixels wide across the middle row, from the left edge to the centre: the
        # axis runs around it (the closed versions fill it).
        rows, cols = np.nonzero(mask)
        r = int(np.median(rows))
        c = cols[rows == r]
        moved = mask.copy()
        moved[r : r + 2, c.min() : (c.min() + c.max()) // 2 + 1] = False
    else:
        # A small bump (3 x 3 pixels) on the boundary: a small spurious branch.
        rows, cols = np.nonzero(mask ^ np.pad(mask[1:], ((0, 1), (0, 0))))
        r, c = rows[len(rows) // 3], cols[len(rows) // 3]
        moved = mask.copy()
        moved[r : r + 3, c - 1 : c + 2] = True
    original = kimia_signatures[[p.stem for p in kimia_files].index(name)]
    label = int(name.split("_")[0][5:])
    d = mx.shape_distance(moved, original)
    assert d < _nearest_other_class(original, kimia_signatures, kimia_labels, label)
    assert d < _nearest_other_class(shape_signature(moved), kimia_signatures, kimia_labels, label)


def test_distance_matrix_matches_pairwise_and_jobs(kimia_signatures):
    sigs = kimia_signatures[::11]
    D1 = mx.distance_matrix(sigs, n_jobs=1)
    D2 = mx.distance_matrix(sigs, n_jobs=2, scheduler="threads")
    assert D1.shape == (len(sigs), len(sigs)) and D1.dtype == np.float64
    assert np.array_equal(D1, D2)
    assert np.array_equal(D1, D1.T) and np.all(np.diag(D1) == 0)
    assert D1[0, 3] == mx.shape_distance(sigs[0], sigs[3])
    off = D1[~np.eye(len(sigs), dtype=bool)]
    assert (off > 0).all()


def test_distance_matrix_from_files_uses_cache(kimia_files):
    files = [str(p) for p in kimia_files[:3]]
    first = shape_signature(files[0])
    assert shape_signature(files[0]) is first
    D = mx.distance_matrix(files, n_jobs=1)
    assert D[0, 1] == mx.shape_distance(first, files[1])


def test_compiled_distance_is_the_reference_tour_alignment():
    tour = mx.shape_distance(T_SHAPE, CROSS)
    assert tour > 0
    assert tour == pytest.approx(match_tour(T_SHAPE, CROSS)[0], rel=1e-9) or tour == pytest.approx(
        match_tour(CROSS, T_SHAPE)[0], rel=1e-9
    )


def test_match_tour_pairs_samples_along_both_walks():
    d, pa, pb = match_tour(T_SHAPE, T_SHAPE)
    assert d == 0.0 and np.array_equal(pa, pb) and len(pa) == shape_signature(T_SHAPE).tour.shape[1]
    # L_SHAPE has no symmetry: each matched sample of the moved shape is the image of its partner
    # under the similarity. T_SHAPE is symmetric about x = 5: its partner is the image of the sample
    # or of its mirror image (two alignments of distance 0, which one is found turns on rounding).
    for shape, mirrors in ((L_SHAPE, (lambda p: p,)), (T_SHAPE, (lambda p: p, lambda p: p * [-1, 1] + [10, 0]))):
        d, pa, pb = match_tour(shape, _similarity(shape, 30, 2, 5, 5, True))
        assert d < 1e-9 and pa.shape == pb.shape == (len(pa), 2) and len(pa) > 0
        images = [np.array([g.coords[0] for g in _similarity(MultiPoint(m(pa)), 30, 2, 5, 5, True).geoms])
                  for m in mirrors]
        assert any(np.allclose(moved, pb, atol=1e-6 * 20) for moved in images)


def test_bad_inputs():
    with pytest.raises(EmptyShapeError):
        mx.shape_distance(np.zeros((30, 30), bool), T_SHAPE)
    with pytest.raises(InvalidInputError, match="planar"):
        mx.shape_distance(np.zeros((5, 6, 7), bool), T_SHAPE)
    with pytest.raises(InvalidInputError, match="planar"):
        mx.distance_matrix([T_SHAPE, np.ones((5, 6, 7), bool)])
    with pytest.raises(InvalidInputError, match="paths"):
        mx.shape_distance(T_SHAPE, CROSS, paths=1)  # the retired term: an unknown option now
    with pytest.raises(InvalidInputError, match="gap"):
        mx.shape_distance(T_SHAPE, CROSS, gap=float("nan"))
    with pytest.raises(InvalidInputError, match="n_jobs"):
        mx.distance_matrix([T_SHAPE, CROSS], n_jobs=0)
    with pytest.raises(InvalidInputError, match="at least one"):
        mx.distance_matrix([])


def test_inputs_not_modified():
    mask = np.zeros((60, 90), bool)
    mask[20:40, 10:80] = True
    copy = mask.copy()
    mx.distance_matrix([mask, mask.T], n_jobs=1)
    assert np.array_equal(mask, copy)
