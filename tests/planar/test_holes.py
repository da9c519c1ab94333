"""Raster shapes with holes: one cycle per hole, one axis per piece, at any rotation.

Truth comes from outside medialaxis: the shapes are built with shapely,
rasterized by supersampling, and their pieces and holes counted by
scikit-image (``label``, ``euler_number``).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, note
from hypothesis import strategies as st
from PIL import Image

import medialaxis as mx
from medialaxis.datasets import holed_shapes, rasterize, render
from medialaxis.datasets import raster_counts as truth_counts
from tests.planar.holed import faces_around, hole_points

SHAPES = holed_shapes()
SIZE = 320


def _check_topology(ma, mask: np.ndarray) -> None:
    pieces, holes = truth_counts(mask)
    assert ma.n_components == pieces
    assert ma.n_cycles == holes
    # Each hole sits in its own face of the axis graph: the cycles go round the holes.
    faces = faces_around(ma, hole_points(mask))
    assert (faces >= 0).all() and len(set(faces.tolist())) == holes


@pytest.mark.parametrize("kind", ["bool", "float", "uint8"])
@pytest.mark.parametrize("angle", [0, 15, 30, 45])
@pytest.mark.parametrize("name", sorted(SHAPES))
def test_cycles_equal_holes_counted_by_skimage(name, angle, kind):
    image = rasterize(SHAPES[name], SIZE, angle, kind)
    mask = image if kind == "bool" else image > (0.5 if kind == "float" else 127)
    pieces, holes = truth_counts(mask)
    assert (pieces, holes) == (1, shapely.get_num_interior_rings(SHAPES[name]))
    _check_topology(mx.medial_axis(image), mask)


@pytest.mark.parametrize("kind", ["bool", "uint8"])
@pytest.mark.parametrize("angle", [0, 30])
@pytest.mark.parametrize("name", sorted(SHAPES))
def test_canny_boundary_keeps_holes(name, angle, kind):
    image = rasterize(SHAPES[name], SIZE, angle, kind)
    mask = image if kind == "bool" else image > 127
    _check_topology(mx.medial_axis(image, boundary="canny"), mask)


@pytest.mark.parametrize("boundary", ["contour", "canny"])
@pytest.mark.parametrize("kind", ["bool", "float", "uint8-dark"])
def test_annulus_axis_is_the_mid_circle(kind, boundary):
    """Annulus of radii 60 and 150 in a 512 x 512 image: the axis is the circle of radius 105."""
    centre = 255.5
    rows, cols = np.mgrid[:512, :512]
    r = np.hypot(rows - centre, cols - centre)
    cover = np.clip(150.5 - r, 0, 1) * np.clip(r - 59.5, 0, 1)  # pixel coverage, to first order
    image = {"bool": r < 150, "float": cover, "uint8-dark": np.round(255 * (1 - cover)).astype(np.uint8)}[kind]
    if kind == "bool":
        image = image & (r > 60)
    ma = mx.medial_axis(image, boundary=boundary)
    assert ma.n_cycles == 1 and ma.n_components == 1
    off = np.abs(np.hypot(ma.points[:, 0] - centre, ma.points[:, 1] - centre) - 105.0)
    assert np.percentile(off, 99) <= 1.0
    assert np.percentile(np.abs(ma.radii - 45.0), 99) <= 1.0
    assert ma.metadata["foreground"] == ("dark" if kind.endswith("dark") else "bright")
    # The cycle goes all the way round: every direction from the centre meets the axis.
    angles = np.arctan2(ma.points[:, 0] - centre, ma.points[:, 1] - centre)
    assert np.diff(np.sort(angles)).max() < 0.1


def test_scanned_drawing_dark_on_light_paper(tmp_path):
    """A black washer printed on grey-white paper, with noise, saved as JPEG by PIL."""
    cover = rasterize(SHAPES["washer"], SIZE, 0, "float")
    rng = np.random.default_rng(7)
    paper = 230 - 200 * cover + rng.normal(0, 8, cover.shape)
    path = tmp_path / "scan.jpg"
    Image.fromarray(np.clip(paper, 0, 255).astype(np.uint8)).save(path, quality=85)
    ma = mx.medial_axis(path)
    assert ma.metadata["foreground"] == "dark"
    _check_topology(ma, cover > 0.5)
    assert abs(float(np.median(ma.radii)) - 27.5) < 1.5  # (90 - 35) / 2


@st.composite
def holed_scenes(draw):
    """1-3 pieces side by side, each a rounded blob with 0-3 round or square holes."""
    n_pieces = draw(st.integers(1, 3))
    pieces = []
    for k in range(n_pieces):
        a = draw(st.floats(45, 70))
        b = draw(st.floats(32, a))
        blob = shapely.affinity.scale(shapely.Point(0, 0).buffer(1.0, quad_segs=32), a, b)
        if draw(st.booleans()):  # a rounded rectangle instead of an ellipse
            blob = shapely.box(-a, -b, a, b).buffer(-8).buffer(8, quad_segs=16)
        blob = shapely.affinity.rotate(blob, draw(st.floats(0, 180)), origin=(0, 0))
        # each piece in its own 160-pixel cell: a rotated rectangle's corners may reach past it
        assume(shapely.Point(0, 0).buffer(76).contains(blob))
        holes: list = []
        for _ in range(draw(st.integers(0, 3))):
            x, y = draw(st.floats(-0.7, 0.7)) * a, draw(st.floats(-0.7, 0.7)) * b
            size = draw(st.floats(5, 12))
            if draw(st.booleans()):
                hole = shapely.Point(x, y).buffer(size, quad_segs=16)
            else:
                hole = shapely.affinity.rotate(shapely.box(x - size, y - size, x + size, y + size), draw(st.floats(0, 90)))
            # Walls at least 6 pixels thick: the raster keeps every hole apart.
            if blob.buffer(-6).contains(hole) and all(hole.distance(h) > 6 for h in holes):
                holes.append(hole)
        piece = blob.difference(shapely.union_all(holes)) if holes else blob
        pieces.append(shapely.affinity.translate(piece, 80 + 160 * k, 80))
    kind = draw(st.sampled_from(["bool", "float", "uint8", "int16"]))
    dark = draw(st.booleans())
    return shapely.union_all(pieces), n_pieces, kind, dark


@given(holed_scenes())
def test_random_shapes_with_random_holes(scene):
    geom, n_pieces, kind, dark = scene
    note(f"{kind} dark={dark}: {geom.wkt}")
    cover = render(geom, (160, 160 * n_pieces), 2)
    mask = cover > 0.5
    image = {
        "bool": mask,
        "float": cover,
        "uint8": np.round(cover * 255).astype(np.uint8),
        "int16": np.round(cover * 2000 - 1000).astype(np.int16),  # signed, as CT slices are
    }[kind]
    if dark:
        image = ~image if kind == "bool" else -image if kind == "int16" else (1.0 - image if kind == "float" else 255 - image)
    ma = mx.medial_axis(image)
    assert truth_counts(mask)[0] == n_pieces
    assert ma.metadata["foreground"] == ("dark" if dark else "bright")
    _check_topology(ma, mask)
