"""Every planar input kind gives the same axis for the same shape."""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely
from PIL import Image

import medialaxis as mx

RECT = shapely.box(10, 20, 90, 60)


def _check_rect(ma, scale=1.0):
    assert len(ma.endpoints) == 4 and len(ma.junctions) == 2 and ma.n_components == 1
    np.testing.assert_allclose(ma.radii.max(), 20 * scale, rtol=0.05)


def test_vector_files(tmp_path):
    (tmp_path / "r.wkt").write_text(RECT.wkt)
    (tmp_path / "r.geojson").write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {}, "geometry": shapely.geometry.mapping(RECT)}]}))
    (tmp_path / "r.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg"><rect x="10" y="20" width="80" height="40"/></svg>')
    (tmp_path / "p.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg"><path d="M10 20 h80 v40 h-80 Z"/></svg>')
    (tmp_path / "q.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg"><polygon points="10,20 90,20 90,60 10,60"/></svg>')
    for name in ("r.wkt", "r.geojson", "r.svg", "p.svg", "q.svg"):
        ma = mx.medial_axis(tmp_path / name)
        _check_rect(ma)
        np.testing.assert_allclose(ma.points[ma.junctions].mean(0), [50, 40], atol=1e-6)


def test_geometry_kinds():
    _check_rect(mx.medial_axis(RECT))
    _check_rect(mx.medial_axis(np.asarray(RECT.exterior.coords)[:-1]))
    two = mx.medial_axis([RECT, shapely.box(200, 0, 240, 40)])
    assert two.n_components == 2
    multi = mx.medial_axis(shapely.MultiPolygon([RECT, shapely.box(200, 0, 240, 40)]))
    assert multi.n_components == 2


@pytest.mark.parametrize("fmt", ["png", "jpeg", "tiff", "bmp"])
def test_image_files(tmp_path, fmt):
    img = np.full((80, 120), 30, np.uint8)
    img[20:60, 10:110] = 220
    path = tmp_path / f"r.{fmt}"
    Image.fromarray(img).save(path)
    ma = mx.medial_axis(path)
    _check_rect(ma)
    assert ma.metadata["image_shape"] == [80, 120]
    assert 30 <= ma.metadata["threshold"] < 220


def test_grey_threshold_and_otsu():
    img = np.zeros((80, 120))
    img[20:60, 10:110] = 0.6
    img[30:50, 30:90] = 1.0
    outer = mx.medial_axis(img, threshold=0.3)
    inner = mx.medial_axis(img, threshold=0.8)
    assert outer.radii.max() > inner.radii.max() + 5


def test_npy_file(tmp_path):
    mask = np.zeros((60, 100), bool)
    mask[10:50, 10:90] = True
    np.save(tmp_path / "m.npy", mask)
    _check_rect(mx.medial_axis(tmp_path / "m.npy"))


def test_foreground_touching_the_border():
    mask = np.zeros((40, 80), bool)
    mask[:, 20:60] = True
    ma = mx.medial_axis(mask)
    assert ma.n_components == 1
    assert len(ma.endpoints) >= 2



def test_vertices_a_rounding_error_apart_do_not_make_wrong_discs():
    # the bundled CAD plate: its LWPOLYLINE closes 1.8e-15 off its start; before the near-duplicate
    # vertex was merged, a Delaunay circle through it reached 0.25 past the plate's edge
    pytest.importorskip("ezdxf")
    from medialaxis.datasets import data_path

    ma = mx.medial_axis(data_path("plate_slot.dxf"), layers=["CUT"])
    true = shapely.distance(shapely.points(ma.points), ma.shape.boundary)
    np.testing.assert_allclose(ma.radii, true, atol=1e-9 * 100)
    assert mx.reconstruction_error(ma).hausdorff < 0.05
