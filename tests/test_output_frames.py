"""Outputs in the source's frame: an SVG of an SVG drawing lies over it, an image's over the image,
the same (x, y) in GraphML, GeoJSON and SVG; 2D HTML pages."""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from html.parser import HTMLParser

import numpy as np
import pytest
import shapely

import medialaxis as mx

pytest.importorskip("svgelements")
SVG = "{http://www.w3.org/2000/svg}"


def _svg(tmp_path, root_attrs, body, name="drawing.svg"):
    path = tmp_path / name
    path.write_text(f'<svg xmlns="http://www.w3.org/2000/svg" {root_attrs}>{body}</svg>')
    return path


def _polylines(root):
    return [np.array([[float(v) for v in pair.split(",")] for pair in el.get("points").split()])
            for el in root.iter(SVG + "polyline")]


def _longest(lines):
    return max(lines, key=lambda xy: np.linalg.norm(np.diff(xy, axis=0), axis=1).sum())


@pytest.mark.parametrize("root", ['width="400" height="200" viewBox="0 0 200 100"',
                                  'width="300" height="150" viewBox="-20 10 200 100"',
                                  'viewBox="0 0 200 100"'])
def test_svg_of_an_svg_drawing_has_its_frame_and_overlays_it(tmp_path, root):
    drawing = _svg(tmp_path, root, '<rect x="0" y="15" width="200" height="20"/>')
    out = tmp_path / "axis.svg"
    mx.medial_axis(drawing).save(out)
    given, written = ET.parse(drawing).getroot(), ET.parse(out).getroot()
    for name in ("width", "height"):
        if given.get(name):
            assert float(written.get(name)) == float(given.get(name))
    assert [float(v) for v in written.get("viewBox").split()] == [float(v) for v in given.get("viewBox").split()]
    assert all(g.get("transform") is None for g in written.iter(SVG + "g"))  # drawn in user units, y down
    main = _longest(_polylines(written))
    np.testing.assert_allclose(main[:, 1], 25.0, atol=1e-6)  # the bar's axis, where the drawing has it
    assert main[:, 0].min() < 20 and main[:, 0].max() > 180


def test_svg_of_a_scaled_nonuniform_drawing_keeps_its_user_units(tmp_path):
    drawing = _svg(tmp_path, 'width="400" height="100" viewBox="0 0 200 100" preserveAspectRatio="none"',
                   '<rect x="0" y="15" width="200" height="20"/>')
    out = tmp_path / "axis.svg"
    ma = mx.medial_axis(drawing)
    ma.save(out)
    written = ET.parse(out).getroot()
    assert written.get("viewBox") == "0 0 200 100" and written.get("preserveAspectRatio") == "none"
    np.testing.assert_allclose(_longest(_polylines(written))[:, 1], 25.0, atol=1e-6)


def _bar_image():
    image = np.zeros((60, 90), bool)
    image[15:45, 10:80] = True  # rows 15-44, columns 10-79
    return image


def test_svg_of_an_image_is_in_its_pixel_frame(tmp_path):
    out = tmp_path / "axis.svg"
    mx.medial_axis(_bar_image()).save(out)
    root = ET.parse(out).getroot()
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == ("90", "60", "-0.5 -0.5 90 60")
    main = _longest(_polylines(root))
    np.testing.assert_allclose(main[:, 1], 29.5, atol=0.5)  # y = row, downwards
    assert main[:, 0].min() < 30 and main[:, 0].max() > 60  # x = column: the long side


def test_svg_of_an_image_with_spacing_has_one_css_pixel_per_image_pixel(tmp_path):
    out = tmp_path / "axis.svg"
    ma = mx.medial_axis(_bar_image(), spacing=(0.5, 2.0))  # rows 0.5 apart, columns 2
    ma.save(out)
    root = ET.parse(out).getroot()
    assert (root.get("width"), root.get("height")) == ("90", "60")
    assert root.get("viewBox") == "-1 -0.25 180 30" and root.get("preserveAspectRatio") == "none"
    main = _longest(_polylines(root))
    np.testing.assert_allclose(main[:, 1], 0.5 * 29.5, atol=0.25)
    assert main[:, 0].min() < 60 and main[:, 0].max() > 120


def test_svg_of_a_y_up_polygon_writes_its_own_coordinates_flipped_in_the_transform(tmp_path):
    polygon = shapely.Polygon([(100, 200), (170, 200), (170, 230), (100, 230)])
    ma = mx.medial_axis(polygon)
    out = tmp_path / "axis.svg"
    ma.save(out)
    root = ET.parse(out).getroot()
    assert root.find(SVG + "g").get("transform") == "scale(1,-1)"
    x0, y0, w, h = (float(v) for v in root.get("viewBox").split())
    main = _longest(_polylines(root))
    np.testing.assert_allclose(main[:, 1], 215.0, atol=1e-6)
    assert np.all((x0 <= main[:, 0]) & (main[:, 0] <= x0 + w) & (y0 <= -main[:, 1]) & (-main[:, 1] <= y0 + h))


def test_png_of_an_svg_drawing_has_y_down(tmp_path, monkeypatch):
    import matplotlib.figure

    drawing = _svg(tmp_path, 'viewBox="0 0 200 100"', '<rect x="0" y="15" width="200" height="20"/>')
    seen = []
    original = matplotlib.figure.Figure.savefig

    def savefig(fig, *args, **kwargs):
        seen.append(fig.axes[0].yaxis_inverted())
        return original(fig, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", savefig)
    mx.medial_axis(drawing).save(tmp_path / "a.png")
    mx.medial_axis(_bar_image()).save(tmp_path / "b.png")
    mx.medial_axis(shapely.box(0, 0, 4, 1)).save(tmp_path / "c.png")
    assert seen == [True, True, False]


def test_graphml_geojson_and_svg_name_the_axes_alike(tmp_path):
    nx = pytest.importorskip("networkx")
    image = _bar_image()
    image[20:30, 70:85] = True  # not symmetric: a swapped axis would show
    ma = mx.medial_axis(image)
    for ext in ("graphml", "geojson", "svg"):
        ma.save(tmp_path / f"axis.{ext}")
    g = nx.read_graphml(tmp_path / "axis.graphml")
    assert g.graph["coordinates"].startswith("x = column, y = row")
    doc = json.loads((tmp_path / "axis.geojson").read_text())
    ends = {f["properties"]["index"]: f["geometry"]["coordinates"] for f in doc["features"]
            if f["properties"]["kind"] == "endpoint"}
    assert ends
    for i, (x, y) in ends.items():
        node = g.nodes[str(i)]
        assert (node["x"], node["y"]) == pytest.approx((x, y))
        assert (x, y) == pytest.approx(tuple(ma.points[i, ::-1]))  # column, row
    root = ET.parse(tmp_path / "axis.svg").getroot()
    dots = [(float(c.get("cx")), float(c.get("cy"))) for c in root.find(SVG + "g").iter(SVG + "circle")]
    for x, y in ends.values():
        assert min(np.hypot(x - cx, y - cy) for cx, cy in dots) < 1e-6


# ------------------------------------------------------------------ 2D pages
class _Scripts(HTMLParser):
    def __init__(self):
        super().__init__()
        self.scripts, self.divs, self._in = [], [], None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "script":
            self._in = attrs
            self.scripts.append([attrs, ""])
        elif tag == "div":
            self.divs.append(attrs.get("id"))

    def handle_endtag(self, tag):
        if tag == "script":
            self._in = None

    def handle_data(self, data):
        if self._in is not None:
            self.scripts[-1][1] += data


def _page_figure(path):
    parser = _Scripts()
    parser.feed(path.read_text())
    data = [text for attrs, text in parser.scripts if attrs.get("id") == "medialaxis-data"]
    assert len(data) == 1 and "medialaxis-plot" in parser.divs
    from tests.test_pages import _decoded  # the page's blobs inflated as its loader does

    return _decoded(json.loads(data[0].replace("<\\/", "</"))), parser


@pytest.mark.parametrize("source", ["image", "polygon"])
def test_html_page_of_a_2d_result_holds_the_shape_and_the_points(tmp_path, source):
    pytest.importorskip("plotly")
    if source == "image":
        ma = mx.medial_axis(_bar_image())
    else:
        ma = mx.medial_axis(shapely.Polygon([(0, 0), (10, 0), (10, 4), (0, 4)], [[(2, 1), (8, 1), (8, 3), (2, 3)]]))
    ma.save(tmp_path / "axis.html")
    assert list(tmp_path.glob("plotly-*.min.js"))  # offline: the viewer beside the page
    text = (tmp_path / "axis.html").read_text()
    assert not re.search(r"<script[^>]+src=[\"']?(https?:)?//", text)
    figure, parser = _page_figure(tmp_path / "axis.html")
    traces = {t["name"]: t for t in figure["data"]}
    assert {"shape", "medial axis", "medial points"} <= set(traces)
    points = traces["medial points"]
    xy = ma.points[:, ::-1] if source == "image" else ma.points
    np.testing.assert_allclose(np.c_[points["x"], points["y"]], xy.astype(np.float32), rtol=1e-6)
    np.testing.assert_allclose(points["marker"]["color"], ma.radii.astype(np.float32), rtol=1e-6)
    outline = np.c_[traces["shape"]["x"], traces["shape"]["y"]]
    rings = outline[~np.isnan(outline[:, 0])]
    shape_xy = np.vstack([np.asarray(r.coords) for p in shapely.get_parts(ma.shape) for r in [p.exterior, *p.interiors]])
    np.testing.assert_allclose(np.sort(rings, axis=0),
                               np.sort((shape_xy[:, ::-1] if source == "image" else shape_xy).astype(np.float32), axis=0),
                               rtol=1e-6)
    yaxis = figure["layout"]["yaxis"]
    assert yaxis["scaleanchor"] == "x" and yaxis["autorange"] == ("reversed" if source == "image" else True)


# ------------------------------------------------------------------ overlays, as an independent renderer paints them
def _painted(svg, tmp_path, name):
    import shutil
    import subprocess

    from PIL import Image

    if shutil.which("rsvg-convert") is None:
        pytest.skip("rsvg-convert (librsvg2-bin) is not installed")
    png = tmp_path / f"{name}.png"
    subprocess.run(["rsvg-convert", str(svg), "-o", str(png)], check=True, capture_output=True, timeout=60)
    return np.asarray(Image.open(png).convert("RGBA"), float)


def _axis_pixels(rgba):
    r, g, b, a = np.moveaxis(rgba, -1, 0)
    return (a > 200) & (r > 150) & (g < 110) & (b < 110)  # the axis' red, not the shape's grey-blue


def test_the_svg_output_lies_over_the_drawing_as_rsvg_paints_them(tmp_path):
    drawing = _svg(tmp_path, 'width="300" height="200" viewBox="-10 -20 150 100"',
                   '<g transform="rotate(25 60 30)"><rect x="0" y="20" width="120" height="24" fill="black"/></g>')
    out = tmp_path / "axis.svg"
    mx.medial_axis(drawing).save(out)
    under, over = _painted(drawing, tmp_path, "under"), _painted(out, tmp_path, "over")
    assert under.shape == over.shape == (200, 300, 4)
    axis = _axis_pixels(over)
    assert axis.sum() > 100 and (under[..., 3][axis] > 0).mean() > 0.97  # the axis is on the bar


def test_the_svg_output_of_an_image_lies_over_the_image(tmp_path):
    image = _bar_image()
    image[20:30, 70:85] = True
    out = tmp_path / "axis.svg"
    mx.medial_axis(image).save(out)
    over = _painted(out, tmp_path, "over")
    assert over.shape[:2] == image.shape
    axis = _axis_pixels(over)
    assert axis.sum() > 30 and image[axis].mean() > 0.97
