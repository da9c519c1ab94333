"""SVG drawings read as they are painted: exact answers, and librsvg's pictures of W3C test files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely
from PIL import Image
from scipy import ndimage

import medialaxis as mx
from medialaxis.errors import UnsupportedFeatureError
from medialaxis.planar.drawings.svg import read_svg

DATA = Path(__file__).resolve().parents[1] / "data" / "svg"
HEAD = '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"'


def _svg(tmp_path: Path, body: str, attrs: str = 'width="400" height="300"', name: str = "d.svg") -> Path:
    path = tmp_path / name
    path.write_text(f"{HEAD} {attrs}>{body}</svg>")
    return path


def _read(tmp_path: Path, body: str, **kwargs):
    return read_svg(_svg(tmp_path, body), **kwargs)[0]


# ------------------------------------------------------------- what the issue found wrong
def test_unfilled_stroked_frame_is_a_frame(tmp_path):
    region = _read(tmp_path, '<rect x="10" y="10" width="100" height="50" fill="none" stroke="black" stroke-width="4"/>')
    assert region.area == pytest.approx(104 * 54 - 96 * 46)
    assert len(region.interiors) == 1


def test_unpainted_elements_are_not_read(tmp_path):
    body = ('<rect width="10" height="10" fill="none"/>'
            '<rect x="20" width="10" height="10" fill="none" stroke="none"/>')
    with pytest.raises(mx.EmptyShapeError):
        read_svg(_svg(tmp_path, body))


def test_transform_of_element_and_group(tmp_path):
    rect = '<rect width="100" height="20" transform="translate(100,0) scale(2)"/>'
    ma = mx.medial_axis(_svg(tmp_path, rect))
    assert ma.radii.max() == pytest.approx(20.0, rel=1e-6)
    np.testing.assert_allclose(ma.shape.bounds, (100, 0, 300, 40))
    grouped = '<g transform="translate(100,0)"><g transform="scale(2)"><rect width="100" height="20"/></g></g>'
    np.testing.assert_allclose(_read(tmp_path, grouped).bounds, (100, 0, 300, 40))


def test_circle_of_two_arcs(tmp_path):
    tol = 0.01
    path = _svg(tmp_path, '<path d="M 50 100 A 50 50 0 0 1 150 100 A 50 50 0 0 1 50 100 Z"/>')
    region = read_svg(path, tolerance=tol)[0]
    xy = shapely.get_coordinates(region.exterior)
    radius = np.hypot(xy[:, 0] - 100, xy[:, 1] - 100)
    np.testing.assert_allclose(radius, 50.0, atol=1e-9)  # every vertex on the circle
    # chord error: the circle lies within tol of the polygon (a sagitta is at most tol)
    assert np.pi * 50**2 - region.area <= 2 * np.pi * 50 * tol
    np.testing.assert_allclose(region.bounds, (50, 50, 150, 150), atol=tol)
    ma = mx.medial_axis(path, tolerance=tol)
    assert ma.radii.max() == pytest.approx(50.0, abs=2 * tol)


def _cubic(p, n=20001):
    t = np.linspace(0, 1, n)[:, None]
    return (1 - t) ** 3 * p[0] + 3 * (1 - t) ** 2 * t * p[1] + 3 * (1 - t) * t**2 * p[2] + t**3 * p[3]


def _quad(p, n=20001):
    t = np.linspace(0, 1, n)[:, None]
    return (1 - t) ** 2 * p[0] + 2 * (1 - t) * t * p[1] + t**2 * p[2]


def test_smooth_curves_s_and_t(tmp_path):
    # S reflects the previous cubic's second control point; T the previous quadratic's control point.
    d = "M 0 0 C 0 -50 100 -50 100 0 S 200 50 200 0 L 200 100 Q 150 150 100 100 T 0 100 Z"
    region = _read(tmp_path, f'<path d="{d}"/>', tolerance=1e-3)
    a = np.array
    exact = np.vstack([
        _cubic([a([0, 0]), a([0, -50]), a([100, -50]), a([100, 0])]),
        _cubic([a([100, 0]), a([100, 50]), a([200, 50]), a([200, 0])]),
        _quad([a([200, 100]), a([150, 150]), a([100, 100])]),
        _quad([a([100, 100]), a([50, 50]), a([0, 100])]),
    ])
    truth = shapely.Polygon(exact)
    assert truth.is_valid
    assert region.symmetric_difference(truth).area < 1e-3 * truth.length
    assert shapely.hausdorff_distance(region.exterior, truth.exterior) < 2e-3


@pytest.mark.parametrize("rule, area", [("nonzero", 100 * 100), ("evenodd", 100 * 100 - 50 * 50)])
def test_fill_rules(tmp_path, rule, area):
    # two squares of the same orientation: nonzero (SVG's default) paints the inner one
    d = "M 0 0 H 100 V 100 H 0 Z M 25 25 H 75 V 75 H 25 Z"
    attr = "" if rule == "nonzero" else ' fill-rule="evenodd"'
    assert _read(tmp_path, f'<path d="{d}"{attr}/>').area == pytest.approx(area)
    # opposite orientations leave a hole under both rules
    d2 = "M 0 0 H 100 V 100 H 0 Z M 25 25 V 75 H 75 V 25 Z"
    assert _read(tmp_path, f'<path d="{d2}"{attr}/>').area == pytest.approx(100 * 100 - 50 * 50)


def test_separate_elements_are_painted_over_each_other(tmp_path):
    body = '<rect width="100" height="50"/><circle cx="30" cy="25" r="10" fill="white"/>'
    region = _read(tmp_path, body)
    assert region.area == pytest.approx(5000) and len(region.interiors) == 0


def test_holes_of_one_path_give_cycles(tmp_path):
    d = "M0 0 H100 V50 H0 Z M20 15 V35 H40 V15 Z M60 15 V35 H80 V15 Z"
    ma = mx.medial_axis(_svg(tmp_path, f'<path d="{d}"/>'))
    assert ma.n_cycles == 2 and ma.n_components == 1


# ---------------------------------------------------------------------- strokes
def test_stroke_caps_joins_and_non_uniform_scale(tmp_path):
    line = '<path d="M 10 10 L 110 10" fill="none" stroke="black" stroke-width="4" stroke-linecap="{}"/>'
    assert _read(tmp_path, line.format("butt")).area == pytest.approx(400)
    assert _read(tmp_path, line.format("square")).area == pytest.approx(416)
    assert _read(tmp_path, line.format("round")).area == pytest.approx(400 + np.pi * 4, rel=1e-3)
    # the stroke is drawn in the element's own coordinates, then scaled: a 6-high band
    scaled = '<path d="M 10 10 L 110 10" stroke="black" stroke-width="2" transform="scale(1,3)"/>'
    np.testing.assert_allclose(_read(tmp_path, scaled).bounds, (10, 27, 110, 33))


def test_mitre_limit_bevels_beyond_it(tmp_path):
    # a right angle: mitre ratio sqrt(2); below the limit it is mitred, above it bevelled
    d = "M 0 100 L 100 100 L 100 0"
    stroke = '<path d="{}" fill="none" stroke="black" stroke-width="10" stroke-miterlimit="{}"/>'
    mitred = _read(tmp_path, stroke.format(d, 4))
    bevelled = _read(tmp_path, stroke.format(d, 1.2))
    assert mitred.area - bevelled.area == pytest.approx(5 * 5 / 2)
    np.testing.assert_allclose(mitred.bounds, (0, 0, 105, 105))


def test_dashes(tmp_path):
    d = '<path d="M 0 0 L 100 0" stroke="black" stroke-width="2" stroke-dasharray="10 10" stroke-dashoffset="5"/>'
    region = _read(tmp_path, d)
    # dashes on [0, 5], [15, 25], ..., [95, 100]: 5 + 4 * 10 + 5 = 50 units long
    assert region.area == pytest.approx(2 * 50)
    assert len(region.geoms) == 6


def test_fills_only(tmp_path):
    path = _svg(tmp_path, '<rect width="10" height="10" stroke="black" stroke-width="2"/>')
    assert read_svg(path, strokes=False)[0].area == pytest.approx(100)
    assert read_svg(path)[0].area == pytest.approx(144)
    ma = mx.medial_axis(path, strokes=False)
    assert ma.shape.area == pytest.approx(100)


# ---------------------------------------------------------- structure and styles
def test_units_and_viewbox_give_user_units(tmp_path):
    path = _svg(tmp_path, '<rect x="10" y="10" width="1in" height="50"/>',
                attrs='width="100mm" height="50mm" viewBox="0 0 200 100"')
    region, info = read_svg(path)
    np.testing.assert_allclose(region.bounds, (10, 10, 106, 60))  # 1in = 96 user units
    scale = 100 / 25.4 * 96 / 200  # CSS pixels per user unit
    np.testing.assert_allclose(info["viewport"], [scale, 0, 0, scale, 0, 0], rtol=1e-6)  # svgelements rounds to 7 digits


def test_use_symbol_css_and_hidden(tmp_path):
    body = (
        '<style>.hollow { fill: none; stroke: black; stroke-width: 2 }</style>'
        '<defs><rect id="r" width="10" height="10"/></defs>'
        '<symbol id="s" viewBox="0 0 10 10"><rect width="20" height="20"/></symbol>'
        '<use xlink:href="#r" x="100" y="100"/>'
        '<use href="#s" x="200" y="0" width="50" height="50"/>'
        '<rect class="hollow" x="0" y="200" width="20" height="20"/>'
        '<rect x="300" width="10" height="10" display="none"/>'
        '<rect x="300" width="10" height="10" visibility="hidden"/>'
        '<rect x="300" width="10" height="10" opacity="0"/>'
    )
    region = _read(tmp_path, body)
    parts = sorted(shapely.get_parts(region), key=lambda g: g.bounds)
    np.testing.assert_allclose(parts[0].bounds, (-1, 199, 21, 221))
    assert parts[0].area == pytest.approx(22 * 22 - 18 * 18)  # the CSS class: a stroked frame
    np.testing.assert_allclose(parts[1].bounds, (100, 100, 110, 110))
    np.testing.assert_allclose(parts[2].bounds, (200, 0, 250, 50))  # the symbol, clipped to its viewport
    assert len(parts) == 3


def test_clip_path(tmp_path):
    body = ('<clipPath id="c"><circle cx="0" cy="0" r="10"/></clipPath>'
            '<g transform="translate(50,50)"><rect x="0" y="0" width="40" height="40" clip-path="url(#c)"/></g>')
    region = _read(tmp_path, body, tolerance=1e-4)
    assert region.area == pytest.approx(np.pi * 100 / 4, rel=1e-4)
    np.testing.assert_allclose(region.bounds, (50, 50, 60, 60), atol=1e-4)


def test_gradients_paint_unless_empty(tmp_path):
    body = ('<linearGradient id="none"/><linearGradient id="g"><stop offset="0" stop-color="red"/></linearGradient>'
            '<rect width="10" height="10" fill="url(#none)"/><rect x="20" width="10" height="10" fill="url(#g)"/>')
    assert _read(tmp_path, body).bounds == (20, 0, 30, 10)


def test_text_and_images_are_skipped_with_a_warning(tmp_path):
    path = _svg(tmp_path, '<rect width="40" height="20"/><text x="0" y="50">label</text>')
    with pytest.warns(mx.MedialAxisWarning, match="1 text"):
        ma = mx.medial_axis(path)
    assert ma.metadata["drawing"]["skipped"] == {"text": 1}


@pytest.mark.parametrize("body, feature", [
    ('<marker id="m"><circle r="2"/></marker><path d="M0 0 L10 10" stroke="black" marker-end="url(#m)"/>',
     "markers"),
    ('<mask id="m"><rect width="5" height="5" fill="white"/></mask><rect width="10" height="10" mask="url(#m)"/>',
     "masks"),
    ('<filter id="f"><feGaussianBlur stdDeviation="2"/></filter><rect width="10" height="10" filter="url(#f)"/>',
     "filters"),
    ('<pattern id="p" width="2" height="2"><rect width="1" height="1"/></pattern>'
     '<rect width="10" height="10" fill="url(#p)"/>', "pattern"),
    ('<switch><rect width="10" height="10"/></switch>', "switch"),
])
def test_unsupported_features_are_named(tmp_path, body, feature):
    with pytest.raises(UnsupportedFeatureError, match=feature):
        mx.medial_axis(_svg(tmp_path, body))


def test_bad_documents(tmp_path):
    (tmp_path / "cut.svg").write_text("<svg><polygon points='0,0 1")
    (tmp_path / "html.svg").write_text("<html><body/></html>")
    for name in ("cut.svg", "html.svg"):
        with pytest.raises(mx.InputFileError):
            mx.medial_axis(tmp_path / name)
    with pytest.raises(mx.InvalidInputError, match="layers"):
        mx.medial_axis(_svg(tmp_path, '<rect width="5" height="5"/>'), layers=["CUT"])
    with pytest.raises(mx.InvalidInputError, match="strokes"):
        mx.medial_axis(shapely.box(0, 0, 2, 1), strokes=False)


def test_path_data_error_draws_up_to_it(tmp_path):
    path = _svg(tmp_path, '<path d="M 0 0 L 10 0 L 10 10 L 0 10 Z L 5 x"/>')
    with pytest.warns(mx.MedialAxisWarning, match="drawn up to the error"):
        ma = mx.medial_axis(path)
    assert ma.shape.area == pytest.approx(100)


# -------------------------------------------------- an independent renderer's pictures
def _raster(region, viewport, shape):
    a, b, c, d, e, f = viewport
    px = shapely.affinity.affine_transform(region, [a, c, b, d, e, f])
    rows, cols = np.mgrid[: shape[0], : shape[1]]
    return shapely.contains_xy(px, cols.ravel() + 0.5, rows.ravel() + 0.5).reshape(shape)


@pytest.mark.parametrize("name", sorted(p.stem for p in DATA.glob("*.svg")))
def test_w3c_files_match_librsvg(name):
    """The outline, rasterized, paints what librsvg paints (tests/data/README.md says how the pictures were made)."""
    reference = np.asarray(Image.open(DATA / f"{name}-notext.png")) > 0
    region, info = read_svg(DATA / f"{name}.svg")
    assert info["skipped"]["text"] >= 1  # the suite's captions
    ours = _raster(region, info["viewport"], reference.shape)
    band = ndimage.binary_dilation(reference, iterations=2) & ~ndimage.binary_erosion(reference, iterations=2)
    wrong = ((ours != reference) & ~band).sum()
    assert wrong <= 0.005 * reference.sum(), f"{wrong} of {reference.sum()} painted pixels disagree"


def test_w3c_file_through_the_whole_route():
    with pytest.warns(mx.MedialAxisWarning, match="text"):
        ma = mx.medial_axis(DATA / "shapes-intro-01-t.svg")
    assert ma.metadata["drawing"]["format"] == "svg"
    # every medial disc lies inside the painted region (a float tolerance aside)
    inside = shapely.contains_xy(ma.shape.buffer(1e-6), ma.points[:, 0], ma.points[:, 1])
    assert inside.all()
    distance = shapely.distance(shapely.points(ma.points), ma.shape.boundary)
    np.testing.assert_allclose(ma.radii, distance, atol=ma.metadata["tolerance"] * 2)


def test_inherit_takes_the_parents_value(tmp_path):
    body = ('<g fill="none" stroke="black" stroke-width="4"><rect width="10" height="10" fill="inherit"'
            ' style="stroke-width: inherit"/></g>'
            '<g display="none"><rect x="50" width="10" height="10" display="inherit"/></g>')
    region = _read(tmp_path, body)
    assert region.area == pytest.approx(14 * 14 - 6 * 6)  # unfilled, stroked 4 wide; the hidden one not read


def test_slot_axis_is_the_segment_between_arc_centres(tmp_path):
    # a stadium: centres (40, 50) and (160, 50), radius 20; drawn with two arcs, as drawing programs write it
    d = "M 40 30 L 160 30 A 20 20 0 0 1 160 70 L 40 70 A 20 20 0 0 1 40 30 Z"
    ma = mx.medial_axis(_svg(tmp_path, f'<path d="{d}"/>'))
    size = 160.0  # the part's length
    ends = np.sort(ma.points[ma.endpoints][:, 0])
    np.testing.assert_allclose(ends, [40, 160], atol=1e-3 * size)
    np.testing.assert_allclose(ma.points[:, 1], 50, atol=1e-3 * size)
    np.testing.assert_allclose(ma.radii, 20, atol=1e-3 * size)
    assert len(ma.endpoints) == 2 and len(ma.junctions) == 0
